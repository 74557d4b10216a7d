#!/usr/bin/env python3
"""Draws the corpus's random machines (tests/corpus/machines.txt) from a fixed seed.

Each line is a run: `--example N` or an input file, then `--set` overrides. Only machines the
whatnext command accepts are kept, 200 of them, with every switch, impact law and integrator.
Run once; the file is committed, and check.sh compares every run's outputs with digests.txt.
usage: make_machines.py WHATNEXT > machines.txt
"""
import math
import random
import subprocess
import sys

cli = sys.argv[1]
rng = random.Random(20261125)
base = {  # example: rope, hinge (dx, dh), sandbag_x, height, seesaw angle
    1: dict(r_h=0.6, r_l=0.2, rope=1.0, hinge=(0.8 * math.cos(math.radians(27)), 0.8 * math.sin(math.radians(27))), x=-0.3, h=1.0, phi=-25, m_s=0.6, m_l=0.5),
    2: dict(r_h=0.6, r_l=0.2, rope=0.62, hinge=(0.8 * math.cos(math.radians(27)), 0.8 * math.sin(math.radians(27))), x=-0.3, h=0.5, phi=-35, m_s=0.6, m_l=0.5),
    3: dict(r_h=0.6, r_l=0.2, rope=1.0, hinge=(0.8 * math.cos(math.radians(27)), 0.8 * math.sin(math.radians(27))), x=-0.3, h=0.0, phi=0, m_s=0.6, m_l=0.5),
    4: dict(r_h=0.45, r_l=0.2, rope=0.9, hinge=(0.64, 0.29), x=-0.3, h=0.5, phi=-20, m_s=0.7, m_l=0.4),
}


def factor(most):
    return math.exp(rng.uniform(-math.log(most), math.log(most)))


def machine():
    ex = rng.randint(1, 4)
    b = base[ex]
    s = []
    add = lambda k, v: s.append(f"{k}={v!r}" if isinstance(v, float) else f"{k}={v}")
    add("geometry.seesaw_right_arm", b["r_h"] * factor(1.5))
    add("geometry.lid_half_length", b["r_l"] * factor(1.5))
    add("geometry.rope_length", b["rope"] * factor(1.2))
    dx, dh = b["hinge"][0] * factor(1.3), b["hinge"][1] * factor(1.3)
    s.append(f"geometry.hinge_offset=[{dx!r}, {dh!r}]")
    add("masses.sandbag", b["m_s"] * factor(2.0))
    add("masses.lid", b["m_l"] * factor(2.0))
    add("air.helium_density", 0.18 * factor(2.0))
    add("start.sandbag_x", b["x"] * factor(2.0))
    add("start.sandbag_height", b["h"] * factor(2.0) if b["h"] > 0 else 0.0)
    add("start.seesaw_angle", max(-80.0, min(80.0, b["phi"] + rng.uniform(-15, 15))))
    add("start.lid_angle", max(0.0, min(60.0, 5.0 * factor(2.0))))
    if rng.random() < 0.3:
        add("balloon.radius", b["r_l"] * factor(1.5))
    if rng.random() < 0.2:
        add("run.gravity", 9.81 * factor(1.3))
    add("balloon.model", rng.choice(["program", "lagrangian", "added-mass"]))
    if rng.random() < 0.3:
        add("radio.enabled", "true")
        if rng.random() < 0.5:
            add("radio.string_length", rng.uniform(0.6, 1.6))
    if rng.random() < 0.3:
        add("balloon.drag_coefficient", rng.uniform(0.2, 1.0))
    if rng.random() < 0.3:
        add("balloon.rubber_mass", rng.uniform(0.0, 0.004))
    pivot_damper = rng.random() < 0.3
    if rng.random() < 0.3:
        add("damping.lid_hinge", rng.uniform(0.0, 0.05))
    if rng.random() < 0.3:
        add("seesaw.left_arm", abs(b["x"]) * rng.uniform(1.0, 6.0) + 0.05)
        if rng.random() < 0.5:
            add("seesaw.mass", rng.uniform(0.05, 1.0))
            if pivot_damper:
                add("damping.pivot", rng.uniform(0.0, 0.05))
    add("run.impact_law", rng.choice(["rope", "angular-momentum-sum", "kinetic-energy", "linear-momentum"]))
    integrator = rng.randint(0, 4)
    if integrator == 3:
        add("run.integrator", "euler")
    if integrator == 4:
        add("run.integrator", "rk4")
    if integrator >= 3:
        add("run.step", rng.choice([1e-3, 5e-4]))
    if rng.random() < 0.3:
        add("run.tolerance", rng.choice([1e-9, 1e-10, 1e-14]))
    add("run.t_max", rng.choice([2.0, 5.0]))
    add("run.output_step", rng.choice([1e-3, 2e-3, 0.01]))
    return [f"--example {ex}"] + [f"--set {x}" for x in s]


kept = 0
while kept < 200:
    args = machine()
    argv = [cli, "run", "-q"] + " ".join(args).replace("--set ", "--set\0").split(" ")
    argv = [a for part in argv for a in part.split("\0")]
    argv = [cli, "run", "-q"]
    for a in args:
        argv += a.split(" ", 1)
    r = subprocess.run(argv, capture_output=True, text=True)
    if r.returncode != 0:
        continue
    print(" ".join(a.split(" ", 1)[0] + " " + "'" + a.split(" ", 1)[1] + "'" for a in args))
    kept += 1

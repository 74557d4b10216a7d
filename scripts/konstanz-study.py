#!/usr/bin/env python3
"""Would the students' machine switch the radio on? A Monte Carlo over the build's uncertainties.

examples/konstanz.toml is the machine students build, with a real party balloon (its rubber, the
air's drag, the gas) and the lightest switch they could make; each of its "±" is drawn here from a
normal distribution (one standard deviation) by `whatnext sweep --spread`. Printed: how often the
radio comes on and when; the balloon's pull against the switch's force, machine by machine; the
chance of the radio over a grid of builds (the balloon's size, the switch's force), the smallest
change that makes it come on reliably, and that build's own Monte Carlo. Drawn:
docs/img/konstanz-study.png. docs/extensions.md ("Would the radio come on?") quotes the output.

Usage: scripts/konstanz-study.py [WHATNEXT] [IMAGE]
  defaults: build/whatnext, docs/img/konstanz-study.png
Needs Debian's python3-matplotlib; about 40,000 machines, a few seconds on two cores.
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PRESET = os.path.join(ROOT, "examples", "konstanz.toml")
MACHINES, SEED = 4000, 35
# The build's uncertainties, as examples/konstanz.toml states them (one standard deviation);
# the switch's is a quarter of its force, whatever that force is.
SPREADS = {
    "balloon.radius": 0.005, "balloon.rubber_mass": 0.0003, "balloon.drag_coefficient": 0.05,
    "air.density": 0.02, "air.helium_density": 0.01,
    "geometry.rope_length": 0.003, "geometry.rope_on_lid": 0.003, "radio.string_length": 0.003,
    "masses.sandbag": 0.005, "masses.lid": 0.005, "seesaw.mass": 0.01,
    "start.sandbag_x": 0.005, "start.sandbag_height": 0.005,
}
SWITCH_SPREAD = 0.25
G = 9.81


def monte_carlo(whatnext, sets, machines, seed, work):
    """The rows of a Monte Carlo around the preset with these --set values."""
    out = os.path.join(work, "mc.csv")
    switch = dict(sets).get("radio.switch_force", 0.03)
    cmd = [whatnext, "sweep", PRESET, "--samples", str(machines), "--seed", str(seed), "--out", out]
    for key, value in sets:
        cmd += ["--set", f"{key}={value}"]
    for key, sd in list(SPREADS.items()) + [("radio.switch_force", SWITCH_SPREAD * switch)]:
        cmd += ["--spread", f"{key}=±{sd:g}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(out, newline="") as f:
        return list(csv.DictReader(f))


def pull(row):
    """The string's pull once straight: the balloon's net lift (docs/extensions.md, "Balloon
    physics"), computed here from the machine's own numbers, not read from the program."""
    r = float(row["balloon.radius"])
    volume = 4.0 / 3.0 * math.pi * r ** 3
    return G * (volume * (float(row["air.density"]) - float(row["air.helium_density"]))
                - float(row["balloon.rubber_mass"]))


def quantiles(values, qs=(0.05, 0.5, 0.95)):
    v = sorted(values)
    return [v[min(len(v) - 1, int(q * len(v)))] for q in qs] if v else [float("nan")] * len(qs)


def summary(name, rows):
    on = [float(r["radio_on"]) for r in rows if r["outcome"] == "radio_on"]
    off = [float(r["switch_stays_off"]) for r in rows if r["outcome"] == "switch_stays_off"]
    # A skin heavier than the lift is refused as input: that balloon does not float at all.
    sinks = sum(1 for r in rows if r["outcome"] == "invalid" and "so that the balloon rises" in r["error"])
    slow = sum(1 for r in rows if r["outcome"] == "timeout")
    other = len(rows) - len(on) - len(off) - sinks - slow
    q = quantiles(on)
    print(f"{name}: radio on in {len(on)} of {len(rows)} machines ({100 * len(on) / len(rows):.1f} %)"
          + (f", at {q[1]:.3f} s (5 % {q[0]:.3f} s, 95 % {q[2]:.3f} s)" if on else "")
          + f"; off: the string pulls too weakly in {len(off)}, the balloon does not float in {sinks}, "
          f"has not reached its string after 5 s in {slow}; other outcomes {other}", flush=True)
    return on, off


def main():
    whatnext = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "whatnext")
    image = sys.argv[2] if len(sys.argv) > 2 else os.path.join(ROOT, "docs", "img", "konstanz-study.png")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with tempfile.TemporaryDirectory() as work:
        built = monte_carlo(whatnext, [], MACHINES, SEED, work)
        on_built, off_built = summary("the built machine (examples/konstanz.toml)", built)
        pulls = [pull(r) for r in built]
        switches = [float(r["radio.switch_force"]) for r in built]
        q = quantiles(pulls)
        print(f"  the string's pull: median {q[1]:.4f} N (5 % {q[0]:.4f}, 95 % {q[2]:.4f}); "
              f"radio on exactly where the pull reaches the switch's force: "
              f"{all((p >= s) == (r['outcome'] == 'radio_on') for p, s, r in zip(pulls, switches, built))}")
        # The builds within reach: the balloon's size (up to the box's 0.12 m), the switch's force.
        radii = [0.09, 0.095, 0.10, 0.105, 0.11, 0.115]
        forces = [0.005, 0.0075, 0.01, 0.0125, 0.015, 0.02, 0.025, 0.03, 0.04]
        chance = []
        for r in radii:
            line = []
            for f in forces:
                rows = monte_carlo(whatnext, [("balloon.radius", r), ("radio.switch_force", f)], 400, SEED, work)
                line.append(sum(x["outcome"] == "radio_on" for x in rows) / len(rows))
            chance.append(line)
            print(f"  balloon {r:.3f} m: " + ", ".join(f"{f:g} N {100 * c:.0f} %" for f, c in zip(forces, line)),
                  flush=True)
        # The change that makes it reliable: the largest balloon that still fits the box with two of
        # its standard deviations to spare, and the strongest switch it flips in 99.5 % of builds.
        fix_radius = max(r for r in radii if r + 2 * SPREADS["balloon.radius"] <= 0.12 + 1e-12)
        line = chance[radii.index(fix_radius)]
        fix_force = max(f for f, c in zip(forces, line) if c >= 0.995)
        fixed = monte_carlo(whatnext, [("balloon.radius", fix_radius), ("radio.switch_force", fix_force)],
                            MACHINES, SEED + 1, work)
        on_fixed, _ = summary(f"the fix: a balloon of {fix_radius:g} m and a {fix_force:g} N switch", fixed)
        print(f"  the string's pull: median {quantiles([pull(r) for r in fixed])[1]:.4f} N")

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    ax = axes[0]
    colour = ["tab:green" if r["outcome"] == "radio_on" else "tab:red" for r in built]
    ax.scatter(pulls, switches, s=4, c=colour, alpha=0.5, linewidths=0)
    top = max(max(pulls), max(switches)) * 1.05
    ax.plot([0, top], [0, top], color="black", lw=1)
    ax.set_xlim(0, top)
    ax.set_ylim(0, top)
    ax.set_xlabel("the balloon's pull on its string [N]")
    ax.set_ylabel("the switch's force [N]")
    ax.set_title(f"the built machine: radio on in {100 * len(on_built) / len(built):.0f} % of {len(built)}\n"
                 "(green on, red off; on the line the pull is the force)")
    ax = axes[1]
    mesh = ax.imshow([[100 * c for c in line] for line in chance], origin="lower", aspect="auto",
                     cmap="RdYlGn", vmin=0, vmax=100)
    ax.set_xticks(range(len(forces)), [f"{f:g}" for f in forces], rotation=45)
    ax.set_yticks(range(len(radii)), [f"{r:g}" for r in radii])
    for i, line in enumerate(chance):
        for j, c in enumerate(line):
            ax.text(j, i, f"{100 * c:.0f}", ha="center", va="center", fontsize=8)
    ax.add_patch(plt.Rectangle((forces.index(0.03) - 0.5, radii.index(0.10) - 0.5), 1, 1, fill=False, lw=2))
    ax.add_patch(plt.Rectangle((forces.index(fix_force) - 0.5, radii.index(fix_radius) - 0.5), 1, 1, fill=False,
                               lw=2, ls="--"))
    ax.set_xlabel("the switch's force [N]")
    ax.set_ylabel("the balloon's radius [m]")
    ax.set_title("chance of the radio [%], 400 builds each\n(solid: as built; dashed: the fix)")
    fig.colorbar(mesh, ax=ax)
    ax = axes[2]
    bins = [0.8 + 0.02 * i for i in range(41)]
    ax.hist(on_fixed, bins=bins, color="tab:blue", alpha=0.7, label=f"the fix: {fix_radius:g} m, {fix_force:g} N ({len(on_fixed)})")
    ax.hist(on_built, bins=bins, color="tab:green", alpha=0.7, label=f"as built, when on ({len(on_built)})")
    ax.set_xlabel("radio on [s]")
    ax.set_ylabel("machines")
    ax.set_title("when the radio comes on")
    ax.legend()
    fig.tight_layout()
    fig.savefig(image, dpi=90, metadata={"Software": None})
    print(f"written to {image}")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The impact study of docs/impact.md: a rope that stretches against the four impact laws.

For the paper's examples 1, 2 and 4 it runs the machine with a rope of growing stiffness k
(1e2 ... 1e8 N/m) at a few damping ratios zeta, records the outcome and the lid's angular speed
when the first jerk is over (the rope's first rope_slack after its first rope_taut), and compares
them with the inextensible rope under each of the four impact laws, and with the rope law followed
by Newton's restitution e(zeta) on the rope (restitution.rope), the limit docs/impact.md derives.

  scripts/impact-study.py build/whatnext docs/img      # writes impact-*.png and prints the tables
"""
import json
import math
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

EXAMPLES = (1, 2, 4)
LAWS = ("rope", "angular-momentum-sum", "kinetic-energy", "linear-momentum")
ZETAS = (0.0, 0.1, 1.0, 10.0)
STIFFNESS = [10.0 ** (2 + i / 2) for i in range(13)]  # 1e2 ... 1e8 N/m, half decades


STATS = {"runs": 0, "residual": 0.0, "slowest": (0.0, "")}


def run(exe, example, sets):
    """The events and outcome of one run (None and the message if it fails)."""
    STATS["runs"] += 1
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        ev = Path(tmp) / "e.json"
        args = [exe, "run", "--example", str(example), "--events", str(ev)]
        for s in sets:
            args += ["--set", s]
        p = subprocess.run(args, capture_output=True, text=True)
        if p.returncode != 0:
            return None, (p.stderr.strip() or p.stdout.strip()).splitlines()[-1]
        doc = json.loads(ev.read_text())
        took = time.perf_counter() - start
        if took > STATS["slowest"][0]:
            STATS["slowest"] = (took, f"example {example} " + " ".join(sets))
        STATS["residual"] = max([STATS["residual"]] + [abs(e["ledger"]["residual"]) for e in doc["events"]])
        return doc, None


def first_jerk_end(doc):
    """The lid's angular speed [deg/s] at the first rope_slack after the first rope_taut, and its time."""
    taut = False
    for e in doc["events"]:
        if e["type"] == "rope_taut":
            taut = True
        elif taut and e["type"] == "rope_slack":
            return e["state"]["dphi_l_deg_per_s"], e["t"]
    return float("nan"), float("nan")


def jerk_state(doc):
    for e in doc["events"]:
        if e["type"] == "rope_taut":
            return e["state"]
    raise RuntimeError("no rope_taut")


def outcome(doc):
    last = doc["events"][-1]
    return last["type"], last["t"]


def effective_mass(exe, example, st):
    """The rope's effective mass at the rigid jerk: 1/m = a_S^2 / (m_S r^2) + a_L^2 / I_L, with a_S, a_L
    the span's derivatives along phiS and phiL (the massless seesaw carries the sandbag as m_S r^2)."""
    cfg = tomllib.loads(subprocess.run([exe, "examples", str(example)], capture_output=True, text=True,
                                       check=True).stdout)
    g = cfg["geometry"]
    rh, rl = g["seesaw_right_arm"], g["lid_half_length"]
    if "hinge_offset" in g:
        hx, hh = g["hinge_offset"][0], -g["hinge_offset"][1]
    else:
        gam = math.radians(g["hinge_angle"])
        hx, hh = g["hinge_distance"] * math.cos(gam), -g["hinge_distance"] * math.sin(gam)
    knot = g.get("rope_on_lid", 2 * rl)
    ms, ml = cfg["masses"]["sandbag"], cfg["masses"]["lid"]
    il = ml * (2 * rl) ** 2 / 3
    ps, pl, r = math.radians(st["phi_s_deg"]), math.radians(st["phi_l_deg"]), st["r"]
    R = (rh * math.cos(ps), rh * math.sin(ps))
    E = (hx + knot * math.cos(pl), hh + knot * math.sin(pl))
    D = (R[0] - E[0], R[1] - E[1])
    span = math.hypot(*D)
    a_s = (D[0] * -R[1] + D[1] * R[0]) / span
    a_l = -(D[0] * -knot * math.sin(pl) + D[1] * knot * math.cos(pl)) / span
    return 1.0 / (a_s ** 2 / (ms * r * r) + a_l ** 2 / il)


def restitution(zeta):
    """Newton's coefficient of the one-sided linear spring-damper: x'' = -max(0, x + 2 zeta x'),
    x(0) = 0, x'(0) = 1, until the pull is zero; e = -x' then (RK4, 2e5 steps per unit time)."""
    if zeta == 0.0:
        return 1.0
    h = 1e-5 / max(1.0, zeta)
    x, v = 0.0, 1.0

    def f(x, v):
        return v, -max(0.0, x + 2 * zeta * v)

    t = 0.0
    while True:
        k1 = f(x, v)
        k2 = f(x + h / 2 * k1[0], v + h / 2 * k1[1])
        k3 = f(x + h / 2 * k2[0], v + h / 2 * k2[1])
        k4 = f(x + h * k3[0], v + h * k3[1])
        xn = x + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        vn = v + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        t += h
        if t > h and xn + 2 * zeta * vn <= 0.0:  # the pull reached zero: the ends part
            # linear interpolation of v to the zero of the pull
            p0, p1 = x + 2 * zeta * v, xn + 2 * zeta * vn
            w = p0 / (p0 - p1)
            return -(v + w * (vn - v))
        x, v = xn, vn


def main():
    exe = sys.argv[1] if len(sys.argv) > 1 else "build/whatnext"
    out = Path(sys.argv[2] if len(sys.argv) > 2 else "docs/img")
    out.mkdir(parents=True, exist_ok=True)
    es = {z: restitution(z) for z in ZETAS}
    print("e(zeta):", ", ".join(f"{z:g}: {es[z]:.4f}" for z in ZETAS))
    results = {}
    for ex in EXAMPLES:
        laws = {}
        for law in LAWS:
            doc, err = run(exe, ex, [f"run.impact_law={law}"])
            laws[law] = (first_jerk_end(doc), outcome(doc))
        rigid, _ = run(exe, ex, [])
        m_eff = effective_mass(exe, ex, jerk_state(rigid))
        pred = {}
        for z in ZETAS:
            doc, err = run(exe, ex, [f"restitution.rope={min(es[z], 1 - 1e-9):.12g}"])
            pred[z] = (first_jerk_end(doc), outcome(doc))
        spring = {}
        for z in ZETAS:
            for k in STIFFNESS:
                c = 2 * z * math.sqrt(k * m_eff)
                doc, err = run(exe, ex, [f"rope.stiffness={k:.6g}", f"rope.damping={c:.6g}"])
                spring[(z, k)] = (first_jerk_end(doc), outcome(doc)) if doc else (None, err)
        results[ex] = dict(laws=laws, pred=pred, spring=spring, m_eff=m_eff)
        print(f"\nexample {ex}: effective mass at the jerk {m_eff:.4f} kg")
        for law in LAWS:
            (w, t), (o, to) = laws[law]
            print(f"  {law:22s} lid {w:9.2f} deg/s at {t:.6f} s; {o} {to:.4f} s")
        for z in ZETAS:
            (w, t), (o, to) = pred[z]
            print(f"  rope law, e = {es[z]:.4f} (zeta {z:g}): lid {w:9.2f} deg/s at {t:.6f} s; {o} {to:.4f} s")
        for z in ZETAS:
            for k in STIFFNESS:
                a, b = spring[(z, k)]
                if a is None:
                    print(f"  zeta {z:5g} k {k:9.3g}: fails: {b}")
                    continue
                (w, t), (o, to) = a, b
                print(f"  zeta {z:5g} k {k:9.3g} (c {2 * z * math.sqrt(k * m_eff):9.4g}): lid {w:9.2f} deg/s "
                      f"at {t:.6f} s; {o} {to:.4f} s")
    print(f"\n{STATS['runs']} runs; the largest ledger residual {STATS['residual']:.2g} J; the slowest run "
          f"{STATS['slowest'][0]:.2f} s: {STATS['slowest'][1]}")
    plot(results, es, out)


COLORS = {0.0: "tab:red", 0.1: "tab:orange", 1.0: "tab:green", 10.0: "tab:blue"}
LAW_STYLE = {"rope": "-", "angular-momentum-sum": "--", "kinetic-energy": "-.", "linear-momentum": ":"}


def plot(results, es, out):
    for what, idx, ylabel, name in (("speed", 0, "lid speed when the first jerk ends [deg/s]", "impact-speed.png"),
                                    ("outcome", 1, "outcome time [s]", "impact-outcome.png")):
        fig, axes = plt.subplots(1, 3, figsize=(15, 5.4))
        for ax, ex in zip(axes, EXAMPLES):
            r = results[ex]
            shown = []
            for z in ZETAS:
                ks, vs = [], []
                for k in STIFFNESS:
                    a, b = r["spring"][(z, k)]
                    if a is None or not math.isfinite(a[0]):
                        continue
                    ks.append(k)
                    vs.append(a[0] if what == "speed" else b[1])
                ax.semilogx(ks, vs, "o-", color=COLORS[z], ms=4, label=f"stretching rope, ζ = {z:g}")
                pv = r["pred"][z][idx][0] if what == "speed" else r["pred"][z][idx][1]
                ax.plot([STIFFNESS[-1] * 2.5], [pv], marker="<", color=COLORS[z], ms=9, ls="none")
                shown += vs + [pv]
            top = 1.15 * max(shown)
            if what == "outcome":
                top = min(top, 1.2)
            off = []
            for law in LAWS:
                (w, _), (o, to) = r["laws"][law]
                v = w if what == "speed" else to
                if v > top:
                    off.append(f"{law}: {v:.4g}")
                    continue
                ax.axhline(v, color="0.3", ls=LAW_STYLE[law], lw=1.3, label=f"inextensible rope, {law} law")
            if off:
                ax.text(0.02, 0.98, "off the scale, " + "; ".join(off), transform=ax.transAxes, fontsize=8,
                        va="top")
            ax.set_ylim(0, top)
            ax.set_xlim(STIFFNESS[0] / 2, STIFFNESS[-1] * 5)
            ax.set_title(f"example {ex}")
            ax.set_xlabel("rope stiffness k [N/m]")
            ax.set_ylabel(ylabel)
            ax.grid(True, which="major", alpha=0.3)
        handles, labels = [], []
        for ax in axes:
            for h, l in zip(*ax.get_legend_handles_labels()):
                if l not in labels:
                    handles.append(h)
                    labels.append(l)
        fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8.5)
        fig.suptitle("triangles at the right: the inextensible rope under the rope law with Newton's restitution e(ζ) "
                     "(the predicted limit)", fontsize=10)
        fig.tight_layout(rect=(0, 0.1, 1, 0.97))
        fig.savefig(out / name, dpi=90)
        plt.close(fig)
    # Convergence: relative distance of the lid's speed from the predicted limit.
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5), constrained_layout=True)
    for ax, ex in zip(axes, EXAMPLES):
        r = results[ex]
        for z in ZETAS:
            target = r["pred"][z][0][0]
            ks, errs = [], []
            for k in STIFFNESS:
                a, _ = r["spring"][(z, k)]
                if a is None or not math.isfinite(a[0]):
                    continue
                ks.append(k)
                errs.append(max(abs(a[0] - target) / abs(target), 1e-12))
            ax.loglog(ks, errs, "o-", color=COLORS[z], ms=4, label=f"ζ = {z:g} (e = {es[z]:.3f})")
        # The heavily damped rope against the rope law itself (no restitution).
        target = r["laws"]["rope"][0][0]
        ks, errs = [], []
        for k in STIFFNESS:
            a, _ = r["spring"][(10.0, k)]
            if a is not None and math.isfinite(a[0]):
                ks.append(k)
                errs.append(max(abs(a[0] - target) / abs(target), 1e-12))
        ax.loglog(ks, errs, "s--", color=COLORS[10.0], ms=3, lw=1, label="ζ = 10 against the rope law itself")
        ax.loglog(STIFFNESS, [0.3 * (STIFFNESS[0] / k) ** 0.5 for k in STIFFNESS], "k:", lw=1, label="∝ k^(-1/2)")
        ax.set_title(f"example {ex}")
        ax.set_xlabel("rope stiffness k [N/m]")
        ax.set_ylabel("|lid speed − limit| / limit")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.savefig(out / "impact-convergence.png", dpi=90)
    plt.close(fig)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The paper's equations for example 1 with SciPy's solve_ivp: what a user would write instead of
whatnext (docs/performance.md, "Peers"). Our own code, from docs/model.md's equations: free fall
(M1), the polar equations of the sandbag on the massless seesaw (M3), eqs. (3)-(4) with the rope
straight (M4), the rope law's impact (eq. 7), the free lid, events found by solve_ivp's root finder.
It handles the events example 1 meets (landing, the rope's jerk, the lid's swing) and says so if
a machine needs another.

Usage: bench/peers/scipy_example1.py [RTOL] [REPEATS]
Prints the lid-open time and the wall time per run (best of REPEATS).
"""
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

# Example 1 (examples/example1.toml)
G = 9.81
R_H, R_L, L_R, F, GAMMA = 0.6, 0.2, 1.0, 0.8, math.radians(27.0)
M_S, M_L = 0.6, 0.5
X0, H0, PHI_S0, PHI_L0 = -0.3, 1.0, math.radians(-25.0), math.radians(5.0)
I_L = M_L * (2 * R_L) ** 2 / 3
HX, HY = F * math.cos(GAMMA), -F * math.sin(GAMMA)
OPEN = math.pi / 2 - math.pi / 200  # lid_open: 90 deg minus the 0.9 deg margin
T_MAX = 2.0


def rope(ps, pl):
    """Gap C = |R - E|^2 - l_R^2 and its partial derivatives (docs/model.md, section 3)."""
    R = np.array([R_H * math.cos(ps), R_H * math.sin(ps)])
    EH = np.array([2 * R_L * math.cos(pl), 2 * R_L * math.sin(pl)])
    D = R - (np.array([HX, HY]) + EH)
    perp = lambda v: np.array([-v[1], v[0]])
    C = D @ D - L_R**2
    CS = 2 * D @ perp(R)
    CL = -2 * D @ perp(EH)
    CSS = 2 * (R_H**2 - D @ R)
    CLL = 2 * (4 * R_L**2 + D @ EH)
    CSL = -2 * perp(R) @ perp(EH)
    return C, CS, CL, CSS, CLL, CSL


def transfer(ps, pl):
    C, CS, CL, CSS, CLL, CSL = rope(ps, pl)
    k = -CS / CL
    k2 = -(CSS + 2 * CSL * k + CLL * k * k) / CL
    return k, k2


def lid_free(pl, wl, resting):
    return 0.0 if resting else -M_L * G * R_L * math.cos(pl) / I_L


def simulate(rtol):
    atol = rtol * 1e-2
    t = 0.0
    # M1: sandbag falling, seesaw still, lid resting on the box.
    def m1(t, y):
        return [y[2], y[3], 0.0, -G]
    def lands(t, y):  # the sandbag reaches the left arm's line
        return y[1] - y[0] * math.tan(PHI_S0)
    lands.terminal, lands.direction = True, -1
    s = solve_ivp(m1, (0.0, T_MAX), [X0, H0, 0.0, 0.0], method="DOP853", rtol=rtol, atol=atol, events=lands)
    t = s.t_events[0][0]
    x, h, vx, vh = s.y_events[0][0]
    events = [("sandbag_lands", t)]
    # M3: on the massless seesaw with the rope slack: the paper's polar equations.
    r, ps = math.hypot(x, h), math.atan2(-h, -x)
    rd = -vx * math.cos(ps) - vh * math.sin(ps)
    psd = (vx * math.sin(ps) - vh * math.cos(ps)) / r
    pl, pld, resting = PHI_L0, 0.0, True
    while t < T_MAX:
        def m3(t, y):
            r, rd, ps, psd, pl, pld = y
            return [rd, G * math.sin(ps) + r * psd**2, psd, (G * math.cos(ps) - 2 * rd * psd) / r,
                    pld, lid_free(pl, pld, resting)]
        def taut(t, y):
            return rope(y[2], y[4])[0]
        taut.terminal, taut.direction = True, 1
        def opened(t, y):
            return y[4] - OPEN
        opened.terminal, opened.direction = True, 1
        def rests(t, y):
            return PHI_L0 - y[4]
        rests.terminal, rests.direction = True, 1
        evs = [taut, opened] + ([] if resting else [rests])
        s = solve_ivp(m3, (t, T_MAX), [r, rd, ps, psd, pl, pld], method="DOP853", rtol=rtol, atol=atol, events=evs)
        hit = [i for i, te in enumerate(s.t_events) if len(te)]
        if not hit:
            events.append(("timeout", T_MAX))
            return events
        i = min(hit, key=lambda i: s.t_events[i][0])
        t = s.t_events[i][0]
        r, rd, ps, psd, pl, pld = s.y_events[i][0]
        if evs[i] is opened:
            events.append(("lid_open", t))
            return events
        if evs[i] is rests:
            raise SystemExit("the lid falls back onto the box: not handled here (example 1 does not)")
        # The rope comes straight: the rope law (eq. 7), the sandbag's speed along the arm kept.
        k, k2 = transfer(ps, pl)
        vperp = r * psd
        psd = (M_S * r * vperp + k * I_L * pld) / (M_S * r * r + I_L * k * k)
        pld = k * psd
        resting = False
        events.append(("rope_taut", t))
        # Does it stay straight? Eq. (4) gives the seesaw's acceleration with the rope straight;
        # the rope pulls if the lid then needs more than its free swing (the connecting-rod check).
        psdd = (M_S * G * r * math.cos(ps) - 2 * M_S * r * rd * psd
                - (M_L * G * R_L * math.cos(pl) + I_L * k2 * psd**2) * k) / (M_S * r * r + I_L * k * k)
        pldd = k * psdd + k2 * psd**2
        if I_L * pldd + M_L * G * R_L * math.cos(pl) >= 0.0:
            raise SystemExit("the rope stays straight (M4): not handled here (example 1 does not)")
        events.append(("rope_slack", t))
    events.append(("timeout", T_MAX))
    return events


def main():
    rtol = float(sys.argv[1]) if len(sys.argv) > 1 else 1e-10
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    best = math.inf
    for _ in range(repeats):
        start = time.perf_counter()
        events = simulate(rtol)
        best = min(best, time.perf_counter() - start)
    for name, t in events:
        print(f"{name} {t:.12f}")
    print(f"seconds_per_run {best:.6g}")


if __name__ == "__main__":
    main()

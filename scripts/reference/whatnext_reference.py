#!/usr/bin/env python3
"""An accuracy reference for whatnext, written apart from its C++ code.

The paper's machine with the massless seesaw (docs/model.md, sections 1-8): the sandbag falling,
landing on the arm, the rope jerked straight (the `rope` impact law: the perfectly inelastic
impact), the rope going slack, the lid swinging and landing on the box, the balloon caught and
freed by the lid, and the stops (lid open, seesaw vertical, sandbag at the pivot, timeout).

What is independent of whatnext here:
* the equations of motion: the straight-rope phase (M4) is derived at import by SymPy from the
  Lagrangian, with the lid's angle phiL a function of the seesaw's angle whose first and second
  derivatives come from differentiating the rope's closure |R - E|^2 = l_R^2 implicitly;
  the lid's angle is carried as a state of its own (phiL' = k phiS'), with no closed-form
  closure, no atan2 branches and no chart switch;
* the impact: the projection of the velocities onto the straight rope in the kinetic energy's
  metric, computed numerically (not eq. 7 written out);
* the integrator: Gragg-Bulirsch-Stoer extrapolation (the modified midpoint rule, Richardson
  extrapolated in h^2 to order 16), not a Runge-Kutta method, with no dense output;
* the events: each guard is watched at step ends (steps also bounded by the angles turned), and a
  sign change is located by bisection, re-integrating from the step's start to each trial time
  (a single extrapolation step), to 1e-15 s: no interpolant, no expansion of the guard.

On this seesaw it also has the extensions that are forces: the lid hinge's damper, the balloon's
drag and skin, and the rope that stretches (a one-sided spring-damper). A seesaw with mass, with
the built machine's floor and end stop, runs in full coordinates (full_coordinates.py).

It also has the four impact laws, the radio, a balloon smaller than the box (small_balloon.py)
and Coulomb friction: at the lid's hinge here, on the sandbag, the pivot and the hinge on the
seesaw with mass. Machines it does not cover (the sandbag's friction on the massless seesaw, a
rope straight at the start or at a landing, a lid left resting on a straight rope, a jerk with
k < 0 ...) raise NotCovered; it never guesses.

    from whatnext_reference import simulate, load_machine
    events = simulate(load_machine("examples/example2.toml", {"geometry.rope_length": 0.7}))
    # -> [("sandbag_lands", 0.2431...), ("rope_taut", ...), ...]

Command line: whatnext_reference.py FILE.toml [KEY=VALUE ...] prints the events.
Needs Debian's python3-sympy (and Python >= 3.11 for tomllib). README.md here says more.
"""
import math
import sys
import tomllib

import mpmath
import sympy as sp


class NotCovered(Exception):
    """The machine, or a situation in its run, is outside what this reference models."""


# ----------------------------------------------------------------------------------------------
# The equations, derived once by SymPy.

def _derive():
    s, L, r, rd, sd = sp.symbols("phiS phiL r rd sd", real=True)
    rH, Hx, Hy, a, lR, m, mL, rL, g, I = sp.symbols("rH Hx Hy a lR m mL rL g I", positive=True)
    R = sp.Matrix([rH * sp.cos(s), rH * sp.sin(s)])
    E = sp.Matrix([Hx + a * sp.cos(L), Hy + a * sp.sin(L)])
    C = (R - E).dot(R - E) - lR ** 2
    # phiL = P(phiS) on the straight rope: C(phiS, P(phiS)) = 0, differentiated twice.
    P = sp.Function("P")
    Cs = C.subs(L, P(s))
    d1 = sp.solve(sp.diff(Cs, s), sp.Derivative(P(s), s))[0]
    d2 = sp.solve(sp.diff(Cs, s, 2), sp.Derivative(P(s), (s, 2)))[0]
    k_expr = d1.subs(P(s), L)
    kp_expr = d2.subs(sp.Derivative(P(s), s), d1).subs(P(s), L)
    # The Lagrangian of M4: the sandbag at (-r cos phiS, -r sin phiS) on the arm, the lid P(phiS).
    t = sp.symbols("t")
    rt, st = sp.Function("r")(t), sp.Function("s")(t)
    Pt = P(st)
    x, h = -rt * sp.cos(st), -rt * sp.sin(st)
    T = m / 2 * (sp.diff(x, t) ** 2 + sp.diff(h, t) ** 2) + I / 2 * sp.diff(Pt, t) ** 2
    V = m * g * h + mL * g * rL * sp.sin(Pt)
    Lag = T - V
    cL, Tf = sp.symbols("cL Tf")
    D = cL / 2 * sp.diff(Pt, t) ** 2  # Rayleigh's dissipation function: the lid hinge's damper
    # and the hinge's Coulomb torque Tf against the lid's turning: its generalised forces
    # Tf d(phiL')/d(q') (docs/extensions.md, "Friction")
    eqs = [sp.diff(sp.diff(Lag, sp.diff(q, t)), t) - sp.diff(Lag, q) + sp.diff(D, sp.diff(q, t))
           + Tf * sp.diff(sp.diff(Pt, t), sp.diff(q, t)) for q in (rt, st)]
    k, kp = sp.symbols("k kp")
    rdd, sdd = sp.symbols("rdd sdd")
    rep = {sp.Derivative(rt, (t, 2)): rdd, sp.Derivative(st, (t, 2)): sdd}
    eqs = [e.subs(rep) for e in eqs]
    rep2 = {sp.Derivative(P(st), st, 2): kp}
    eqs = [e.subs(sp.Subs(sp.Derivative(P(s), (s, 2)), s, st), kp) for e in eqs]
    eqs = [e.doit() for e in eqs]
    eqs = [e.subs({sp.Derivative(P(st), (st, 2)): kp}) for e in eqs]
    eqs = [e.subs({sp.Derivative(P(st), st): k}) for e in eqs]
    eqs = [e.subs({sp.Derivative(rt, t): rd, sp.Derivative(st, t): sd}) for e in eqs]
    eqs = [e.subs({P(st): L, rt: r, st: s}) for e in eqs]
    sol = sp.solve(eqs, [rdd, sdd], dict=True)[0]
    params = (rH, Hx, Hy, a, lR, m, mL, rL, g, I, cL)
    geo = (s, L) + params
    acc = [sp.simplify(sol[rdd]), sp.simplify(sol[sdd])]
    funs = []
    for module in ("math", "mpmath"):
        funs.append({
            "C": sp.lambdify(geo, C, module),
            "Cs": sp.lambdify(geo, sp.diff(C, s), module),
            "CL": sp.lambdify(geo, sp.diff(C, L), module),
            # the rope's span |R - E| and its partial derivatives, for the rope that stretches
            "span": sp.lambdify(geo, [sp.sqrt(C + lR ** 2), sp.diff(sp.sqrt(C + lR ** 2), s),
                                      sp.diff(sp.sqrt(C + lR ** 2), L)], module),
            "k": sp.lambdify(geo, k_expr, module),
            "kp": sp.lambdify(geo, kp_expr, module),
            "acc": sp.lambdify((r, s, L, rd, sd, k, kp) + params + (Tf,), acc, module),
        })
    return funs


F_FLOAT, F_MP = _derive()
# The numbers a run computes with: floats (math) by default, or mpmath's at more digits (precise()).
N, F = math, F_FLOAT


def num(x):
    return N.mpf(x) if N is not math else float(x)


def precise(digits):
    """Run with mpmath's numbers at this many digits (None: back to floats). Slow: for the
    ill-conditioned events where a float's rounding of the rope's gap is the error."""
    global N, F
    if digits:
        N, F = mpmath, F_MP
        mpmath.mp.dps = digits
    else:
        N, F = math, F_FLOAT


# ----------------------------------------------------------------------------------------------
# The machine's inputs.

DEFAULTS = {
    "geometry.seesaw_right_arm": 0.6, "geometry.lid_half_length": 0.2, "geometry.rope_length": 1.0,
    "geometry.hinge_distance": 0.8, "geometry.hinge_angle": 27.0, "masses.sandbag": 0.6,
    "masses.lid": 0.5, "air.density": 1.29, "air.helium_density": 0.18, "balloon.model": "program",
    "start.sandbag_x": -0.3, "start.sandbag_height": 1.0, "start.seesaw_angle": -25.0,
    "start.lid_angle": 5.0, "run.t_max": 5.0, "run.vertical_margin": 0.9, "run.gravity": 9.81,
    "run.impact_law": "rope",
}
# Keys that do not change the physics (how whatnext integrates or samples).
IGNORED = {"run.output_step", "run.step", "run.integrator", "run.tolerance"}
OTHER = {"geometry.hinge_offset", "geometry.rope_on_lid", "balloon.radius", "balloon.rubber_mass", "balloon.drag",
         "balloon.drag_coefficient"}
# The radio (docs/extensions.md, "The radio"), on the massless seesaw.
RADIO = {"radio.enabled", "radio.switch_offset", "radio.string_length", "radio.switch_force"}
STOPS = {"lid_open", "seesaw_vertical", "sandbag_at_pivot", "rope_locked", "radio_on", "switch_stays_off"}
# A seesaw with mass and the dampers: the full-coordinates run (full_coordinates.py).
HEAVY = {"seesaw.mass", "seesaw.left_arm", "seesaw.inertia", "seesaw.com_offset", "damping.pivot",
         "damping.lid_hinge", "rope.stiffness", "rope.damping", "floor.enabled", "floor.restitution",
         "seesaw.end_stop", "restitution.sandbag", "restitution.rope", "restitution.lid", "restitution.stop",
         "friction.sandbag", "friction.pivot", "friction.lid_hinge"}


def load_machine(path=None, overrides=None):
    """The machine of a TOML file (or the defaults) with 'section.key' overrides, as a dict."""
    keys = dict(DEFAULTS)
    if path:
        with open(path, "rb") as f:
            for section, table in tomllib.load(f).items():
                for name, value in table.items():
                    keys[f"{section}.{name}"] = value
    for name, value in (overrides or {}).items():
        keys[name] = value
    if "geometry.hinge_offset" in (overrides or {}):
        keys.pop("geometry.hinge_distance", None)
    for name in keys:
        if name not in DEFAULTS.keys() | IGNORED | OTHER | HEAVY | RADIO:
            raise NotCovered(f"{name} is not modelled by the reference")
    if keys["run.impact_law"] not in ("rope", "angular-momentum-sum", "kinetic-energy", "linear-momentum"):
        raise NotCovered(f"the {keys['run.impact_law']} impact law")
    return keys


class Machine:
    def __init__(self, keys):
        self.rH = num(keys["geometry.seesaw_right_arm"])
        self.rL = num(keys["geometry.lid_half_length"])
        self.lR = num(keys["geometry.rope_length"])
        if "geometry.hinge_offset" in keys:
            dx, dh = keys["geometry.hinge_offset"]
            self.Hx, self.Hy = num(dx), -num(dh)
        else:
            f, gam = num(keys["geometry.hinge_distance"]), N.radians(num(keys["geometry.hinge_angle"]))
            self.Hx, self.Hy = f * N.cos(gam), -f * N.sin(gam)
        self.a = num(keys.get("geometry.rope_on_lid", 2 * self.rL))
        self.m = num(keys["masses.sandbag"])
        self.mL = num(keys["masses.lid"])
        self.I = self.mL * (2 * self.rL) ** 2 / 3
        self.g = num(keys["run.gravity"])
        self.rB = num(keys.get("balloon.radius", self.rL))
        self.small = self.rB < self.rL  # a disc in the box (small_balloon.py)
        # the balloon (docs/extensions.md, "Balloon physics"): net lift F over the accelerated mass,
        # less its drag D v|v|
        rho_a, rho_he = num(keys["air.density"]), num(keys["air.helium_density"])
        # (per unit of the balloon's volume: the skin's mass as a density)
        vol = 4 * N.pi * self.rB ** 3 / 3
        rho_r = num(keys.get("balloon.rubber_mass", 0.0)) / vol
        denominator = {"program": rho_a, "lagrangian": rho_he, "added-mass": rho_he + rho_a / 2}
        density = denominator[keys["balloon.model"]] + rho_r
        self.aB = self.g * (rho_a - rho_he - rho_r) / density
        drag = keys.get("balloon.drag", False) in (True, "true") or "balloon.drag_coefficient" in keys
        cd = num(keys.get("balloon.drag_coefficient", 0.47))
        self.drag = rho_a * cd * N.pi * self.rB ** 2 / 2 / (density * vol) if drag else 0.0
        self.lift = self.g * (rho_a - rho_he - rho_r) * vol  # what a straight string pulls with
        self.radio = keys.get("radio.enabled", False) in (True, "true") or any(
            k in keys for k in RADIO - {"radio.enabled"})
        dx, dh = keys.get("radio.switch_offset", [0.5, 0.0])
        self.switch = (self.Hx + 2 * self.rL + num(dx), self.Hy + num(dh))
        self.string = num(keys.get("radio.string_length", 1.0))
        self.switch_force = num(keys.get("radio.switch_force", 0.0))
        self.x0, self.h0 = num(keys["start.sandbag_x"]), num(keys["start.sandbag_height"])
        self.s0 = N.radians(num(keys["start.seesaw_angle"]))
        self.L0 = N.radians(num(keys["start.lid_angle"]))
        self.t_max = num(keys["run.t_max"])
        self.law = keys["run.impact_law"]
        self.top = N.pi / 2 - N.radians(num(keys["run.vertical_margin"]))
        self.cL = num(keys.get("damping.lid_hinge", 0.0))
        self.stretchy = "rope.stiffness" in keys  # a one-sided spring-damper (docs/impact.md)
        # Coulomb friction at the lid's hinge: the bound, and the torque against the lid's turning
        # now (+-Th slipping, 0 idle on the box), or the lid stuck
        self.Th = num(keys.get("friction.lid_hinge", 0.0))
        self.Tf, self.lid_stuck = num(0.0), False
        self.k_rope = num(keys.get("rope.stiffness", 0.0))
        self.c_rope = num(keys.get("rope.damping", 0.0))
        self.params = (self.rH, self.Hx, self.Hy, self.a, self.lR, self.m, self.mL, self.rL, self.g, self.I,
                       self.cL)

    # geometry
    def C(self, s, L):
        return F["C"](s, L, *self.params)

    def lock(self, s, L):
        """(R - H) x (E - H): negative with the lid below the rope, the linkage's physical shape
        (docs/model.md, section 3); zero where the rope would touch the hinge."""
        Rx, Ry = self.rH * N.cos(s), self.rH * N.sin(s)
        Ex, Ey = self.Hx + self.a * N.cos(L), self.Hy + self.a * N.sin(L)
        return (Rx - self.Hx) * (Ey - self.Hy) - (Ry - self.Hy) * (Ex - self.Hx)

    def k(self, s, L):
        return F["k"](s, L, *self.params), F["kp"](s, L, *self.params)

    def m4_acc(self, r, s, L, rd, sd):
        k, kp = self.k(s, L)
        rdd, sdd = F["acc"](r, s, L, rd, sd, k, kp, *self.params, self.Tf)
        Ldd = k * sdd + kp * sd * sd
        # the rope's on the lid
        torque = self.I * Ldd + self.mL * self.g * self.rL * N.cos(L) + self.cL * k * sd + self.Tf
        return rdd, sdd, k, torque

    def balloon_acc(self, v):
        return self.aB - self.drag * v * abs(v)

    def lid_free_acc(self, L, Ld):
        if self.lid_stuck:
            return 0.0
        return -(self.mL * self.g * self.rL * N.cos(L) + self.cL * Ld + self.Tf) / self.I

    def h_lim(self, L, Ld):
        c, sn = N.cos(L), N.sin(L)
        return -self.rB * c / (1 + sn), self.rB * Ld / (1 + sn)

    def h_lim_acc(self, L, Ld, Ldd):
        sn, c = N.sin(L), N.cos(L)
        return self.rB * (Ldd / (1 + sn) - Ld * Ld * c / (1 + sn) ** 2)


# ----------------------------------------------------------------------------------------------
# Gragg-Bulirsch-Stoer extrapolation.

SEQ = [2 * (j + 1) for j in range(8)]


def gbs(f, y, h):
    """One extrapolation step of the autonomous y' = f(y); the result and its error estimate."""
    table = []
    for j, n in enumerate(SEQ):
        hs = h / n
        z0 = y
        d = f(z0)
        z1 = [a + hs * b for a, b in zip(z0, d)]
        for _ in range(n - 1):
            d = f(z1)
            z0, z1 = z1, [a + 2 * hs * b for a, b in zip(z0, d)]
        d = f(z1)
        row = [[0.5 * (a + b + hs * c) for a, b, c in zip(z0, z1, d)]]
        for kk in range(1, j + 1):
            ratio = (n / SEQ[j - kk]) ** 2 - 1
            row.append([a + (a - b) / ratio for a, b in zip(row[kk - 1], table[j - 1][kk - 1])])
        table.append(row)
    best, prev = table[-1][-1], table[-1][-2]
    return best, [abs(a - b) for a, b in zip(best, prev)]


# ----------------------------------------------------------------------------------------------
# The run.

class Run:
    def __init__(self, mc, tol=1e-13):
        self.mc, self.tol = mc, tol
        self.events = []
        self.energy = []
        self.spring = False  # the rope that stretches pulling (with the sandbag on the arm)
        self.latched = False  # the radio's latch holds the lid open: only the balloon matters
        self.stops = STOPS - {"radio_on"} - ({"lid_open"} if mc.radio else set())
        # a balloon smaller than the box: a disc among the lid and the walls (small_balloon.py),
        # its four entries at the state's end instead of (hB, vB)
        self.small = None
        if mc.small:
            if N is not math:
                raise NotCovered("more digits with a balloon smaller than the box")
            import small_balloon
            self.small = small_balloon.SmallBalloon(mc, self)

    # The state: sandbag 'air' (M1) or 'arm' with rope 'slack' (M3, free fall) or 'taut' (M4);
    # free fall: y = [x, h, vx, vh, phiL, phiL', hB, vB]; M4: y = [r, phiS, phiL, r', phiS', hB, vB].
    def flow(self, y):
        if self.small:
            d = self.machine_flow(y[:-4] + [0.0, 0.0])[:-2]
            _, _, L, Ld, Ldd, _ = self.kin(y)
            return d + self.small.flow(y[-4:], L, Ld, Ldd)
        return self.machine_flow(y)

    def machine_flow(self, y):
        mc = self.mc
        if self.rope == "taut":
            r, s, L, rd, sd, hB, vB = y
            rdd, sdd, k, _ = mc.m4_acc(r, s, L, rd, sd)
            return [rd, sd, k * sd, rdd, sdd] + self.balloon_flow(vB)
        x, h, vx, vh, L, Ld, hB, vB = y
        if self.spring:
            ax, ah, Ldd, _, _, _ = self.spring_acc(y)
            return [vx, vh, ax, ah, Ld, Ldd] + self.balloon_flow(vB)
        Ldd = 0.0 if self.lid == "rest" else mc.lid_free_acc(L, Ld)
        return [vx, vh, 0.0, -mc.g, Ld, Ldd] + self.balloon_flow(vB)

    def tension(self, y, slack=False):
        """k s + c s' of the rope that stretches, with the sandbag on the massless seesaw; and the
        span's partial derivatives. slack: the damper's part only while longer than l_R."""
        mc = self.mc
        x, h, vx, vh, L, Ld = y[:6]
        s = N.atan2(-h, -x)
        sd = (vx * N.sin(s) - vh * N.cos(s)) / N.hypot(x, h)
        span, dS, dL = F["span"](s, L, *mc.params)
        stretch = span - mc.lR
        damper = mc.c_rope * (dS * sd + dL * Ld)
        return mc.k_rope * stretch + (damper if stretch >= 0 or not slack else 0.0), s, dS, dL

    def spring_acc(self, y):
        """The accelerations while the stretched rope pulls: its torque on the massless seesaw is
        taken by the arm's push on the sandbag, N r = -Q_S (docs/impact.md), its torque on the
        lid Q_L. Also N, the box's push on a resting lid, and T."""
        mc = self.mc
        x, h, vx, vh, L, Ld = y[:6]
        T, s, dS, dL = self.tension(y)
        r = N.hypot(x, h)
        push = T * dS / r  # N = -Q_S / r with Q_S = -T d span/d phiS
        ax, ah = -push * N.sin(s) / mc.m, -mc.g + push * N.cos(s) / mc.m
        lid = -mc.mL * mc.g * mc.rL * N.cos(L) - mc.cL * Ld - T * dL
        if self.lid == "rest":
            return ax, ah, 0.0, push, -lid, T
        return ax, ah, lid / mc.I, push, None, T

    def balloon_flow(self, vB):
        # A stuck balloon is wherever the lid's limit is: its two entries are not integrated.
        return [vB, self.mc.balloon_acc(vB)] if self.balloon == "free" else [0.0, 0.0]

    def kin(self, y):
        """phiS, phiS', phiL, phiL', phiL'' and the sandbag's r of the state y."""
        mc = self.mc
        if self.rope == "taut":
            r, s, L, rd, sd = y[:5]
            rdd, sdd, k, _ = mc.m4_acc(r, s, L, rd, sd)
            kk, kp = mc.k(s, L)
            return s, sd, L, k * sd, k * sdd + kp * sd * sd, r
        x, h, vx, vh, L, Ld = y[:6]
        Ldd = 0.0 if self.lid == "rest" else mc.lid_free_acc(L, Ld)
        if self.spring:
            Ldd = self.spring_acc(y)[2]
        if self.bag == "air":
            return self.s_air, 0.0, L, Ld, Ldd, N.hypot(x, h)
        r = N.hypot(x, h)
        s = N.atan2(-h, -x)
        sd = (vx * N.sin(s) - vh * N.cos(s)) / r
        return s, sd, L, Ld, Ldd, r

    def guards(self, y):
        """name -> value; an event where a value reaches zero from above."""
        mc = self.mc
        if mc.radio:
            radio = {"radio_on": mc.string - N.hypot(mc.Hx + mc.rL - mc.switch[0], mc.Hy + y[-2] - mc.switch[1])}
            if self.small:
                radio["radio_on"] = mc.string - N.hypot(mc.Hx + y[-4] - mc.switch[0], mc.Hy + y[-3] - mc.switch[1])
            if self.latched:
                return radio | self.small_guards(y)
            return radio | self.machine_guards(y)
        return self.machine_guards(y)

    def small_guards(self, y):
        if not self.small:
            return {}
        _, _, L, Ld, Ldd, _ = self.kin(y)
        return self.small.guards(y[-4:], L, Ld, Ldd)

    def machine_guards(self, y):
        mc = self.mc
        s, sd, L, Ld, Ldd, r = self.kin(y)
        out = {"lid_open": mc.top - L}
        if mc.Th > 0 and self.lid == "free":  # the hinge's friction: its limit, or its slip stopping
            if mc.lid_stuck:
                out["hinge_stick"] = (mc.Th - abs(mc.mL * mc.g * mc.rL * N.cos(L))) / ((mc.m + mc.mL) * mc.g)
            else:
                out["hinge_slip"] = (1 if mc.Tf > 0 else -1) * Ld * 2 * mc.rL
        if self.lid == "free":
            out["lid_rests"] = L - mc.L0
        hl, hld = mc.h_lim(L, Ld)
        if self.small:
            out |= self.small.guards(y[-4:], L, Ld, Ldd)
        elif self.balloon == "free":
            out["balloon_caught"] = hl - y[-2]
        else:
            out["balloon_free"] = mc.balloon_acc(hld) - mc.h_lim_acc(L, Ld, Ldd)
        if self.bag == "air":
            x, h = y[0], y[1]
            out["sandbag_lands"] = -x * N.sin(self.s_air) + h * N.cos(self.s_air)
            out["rope_taut"] = -mc.C(self.s_air, L)
            return out
        out["seesaw_vertical"] = mc.top - abs(s)
        if self.rope == "slack" and mc.stretchy:
            force = (mc.m + mc.mL) * mc.g
            out["sandbag_at_pivot"] = -y[0]
            if not self.spring:
                out["spring_slack"] = -self.tension(y, slack=True)[0] / force
                return out
            _, _, _, push, box, T = self.spring_acc(y)
            out["spring_pull"] = T / force
            out["rope_locked"] = -mc.lock(s, L)
            out["arm_pull"] = push / force
            if box is not None:
                out["lid_lifts"] = box / force
        elif self.rope == "slack":
            out["rope_taut"] = -mc.C(s, L)
            out["sandbag_at_pivot"] = -y[0]
        else:
            _, _, k, torque = mc.m4_acc(*y[:5])
            out["rope_slack"] = torque
            out["k"] = k
            out["sandbag_at_pivot"] = y[0]
        return out

    def energy_of(self, y):
        mc = self.mc
        s, sd, L, Ld, Ldd, r = self.kin(y)
        if self.rope == "taut":
            v2 = y[3] ** 2 + (r * sd) ** 2
            h = -r * N.sin(s)
        else:
            v2 = y[2] ** 2 + y[3] ** 2
            h = y[1]
        return 0.5 * mc.m * v2 + mc.m * mc.g * h + 0.5 * mc.I * Ld * Ld + mc.mL * mc.g * mc.rL * N.sin(L)

    def to_free_fall(self, y):
        r, s, L, rd, sd = y[:5]
        for _ in range(3):  # the lid's angle back onto the closure, from the integration's drift
            L -= F["C"](s, L, *self.mc.params) / F["CL"](s, L, *self.mc.params)
        Ld = self.mc.k(s, L)[0] * sd
        x, h = -r * N.cos(s), -r * N.sin(s)
        vx = -rd * N.cos(s) + r * sd * N.sin(s)
        vh = -rd * N.sin(s) - r * sd * N.cos(s)
        return [x, h, vx, vh, L, Ld] + y[5:]

    def event(self, name, t):
        self.events.append((name, t))

    # --- what happens at an event
    def settle_balloon(self, y, t, released, v_before=None):
        """A stuck balloon that the lid leaves behind goes free: by its rate if an impact jumped the
        lid's (v_before: the balloon's speed before it), else by its acceleration."""
        if self.small:
            _, _, L, Ld, Ldd, _ = self.kin(y)
            return y[:-4] + self.small.decide(y[-4:], L, Ld, Ldd, t)
        if self.balloon != "stuck":
            return y
        s, sd, L, Ld, Ldd, r = self.kin(y)
        hl, hld = self.mc.h_lim(L, Ld)
        if v_before is None:
            v_before = hld
        if hld > v_before + 1e-12 * (1 + abs(v_before)) or (
                hld >= v_before and self.mc.h_lim_acc(L, Ld, Ldd) > self.mc.balloon_acc(hld)):
            self.balloon = "free"
            self.event("balloon_free", t)
            released.add("balloon_caught")
            return y[:-2] + [hl, v_before]
        return y[:-2] + [hl, hld]

    def jerk(self, y, t, released):
        """The rope jerked straight from free fall with the sandbag on the arm."""
        mc = self.mc
        x, h, vx, vh, L, Ld = y[:6]
        hB, vB = (y[6], y[7]) if not self.small else (None, None)
        r = N.hypot(x, h)
        s = N.atan2(-h, -x)
        rd = -vx * N.cos(s) - vh * N.sin(s)
        sd = (vx * N.sin(s) - vh * N.cos(s)) / r
        k, _ = mc.k(s, L)
        if k <= 0:
            raise NotCovered(f"the rope jerked with k = {k:.3g} <= 0 at t = {t}")
        e0 = self.energy_of(y)
        if self.balloon == "stuck":
            hB, vB = mc.h_lim(L, Ld)  # moving with the lid until the jerk
        # Project (r', phiS', phiL') onto phiL' = k phiS' in the metric diag(m, m r^2, I).
        minv = (1 / mc.m, 1 / (mc.m * r * r), 1 / mc.I)
        n = (0.0, -k, 1.0)
        lam = (n[1] * sd + n[2] * Ld) / (n[1] ** 2 * minv[1] + n[2] ** 2 * minv[2])
        sd1 = sd - minv[1] * n[1] * lam
        Ld1 = Ld - minv[2] * n[2] * lam
        if self.lid == "rest" and Ld1 <= 0:
            raise NotCovered(f"a jerk that leaves the lid on the box at t = {t}")
        # The other impact laws set the speeds after the jerk themselves (docs/model.md, section
        # 7); where one would drive the resting lid into the box the inelastic jerk stands.
        J, p = mc.m * r * r, mc.m * r * r * sd
        law = {"rope": sd1, "angular-momentum-sum": (p + mc.I * Ld) / (J + mc.I * k),
               "kinetic-energy": N.sqrt((J * sd * sd + mc.I * Ld * Ld) / (J + mc.I * k * k)) * (1 if sd1 >= 0 else -1)}
        rd1 = rd  # kept (eq. 5), but by the linear-momentum law
        if mc.law == "linear-momentum":
            sd_law, rd_law = linear_momentum_law(mc, r, s, L, k, x, h, vx, vh, Ld)
        else:
            sd_law, rd_law = law[mc.law], rd
        if not (self.lid == "rest" and k * sd_law <= 0):
            sd1, rd1 = sd_law, rd_law
        self.lid, self.rope = "free", "taut"
        if mc.Th > 0:  # the hinge slips the way the jerk turns the lid (no impulse of its own)
            if k * sd1 == 0:
                raise NotCovered(f"a jerk that leaves the lid at rest against its hinge's friction at t = {t}")
            if mc.lid_stuck:
                self.event("lid_slips", t)
            mc.lid_stuck, mc.Tf = False, mc.Th if k * sd1 > 0 else -mc.Th
            released.add("hinge_slip")
        y4 = [r, s, L, rd1, sd1] + (y[6:] if self.small else [hB, vB])
        self.event("rope_taut", t)
        self.energy.append((t, e0, self.energy_of(y4)))
        # hB, vB of a stuck balloon: decided on the velocities after the jerk
        _, _, _, torque = mc.m4_acc(*y4[:5])
        if torque < 0:
            self.rope = "slack"
            self.event("rope_slack", t)
            released.add("rope_taut")
            return self.settle_balloon(self.to_free_fall(y4), t, released, vB)
        released.add("rope_slack")
        return self.settle_balloon(y4, t, released, vB)

    def simulate(self):
        mc = self.mc
        # start: the sandbag on the arm if it is within 1e-9 m of it
        gap = -mc.x0 * N.sin(mc.s0) + mc.h0 * N.cos(mc.s0)
        self.bag = "arm" if abs(gap) <= 1e-9 else "air"
        self.s_air = mc.s0
        self.rope, self.lid, self.balloon = "slack", "rest", "stuck"
        if mc.C(mc.s0, mc.L0) > -2 * mc.lR * 1e-9:
            raise NotCovered("a rope straight (or too short) at the start")
        hl, _ = mc.h_lim(mc.L0, 0.0)
        y = [mc.x0, mc.h0, 0.0, 0.0, mc.L0, 0.0] + (self.small.start(mc.L0) if self.small else [hl, 0.0])
        self.released = set()
        if self.small:
            self.balloon = "small"
        return march(self, y)

    # what march() asks of a run
    def angles(self, y):
        s, _, L, _, _, _ = self.kin(y)
        return s, L

    def after_step(self, y):
        if self.small:
            _, _, L, Ld, _, _ = self.kin(y)
            return y[:-4] + self.small.project(y[-4:], L, Ld)
        return y

    def closing_within_rounding(self, name, y):
        if name.startswith("B_"):
            _, _, L, Ld, Ldd, _ = self.kin(y)
            return self.small.closing_within_rounding(name, y[-4:], L, Ld, Ldd)
        if name != "balloon_caught":
            return None
        _, _, L, Ld, Ldd, _ = self.kin(y)
        return balloon_closing(self.mc, L, Ld, Ldd, y[-2], y[-1])

    def hinge(self, name, y, t, released):
        """The hinge's Coulomb friction on a free lid (docs/extensions.md, "Friction"): a slip that
        stops sticks while the lid's weight needs at most T_h to hold it, else slips back; a
        stuck lid slips where its weight needs more."""
        mc = self.mc
        if self.rope == "taut":
            raise NotCovered(f"the lid's hinge sticking with the rope straight on the massless seesaw at t = {t}")
        x, h, vx, vh, L, Ld = y[:6]
        weight = mc.mL * mc.g * mc.rL * N.cos(L)
        if name == "hinge_slip" and abs(weight) <= mc.Th:
            mc.lid_stuck, mc.Tf = True, num(0.0)
            self.event("lid_sticks", t)
            released.add("hinge_stick")
            return self.settle_balloon(y[:5] + [num(0.0)] + y[6:], t, released)
        if name == "hinge_stick":
            self.event("lid_slips", t)
        mc.lid_stuck, mc.Tf = False, -mc.Th if weight > 0 else mc.Th  # slipping the way it falls
        released.add("hinge_slip")
        return self.settle_balloon(y, t, released)

    def handle_event(self, name, y, t):
        return self.handle(name, y, t, self.released)

    def noise(self, name):
        """How near zero a guard's value is rounding (and the integration's error), not a gap."""
        scale = {"rope_taut": self.mc.lR ** 2, "balloon_caught": self.mc.rB}
        return 10 * self.tol * (self.mc.rB if name.startswith("B_") else scale.get(name, 1.0))

    def handle(self, name, y, t, released):
        mc = self.mc
        if name in ("hinge_slip", "hinge_stick"):
            return self.hinge(name, y, t, released)
        if name.startswith("B_") or name == "balloon_escapes":
            _, _, L, Ld, Ldd, _ = self.kin(y)
            return y[:-4] + self.small.handle(name, y[-4:], L, Ld, Ldd, t)
        if name == "radio_on":  # the string straight: it pulls with the balloon's net lift
            self.event("radio_on" if mc.lift >= mc.switch_force else "switch_stays_off", t)
            return None
        if name == "lid_open":  # the radio's latch (docs/extensions.md, "The radio")
            self.event("lid_open", t)
            if self.rope == "taut":
                y = self.to_free_fall(y)
                self.rope = "slack"
                self.event("rope_slack", t)
            self.spring = False
            x, h, vx, vh, L, Ld = y[:6]
            if self.small:  # freed with its current velocity, the latched lid no limit to it
                if "lid" in self.small.active:
                    self.event("balloon_free", t)
                self.small.latch(y[-4:], L)
                self.latched, self.lid, self.bag, self.s_air = True, "rest", "air", N.atan2(-h, -x)
                mc.Tf, mc.lid_stuck = num(0.0), False
                return [x, h, vx, vh, L, 0.0] + y[6:]
            hB, vB = y[6:8]
            if self.balloon == "stuck":  # freed with its current velocity
                hB, vB = mc.h_lim(L, Ld)
                self.balloon = "free"
                self.event("balloon_free", t)
            # the rope let go for good, the sandbag off the seesaw (which stays where it is)
            self.latched, self.lid, self.bag, self.s_air = True, "rest", "air", N.atan2(-h, -x)
            mc.Tf, mc.lid_stuck = num(0.0), False
            return [x, h, vx, vh, L, 0.0, hB, vB]
        if name == "balloon_free":
            return self.settle_balloon(y, t, released)
        if name == "sandbag_lands":
            r = -(y[0] * N.cos(self.s_air) + y[1] * N.sin(self.s_air))
            if r <= 0:
                self.event("sandbag_at_pivot", t)
                return None
            if mc.C(self.s_air, y[4]) > -2 * mc.lR * 1e-9:
                raise NotCovered("a landing on a straight rope")
            self.bag = "arm"
            self.event(name, t)
            return y
        if name == "rope_taut":
            if self.bag == "air":
                raise NotCovered("a rope pulled straight by the lid with the sandbag in the air")
            return self.jerk(y, t, released)
        if name in ("rope_slack", "k"):
            self.rope = "slack"
            self.event("rope_slack", t)
            released.add("rope_taut")
            y = self.to_free_fall(y)
            return self.settle_balloon(y, t, released)
        if name == "arm_pull":
            raise NotCovered(f"a stretched rope that would need the arm to pull the sandbag at t = {t}")
        if name == "spring_slack" and mc.lock(*self.kin(y)[0:3:2]) >= 0:
            self.event("rope_locked", t)  # straight on the far side of the hinge
            return None
        if name == "spring_slack":
            self.spring = True
            self.event("rope_taut", t)
            released.add("spring_pull")
            box = self.spring_acc(y)[4]
            if box is not None and box < -1e-9 * (mc.m + mc.mL) * mc.g:  # a damped rope's pull at once
                name = "lid_lifts"
            else:
                if box is not None:
                    released.add("lid_lifts")
                return self.settle_balloon(y, t, released)
        if name == "lid_lifts":
            self.lid = "free"
            self.event("lid_lifts", t)
            released.add("lid_rests")
            return self.settle_balloon(y, t, released)
        if name == "spring_pull":
            self.spring = False
            self.event("rope_slack", t)
            released.add("spring_slack")
            return self.settle_balloon(y, t, released)
        if name == "lid_rests" and mc.stretchy and self.bag == "arm" and self.rope == "slack":
            # the lid's stop jumps s': a pulling rope that would push lets go, a slack one longer
            # than l_R that would pull (k s + c s' > 0) pulls, at that instant (docs/impact.md)
            v_balloon = mc.h_lim(y[4], y[5])[1] if self.balloon == "stuck" else None
            self.event("lid_rests", t)
            self.lid = "rest"
            mc.Tf, mc.lid_stuck = num(0.0), False  # the hinge's friction idle: the box holds the lid
            y = y[:4] + [mc.L0, 0.0] + y[6:]
            zero = 1e-9 * (mc.m + mc.mL) * mc.g
            pulls = self.tension(y, slack=not self.spring)[0] > (-zero if self.spring else zero)
            if pulls != self.spring:
                self.spring = pulls
                self.event("rope_taut" if pulls else "rope_slack", t)
            released.add("spring_pull" if pulls else "spring_slack")
            if pulls:
                released.add("lid_lifts")
            if v_balloon is not None:
                y = self.settle_balloon(y[:-1] + [v_balloon], t, released, v_balloon)
            return y
        if name == "lid_rests":
            v_balloon = None  # a stuck balloon moves down with the lid until the box stops it
            if self.balloon == "stuck":
                _, _, L, Ld, _, _ = self.kin(y)
                v_balloon = mc.h_lim(L, Ld)[1]
            self.event("lid_rests", t)
            if self.rope == "taut":
                y = self.to_free_fall(y)
                x, hh, vx, vh = y[:4]
                s = N.atan2(-hh, -x)
                Cs = F["Cs"](s, y[4], *mc.params)
                sd = (vx * N.sin(s) - vh * N.cos(s)) / N.hypot(x, hh)
                if Cs * sd > 0:
                    raise NotCovered("a lid landing while the seesaw stretches the rope")
                self.rope = "slack"
                self.event("rope_slack", t)
                released.add("rope_taut")
            self.lid = "rest"
            mc.Tf, mc.lid_stuck = num(0.0), False  # the hinge's friction idle: the box holds the lid
            y = y[:4] + [mc.L0, 0.0] + y[6:]
            if v_balloon is not None:  # it goes on down, free, if it was moving
                y = self.settle_balloon(y[:-1] + [v_balloon], t, released, v_balloon)
            return y
        raise AssertionError(name)


def linear_momentum_law(mc, r, s, L, k, x, h, vx, vh, Ld):
    """The `linear-momentum` law (docs/model.md, section 7): the linear momentum of the sandbag
    and of the lid's centre of mass (r_L along the lid, moving r_L phiL' across it) kept through
    the jerk, the sandbag on the arm and phiL' = k phiS' after it: phiS' and r' after it, from
    the 2x2 system. The sandbag at -r (cos phiS, sin phiS): its velocity
    -r' (cos, sin) + r phiS' (sin, -cos)."""
    cs, sn, cL, sL = N.cos(s), N.sin(s), N.cos(L), N.sin(L)
    m, lid = mc.m, mc.mL * mc.rL
    Px, Py = m * vx - lid * Ld * sL, m * vh + lid * Ld * cL
    # unknowns (r', phiS'): columns of the momentum after the jerk
    a11, a12 = -m * cs, m * r * sn - lid * k * sL
    a21, a22 = -m * sn, -m * r * cs + lid * k * cL
    det = a11 * a22 - a12 * a21
    if det == 0:
        raise NotCovered("the linear-momentum law without a solution")
    return (a11 * Py - a21 * Px) / det, (Px * a22 - a12 * Py) / det


def quadratic_closing(g, r, a):
    """When g + r tau + a tau^2 / 2, a gap that has not opened beyond rounding, is zero again:
    over a microsecond the expansion's next term is far below rounding. None if it does not close."""
    if a >= 0:
        return None
    return (r + N.sqrt(r * r - 2 * a * max(g, 0.0))) / -a


def balloon_closing(mc, L, Ld, Ldd, hB, vB):
    """The freed balloon's gap below the lid's limit closing again within rounding."""
    hl, hld = mc.h_lim(L, Ld)
    return quadratic_closing(hl - hB, hld - vB, mc.h_lim_acc(L, Ld, Ldd) - mc.balloon_acc(vB))


def march(run, y, t=0.0):
    """Integrate the run from (t, y) event to event until it stops; its events.

    Every guard of run.guards is looked at at the step ends; the earliest sign change is located
    by bisection, each trial time integrated again from the step's start in one extrapolation
    step, and run.handle_event applies it. A guard in run.released (a contact just released, a
    force that starts at zero) is open by construction until it leaves run.noise."""
    mc = run.mc
    h = 1e-6
    pending = set()  # released guards still within rounding of zero: open by construction
    while True:
        if t >= mc.t_max:
            run.event("timeout", t)
            return run.events
        pending |= run.released
        run.released = set()
        g0 = run.guards(y)
        pending &= set(g0)
        # one accepted step
        while True:
            h = min(h, mc.t_max - t)
            y1, err = gbs(run.flow, y, h)
            e = max(a / (run.tol * (1 + abs(b))) for a, b in zip(err, y1))
            if e > 1:
                h *= max(0.2, 0.8 * e ** (-1 / 15))
                continue
            # bound the angles turned in one step, so that a guard cannot dip and come back
            # between two looks
            turn = max(abs(p - q) for p, q in zip(run.angles(y1), run.angles(y)))
            if turn > 0.02:
                h *= 0.5 * 0.02 / turn
                continue
            break
        y1 = run.after_step(y1)
        g1 = run.guards(y1)
        noise = {n: run.noise(n) for n in g1}
        crossed = [n for n in g1 if n in g0 and (
            (n in pending and g1[n] < -noise[n]) or (n not in pending and g0[n] > 0 and g1[n] <= 0))]
        if not crossed:
            t += h
            y = y1
            pending = {n for n in pending if abs(g1[n]) <= noise[n]}
            h = min(4 * h, h * max(1.0, 0.8 * max(e, 1e-30) ** (-1 / 15)), 0.05)
            continue
        # locate the earliest crossing by bisection on re-integrations from t
        best = None
        for name in crossed:
            lo = 0.0
            if name in pending:  # from the last time where the gap is clearly open
                lo = None
                for j in range(1, 60):
                    ym, _ = gbs(run.flow, y, h * 0.5 ** j)
                    if run.guards(ym)[name] > noise[name]:
                        lo = h * 0.5 ** j
                        break
                if lo is None:
                    dt = run.closing_within_rounding(name, y)
                    if dt is None or dt > h:
                        raise NotCovered(f"{name}: a released contact closing again within rounding at t = {t}")
                    if best is None or dt < best[0]:
                        best = (dt, name)
                    continue
            hi = h
            while hi - lo > 0.01 * run.tol * max(1.0, t):
                mid = 0.5 * (lo + hi)
                ym, _ = gbs(run.flow, y, mid)
                if run.guards(ym)[name] > 0:
                    lo = mid
                else:
                    hi = mid
            if best is None or hi < best[0]:
                best = (hi, name)
        dt, name = best
        y, _ = gbs(run.flow, y, dt)
        t += dt
        pending = set()
        h = 1e-6
        if name in run.stops:
            run.event(name, t)
            return run.events
        if name == "balloon_caught":  # it sticks under the lid, moving with its limit
            run.balloon = "stuck"
            run.event(name, t)
            continue
        y = run.handle_event(name, y, t)
        if y is None:
            return run.events


def simulate(keys, tol=1e-13, digits=None):
    """The events of the machine `keys` (from load_machine) as (name, time) pairs, in order:
    with floats, each step's error within tol (relative to 1 + |y|); with digits, in mpmath's
    numbers at that many digits (tol then 10^(10 - digits) unless given smaller)."""
    precise(digits)
    try:
        if digits:
            tol = min(tol, 10.0 ** (10 - digits))
        return [(name, float(t)) for name, t in make_run(keys, tol).simulate()]
    finally:
        precise(None)


def make_run(keys, tol=1e-13):
    """The run of the machine: the massless seesaw's (Run), or with a seesaw that has mass the
    full-coordinates one (full_coordinates.py)."""
    if float(keys.get("seesaw.mass", 0.0)) > 0:
        if keys["run.impact_law"] != "rope" and float(keys.get("restitution.rope", 0.0)) > 0:
            raise NotCovered("restitution.rope with another impact law")
        if N is not math:
            raise NotCovered("more digits for a seesaw with mass")
        import full_coordinates
        return full_coordinates.HeavyRun(Machine(keys), keys, tol)
    for name in HEAVY:
        if name in keys and name not in ("seesaw.mass", "damping.lid_hinge", "rope.stiffness", "rope.damping",
                                          "friction.lid_hinge"):
            raise NotCovered(f"{name} on the massless seesaw")
    mc = Machine(keys)
    if mc.Th > 0 and mc.stretchy:
        raise NotCovered("the hinge's friction with the rope that stretches on the massless seesaw")
    return Run(mc, tol)


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    over = {}
    for item in sys.argv[2:]:
        key, value = item.split("=", 1)
        over[key] = tomllib.loads(f"v = {value}")["v"]
    run = make_run(load_machine(sys.argv[1], over))
    for name, t in run.simulate():
        print(f"{t:.12f}  {name}")
    for t, e0, e1 in run.energy:
        print(f"  energy at {t:.9f}: {e0:.6f} J -> {e1:.6f} J")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The reference's machine with a seesaw that has mass, in the machine's full coordinates.

A seesaw with a moment of inertia (docs/extensions.md, "A seesaw with mass") has its angle as a
degree of freedom in every phase, so the whole machine is q = (x, h, phiS, phiL) with the
constant mass matrix M = diag(m, m, I_S, I_L), and every phase is the same Lagrange equation of
the first kind

    M q'' = f(q, q') + sum_{i in A} W_i^T lambda_i,    W_i q'' + q'^T (d2 g_i) q' = 0  (i in A),

for the set A of contacts that hold (the sandbag on the arm, the rope straight, the lid on the
box; on the built machine the seesaw's ends and the sandbag on the floor, the sandbag at the arm's
end stop), each with its gap g_i (>= 0 open) and its force lambda_i (>= 0: the arm, the box, the
floor and the stop push, the rope pulls). A rope that stretches is no contact but a force in f. SymPy derives M and f from the kinetic energy, the potential and the dampers'
dissipation function, and W_i and the velocity terms from the gaps. Nothing here is a reduced
equation of one phase, as whatnext integrates: the multipliers are solved for at every evaluation
(a 3x3 problem at most), and after each step the state is projected back onto the holding
contacts (their gaps and rates to zero in the metric M), against the drift.

Which contacts hold is decided at each event as docs/model.md, section 5 defines it: the impact
as the velocities' projection in the metric M with one-signed impulses (every subset tried), with
Newton's restitution as its target rates (docs/extensions.md), then the problem on accelerations
(every subset tried), the same zeros of the machine's scale as the model names (rates 1e-6 of its
speed scale count as held, the end of a cascade). Friction's tangential contacts (the sandbag's
slide along the arm, the seesaw's turn at the pivot) join the same problems, sticking as a row,
slipping as a force bounded by mu N or T_p; the other impact laws set the jerk's speeds after the
inelastic impact has decided it; the radio's latch holds the lid and lets the rope go.
"""
import itertools
import math

import sympy as sp

from whatnext_reference import STOPS, NotCovered, balloon_closing, linear_momentum_law, march, quadratic_closing
import small_balloon

CONTACTS = ("arm", "rope", "lid", "floor_left", "floor_right", "bag_floor", "stop")
CLOSED = {"arm": "sandbag_lands", "rope": "rope_taut", "lid": "lid_rests", "floor_left": "seesaw_on_floor",
          "floor_right": "seesaw_on_floor", "bag_floor": "sandbag_on_floor", "stop": "sandbag_at_stop"}
OPENED = {"arm": "sandbag_leaves", "rope": "rope_slack", "lid": "lid_lifts", "floor_left": "seesaw_lifts",
          "floor_right": "seesaw_lifts", "bag_floor": "sandbag_bounces", "stop": "sandbag_leaves_stop"}
# The input keys of each contact's restitution (docs/extensions.md, "The machine students build")
RESTITUTION = {"arm": "restitution.sandbag", "rope": "restitution.rope", "lid": "restitution.lid",
               "floor_left": "floor.restitution", "floor_right": "floor.restitution",
               "bag_floor": "floor.restitution", "stop": "restitution.stop"}


def _derive():
    x, h, s, L = q = sp.symbols("x h phiS phiL", real=True)
    u = sp.symbols("xd hd sd Ld", real=True)
    rH, Hx, Hy, a, lR, m, mL, rL, g, IL, mb, c, IS, cp, cL, L0, hf, La = params = sp.symbols(
        "rH Hx Hy a lR m mL rL g IL mb c IS cp cL L0 hf La", real=True)
    T = m / 2 * (u[0] ** 2 + u[1] ** 2) + IS / 2 * u[2] ** 2 + IL / 2 * u[3] ** 2
    V = m * g * h + mb * g * c * sp.sin(s) + mL * g * rL * sp.sin(L)
    D = cp / 2 * u[2] ** 2 + cL / 2 * u[3] ** 2  # Rayleigh's dissipation function: the dampers
    # Lagrange: d/dt dT/du - dT/dq + dV/dq + dD/du = contact forces, with d/dt dT/du = M q'' + (d2T/du dq) u
    M = sp.hessian(T, u)
    assert all(M[i, j] == 0 for i in range(4) for j in range(4) if i != j)
    f = [sp.diff(T, q[i]) - sum(sp.diff(T, u[i], q[j]) * u[j] for j in range(4))
         - sp.diff(V, q[i]) - sp.diff(D, u[i]) for i in range(4)]
    R = sp.Matrix([rH * sp.cos(s), rH * sp.sin(s)])
    E = sp.Matrix([Hx + a * sp.cos(L), Hy + a * sp.sin(L)])
    gaps = {
        "arm": -x * sp.sin(s) + h * sp.cos(s),
        "rope": lR - sp.sqrt((R - E).dot(R - E)),
        "lid": L - L0,
        # the built machine: the floor under the seesaw's ends and the sandbag, the arm's end stop
        "floor_left": -La * sp.sin(s) - hf,
        "floor_right": rH * sp.sin(s) - hf,
        "bag_floor": h - hf,
        "stop": La + (x * sp.cos(s) + h * sp.sin(s)),
        # the tangential contacts of friction (docs/extensions.md, "Friction"): the sandbag's
        # distance along the arm, and the seesaw's angle at the pivot
        "slide": -(x * sp.cos(s) + h * sp.sin(s)),
        "turn": s,
    }
    args = tuple(q) + tuple(u) + params
    out = {"M": sp.lambdify(params, [M[i, i] for i in range(4)], "math"),
           "f": sp.lambdify(args, f, "math", cse=True),
           "along": sp.lambdify(args, -(x * sp.cos(s) + h * sp.sin(s)), "math"),
           # (R - H) x (E - H): negative with the lid below the rope, the linkage's physical shape
           # (docs/model.md, section 3); zero where the rope would touch the hinge
           "lock": sp.lambdify(args, (R[0] - Hx) * (E[1] - Hy) - (R[1] - Hy) * (E[0] - Hx), "math"),
           "energy": sp.lambdify(args, T + V, "math")}
    span = sp.sqrt((R - E).dot(R - E))
    out["span"] = sp.lambdify(args, [span, [sp.diff(span, v) for v in q]], "math", cse=True)
    rows = {}
    for name, gap in gaps.items():
        W = [sp.diff(gap, v) for v in q]
        w = sum(sp.diff(gap, q[i], q[j]) * u[i] * u[j] for i in range(4) for j in range(4))
        rows[name] = [W, w]
        out[name] = sp.lambdify(args, [gap, W, w], "math", cse=True)
    return out


F = _derive()


def solve(A, b):
    """A x = b for a small dense system (Gaussian elimination with partial pivoting)."""
    n = len(b)
    scale = max((abs(v) for row in A for v in row), default=0.0)
    A = [row[:] + [b[i]] for i, row in enumerate(A)]
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(A[i][k]))
        if abs(A[p][k]) <= 1e-12 * scale:  # dependent rows within rounding: no unique forces
            raise ZeroDivisionError("singular contact problem")
        A[k], A[p] = A[p], A[k]
        for i in range(k + 1, n):
            r = A[i][k] / A[k][k]
            for j in range(k, n + 1):
                A[i][j] -= r * A[k][j]
    xs = [0.0] * n
    for k in reversed(range(n)):
        xs[k] = (A[k][n] - sum(A[k][j] * xs[j] for j in range(k + 1, n))) / A[k][k]
    return xs


class HeavyMachine:
    """The machine's numbers, as whatnext_reference.Machine plus the seesaw's."""

    def __init__(self, mc, keys):
        self.mc = mc
        mb = float(keys["seesaw.mass"])
        if "seesaw.left_arm" not in keys:
            raise NotCovered("a seesaw with mass needs seesaw.left_arm")
        self.arm = float(keys["seesaw.left_arm"])
        rH = mc.rH
        c = float(keys.get("seesaw.com_offset", (rH - self.arm) / 2))
        IS = keys.get("seesaw.inertia")
        IS = float(IS) if IS is not None else mb * (self.arm ** 3 + rH ** 3) / (3 * (self.arm + rH))
        if IS <= 0:
            raise NotCovered("a seesaw without inertia")
        self.IS, self.mb, self.c = IS, mb, c
        self.cp = float(keys.get("damping.pivot", 0.0))
        self.cL = float(keys.get("damping.lid_hinge", 0.0))
        self.floor = keys.get("floor.enabled", False) in (True, "true")
        self.end_stop = keys.get("seesaw.end_stop", False) in (True, "true")
        self.contacts = tuple(n for n in CONTACTS if (n not in ("floor_left", "floor_right", "bag_floor") or self.floor)
                              and (n != "stop" or self.end_stop))
        self.e = {n: float(keys.get(RESTITUTION[n], 0.0)) for n in CONTACTS}
        hf = mc.Hy - 2 * mc.rL  # the floor through the box's bottom
        self.params = (rH, mc.Hx, mc.Hy, mc.a, mc.lR, mc.m, mc.mL, mc.rL, mc.g, mc.I, mb, c, IS,
                       self.cp, self.cL, mc.L0, hf, self.arm)
        self.Minv = [1 / v for v in F["M"](*self.params)]
        # the machine's scales (docs/model.md, section 5): length, speed, mass, acceleration
        self.ell = rH + 2 * mc.rL + mc.lR
        self.mass = mc.m + mc.mL + mb
        # a rope that stretches (docs/impact.md): a one-sided spring-damper, a force, no contact
        self.stretchy = "rope.stiffness" in keys
        self.k_rope = float(keys.get("rope.stiffness", 0.0))
        self.c_rope = float(keys.get("rope.damping", 0.0))
        # the lid's gap is an angle: its rates and accelerations are taken at its far edge
        self.gap_scale = {n: 1.0 for n in CONTACTS} | {"lid": 2 * mc.rL}
        # Coulomb friction: the sandbag on the arm (mu), the pivot's torque bound (N m)
        self.mu = float(keys.get("friction.sandbag", 0.0))
        self.Tp = float(keys.get("friction.pivot", 0.0))
        self.Th = float(keys.get("friction.lid_hinge", 0.0))
        if self.mu > 0 and (self.e["arm"] > 0 or self.e["stop"] > 0 or self.e["bag_floor"] > 0):
            raise NotCovered("friction with restitution on the sandbag's contacts")
        if (self.mu > 0 or self.Tp > 0 or self.Th > 0) and (mc.law != "rope" or self.stretchy):
            raise NotCovered("friction with another impact law or the rope that stretches")


class HeavyRun:
    """A run of the machine with a heavy seesaw. y = [x, h, phiS, phiL, x', h', phiS', phiL', hB, vB]."""

    def __init__(self, mc, keys, tol=1e-13):
        self.mc, self.hm, self.tol = mc, HeavyMachine(mc, keys), tol
        self.events, self.energy = [], []
        self.active = set()
        self.balloon = "stuck"
        # a balloon smaller than the box: a disc among the lid and the walls (small_balloon.py)
        self.small = small_balloon.SmallBalloon(mc, self) if mc.small else None
        if self.small:
            self.balloon = "small"
        self.fell_off = False
        self.spring = False  # the rope that stretches pulling
        # the friction contacts' states: "stick", a slip's sign (+1, -1), "idle" (the angle held
        # by other contacts, the load theirs), or None (absent)
        self.fric = {"arm": None, "pivot": None, "hinge": None}
        self.latched = False  # the radio's latch holds the lid open, the rope let go for good
        self.stops = STOPS - {"radio_on"} - ({"lid_open"} if mc.radio else set())

    # --- the flow
    def contact(self, name, y):
        return F[name](*y[:8], *self.hm.params)

    def accel(self, y, active=None, fric=None):
        """q'' and the forces lambda of the contacts in `active` (default: those that hold), with
        friction in the states `fric` (default: the run's): a sticking contact is one more row
        (its force "arm_t", "pivot_t"), a slipping sandbag pushes along W_n - s mu W_t, a slipping
        pivot adds -s T_p to the seesaw's equation (docs/extensions.md, "Friction")."""
        active = self.active if active is None else active
        fric = self.fric if fric is None else fric
        hm = self.hm
        names = [n for n in CONTACTS if n in active]
        f = F["f"](*y[:8], *hm.params)
        rows = [self.contact(n, y)[1:] for n in names]
        cols = [r[0] for r in rows]
        if "arm" in names and fric["arm"] in (1, -1):
            Wt = F["slide"](*y[:8], *hm.params)[1]
            i = names.index("arm")
            cols[i] = [cols[i][k] - fric["arm"] * hm.mu * Wt[k] for k in range(4)]
        if "arm" in names and fric["arm"] == "stick":
            _, Wt, wt = F["slide"](*y[:8], *hm.params)
            names.append("arm_t")
            rows.append((Wt, wt))
            cols.append(Wt)
        if fric["pivot"] == "stick":
            names.append("pivot_t")
            rows.append(([0.0, 0.0, 1.0, 0.0], 0.0))
            cols.append([0.0, 0.0, 1.0, 0.0])
        if fric["hinge"] == "stick":
            names.append("hinge_t")
            rows.append(([0.0, 0.0, 0.0, 1.0], 0.0))
            cols.append([0.0, 0.0, 0.0, 1.0])
        f = list(f)
        if fric["pivot"] in (1, -1):
            f[2] -= fric["pivot"] * hm.Tp
        if fric["hinge"] in (1, -1):
            f[3] -= fric["hinge"] * hm.Th
        if self.spring:  # the stretched rope's pull, Q = -T d span / dq
            T, grad = self.tension(y)
            f = [f[k] - T * grad[k] for k in range(4)]
        Mi = hm.Minv
        if not names:
            return [Mi[k] * f[k] for k in range(4)], {}
        Ws = [r[0] for r in rows]
        ws = [r[1] for r in rows]
        A = [[sum(Wi[k] * Mi[k] * Cj[k] for k in range(4)) for Cj in cols] for Wi in Ws]
        b = [-ws[i] - sum(Ws[i][k] * Mi[k] * f[k] for k in range(4)) for i in range(len(names))]
        lam = solve(A, b)
        acc = [Mi[k] * (f[k] + sum(lam[i] * cols[i][k] for i in range(len(names)))) for k in range(4)]
        return acc, dict(zip(names, lam))

    def tension(self, y):
        """k s + c s' of the rope that stretches, and the span's gradient."""
        hm = self.hm
        span, grad = F["span"](*y[:8], *hm.params)
        return hm.k_rope * (span - self.mc.lR) + hm.c_rope * sum(grad[k] * y[4 + k] for k in range(4)), grad

    def spring_guard(self, y):
        """While it pulls: its tension; slack: minus the tension it would have (its spring's part
        alone while shorter than l_R, so the guard does not fire as it shortens through l_R)."""
        hm = self.hm
        span, grad = F["span"](*y[:8], *hm.params)
        s = span - self.mc.lR
        T = hm.k_rope * s + (hm.c_rope * sum(grad[k] * y[4 + k] for k in range(4)) if s >= 0 else 0.0)
        return (T if self.spring else -T) / (hm.mass * self.mc.g * (1 + hm.ell))

    def flow(self, y):
        acc, _ = self.accel(y)
        if self.small:
            return list(y[4:8]) + acc + self.small.flow(y[8:], y[3], y[7], acc[3])
        vB = y[9]
        return list(y[4:8]) + acc + ([vB, self.mc.balloon_acc(vB)] if self.balloon == "free" else [0.0, 0.0])

    def project(self, y, names):
        """The state moved onto the contacts `names` (gaps and rates zero), in the metric M."""
        names = [n for n in CONTACTS if n in names]
        if not names:
            return y
        Mi = self.hm.Minv
        y = list(y)
        for it in range(4):
            rows = [self.contact(n, y) for n in names]
            Ws = [r[1] for r in rows]
            A = [[sum(Wi[k] * Mi[k] * Wj[k] for k in range(4)) for Wj in Ws] for Wi in Ws]
            if it < 3:
                mu = solve(A, [-r[0] for r in rows])
                for k in range(4):
                    y[k] += Mi[k] * sum(mu[i] * Ws[i][k] for i in range(len(names)))
            else:
                rates = [sum(W[k] * y[4 + k] for k in range(4)) for W in Ws]
                mu = solve(A, [-r for r in rates])
                for k in range(4):
                    y[4 + k] += Mi[k] * sum(mu[i] * Ws[i][k] for i in range(len(names)))
        if "lid" in names:
            y[3], y[7] = self.mc.L0, 0.0
        return y

    # --- the balloon (one-way coupled, as in whatnext_reference.Run)
    def settle_balloon(self, y, acc, t, v_before=None):
        if self.small:
            return y[:8] + self.small.decide(y[8:], y[3], y[7], acc[3], t)
        if self.balloon != "stuck":
            return y
        mc = self.mc
        L, Ld, Ldd = y[3], y[7], acc[3]
        hl, hld = mc.h_lim(L, Ld)
        if v_before is None:
            v_before = hld
        if hld > v_before + 1e-12 * (1 + abs(v_before)) or (
                hld >= v_before and mc.h_lim_acc(L, Ld, Ldd) > mc.balloon_acc(hld)):
            self.balloon = "free"
            self.event("balloon_free", t)
            self.released.add("balloon_caught")
            return y[:8] + [hl, v_before]
        return y[:8] + [hl, hld]

    # --- guards: a value reaching zero from above is an event
    def contacts(self):
        """The contacts that exist: after the radio's latch neither the rope nor the lid's box."""
        if self.latched and not (self.hm.floor or self.hm.end_stop):
            return ()  # the paper's machine: the sandbag has fallen out of the story
        return tuple(n for n in self.hm.contacts if not (self.latched and n in ("rope", "lid")))

    def guards(self, y):
        mc, hm = self.mc, self.hm
        acc, lam = self.accel(y)
        out = {"seesaw_vertical": mc.top - abs(y[2])}
        if mc.radio:  # the string straight (docs/extensions.md, "The radio")
            bx, by = (y[8], y[9]) if self.small else (mc.rL, y[8])  # its centre from the hinge
            out["radio_on"] = mc.string - math.hypot(mc.Hx + bx - mc.switch[0], mc.Hy + by - mc.switch[1])
        if not self.latched:
            out["lid_open"] = mc.top - y[3]
        force = hm.mass * (mc.g + 0.0) * (1 + hm.ell)
        if hm.stretchy and not self.latched:
            out["spring_pull" if self.spring else "spring_slack"] = self.spring_guard(y)
        for n in self.contacts():
            if n == "rope" and hm.stretchy:
                continue
            if n in self.active:
                out[n + "_force"] = lam[n] / force
            elif not self.exists(n):
                continue
            else:
                out[n + "_gap"] = self.contact(n, y)[0] * hm.gap_scale[n]
        fa, fp = self.fric["arm"], self.fric["pivot"]
        if "arm" in self.active and fa == "stick":
            out["fric_arm_stick"] = (hm.mu * lam["arm"] - abs(lam["arm_t"])) / force
        if "arm" in self.active and fa in (1, -1):
            out["fric_arm_slip"] = fa * self.slide_rate(y)
        if fp == "stick":
            out["fric_pivot_stick"] = (self.pivot_bound(y, self.active, self.fric) - abs(lam["pivot_t"])) / force
        if fp in (1, -1):
            out["fric_pivot_slip"] = fp * y[6] * hm.ell
        fh = self.fric["hinge"]
        if fh == "stick":
            out["fric_hinge_stick"] = (hm.Th - abs(lam["hinge_t"])) / force
        if fh in (1, -1):
            out["fric_hinge_slip"] = fh * y[7] * 2 * mc.rL
        if "arm" in self.active:
            along = F["along"](*y[:8], *hm.params)
            out["sandbag_at_pivot"] = along
            if not hm.end_stop:
                out["sandbag_falls_off"] = hm.arm - along
        if "rope" in self.active or self.spring:
            out["rope_locked"] = -F["lock"](*y[:8], *hm.params)
        L, Ld = y[3], y[7]
        hl, hld = mc.h_lim(L, Ld)
        if self.small:
            out |= self.small.guards(y[8:], L, Ld, acc[3])
        elif self.latched:
            pass  # the balloon rises without a limit
        elif self.balloon == "free":
            out["balloon_caught"] = hl - y[8]
        else:
            out["balloon_free"] = mc.balloon_acc(hld) - mc.h_lim_acc(L, Ld, acc[3])
        return out

    def noise(self, name):
        return 10 * self.tol * (self.hm.ell if name in ("balloon_caught",) or name.startswith("B_") else 1.0)

    def event(self, name, t):
        self.events.append((name, t))

    # --- the decision at an event (docs/model.md, section 5)
    def tolerances(self, y):
        hm, mc = self.hm, self.mc
        v = max(math.sqrt(mc.g * hm.ell), abs(y[4]), abs(y[5]), hm.ell * abs(y[6]), hm.ell * abs(y[7]))
        acc = mc.g + v * v / hm.ell
        return {"force": 1e-9 * hm.mass * acc * (1 + hm.ell), "impulse": 1e-9 * hm.mass * v * (1 + hm.ell),
                "rate": 1e-6 * v, "closing": 1e-12 * v, "accel": 1e-9 * acc}

    def exists(self, n, arm=None):
        """Whether contact n can close now: the arm's while the sandbag has not fallen off, the
        sandbag's floor while it is off the arm, the stop only with the sandbag on the arm."""
        arm = "arm" in self.active if arm is None else arm
        if n == "arm":
            return not self.fell_off
        if n == "bag_floor":
            return not arm
        if n == "stop":
            return arm
        return True

    def touching(self, y):
        hm = self.hm
        out = set()
        for n in self.contacts():
            if n in self.active:
                out.add(n)
                continue
            if n == "rope" and hm.stretchy:
                continue
            if n == "stop":
                continue  # closed with the arm only: added below
            if n == "bag_floor" and "arm" in self.active:
                continue
            if n == "arm":
                along = F["along"](*y[:8], *hm.params)
                if self.fell_off or not 0 <= along <= hm.arm:
                    continue
            # a gap within 1e-9 of its own units (m, the lid's rad) touches, at an event as at the
            # start (docs/model.md, section 6)
            if abs(self.contact(n, y)[0]) <= 1e-9:
                out.add(n)
        if hm.end_stop and "arm" in out and abs(self.contact("stop", y)[0]) <= 1e-9:
            out.add("stop")
        return out

    def rate(self, n, y):
        _, W, _ = self.contact(n, y)
        return sum(W[k] * y[4 + k] for k in range(4)) * self.hm.gap_scale[n]

    def decide(self, y, t, trigger, fric_trigger=None):
        """The contacts that hold after the event triggered by contact `trigger` (or None), or by
        the friction contact `fric_trigger` reaching its limit (which then slips where it may)."""
        hm = self.hm
        before = set(self.active)
        touch = self.touching(y) | ({trigger} if trigger else set())
        y = self.project(y[:4] + [0.0] * 4 + y[8:], touch)[:4] + y[4:]  # the positions exactly touching
        tol = self.tolerances(y)
        L0, Ld0 = y[3], y[7]
        v_balloon = self.mc.h_lim(L0, Ld0)[1] if self.balloon == "stuck" else None
        rates = {n: self.rate(n, y) for n in touch}
        impact = any(r < -tol["closing"] for r in rates.values())
        e0 = F["energy"](*y[:8], *hm.params)
        if impact:
            # Newton's restitution on each contact's own rate, g'+ = -e g'-, the inelastic impact
            # where that would gain energy (docs/extensions.md, "Restitution")
            bounce = {n: -hm.e[n] * rates[n] if rates[n] < -tol["closing"] else 0.0 for n in touch}
            for targets in (bounce, dict.fromkeys(touch, 0.0)):
                valid = []
                for S in subsets(touch):
                    for mode in (("stick", 1, -1) if "arm" in S and hm.mu > 0 else (None,)):
                        y1, imp = self.impulse(y, S, targets, mode)
                        if imp is None or any(p < -tol["impulse"] for n, p in imp.items() if n != "arm_t"):
                            continue
                        if mode == "stick" and abs(imp["arm_t"]) > hm.mu * imp["arm"] + tol["impulse"]:
                            continue
                        if mode in (1, -1) and mode * self.slide_rate(y1) < -tol["closing"]:
                            continue
                        if any(self.rate(n, y1) < -tol["closing"] for n in touch - S):
                            continue
                        valid.append((S, (y1, mode)))
                S, (y1, arm_mode) = self.prefer(valid, before, trigger, closing=True)
                if self.kinetic(y1) <= self.kinetic(y) * (1 + 1e-12):
                    break
            # the rope's jerk under another impact law: its speeds (docs/model.md, section 7)
            y2 = y1
            # (a jerk: the rope closing, or a landing that the straight rope takes up)
            if self.mc.law != "rope" and "rope" in S and (
                    rates["rope"] < -tol["closing"] or "arm" in S and rates["arm"] < -tol["closing"]):
                y2 = self.law_jerk(y, y1, S, touch, tol)
            if y2 is not y1:
                # what it leaves separating slower than the machine's zero of speed is held
                held = {n for n in touch if self.rate(n, y2) < tol["rate"]}
                mid = S | held
                y = y2 if held <= S else self.impulse(y2, mid, dict.fromkeys(mid, 0.0), arm_mode)[0]
            else:
                # a rebound slower than the machine's zero of speed is held: the end of a cascade
                held = {n for n in S if targets[n] < tol["rate"]}
                held |= {n for n in touch - S if self.rate(n, y1) < tol["rate"]}
                mid = S | held
                if held != {n for n in S if targets[n] == 0.0}:
                    y1, _ = self.impulse(y, mid, {n: 0.0 if n in held else targets[n] for n in mid}, arm_mode)
                y = y1
            self.energy.append((t, e0, F["energy"](*y[:8], *hm.params)))
        else:
            held = mid = {n for n in touch if rates[n] <= tol["rate"]}
            y = self.project(y, held)
        # a jump that would make the stretched rope push lets it go at once, and one that makes a
        # slack rope longer than l_R pull (k s + c s' > 0) has it pull at once (docs/impact.md)
        let_go = self.spring and self.tension(y)[0] < -tol["force"]
        engage = (self.hm.stretchy and not self.spring and impact
                  and self.spring_guard(y) * hm.mass * self.mc.g * (1 + hm.ell) < -tol["force"])
        if let_go or engage:
            self.spring = bool(engage)
        # friction: a slip at rest starts from exactly zero speed (docs/extensions.md, "Friction");
        # at rest or not is judged with the contacts of each candidate set
        sign = lambda v: 1 if v > 0 else -1
        # at rest: sticking where it may, or slipping where its limit was the event
        rest_opts = {c: (1, -1, "stick", "idle") if fric_trigger == c else ("stick", "idle", 1, -1)
                     for c in ("arm", "pivot", "hinge")}
        before_fric = dict(self.fric)
        y_event = y
        valid = []
        for A in subsets(held):
            if "stop" in A and "arm" not in A:
                continue
            y = y_event
            arm_rest = piv_rest = lid_rest = None
            if hm.mu > 0 and "arm" in A:
                arm_rest = self.at_rest(y, A, "slide", tol)
                y = arm_rest or y
            if hm.Tp > 0:
                piv_rest = self.at_rest(y, A, "turn", tol)
                y = piv_rest or y
            if hm.Th > 0 and not self.latched:
                lid_rest = self.at_rest(y, A, "turnL", tol)
                y = lid_rest or y
            piv_opts = ((rest_opts["pivot"] if piv_rest else (sign(y[6]),)) if hm.Tp > 0 else (None,))
            lid_opts = ((rest_opts["hinge"] if lid_rest else (sign(y[7]),)) if hm.Th > 0 and not self.latched
                        else (None,))
            arm_opts = ((rest_opts["arm"] if arm_rest else (sign(self.slide_rate(y)),))
                        if hm.mu > 0 and "arm" in A else (None,))
            for fa, fp, fh in itertools.product(arm_opts, piv_opts, lid_opts):
                fric = {"arm": fa, "pivot": fp, "hinge": fh}
                try:
                    acc, lam = self.accel(y, A, fric)
                except ZeroDivisionError:
                    continue
                # idle only where other contacts hold it already (the pivot: other than the
                # hinge's friction, so that the pivot is the one named stuck)
                idle_ok = True
                for c in ("arm", "pivot", "hinge"):
                    if fric[c] != "idle":
                        continue
                    stuck = dict(fric, **{c: "stick"}) | ({"hinge": None} if c == "pivot" else {})
                    try:
                        self.accel(y, A, stuck)
                        idle_ok = False
                    except ZeroDivisionError:
                        pass
                if not idle_ok:
                    continue
                if any(v < -tol["force"] for n, v in lam.items() if n not in ("arm_t", "pivot_t", "hinge_t")):
                    continue
                if fa == "stick" and abs(lam["arm_t"]) > hm.mu * lam["arm"] + tol["force"]:
                    continue
                if fp == "stick" and abs(lam["pivot_t"]) > self.pivot_bound(y, A, fric) + tol["force"]:
                    continue
                if fh == "stick" and abs(lam["hinge_t"]) > hm.Th + tol["force"]:
                    continue
                if arm_rest and fa in (1, -1) and fa * self.slide_acc(y, acc) < -tol["accel"]:
                    continue
                if piv_rest and fp in (1, -1) and fp * acc[2] * hm.ell < -tol["accel"]:
                    continue
                if lid_rest and fh in (1, -1) and fh * acc[3] * 2 * self.mc.rL < -tol["accel"]:
                    continue
                if any(self.gap_acc(n, y, acc) < -tol["accel"] for n in held - A):
                    continue
                valid.append((A, (acc, fric, y)))
        A, (acc, fric, y) = self.prefer(valid, before, trigger, closing=bool(trigger) and trigger not in before)
        self.active = set(A)
        self.fric = fric
        # the events, named by what changed: the trigger's first, then the impact's, then the rest
        changes = []
        for n in CONTACTS:
            if n not in before and (n in mid):
                changes.append(CLOSED[n])
            if (n in before or n in mid) and n not in A:
                if n == "lid" and "rope" in mid and "rope" not in before:
                    continue  # a lid the rope's jerk knocks off the box: part of that impact
                changes.append(OPENED[n])
        first = [c for c in changes if trigger and c in (CLOSED[trigger], OPENED[trigger])][:1]
        for c in first + [c for c in changes if c not in first] + (["rope_slack"] if let_go else []) + (
                ["rope_taut"] if engage else []):
            self.event(c, t)
        # friction's events: sticking, slipping (from sticking, or back the other way)
        for c, (stick_event, slip_event) in (("arm", ("sandbag_sticks", "sandbag_slips")),
                                             ("pivot", ("seesaw_sticks", "seesaw_slips")),
                                             ("hinge", ("lid_sticks", "lid_slips"))):
            was, now = (before_fric[c] if c != "arm" or "arm" in before else None), fric[c]
            if now == "stick" and was != "stick":
                self.event(stick_event, t)
            if now in (1, -1) and was == "stick":
                self.event(slip_event, t)
            for kind in ("stick", "slip"):
                self.released.add(f"fric_{c}_{kind}")
        if let_go or engage:
            self.released.add("spring_pull" if engage else "spring_slack")
        for n in touch:  # guards that start at zero: open (or holding) by construction
            self.released.add(n + ("_force" if n in A else "_gap"))
        return self.settle_balloon(y, acc, t, v_balloon if (y[3], y[7]) != (L0, Ld0) else None)

    def law_jerk(self, y0, y1, S, touch, tol):
        """The speeds after the rope's jerk by the chosen impact law (docs/model.md, section 7,
        with I_S on both sides: docs/extensions.md, "A seesaw with mass"), from the state before
        it, y0; y1 (the inelastic impact, the rope law) where the law cannot be applied: the jerk
        also presses the lid onto the box, or the law would leave a touching contact closing."""
        hm, mc = self.hm, self.mc
        if "lid" in S:
            return y1
        if S - {"rope", "arm"}:
            raise NotCovered(f"the {mc.law} law with {sorted(S - {'rope', 'arm'})} in the jerk")
        if mc.law == "linear-momentum" and "arm" not in S:
            return y1  # the law has nothing to keep without the sandbag: the rope law
        x, h, s = y0[:3]
        vx, vh, sd, Ld = y0[4:8]
        W = self.contact("rope", y0)[1]
        k = -W[2] / W[3]  # phiL' = k phiS' on the straight rope
        loaded = "arm" in S
        r = -(x * math.cos(s) + h * math.sin(s))
        v_across = vx * math.sin(s) - vh * math.cos(s)
        r_rate = -vx * math.cos(s) - vh * math.sin(s)  # kept (eq. 5)
        m, IS, IL = (mc.m if loaded else 0.0), hm.IS, mc.I
        if mc.law == "linear-momentum":  # the sandbag's and the lid's, as on the massless seesaw
            sd1, r_rate = linear_momentum_law(mc, r, s, y0[3], k, x, h, vx, vh, Ld)
        elif mc.law == "angular-momentum-sum":
            den = m * r * r + IS + IL * k
            if den == 0:
                return y1
            sd1 = (m * r * v_across + IS * sd + IL * Ld) / den
        else:
            sd1 = math.copysign(math.sqrt((m * v_across ** 2 + IS * sd * sd + IL * Ld * Ld) / (m * r * r + IS + IL * k * k)),
                                y1[6])
        y2 = list(y1)
        if loaded:
            y2[4] = -r_rate * math.cos(s) + r * sd1 * math.sin(s)
            y2[5] = -r_rate * math.sin(s) - r * sd1 * math.cos(s)
        y2[6], y2[7] = sd1, k * sd1
        if any(self.rate(n, y2) < -tol["closing"] for n in touch):
            return y1
        return y2

    def kinetic(self, y):
        return sum(y[4 + k] ** 2 / self.hm.Minv[k] for k in range(4) if self.hm.Minv[k]) / 2

    def impulse(self, y, S, targets=None, arm_mode=None, extra=()):
        """The velocities after impulses on the contacts S that leave them with the rates
        `targets` (default zero; in the units of their gaps). With friction on the arm
        (arm_mode): "stick" stops the slip too (its impulse "arm_t", |p_t| <= mu p_n to be
        checked), a sign s takes mu p_n off it (the impulse along W_n - s mu W_t). `extra`:
        the tangential rows ("slide", "turn") to bring to rest as well."""
        hm = self.hm
        names = [n for n in CONTACTS if n in S]
        Ws = [self.contact(n, y)[1] for n in names]
        rhs = [(targets[n] / hm.gap_scale[n] if targets else 0.0) - sum(W[k] * y[4 + k] for k in range(4))
               for n, W in zip(names, Ws)]
        cols = list(Ws)
        Wt = F["slide"](*y[:8], *hm.params)[1]
        if "arm" in names and arm_mode in (1, -1):
            i = names.index("arm")
            cols[i] = [Ws[i][k] - arm_mode * hm.mu * Wt[k] for k in range(4)]
        rest = list(extra) + (["slide"] if "arm" in names and arm_mode == "stick" else [])
        for n in rest:
            W = {"slide": Wt, "turn": [0.0, 0.0, 1.0, 0.0], "turnL": [0.0, 0.0, 0.0, 1.0]}[n]
            names.append({"slide": "arm_t", "turn": "pivot_t", "turnL": "hinge_t"}[n])
            Ws.append(W)
            cols.append(W)
            rhs.append(-sum(W[k] * y[4 + k] for k in range(4)))
        if not names:
            return y, {}
        Mi = hm.Minv
        A = [[sum(Wi[k] * Mi[k] * Cj[k] for k in range(4)) for Cj in cols] for Wi in Ws]
        try:
            p = solve(A, rhs)
        except ZeroDivisionError:
            return y, None
        y1 = list(y)
        for k in range(4):
            y1[4 + k] += Mi[k] * sum(p[i] * cols[i][k] for i in range(len(names)))
        return y1, dict(zip(names, p))

    def pivot_bound(self, y, A, fric):
        """The pivot's bound: T_p, or, with the hinge idle while the taut rope couples the two
        (phiL' = k phiS'), T_p + |k| T_h (docs/extensions.md, "Friction")."""
        hm = self.hm
        if fric["hinge"] == "idle" and "rope" in A and "lid" not in A:
            W = self.contact("rope", y)[1]
            return hm.Tp + abs(W[2] / W[3]) * hm.Th
        return hm.Tp

    def slide_rate(self, y):
        W = F["slide"](*y[:8], *self.hm.params)[1]
        return sum(W[k] * y[4 + k] for k in range(4))

    def slide_acc(self, y, acc):
        _, W, w = F["slide"](*y[:8], *self.hm.params)
        return sum(W[k] * acc[k] for k in range(4)) + w

    def at_rest(self, y, held, row, tol):
        """A slip at rest (docs/extensions.md, "Friction"): slower than the zero of speed, and
        stopping it with the contacts that hold takes no more kinetic energy than the machine's
        mass has at that speed. The velocities with it stopped, or None."""
        speed = {"slide": self.slide_rate(y), "turn": y[6] * self.hm.ell, "turnL": y[7] * 2 * self.mc.rL}[row]
        if abs(speed) >= tol["rate"]:
            return None
        y1, p = self.impulse(y, held, None, None, (row,))
        if p is None:  # the contacts that hold keep it still already
            y1 = y
        if self.kinetic(y) - self.kinetic(y1) > 0.5 * self.hm.mass * tol["rate"] ** 2:
            return None
        return y1

    def gap_acc(self, n, y, acc):
        _, W, w = self.contact(n, y)
        return (sum(W[k] * acc[k] for k in range(4)) + w) * self.hm.gap_scale[n]

    @staticmethod
    def prefer(valid, before, trigger, closing):
        """The valid set; where rounding leaves more than one, the one that changes least (the
        trigger going the way it tends)."""
        if not valid:
            raise NotCovered("no set of contacts is consistent")
        want = set(before)
        if trigger:
            (want.add if closing else want.discard)(trigger)
        return min(valid, key=lambda v: (bool(trigger) and (trigger in v[0]) != (trigger in want),
                                         len(v[0] ^ want)))

    # --- the run
    def simulate(self):
        mc = self.mc
        if abs(-mc.x0 * math.sin(mc.s0) + mc.h0 * math.cos(mc.s0)) <= 1e-9:
            raise NotCovered("a sandbag on the arm at the start")
        if mc.C(mc.s0, mc.L0) > -2 * mc.lR * 1e-9:
            raise NotCovered("a rope straight (or too short) at the start")
        hl, _ = mc.h_lim(mc.L0, 0.0)
        y = [mc.x0, mc.h0, mc.s0, mc.L0, 0.0, 0.0, 0.0, 0.0] + (self.small.start(mc.L0) if self.small else [hl, 0.0])
        self.active = {"lid"}
        self.released = set()
        touch = self.touching(y)
        if touch != self.active or self.hm.mu > 0 or self.hm.Tp > 0 or self.hm.Th > 0:
            # a seesaw standing on the floor, friction: decided on forces, at rest (friction's
            # state at the start is no event)
            self.active = touch
            y = self.decide(y, 0.0, None)
            self.events = [e for e in self.events if not e[0].endswith(("_sticks", "_slips"))]
        return march(self, y)

    # what whatnext_reference.march asks of a run
    def angles(self, y):
        return y[2], y[3]

    def after_step(self, y):
        y = self.project(y, self.active)  # back onto the holding contacts, against the drift
        extra = (("slide",) if self.fric["arm"] == "stick" and "arm" in self.active else ()) + (
            ("turn",) if self.fric["pivot"] == "stick" else ()) + (("turnL",) if self.fric["hinge"] == "stick" else ())
        if extra:  # and the sticking ones' rates
            y = self.impulse(y, self.active, None, None, extra)[0]
        if self.small:
            y = y[:8] + self.small.project(y[8:], y[3], y[7])
        return y

    def handle_event(self, name, y, t):
        return self.handle(name, y, t)

    def closing_within_rounding(self, name, y):
        """When a gap that never opens beyond rounding closes again: the zero of its expansion
        g + g' tau + g'' tau^2 / 2 (over a microsecond its next term is far below rounding)."""
        acc, _ = self.accel(y)
        if name.startswith("B_"):
            return self.small.closing_within_rounding(name, y[8:], y[3], y[7], acc[3])
        if name == "balloon_caught":
            return balloon_closing(self.mc, y[3], y[7], acc[3], y[8], y[9])
        contact, kind = name.rsplit("_", 1)
        if kind != "gap":
            return None
        g = self.contact(contact, y)[0] * self.hm.gap_scale[contact]
        return quadratic_closing(g, self.rate(contact, y), self.gap_acc(contact, y, acc))

    def handle(self, name, y, t):
        hm, mc = self.hm, self.mc
        if name == "radio_on":  # the string straight: it pulls with the balloon's net lift
            self.event("radio_on" if mc.lift >= mc.switch_force else "switch_stays_off", t)
            return None
        if name == "lid_open":  # the radio's latch (docs/extensions.md, "The radio")
            self.event(name, t)
            if "rope" in self.active or self.spring:
                self.event("rope_slack", t)  # let go from the seesaw for good
            if self.small and "lid" in self.small.active:  # freed with its current velocity
                self.event("balloon_free", t)
            if self.small:  # and the latched lid no longer limits it
                self.small.latch(y[8:], y[3])
            if self.balloon == "stuck":  # freed with its current velocity
                self.balloon = "free"
                self.event("balloon_free", t)
                y = y[:8] + list(mc.h_lim(y[3], y[7]))
            # the lid held where it is: its coordinate without motion (an infinite inertia)
            self.latched, self.spring = True, False
            self.fric["hinge"] = None
            if not (hm.floor or hm.end_stop):
                # the paper's machine (docs/extensions.md, "The radio"): the sandbag goes on in free
                # fall, no machine event is checked but the seesaw turning vertical under its own
                # weight; the built machine's seesaw and sandbag go on on its floor and stop
                self.active = set()
                self.fell_off = True
                self.fric["arm"] = None
            self.active -= {"rope", "lid"}
            hm.Minv = hm.Minv[:3] + [0.0]
            y = y[:7] + [0.0] + y[8:]
            return self.decide(y, t, None)
        if name == "balloon_free":
            acc, _ = self.accel(y)
            return self.settle_balloon(y, acc, t)
        if name.startswith("fric_"):
            _, c, kind = name.split("_")
            return self.decide(y, t, None, c if kind == "stick" else None)
        if name.startswith("B_") or name == "balloon_escapes":
            acc, _ = self.accel(y)
            return y[:8] + self.small.handle(name, y[8:], y[3], y[7], acc[3], t)
        if name == "spring_slack" and F["lock"](*y[:8], *hm.params) >= 0:
            self.event("rope_locked", t)  # straight on the far side of the hinge
            return None
        if name in ("spring_pull", "spring_slack"):
            self.spring = name == "spring_slack"
            self.event("rope_taut" if self.spring else "rope_slack", t)
            self.released.add("spring_pull" if self.spring else "spring_slack")
            return self.decide(y, t, None)
        if name == "sandbag_falls_off":
            self.event(name, t)
            self.fell_off = True
            self.active.discard("arm")
            return self.decide(y, t, None)
        contact, kind = name.rsplit("_", 1)
        if contact == "arm" and kind == "gap":
            along = F["along"](*y[:8], *hm.params)
            if along <= 0:
                self.event("sandbag_at_pivot", t)
                return None
            if along > hm.arm:  # past the arm's end: it missed the arm, and never lands again
                self.event("sandbag_falls_off", t)
                self.fell_off = True
                self.released.add("arm_gap")
                return y
        if contact == "rope" and kind == "gap" and F["lock"](*y[:8], *hm.params) >= 0:
            self.event("rope_locked", t)  # straight on the far side of the hinge
            return None
        return self.decide(y, t, contact)


def subsets(items):
    items = sorted(items)
    return [set(c) for r in range(len(items) + 1) for c in itertools.combinations(items, r)
            if "stop" not in c or "arm" in c]  # the stop is an edge of the arm

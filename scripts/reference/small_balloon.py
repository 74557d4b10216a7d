"""The reference's balloon smaller than the box (docs/extensions.md, "A balloon smaller than the box").

A disc of radius r_B in the box's plane, its centre p = (p_x, p_y) from the hinge H (y up),
buoyant with the balloon's a_B(v) (lift up, drag against its velocity in the plane), one-way
coupled: the lid's motion phiL(t) is prescribed by the machine's run. Its obstacles are unilateral
contacts, each a gap >= 0 that is a function of (p, phiL):

    lid    the lid's segment from H to its free edge E = 2 r_L u: p.n - r_B beside it (n = (sin phiL,
           -cos phiL), away from the lid into the box), |p - E| - r_B beyond the edge;
    wall   the far wall x = 2 r_L: 2 r_L - r_B - p_x below its top W = (2 r_L, 0), |p - W| - r_B above;
    hinge  the hinge's wall x = 0: p_x - r_B below the box's top, |p - H| - r_B above.

SymPy derives each gap's gradient and second derivatives; the run is the same event-driven method
as the machine's (docs/model.md, section 5) with the disc's metric: at an event the velocities are
projected (one-signed impulses, every subset tried: the inelastic stop, "its velocity across the
lid becomes the lid's, along it is kept"), then the forces on the accelerations decide which
contacts hold. Nothing here is the docs' closed forms (q_max, the 2x2 corner problem): those follow.

The story's rules on top (docs/extensions.md): the lid's contact closing beside its face is
`balloon_caught`, opening there `balloon_free` (the walls' and the free edge's are not reported); on the lid the balloon escapes when its centre
passes the perpendicular from W to the lid (p.u = 2 r_L cos phiL), free in the box when it is higher
than the lid can reach (p_y >= 2 r_L + r_B) or beyond the free edge and above the lid's line; escaped, only the lid is an obstacle, and once it has
left the lid nothing is (out). It starts in the corner, at rest, the lid resting.
"""
import itertools
import math

import sympy as sp

from whatnext_reference import NotCovered as NotCoveredBalloon


def _derive():
    px, py, L, vx, vy, Ld = sp.symbols("px py L vx vy Ld", real=True)
    rB, rL = sp.symbols("rB rL", positive=True)
    pieces = {
        "lid_face": px * sp.sin(L) - py * sp.cos(L) - rB,
        "lid_edge": sp.sqrt((px - 2 * rL * sp.cos(L)) ** 2 + (py - 2 * rL * sp.sin(L)) ** 2) - rB,
        "wall_face": 2 * rL - rB - px,
        "wall_top": sp.sqrt((px - 2 * rL) ** 2 + py ** 2) - rB,
        "hinge_face": px - rB,
        "hinge_top": sp.sqrt(px ** 2 + py ** 2) - rB,
    }
    q, v = (px, py, L), (vx, vy, Ld)
    out = {}
    for name, g in pieces.items():
        grad = [sp.diff(g, x) for x in q]
        # g'' = N . p'' + g_L phiL'' + w, w the terms quadratic in the rates
        w = sum(sp.diff(g, q[i], q[j]) * v[i] * v[j] for i in range(3) for j in range(3))
        out[name] = sp.lambdify((px, py, L, vx, vy, Ld, rB, rL), [g, grad, w], "math", cse=True)
    return out


G = _derive()
CONTACTS = ("lid", "wall", "hinge")


class SmallBalloon:
    """The disc's state b = [p_x, p_y, v_x, v_y] and what holds it; `run` reports its events."""

    def __init__(self, mc, run):
        self.mc, self.run = mc, run
        self.rB, self.rL = float(mc.rB), float(mc.rL)
        self.status = "in"  # in the box, escaped (on the lid outside), out (free of everything)
        self.active = {"lid", "wall"}
        self.latched = False
        self.side = {}  # which piece of each held contact's gap: a kink guard watches its change

    def start(self, L0):
        """At rest in the corner of the resting lid and the far wall."""
        rB, rL = self.rB, self.rL
        s, c = math.sin(L0), math.cos(L0)
        if s * rL >= rB:
            raise NotCoveredBalloon("a resting lid so steep that the corner does not hold")
        if (2 * rL - rB) * s <= rB:  # against the wall's face
            q = (2 * rL - rB - rB * s) / c
        else:  # against its top
            D = 2 * rL * s
            q = 2 * rL * c - math.sqrt(D * (2 * rB - D))
        b = [q * c + rB * s, q * s - rB * c, 0.0, 0.0]
        self.active = {"lid", "wall"}
        self.set_sides(b, L0)
        return b

    def latch(self, b, L):
        """The radio's latch holds the lid open: the balloon is freed with its velocity and the
        lid limits it no more (docs/extensions.md, "The radio")."""
        self.latched = True
        self.active.discard("lid")
        if self.status == "escaped":
            self.status = "out"
        self.set_sides(b, L)

    # --- the contacts
    def exists(self):
        out = {"in": CONTACTS, "escaped": ("lid",), "out": ()}[self.status]
        return tuple(n for n in out if not (self.latched and n == "lid"))

    def piece(self, name, b, L):
        if name == "lid":
            along = b[0] * math.cos(L) + b[1] * math.sin(L)
            return "lid_face" if along <= 2 * self.rL else "lid_edge"
        if name == "wall":
            if b[0] > 2 * self.rL and b[1] <= 0:
                raise NotCoveredBalloon("a balloon outside the box below its top before it escaped")
            return "wall_face" if b[1] <= 0 else "wall_top"
        return "hinge_face" if b[1] <= 0 else "hinge_top"

    def contact(self, name, b, L, Ld, piece=None):
        """gap, its gradient in (p_x, p_y, phiL), and the quadratic terms of its second derivative."""
        return G[piece or self.piece(name, b, L)](b[0], b[1], L, b[2], b[3], Ld, self.rB, self.rL)

    def rate(self, name, b, L, Ld):
        _, N, _ = self.contact(name, b, L, Ld)
        return N[0] * b[2] + N[1] * b[3] + N[2] * Ld

    def free_acc(self, b):
        v = math.hypot(b[2], b[3])
        mc = self.mc
        return [-mc.drag * v * b[2], mc.aB - mc.drag * v * b[3]]

    def accel(self, b, L, Ld, Ldd, active=None):
        """p'' and the contact forces (per unit of the balloon's accelerated mass)."""
        names = [n for n in CONTACTS if n in (self.active if active is None else active)]
        f = self.free_acc(b)
        if not names:
            return f, {}
        rows = []
        for n in names:
            _, N, w = self.contact(n, b, L, Ld)
            rows.append((N, w + N[2] * Ldd))
        A = [[Ni[0] * Nj[0] + Ni[1] * Nj[1] for Nj, _ in rows] for Ni, _ in rows]
        rhs = [-(N[0] * f[0] + N[1] * f[1] + c) for N, c in rows]
        lam = _solve(A, rhs)
        a = [f[k] + sum(lam[i] * rows[i][0][k] for i in range(len(rows))) for k in range(2)]
        return a, dict(zip(names, lam))

    def flow(self, b, L, Ld, Ldd):
        a, _ = self.accel(b, L, Ld, Ldd)
        return [b[2], b[3], a[0], a[1]]

    def project(self, b, L, Ld, names=None):
        """Back onto the holding contacts (gaps and rates zero), against the drift."""
        names = [n for n in CONTACTS if n in (self.active if names is None else names)]
        if not names:
            return b
        b = list(b)
        for it in range(4):
            rows = [self.contact(n, b, L, Ld) for n in names]
            A = [[r[1][0] * s[1][0] + r[1][1] * s[1][1] for s in rows] for r in rows]
            if it < 3:
                mu = _solve(A, [-r[0] for r in rows])
                for k in range(2):
                    b[k] += sum(mu[i] * rows[i][1][k] for i in range(len(names)))
            else:
                mu = _solve(A, [-(r[1][0] * b[2] + r[1][1] * b[3] + r[1][2] * Ld) for r in rows])
                for k in range(2):
                    b[2 + k] += sum(mu[i] * rows[i][1][k] for i in range(len(names)))
        return b

    def set_sides(self, b, L):
        self.side = {n: self.piece(n, b, L) for n in self.active}

    # --- guards
    def guards(self, b, L, Ld, Ldd):
        out = {}
        _, lam = self.accel(b, L, Ld, Ldd)
        g = self.mc.g
        for n in self.exists():
            if n in self.active:
                out["B_" + n + "_force"] = lam[n] / g
            else:
                out["B_" + n + "_gap"] = self.contact(n, b, L, Ld)[0]
        for n in self.active:  # a held contact passing from one piece of its gap to the other
            out["B_" + n + "_kink"] = self.kink(n, b, L)
        if self.status == "in":
            if "lid" in self.active:
                out["balloon_escapes"] = 2 * self.rL * math.cos(L) - (b[0] * math.cos(L) + b[1] * math.sin(L))
            else:
                out["balloon_escapes"] = 2 * self.rL + self.rB - b[1]
                # or its centre above the lid's line, beyond the free edge (beside the lid's face it
                # cannot be): nothing of the box is over it (docs/extensions.md)
                out["B_above_line"] = b[0] * math.sin(L) - b[1] * math.cos(L)
        return out

    def kink(self, n, b, L):
        side = self.side[n]
        if n == "lid":
            d = 2 * self.rL - (b[0] * math.cos(L) + b[1] * math.sin(L))
        else:
            d = -b[1]
        return d if side.endswith("face") else -d

    # --- events
    def decide(self, b, L, Ld, Ldd, t, trigger=None):
        """Which contacts hold after an event (the machine's, which may have jumped the lid's
        rate, or the disc's own): the impact, then the forces; its events reported."""
        before = set(self.active)
        exists = self.exists()
        touch = {n for n in exists if n in before or abs(self.contact(n, b, L, Ld)[0]) <= 1e-9}
        if trigger:
            touch.add(trigger)
        zero_v = 1e-6 * max(math.sqrt(self.mc.g * self.rL), abs(b[2]), abs(b[3]), abs(Ld) * 2 * self.rL)
        rates = {n: self.rate(n, b, L, Ld) for n in touch}
        S = set()
        if any(r < -1e-12 * zero_v * 1e6 for r in rates.values()):
            valid = []
            for S in _subsets(touch):
                b1, p = self.impulse(b, L, Ld, S)
                if p is None or any(v < -1e-12 for v in p.values()):
                    continue
                if any(self.rate(n, b1, L, Ld) < -1e-12 * zero_v * 1e6 for n in touch - S):
                    continue
                valid.append((S, b1))
            S, b = _prefer(valid, before, trigger)
        held = {n for n in touch if self.rate(n, b, L, Ld) < zero_v}
        b = self.project(b, L, Ld, held)
        valid = []
        for A in _subsets(held):
            try:
                a, lam = self.accel(b, L, Ld, Ldd, A)
            except ZeroDivisionError:
                continue
            if any(v < -1e-9 * self.mc.g for v in lam.values()):
                continue
            ok = True
            for n in held - A:
                _, N, w = self.contact(n, b, L, Ld)
                if N[0] * a[0] + N[1] * a[1] + N[2] * Ldd + w < -1e-9 * self.mc.g:
                    ok = False
            if ok:
                valid.append((A, a))
        # a contact that would hold with no force is let go: it stays touching within rounding
        # while nothing presses it on (a disc rising along a wall's face)
        A, _ = min(valid, key=lambda v: (len(v[0]), len(v[0] ^ before)))
        self.active = set(A)
        self.set_sides(b, L)
        # a lid that strikes the balloon and leaves it at once: caught and free at one instant;
        # named beside the lid's face only (its free edge stops the balloon from beside like a
        # wall, and rolling off it is the way out: docs/extensions.md)
        face = self.piece("lid", b, L) == "lid_face"
        struck = "lid" in S
        if ("lid" in A or struck) and "lid" not in before and face:
            self.run.event("balloon_caught", t)
            if "lid" in A and self.status == "in" and (
                    b[0] * math.cos(L) + b[1] * math.sin(L) >= 2 * self.rL * math.cos(L)):
                # caught beyond the perpendicular from the wall's top: out of the box already
                self.run.event("balloon_escapes", t)
                self.status = "escaped"
                A = self.active = set(A) & set(self.exists())
                self.set_sides(b, L)
        # let go by the lid beside its face
        if ("lid" in before or struck) and "lid" not in A and face:
            self.run.event("balloon_free", t)
        if self.status == "escaped" and "lid" not in A:
            self.status = "out"
        for n in touch:
            self.run.released.add("B_" + n + ("_force" if n in A else "_gap"))
        return b

    def impulse(self, b, L, Ld, S):
        names = [n for n in CONTACTS if n in S]
        if not names:
            return b, {}
        rows = [self.contact(n, b, L, Ld)[1] for n in names]
        A = [[r[0] * s[0] + r[1] * s[1] for s in rows] for r in rows]
        try:
            p = _solve(A, [-(r[0] * b[2] + r[1] * b[3] + r[2] * Ld) for r in rows])
        except ZeroDivisionError:
            return b, None
        b1 = list(b)
        for k in range(2):
            b1[2 + k] += sum(p[i] * rows[i][k] for i in range(len(names)))
        return b1, dict(zip(names, p))

    def handle(self, name, b, L, Ld, Ldd, t):
        if name == "balloon_escapes":
            self.run.event(name, t)
            self.status = "escaped" if "lid" in self.active else "out"
            self.active &= set(self.exists())
            self.set_sides(b, L)
            return b
        if name == "B_above_line":
            if b[0] * math.cos(L) + b[1] * math.sin(L) <= 2 * self.rL:
                raise NotCoveredBalloon("a free balloon crossing the lid's line beside the lid")
            self.run.event("balloon_escapes", t)
            self.status = "out"
            self.active = set()
            self.set_sides(b, L)
            return b
        _, contact, kind = name.split("_")
        if kind == "kink":
            self.set_sides(b, L)
            return self.decide(b, L, Ld, Ldd, t)
        return self.decide(b, L, Ld, Ldd, t, contact if kind == "gap" else None)

    def closing_within_rounding(self, name, b, L, Ld, Ldd):
        _, contact, kind = name.split("_")
        if kind != "gap":
            return None
        gap, N, w = self.contact(contact, b, L, Ld)
        a = self.free_acc(b)
        acc = N[0] * a[0] + N[1] * a[1] + N[2] * Ldd + w
        r = N[0] * b[2] + N[1] * b[3] + N[2] * Ld
        if acc >= 0:
            return None
        return (r + math.sqrt(max(r * r - 2 * acc * max(gap, 0.0), 0.0))) / -acc


def _solve(A, rhs):
    n = len(rhs)
    if n == 1:
        if A[0][0] == 0:
            raise ZeroDivisionError
        return [rhs[0] / A[0][0]]
    if n == 2:
        det = A[0][0] * A[1][1] - A[0][1] * A[1][0]
        if abs(det) <= 1e-12 * (abs(A[0][0] * A[1][1]) + abs(A[0][1] * A[1][0])):
            raise ZeroDivisionError
        return [(rhs[0] * A[1][1] - A[0][1] * rhs[1]) / det, (A[0][0] * rhs[1] - A[1][0] * rhs[0]) / det]
    raise ZeroDivisionError  # three contacts on a disc in the plane: over-determined


def _subsets(items):
    items = sorted(items)
    return [set(c) for r in range(len(items) + 1) for c in itertools.combinations(items, r)]


def _prefer(valid, before, trigger):
    if not valid:
        raise NotCoveredBalloon("no set of the balloon's contacts is consistent")
    want = set(before) | ({trigger} if trigger else set())
    return min(valid, key=lambda v: (bool(trigger) and trigger not in v[0], len(v[0] ^ want)))

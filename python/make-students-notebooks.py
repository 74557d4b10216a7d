"""Writes examples/students.ipynb and examples/students-teacher.ipynb from one list of cells, so
that the two copies differ only in the answers (tests/python/test_notebook.py checks that):

    /usr/bin/python3 python/make-students-notebooks.py           # writes into examples/
"""
import pathlib
import sys

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

out = sys.argv[1] if len(sys.argv) > 1 else str(pathlib.Path(__file__).resolve().parents[1] / "examples")
cells = []  # (kind, text, answer_text or None)
def md(t): cells.append(("md", t.strip("\n"), None))
def code(t, answer=None): cells.append(("code", t.strip("\n"), None if answer is None else answer.strip("\n")))

md(r"""
# Kermit's machine as a mechanics exercise

These exercises follow U. Schröter's paper *Kermit's What-Happens-Next-Machine Reloaded*: a sandbag
falls onto a massless seesaw, a rope from the seesaw's right end pulls the lid of a box open. You will

1. set up the paper's Lagrangian and derive its equations of motion (3) and (4) with SymPy,
2. check them against the simulator `whatnext` at states of a real run,
3. compare the impact laws for the moment the rope tightens,
4. run a sweep over many machines and test it against a free fall you compute yourself.

Cells marked **Exercise** are yours: replace the `None` and run the check below it. The teacher's
copy (`students-teacher.ipynb`) has the answers.

To run it from a clone of the project on Debian 12: `./run.sh notebook` installs Jupyter (Debian's
`jupyter-notebook`) and opens the notebooks; elsewhere, start Jupyter with
`PYTHONPATH=/path/to/whatnext/build/python` and Debian's Python. The notebook needs no other files:
the machines ship with the module (`whatnext.example(2)`).
""")
code(r"""
import numpy as np
import sympy as sp
import matplotlib.pyplot as plt
import whatnext

sp.init_printing()
""")
md(r"""
## 1. The Lagrangian (the paper's section 2)

While the sandbag sits on the seesaw at distance $r_S$ from the pivot and the rope is straight,
the machine has two degrees of freedom, $r_S$ and $\varphi_S$; the lid's angle is a function of the
seesaw's, $\varphi_L = \Phi(\varphi_S)$ (the rope's constraint, exercise 2). The seesaw and the rope
have no mass. Positive $\varphi_S$ lowers the left arm, where the sandbag is, so its height is
$h_S = -r_S \sin\varphi_S$; the lid's centre of mass is $r_L \sin\varphi_L$ above its hinge.

**Exercise 1a.** Write the Lagrangian $\mathcal{L} = T - V$ of the sandbag and the lid (without the
balloon), using the symbols below. The lid turns about its hinge with moment of inertia $I_L$.
""")
code(r"""
t = sp.symbols("t")
m_S, m_L, g, r_L, I_L = sp.symbols("m_S m_L g r_L I_L", positive=True)
r = sp.Function("r_S")(t)
phi_S = sp.Function("varphi_S")(t)
Phi = sp.Function("Phi")        # the lid's angle as a function of the seesaw's (rope straight)
phi_L = Phi(phi_S)
""")
code(r"""
# Exercise 1a: the Lagrangian, in r, phi_S, phi_L and their time derivatives (r.diff(t), ...)
L = None
""", r"""
# Exercise 1a: the Lagrangian, in r, phi_S, phi_L and their time derivatives (r.diff(t), ...)
L = (m_S / 2 * (r.diff(t)**2 + r**2 * phi_S.diff(t)**2) + m_S * g * r * sp.sin(phi_S)
     + I_L / 2 * phi_L.diff(t)**2 - m_L * g * r_L * sp.sin(phi_L))
""")
md(r"""
**Exercise 1b.** Write the Euler–Lagrange equations for $r_S$ and $\varphi_S$ and solve them for the
accelerations $\ddot r_S$ and $\ddot\varphi_S$. (Hint: `sp.diff(L, q) - sp.diff(sp.diff(L, q.diff(t)), t)`;
replace the second derivatives by symbols before `sp.solve`.) Put the results in `r_dd` and `phi_S_dd`.
""")
code(r"""
# Exercise 1b
r_dd = None
phi_S_dd = None
""", r"""
# Exercise 1b
def euler_lagrange(q):
    return sp.diff(L, q) - sp.diff(sp.diff(L, q.diff(t)), t)

a_r, a_phi = sp.symbols("a_r a_phi")
second = {r.diff(t, 2): a_r, phi_S.diff(t, 2): a_phi}
solution = sp.solve([euler_lagrange(r).subs(second), euler_lagrange(phi_S).subs(second)], [a_r, a_phi], dict=True)[0]
r_dd, phi_S_dd = solution[a_r], solution[a_phi]
""")
md(r"""
The paper's equations, with $k = d\varphi_L/d\varphi_S$ and $k' = d^2\varphi_L/d\varphi_S^2$:

$$\ddot r_S = g\sin\varphi_S + r_S\dot\varphi_S^2 \qquad (3)$$

$$\ddot\varphi_S = \frac{m_S g r_S\cos\varphi_S - 2 m_S r_S \dot r_S\dot\varphi_S
 - (m_L g r_L\cos\varphi_L + I_L k' \dot\varphi_S^2)\,k}{m_S r_S^2 + I_L k^2} \qquad (4)$$

The check writes your results in plain symbols and compares them with (3) and (4).
""")
code(r"""
r_, rd, ps, pd, pl, k, kp = sp.symbols("r rdot varphi_S varphidot_S varphi_L k kprime")

def plain(e):
    # derivatives of Phi first, then Phi itself, then the time derivatives, then the functions
    e = e.subs(sp.Derivative(Phi(phi_S), (phi_S, 2)), kp).subs(sp.Derivative(Phi(phi_S), phi_S), k)
    e = e.subs(Phi(phi_S), pl).subs({r.diff(t): rd, phi_S.diff(t): pd})
    return e.subs({r: r_, phi_S: ps})

eq3 = g * sp.sin(ps) + r_ * pd**2
eq4 = (m_S * g * r_ * sp.cos(ps) - 2 * m_S * r_ * rd * pd - (m_L * g * r_L * sp.cos(pl) + I_L * kp * pd**2) * k) \
      / (m_S * r_**2 + I_L * k**2)
if r_dd is None or phi_S_dd is None:
    print("Exercise 1 is still open.")
else:
    assert sp.simplify(plain(r_dd) - eq3) == 0, "r_dd differs from eq. (3)"
    assert sp.simplify(plain(phi_S_dd) - eq4) == 0, "phi_S_dd differs from eq. (4)"
    print("Both accelerations are the paper's eqs. (3) and (4).")
""")
md(r"""
## 2. The rope, and the simulator's accelerations

The seesaw's right end is $R = r_H(\cos\varphi_S, \sin\varphi_S)$, the lid's hinge $H$ and its free
edge $E = H + 2r_L(\cos\varphi_L, \sin\varphi_L)$ (docs/model.md, section 2). A straight rope means
$C(\varphi_S, \varphi_L) = |R - E|^2 - l_R^2 = 0$.

**Exercise 2.** Write $C$ and get $k = d\varphi_L/d\varphi_S$ and $k'$ by implicit differentiation of
$C(\varphi_S, \varphi_L(\varphi_S)) = 0$, as SymPy expressions in `ps` and `pl`.
""")
code(r"""
m2 = whatnext.example(2)           # the paper's example 2: the rope stays straight while it pulls
inputs = m2.inputs
r_H, l_R = inputs["geometry.seesaw_right_arm"], inputs["geometry.rope_length"]
f, gamma = inputs["geometry.hinge_distance"], np.radians(inputs["geometry.hinge_angle"])
H = sp.Matrix([f * np.cos(gamma), -f * np.sin(gamma)])
numbers = {m_S: inputs["masses.sandbag"], m_L: inputs["masses.lid"], g: 9.81,
           r_L: inputs["geometry.lid_half_length"]}
numbers[I_L] = numbers[m_L] * (2 * numbers[r_L])**2 / 3
R = r_H * sp.Matrix([sp.cos(ps), sp.sin(ps)])
E = H + 2 * numbers[r_L] * sp.Matrix([sp.cos(pl), sp.sin(pl)])
""")
code(r"""
# Exercise 2
C = None
k_expr = None
kp_expr = None
""", r"""
# Exercise 2
C = (R - E).dot(R - E) - l_R**2
C_S, C_L = C.diff(ps), C.diff(pl)
k_expr = -C_S / C_L
kp_expr = -(C.diff(ps, 2) + 2 * C.diff(ps, pl) * k_expr + C.diff(pl, 2) * k_expr**2) / C_L
""")
md(r"""
Now a run of example 2, sampled every 10 µs. Between `rope_taut` and `rope_slack` (mode M4) the
sandbag is on the seesaw and the rope straight. At a few of those samples the check evaluates (3)
and (4) at the simulator's state and compares them with the simulator's own accelerations, taken as
central differences of its velocities $\dot r_S$ and $\dot\varphi_S$.
""")
code(r"""
run = whatnext.simulate(m2, output_step=1e-5, t_max=0.5)
s = run.samples
h = 1e-5
taut, slack = run.event("rope_taut").time, run.event("rope_slack").time
print(f"rope straight from {taut:.4f} s to {slack:.4f} s")
rows = [i for i in np.searchsorted(s["t_s"], np.linspace(taut + 0.01, slack - 0.01, 5))]
if C is None or k_expr is None or kp_expr is None or r_dd is None:
    print("Exercises 1 and 2 are still open.")
else:
    accel = sp.lambdify((r_, rd, ps, pd, pl, k, kp), [eq3.subs(numbers), eq4.subs(numbers)])
    k_f, kp_f, C_f = sp.lambdify((ps, pl), k_expr), sp.lambdify((ps, pl), kp_expr), sp.lambdify((ps, pl), C)
    print(f"{'t [s]':>8s} {'C [m²]':>10s} {'r_dd eq.3':>12s} {'simulator':>12s} {'phi_dd eq.4':>12s} {'simulator':>12s}")
    for i in rows:
        assert s["mode"][i - 1] == s["mode"][i + 1] == "M4" and s["event"][i - 1: i + 2].tolist() == ["", "", ""]
        state = dict(r=s["r_m"][i], rd=s["dr_m_per_s"][i], ps=np.radians(s["phi_s_deg"][i]),
                     pd=np.radians(s["dphi_s_deg_per_s"][i]), pl=np.radians(s["phi_l_deg"][i]))
        k_i, kp_i = k_f(state["ps"], state["pl"]), kp_f(state["ps"], state["pl"])
        a3, a4 = accel(state["r"], state["rd"], state["ps"], state["pd"], state["pl"], k_i, kp_i)
        sim_r = (s["dr_m_per_s"][i + 1] - s["dr_m_per_s"][i - 1]) / (2 * h)
        sim_phi = np.radians(s["dphi_s_deg_per_s"][i + 1] - s["dphi_s_deg_per_s"][i - 1]) / (2 * h)
        print(f"{s['t_s'][i]:8.4f} {C_f(state['ps'], state['pl']):10.1e} {a3:12.5f} {sim_r:12.5f} {a4:12.5f} {sim_phi:12.5f}")
        assert abs(C_f(state["ps"], state["pl"])) < 1e-6            # the rope is straight there
        assert abs(a3 - sim_r) < 1e-4 * max(1.0, abs(a3))
        assert abs(a4 - sim_phi) < 1e-4 * max(1.0, abs(a4))
    print("The simulator moves by the paper's equations (3) and (4).")
""")
md(r"""
## 3. The impact laws (the paper's section 3)

When the rope tightens the lid starts to move in an instant: an impact, whose outcome the smooth
equations do not fix. The paper compares four laws; `run.impact_law` chooses one. The `rope` law
(the paper's eq. 7, the default) is a perfectly inelastic jerk along the rope; the `kinetic-energy`
law keeps the kinetic energy by construction.

**Exercise 3.** For example 2, compute for the `rope` and the `kinetic-energy` law the fraction of
the machine's energy lost at the `rope_taut` event (use `run.event("rope_taut").energy_before` and
`.energy_after`). Put them in `lost_rope` and `lost_kinetic`. Which law opens the lid sooner, and why?
""")
code(r"""
# Exercise 3
lost_rope = None
lost_kinetic = None
""", r"""
# Exercise 3
def lost(law):
    pull = whatnext.simulate(m2.set("run.impact_law", law), samples=False).event("rope_taut")
    return 1 - pull.energy_after / pull.energy_before

lost_rope, lost_kinetic = lost("rope"), lost("kinetic-energy")
# The rope law loses energy (an inelastic jerk), the kinetic-energy law none: with more energy left
# the lid opens sooner (the paper: 0.54 s against 0.47 s).
""")
code(r"""
if lost_rope is None or lost_kinetic is None:
    print("Exercise 3 is still open.")
else:
    print(f"energy lost at the pull: rope law {lost_rope:.1%}, kinetic-energy law {lost_kinetic:.1%}")
    assert lost_rope > 0.1 and abs(lost_kinetic) < 1e-9
    laws = {"rope": 0.54, "kinetic-energy": 0.47}     # the paper's lid-open times
    times = {law: whatnext.simulate(m2.set("run.impact_law", law), samples=False).event("lid_open").time for law in laws}
    print("lid open:", {law: round(t, 3) for law, t in times.items()}, "paper:", laws)
    assert times["kinetic-energy"] < times["rope"]
""")
md(r"""
## 4. Many machines: a sweep

`whatnext.sweep` runs a machine for every value of a key and returns one row per machine, with the
first time of every event. Before it lands, the sandbag falls freely: from $(x_0, h_0)$ it meets the
seesaw's left arm, the line $h = x\tan\varphi_{S0}$, after $t = \sqrt{2(h_0 - h)/g}$.

**Exercise 4.** Sweep `start.sandbag_height` of example 2 over 0.3 m to 1.5 m (60 values). Compute the
free-fall landing time for each height yourself and put it in `t_fall`; the check compares it with the
sweep's `sandbag_lands` column. The plot then shows when the lid opens, counted from the start and
from the landing: what does a higher drop buy, and what does it cost?
""")
code(r"""
heights = np.linspace(0.3, 1.5, 60)
sweep = whatnext.sweep(m2, {"start.sandbag_height": heights})
x0, phi0 = inputs["start.sandbag_x"], np.radians(inputs["start.seesaw_angle"])
# Exercise 4
t_fall = None
""", r"""
heights = np.linspace(0.3, 1.5, 60)
sweep = whatnext.sweep(m2, {"start.sandbag_height": heights})
x0, phi0 = inputs["start.sandbag_x"], np.radians(inputs["start.seesaw_angle"])
# Exercise 4
h_arm = x0 * np.tan(phi0)
t_fall = np.sqrt(2 * (heights - h_arm) / 9.81)
""")
code(r"""
if t_fall is None:
    print("Exercise 4 is still open.")
else:
    assert np.allclose(sweep["sandbag_lands"], t_fall, rtol=0, atol=1e-7)
    print("every landing time is the free fall's")
fig, ax = plt.subplots(figsize=(7, 3.5))
ax.plot(sweep["start.sandbag_height"], sweep["lid_open"], ".", label="from the start")
ax.plot(sweep["start.sandbag_height"], sweep["lid_open"] - sweep["sandbag_lands"], ".", label="from the landing")
ax.set_xlabel("sandbag's start height [m]")
ax.set_ylabel("lid open after [s]")
ax.set_title("example 2: a higher drop opens the lid faster once it lands, but falls longer")
ax.legend();
""")

def build(teacher):
    nb = new_notebook()
    nb.metadata = {"kernelspec": {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"},
                   "language_info": {"name": "python"}}
    for kind, text, answer in cells:
        if kind == "md":
            nb.cells.append(new_markdown_cell(text))
        else:
            cell = new_code_cell(answer if (teacher and answer is not None) else text)
            if answer is not None:
                cell.metadata["tags"] = ["answer" if teacher else "exercise"]
            nb.cells.append(cell)
    if teacher:
        nb.cells[0].source = nb.cells[0].source.replace("# Kermit's machine as a mechanics exercise",
                                                        "# Kermit's machine as a mechanics exercise — the teacher's copy, with the answers", 1)
    for i, c in enumerate(nb.cells):
        c.id = f"cell-{i}"  # fixed ids: the files change only where their text does
    return nb

nbformat.write(build(False), f"{out}/students.ipynb", version=4)
nbformat.write(build(True), f"{out}/students-teacher.ipynb", version=4)

"""The paper's figures with matplotlib, for a :class:`whatnext.Run` or a :class:`whatnext.Sweep`.

``figure8(run)``: the sandbag's x(t) and h(t), its trajectory, the seesaw and lid angles, the
balloon with its limit under the lid, and the energy (the set of the paper's Fig. 8, as
``whatnext plot`` draws it, docs/pictures.md). ``figure9(machine)``: the angles under the four
impact laws (the paper's Fig. 9). ``heatmap(sweep, value)``: a value over two varied keys.

matplotlib is imported only when one of these is called; ``import whatnext`` does not need it.
Every function returns the matplotlib Figure (in a notebook, end the line with ``;`` or assign
it to show it once).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from . import Machine, Run, Sweep

# Pastel bands for the modes M1..M5 (the colours of `whatnext plot`) and the curve colours.
_MODE_COLOURS = {"M1": "#ffecb3", "M2": "#ffcdd2", "M3": "#c8e6c9", "M4": "#bbdefb", "M5": "#e1c8f0"}
_LAWS = ("rope", "angular-momentum-sum", "kinetic-energy", "linear-momentum")


def _pyplot() -> Any:
    import matplotlib.pyplot as plt  # lazily: plotting is optional
    return plt


def _event_groups(run: "Run") -> List[Tuple[float, str]]:
    """Events at the same instant share a line: (time, "rope_taut + rope_slack + ...")."""
    groups: List[Tuple[float, List[str]]] = []
    for e in run.events:
        if groups and groups[-1][0] == e.time:
            groups[-1][1].append(e.type)
        else:
            groups.append((e.time, [e.type]))
    return [(t, " + ".join(names)) for t, names in groups]


def _mode_spans(run: "Run") -> List[Tuple[float, float, str]]:
    t, mode = run.samples["t_s"], run.samples["mode"]
    change = np.flatnonzero(mode[1:] != mode[:-1]) + 1
    starts = np.concatenate(([0], change))
    ends = np.concatenate((change, [len(t) - 1]))
    spans: List[Tuple[float, float, str]] = []
    for a, b in zip(starts, ends):
        if t[b] <= t[a]:
            continue  # a mode held for no time (M4 for the instant of an impact) gets no band
        if spans and spans[-1][2] == mode[a]:
            spans[-1] = (spans[-1][0], float(t[b]), spans[-1][2])
        else:
            spans.append((float(t[a]), float(t[b]), str(mode[a])))
    return spans


def _time_axes(ax: "Axes", run: "Run", ylabel: str, labels: bool = False) -> None:
    """Mode bands named at their foot, a dashed line at every event (labelled if asked), the time axis."""
    t_end = run.outcome.time * 1.04 if run.outcome.time > 0 else 1.0
    for t0, t1, mode in _mode_spans(run):
        ax.axvspan(t0, t1, color=_MODE_COLOURS.get(mode, "#eeeeee"), alpha=0.45, lw=0)
        if (t1 - t0) / t_end > 0.04:  # only where the name fits
            ax.annotate(mode, (t0, 0.0), xycoords=("data", "axes fraction"), xytext=(2, 2),
                        textcoords="offset points", fontsize=7, color="0.35")
    for t, names in _event_groups(run):
        ax.axvline(t, color="0.45", ls="--", lw=0.8)
        if labels:
            ax.annotate(f"{t:.3f} s {names}", (t, 1.0), xycoords=("data", "axes fraction"),
                        xytext=(3, -4), textcoords="offset points", rotation=90, va="top",
                        ha="left", fontsize=7)
    ax.set_xlim(0.0, t_end)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel(ylabel)


def _samples(run: "Run") -> Dict[str, np.ndarray]:
    if run.samples is None:
        raise ValueError("this run kept no samples: simulate(..., samples=True)")
    return run.samples


def figure8(run: "Run", *, title: Optional[str] = None, figsize: Tuple[float, float] = (15, 8.5)) -> "Figure":
    """The paper's figure set (Fig. 8) for one run, on one page of six panels.

    x(t) and h(t) of the sandbag, its trajectory h over x (to scale, with the seesaw at t = 0
    and a dot at every event), the seesaw angle phiS and the lid angle phiL, the balloon's height
    with the limit the lid sets, and the machine's energy (impacts as steps). Time plots show a
    dashed line at every event and the modes M1-M5 as coloured bands.
    """
    plt = _pyplot()
    s = _samples(run)
    t = s["t_s"]
    fig, axes = plt.subplots(2, 3, figsize=figsize, layout="constrained")
    fig.suptitle(title if title is not None else f"{run.machine.source}: {run.outcome.sentence}")
    ax_x, ax_h, ax_tr, ax_ang, ax_bal, ax_en = axes.ravel()

    _time_axes(ax_x, run, "x [m] (from the pivot)")
    ax_x.plot(t, s["x_m"], color="C0")
    ax_x.set_title("sandbag, horizontal position")

    _time_axes(ax_h, run, "h [m] (above the pivot)")
    ax_h.plot(t, s["h_m"], color="C0")
    ax_h.set_title("sandbag, height")

    ax_tr.plot(s["x_m"], s["h_m"], color="C0", label="sandbag")
    phi0 = np.radians(s["phi_s_deg"][0])
    right = run.machine._handle.seesaw_right_arm
    left = max(right, 1.2 * abs(s["x_m"][0]) / max(0.2, np.cos(phi0)))
    ax_tr.plot([-left * np.cos(phi0), right * np.cos(phi0)], [-left * np.sin(phi0), right * np.sin(phi0)],
               color="#8c564b", ls="--", lw=1.5, label="seesaw at t = 0")
    ex = [e.state["x_m"] for e in run.events]
    eh = [e.state["h_m"] for e in run.events]
    ax_tr.plot(ex, eh, "o", color="C3", ms=4, label="events")
    ax_tr.set_aspect("equal", adjustable="datalim")
    ax_tr.set_xlabel("x [m]")
    ax_tr.set_ylabel("h [m]")
    ax_tr.set_title("sandbag, trajectory")
    ax_tr.legend(loc="best", fontsize=8)

    _time_axes(ax_ang, run, "angle [deg]", labels=True)
    ax_ang.plot(t, s["phi_s_deg"], color="C0", label="φS seesaw (+ = left arm down)")
    ax_ang.plot(t, s["phi_l_deg"], color="C1", label="φL lid")
    ax_ang.axhline(90.0, color="0.3", ls=":", lw=1)
    ax_ang.set_title("seesaw and lid angles")
    ax_ang.legend(loc="best", fontsize=8)

    _time_axes(ax_bal, run, "balloon's centre [m] (from the hinge level)")
    ax_bal.plot(t, s["balloon_h_m"], color="C0", label="balloon h_B")
    ax_bal.plot(t, s["balloon_limit_m"], color="C1", ls="--", label="limit under the lid h_lim")
    ax_bal.set_title("balloon")
    ax_bal.legend(loc="best", fontsize=8)

    _time_axes(ax_en, run, "energy [J]")
    ax_en.plot(t, s["energy_J"], color="k", lw=2, label="total")
    ax_en.plot(t, s["sandbag_kinetic_J"] + s["sandbag_potential_J"], color="C2", lw=1.2, label="sandbag")
    ax_en.plot(t, s["lid_kinetic_J"] + s["lid_potential_J"], color="C4", lw=1.2, label="lid")
    for e in run.events:
        if e.impact:
            ax_en.plot([e.time, e.time], [e.energy_before, e.energy_after], color="k", lw=2)
    ax_en.set_title("mechanical energy")
    ax_en.legend(loc="best", fontsize=8)
    return fig


def figure9(machine: "Machine", *, laws: Sequence[str] = _LAWS, figsize: Tuple[float, float] = (11, 8)) -> "Figure":
    """The paper's Fig. 9: the seesaw angle (top) and the lid angle (bottom) of one machine under
    each impact law (``run.impact_law``), with a dot at every event and each law's outcome."""
    from . import simulate  # here, not at import: whatnext imports this module
    plt = _pyplot()
    fig, (ax_s, ax_l) = plt.subplots(2, 1, figsize=figsize, sharex=True, layout="constrained")
    styles = ["-", "--", "-.", ":"]
    t_end = 0.0
    for i, law in enumerate(laws):
        run = simulate(machine.set("run.impact_law", law))
        s = _samples(run)
        label = f"{law}: {run.outcome.type} {run.outcome.time:.3f} s"
        for ax, col in ((ax_s, "phi_s_deg"), (ax_l, "phi_l_deg")):
            ax.plot(s["t_s"], s[col], color=f"C{i}", ls=styles[i % 4], label=label)
            ax.plot([e.time for e in run.events], [e.state[col] for e in run.events], "o", color=f"C{i}", ms=3)
        t_end = max(t_end, run.outcome.time)
    for ax, name in ((ax_s, "φS seesaw"), (ax_l, "φL lid")):
        ax.axhline(90.0, color="0.3", ls=":", lw=1)
        ax.set_ylabel(f"{name} [deg]")
        ax.set_xlim(0.0, t_end * 1.04)
        ax.legend(fontsize=8, loc="lower right" if ax is ax_s else "upper left")
    ax_s.set_title(f"{machine.source}: the four impact laws")
    ax_l.set_xlabel("time t [s]")
    return fig


def heatmap(sweep: "Sweep", value: str = "lid_open", *, ax: Optional["Axes"] = None,
            cmap: str = "viridis") -> "Figure":
    """``value`` (an event's first time such as ``"lid_open"``, or ``"outcome_t"``, ``"final_r"``,
    ``"final_phi_l_deg"``) over the two varied keys of a grid sweep. Machines where it never
    happens are light grey, invalid machines black."""
    plt = _pyplot()
    if sweep.axes is None or len(sweep.axes) != 2:
        raise ValueError("heatmap(): needs a grid sweep over exactly two keys")
    (kx, xs), (ky, ys) = list(sweep.axes.items())
    z = sweep.grid(value)  # z[i, j]: i-th value of the first key (x), j-th of the second (y)
    valid = sweep.valid.reshape(sweep.shape)
    if ax is None:
        fig, ax = plt.subplots(figsize=(8, 6), layout="constrained")
    else:
        fig = ax.figure
    ax.set_facecolor("0.85")
    mesh = ax.pcolormesh(xs, ys, np.ma.masked_invalid(z).T, shading="nearest", cmap=cmap)
    if not valid.all():
        ax.pcolormesh(xs, ys, np.ma.masked_where(valid, np.zeros_like(z)).T, shading="nearest",
                      cmap="gray", vmin=0, vmax=1)
    from . import input_keys
    units = {k: unit for k, (unit, _) in input_keys().items()}
    value_unit = {"final_r": "m", "final_phi_l_deg": "deg"}.get(value, "s")
    fig.colorbar(mesh, ax=ax, label=f"{value} [{value_unit}]")
    ax.set_xlabel(f"{kx} [{units[kx]}]" if units.get(kx) else kx)
    ax.set_ylabel(f"{ky} [{units[ky]}]" if units.get(ky) else ky)
    ax.set_title(f"{value}: grey where it never happens" + (", black: invalid" if not valid.all() else ""))
    return fig

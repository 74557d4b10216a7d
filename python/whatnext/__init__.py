"""Kermit's What-Happens-Next machine, simulated event by event.

A sandbag drops onto a massless seesaw, the seesaw pulls a rope, the rope lifts the lid of a box,
a helium balloon rises and may switch on a radio. This package is the C++ library of the
``whatnext`` command, for Python and Jupyter::

    import whatnext
    m = whatnext.example(2)                          # the paper's example 2 (also load(), machine())
    m = m.set("geometry.rope_length", 0.65)          # a new machine; m itself never changes
    run = whatnext.simulate(m)
    run.outcome                                      # Outcome(type='lid_open', time=..., sentence=...)
    run.samples["phi_l_deg"]                         # numpy arrays named like the CSV's columns
    run.plot()                                       # the paper's Fig. 8 (matplotlib)
    s = whatnext.sweep(m, {"geometry.rope_length": np.linspace(0.62, 0.9, 29)})

Input keys are those of docs/inputs.md (``whatnext.input_keys()`` lists them): angles in degrees,
everything else SI. Bad input raises :class:`InputError` with the command's one-line message.
"""

import dataclasses
import os
from typing import Any, Dict, Iterator, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import InputError, SimulationError

__all__ = [
    "InputError", "SimulationError", "Machine", "example", "load", "machine", "input_keys",
    "simulate", "Run", "Event", "Outcome", "sweep", "grid", "Sweep", "plot",
]

InputError.__module__ = SimulationError.__module__ = "whatnext"  # as users import them
InputError.__doc__ = """Bad input: the message is the command line's one line, naming the input
(file and line, or the set() as a --set), the rule and the value given. A ValueError."""
SimulationError.__doc__ = """A run that cannot go on (its state turned non-finite, or the
integrator ran out of steps); the message names the time and the mode. A RuntimeError."""

Value = Union[float, int, bool, str, Sequence[float]]


def _toml_value(key: str, value: Any) -> str:
    """value as the text of a --set KEY=VALUE, so that the library checks (and words) it as the CLI."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, str):
        return value  # a bare word, as typed after --set KEY=
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))  # the shortest text that reads back as the same double
    if isinstance(value, (Sequence, np.ndarray)):
        return "[" + ", ".join(_toml_value(key, v) for v in value) + "]"
    raise TypeError(f"{key}: a number, text, true/false or a pair [dx, dh] is expected, not "
                    f"{type(value).__name__}")


def _assignments(values: Mapping[str, Value]) -> List[str]:
    return [f"{k}={_toml_value(k, v)}" for k, v in values.items()]


class Machine:
    """One machine and its run settings, validated and immutable.

    Make one with :func:`example`, :func:`load` or :func:`machine`; change it with :meth:`set`,
    which returns a new machine. ``m.inputs`` holds the keys the input gives (units of
    docs/inputs.md), ``m.source`` says where it came from, ``m.to_toml()`` writes it as a TOML
    file that ``whatnext run`` and :func:`load` accept.
    """

    __slots__ = ("_handle",)

    def __init__(self, handle: "_core.MachineHandle") -> None:
        self._handle = handle

    def set(self, key: Union[str, Mapping[str, Value]], value: Optional[Value] = None) -> "Machine":
        """A copy of this machine with input keys changed: the Python form of ``--set KEY=VALUE``.

        ``m.set("geometry.rope_length", 0.7)`` or, for several keys at once,
        ``m.set({"geometry.rope_length": 0.7, "run.impact_law": "kinetic-energy"})``.
        Keys and units are docs/inputs.md's (angles in degrees). Values: numbers, text
        (``"kinetic-energy"``), ``True``/``False`` for switches such as ``"radio.enabled"``, and
        pairs ``(dx, dh)`` for ``"geometry.hinge_offset"`` and ``"radio.switch_offset"``.
        The new machine is validated at once: a bad value raises :class:`InputError` with the
        command line's message for the same ``--set``.
        """
        if isinstance(key, Mapping):
            if value is not None:
                raise TypeError("set(mapping) takes no second argument")
            values = key
        else:
            if value is None:
                raise TypeError(f"set({key!r}, value): the value is missing")
            values = {key: value}
        return Machine(self._handle.set(_assignments(values)))

    @property
    def source(self) -> str:
        """Where the machine came from, named as the command line names a run: ``"example 1"``, a
        file name or ``"whatnext.machine()"``, and the changes made with :meth:`set` as the
        ``--set`` options that make them (``"example 2 with --set geometry.rope_length=0.7"``).
        The timeline and the events JSON begin with it."""
        return self._handle.source

    @property
    def inputs(self) -> Dict[str, Value]:
        """The keys the input gives and their values, in docs/inputs.md's units."""
        return self._handle.inputs()

    def to_toml(self) -> str:
        """The machine as a complete TOML input (every key, full precision)."""
        return self._handle.to_toml()

    def __repr__(self) -> str:
        return f"<whatnext.Machine {self.source}>"


def example(n: int) -> Machine:
    """The paper's example ``n`` (1-4), as in examples/exampleN.toml and ``whatnext run --example N``.

    1: the rope tightens with one hard pull and the lid flies open at 0.82 s.
    2: the rope stays taut while it pulls the lid open (the paper's Fig. 9).
    3: the seesaw turns vertical after 20 s; the lid never opens.
    4: a hard hit, the rope slack at once, taut again, the seesaw vertical after 10 s.
    """
    return Machine(_core.example(int(n)))


def load(path: Union[str, "os.PathLike[str]"]) -> Machine:
    """A machine from a TOML file or the paper's 15-line ``whatnext.inp`` (docs/inputs.md).

    Raises :class:`InputError` (file and line, the rule, the value) for anything wrong in it.
    """
    return Machine(_core.load(os.fspath(path)))


def machine(keys: Optional[Mapping[str, Value]] = None, /, **sections: Mapping[str, Value]) -> Machine:
    """A machine from input keys; every key not given takes its default (the paper's example 1).

    Either dotted keys, as in docs/inputs.md::

        whatnext.machine({"geometry.rope_length": 0.62, "start.sandbag_height": 0.5})

    or TOML's sections as keyword arguments::

        whatnext.machine(geometry={"rope_length": 0.62}, start={"sandbag_height": 0.5})

    Values are checked as :meth:`Machine.set` checks them.
    """
    values: Dict[str, Value] = dict(keys or {})
    for section, table in sections.items():
        if not isinstance(table, Mapping):
            raise TypeError(f"machine({section}=...): a dict of that section's keys is expected, e.g. "
                            f"{section}={{'key': value}}")
        for name, v in table.items():
            values[f"{section}.{name}"] = v
    base = Machine(_core.defaults("whatnext.machine()"))
    return base.set(values) if values else base


def input_keys() -> Dict[str, Tuple[str, str]]:
    """Every input key: ``{key: (unit, meaning)}``, in docs/inputs.md's order (angles in degrees)."""
    return {key: (unit, help_) for key, unit, help_ in _core.known_keys()}


class Outcome(NamedTuple):
    """How the run ended: its last event's ``type`` and ``time`` [s], and the outcome in words."""

    type: str
    time: float
    sentence: str


@dataclasses.dataclass(frozen=True)
class Event:
    """One event of a run (docs/model.md's names: sandbag_lands, rope_taut, lid_open, ...).

    ``time`` is located to the integrator's tolerance (not to a time step); ``state`` is the
    machine right after the event, keyed like the CSV's columns (``x_m``, ``phi_s_deg``,
    ``energy_J``, ...). An impact (``impact``) changes the machine's energy from
    ``energy_before`` to ``energy_after`` [J]; otherwise the two are equal.
    """

    type: str
    time: float
    mode_before: str
    mode_after: str
    impact: bool
    energy_before: float
    energy_after: float
    state: Dict[str, Any]


class Run:
    """One simulated run: :attr:`outcome`, :attr:`events` and :attr:`samples`.

    ``samples`` is a dict of numpy arrays named like the CSV's columns of ``whatnext run --csv``
    (docs/inputs.md): a row every ``run.output_step`` seconds and a row right after each event
    (its ``event`` column names it, empty for plain samples). ``t_s`` is the time, ``mode`` the
    mode M1-M5, ``rope_taut`` a bool, the rest float64 (angles in degrees, everything else SI).
    """

    def __init__(self, machine: Machine, raw: Dict[str, Any]) -> None:
        self.machine: Machine = machine
        self.outcome: Outcome = Outcome(*raw["outcome"])
        self.events: List[Event] = [Event(**e) for e in raw["events"]]
        self.samples: Optional[Dict[str, np.ndarray]] = raw["samples"]
        self._timeline: str = raw["timeline"]
        self._events_json: str = raw["events_json"]

    def event(self, type: str) -> Optional[Event]:
        """The first event of this type (``"lid_open"``, ``"rope_taut"``, ...), or None."""
        return next((e for e in self.events if e.type == type), None)

    def timeline(self) -> str:
        """The timeline that ``whatnext run`` prints: events, modes, angles, impacts, outcome."""
        return self._timeline

    def events_json(self) -> str:
        """The events as JSON, the same text as ``whatnext run --events FILE`` writes."""
        return self._events_json

    def to_toml(self) -> str:
        """The machine of this run as a complete TOML input (``whatnext run`` re-runs it)."""
        return self.machine.to_toml()

    def plot(self, **kwargs: Any) -> Any:
        """The paper's Fig. 8 for this run (see :func:`whatnext.plot.figure8`); returns the figure."""
        from . import plot as _plot
        return _plot.figure8(self, **kwargs)

    def __repr__(self) -> str:
        n = 0 if self.samples is None else len(self.samples["t_s"])
        return (f"<whatnext.Run {self.machine.source}: {self.outcome.sentence}; "
                f"{len(self.events)} events, {n} rows>")


def simulate(machine: Machine, *, output_step: Optional[float] = None, t_max: Optional[float] = None,
             samples: bool = True) -> Run:
    """Run one machine; the Python form of ``whatnext run``.

    Arguments:
        machine: from :func:`example`, :func:`load`, :func:`machine` or :meth:`Machine.set`.
        output_step: seconds between rows of ``run.samples`` (``run.output_step``, default the
            machine's, 0.001 s in the examples). Events are exact whatever the step.
        t_max: end of the simulated time [s] (``run.t_max``); the run stops with ``timeout``.
        samples: False to keep only the events (faster for long runs).

    Returns a :class:`Run`:
        ``run.outcome``: ``(type, time, sentence)``, e.g. ``('lid_open', 0.8203..., 'lid open at 0.820 s')``;
        ``run.events``: list of :class:`Event` (type, time, mode_before, mode_after, impact,
        energy_before, energy_after, state);
        ``run.samples``: dict of numpy arrays, the CSV's columns (``t_s``, ``x_m``, ``h_m``,
        ``phi_s_deg``, ``phi_l_deg``, ``balloon_h_m``, ``balloon_limit_m``, ``energy_J``, ...);
        ``run.timeline()``, ``run.events_json()``, ``run.to_toml()``, ``run.plot()``.

    Event times and states are exactly those of the command line for the same input. Raises
    :class:`InputError` for a bad ``output_step``/``t_max`` and :class:`SimulationError` if the run
    cannot go on. The GIL is released while the machine runs.

    Example::

        run = whatnext.simulate(whatnext.example(1))
        print(run.timeline())
        t, phi = run.samples["t_s"], run.samples["phi_l_deg"]
    """
    if not isinstance(machine, Machine):
        raise TypeError("simulate(machine): make one with whatnext.example(), load() or machine()")
    overrides: Dict[str, Value] = {}
    if output_step is not None:
        overrides["run.output_step"] = output_step
    if t_max is not None:
        overrides["run.t_max"] = t_max
    m = machine.set(overrides) if overrides else machine
    return Run(m, _core.simulate(m._handle, bool(samples)))


class Sweep(Mapping[str, np.ndarray]):
    """The outcome of every machine of a sweep, as columns (a read-only dict of numpy arrays).

    The columns are those of ``whatnext sweep --out``'s CSV: ``index``; the varied keys;
    ``outcome`` (an event name, or ``"invalid"``); ``outcome_t``, ``final_r`` [m] and
    ``final_phi_l_deg``; one column per event type with the time of its first occurrence [s]
    (NaN if it never happened); and ``error``, the one-line reason of an invalid machine (empty
    otherwise). Invalid machines have NaN in every number column.

    For a grid, ``shape`` is the number of values per key and :meth:`grid` reshapes a column to
    it (axis k is the k-th key, whose values are ``axes[key]``).
    """

    def __init__(self, keys: List[str], columns: Dict[str, np.ndarray],
                 axes: Optional[Dict[str, np.ndarray]]) -> None:
        self.keys_varied: List[str] = keys
        self.columns: Dict[str, np.ndarray] = columns
        self.axes: Optional[Dict[str, np.ndarray]] = axes
        self.shape: Tuple[int, ...] = (tuple(len(a) for a in axes.values()) if axes is not None
                                       else (len(columns["index"]),))

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self.columns)

    def __len__(self) -> int:
        return len(self.columns)

    @property
    def valid(self) -> np.ndarray:
        """True where the machine's inputs passed validation (False: see the ``error`` column)."""
        return self.columns["outcome"] != "invalid"

    def grid(self, name: str) -> np.ndarray:
        """Column ``name`` (e.g. ``"lid_open"``) shaped as the grid: ``grid(name)[i, j]`` belongs to
        the i-th value of the first key and the j-th of the second."""
        if self.axes is None:
            raise ValueError("grid(): a Latin hypercube sweep has no grid; use the columns")
        return self.columns[name].reshape(self.shape)

    def plot(self, value: str = "lid_open", **kwargs: Any) -> Any:
        """A heat map of ``value`` over the two varied keys (see :func:`whatnext.plot.heatmap`)."""
        from . import plot as _plot
        return _plot.heatmap(self, value, **kwargs)

    def __repr__(self) -> str:
        return f"<whatnext.Sweep {' x '.join(map(str, self.shape))} machines over {', '.join(self.keys_varied)}>"


def grid(a: float, b: float, n: int) -> np.ndarray:
    """n values from a to b (both included), exactly those of the command line's ``--vary KEY=a:b:n``.

    Like ``np.linspace(a, b, n)``, which may differ in the last bit; use this one to compare a
    sweep with the CSV of ``whatnext sweep``.
    """
    return _core.grid_values(float(a), float(b), int(n))


def sweep(machine: Machine, values: Mapping[str, Any], *, samples: Optional[int] = None, seed: int = 1,
          threads: Optional[int] = None, accuracy: Optional[float] = _core.DEFAULT_ACCURACY) -> Sweep:
    """Run many variants of a machine on all cores; the Python form of ``whatnext sweep``.

    ``values`` maps input keys (any numeric key of docs/inputs.md, angles in degrees) to the
    values they take: a sequence or numpy array each, e.g. ``np.linspace(0.62, 0.9, 29)``
    (``whatnext.grid(0.62, 0.9, 29)`` gives the command line's ``--vary KEY=0.62:0.9:29``
    values to the last bit). The sweep runs every combination (a grid; the last key varies
    fastest, so ``result.grid("lid_open")`` has one axis per key in the order given). With
    ``samples=N`` each entry is a pair ``(a, b)`` instead and N machines are drawn from a Latin
    hypercube (``--samples N --seed S``; the same seed gives the same machines).

    Each machine is ``machine`` with those values set; a machine whose inputs break a rule is
    not an error: its ``outcome`` is ``"invalid"`` and ``error`` says why. The machines run in
    C++ on ``threads`` threads (default: all cores) with the GIL released; the results do not
    depend on the thread count. Ctrl-C stops the sweep (KeyboardInterrupt).

    ``accuracy`` is the event-time accuracy in seconds (default 1e-8, as ``--accuracy`` of
    ``whatnext sweep``): every event time is then within it of the exact time, and the machines run
    with the loosest integrator tolerance that guarantees it (unless the machine sets
    ``run.tolerance`` itself). ``accuracy=None`` runs each machine with its own run settings,
    exactly as :func:`simulate` would.

    Returns a :class:`Sweep`: columns named like the sweep CSV (``outcome``, ``outcome_t``,
    ``lid_open``, ``rope_taut``, ..., ``error``), each a numpy array with a row per machine.

    Example::

        s = whatnext.sweep(whatnext.example(2), {"geometry.rope_length": np.linspace(0.62, 0.9, 29),
                                                 "masses.sandbag": np.linspace(0.2, 2.0, 37)})
        s.grid("lid_open")        # 29 x 37, NaN where the lid never opens
    """
    if not isinstance(machine, Machine):
        raise TypeError("sweep(machine, values): make the machine with whatnext.example(), load() or machine()")
    if not values:
        raise InputError("sweep: give at least one key to vary")
    n_threads = 0 if threads is None else int(threads)
    accuracy_s = None if accuracy is None else float(accuracy)
    if threads is not None and n_threads < 1:
        raise ValueError(f"sweep: threads must be >= 1 (given {threads})")
    keys = list(values)
    if samples is not None:
        specs = []
        for k, v in values.items():
            if not (isinstance(v, Sequence) and len(v) == 2):
                raise TypeError(f"sweep(samples=...): {k} needs a pair (a, b), not {v!r}")
            specs.append(f"{k}={_toml_value(k, v[0])}:{_toml_value(k, v[1])}")
        return Sweep(keys, _core.sweep_lhs(machine._handle, specs, int(samples), int(seed), n_threads, accuracy_s), None)
    axes = {k: np.ascontiguousarray(np.atleast_1d(np.asarray(v, dtype=np.float64))) for k, v in values.items()}
    columns = _core.sweep_grid(machine._handle, keys, list(axes.values()), n_threads, accuracy_s)
    return Sweep(keys, columns, axes)


from . import plot  # noqa: E402  (matplotlib itself is imported only when a figure is drawn)

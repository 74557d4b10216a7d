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

import builtins
import copyreg
import dataclasses
import difflib
import numbers
import os
import pathlib
import sys
import tempfile
from typing import (Any, Callable, Dict, Iterator, List, Mapping, NamedTuple, Optional, Sequence, Tuple,
                    Union)

import numpy as np

from . import _core
from ._core import InputError, SimulationError

__all__ = [
    "InputError", "SimulationError", "Machine", "example", "examples", "example_path", "load", "machine",
    "input_keys", "simulate", "Run", "Event", "Outcome", "sweep", "grid", "Sweep", "plot",
]

InputError.__module__ = SimulationError.__module__ = "whatnext"  # as users import them
InputError.__doc__ = """Bad input: one line naming the input (the Python call and its key, or a
file and its line), the rule and the value given. A ValueError."""
SimulationError.__doc__ = """A run that cannot go on (its state turned non-finite, or the
integrator ran out of steps); the message names the time and the mode. A RuntimeError."""

Value = Union[float, int, bool, str, Sequence[float]]
Plain = Union[bool, int, float, str, Tuple[Any, ...]]

# The machine files of examples/ ship inside the package (python/CMakeLists.txt copies them).
_MACHINES = pathlib.Path(__file__).resolve().with_name("machines")
_ALIASES = {"radio": "example1-radio"}


def _whole(what: str, value: Any, lo: int, hi: int) -> int:
    """value as a whole number in [lo, hi]; a TypeError or InputError naming ``what`` otherwise."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{what} must be a whole number, not {type(value).__name__} {value!r}")
    v = int(value)
    if not lo <= v <= hi:
        raise InputError(f"{what} must be from {lo} to {hi} (given {v})")
    return v


def _real(what: str, value: Any) -> float:
    """value as a float; a TypeError naming ``what`` for anything that is not a real number."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if isinstance(value, (bool, np.bool_, str)) or not isinstance(value, numbers.Real):
        kind = "a complex number" if isinstance(value, numbers.Complex) else type(value).__name__
        raise TypeError(f"{what} must be a real number, not {kind} {value!r}")
    return float(value)


def _plain(key: str, value: Any) -> Plain:
    """A value given for ``key`` as plain Python (bool, int, float, text, or a tuple of numbers for
    a pair); a TypeError in Python's words naming the key for any other kind of value."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()  # np.array(0.7): a number
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, str):
        if any(ord(c) < 0x20 and c != "\t" or ord(c) == 0x7F for c in value):
            raise InputError(f"{key}: the text must be one line without control characters (given {value!r})")
        return str(value)
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        return float(value)
    if isinstance(value, numbers.Complex):
        raise TypeError(f"{key}: a real number is expected, not the complex number {value!r}")
    if isinstance(value, (Sequence, np.ndarray)) and not isinstance(value, (bytes, bytearray)):
        return tuple(_real(f"{key}: each entry of a pair [dx, dh]", v) for v in value)
    raise TypeError(f"{key}: a number, text, True/False or a pair (dx, dh) is expected, not "
                    f"{type(value).__name__} {value!r}")


def _toml_text(value: Plain) -> str:
    """A plain value as the text of a --set KEY=VALUE, so that the library checks it as the CLI does."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return value  # a bare word, as typed after --set KEY=
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)  # the shortest text that reads back as the same double
    return "[" + ", ".join(_toml_text(v) for v in value) + "]"


def _check_key(call: str, key: Any) -> str:
    if not isinstance(key, str):
        raise TypeError(f"{call}: a key is text such as 'geometry.rope_length', not {type(key).__name__} {key!r}")
    return key


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
        Keys and units are docs/inputs.md's (angles in degrees). Values: numbers (numpy scalars
        and 0-d arrays too), text (``"kinetic-energy"``), ``True``/``False`` for switches such as
        ``"radio.enabled"``, and pairs ``(dx, dh)`` for ``"geometry.hinge_offset"`` and
        ``"radio.switch_offset"``. The new machine is validated at once: a bad value raises
        :class:`InputError` (a wrong kind of value :class:`TypeError`) naming the call and the key,
        e.g. ``set('masses.lid', -0.5): masses.lid must be > 0 kg (given -0.5)``.
        """
        if isinstance(key, Mapping):
            if value is not None:
                raise TypeError("set(mapping) takes no second argument")
            return self._set(key, "set(mapping)", lambda k, v: f"set({k!r}, {v!r})")
        _check_key("set(key, value)", key)
        if value is None:
            raise TypeError(f"set({key!r}, value): the value is missing")
        return self._set({key: value}, "set(key, value)", lambda k, v: f"set({k!r}, {v!r})")

    def _set(self, values: Mapping[str, Value], call: str, label: Callable[[str, Plain], str]) -> "Machine":
        """set() with the message prefix of each value: the call that gave it, in Python's words."""
        assignments, labels = [], []
        for k, v in values.items():
            _check_key(call, k)
            plain = _plain(k, v)
            assignments.append(f"{k}={_toml_text(plain)}")
            labels.append(label(k, plain))
        return Machine(self._handle.set(assignments, labels))

    def __reduce__(self) -> Tuple[Any, ...]:
        # pickle and copy: the input's every value and where it came from (bindings.cpp), so the
        # copy is the same machine to the last bit and to_toml() gives the same text. As plain
        # values, so that every pickle protocol (0-5) works: see _handle_from_state.
        return (_machine_from_state, (self._handle.__getstate__(),))

    def __copy__(self) -> "Machine":
        return self  # immutable

    def __deepcopy__(self, memo: Dict[int, Any]) -> "Machine":
        return self

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


def _handle_from_state(state: Tuple[Any, ...]) -> "_core.MachineHandle":
    # The compiled machine rebuilt from its plain values. Pickle protocols 0 and 1 would make the
    # object with object.__new__, which a compiled class cannot survive (the interpreter aborts),
    # so every protocol goes through here: the class's own __new__, then its __setstate__.
    handle = _core.MachineHandle.__new__(_core.MachineHandle)
    handle.__setstate__(state)
    return handle


def _machine_from_state(state: Tuple[Any, ...]) -> "Machine":
    return Machine(_handle_from_state(state))


copyreg.pickle(_core.MachineHandle, lambda handle: (_handle_from_state, (handle.__getstate__(),)))


def example(n: Union[int, str]) -> Machine:
    """The paper's example ``n`` (1-4), as in examples/exampleN.toml and ``whatnext run --example N``,
    or a machine file of examples/ by name, shipped with the package: ``example("radio")``
    (example 1 with Kermit's radio, examples/example1-radio.toml); :func:`examples` lists the names.

    1: the rope tightens with one hard pull and the lid flies open at 0.82 s.
    2: the rope stays taut while it pulls the lid open (the paper's Fig. 9).
    3: the seesaw turns vertical after 20 s; the lid never opens.
    4: a hard hit, the rope slack at once, taut again, the seesaw vertical after 10 s.
    """
    if isinstance(n, str):
        path = example_path(n)
        return Machine(_core.parse(path.read_text(encoding="utf-8"), path.name))
    if isinstance(n, np.ndarray) and n.ndim == 0:
        n = n.item()
    if isinstance(n, (bool, np.bool_)) or not isinstance(n, numbers.Integral):
        raise TypeError(f"example(n): n is a whole number 1-4 or a name ({', '.join(map(repr, examples()))}), "
                        f"not {type(n).__name__} {n!r}")
    if not 1 <= int(n) <= 4:
        raise InputError(f"example({int(n)}): the paper has examples 1 to 4; the other shipped machines are "
                         f"named: {', '.join(map(repr, examples()))}")
    return Machine(_core.example(int(n)))


def examples() -> List[str]:
    """The names :func:`example` takes besides 1-4: every machine file of examples/ (shipped in the
    package), without ``.toml``, and ``"radio"`` for ``"example1-radio"``."""
    names = sorted(p.stem for p in _MACHINES.glob("*.toml")) if _MACHINES.is_dir() else []
    return [alias for alias, name in _ALIASES.items() if name in names] + names


def example_path(name: Union[int, str]) -> pathlib.Path:
    """Where the package keeps a shipped machine file (``"radio"``, ``"example2"``, or 1-4), to read
    or copy it: ``shutil.copy(whatnext.example_path("radio"), "my-machine.toml")``."""
    if not isinstance(name, str):
        name = f"example{_whole('example_path(name)', name, 1, 4)}"
    stem = _ALIASES.get(name, name[:-5] if name.endswith(".toml") else name)
    names = examples()
    if stem not in names or "/" in stem or os.sep in stem:
        near = difflib.get_close_matches(name, names, n=1)
        hint = f" (did you mean {near[0]!r}?)" if near else ""
        raise InputError(f"example({name!r}): no shipped machine of that name{hint}; the names are: "
                         f"{', '.join(map(repr, names))}")
    return _MACHINES / f"{stem}.toml"


def load(path: Union[str, "os.PathLike[str]"]) -> Machine:
    """A machine from a TOML file or the paper's 15-line ``whatnext.inp`` (docs/inputs.md).

    Raises :class:`InputError` (file and line, the rule, the value) for anything wrong in it.
    The machines of examples/ are also shipped with the package: see :func:`example`.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"load(path): a file name is expected, not {type(path).__name__} {path!r}")
    return Machine(_core.load(os.fspath(path)))


def machine(keys: Optional[Mapping[str, Value]] = None, /, **sections: Mapping[str, Value]) -> Machine:
    """A machine from input keys; every key not given takes its default (the paper's example 1).

    Either dotted keys, as in docs/inputs.md::

        whatnext.machine({"geometry.rope_length": 0.62, "start.sandbag_height": 0.5})

    or TOML's sections as keyword arguments::

        whatnext.machine(geometry={"rope_length": 0.62}, start={"sandbag_height": 0.5})

    Values are checked as :meth:`Machine.set` checks them.
    """
    if keys is not None and not isinstance(keys, Mapping):
        raise TypeError(f"machine(keys): a dict of input keys is expected, e.g. "
                        f"{{'geometry.rope_length': 0.62}}, not {type(keys).__name__}")
    values: Dict[str, Value] = dict(keys or {})
    for section, table in sections.items():
        if not isinstance(table, Mapping):
            raise TypeError(f"machine({section}=...): a dict of that section's keys is expected, e.g. "
                            f"{section}={{'key': value}}")
        for name, v in table.items():
            values[f"{section}.{name}"] = v
    base = Machine(_core.defaults("whatnext.machine()"))
    return base._set(values, "machine(keys)", lambda k, v: f"machine({{{k!r}: {v!r}}})") if values else base


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
    ``energy_before`` to ``energy_after`` [J]; otherwise the two are equal. An impact also has
    ``impulses`` (N s per contact, the lid's N m s: docs/model.md "Impulses") and ``law_applied``;
    a law that could not be applied is never replaced silently: ``law_note`` says why.
    """

    type: str
    time: float
    mode_before: str
    mode_after: str
    impact: bool
    energy_before: float
    energy_after: float
    state: Dict[str, Any]
    #: An impact's impulse per contact (``sandbag_N_s``, ``rope_N_s``, ``lid_N_m_s``), else None.
    impulses: Optional[Dict[str, float]] = None
    #: The impact law that set the velocities after a rope's jerk (impacts only).
    law_applied: Optional[str] = None
    #: Why that is not the run's impact law, where it is not ("" otherwise).
    law_note: Optional[str] = None


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
        self._freeze()

    def _freeze(self) -> None:
        # The samples are the run's record: read-only, so that no plot or analysis changes them
        # for the next reader by accident (np.array(run.samples[...]) gives a copy to change).
        for column in (self.samples or {}).values():
            column.flags.writeable = False

    def __setstate__(self, state: Dict[str, Any]) -> None:  # pickle and deepcopy: read-only again
        self.__dict__.update(state)
        self._freeze()

    def event(self, type: str) -> Optional[Event]:
        """The first event of this type (``"lid_open"``, ``"rope_taut"``, ...), or None if the run
        had none. A name that is no event at all raises :class:`InputError` (did you mean ...?)."""
        names = _core.event_names()
        if not isinstance(type, str) or type not in names:
            if not isinstance(type, str):
                raise TypeError(f"event(name): a name such as 'lid_open' is expected, not "
                                f"{builtins.type(type).__name__} {type!r}")
            near = difflib.get_close_matches(type, names, n=1)
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            raise InputError(f"event({type!r}): no event is called that{hint}; the events are: {', '.join(names)}")
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
    cannot go on. The GIL is released while the machine runs, and Ctrl-C stops it within a few
    hundredths of a second (KeyboardInterrupt).

    Example::

        run = whatnext.simulate(whatnext.example(1))
        print(run.timeline())
        t, phi = run.samples["t_s"], run.samples["phi_l_deg"]
    """
    if not isinstance(machine, Machine):
        raise TypeError("simulate(machine): make one with whatnext.example(), load() or machine()")
    if not isinstance(samples, (bool, np.bool_)):  # bool('no') is True: a word would be taken as yes
        raise TypeError(f"simulate(samples={samples!r}): True or False is expected, "
                        f"not {type(samples).__name__}")
    overrides: Dict[str, Value] = {}
    if output_step is not None:
        overrides["run.output_step"] = output_step
    if t_max is not None:
        overrides["run.t_max"] = t_max
    keyword = {"run.output_step": "output_step", "run.t_max": "t_max"}
    m = machine._set(overrides, "simulate()", lambda k, v: f"simulate({keyword.get(k, k)}={v!r})") if overrides else machine
    return Run(m, _core.simulate(m._handle, bool(samples)))


class Sweep(Mapping[str, np.ndarray]):
    """The outcome of every machine of a sweep, as columns (a read-only dict of read-only numpy arrays).

    The columns are those of ``whatnext sweep --out``'s CSV: ``index``; the varied keys;
    ``outcome`` (an event name, ``"invalid"`` for inputs that break a rule, ``"failed"`` for a run
    that could not go on); ``outcome_t``, ``final_r`` [m] and ``final_phi_l_deg``; one column per
    event type with the time of its first occurrence [s] (NaN if it never happened); and ``error``,
    the one-line reason of an invalid or failed machine (empty otherwise). Those have NaN in every
    number column. :meth:`to_csv` writes the command's CSV, byte for byte.

    For a grid, ``shape`` is the number of values per key and :meth:`grid` reshapes a column to
    it (axis k is the k-th key, whose values are ``axes[key]``).
    """

    def __init__(self, keys: List[str], columns: Dict[str, np.ndarray],
                 axes: Optional[Dict[str, np.ndarray]], study_info: Optional[Dict[str, Any]] = None) -> None:
        self.keys_varied: List[str] = keys
        self.columns: Dict[str, np.ndarray] = columns
        self.axes: Optional[Dict[str, np.ndarray]] = axes
        # What made the sweep (the machine's TOML, the accuracy, samples and seed): to_xarray()'s attributes.
        self.study_info: Optional[Dict[str, Any]] = study_info
        self.shape: Tuple[int, ...] = (tuple(len(a) for a in axes.values()) if axes is not None
                                       else (len(columns["index"]),))
        self._freeze()

    def _freeze(self) -> None:
        for column in [*self.columns.values(), *(self.axes or {}).values()]:
            column.flags.writeable = False

    def __setstate__(self, state: Dict[str, Any]) -> None:  # pickle and deepcopy: read-only again
        self.__dict__.update(state)
        self._freeze()

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self.columns)

    def __len__(self) -> int:
        return len(self.columns)

    @property
    def valid(self) -> np.ndarray:
        """True where the machine ran (False: its inputs broke a rule or its run failed; see ``error``)."""
        return (self.columns["outcome"] != "invalid") & (self.columns["outcome"] != "failed")

    def grid(self, name: str) -> np.ndarray:
        """Column ``name`` (e.g. ``"lid_open"``) shaped as the grid: ``grid(name)[i, j]`` belongs to
        the i-th value of the first key and the j-th of the second."""
        if self.axes is None:
            raise ValueError("grid(): a Latin hypercube sweep has no grid; use the columns")
        return self.columns[name].reshape(self.shape)

    def to_csv(self, path: Union[None, str, "os.PathLike[str]"] = None) -> Optional[str]:
        """The sweep as the CSV of ``whatnext sweep --out`` (the same bytes for the same sweep).

        With a path, the file is written through a temporary file in its folder and renamed over
        the old one only when complete, so an existing file is never left half-written. Without
        one, the text is returned."""
        data = _core.sweep_csv(self.keys_varied, self.columns)
        if path is None:
            return data.decode("utf-8")
        target = pathlib.Path(os.fspath(path))
        try:
            fd, part = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part", dir=target.parent)
        except OSError as e:  # named in the user's words, not the hidden temporary file's
            raise type(e)(e.errno, f"to_csv({os.fspath(path)!r}): cannot write into the folder "
                                   f"'{target.parent}' ({e.strerror})") from None
        try:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(part, 0o666 & ~umask)  # as open() would make it, not mkstemp's private 0600
            with os.fdopen(fd, "wb") as f:
                f.write(data)
                f.flush()
                os.fsync(f.fileno())
            os.replace(part, target)
        except BaseException:
            os.unlink(part)
            raise
        return None

    def to_xarray(self) -> Any:
        """The sweep as an ``xarray.Dataset``: for a grid one dimension per varied key (its values the
        coordinate), for a Latin hypercube a ``machine`` dimension with the drawn values as
        coordinates; every other column a variable with its unit (``attrs["units"]``); the machine's
        TOML, the accuracy and the program's version as attributes. ``to_zarr()``/``to_netcdf()``
        and back keep every value (see :mod:`whatnext.dataset`)."""
        from . import dataset as _dataset
        return _dataset.to_xarray(self)

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
    return _core.grid_values(_real("grid(a, b, n): a", a), _real("grid(a, b, n): b", b),
                             _whole("grid(a, b, n): n", n, 1, _core.MAX_MACHINES))


# Sweeps larger than this need force_large=True, as the command's --force-large: every row is
# kept in memory (a few hundred bytes each).
LARGE_SWEEP = 1_000_000
# A grid written into a Zarr store (sweep(store=...)) is never held in memory: its bound is the
# machine index's (whole numbers exact in a float64 coordinate).
MAX_STUDY = 2**53


@dataclasses.dataclass(frozen=True)
class _Plan:
    """A checked sweep: what every chunk of it needs to run (pickled to Dask's workers)."""

    machine: Machine
    keys: List[str]
    axes: Optional[Dict[str, np.ndarray]]  # a grid's values per key
    points: Optional[np.ndarray]           # or a Latin hypercube's machines, one row each
    size: int
    accuracy: Optional[float]
    first: int = 0  # points[0] is machine `first`: a chunk of a Latin hypercube carries its rows only
    samples: Optional[int] = None  # a Latin hypercube's size and seed, for the result's description
    seed: Optional[int] = None

    def info(self) -> Dict[str, Any]:
        """What made the sweep, for :meth:`Sweep.to_xarray`'s attributes."""
        return {"machine": self.machine.to_toml(), "accuracy": self.accuracy, "samples": self.samples,
                "seed": self.seed}

    def run(self, start: int, stop: int, threads: int) -> Dict[str, np.ndarray]:
        """Machines start..stop-1 of the sweep: their columns (index start..stop-1)."""
        if self.points is None:
            assert self.axes is not None
            return _core.sweep_grid(self.machine._handle, self.keys, list(self.axes.values()), threads,
                                    self.accuracy, start, stop)
        return _core.sweep_points(self.machine._handle, self.keys,
                                  self.points[start - self.first:stop - self.first], start, threads, self.accuracy)

    def part(self, start: int, stop: int) -> "_Plan":
        """What machines start..stop-1 need: the whole plan for a grid (its values per key are
        small), only their own rows of a Latin hypercube."""
        if self.points is None:
            return self
        return dataclasses.replace(self, points=np.array(self.points[start - self.first:stop - self.first]),
                                   first=start)


def _plan(machine: Machine, values: Mapping[str, Any], samples: Optional[int], seed: int,
          accuracy: Optional[float], force_large: bool, stored: bool = False) -> _Plan:
    """Checks a sweep's arguments, each wrong one named in Python's words."""
    if not isinstance(machine, Machine):
        raise TypeError("sweep(machine, values): make the machine with whatnext.example(), load() or machine()")
    if not isinstance(values, Mapping):
        raise TypeError(f"sweep(machine, values): values is a dict of key -> values, e.g. "
                        f"{{'geometry.rope_length': np.linspace(0.62, 0.9, 29)}}, not {type(values).__name__}")
    if not values:
        raise InputError("sweep: give at least one key to vary")
    keys = [_check_key("sweep(machine, values)", k) for k in values]
    accuracy_s = None if accuracy is None else _real("sweep: accuracy", accuracy)
    axes: Optional[Dict[str, np.ndarray]] = None
    points: Optional[np.ndarray] = None
    if samples is not None:
        n = _whole("sweep: samples", samples, 1, _core.MAX_MACHINES)
        seed_n = _whole("sweep: seed", seed, 0, 2**64 - 1)
        lo, hi = [], []
        for k, v in values.items():
            if isinstance(v, (str, bytes)) or not (isinstance(v, (Sequence, np.ndarray)) and len(v) == 2):
                raise TypeError(f"sweep(samples=...): {k} needs a pair (a, b), not {v!r}")
            a, b = _real(f"sweep: {k}: a", v[0]), _real(f"sweep: {k}: b", v[1])
            if not (np.isfinite(a) and np.isfinite(b) and a <= b):
                raise InputError(f"sweep: {k} needs finite a <= b (given ({a!r}, {b!r}))")
            lo.append(a)
            hi.append(b)
        size = n
    else:
        axes = {}
        size = 1
        for k, v in values.items():
            given = np.asarray(v)
            if given.dtype.kind == "c":
                raise TypeError(f"sweep: {k} needs real numbers, not complex ones")
            if given.dtype.kind not in "iuf":
                try:
                    if given.dtype.kind in "bSUV":
                        raise TypeError
                    given = np.array(given, dtype=np.float64)
                except (TypeError, ValueError):
                    raise TypeError(f"sweep: {k} needs numbers (a sequence or numpy array), not {v!r:.60}") from None
            axis = np.array(np.atleast_1d(given), dtype=np.float64, order="C")  # a copy: ours to freeze
            if axis.ndim != 1 or axis.size == 0:
                raise InputError(f"sweep: {k} needs a one-dimensional sequence of at least one value")
            axes[k] = axis
            size *= axis.size
        if size > (MAX_STUDY if stored else _core.MAX_MACHINES):
            raise InputError(f"sweep: the grid has {size} machines, more than {_core.MAX_MACHINES}; use fewer values")
    if size > LARGE_SWEEP and not force_large and not stored:
        row_bytes = 8 * (4 + len(keys) + len(_core.event_names())) + 4 * 16
        raise InputError(f"sweep: {size} machines would hold at least {size * row_bytes / 1e9:.1f} GB in memory; "
                         f"use fewer, or pass force_large=True")
    if samples is not None:
        points = _core.lhs_points(keys, lo, hi, size, seed_n)
        points.flags.writeable = False
    return _Plan(machine, keys, axes, points, size, accuracy_s, samples=None if samples is None else size,
                 seed=None if samples is None else seed_n)


def sweep(machine: Machine, values: Mapping[str, Any], *, samples: Optional[int] = None, seed: int = 1,
          threads: Optional[int] = None, accuracy: Optional[float] = _core.DEFAULT_ACCURACY,
          force_large: bool = False, client: Any = None, chunk: Optional[int] = None,
          progress: Union[bool, Callable[[int, int], None]] = False,
          csv: Union[None, str, "os.PathLike[str]"] = None, resume: bool = False,
          store: Union[None, str, "os.PathLike[str]"] = None) -> Any:
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
    depend on the thread count. Ctrl-C stops the sweep (KeyboardInterrupt) once the machines
    running finish, normally within a tenth of a second.

    ``accuracy`` is the event-time accuracy in seconds (default 1e-8, as ``--accuracy`` of
    ``whatnext sweep``): every event time is then within it of the exact time, and the machines run
    with the loosest integrator tolerance that guarantees it (unless the machine sets
    ``run.tolerance`` itself). ``accuracy=None`` runs each machine with its own run settings,
    exactly as :func:`simulate` would.

    More than a million machines need ``force_large=True`` (as the command's ``--force-large``):
    every row is kept in memory.

    ``client=`` a ``dask.distributed.Client`` runs the sweep on that cluster's workers instead,
    in chunks of ``chunk`` machines, with the same result to the last bit (see
    :func:`whatnext.dask.sweep`); ``progress=True`` then prints the machines done, or a function
    ``progress(done, total)`` is called as chunks finish.

    ``csv=path`` writes the sweep's CSV while it runs, exactly as ``whatnext sweep --out path``
    does (the same bytes as ``to_csv()``): the rows go to ``path.part`` in machine order and are
    synced to the disk about once a second, and the file gets its name when the sweep ends (until
    then an existing ``path`` stays as it was). Killed, crashed or cut off by a power cut, the sweep
    leaves its rows in ``path.part``; Ctrl-C gives the file its name with the rows done, then
    raises KeyboardInterrupt. ``resume=True`` continues such a sweep: called again with the same
    machine, values, samples, seed and accuracy, it keeps every complete row of ``path.part`` (or
    of ``path``), runs only the other machines, and ends with the bytes an uninterrupted sweep
    writes, whatever was interrupted and how often; the file is the command's, so ``whatnext sweep
    --resume`` continues it too when its values are the command's (``whatnext.grid``). A file of
    another sweep is refused with :class:`InputError` and left as it was; so is a second sweep
    writing the same file while the first runs. Not with ``client=``.

    ``store="study.zarr"`` with ``client=`` runs a study of any size: each Dask worker writes its
    chunks straight into that Zarr store (Debian's ``python3-zarr``), laid out as
    :meth:`Sweep.to_xarray`'s dataset, so the client never holds the results; the call returns the
    store opened lazily as an ``xarray.Dataset`` (``whatnext.dataset.open_study`` opens it later).
    Interrupted (the client or workers killed), the same call continues from the chunks already
    written; a store of another study is refused with :class:`InputError` naming what differs.
    A grid may then have up to 2^53 machines; a Latin hypercube's points are drawn on the client.

    Returns a :class:`Sweep`: columns named like the sweep CSV (``outcome``, ``outcome_t``,
    ``lid_open``, ``rope_taut``, ..., ``error``), each a read-only numpy array with a row per
    machine; ``to_csv(path)`` writes that CSV.

    Example::

        s = whatnext.sweep(whatnext.example(2), {"geometry.rope_length": np.linspace(0.62, 0.9, 29),
                                                 "masses.sandbag": np.linspace(0.2, 2.0, 37)})
        s.grid("lid_open")        # 29 x 37, NaN where the lid never opens
    """
    if store is not None and client is None:
        raise TypeError("sweep: store= is written by the workers of a Dask cluster: give client=... too "
                        "(on this computer use csv=...)")
    plan = _plan(machine, values, samples, seed, accuracy, force_large, stored=store is not None)
    if client is None and (chunk is not None or progress is not False):
        raise TypeError("sweep: chunk= and progress= belong to a sweep on a Dask cluster (client=...)")
    if not isinstance(resume, (bool, np.bool_)):
        raise TypeError(f"sweep: resume is True or False, not {type(resume).__name__} {resume!r}")
    if resume and csv is None:
        raise TypeError("sweep: resume=True continues the CSV file of an interrupted sweep: give it as csv=...")
    if csv is not None and not isinstance(csv, (str, os.PathLike)):
        raise TypeError(f"sweep: csv is a file name, not {type(csv).__name__} {csv!r}")
    if client is not None:
        if csv is not None:
            raise TypeError("sweep: csv= writes a sweep on this computer; on a Dask cluster write the "
                            "result with to_csv(path)")
        if not callable(getattr(client, "submit", None)):
            raise TypeError(f"sweep: client is a dask.distributed.Client, not {type(client).__name__} {client!r:.60}")
        if store is not None:
            from . import dataset as _dataset
            return _dataset.study(plan, client, store, chunk=chunk, threads=threads, progress=progress)
        from . import dask as _dask
        return _dask.run(plan, client, chunk=chunk, threads=threads, progress=progress)
    n_threads = 0 if threads is None else _whole("sweep: threads", threads, 1, 4096)
    if csv is not None:
        path = os.fspath(csv)
        if not isinstance(path, str):
            raise TypeError(f"sweep: csv is a file name as text, not {type(path).__name__} {path!r}")
        axes = list(plan.axes.values()) if plan.axes is not None else None
        return Sweep(plan.keys, _core.sweep_to_file(plan.machine._handle, plan.keys, axes, plan.points, n_threads,
                                                    plan.accuracy, path, bool(resume)), plan.axes, plan.info())
    return Sweep(plan.keys, plan.run(0, plan.size, n_threads), plan.axes, plan.info())


from . import plot  # noqa: E402  (matplotlib itself is imported only when a figure is drawn)
from . import dataset  # noqa: E402  (xarray and Zarr themselves are imported only when used)

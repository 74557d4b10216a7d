"""Sweeps as labelled arrays: an :class:`xarray.Dataset` per sweep, and studies of any size that
Dask workers write straight into a Zarr store.

A grid sweep becomes a dataset with one dimension per varied key (its values are the coordinate);
a Latin hypercube, a ``machine`` dimension with the drawn values as coordinates along it. Every
other column of the sweep (``outcome``, ``outcome_t``, the event times, ``error``, ...) is a
variable with its unit in ``attrs["units"]``; the dataset's attributes hold the machine (its TOML),
the accuracy and the program's version, so that a file says which study it is.

Uses Debian's ``python3-xarray`` and, for stores, ``python3-zarr``; both are imported only here.
"""

import os
import pathlib
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np

from . import InputError, _core, input_keys

if TYPE_CHECKING:  # pragma: no cover
    import xarray

    from . import Sweep, _Plan

__all__ = ["to_xarray", "study", "open_study"]

# The sweep's columns that are not event times, with their units (event times are in seconds;
# a varied key has the unit of docs/inputs.md).
_COLUMN_UNITS = {"index": "", "outcome": "", "outcome_t": "s", "final_r": "m", "final_phi_l_deg": "deg",
                 "error": ""}
_COLUMN_MEANINGS = {
    "index": "the machine's index in the sweep (the CSV's row)",
    "outcome": "how the run ended: an event name, 'invalid' (a rule broken) or 'failed'",
    "outcome_t": "time of the outcome",
    "final_r": "the sandbag's final distance from the pivot",
    "final_phi_l_deg": "the lid's final angle",
    "error": "why a machine is invalid or failed (empty otherwise)",
}
_MACHINE_DIM = "machine"


def _version() -> str:
    return str(_core.VERSION)


def _column_attrs(name: str) -> Dict[str, str]:
    if name in _COLUMN_UNITS:
        return {"units": _COLUMN_UNITS[name], "long_name": _COLUMN_MEANINGS[name]}
    return {"units": "s", "long_name": f"time of the first {name} (NaN: it never happened)"}


def _key_attrs(key: str) -> Dict[str, str]:
    unit, meaning = input_keys().get(key, ("", ""))
    return {"units": unit, "long_name": meaning or key}


def _layout(keys: List[str], axes: Optional[Dict[str, np.ndarray]], size: int) -> Tuple[Tuple[str, ...],
                                                                                      Tuple[int, ...]]:
    if axes is None:
        return (_MACHINE_DIM,), (size,)
    return tuple(keys), tuple(len(axes[k]) for k in keys)


def _attrs(info: Dict[str, Any], keys: List[str]) -> Dict[str, Any]:
    """A dataset's attributes from what made the sweep (_Plan.info(), a Sweep's study_info)."""
    accuracy, samples, seed = info.get("accuracy"), info.get("samples"), info.get("seed")
    attrs: Dict[str, Any] = {
        "title": "whatnext sweep",
        "whatnext_version": _version(),
        "machine": info.get("machine", ""),
        # The names apart by spaces, as netCDF's own lists of variables (CF's `coordinates`): a list of
        # one name would come back from a netCDF file as a bare name.
        "varied": " ".join(keys),
        "accuracy_s": "none (each machine's own run settings)" if accuracy is None else float(accuracy),
        "plan": "grid" if samples is None else "latin hypercube",
    }
    if samples is not None:
        attrs["samples"] = int(samples)
        attrs["seed"] = int(seed) if seed is not None else "unknown"
    return attrs


def _skeleton(keys: List[str], axes: Optional[Dict[str, np.ndarray]], points: Optional[np.ndarray],
              first: int, size: int) -> Tuple[Tuple[str, ...], Tuple[int, ...], Dict[str, Tuple[Any, ...]]]:
    """Dimensions, shape and coordinates of a sweep's dataset."""
    dims, shape = _layout(keys, axes, size)
    coords: Dict[str, Tuple[Any, ...]] = {}
    if axes is not None:
        for k in keys:
            coords[k] = (k, np.asarray(axes[k]), _key_attrs(k))
    else:
        assert points is not None
        coords[_MACHINE_DIM] = (_MACHINE_DIM, np.arange(first, first + size, dtype=np.int64),
                                {"long_name": "the machine's index in the sweep"})
        for j, k in enumerate(keys):
            coords[k] = (_MACHINE_DIM, np.asarray(points[:, j]), _key_attrs(k))
    return dims, shape, coords


def to_xarray(sweep: "Sweep") -> "xarray.Dataset":
    """The sweep as an :class:`xarray.Dataset` (see the module's help); :meth:`Sweep.to_xarray`."""
    import xarray as xr

    keys = list(sweep.keys_varied)
    size = len(sweep.columns["index"])
    points = None
    if sweep.axes is None:
        points = np.stack([sweep.columns[k] for k in keys], axis=1) if keys else np.empty((size, 0))
    dims, shape, coords = _skeleton(keys, sweep.axes, points, int(sweep.columns["index"][0]) if size else 0, size)
    data_vars = {}
    for name, column in sweep.columns.items():
        if name in keys:
            continue  # a coordinate
        values = np.asarray(column)
        if values.dtype.kind == "U":
            values = values.astype(object)  # as a Zarr store holds text: any length per machine
        data_vars[name] = (dims, values.reshape(shape), _column_attrs(name))
    attrs = _attrs(getattr(sweep, "study_info", None) or {}, keys)
    return xr.Dataset(data_vars, coords=coords, attrs=attrs)


# -- studies of any size: Dask workers write their chunks into a Zarr store --------------------

_DONE = ".whatnext-done"  # a file per finished chunk, inside the store (Zarr ignores it)


def _chunking(shape: Tuple[int, ...], target: int) -> Tuple[int, ...]:
    """Zarr chunks whose machines are consecutive in the sweep's order (the last key fastest): whole
    trailing dimensions, a slab of the dimension before them, ones before that; about ``target``
    machines each. A chunk of the store is then exactly one task of consecutive machines."""
    chunks = [1] * len(shape)
    trailing = 1
    j = len(shape) - 1
    while j >= 0 and trailing * shape[j] <= target:
        trailing *= shape[j]
        chunks[j] = shape[j]
        j -= 1
    if j >= 0:
        chunks[j] = max(1, min(shape[j], target // trailing))
    return tuple(chunks)


def _task_bounds(shape: Tuple[int, ...], chunks: Tuple[int, ...]) -> List[Tuple[int, int]]:
    """The machine ranges [a, b) of the store's chunks, in order."""
    n = int(np.prod(shape, dtype=np.int64))
    j = next((i for i, c in enumerate(chunks) if c != 1 or i == len(chunks) - 1), 0)
    trailing = int(np.prod(shape[j + 1:], dtype=np.int64))
    per_slab = shape[j] * trailing  # machines per step of the dimensions before j
    out = []
    for base in range(0, n, per_slab):
        for i in range(0, shape[j], chunks[j]):
            out.append((base + i * trailing, base + min(shape[j], i + chunks[j]) * trailing))
    return out


def _region(shape: Tuple[int, ...], a: int, b: int) -> Tuple[slice, ...]:
    """The N-d slices of machines a..b-1 (a chunk of :func:`_chunking`)."""
    idx = np.unravel_index(a, shape)
    last = np.unravel_index(b - 1, shape)
    region = []
    for d in range(len(shape)):
        if idx[d] == last[d]:
            region.append(slice(int(idx[d]), int(idx[d]) + 1))
        else:
            # The dimension the chunk spans; every later one is whole.
            region.append(slice(int(idx[d]), int(last[d]) + 1))
            region.extend(slice(0, s) for s in shape[d + 1:])
            break
    return tuple(region)


def _identity(plan: "_Plan", chunks: Tuple[int, ...]) -> str:
    """Everything that changes a value of the study, as the lines of a resumable CSV's NAME.id
    (the program's version, the accuracy, every value of the machine, the varied values or the
    drawn machines), and the store's chunks: a store is continued only by its own study."""
    axes = list(plan.axes.values()) if plan.axes is not None else None
    text = _core.sweep_identity(plan.machine._handle, plan.keys, axes, plan.points, plan.accuracy)
    return text + f"chunks = {','.join(map(str, chunks))}\n"


def _differences(old: str, new: str) -> List[str]:
    """The names of the identity's lines that differ (in the new one's order)."""
    def lines(text: str) -> Dict[str, str]:
        pairs = (line.split(" = ", 1) for line in text.splitlines() if " = " in line)
        return {k: v for k, v in pairs}
    was, now = lines(old), lines(new)
    return [k for k in now if was.get(k) != now[k]] + [k for k in was if k not in now]


def _write_chunk(store: str, plan: "_Plan", shape: Tuple[int, ...], a: int, b: int, threads: int) -> int:
    """One Dask task: machines a..b-1 run on the worker and go straight into the store."""
    import zarr

    done = pathlib.Path(store) / _DONE / f"{a}-{b}"
    if done.exists():
        return b - a
    columns = plan.run(a, b, threads)
    group = zarr.open_group(store, mode="r+")
    region = _region(shape, a, b)
    sub = tuple(s.stop - s.start for s in region)
    for name, column in columns.items():
        if name in plan.keys:
            continue
        values = np.asarray(column)
        if values.dtype.kind == "U":
            values = values.astype(object)
        group[name][region] = values.reshape(sub)
    # The marker last, through a rename: it exists only once every variable of the chunk is written.
    part = done.with_name(f".{done.name}.part")
    with open(part, "wb") as f:
        f.flush()
        os.fsync(f.fileno())
    os.replace(part, done)
    return b - a


def _create(store: str, dims: Tuple[str, ...], shape: Tuple[int, ...], chunks: Tuple[int, ...],
            coords: Dict[str, Tuple[Any, ...]], names: List[str], attrs: Dict[str, Any],
            identity: str) -> None:
    """The store's layout (xarray's Zarr convention): coordinates written, variables empty."""
    import numcodecs
    import zarr

    group = zarr.open_group(store, mode="w")
    for name, (dim, values, vattrs) in coords.items():
        values = np.asarray(values)
        z = group.create_dataset(name, data=values, shape=values.shape, chunks=values.shape or None,
                                 dtype=values.dtype, fill_value=None)  # no value may read as missing
        z.attrs.update({"_ARRAY_DIMENSIONS": [dim], **vattrs})
    for name in names:
        text = name in ("outcome", "error")
        whole = name == "index"
        # No fill value but NaN for times: xarray would mask a text's "" or turn whole numbers into floats.
        if text:
            z = group.create_dataset(name, shape=shape, chunks=chunks, dtype=object,
                                     object_codec=numcodecs.VLenUTF8(), fill_value=None)
        elif whole:
            z = group.create_dataset(name, shape=shape, chunks=chunks, dtype="<i8", fill_value=None)
        else:
            z = group.create_dataset(name, shape=shape, chunks=chunks, dtype="<f8", fill_value=np.nan)
        z.attrs.update({"_ARRAY_DIMENSIONS": list(dims), **_column_attrs(name)})
    group.attrs.update({**attrs, "whatnext_identity": identity})
    zarr.consolidate_metadata(store)
    (pathlib.Path(store) / _DONE).mkdir()


def study(plan: "_Plan", client: Any, store: Union[str, "os.PathLike[str]"], *, chunk: Optional[int] = None, threads: Optional[int] = None,
          progress: Union[bool, Callable[[int, int], None]] = False) -> "xarray.Dataset":
    """Runs a checked sweep on the client's cluster, each worker writing its chunks into the Zarr
    store ``store``; returns the store opened lazily with xarray. See ``whatnext.sweep(store=...)``."""
    import xarray as xr

    from .dask import run_chunks, settings

    path = os.fspath(store)
    if not isinstance(path, str):
        raise TypeError(f"sweep: store is a folder name as text, not {type(path).__name__} {path!r}")
    dims, shape, coords = _skeleton(plan.keys, plan.axes, plan.points, 0, plan.size)
    target, per_chunk = settings(client, plan.size, chunk, threads)
    chunks = _chunking(shape, target)
    identity = _identity(plan, chunks)
    marker = pathlib.Path(path) / _DONE
    if marker.is_dir():
        import zarr
        try:
            old = str(zarr.open_group(path, mode="r").attrs["whatnext_identity"])
        except Exception:  # noqa: BLE001 (any damage: the store cannot be proven to be this study's)
            raise InputError(f"sweep: store {path} is not a whatnext study that can be continued; "
                             f"remove it or choose another folder") from None
        differ = _differences(old, identity)
        if differ:
            raise InputError(f"sweep: store {path} holds another study ({', '.join(differ)} differ); "
                             f"remove it or choose another folder")
    elif pathlib.Path(path).exists():
        raise InputError(f"sweep: store {path} exists and is not a whatnext study; remove it or choose another folder")
    else:
        names = [n for n in plan.run(0, 1, 1) if n not in plan.keys]  # the columns, from machine 0
        _create(path, dims, shape, chunks, coords, names, _attrs(plan.info(), plan.keys), identity)
    bounds = _task_bounds(shape, chunks)
    finished = {p.name for p in marker.iterdir() if not p.name.startswith(".")}
    todo = [(a, b) for a, b in bounds if f"{a}-{b}" not in finished]
    run_chunks(client, _write_chunk, todo, lambda a, b: (path, plan.part(a, b), shape, a, b, per_chunk),
               plan.size, progress, done=plan.size - sum(b - a for a, b in todo))
    return xr.open_zarr(path)


def open_study(store: Union[str, "os.PathLike[str]"]) -> "xarray.Dataset":
    """A study's store as a dataset (lazy: values are read as they are used)."""
    import xarray as xr

    return xr.open_zarr(os.fspath(store))

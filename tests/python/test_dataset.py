"""Sweeps as xarray datasets and studies written by Dask workers into Zarr: every value where the
command's CSV puts it, round trips without loss, a study continued after its workers or its client
were killed, and a store of another study refused."""

import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import whatnext
from conftest import read_csv, run_cli

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")

GRID = {"geometry.rope_length": (0.5, 0.9, 9), "masses.sandbag": (0.2, 2.0, 5)}


def grid_values(ranges=GRID):
    return {k: whatnext.grid(*r) for k, r in ranges.items()}


def assert_same_values(a, b):
    """Every variable and coordinate of two datasets equal to the bit (NaN where NaN)."""
    assert set(a.variables) == set(b.variables)
    for name in a.variables:
        x, y = np.asarray(a[name].values), np.asarray(b[name].values)
        assert a[name].dims == b[name].dims, name
        assert x.shape == y.shape, name
        if x.dtype.kind == "f":
            assert y.dtype.kind == "f", name
            assert np.array_equal(x.view(np.int64), y.view(np.int64)) or np.array_equal(x, y, equal_nan=True), name
        else:
            assert x.tolist() == y.tolist(), name


def test_a_grid_is_a_dataset_with_a_dimension_per_key(tmp_path):
    # Each cell of the dataset is the CLI's CSV row with those two values: the axes are the right way round.
    out = tmp_path / "s.csv"
    run_cli(["sweep", "--example", 2, "--out", out,
             *[a for k, (lo, hi, n) in GRID.items() for a in ("--vary", f"{k}={lo}:{hi}:{n}")]])
    header, rows = read_csv(out)
    ds = whatnext.sweep(whatnext.example(2), grid_values()).to_xarray()
    assert ds.dims == {"geometry.rope_length": 9, "masses.sandbag": 5}
    for key in GRID:
        assert ds[key].values.tolist() == whatnext.grid(*GRID[key]).tolist()
        assert ds[key].attrs["units"] == whatnext.input_keys()[key][0]
    assert ds["outcome_t"].attrs["units"] == "s" and ds["final_phi_l_deg"].attrs["units"] == "deg"
    assert ds["final_r"].attrs["units"] == "m" and ds["lid_open"].attrs["units"] == "s"
    assert "geometry.rope_length" not in ds.data_vars  # the varied keys are coordinates
    for row in rows:
        cell = dict(zip(header, row))
        at = ds.sel({k: float(cell[k]) for k in GRID})
        assert at["index"].item() == int(cell["index"])
        assert at["outcome"].item() == cell["outcome"] and at["error"].item() == cell["error"]
        for name in ("outcome_t", "lid_open", "rope_taut", "final_r"):
            value = at[name].item()
            assert (np.isnan(value) and cell[name] == "") or value == float(cell[name]), name
    # What made it: the machine (its TOML reads back as the same machine), the accuracy, the version.
    machine = tmp_path / "m.toml"
    machine.write_text(ds.attrs["machine"])
    assert whatnext.load(machine).to_toml() == whatnext.example(2).to_toml()
    assert ds.attrs["accuracy_s"] == 1e-8 and ds.attrs["plan"] == "grid"
    assert ds.attrs["varied"].split() == list(GRID) and ds.attrs["whatnext_version"] == whatnext._core.VERSION


def test_samples_have_a_machine_dimension_with_the_drawn_values():
    values = {"start.sandbag_height": (0.3, 1.5), "geometry.rope_length": (0.3, 0.9)}
    s = whatnext.sweep(whatnext.example(2), values, samples=40, seed=5)
    ds = s.to_xarray()
    assert ds.dims == {"machine": 40}
    assert ds["machine"].values.tolist() == list(range(40))
    for key in values:
        assert ds[key].dims == ("machine",)
        assert np.array_equal(ds[key].values, s[key])
        lo, hi = values[key]
        assert ((ds[key] >= lo) & (ds[key] <= hi)).all()
    assert ds.attrs["plan"] == "latin hypercube" and ds.attrs["seed"] == 5 and ds.attrs["samples"] == 40


def _zarr_round_trip(ds, path):
    ds.to_zarr(path)
    return xr.open_zarr(path).load()


def _netcdf_round_trip(ds, path):
    # netCDF4 (Debian's python3-netcdf4): 64-bit integers and text of any length, which netCDF3 has not.
    pytest.importorskip("netCDF4")
    ds.to_netcdf(path, engine="netcdf4")
    with xr.open_dataset(path, engine="netcdf4") as back:
        return back.load()


@pytest.mark.parametrize("round_trip", [_zarr_round_trip, _netcdf_round_trip], ids=["zarr", "netcdf"])
def test_a_dataset_round_trips_without_loss(tmp_path, round_trip):
    # A grid of two keys, and samples of one key (a list of one name is where netCDF is weakest).
    m = whatnext.example(3)
    for ds in (whatnext.sweep(m, grid_values()).to_xarray(),
               whatnext.sweep(m, {"masses.sandbag": (0.2, 2.0)}, samples=30, seed=2).to_xarray()):
        back = round_trip(ds, tmp_path / ds.attrs["plan"].replace(" ", "-"))
        xr.testing.assert_identical(ds, back)
        assert_same_values(ds, back)
        for name in ds.variables:
            assert back[name].attrs == ds[name].attrs, name
        assert back.attrs == ds.attrs
        assert back["index"].dtype == np.int64 and back["outcome"].values.tolist() == ds["outcome"].values.tolist()


# --- studies written by the workers -------------------------------------------------------------

def test_a_study_in_a_store_equals_the_local_sweep(dask_cluster, tmp_path):
    _, client = dask_cluster
    m = whatnext.example(2)
    big = {"geometry.rope_length": (0.62, 1.0, 13), "masses.sandbag": (0.2, 2.0, 11)}
    for values, kwargs in ((grid_values(big), {}), ({"masses.sandbag": (0.2, 2.0)}, {"samples": 57, "seed": 4})):
        store = tmp_path / f"{len(kwargs)}.zarr"
        ds = whatnext.sweep(m, values, client=client, store=store, chunk=20, **kwargs)
        local = whatnext.sweep(m, values, **kwargs).to_xarray()
        assert_same_values(ds.load(), local)
        assert ds.attrs["machine"] == local.attrs["machine"]
        assert_same_values(whatnext.dataset.open_study(store).load(), local)
        # Run again: everything is there already, nothing runs, the same values.
        assert_same_values(whatnext.sweep(m, values, client=client, store=store, chunk=20, **kwargs).load(), local)


def test_a_store_of_another_study_is_refused_and_left_alone(dask_cluster, tmp_path):
    _, client = dask_cluster
    m = whatnext.example(2)
    store = tmp_path / "s.zarr"
    whatnext.sweep(m, grid_values(), client=client, store=store, chunk=9)
    before = sorted((p.relative_to(store), p.stat().st_mtime_ns) for p in store.rglob("*"))
    other = {"geometry.rope_length": (0.5, 0.9, 9), "masses.sandbag": (0.2, 2.1, 5)}
    with pytest.raises(whatnext.InputError, match=r"^sweep: store .* holds another study \(values of masses.sandbag differ\)"):
        whatnext.sweep(m, grid_values(other), client=client, store=store, chunk=9)
    with pytest.raises(whatnext.InputError, match=r"\(machine masses.lid differ\)"):
        whatnext.sweep(m.set("masses.lid", 0.3), grid_values(), client=client, store=store, chunk=9)
    with pytest.raises(whatnext.InputError, match=r"\(accuracy differ\)"):
        whatnext.sweep(m, grid_values(), client=client, store=store, chunk=9, accuracy=1e-9)
    assert sorted((p.relative_to(store), p.stat().st_mtime_ns) for p in store.rglob("*")) == before
    (tmp_path / "plain").mkdir()
    with pytest.raises(whatnext.InputError, match="is not a whatnext study"):
        whatnext.sweep(m, grid_values(), client=client, store=tmp_path / "plain")
    with pytest.raises(TypeError, match="store= is written by the workers of a Dask cluster"):
        whatnext.sweep(m, grid_values(), store=tmp_path / "x.zarr")


def test_a_study_goes_on_after_a_worker_is_killed(dask_cluster, tmp_path):
    _, client = dask_cluster
    m = whatnext.example(2)
    values = {"geometry.rope_length": whatnext.grid(0.62, 1.0, 60), "masses.sandbag": whatnext.grid(0.2, 2.0, 50)}
    pids = client.run(os.getpid)
    victim = max(pids.values())
    killed = []

    def progress(done, total):
        if not killed:
            os.kill(victim, signal.SIGKILL)
            killed.append(done)

    ds = whatnext.sweep(m, values, client=client, store=tmp_path / "k.zarr", chunk=100, progress=progress)
    assert killed and killed[0] < 3000
    assert_same_values(ds.load(), whatnext.sweep(m, values).to_xarray())


def test_a_study_goes_on_after_its_client_is_killed(dask_cluster, tmp_path):
    # A second client (another process, as a notebook's kernel would be) starts the study and is
    # killed after some chunks are in the store; the same call from here finishes it.
    c, client = dask_cluster
    store = tmp_path / "c.zarr"
    flag = tmp_path / "started"
    script = textwrap.dedent(f"""
        import os, whatnext
        from distributed import Client
        client = Client({c.scheduler_address!r})
        def progress(done, total):
            if done >= 600:
                open({str(flag)!r}, "w").close()
        whatnext.sweep(whatnext.example(2), {{"geometry.rope_length": whatnext.grid(0.62, 1.0, 60),
                                             "masses.sandbag": whatnext.grid(0.2, 2.0, 50)}},
                       client=client, store={str(store)!r}, chunk=100, progress=progress)
        open({str(flag)!r} + ".end", "w").close()
    """)
    child = subprocess.Popen([sys.executable, "-c", script], env=os.environ.copy())
    deadline = time.monotonic() + 120
    while not flag.exists() and child.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    child.send_signal(signal.SIGKILL)
    child.wait()
    assert flag.exists() and not (tmp_path / "started.end").exists()
    written = len(list((store / ".whatnext-done").iterdir()))
    assert 0 < written < 30
    values = {"geometry.rope_length": whatnext.grid(0.62, 1.0, 60), "masses.sandbag": whatnext.grid(0.2, 2.0, 50)}
    ds = whatnext.sweep(whatnext.example(2), values, client=client, store=store, chunk=100)
    assert_same_values(ds.load(), whatnext.sweep(whatnext.example(2), values).to_xarray())
    # The proof of identity is a resumable CSV's (NAME.id), with the store's chunks.
    identity = ds.attrs["whatnext_identity"].splitlines()
    assert "values of geometry.rope_length = 60 from 0.62 to 1 (digest" in "\n".join(identity)
    assert identity[-1] == "chunks = 2,50" and f"program = whatnext {whatnext._core.VERSION}" in identity

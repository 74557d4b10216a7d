"""Sweeps from Python against `whatnext sweep`: the same columns and numbers as its CSV, for a grid
and a Latin hypercube; rows independent of the thread count; the GIL released while it runs."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import whatnext
from conftest import EXAMPLES, read_csv, run_cli

RANGES = {"geometry.rope_length": (0.5, 0.9, 9), "masses.sandbag": (0.2, 2.0, 5)}


def assert_columns_equal_csv(result, path):
    header, rows = read_csv(path)
    assert list(result) == header
    assert len(result["index"]) == len(rows)
    cols = dict(zip(header, zip(*rows)))
    for name in header:
        mine, theirs = result[name], cols[name]
        if name in ("outcome", "error"):
            assert list(mine) == list(theirs), name
        elif name == "index":
            assert mine.tolist() == [int(v) for v in theirs]
        else:
            # The CSV prints the shortest text that reads back to the same double: exact equality.
            expected = np.array([float(v) if v != "" else np.nan for v in theirs])
            assert np.array_equal(mine, expected, equal_nan=True), name


def test_grid_equals_the_cli_csv(tmp_path):
    out = tmp_path / "s.csv"
    run_cli(["sweep", "--example", 2, "--out", out,
             *[a for k, (lo, hi, n) in RANGES.items() for a in ("--vary", f"{k}={lo}:{hi}:{n}")]])
    result = whatnext.sweep(whatnext.example(2), {k: whatnext.grid(*r) for k, r in RANGES.items()})
    # Short ropes are invalid here (the error column says why) and some machines time out: every
    # kind of row is compared.
    assert {"invalid", "lid_open"} <= set(result["outcome"])
    assert_columns_equal_csv(result, out)
    # grid() gives the command line's values, which are the CSV's, in the CSV's order.
    _, rows = read_csv(out)
    assert whatnext.grid(0.5, 0.9, 9).tolist() == sorted({float(r[1]) for r in rows})


def test_latin_hypercube_equals_the_cli_csv(tmp_path):
    out = tmp_path / "lhs.csv"
    run_cli(["sweep", "--example", 1, "--samples", 40, "--seed", 7, "--accuracy", "1e-6", "--out", out,
             "--vary", "start.sandbag_height=0.3:1.5", "--vary", "masses.lid=0.2:1"])
    result = whatnext.sweep(whatnext.example(1), {"start.sandbag_height": (0.3, 1.5), "masses.lid": (0.2, 1)},
                            samples=40, seed=7, accuracy=1e-6)
    assert_columns_equal_csv(result, out)
    assert result.shape == (40,)


def test_errors_naming_a_file_equal_the_cli_csv(tmp_path):
    # Longer hinge distances leave the file's rope too short: the error names the file's line, and
    # the file's name is not ASCII.
    machine = tmp_path / "mäschine.toml"
    machine.write_text((EXAMPLES / "example2.toml").read_text())
    out = tmp_path / "u.csv"
    run_cli(["sweep", machine, "--vary", "geometry.hinge_distance=0.8:1.2:3", "--out", out])
    result = whatnext.sweep(whatnext.load(machine), {"geometry.hinge_distance": whatnext.grid(0.8, 1.2, 3)})
    assert "mäschine.toml:" in result["error"][-1]
    assert_columns_equal_csv(result, out)


def test_columns_dtypes_and_grid_shape():
    axes = {"geometry.rope_length": np.linspace(0.62, 0.9, 6), "start.sandbag_height": [0.4, 0.5, 0.7, 1.0]}
    s = whatnext.sweep(whatnext.example(2), axes, threads=2)
    n = 6 * 4
    assert s.shape == (6, 4)
    for name, col in s.items():
        assert col.shape == (n,), name
    assert s["index"].dtype == np.int64 and s["index"].tolist() == list(range(n))
    assert s["outcome"].dtype.kind == "U" and s["error"].dtype.kind == "U"
    for name in ("geometry.rope_length", "outcome_t", "final_r", "final_phi_l_deg", "lid_open", "rope_taut"):
        assert s[name].dtype == np.float64, name
    # The last key varies fastest: grid(name)[i, j] belongs to value i of the first key, j of the second.
    assert np.array_equal(s.grid("geometry.rope_length"), np.repeat(axes["geometry.rope_length"], 4).reshape(6, 4))
    assert np.array_equal(s.grid("start.sandbag_height")[0], np.array(axes["start.sandbag_height"]))
    # Each machine is the base machine with the values set: row 5 is one simulate() away, to the
    # last bit when the sweep runs the machine's own settings (accuracy=None), and within the
    # event-time accuracy asked for otherwise.
    i, j = 1, 1
    run = whatnext.simulate(whatnext.example(2).set({"geometry.rope_length": axes["geometry.rope_length"][i],
                                                    "start.sandbag_height": axes["start.sandbag_height"][j]}),
                            samples=False)
    own = whatnext.sweep(whatnext.example(2), axes, threads=2, accuracy=None)
    assert own.grid("outcome")[i, j] == run.outcome.type and own.grid("outcome_t")[i, j] == run.outcome.time
    for accuracy in (1e-6, 1e-8):
        loose = s if accuracy == 1e-8 else whatnext.sweep(whatnext.example(2), axes, threads=2, accuracy=accuracy)
        assert loose.grid("outcome")[i, j] == run.outcome.type
        assert abs(loose.grid("outcome_t")[i, j] - run.outcome.time) <= accuracy


def test_rows_do_not_depend_on_the_thread_count():
    values = {"geometry.rope_length": np.linspace(0.6, 1.0, 7), "masses.sandbag": np.linspace(0.3, 1.5, 5)}
    one = whatnext.sweep(whatnext.example(1), values, threads=1)
    two = whatnext.sweep(whatnext.example(1), values, threads=2)
    for name in one:
        a, b = one[name], two[name]
        assert np.array_equal(a, b, equal_nan=a.dtype.kind == "f"), name


def test_bad_keys_raise_input_error():
    m = whatnext.example(2)
    with pytest.raises(whatnext.InputError, match=r"accuracy: must be in \[1e-14, 0.01\] s \(given 0\)"):
        whatnext.sweep(m, {"geometry.rope_length": [0.7]}, accuracy=0)
    with pytest.raises(whatnext.InputError, match="did you mean 'geometry.rope_length'"):
        whatnext.sweep(m, {"geometry.rope_lenght": [0.7]})
    with pytest.raises(whatnext.InputError, match="run.impact_law"):
        whatnext.sweep(m, {"run.impact_law": [1.0]})
    with pytest.raises(whatnext.InputError):
        whatnext.sweep(m, {"geometry.rope_length": []})
    with pytest.raises(whatnext.InputError):
        whatnext.grid(0.9, 0.5, 3)


def test_the_gil_is_released_during_a_sweep():
    # A pure-Python counter runs in another thread while a sweep runs on one worker thread. With the
    # GIL held for the whole sweep the counter would stand still from the sweep's start to its end;
    # released, it keeps counting, so the longest pause between its ticks is a small part of the sweep.
    ticks = []
    stop = threading.Event()

    def counter():
        n = 0
        while not stop.is_set():
            n += 1
            if n % 2000 == 0:
                ticks.append(time.perf_counter())

    values = {"geometry.rope_length": np.linspace(0.62, 0.9, 60), "masses.sandbag": np.linspace(0.3, 2.0, 40)}
    thread = threading.Thread(target=counter)
    thread.start()
    try:
        time.sleep(0.05)
        t0 = time.perf_counter()
        whatnext.sweep(whatnext.example(2), values, threads=1)
        t1 = time.perf_counter()
    finally:
        stop.set()
        thread.join()
    during = [t for t in ticks if t0 <= t <= t1]
    gaps = np.diff([t0, *during, t1])
    assert len(during) > 10, f"the counter did not run during the {t1 - t0:.2f} s sweep"
    assert gaps.max() < 0.5 * (t1 - t0), f"the counter stood still for {gaps.max():.2f} of {t1 - t0:.2f} s"


def test_ctrl_c_stops_a_sweep():
    # A sweep sized to take about 8 s at this machine's measured rate; SIGINT after 0.3 s must end
    # it with KeyboardInterrupt well before it would finish (the check runs ten times a second).
    m = whatnext.example(2)
    t0 = time.perf_counter()
    whatnext.sweep(m, {"geometry.rope_length": np.linspace(0.62, 0.9, 2000)}, threads=2)
    rate = 2000 / (time.perf_counter() - t0)
    n = int(max(20_000, 8 * rate))
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    t0 = time.perf_counter()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            whatnext.sweep(m, {"geometry.rope_length": np.linspace(0.62, 0.9, n)}, threads=2)
    finally:
        timer.cancel()
    assert time.perf_counter() - t0 < 0.5 * n / rate

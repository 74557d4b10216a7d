"""The Python module against the command line: the same input gives the same events (to the last
bit), the same samples (the CSV's columns at the CSV's precision), the same timeline and JSON,
and the same one-line error messages."""

import json

import numpy as np
import pytest

import whatnext
from conftest import EXAMPLES, read_csv, run_cli

# The events JSON's "state" fields and the CSV column with the same quantity.
JSON_TO_COLUMN = {"x": "x_m", "h": "h_m", "r": "r_m", "dr": "dr_m_per_s", "phi_s_deg": "phi_s_deg",
                  "dphi_s_deg_per_s": "dphi_s_deg_per_s", "phi_l_deg": "phi_l_deg",
                  "dphi_l_deg_per_s": "dphi_l_deg_per_s", "balloon_h": "balloon_h_m", "energy": "energy_J"}


def csv_number(v: float) -> float:
    """What the CSV holds for v: nine significant digits, with -0 and non-finite values as 0."""
    return float(f"{v:.9g}") if np.isfinite(v) and v != 0.0 else 0.0


def cli_run(tmp_path, input_args, extra=()):
    events, samples = tmp_path / "ev.json", tmp_path / "s.csv"
    proc = run_cli(["run", *input_args, "--events", events, "--csv", samples, *extra])
    return proc.stdout, events.read_text(), read_csv(samples)


def assert_same_run(run, stdout, events_text, table):
    doc = json.loads(events_text)
    assert run.outcome.type == doc["outcome"]["type"]
    assert run.outcome.time == doc["outcome"]["t"]  # the JSON's digits read back to the same double
    assert run.outcome.sentence == doc["outcome"]["sentence"]
    assert [e.type for e in run.events] == [e["type"] for e in doc["events"]]
    for mine, theirs in zip(run.events, doc["events"]):
        assert mine.time == theirs["t"], mine.type
        assert (mine.mode_before, mine.mode_after) == (theirs["mode_before"], theirs["mode_after"])
        for field, column in JSON_TO_COLUMN.items():
            assert mine.state[column] == theirs["state"][field], (mine.type, field)
        if "energy_before" in theirs:
            assert mine.impact
            assert (mine.energy_before, mine.energy_after) == (theirs["energy_before"], theirs["energy_after"])
        else:
            assert not mine.impact
    # The timeline and the JSON are the library's own text, so they must match byte for byte.
    assert run.timeline() == stdout
    assert run.events_json() == events_text

    header, rows = table
    assert list(run.samples) == header
    n = len(rows)
    for name, column in run.samples.items():
        assert column.shape == (n,), name
    cols = list(zip(*rows))
    for j, name in enumerate(header):
        mine = run.samples[name]
        if name in ("event", "mode"):
            assert list(mine) == list(cols[j]), name
        elif name == "rope_taut":
            assert list(mine) == [c == "1" for c in cols[j]]
        else:
            expected = np.array([float(c) for c in cols[j]])
            got = np.array([csv_number(v) for v in mine])
            assert np.array_equal(got, expected), (name, np.flatnonzero(got != expected)[:5])


@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_examples_equal_the_cli(tmp_path, n):
    stdout, events_text, table = cli_run(tmp_path, ["--example", n])
    assert_same_run(whatnext.simulate(whatnext.example(n)), stdout, events_text, table)


def test_file_inputs_equal_the_cli(tmp_path):
    # A TOML file (the radio runs on after lid_open) and the paper's whatnext.inp layout.
    radio = EXAMPLES / "example1-radio.toml"
    stdout, events_text, table = cli_run(tmp_path, [radio])
    run = whatnext.simulate(whatnext.load(radio))
    assert run.event("radio_on") is not None
    assert_same_run(run, stdout, events_text, table)

    inp = tmp_path / "whatnext.inp"
    inp.write_text("0.5\n-0.3\n-35\n5\n0.8\n0.62\n27\n0.2\n0.6\n0.6\n0.5\n1.29\n0.18\n2.0\n1.0d-3\n")
    stdout, events_text, table = cli_run(tmp_path, [inp])
    assert_same_run(whatnext.simulate(whatnext.load(inp)), stdout, events_text, table)


def test_overrides_equal_cli_set(tmp_path):
    # Every kind of value: a number, a word, a flag, a pair, a numpy scalar, and simulate()'s keywords.
    m = (whatnext.example(2)
         .set("geometry.rope_length", np.float64(0.65))
         .set({"run.impact_law": "kinetic-energy", "radio.enabled": True,
               "geometry.hinge_offset": (0.713, 0.363)}))
    run = whatnext.simulate(m, output_step=0.004, t_max=3)
    sets = ["geometry.rope_length=0.65", "run.impact_law=kinetic-energy", "radio.enabled=true",
            "geometry.hinge_offset=[0.713, 0.363]", "run.output_step=0.004", "run.t_max=3"]
    stdout, events_text, table = cli_run(tmp_path, ["--example", 2, *[a for s in sets for a in ("--set", s)]])
    # Byte for byte, the first lines too: the machine is named as the command line names it.
    assert m.source == "example 2 with --set " + ", ".join(sets[:4])
    assert run.timeline().startswith("whatnext: example 2 with --set geometry.rope_length=0.65, ")
    assert_same_run(run, stdout, events_text, table)


def test_a_machine_never_changes():
    m = whatnext.example(1)
    before = m.to_toml()
    m2 = m.set("masses.sandbag", 1.5)
    assert m.to_toml() == before and m.inputs["masses.sandbag"] == 0.6
    assert m2.inputs["masses.sandbag"] == 1.5


def test_machine_from_keys():
    dotted = whatnext.machine({"geometry.rope_length": 0.62, "start.sandbag_height": 0.5})
    sections = whatnext.machine(geometry={"rope_length": 0.62}, start={"sandbag_height": 0.5})
    assert dotted.to_toml() == sections.to_toml()
    # Every key not given takes its default, the paper's example 1 (docs/inputs.md), whose file
    # differs from the defaults only in run.t_max.
    assert whatnext.machine({"run.t_max": 2.0}).to_toml() == whatnext.example(1).to_toml()
    assert set(whatnext.input_keys()) >= {"geometry.rope_length", "run.impact_law", "radio.enabled"}


def test_to_toml_round_trip(tmp_path):
    run = whatnext.simulate(whatnext.example(2).set("masses.sandbag", 0.9), samples=False)
    path = tmp_path / "m.toml"
    path.write_text(run.to_toml())
    run_cli(["run", path, "--events", tmp_path / "e.json", "-q"])
    again = json.loads((tmp_path / "e.json").read_text())
    assert again["outcome"]["type"] == run.outcome.type
    assert abs(again["outcome"]["t"] - run.outcome.time) < 1e-9  # to_toml: "round trip up to rounding"


def test_sample_columns_are_numpy_arrays():
    run = whatnext.simulate(whatnext.example(1))
    s = run.samples
    n = len(s["t_s"])
    assert n > 800  # 0.82 s at 1 ms, plus a row per event
    for name, col in s.items():
        assert isinstance(col, np.ndarray) and col.ndim == 1 and col.shape == (n,), name
        assert col.flags.c_contiguous, name
    assert s["t_s"].dtype == np.float64 and s["phi_l_deg"].dtype == np.float64
    assert s["rope_taut"].dtype == np.bool_
    assert s["event"].dtype.kind == "U" and s["mode"].dtype == np.dtype("<U2")
    # The numbers are the C++ buffers themselves, adopted by numpy, not copies made in Python.
    assert not s["x_m"].flags.owndata and s["x_m"].base is not None
    assert np.all(np.diff(s["t_s"]) >= 0)
    assert list(s["event"][s["event"] != ""]) == [e.type for e in run.events]
    assert whatnext.simulate(whatnext.example(1), samples=False).samples is None


# Bad input: each Python call and the command line given the same input say the same line.
ERROR_CASES = [
    (lambda: whatnext.example(1).set("geometry.rope_length", 0.1), ["--example", 1, "--set", "geometry.rope_length=0.1"]),
    (lambda: whatnext.example(1).set("geometry.rope_lenght", 1), ["--example", 1, "--set", "geometry.rope_lenght=1"]),
    (lambda: whatnext.example(2).set("run.impact_law", "elastic"), ["--example", 2, "--set", "run.impact_law=elastic"]),
    (lambda: whatnext.example(1).set("start.lid_angle", 95), ["--example", 1, "--set", "start.lid_angle=95"]),
    (lambda: whatnext.example(1).set("masses.lid", -0.5), ["--example", 1, "--set", "masses.lid=-0.5"]),
    (lambda: whatnext.example(1).set("run.t_max", float("inf")), ["--example", 1, "--set", "run.t_max=inf"]),
    (lambda: whatnext.example(1).set("radio.enabled", "yes"), ["--example", 1, "--set", "radio.enabled=yes"]),
    (lambda: whatnext.example(1).set("radio.switch_offset", [0.5]), ["--example", 1, "--set", "radio.switch_offset=[0.5]"]),
    (lambda: whatnext.simulate(whatnext.example(3), output_step=1e-9), ["--example", 3, "--set", "run.output_step=1e-09"]),
    (lambda: whatnext.example(5), ["--example", 5]),
    (lambda: whatnext.load("no/such/machine.toml"), ["no/such/machine.toml"]),
]


@pytest.mark.parametrize("call,args", ERROR_CASES)
def test_errors_raise_the_cli_message(call, args):
    proc = run_cli(["run", *args], check=False)
    assert proc.returncode == 2 and proc.stdout == ""
    with pytest.raises(whatnext.InputError) as err:
        call()
    assert proc.stderr == f"whatnext: error: {err.value}\n"
    assert isinstance(err.value, ValueError)


def test_bad_files_raise_the_cli_message(tmp_path):
    cases = {"bad.toml": "[geometry]\nrope_length = = 1\n",
             "unknown.toml": "[geometry]\nrope_length = 1.0\nhinge_distanse = 0.8\n",
             "short.inp": "0.5\n-0.3\n-35\n"}
    for name, text in cases.items():
        path = tmp_path / name
        path.write_text(text)
        proc = run_cli(["run", path], check=False)
        with pytest.raises(whatnext.InputError) as err:
            whatnext.load(path)
        assert proc.returncode == 2 and proc.stderr == f"whatnext: error: {err.value}\n", name


def test_exception_types():
    assert issubclass(whatnext.InputError, ValueError)
    assert issubclass(whatnext.SimulationError, RuntimeError)
    with pytest.raises(TypeError):
        whatnext.example(1).set("geometry.rope_length", object())


def test_the_stub_matches_the_compiled_module():
    # _core.pyi (what editors and type checkers read) names every function, class and constant of
    # the compiled module with the arguments pybind11 reports (the first line of each docstring).
    import ast
    import pathlib
    import re

    from whatnext import _core

    stub = ast.parse(pathlib.Path(_core.__file__).with_name("_core.pyi").read_text())
    functions = {n.name: n for n in stub.body if isinstance(n, ast.FunctionDef)}
    classes = {n.name: n for n in stub.body if isinstance(n, ast.ClassDef)}
    constants = {n.target.id for n in stub.body if isinstance(n, ast.AnnAssign)}
    assert {n for n in dir(_core) if not n.startswith("_")} == set(functions) | set(classes) | constants

    def arguments(doc):  # "name(a: T, b: U) -> R" -> ["a", "b"]
        line = doc.splitlines()[0]
        return re.findall(r"(\w+): ", line[line.index("(") + 1:line.rindex(")")])

    for name, node in functions.items():
        assert [a.arg for a in node.args.args] == arguments(getattr(_core, name).__doc__), name
    handle = classes["MachineHandle"]
    for node in handle.body:
        if isinstance(node, ast.FunctionDef):
            assert [a.arg for a in node.args.args] == arguments(getattr(_core.MachineHandle, node.name).__doc__), node.name
        else:
            assert isinstance(getattr(_core.MachineHandle, node.target.id), property), node.target.id
    for name in ("InputError", "SimulationError"):
        base = classes[name].bases[0].id
        assert issubclass(getattr(_core, name), {"ValueError": ValueError, "RuntimeError": RuntimeError}[base])


@pytest.mark.parametrize("page", ["README.md", "docs/python.md"])
def test_the_documented_python_runs(page, tmp_path, monkeypatch):
    # A student copies the examples of the page in order into one session: each must run (the
    # InputError example must raise exactly that), and the comments' outcomes must be what it says.
    import pathlib
    import re

    import matplotlib
    matplotlib.use("Agg")
    text = (pathlib.Path(__file__).resolve().parents[2] / page).read_text()
    monkeypatch.chdir(tmp_path)
    space = {}
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks
    for block in blocks:
        if block.startswith(">>> "):  # an interactive session: the call and what it prints
            call, shown = block[4:].split("\n", 1)
            with pytest.raises(whatnext.InputError) as err:
                exec(call, {"whatnext": whatnext})
            assert shown.strip() == f"whatnext.InputError: {err.value}"
            continue
        exec(compile(block, page, "exec"), space)
    assert space["run"].outcome.sentence == "lid open at 0.820 s"  # as the comments say

"""The Python module against the command line: the same input gives the same events (to the last
bit), the same samples (the CSV's columns at the CSV's precision), the same timeline and JSON,
and the same one-line error messages."""

import json
import signal

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


def test_the_built_machine_equals_the_cli(tmp_path):
    # The students' machine (issue 19): its floor, stop and switch, and the stop's and floor's
    # impulses in the samples and events, as the command line has them.
    konstanz = EXAMPLES / "konstanz.toml"
    stdout, events_text, table = cli_run(tmp_path, [konstanz])
    run = whatnext.simulate(whatnext.load(konstanz))
    assert whatnext.example("konstanz").to_toml() == whatnext.load(konstanz).to_toml()
    assert run.outcome.type == "switch_stays_off"  # a real party balloon (docs/extensions.md)
    assert run.event("sandbag_at_stop").impulses["stop_N_s"] > 0.0
    assert "impulse_floor_seesaw_N_s" in run.samples
    assert "impulse_stop_N_s" not in whatnext.simulate(whatnext.example(1)).samples  # the paper's has 3
    assert_same_run(run, stdout, events_text, table)


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


# Bad input: each Python call and the command line given the same input say the same line, but
# where the command names its --set, Python names the call that gave the value.
ERROR_CASES = [
    (lambda: whatnext.example(1).set("geometry.rope_length", 0.1), ["--example", 1, "--set", "geometry.rope_length=0.1"],
     "set('geometry.rope_length', 0.1)"),
    (lambda: whatnext.example(1).set("geometry.rope_lenght", 1), ["--example", 1, "--set", "geometry.rope_lenght=1"],
     "set('geometry.rope_lenght', 1)"),
    (lambda: whatnext.example(2).set("run.impact_law", "elastic"), ["--example", 2, "--set", "run.impact_law=elastic"],
     "set('run.impact_law', 'elastic')"),
    (lambda: whatnext.example(1).set("start.lid_angle", 95), ["--example", 1, "--set", "start.lid_angle=95"],
     "set('start.lid_angle', 95)"),
    (lambda: whatnext.example(1).set("masses.lid", -0.5), ["--example", 1, "--set", "masses.lid=-0.5"],
     "set('masses.lid', -0.5)"),
    (lambda: whatnext.example(1).set("run.t_max", float("inf")), ["--example", 1, "--set", "run.t_max=inf"],
     "set('run.t_max', inf)"),
    (lambda: whatnext.example(1).set("radio.enabled", "yes"), ["--example", 1, "--set", "radio.enabled=yes"],
     "set('radio.enabled', 'yes')"),
    (lambda: whatnext.example(1).set("radio.switch_offset", [0.5]), ["--example", 1, "--set", "radio.switch_offset=[0.5]"],
     "set('radio.switch_offset', (0.5,))"),
    (lambda: whatnext.simulate(whatnext.example(3), output_step=1e-9), ["--example", 3, "--set", "run.output_step=1e-09"],
     "simulate(output_step=1e-09)"),
    (lambda: whatnext.load("no/such/machine.toml"), ["no/such/machine.toml"], None),
]


@pytest.mark.parametrize("call,args,python_call", ERROR_CASES)
def test_errors_raise_the_cli_message(call, args, python_call):
    proc = run_cli(["run", *args], check=False)
    assert proc.returncode == 2 and proc.stdout == ""
    with pytest.raises(whatnext.InputError) as err:
        call()
    cli = proc.stderr.removeprefix("whatnext: error: ").removesuffix("\n")
    if python_call is not None:
        assert cli.startswith("--set")
        cli = python_call + cli[cli.index(":"):]
    assert str(err.value) == cli
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


# --- Ctrl-C, pickle and copy, read-only columns, messages in Python's words (issue 22) ----------

SLOW_RUN = """
import sys, time
import whatnext
# About 10^8 Euler steps: half a minute of work, ended by SIGINT long before.
m = whatnext.example(3).set({"run.integrator": "euler", "run.step": 1e-7, "run.t_max": 10.0, "run.output_step": 0.01})
print("running", flush=True)
try:
    whatnext.simulate(m, samples=sys.argv[1] == "samples")
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
    sys.exit(3)
print("finished", flush=True)
"""


@pytest.mark.parametrize("samples", ["samples", "events-only"])
def test_ctrl_c_stops_simulate(samples):
    # SIGINT to a process in a long simulate(): it must end with KeyboardInterrupt at once, not when
    # the run is done (half a minute later). The time is from the signal to the process's exit,
    # interpreter shutdown too: about 0.1 s, but 0.56 s once with the machine's two cores busy, so
    # the bound is 2 s, still a fifteenth of the run.
    import subprocess
    import sys
    import time

    proc = subprocess.Popen([sys.executable, "-c", SLOW_RUN, samples], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "running"
        time.sleep(0.5)  # well inside the run
        t0 = time.perf_counter()
        proc.send_signal(signal.SIGINT)
        out, _ = proc.communicate(timeout=20)
        elapsed = time.perf_counter() - t0
    finally:
        proc.kill()
    assert out.strip() == "KeyboardInterrupt" and proc.returncode == 3
    assert elapsed < 2.0, f"simulate() took {elapsed:.2f} s to stop after Ctrl-C"


def test_runs_without_samples_have_the_same_events():
    # samples=False runs with an observer (for Ctrl-C) sampled only at the start and the end: the
    # events must be those of the run with samples, to the last bit.
    for m in (whatnext.example(1), whatnext.example(4), whatnext.example(3).set("run.integrator", "rk4")):
        a, b = whatnext.simulate(m), whatnext.simulate(m, samples=False)
        assert a.events == b.events and a.outcome == b.outcome and a.timeline() == b.timeline()


def test_machines_and_runs_pickle_and_copy(tmp_path):
    import copy
    import pickle

    path = tmp_path / "mäschine.toml"
    path.write_text((EXAMPLES / "example2.toml").read_text())
    machines = [whatnext.example(1), whatnext.load(path).set({"masses.sandbag": 0.9, "radio.enabled": True}),
                whatnext.machine(geometry={"hinge_offset": (0.713, 0.363)}), whatnext.example("radio")]
    for m in machines:
        for again in (pickle.loads(pickle.dumps(m)), copy.copy(m), copy.deepcopy(m)):
            assert isinstance(again, whatnext.Machine)
            assert (again.to_toml(), again.source, again.inputs) == (m.to_toml(), m.source, m.inputs)
        # The unpickled machine names its values as before: a rule broken later says where it came from.
        with pytest.raises(whatnext.InputError) as a:
            m.set("geometry.rope_length", 0.1)
        with pytest.raises(whatnext.InputError) as b:
            pickle.loads(pickle.dumps(m)).set("geometry.rope_length", 0.1)
        assert str(a.value) == str(b.value)
    run = whatnext.simulate(machines[1].set("run.t_max", 2.0))
    for again in (pickle.loads(pickle.dumps(run)), copy.copy(run), copy.deepcopy(run)):
        assert again.events == run.events and again.outcome == run.outcome
        assert again.timeline() == run.timeline() and again.to_toml() == run.to_toml()
        assert list(again.samples) == list(run.samples)
        for name, column in run.samples.items():
            assert np.array_equal(again.samples[name], column), name
            assert not again.samples[name].flags.writeable, name
    # A file that no longer exists is no matter: the machine carries its values.
    blob = pickle.dumps(machines[1])
    path.unlink()
    assert pickle.loads(blob).to_toml() == machines[1].to_toml()


def test_sample_columns_are_read_only():
    run = whatnext.simulate(whatnext.example(1))
    for name, column in run.samples.items():
        with pytest.raises(ValueError, match="read-only"):
            column[0] = column[1]
    mine = np.array(run.samples["x_m"])  # a copy is the user's to change
    mine[0] = 1.0


def python_words(call, expected_start):
    """The InputError of call(): one line, in Python's words (never the command line's)."""
    with pytest.raises(whatnext.InputError) as err:
        call()
    text = str(err.value)
    assert text.startswith(expected_start), text
    assert "--set" not in text and "Invoked with" not in text and "\n" not in text
    return text


def test_messages_in_python_words():
    m = whatnext.example(1)
    python_words(lambda: m.set("geometry.rope_length", 0.1),
                 "set('geometry.rope_length', 0.1): geometry.rope_length is shorter than")
    python_words(lambda: m.set("geometry.rope_lenght", 1),
                 "set('geometry.rope_lenght', 1): unknown key 'geometry.rope_lenght' (did you mean 'geometry.rope_length'?)")
    python_words(lambda: m.set({"masses.lid": -0.5}), "set('masses.lid', -0.5): masses.lid")
    python_words(lambda: m.set("radio.enabled", "yes"), "set('radio.enabled', 'yes'): radio.enabled must be true or false")
    python_words(lambda: m.set("run.impact_law", "elastic"), "set('run.impact_law', 'elastic'): ")
    python_words(lambda: whatnext.simulate(whatnext.example(3), output_step=1e-9), "simulate(output_step=1e-09): ")
    python_words(lambda: whatnext.machine({"start.lid_angle": 95}), "machine({'start.lid_angle': 95}): start.lid_angle")
    python_words(lambda: whatnext.machine(masses={"lid": 0}), "machine({'masses.lid': 0}): masses.lid")
    # numpy values: a 0-d array is a number, numpy scalars are numbers, named as plain Python.
    assert m.set("geometry.rope_length", np.array(0.7)).inputs["geometry.rope_length"] == 0.7
    assert m.set("geometry.rope_length", np.float32(0.75)).inputs["geometry.rope_length"] == float(np.float32(0.75))
    python_words(lambda: m.set("geometry.rope_length", np.array(0.1)), "set('geometry.rope_length', 0.1): ")
    python_words(lambda: m.set("geometry.rope_length", 2**70), "set('geometry.rope_length', 1180591620717411303424): ")
    python_words(lambda: m.set("masses.lid", float("nan")), "set('masses.lid', nan): masses.lid must be a finite number")
    python_words(lambda: m.set("run.impact_law", "rope\nx"), "run.impact_law: the text must be one line")


@pytest.mark.parametrize("call,words", [
    (lambda: whatnext.example(1).set("geometry.rope_length", 0.7 + 0.1j), "geometry.rope_length: a real number"),
    (lambda: whatnext.example(1).set("geometry.rope_length", np.complex128(0.7)), "geometry.rope_length: a real number"),
    (lambda: whatnext.example(1).set("geometry.hinge_offset", (0.7, 1j)), "geometry.hinge_offset"),
    (lambda: whatnext.example(1).set("geometry.rope_length", object()), "geometry.rope_length: a number"),
    (lambda: whatnext.example(1).set("geometry.rope_length", b"0.7"), "geometry.rope_length: a number"),
    (lambda: whatnext.example(1).set(7, 0.7), "set(key, value): a key is text"),
    (lambda: whatnext.example(1).set({("a", "b"): 0.7}), "set(mapping): a key is text"),
    (lambda: whatnext.example(1).set("geometry.rope_length"), "set('geometry.rope_length', value): the value is missing"),
    (lambda: whatnext.example(1.9), "example(n): n is a whole number 1-4 or a name"),
    (lambda: whatnext.example(True), "example(n): n is a whole number"),
    (lambda: whatnext.example(None), "example(n): n is a whole number"),
    (lambda: whatnext.machine([("geometry.rope_length", 0.7)]), "machine(keys): a dict"),
    (lambda: whatnext.load(3), "load(path): a file name"),
    (lambda: whatnext.simulate(whatnext.example(1), t_max="long"), None),
    (lambda: whatnext.simulate(whatnext.example(1), t_max=1j), "run.t_max: a real number"),
])
def test_wrong_types_raise_type_error_naming_the_input(call, words):
    with pytest.raises(TypeError) if words else pytest.raises(whatnext.InputError) as err:
        call()
    text = str(err.value)
    if words:
        assert text.startswith(words), text
    else:
        assert text.startswith("simulate(t_max='long'): run.t_max must be a number"), text
    assert "Invoked with" not in text and "--set" not in text


def test_examples_by_number_and_by_name():
    python_words(lambda: whatnext.example(2**70), "example(1180591620717411303424): the paper has examples 1 to 4")
    python_words(lambda: whatnext.example(5), "example(5): the paper has examples 1 to 4")
    python_words(lambda: whatnext.example(0), "example(0): ")
    python_words(lambda: whatnext.example("radoi"), "example('radoi'): no shipped machine of that name (did you mean 'radio'?)")
    assert whatnext.example(np.int64(2)).to_toml() == whatnext.example(2).to_toml()
    # Every machine file of examples/ ships with the module, by name; "radio" is example1-radio.
    names = whatnext.examples()
    assert {"radio", "example1", "example2", "example3", "example4", "example1-radio"} <= set(names)
    assert {p.stem for p in EXAMPLES.glob("*.toml")} <= set(names)
    for p in EXAMPLES.glob("*.toml"):
        assert whatnext.example_path(p.stem).read_bytes() == p.read_bytes()
        assert whatnext.example(p.stem).to_toml() == whatnext.load(p).to_toml()
    assert whatnext.example("example2").to_toml() == whatnext.example(2).to_toml()
    radio = whatnext.example("radio")
    assert radio.source == "example1-radio.toml"
    assert whatnext.simulate(radio, samples=False).outcome.type == "radio_on"


def test_event_of_an_unknown_name_raises():
    run = whatnext.simulate(whatnext.example(1), samples=False)
    assert run.event("radio_on") is None  # a real event this run did not have
    python_words(lambda: run.event("lid_opn"), "event('lid_opn'): no event is called that (did you mean 'lid_open'?)")
    with pytest.raises(TypeError):
        run.event(3)

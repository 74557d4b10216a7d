"""The notebooks of examples/ run from top to bottom (nbconvert, Debian's Python and kernel) from a
folder of their own, as a copy handed out to a class would: their asserts check the paper's numbers
and equations, and their figures must appear."""

import json
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

from conftest import EXAMPLES, ROOT

NOTEBOOK = EXAMPLES / "whatnext.ipynb"
STUDENTS, TEACHER = EXAMPLES / "students.ipynb", EXAMPLES / "students-teacher.ipynb"


def execute(notebook: pathlib.Path, folder: pathlib.Path):
    """Copies the notebook alone into folder and runs it there; its cells' outputs."""
    folder.mkdir()
    copy = folder / notebook.name
    shutil.copy(notebook, copy)
    env = dict(os.environ)
    env.pop("MPLBACKEND", None)  # the kernel's inline backend, so that figures become outputs
    env["PYTHONPATH"] = os.path.abspath(env.get("PYTHONPATH", ""))  # the kernel runs in that folder
    env["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # ipykernel's debugger warns about frozen modules
    proc = subprocess.run([sys.executable, "-m", "nbconvert", "--to", "notebook", "--execute",
                           "--ExecutePreprocessor.timeout=600", "--output", "executed", str(copy)],
                          cwd=folder, env=env, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-4000:]
    assert sorted(p.name for p in folder.iterdir()) == sorted({notebook.name, "executed.ipynb"})
    cells = json.loads((folder / "executed.ipynb").read_text())["cells"]
    outputs = [o for c in cells if c["cell_type"] == "code" for o in c["outputs"]]
    assert not [o for o in outputs if o["output_type"] == "error"]
    text = "".join("".join(o.get("text", "")) for o in outputs)
    figures = [o for o in outputs if "image/png" in o.get("data", {})]
    return text, figures


def test_the_notebook_runs_from_any_folder(tmp_path):
    text, figures = execute(NOTEBOOK, tmp_path / "handed-out")
    assert len(figures) >= 5  # Fig. 8, the samples, Fig. 9, the heat map, the radio
    assert "Without malfunctions the lid of Kermit's box is open" in text
    assert "tension: 0.0 N" not in text and "the rope's jerk" in text
    assert "of the kinetic energy" in text  # an impact's loss as a share of what it can lose


def test_the_first_cell_gives_a_command_the_project_installs():
    first = "".join(json.loads(NOTEBOOK.read_text())["cells"][0]["source"])
    assert "./run.sh notebook" in first
    script = (ROOT / "run.sh").read_text()
    assert "\n  notebook)\n" in script and "jupyter notebook" in script
    packages = (ROOT / "scripts" / "debian-packages.txt").read_text().split("\n")
    assert "jupyter-notebook" in packages and "python3-sympy" in packages


def test_the_students_notebook_runs_with_the_exercises_open(tmp_path):
    text, figures = execute(STUDENTS, tmp_path / "student")
    for n in (1, 3, 4):
        assert f"Exercise {n} is still open." in text
    assert "Exercises 1 and 2 are still open." in text
    assert len(figures) == 1


def test_the_teacher_s_copy_answers_every_exercise(tmp_path):
    # Its checks: the Lagrangian gives the paper's eqs. (3) and (4) (SymPy), these agree with the
    # simulator's accelerations at five states, the rope law loses that share of the free fall's
    # kinetic energy where the kinetic-energy law keeps it, and every landing time of a sweep is the
    # free fall's.
    text, figures = execute(TEACHER, tmp_path / "teacher")
    assert "still open" not in text
    for line in ("Both accelerations are the paper's eqs. (3) and (4).",
                 "The simulator moves by the paper's equations (3) and (4).",
                 "every landing time is the free fall's",
                 "kinetic energy lost at the pull: rope law"):
        assert line in text
    assert len(figures) == 1


def test_the_two_copies_differ_only_in_the_answers():
    student, teacher = (json.loads(p.read_text())["cells"] for p in (STUDENTS, TEACHER))
    assert len(student) == len(teacher)
    answers = 0
    for s, t in zip(student[1:], teacher[1:]):
        if "answer" in t.get("metadata", {}).get("tags", []):
            assert "exercise" in s["metadata"]["tags"] and "None" in "".join(s["source"])
            answers += 1
        else:
            assert s["source"] == t["source"]
    assert answers == 5


@pytest.mark.parametrize("notebook", [NOTEBOOK, STUDENTS, TEACHER])
def test_the_committed_notebooks_have_no_outputs(notebook):
    # Outputs (figures as base64) would bloat the repository and go stale; the tests above make them.
    cells = json.loads(notebook.read_text())["cells"]
    for c in cells:
        if c["cell_type"] == "code":
            assert c["outputs"] == [] and c["execution_count"] is None


@pytest.mark.parametrize("notebook", [NOTEBOOK, STUDENTS, TEACHER])
def test_the_notebooks_point_to_the_impact_question_and_the_lesson(notebook):
    # Which impact law is right (a rope that stretches) and the lesson built on the same jerk.
    cells = json.loads(notebook.read_text())["cells"]
    text = "".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
    for page in ("docs/impact.md", "docs/teaching.md"):
        assert page in text and (ROOT / page).is_file()

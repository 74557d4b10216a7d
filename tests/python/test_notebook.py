"""examples/whatnext.ipynb runs from top to bottom (nbconvert, Debian's Python and kernel), so it
never goes stale: its own asserts check the paper's numbers, and its figures must appear."""

import json
import os
import subprocess
import sys

from conftest import EXAMPLES

NOTEBOOK = EXAMPLES / "whatnext.ipynb"


def test_the_notebook_runs(tmp_path):
    env = dict(os.environ)
    env.pop("MPLBACKEND", None)  # the kernel's inline backend, so that figures become outputs
    env["PYTHONPATH"] = os.path.abspath(env.get("PYTHONPATH", ""))  # the kernel runs in examples/
    env["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # ipykernel's debugger warns about frozen modules
    proc = subprocess.run([sys.executable, "-m", "nbconvert", "--to", "notebook", "--execute",
                           "--ExecutePreprocessor.timeout=600", "--output-dir", str(tmp_path),
                           "--output", "executed", str(NOTEBOOK)],
                          env=env, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr[-4000:]
    cells = json.loads((tmp_path / "executed.ipynb").read_text())["cells"]
    outputs = [o for c in cells if c["cell_type"] == "code" for o in c["outputs"]]
    assert not [o for o in outputs if o["output_type"] == "error"]
    figures = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(figures) >= 5  # Fig. 8, the samples, Fig. 9, the heat map, the radio
    text = "".join("".join(o.get("text", "")) for o in outputs)
    assert "Without malfunctions the lid of Kermit's box is open" in text


def test_the_committed_notebook_has_no_outputs():
    # Outputs (figures as base64) would bloat the repository and go stale; the test above makes them.
    cells = json.loads(NOTEBOOK.read_text())["cells"]
    for c in cells:
        if c["cell_type"] == "code":
            assert c["outputs"] == [] and c["execution_count"] is None

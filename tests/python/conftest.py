"""Shared pieces of the Python tests: where the command line is, and how to run it.

CTest sets WHATNEXT_CLI and PYTHONPATH (tests/CMakeLists.txt); by hand:
    PYTHONPATH=build/python WHATNEXT_CLI=build/whatnext /usr/bin/python3 -m pytest tests/python
"""

import csv
import os
import pathlib
import subprocess
from typing import List

import pytest


ROOT = pathlib.Path(__file__).resolve().parents[2]
CLI = os.environ.get("WHATNEXT_CLI", str(ROOT / "build" / "whatnext"))
EXAMPLES = ROOT / "examples"


def run_cli(args: List[str], cwd=None, check: bool = True) -> subprocess.CompletedProcess:
    """The whatnext command with these arguments; its stdout, stderr and exit code."""
    proc = subprocess.run([CLI, *map(str, args)], cwd=cwd, capture_output=True, text=True)
    if check and proc.returncode != 0:
        raise AssertionError(f"whatnext {' '.join(map(str, args))} failed ({proc.returncode}): {proc.stderr}")
    return proc


def read_csv(path):
    """A CSV file as its header and its rows of text fields."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


@pytest.fixture(scope="module")
def dask_cluster():
    """A local Dask cluster and its client: two worker processes of one thread each, as a small
    cluster would have, so that the machines, the module and the results cross process boundaries
    by pickle, as over a network."""
    import logging

    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                      silence_logs=logging.CRITICAL) as cluster, Client(cluster) as client:
        yield cluster, client

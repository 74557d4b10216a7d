#!/usr/bin/python3
"""Regenerates the pictures docs/python.md and the README show, with the Python module itself:
example 1's Fig. 8 as run.plot() draws it, and a sweep's heat map.
Usage (after building): PYTHONPATH=build/python /usr/bin/python3 scripts/make-python-images.py
"""
import pathlib

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

import whatnext  # noqa: E402

img = pathlib.Path(__file__).resolve().parents[1] / "docs" / "img"
# The PNG's metadata would name the matplotlib version; without it the bytes depend on the figure only.
meta = {"Software": None}

run = whatnext.simulate(whatnext.example(1))
run.plot().savefig(img / "python-figure8.png", dpi=80, metadata=meta)

sweep = whatnext.sweep(whatnext.example(2), {"geometry.rope_length": np.linspace(0.62, 1.0, 39),
                                             "masses.sandbag": np.linspace(0.2, 2.0, 37)})
sweep.plot("lid_open").savefig(img / "python-sweep.png", dpi=80, metadata=meta)
print("wrote", img / "python-figure8.png", "and", img / "python-sweep.png")

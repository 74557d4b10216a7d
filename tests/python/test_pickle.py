"""Every public type of the whatnext package pickles at every protocol (0 to 5) and comes back the
same, or raises a Python exception; it never aborts the interpreter (a Jupyter kernel would die).

Each type and protocol runs in a child interpreter, so that an abort fails one test instead of
killing pytest; the child compares the copy with the original itself and says what differs.
"""

import os
import pickle
import subprocess
import sys

import pytest

import whatnext

# The public names of the package that are types (classes and exceptions), listed from the
# package itself so that a type added later is tested too.
TYPES = sorted(name for name in whatnext.__all__ if isinstance(getattr(whatnext, name), type))

# For each type: an object of it, and the check that its copy is the same. The check is written
# for the child interpreter: `obj` and `copy` are defined there.
MAKE = {
    "Machine": "whatnext.example(1).set('geometry.rope_length', 0.7)",
    "Run": "whatnext.simulate(whatnext.example(1).set('radio.enabled', True), output_step=0.01)",
    "Event": "whatnext.simulate(whatnext.example(2), samples=False).event('rope_taut')",
    "Outcome": "whatnext.simulate(whatnext.example(1), samples=False).outcome",
    "Sweep": "whatnext.sweep(whatnext.example(2), {'geometry.rope_length': whatnext.grid(0.62, 0.7, 3), "
             "'masses.sandbag': whatnext.grid(0.5, 1.0, 2)})",
    "InputError": "whatnext.InputError('set(\\'masses.lid\\', -0.5): masses.lid must be > 0 kg')",
    "SimulationError": "whatnext.SimulationError('the integrator ran out of steps at t = 1 s')",
}
SAME = {
    "Machine": "copy.to_toml() == obj.to_toml() and copy.source == obj.source and copy.inputs == obj.inputs",
    "Run": "copy.timeline() == obj.timeline() and copy.events_json() == obj.events_json() "
           "and copy.events == obj.events and copy.outcome == obj.outcome "
           "and copy.to_toml() == obj.to_toml() and sorted(copy.samples) == sorted(obj.samples) "
           "and all(np.array_equal(copy.samples[k], obj.samples[k]) for k in obj.samples) "
           "and not any(c.flags.writeable for c in copy.samples.values())",
    "Event": "copy == obj",
    "Outcome": "copy == obj and type(copy) is type(obj)",
    "Sweep": "copy.to_csv() == obj.to_csv() and copy.shape == obj.shape and list(copy) == list(obj) "
             "and not any(c.flags.writeable for c in copy.columns.values())",
    "InputError": "type(copy) is type(obj) and str(copy) == str(obj) and isinstance(copy, ValueError)",
    "SimulationError": "type(copy) is type(obj) and str(copy) == str(obj) and isinstance(copy, RuntimeError)",
}

CHILD = """
import pickle, sys
import numpy as np
import whatnext
obj = {make}
assert type(obj).__name__ == {name!r}, type(obj)
copy = pickle.loads(pickle.dumps(obj, protocol={protocol}))
again = pickle.loads(pickle.dumps(copy, protocol={protocol}))  # a copy pickles too
if not ({same}):
    sys.exit("the copy differs from the original")
print("same")
"""


def test_every_public_type_is_tested():
    assert set(TYPES) == set(MAKE), "a public type without an object to pickle in this test"


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
@pytest.mark.parametrize("name", TYPES)
def test_pickle_round_trip_in_a_child(name, protocol):
    code = CHILD.format(make=MAKE[name], name=name, protocol=protocol, same=SAME[name])
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ))
    assert proc.returncode >= 0, f"{name} at protocol {protocol} killed the interpreter (signal " \
                                 f"{-proc.returncode}): {proc.stderr.strip()[-300:]}"
    assert proc.returncode == 0 and proc.stdout.strip() == "same", \
        f"{name} at protocol {protocol}: {proc.stderr.strip()[-500:]}"

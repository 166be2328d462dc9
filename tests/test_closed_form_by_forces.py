"""The closed form is used only where it covers every force present: each force switched on alone
and in pairs, in a single-mass scene, from the command line.

A force says itself whether the closed form m x'' + b x' + k x = F0 cos(ω t) under gravity covers
it (Force.closed_form, physics/forces/). Where every force present is covered, the JSON's "exact"
must agree with a fine rk4 run (so the closed form chosen is the right one); where one is not,
"exact" is null and the note names that force by its label. The cases are made from the forces'
own declarations (each switch constant given a value), so a force added later is tried too.
"""
from __future__ import annotations

import itertools
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from physics.forces import FORCES

ROOT = Path(__file__).resolve().parent.parent

# A value for each switch of the page's scenes, in range, small enough that a 2 s run stays on the
# spring's line: the drive pushes along the spring (y), drag and friction are gentle.
VALUES = {"g": 9.8, "b": 1.5, "C": 0.5, "A": 0.1, "rho": 1.2, "F0": 5.0, "mu_s": 0.2, "mu_k": 0.1}
EXTRA = {"F0": {"omega": 3.0, "drive_axis": (0.0, 1.0, 0.0)}}   # the drive's other constants
NEEDS = {"mu_s": {"g": 9.8}}                                     # friction's load, N = m g


def switches(cls) -> dict:
    """The constants that switch the force on, with values (none for a force always on: the spring)."""
    names = [name for name, declared in cls.CONSTANTS.items() if declared.switch]
    values = {}
    for name in names:
        values[name] = VALUES.get(name, 0.5)
        values.update(EXTRA.get(name, {}))
        values.update(NEEDS.get(name, {}))
    if "mu_s" in values:
        values.setdefault("mu_k", VALUES["mu_k"])
    return values


def takes_switches(cls) -> bool:
    """Whether a single-mass scene can switch the force on from its constants (friction cannot:
    no single-mass scene has a table, tests/test_friction.py checks that it says so)."""
    try:
        return cls.switched_on(**switches(cls)) is not None
    except ValueError:
        return False


SWITCHED = {cls.LABEL: switches(cls) for cls in FORCES
            if cls.LABEL and any(d.switch for d in cls.CONSTANTS.values()) and takes_switches(cls)}
CASES = [(label,) for label in SWITCHED] + list(itertools.combinations(SWITCHED, 2))


def cli_json(*sets) -> dict:
    args = [item for name, value in sets for item in
            ("--set", f"{name}={','.join(map(str, value)) if isinstance(value, tuple) else value}")]
    done = subprocess.run([sys.executable, str(ROOT / "main.py"), "vertical", "--headless", "--json",
                           "--set", "g=0", "--set", "until=2", "--set", "dt=0.001", "--integrator", "rk4", *args],
                          capture_output=True, text=True, cwd=ROOT, timeout=300,
                          env={**os.environ, "SPRING_SCENES": ""})
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_the_cases_cover_every_force_that_can_be_switched():
    assert {"gravity", "damping", "drag", "driving"} <= set(SWITCHED)


@pytest.mark.parametrize("labels", CASES, ids=lambda labels: "+".join(labels))
def test_the_closed_form_only_where_it_covers_every_force_present(labels):
    values = {}
    for label in labels:
        values.update(SWITCHED[label])
    out = cli_json(*values.items())
    present = {cls.LABEL for cls in FORCES if cls.LABEL in SWITCHED and
               all(out["constants"].get(name, {}).get("value") not in (None, 0, 0.0)
                   for name, declared in cls.CONSTANTS.items() if declared.switch)}
    assert set(labels) <= present | {"gravity"}        # a force's load may bring gravity's g along
    exact = out.get("exact")
    if "drag" in present:                               # quadratic drag has no closed form
        assert exact is None
    if present <= {"gravity", "damping", "driving"}:     # the oscillator's own terms: it has one
        assert exact is not None, out["notes"]
    if exact is None:                                   # the note names a force present that has none
        notes = " ".join(out["notes"])
        assert any(f"no closed form with {label}" in notes for label in present), notes
    else:
        # the closed form chosen is the motion: a rk4 run at Δt = 1 ms agrees to well under a µm
        assert np.allclose(out["r"], exact["r"], atol=1e-7) and np.allclose(out["v"], exact["v"], atol=1e-6)


def test_drag_on_one_ball_of_two_leaves_the_other_its_closed_form():
    """A row is judged mass by mass (Force.acts_on): drag acts on the right ball only, whose exact
    answer is null with a note naming drag."""
    done = subprocess.run([sys.executable, str(ROOT / "main.py"), "drag", "--headless", "--json"],
                          capture_output=True, text=True, cwd=ROOT, timeout=300)
    out = json.loads(done.stdout)
    linear, quadratic = out["bodies"]
    assert linear["exact"]["error"]["r"] < 0.01 and "exact_note" not in linear
    assert quadratic["exact"] is None and quadratic["exact_note"] == "no closed form with drag"

"""docs/architecture.md's "Adding a force", followed literally: one new module in physics/forces/.

The project's code is copied to a temporary folder (the tree itself is never written), and one
file is added there, physics/forces/wind.py: a steady push of the wind, F = w x̂, declared as the
recipe says (law, LABEL, CONSTANTS with a default that switches it off, TERM and PROGRAM; no
closed form). Nothing else is edited. Then, in the copy:

- `vertical --set w=3` switches it on (a single-mass scene takes every force's constants), and the
  first momentum update has F_net along x of exactly w;
- `--json` has "exact": null with the note "no closed form with wind";
- the handed-out program writes its line, its constant with its unit and meaning, and names it
  on its arrows; the page's arrow label (export/arrows.py's force_name) is its LABEL;
- `--constants` lists it with its unit where it is set, and `--set w=-5000` is refused with its range.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("physics", "scenes", "export", "reports", "cli", "lab", "browser")

WIND = '''
"""A steady wind: a force in a module of its own."""
from dataclasses import dataclass

import numpy as np

from ..declared import Declared
from .base import Force


@dataclass(frozen=True, eq=False)
class Wind(Force):
    """A steady push of the wind along x.

    F = w x̂,  w in N (negative: it blows towards −x).
    """

    w: float = 0.0
    conservative = False
    uses_velocity = False
    LABEL = "wind"
    CONSTANTS = {"w": Declared("N", -1e3, 1e3, default=0.0, switch=True, slider_from_zero=True,
                               meaning="steady push of the wind along x")}
    TERM = "Fwind"
    PROGRAM = (("Fwind = vector({w}, 0, 0)", "wind: a steady push along x"),)

    def __call__(self, t, r, v, m):
        F = np.zeros_like(r, dtype=float)
        F[:, 0] = self.w
        return F
'''


@pytest.fixture(scope="module")
def project(tmp_path_factory) -> Path:
    copy = tmp_path_factory.mktemp("project")
    for package in PACKAGES:
        shutil.copytree(ROOT / package, copy / package, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "main.py", copy / "main.py")
    (copy / "physics" / "forces" / "wind.py").write_text(textwrap.dedent(WIND), encoding="utf-8")
    return copy


def main_py(project: Path, *args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(project / "main.py"), *args], capture_output=True, text=True,
                          cwd=project, timeout=300, env={**os.environ, "SPRING_SCENES": ""})


def test_set_switches_the_new_force_on_in_a_single_mass_scene(project):
    done = main_py(project, "vertical", "--set", "w=3", "--steps", "1", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    (first,) = json.loads(done.stdout)["step_table"]
    assert first["F_net"] == [3.0, -78.0, 0.0]          # the wind along x; −k(|L| − L0) + m g along y
    off = main_py(project, "vertical", "--headless", "--json")
    assert json.loads(off.stdout)["r"][0] == 0.0       # w = 0 by default: no wind, as before


def test_its_model_has_no_exact_answer_and_says_why(project):
    done = main_py(project, "vertical", "--set", "w=3", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["exact"] is None
    assert "exact_valid_until: null, no closed form with wind" in out["notes"]
    assert out["constants"]["w"] == {"value": 3.0, "unit": "N", "meaning": "steady push of the wind along x"}
    text = main_py(project, "vertical", "--set", "w=3", "--headless").stdout
    assert "exact: none (no closed form with wind)" in text


def test_the_program_writes_its_line_and_names_its_arrow(project):
    done = main_py(project, "vertical", "--set", "w=3", "--arrows", "forces", "--vpython", "-")
    assert done.returncode == 0, done.stderr
    program = done.stdout
    assert "Fwind = vector(w, 0, 0)" in program and "wind: a steady push along x" in program
    assert "Fnet = Fspring + Fgravity + Fwind" in program
    assert any(line.startswith("w = 3") and "N: steady push of the wind along x" in line
               for line in program.splitlines())
    assert '"wind"' in program                          # the label on its arrow
    label = subprocess.run([sys.executable, "-c", textwrap.dedent("""
        from export.arrows import force_name
        from scenes import catalog
        model = catalog.configure("vertical", assignments=["w=3"]).build()
        print([force_name(force) for force in model.forces])
    """)], capture_output=True, text=True, cwd=project, timeout=120)
    assert label.returncode == 0, label.stderr
    assert label.stdout.strip() == "['spring', 'gravity', 'wind']"


def test_its_range_and_unit_come_from_its_declaration(project):
    bad = main_py(project, "vertical", "--set", "w=-5000", "--headless")
    assert bad.returncode == 2
    (line,) = bad.stderr.strip().splitlines()
    assert "w must be from -1000 to 1000 N" in line
    listed = main_py(project, "vertical", "--set", "w=3", "--constants")
    assert listed.returncode == 0, listed.stderr
    assert any(line.split()[:1] == ["w"] and "N" in line for line in listed.stdout.splitlines())

"""A scene's per-mass rules are data that its build and the handed-out program both read.

A row of masses whose values follow a rule of the scene's constants (anchors `spacing` apart, b
growing along the row) declares that rule on its Model (Model.per_mass, scenes/_row.py's
MassLoop and MassList). The program writer writes the declared lists as they are: it tries no
expression with exec and holds no scene's constants, so a rule no scene of ours has (here
b·(i + 1) along a row, from a teacher's folder) is written as the rule, and the program, run,
reaches the engine's state; edit b in it and the whole row changes.
"""
from __future__ import annotations

import ast
import json
import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from scenes._constants import SCENE_CONSTANTS
from test_export import run_to_end, stand_in  # noqa: F401  (stand_in is a fixture)

ROOT = Path(__file__).resolve().parent.parent

LADDER = '''
"""A row of four hanging masses, each damped b more than the one before."""
import numpy as np

from physics.forces import Gravity, LinearDamping, Spring
from physics.state import make_state

from ._model import Model
from ._row import MassList, anchors_in_a_row, row_anchors, row_loop, row_starts, start_positions

# ---- constants: edit these (unit: meaning) ----
m = 1.0                    # kg: mass of each block
k = 16.0                   # N/m: spring constant of each spring
L0 = 1.0                   # m: relaxed length of each spring
g = 9.8                    # m/s²: strength of gravity
b = 0.75                   # kg/s: damping of the first mass; the i-th has b·(i + 1)
x0 = 0.3                   # m: start stretch below equilibrium
spacing = 0.8              # m: distance between neighbouring anchors along x
dt = 0.01                  # s: time step Δt
until = 2.0                # s: how long to run
# ---- end of constants ----

COUNT = 4


def build(*, m, k, L0, g, b, x0, spacing, dt, until):
    """Four hanging masses; b·(i + 1) for mass i, as the program's list says."""
    anchors = anchors_in_a_row(count=COUNT, spacing=spacing)
    r0 = start_positions(anchors=anchors, L0=L0, m=m, k=k, g=g, x0=x0)
    b_each = np.array([b * (i + 1) for i in range(COUNT)])
    loop = row_loop(count=COUNT)
    rule = MassList("b", "kg/s: each b more than the one before", each="b*(i + 1)")
    return Model(state=make_state(r=r0, m=m), dt=float(dt), until=float(until), anchors=anchors,
                 forces=(Spring(k=k, L0=L0, anchor=anchors), Gravity(g=g), LinearDamping(b=b_each)),
                 labels=tuple(f"b = {x:g} kg/s" for x in b_each),
                 per_mass=loop.then(row_anchors(loop, count=COUNT), row_starts(k=k), rule))


VIEW = {"support": "ceiling", "plot": "y", "exact": False}
'''


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("teacher_rows")
    (folder / "ladder.py").write_text(textwrap.dedent(LADDER), encoding="utf-8")
    return folder


def main_py(folder, *args):
    return subprocess.run([sys.executable, str(ROOT / "main.py"), "ladder", *args], capture_output=True,
                          text=True, cwd=ROOT, env={**os.environ, "SPRING_SCENES": str(folder)}, timeout=300)


def test_a_rule_no_scene_of_ours_has_is_written_as_the_rule(folder, stand_in, tmp_path):  # noqa: F811
    path = tmp_path / "ladder.py"
    written = main_py(folder, "--vpython", str(path), "--until", "2")   # it ends at the question time, 2 s
    assert written.returncode == 0, written.stderr
    text = path.read_text(encoding="utf-8")
    assert re.search(r"^    b_each\.append\(b\*\(i \+ 1\)\) +# kg/s: each b more than the one before$", text, re.M)
    assert re.search(r"^b = 0\.75 +# kg/s: damping of the first mass", text, re.M)
    assert "a = vector((i - 1.5)*spacing, 0, 0)" in text and "s_eq = L0 + m*g/k" in text
    headless = main_py(folder, "--headless", "--json")
    assert headless.returncode == 0, headless.stderr
    expected = json.loads(headless.stdout)
    answers = run_to_end(path, stand_in)
    assert len(answers) == 4
    for (t, r, p), r_engine, p_engine in zip(answers, expected["r"], expected["p"]):
        assert t == pytest.approx(expected["t"], rel=1e-12)
        assert np.allclose(r, r_engine, rtol=1e-12, atol=1e-12)
        assert np.allclose(p, p_engine, rtol=1e-12, atol=1e-12)
    # b edited in the program: the whole row follows, as --set b does for the engine
    path.write_text(re.sub(r"^b = 0\.75", "b = 2", text, flags=re.M), encoding="utf-8")
    edited = run_to_end(path, stand_in)
    again = json.loads(main_py(folder, "--set", "b=2", "--headless", "--json").stdout)
    for (t, r, p), r_engine in zip(edited, again["r"]):
        assert np.allclose(r, r_engine, rtol=1e-12, atol=1e-12)


def _code_words(path: Path) -> set[str]:
    """Every name and every word of a string in a module's code, leaving out docstrings and comments."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                  if isinstance(node, (ast.Module, ast.FunctionDef, ast.ClassDef)) and node.body
                  and isinstance(node.body[0], ast.Expr) and isinstance(node.body[0].value, ast.Constant)}
    words = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name):
            words.add(node.id)
        elif isinstance(node, ast.Attribute):
            words.add(node.attr)
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings:
            words |= set(re.findall(r"[A-Za-z_]\w*", node.value))
    return words


def test_the_program_writer_runs_no_expression_and_knows_no_scenes_constants():
    scene_only = set(SCENE_CONSTANTS) - {"m", "r0", "v0", "dt", "until", "count"}
    assert {"spacing", "x0", "under_fraction", "b_ratio", "omega_min", "curves"} <= scene_only
    for path in sorted((ROOT / "export").glob("*.py")):
        words = _code_words(path)
        assert "exec" not in words and "eval" not in words, path.name
        assert not words & scene_only, (path.name, words & scene_only)

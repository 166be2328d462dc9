"""Issue 26 item 1, the program's exact curve: export/ names no force's constant.

The closed form's parameters are roles (physics/exact.py Role: stiffness, natural length, anchor,
gravity, damping, drive amplitude, frequency and axis); each force declares which of its constants
holds each role (CLOSED_FORM), beside its law and its closed_form(). export/exact_curve.py finds the
program's constants through that declaration. Checked three ways: the declarations agree with the
laws' closed_form(); exact_curve.py holds no force constant's name as a string; and with every
role's constant renamed in the declaration, the exact lines follow the new names and nothing else
changes. (The handed-out programs are byte for byte as before: compared for every scene and
several --set, --preset and --scenario cases when this was built.)
"""
from __future__ import annotations

import ast
import re
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from export import exact_curve  # noqa: E402
from export.lines import COMMENT  # noqa: E402
from export.vpython_program import _Case  # noqa: E402
from physics.exact import ROLES, Role  # noqa: E402
from physics.forces import FORCES, Force, closed_form_constants, declared_constants  # noqa: E402
from physics.forces.page import Driving, Gravity, LinearDamping, Spring  # noqa: E402
from scenes import configure  # noqa: E402


def test_each_role_is_declared_by_the_force_whose_closed_form_gives_it():
    """A force's CLOSED_FORM names its own constants, for the very roles its closed_form() gives."""
    held = closed_form_constants(FORCES)
    assert sorted(held) == sorted(ROLES)
    forces = [Spring(k=3.0, L0=0.5), Gravity(g=9.8), LinearDamping(b=0.2),
              Driving(F0=1.0, omega=2.0, axis=(0.0, 1.0, 0.0))]
    for force in forces:
        assert set(force.closed_form()) == set(type(force).CLOSED_FORM), type(force).__name__
        for role, name in type(force).CLOSED_FORM.items():
            assert name in type(force).CONSTANTS
            # the value the law gives for the role is the constant's value the program writes
            assert np.array_equal(force.closed_form()[role], force.program_values().get(name, force.closed_form()[role]))
    # a force with no closed form declares no role
    for cls in FORCES:
        if cls.closed_form is Force.closed_form:
            assert cls.CLOSED_FORM == {}, cls.__name__


def test_exact_curve_spells_no_force_constant():
    """No string in export/exact_curve.py is the name of a force's constant (k, b, g, F0, ...)."""
    names = set(declared_constants())
    tree = ast.parse((ROOT / "export" / "exact_curve.py").read_text(encoding="utf-8"))
    spelled = sorted({node.value for node in ast.walk(tree)
                      if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in names})
    assert spelled == []


class Renamed:
    """The program's constants as a program whose force constants are called X_k, X_b, ...: the
    values are the same, only the names differ."""

    def __init__(self, constants, renamed: dict[str, str]):
        self.constants, self.back = constants, {new: old for old, new in renamed.items()}
        self.roles = {role: renamed[name] for role, name in constants.roles.items()}   # as CLOSED_FORM would say

    def has(self, name):
        return name in self.back and self.constants.has(self.back[name]) or \
            name not in self.back and name not in self.back.values() and self.constants.has(name)

    def each(self, name):
        return self.constants.each(self.back.get(name, name))

    def name(self, name):
        if name not in self.back:
            assert name not in self.back.values(), f"exact_curve asked for {name!r} by its name"
            return self.constants.name(name)
        return "X_" + self.constants.name(self.back[name])


def code_renamed(line: str, names) -> str:
    """The line with each force constant's name in its code (not its comment) prefixed by X_."""
    if line.lstrip().startswith("#"):
        return line
    code, comment_mark, comment = line.partition(COMMENT)
    pattern = r"\b(" + "|".join(map(re.escape, sorted(names, key=len, reverse=True))) + r")(?=_each\[|\b)"
    return re.sub(pattern, r"X_\1", code) + comment_mark + comment


@pytest.mark.parametrize("scene, values", [
    ("vertical", {}), ("damped", {}), ("driven", {}), ("driven", {"b": 0.0, "F0": 1.0, "omega": 5.0}),
    ("driven", {"b": 2.0}), ("regimes", {}), ("integrators", {}), ("damped", {"L0": 0.0}),
])
def test_the_exact_lines_follow_the_declared_constants(scene, values):
    setup = configure(scene).with_values(**values) if values else configure(scene)
    model = setup.build()
    case = _Case(setup, model, None)
    axis, m = case.axes[0], case.m
    original = exact_curve.exact_lines(model, case.constants, case.forces, axis=axis, m=m)
    assert original is not None
    declared = case.constants.roles       # the model's forces' CLOSED_FORM, read when the program is written
    renamed = {name: "X_" + name for name in declared.values()}
    followed = exact_curve.exact_lines(model, Renamed(case.constants, renamed), case.forces, axis=axis, m=m)
    assert followed is not None
    names = list(declared.values())
    assert [[code_renamed(line, names) for line in part] for part in original] == [list(part) for part in followed]
    assert any("X_" + declared[Role.STIFFNESS] in line for line in followed[0])

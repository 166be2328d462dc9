"""The program's named values: the constants block at its top, `k = 40  # N/m: spring constant`.

Every number comes from the scene's model (the force objects and the initial state), written with
repr, so the program starts from exactly the model's values. A name that is one of the scene's
constants, with the scene's value, keeps the comment of the scene's constants block; otherwise its
unit and meaning are those declared once, in DECLARED (scenes/_constants.py, which reads each
force's CONSTANTS). A value that differs between masses becomes a list (`b_each`).
"""
from __future__ import annotations

import re

import numpy as np

from physics.exact import Role
from physics.forces import closed_form_constants
from scenes import DECLARED, catalog

from .lines import CONSTANT_COLUMN, ProgramError, commented, number, unit_and_meaning, vector


class ProgramConstants:
    """The program's named values, from the model's numbers: one value, or one per mass.

    A name that is one of the scene's constants, with the scene's value, keeps the comment of the
    scene's constants block; otherwise its unit and meaning are DECLARED's.
    """

    def __init__(self, setup, count: int, forces=()):
        self.setup, self.count = setup, count
        # the constant holding each role of the closed form among the model's forces, as each
        # declares it (physics/forces/ CLOSED_FORM): read here, when a program is written, never at import
        self.roles: dict[str, str] = closed_form_constants(forces)
        self.single: dict[str, object] = {}       # name -> a float, or a 3-tuple for a vector
        self.per_mass: dict[str, np.ndarray] = {}  # name -> (count,) or (count, 3)
        self.meanings: dict[str, str] = {}         # name -> what the program means by it, where the scene's
                                                   # meaning does not fit (t_end, until beside it)

    def add(self, name: str, value, *, is_vector: bool = False, meaning: str | None = None) -> None:
        """Record a value of the model: one for all the masses, or one per mass where they differ;
        `meaning` (unit and meaning, `s: when the program stops`) replaces the scene's and DECLARED's
        comment."""
        if meaning is not None:
            self.meanings[name] = meaning
        array = np.asarray(value, dtype=float)
        rows = np.broadcast_to(array.reshape(-1, 3) if is_vector else array.reshape(-1),
                               (self.count, 3) if is_vector else (self.count,))
        varies = not np.all(rows == rows[0])
        value = rows.copy() if varies else (tuple(float(x) for x in rows[0]) if is_vector else float(rows[0]))
        before = self.per_mass.get(name, self.single.get(name))
        if before is not None and not np.array_equal(before, value):
            raise ProgramError(f"two forces use different values of {name}: the program cannot name both")
        (self.per_mass if varies else self.single)[name] = value

    def has(self, name: str) -> bool:
        return name in self.single or name in self.per_mass

    def each(self, name: str) -> np.ndarray:
        """The value of `name` for each mass: (count,), or (count, 3) for a vector."""
        if name in self.per_mass:
            return self.per_mass[name]
        value = np.asarray(self.single[name], dtype=float)
        return np.broadcast_to(value, (self.count,) + value.shape)

    def list_name(self, name: str) -> str:
        """The name of a list with one value per mass: `anchor`, or `b_each` where the scene has a b."""
        return f"{name}_each" if name in self.setup.constants else name

    def name(self, name: str) -> str:
        """How the loop spells a value: `b`, or `b_each[i]` for one value per mass."""
        return f"{self.list_name(name)}[i]" if name in self.per_mass else name

    def comment(self, name: str, *, per_mass: bool = False) -> str:
        """`N/m: spring constant`: the scene's comment where the program's value is the scene's."""
        constant = self.setup.constants.get(name)
        unit = DECLARED[name].unit if name in DECLARED else ""
        if name in self.meanings:
            return self.meanings[name]
        same = (constant is not None and not per_mass and self.setup.values.get(name) is not None
                and np.array_equal(np.asarray(self.setup.values[name], dtype=float),
                                   np.asarray(self.single.get(name, self.setup.values[name]), dtype=float)))
        meaning = _without_none(constant.meaning) if same else (DECLARED[name].meaning if name in DECLARED else "") or name
        return unit_and_meaning(unit, meaning + (", one per mass" if per_mass else ""))


def _without_none(meaning: str) -> str:
    """A scene's meaning without what None means in the scene file: the program has a number."""
    return re.sub(r"\s*\(None\b.*\)\s*$", "", meaning)


def _literal(value) -> str:
    return vector(value) if isinstance(value, (tuple, list, np.ndarray)) else number(value)


def constants_block(setup, constants: ProgramConstants, used: set[str]) -> list[str]:
    """One line per constant, `k = 40  # N/m: spring constant`, in the scene file's order (dt and
    until last): the program's values, and the scene's constants the lists of masses are built from."""
    values = {name: constants.single[name] for name in constants.single}
    values.update({name: setup.values[name] for name in used if name not in values})
    scene = [name for name in setup.constants if name not in ("dt", "until")]
    order = [name for name in scene if name in values] + [name for name in values if name not in scene]
    order = [name for name in order if name not in ("dt", "until", "t_end")] + \
        [name for name in ("dt", "until", "t_end") if name in values]
    critical = _critical(setup, constants, order)
    b = constants.roles.get(Role.DAMPING)      # the damping and stiffness constants by their role in the
    return [commented(f"{b} = {critical_line(constants)}", critical_comment(constants), width=CONSTANT_COLUMN)
            if name == b and critical      # closed form (CLOSED_FORM): this module names no force's constant
            else commented(f"{name} = {_literal(values[name])}", constants.comment(name), width=CONSTANT_COLUMN)
            for name in order]


def critical_line(constants: ProgramConstants) -> str:
    """The preset's b = None (scenes/_catalog.py resolve), in the program's arithmetic: 2*sqrt(m*k)."""
    return f"2*sqrt(m*{constants.roles[Role.STIFFNESS]})"


def critical_comment(constants: ProgramConstants) -> str:
    b, k = constants.roles[Role.DAMPING], constants.roles[Role.STIFFNESS]
    return unit_and_meaning(DECLARED[b].unit, f"critical damping, {b} = 2√(m{k})")


def _critical(setup, constants: ProgramConstants, order: list[str]) -> bool:
    """Whether the program's b is critical damping for its m and k, as the preset works it out
    (scenes/_catalog.py resolve), with m and k named above it: then it is written `b = 2*sqrt(m*k)`,
    the same float (a correctly rounded square root, doubled), not 52.76362383309168."""
    b, k = constants.roles.get(Role.DAMPING), constants.roles.get(Role.STIFFNESS)
    if b is None or k is None or not all(name in constants.single for name in (b, "m", k)) or \
            not order.index("m") < order.index(b) > order.index(k):
        return False
    single = {name: constants.single[name] for name in ("m", k)}
    return catalog.resolve({**single, b: None})[b] == constants.single[b] != 0

"""A force written as an expression: the law a student types on the page, or a teacher gives with
`--force "push=vector(2, 0, 0)"`, read by physics/expression.py's grammar and never run as code.

    F = the expression, worked out for every mass at (t, r, v = p/m), in N

Its names are the program's: r (m), v (m/s), p = m v (kg·m/s), t (s), m (kg), and the scene's k
(N/m), b (kg/s), g (m/s²) and Δt (s), with pi; the engine evaluates the tree here with numpy, one
row per mass, and the program writes the same tree as its line `Fpush = ...` (program_text), in
the same order of operations, so the two agree to round-off. hat(0) and norm(0) are the zero
vector, as in VPython and GlowScript. The fast loop (physics/compiled.py) traces it like any
other force.

Nothing is known about it beyond its law: it is not conservative (a student's force is metered in
W_nc, its work, unless one can show it has a potential energy), it adds nothing to the stability
judgement (a force that makes the run blow up is caught by the engine), it has no closed form,
and it may push along any axis.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..expression import CONSTANT_NAMES, Binary, Call, Expression, Name, Number, Unary, names_in, program_text
from ..rows import row_dot
from .base import Force, _new_like, compare, where


def _magnitude(a):
    return np.sqrt(row_dot(a, a))[..., None]


def _hat(a):
    """a/|a|, and the zero vector for a = 0 (as VPython's hat and norm)."""
    length = _magnitude(a)
    moving = compare(length, ">", 0.0)
    return where(moving, a / where(moving, length, 1.0), 0.0)


def _vector(x, y, z):
    """(x, y, z) from three numbers, or one row per mass where any is one per mass."""
    parts = [np.asarray(c) for c in (x, y, z)]
    if all(part.ndim == 0 for part in parts):
        return np.array([part[()] for part in parts], dtype=np.result_type(*parts, float))
    count = max(part.reshape(-1, 1).shape[0] for part in parts)
    return np.concatenate([np.broadcast_to(part.reshape(-1, 1), (count, 1)) for part in parts], axis=1)


def _cross(a, b):
    """a × b = (a_y b_z − a_z b_y, a_z b_x − a_x b_z, a_x b_y − a_y b_x)."""
    ax, ay, az = a[..., 0], a[..., 1], a[..., 2]
    bx, by, bz = b[..., 0], b[..., 1], b[..., 2]
    return np.stack(np.broadcast_arrays(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx), axis=-1)


LAWS = {
    "vector": _vector,
    "mag": _magnitude,
    "norm": _hat,
    "hat": _hat,
    "dot": lambda a, b: row_dot(a, b)[..., None],
    "cross": _cross,
    "cos": np.cos,
    "sin": np.sin,
    "exp": np.exp,
    "sqrt": np.sqrt,
}
_BINARY = {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b,
           "/": lambda a, b: a / b, "**": lambda a, b: a ** b}


def evaluate(node, values: dict):
    """The tree's value: a vector is (3,) or one row per mass (N, 3); a number, a number or (N, 1)."""
    if isinstance(node, Number):
        return np.float64(node.text)
    if isinstance(node, Name):
        return values[node.name]
    if isinstance(node, Unary):
        return -evaluate(node.operand, values)
    if isinstance(node, Binary):
        return _BINARY[node.op](evaluate(node.left, values), evaluate(node.right, values))
    if isinstance(node, Call):
        return LAWS[node.function](*(evaluate(arg, values) for arg in node.args))
    raise TypeError(f"not a node of the grammar: {node!r}")


@dataclass(frozen=True, eq=False)
class WrittenForce(Force):
    """A force whose law is an expression of the grammar (physics/expression.py), in N.

    name       its name: the label of its arrow and energy bar; F_name in the program (no line the
               program writes itself has a name that starts F_: Fnet, Fspring)
    law        the expression, as read (physics.expression.parse)
    constants  the values of the scene's constants it reads (k, b, g, dt), in their units
    """

    name: str
    law: Expression
    constants: dict = field(default_factory=dict)
    conservative = False

    def __post_init__(self):
        used = names_in(self.law.tree)
        missing = sorted(used & set(CONSTANT_NAMES) - set(self.constants))
        if missing:
            raise ValueError(f"the force {self.name} uses {', '.join(missing)}, which this scene does not have")
        object.__setattr__(self, "constants", {name: float(self.constants[name]) for name in CONSTANT_NAMES
                                               if name in used})
        object.__setattr__(self, "_used", used)

    @property
    def LABEL(self) -> str:          # noqa: N802  (the name every force declares its label by)
        return self.name

    @property
    def TERM(self) -> str:           # noqa: N802
        return f"F_{self.name}"

    @property
    def uses_velocity(self) -> bool:
        return bool(self._used & {"v", "p"})

    def __call__(self, t, r, v, m):
        values = dict(self.constants, t=t, r=r, m=np.asarray(m).reshape(-1, 1), pi=np.float64(math.pi))
        if self.uses_velocity:
            values["v"] = v
            values["p"] = values["m"] * v
        with np.errstate(all="ignore"):      # a non-finite force is judged by the caller, not warned of
            value = evaluate(self.law.tree, values)
        F = _new_like(r)
        F[...] = value
        return F

    def program(self) -> tuple[tuple[str, str], ...]:
        spelled = {name: "{" + name + "}" for name in ("r", "v", "t", "m", *self.constants)}
        spelled.update(p="({m}*{v})", pi="pi")
        return ((f"{self.TERM} = {program_text(self.law.tree, spelled)}", f"{self.name}, added: F = {self.law.text}"),)

    def program_values(self) -> dict:
        return dict(self.constants)

"""Reading, checking and overriding a scene's constants.

A scene keeps its constants as plain assignments at the top of its file, each with its unit and
meaning in a trailing comment, ``k = 40.0  # N/m: spring constant``. That block is the one place a
teacher edits, so this module reads the units and meanings from those comments rather than keeping
a second copy. Overrides from the command line (``--set k=25``) are parsed and checked here, with
one clear message per problem.
"""
from __future__ import annotations

import ast
import difflib
import inspect
import io
import math
import tokenize
from dataclasses import dataclass

VECTOR_NAMES = {"anchor", "r0", "v0", "drive_axis"}

# name -> (test, what it must be)
RULES = {
    "m": (lambda x: x > 0, "greater than 0 kg"),
    "k": (lambda x: x >= 0, "0 N/m or more"),
    "b": (lambda x: x >= 0, "0 kg/s or more"),
    "C": (lambda x: x >= 0, "0 or more"),
    "A": (lambda x: x >= 0, "0 m² or more"),
    "rho": (lambda x: x >= 0, "0 kg/m³ or more"),
    "L0": (lambda x: x >= 0, "0 m or more"),
    "g": (lambda x: x >= 0, "0 m/s² or more (it is a magnitude; gravity acts along −y)"),
    "omega": (lambda x: x >= 0, "0 rad/s or more"),
    "dt": (lambda x: x > 0, "greater than 0 s"),
    "until": (lambda x: x >= 0, "0 s or more"),
    "drive_axis": (lambda v: any(c != 0 for c in v), "a non-zero direction"),
}


class ConstantError(ValueError):
    """A bad constant: its message is one line a teacher can act on."""


@dataclass(frozen=True)
class Constant:
    """One constant of a scene: its default value, unit and meaning (from the trailing comment)."""

    name: str
    value: object
    unit: str
    meaning: str

    @property
    def is_vector(self) -> bool:
        return self.name in VECTOR_NAMES


END_OF_CONSTANTS = "# ---- end of constants ----"


def read_constants(module) -> dict[str, Constant]:
    """The constants block of a scene module: top-level assignments with a `# unit: meaning` comment,
    up to the line `# ---- end of constants ----` (or the first function or class)."""
    source = inspect.getsource(module)
    comments = {tok.start[0]: tok.string.lstrip("#").strip()
                for tok in tokenize.generate_tokens(io.StringIO(source).readline)
                if tok.type == tokenize.COMMENT}
    lines = source.splitlines()
    block_end = next((number for number, line in enumerate(lines, start=1)
                      if line.strip() == END_OF_CONSTANTS), len(lines) + 1)
    constants = {}
    for node in ast.parse(source).body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)) or node.lineno > block_end:
            break
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1
                and isinstance(node.targets[0], ast.Name)):
            continue
        comment = comments.get(node.end_lineno)
        if comment is None or ":" not in comment:
            continue
        unit, meaning = (part.strip() for part in comment.split(":", 1))
        name = node.targets[0].id
        constants[name] = Constant(name, getattr(module, name), unit, meaning)
    return constants


def parse_value(name: str, text: str):
    """A number, or for vector constants three numbers written `0,0.284,0` (optionally in < >)."""
    if name in VECTOR_NAMES:
        parts = text.strip().strip("<>()[] ").split(",")
        try:
            vector = tuple(float(part) for part in parts)
        except ValueError:
            vector = ()
        if len(vector) != 3:
            raise ConstantError(f"{name} needs a 3-vector written like {name}=0,-1.5,0 (got {text!r})")
        return vector
    try:
        return float(text)
    except ValueError:
        raise ConstantError(f"{name} needs a number (got {text!r})") from None


def check_value(name: str, value, unit: str = "") -> None:
    """Raise ConstantError unless value is finite and within the rule for its name."""
    numbers = value if isinstance(value, tuple) else (value,)
    if value is None:
        return
    if not all(isinstance(x, (int, float)) and math.isfinite(x) for x in numbers):
        what = "three finite numbers" if isinstance(value, tuple) else "a finite number"
        raise ConstantError(f"{name} must be {what} (got {format_value(value, unit)})")
    rule = RULES.get(name)
    if rule and not rule[0](value):
        raise ConstantError(f"{name} must be {rule[1]} (got {format_value(value, unit)})")


def unknown_name_message(name: str, known) -> str:
    close = difflib.get_close_matches(name, list(known), n=1, cutoff=0.5)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    return f"unknown constant {name!r}{hint} (known: {', '.join(known)})"


def parse_assignments(texts, constants: dict[str, Constant]) -> dict:
    """Turn ['k=25', 'r0=0,1,0'] into {'k': 25.0, 'r0': (0.0, 1.0, 0.0)}, checking each."""
    values = {}
    for text in texts:
        name, sep, raw = text.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ConstantError(f"--set needs NAME=VALUE, like --set k=25 (got {text!r})")
        if name not in constants:
            raise ConstantError(unknown_name_message(name, constants))
        value = parse_value(name, raw)
        check_value(name, value, constants[name].unit)
        values[name] = value
    return values


def format_value(value, unit: str = "") -> str:
    """A number or vector in Matter & Interactions style: `< 0, -1.5, 0 > m`."""
    if value is None:
        text = "(derived)"
    elif isinstance(value, (tuple, list)):
        text = "< " + ", ".join(f"{float(x):.6g}" for x in value) + " >"
    else:
        text = f"{float(value):.6g}"
    return f"{text} {unit}".rstrip() if unit and unit != "1" else text

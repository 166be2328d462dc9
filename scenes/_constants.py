"""What each constant is, and reading, checking and overriding a scene's constants.

Everything about a constant that is the same in every scene is declared once, in DECLARED: its
unit, the symbol the page writes, whether it is a vector, the values it may take, and where a
slider for it starts (PhET's NumberProperty carries its units and range the same way). What
differs between scenes, its default and its meaning in that scene, stays in the scene's file as
the readable list a teacher edits, ``k = 40.0  # N/m: spring constant``; the unit in that comment
must agree with the declaration, and a line that is not of that form is refused with its file and
line. Overrides from the command line (``--set k=25``) are parsed and checked here, with one clear
message per problem.
"""
from __future__ import annotations

import ast
import difflib
import inspect
import io
import math
import numbers
import os
import sys
import tokenize
from collections.abc import Mapping
from dataclasses import dataclass

from physics.declared import NONZERO, SMALLEST, Declared, _short  # noqa: F401  (scenes import them from here)
from physics.forces import FORCES, DeclarationError, declared_constants


class ConstantError(ValueError):
    """A bad constant: its message is one line a teacher can act on."""


# What each constant that is not a force's may be, for every scene (the units are the scene files').
# A force's own constants (k, b, ω, ...) are declared beside its law, in its CONSTANTS (physics/forces/).
SCENE_CONSTANTS = {
    "m": Declared("kg", 1e-6, 1e6, meaning="mass"),
    "r0": Declared("m", -1e4, 1e4, vector=True, none="worked out by the scene", meaning="start position"),
    "v0": Declared("m/s", -1e4, 1e4, vector=True, meaning="start velocity"),
    "x0": Declared("m", -1e4, 1e4, slider_from_zero=True),
    "spacing": Declared("m", 0, 1e3),
    "under_fraction": Declared("1", 0, 1e3),
    "over_multiple": Declared("1", 0, 1e3),
    "b_ratio": Declared("1", 0, 1e3, above_low=True),
    "curves": Declared("1", 1, 100, whole=True),
    "count": Declared("1", 2, 10_000, whole=True),
    "omega_min": Declared("rad/s", 0, 1e4, symbol="ω_min", above_low=True),
    "omega_max": Declared("rad/s", 0, 1e4, symbol="ω_max", above_low=True),
    "settle": Declared("s", 0, 1e6),
    "periods": Declared("1", 0, 1e4, above_low=True),
    "dt": Declared("s", 1e-6, 1e3, symbol="Δt", slider_round=True, numerical=True,
                   meaning="time step Δt of the momentum update"),
    "until": Declared("s", 0, 1e6, numerical=True, meaning="when to stop"),
}


class _Declarations(Mapping):
    """The one table of what each constant may be, for every scene: SCENE_CONSTANTS, and every
    force's CONSTANTS (physics.forces.declared_constants), read when asked, so a force a teacher's
    scene brings (tests/test_new_force.py) declares its constants as ours do."""

    def _table(self) -> dict[str, Declared]:
        forces = declared_constants()
        both = sorted(forces.keys() & SCENE_CONSTANTS.keys())
        if both:
            raise DeclarationError(f"the constant {both[0]} is declared twice, by a force and in scenes/_constants.py "
                                   f"SCENE_CONSTANTS; give the force's a name of its own")
        return {**forces, **SCENE_CONSTANTS}

    def __getitem__(self, name: str) -> Declared:
        return self._table()[name]

    def __iter__(self):
        return iter(self._table())

    def __len__(self) -> int:
        return len(self._table())


DECLARED = _Declarations()


def idle(values: dict) -> set[str]:
    """The constants of the forces these values switch off, which then do nothing (drive_axis and
    ω where F0 = 0): a caption leaves them out. A constant another force that is on uses (g for
    friction) is not idle."""
    off, used = set(), set()
    for cls in FORCES:
        declared = {name: d for name, d in cls.CONSTANTS.items() if name in values}
        if not declared:
            continue
        is_off = any(d.switch and values[name] == d.default for name, d in declared.items())
        (off if is_off else used).update(declared)
    return off - used


@dataclass(frozen=True)
class Constant:
    """One constant of a scene: its default value, unit and meaning (from the trailing comment)."""

    name: str
    value: object
    unit: str
    meaning: str

    @property
    def is_vector(self) -> bool:
        return DECLARED[self.name].vector

    @property
    def symbol(self) -> str:
        return DECLARED[self.name].symbol or self.name


END_OF_CONSTANTS = "# ---- end of constants ----"


def shown_path(path) -> str:
    """A scene file's name as messages give it: relative to the current folder when it lies inside."""
    try:
        relative = os.path.relpath(path)
    except (OSError, ValueError):   # the current folder is gone, or on another drive
        return str(path)
    return str(path) if relative.startswith(os.pardir) else relative


def _is_number(x) -> bool:
    return isinstance(x, numbers.Real) and not isinstance(x, bool)


def value_problem(name: str, value) -> str:
    """What is wrong with the kind of value a scene file gives a constant, or "" if nothing.

    A value is a number (not True or False, not text in quotes), three numbers in parentheses for
    a vector, or None where DECLARED says what None means.
    """
    declared = DECLARED[name]
    if declared.vector:
        fits = isinstance(value, tuple) and len(value) == 3 and all(map(_is_number, value))
        wanted = "three numbers in parentheses, like (0, -1.5, 0)"
    else:
        fits = _is_number(value)
        wanted = "a number, like 40.0"
    if fits or (value is None and declared.none):
        return ""
    either = f", or None ({declared.none})" if declared.none else ""
    got = ("text in quotes" if isinstance(value, str) else
           repr(value) if value is None or isinstance(value, (bool, tuple, list)) else f"a {type(value).__name__}")
    return f"{name} needs {wanted}{either}, not {got}"


def read_constants(module) -> dict[str, Constant]:
    """The constants block of a scene module: its top-level assignments up to the line
    `# ---- end of constants ----`, each `name = value  # unit: meaning`.

    Raises ConstantError naming the file and line of an assignment without that comment, of a
    name DECLARED does not know, of a unit that is not the declared one, or of a value that is not
    a number (three numbers for a vector; see :func:`value_problem`).
    """
    where = shown_path(module.__file__) if getattr(module, "__file__", None) else module.__name__
    try:
        source = inspect.getsource(module)
    except OSError:  # Python ran the file, but its text is not UTF-8 (an editor's Latin-1 "é")
        with open(module.__file__, "rb") as file:
            raw = file.read()
        try:
            raw.decode("utf-8")
        except UnicodeDecodeError as bad:
            line = raw.count(b"\n", 0, bad.start) + 1
            raise ConstantError(f"{where}, line {line}: the file is not UTF-8 text (byte 0x{raw[bad.start]:02x}); "
                                f"save it as UTF-8") from None
        raise
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
        if not isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            continue

        def refuse(problem):
            raise ConstantError(f"{where}, line {node.lineno}: {problem}; each line of the constants "
                                f"block is `name = value  # unit: meaning`, like "
                                f"`k = 40.0  # N/m: spring constant` (got: {lines[node.lineno - 1].strip()})")
        if not (isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)):
            refuse("expected one name, an = sign and a value")
        name = node.targets[0].id
        comment = comments.get(node.end_lineno)
        if comment is None or ":" not in comment:
            refuse(f"{name} needs a comment with its unit and meaning, separated by a colon")
        unit, meaning = (part.strip() for part in comment.split(":", 1))
        if name not in DECLARED:
            refuse(f"{name} is not a constant any scene knows: declare it in scenes/_constants.py")
        if unit != DECLARED[name].unit:
            refuse(f"the unit of {name} is {DECLARED[name].unit}, not {unit!r}")
        value = getattr(module, name)
        problem = value_problem(name, value)
        if problem:
            refuse(problem)
        try:
            check_value(name, value, unit)  # in its declared range: named here, with its file and line
        except ConstantError as out_of_range:
            raise ConstantError(f"{where}, line {node.lineno}: {out_of_range}") from None
        constants[name] = Constant(name, value, unit, meaning)
    return constants


def parse_value(name: str, text: str):
    """A number, or for vector constants three numbers written `0,0.284,0` (optionally in < >)."""
    if name in DECLARED and DECLARED[name].vector:
        parts = text.strip().strip("<>()[] ").split(",")
        try:
            vector = tuple(float(part) for part in parts)
        except ValueError:
            vector = ()
        if len(vector) != 3:
            raise ConstantError(f"{name} needs a 3-vector written like {name}=0,-1.5,0 (got {text!r})")
        for part, x in zip(parts, vector):
            _refuse_underflow(name, part, x)
        return vector
    try:
        value = float(text)
    except ValueError:
        raise ConstantError(f"{name} needs a number (got {text!r})") from None
    _refuse_underflow(name, text, value)
    return value


def _refuse_underflow(name: str, text: str, value: float) -> None:
    """`1e-400` is read as 0 (too small for a double), which would switch a force off unasked."""
    mantissa = text.strip().lower().partition("e")[0]
    if value == 0 and any(digit in mantissa for digit in "123456789"):
        raise ConstantError(f"{name} = {text.strip()} is too small for the computer to tell from 0; "
                            f"write 0 to switch it off, or give at least {_short(SMALLEST)} in size")


def check_value(name: str, value, unit: str = "") -> None:
    """Raise ConstantError unless value is finite and within its declaration (DECLARED[name]).

    The message names the constant, the value given and the range that works.
    """
    numbers = value if isinstance(value, tuple) else (value,)
    if value is None:
        return
    declared = DECLARED.get(name)
    vector = isinstance(value, tuple)
    if not all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in numbers):
        what = declared.words(unit, vector=vector) if declared else (
            "three finite numbers" if vector else "a finite number")
        raise ConstantError(f"{name} must be {what} (got {format_value(value, unit)})")
    if declared is not None and not declared.allows(value):
        raise ConstantError(f"{name} must be {declared.words(unit, vector=vector)} "
                            f"(got {format_value(value, unit)})")
    if Declared.too_small(value):
        shown = f" {unit}" if unit and unit != "1" else ""
        raise ConstantError(f"{name} must be 0 or at least {_short(SMALLEST)}{shown} in size "
                            f"(got {format_value(value, unit)})")


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
        text = "< " + ", ".join(_six_digits(x) for x in value) + " >"
    else:
        text = _six_digits(value)
    return f"{text} {unit}".rstrip() if unit and unit != "1" else text


def _six_digits(x) -> str:
    """x to 6 significant digits; a number below the normal doubles (1e-320) as typed, since its
    binary value has fewer digits than that and .6g shows the error (9.99989e-321)."""
    x = float(x)
    return repr(x) if 0 < abs(x) < sys.float_info.min else f"{x:.6g}"

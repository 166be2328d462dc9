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
import re
import tokenize
from dataclasses import dataclass


class ConstantError(ValueError):
    """A bad constant: its message is one line a teacher can act on."""


def _short(x: float) -> str:
    """1e+06 -> 1e6, 1e-06 -> 1e-6, 0.5 -> 0.5: a bound as a teacher writes it."""
    return re.sub(r"e([+-])0*(\d)", lambda m: "e" + ("-" if m[1] == "-" else "") + m[2], f"{x:g}")


@dataclass(frozen=True)
class Declared:
    """One constant, as every scene has it: its unit and symbol, and what values it may take.

    unit      its SI unit ("1" for a pure number), as the scene files' comments write it
    symbol    how the page writes it (ω, ρ); "" means its name
    vector    three numbers (a position, a velocity, a direction) rather than one
    low, high every number it (or each component) may take lies from `low` to `high`; `above_low`
              leaves `low` itself out (m > 0). Wide for teaching, narrow enough that the products
              the forces take, m·g, k·(|L| − L0), b·v, ½ρCA|v|², stay far from floating-point
              overflow (10³⁰⁸) and Δt far from round-off (10⁻¹⁶ of t).
    whole     a whole number (a count); `nonzero`: a vector of non-zero length (a direction)
    note      added to the range in the message
    none      what None means, where a scene file may write it instead of a number ("" if it may not)
    slider_from_zero  a slider for it starts at 0, where 0 switches its force off (b, F0, ω, ...);
              otherwise at a tenth of its default (m, k, Δt must stay positive)
    """

    unit: str
    low: float
    high: float
    symbol: str = ""
    vector: bool = False
    above_low: bool = False
    whole: bool = False
    nonzero: bool = False
    note: str = ""
    none: str = ""
    slider_from_zero: bool = False

    def allows(self, value) -> bool:
        numbers = value if isinstance(value, tuple) else (value,)
        inside = all((x > self.low if self.above_low else x >= self.low) and x <= self.high
                     and (not self.whole or x == int(x)) for x in numbers)
        return inside and (not self.nonzero or max(abs(x) for x in numbers) >= NONZERO)

    @staticmethod
    def too_small(value) -> bool:
        """Whether a number is nonzero but below SMALLEST in size: round-off, not a value to
        compute with (k = 1e-320 N/m makes the stretch m·g/k overflow)."""
        numbers = value if isinstance(value, tuple) else (value,)
        return any(0 < abs(x) < SMALLEST for x in numbers)

    def words(self, unit: str = "", *, vector: bool = False) -> str:
        """`from 0 to 1e6 N/m`, `greater than 0 and at most 1e6 kg`, `a whole number from 2 to 10000`."""
        unit = f" {unit}" if unit and unit != "1" else ""
        low, high = _short(self.low), _short(self.high)
        span = (f"greater than {low} and at most {high}{unit}" if self.above_low
                else f"from {low} to {high}{unit}")
        if self.whole:
            span = f"a whole number {span}"
        if vector:
            span = f"three numbers, each {span}"
            if self.nonzero:
                span += f", not all near 0 (the largest at least {_short(NONZERO)})"
        return f"{span} ({self.note})" if self.note else span


NONZERO = 1e-6  # a direction's largest component must be at least this, so its length is not round-off
SMALLEST = 1e-9  # any number given is 0 or at least this in size

# The one table of what each constant may be, for every scene (the units are the scene files').
DECLARED = {
    "m": Declared("kg", 1e-6, 1e6),
    "k": Declared("N/m", 0, 1e6),
    "b": Declared("kg/s", 0, 1e6, none="critical damping, b = 2√(mk)", slider_from_zero=True),
    "C": Declared("1", 0, 100, slider_from_zero=True),
    "A": Declared("m²", 0, 1e3),
    "rho": Declared("kg/m³", 0, 1e5, symbol="ρ"),
    "L0": Declared("m", 0, 1e4),
    "g": Declared("m/s²", 0, 1e3, note="it is a magnitude; gravity acts along −y", slider_from_zero=True),
    "F0": Declared("N", -1e6, 1e6, slider_from_zero=True),
    "omega": Declared("rad/s", 0, 1e4, symbol="ω", slider_from_zero=True),
    "drive_axis": Declared("1", -1e6, 1e6, vector=True, nonzero=True),
    "anchor": Declared("m", -1e4, 1e4, vector=True),
    "r0": Declared("m", -1e4, 1e4, vector=True, none="worked out by the scene"),
    "v0": Declared("m/s", -1e4, 1e4, vector=True),
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
    "dt": Declared("s", 1e-6, 1e3, symbol="Δt"),
    "until": Declared("s", 0, 1e6),
}


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
        text = "< " + ", ".join(f"{float(x):.6g}" for x in value) + " >"
    else:
        text = f"{float(value):.6g}"
    return f"{text} {unit}".rstrip() if unit and unit != "1" else text

"""How the program spells things: numbers that read back exactly, lists, and comments lined up.

Every physics number goes into the program through :func:`number` (repr of the float, whole
numbers without .0), so the program starts from exactly the model's values.
"""
from __future__ import annotations

import math


LINE_BREAKS = set("\n\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029")


def one_line(message: str) -> str:
    """`message` as one line: a line break or control character in it (a file name, a --fit
    value) written as Python writes it in a string, \\n, so the message stays one line and still
    names the value exactly. Tabs stay. Every message and report line that names a user's value
    goes through it: the command line's errors and notes, and the lab's report of a data file."""
    return "".join(repr(c)[1:-1] if c in LINE_BREAKS or (c < " " and c != "\t") or c == "\x7f" else c
                   for c in message)


class ProgramError(ValueError):
    """A program that cannot be written (a bad path, a scene the writer cannot follow): one line."""


def number(x) -> str:
    """A float as a literal that reads back exactly: 10, -1.5, 0.1 (whole numbers without .0)."""
    x = float(x)
    if not math.isfinite(x):
        raise ProgramError(f"cannot write the value {x} into a program")
    if x.is_integer() and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


def vector(v) -> str:
    return "vector(" + ", ".join(number(c) for c in v) + ")"


def unit_and_meaning(unit: str, meaning: str) -> str:
    """A constant's comment, `N/m: spring constant`; a pure number (unit "1") gets no unit."""
    return meaning if unit in ("", "1") else f"{unit}: {meaning}"


COMMENT = "\0"             # marks where a line's comment starts, until align_comments lines them up
COMMENT_COLUMN = 48
CONSTANT_COLUMN = 24       # the constants block's comments start here, as in the scene files
ONE_LINE = 72              # a list longer than this is written one item per line


def commented(code: str, comment: str, width: int | None = None) -> str:
    """A line of code with a trailing comment: at column `width`, or where align_comments puts it."""
    if not comment:
        return code
    return f"{code:<{width}} # {comment}" if width else f"{code}{COMMENT}{comment}"


def listed(name: str, items: list[str], comment: str) -> list[str]:
    """`name = [a, b, c]` with its comment, or one item a line where that would be long."""
    one_line = f"{name} = [{', '.join(items)}]"
    if len(one_line) <= ONE_LINE:
        return [commented(one_line, comment, width=CONSTANT_COLUMN)]
    return [commented(f"{name} = [", comment, width=CONSTANT_COLUMN), *(f"    {item}," for item in items), "]"]


def align_comments(lines: list[str]) -> list[str]:
    """The lines, with every marked comment at COMMENT_COLUMN (or just after longer code)."""
    return [f"{line.partition(COMMENT)[0]:<{COMMENT_COLUMN - 1}} # {line.partition(COMMENT)[2]}"
            if COMMENT in line else line for line in lines]

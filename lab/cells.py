"""How a measured file writes its numbers: the separator between cells, and the decimal mark and
thousands separator inside them (lab/readers.py reads the rest).

    separator   tab, semicolon, comma, or runs of spaces; a cell in double quotes may hold the
                separator ("1,600.7" in a comma-separated file)
    style       the decimal mark (. or ,) and the thousands separator (none, , or .), decided once
                for the whole file from what its cells show:
                  - a cell with both marks (1,600.7 or 1.600,7): the later one is the decimal mark
                  - a cell whose comma cannot be a thousands separator (0,25; 12,5; 1,6012): a
                    decimal comma; a dot then can only be a thousands separator
                  - a cell whose dot cannot be one (0.25): a decimal point; a comma then is one
                  - commas that could be either (1,601 and nothing else to tell): refused, since
                    1.601 and 1601 are both readings a program has made of such files
                A thousands separator must group three digits (1,600 or 12,345,678), else the cell
                is not a number.
"""
from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass

GROUPED = {",": re.compile(r"^[+-]?[1-9]\d{0,2}(,\d{3})+$"), ".": re.compile(r"^[+-]?[1-9]\d{0,2}(\.\d{3})+$")}


@dataclass(frozen=True)
class Style:
    """The decimal mark and the thousands separator ("" for none)."""

    decimal: str = "."
    thousands: str = ""


class Ambiguous(ValueError):
    """A cell whose comma (or dot) may be a decimal mark or a thousands separator, in a file that never says."""

    def __init__(self, cell: str):
        super().__init__(cell)
        self.cell = cell


def separator(line: str) -> str | None:
    """The separator a line uses: tab, semicolon, comma, or None for runs of spaces."""
    for mark in ("\t", ";", ","):
        if mark in line:
            return mark
    return None


def cells(line: str, separator: str | None) -> list[str]:
    """The line's cells, stripped of spaces and quotes (a quoted cell may hold the separator)."""
    if separator and '"' in line:
        parts = next(csv.reader([line], delimiter=separator))
    else:
        parts = line.split(separator) if separator else line.split()
    return [part.strip().strip('"').strip() for part in parts]


def _could_group(text: str, mark: str) -> bool:
    """Whether `text` (its whole part) is digits grouped in threes by `mark`."""
    return bool(GROUPED[mark].match(text))


def style_of(rows) -> Style:
    """The file's Style from its rows of cells (see the module's docstring); raises Ambiguous."""
    both = comma = dot = None
    comma_decimal = dot_decimal = False
    for row in rows:
        for cell in row:
            has_comma, has_dot = "," in cell, "." in cell
            if has_comma and has_dot:
                both = both or cell
            elif has_comma:
                comma = comma or cell
                mantissa = re.split(r"[eE]", cell)[0]
                comma_decimal = comma_decimal or not _could_group(mantissa, ",")
            elif has_dot:
                dot = dot or cell
                mantissa = re.split(r"[eE]", cell)[0]
                dot_decimal = dot_decimal or not _could_group(mantissa, ".")
    if both:
        decimal = "," if both.rfind(",") > both.rfind(".") else "."
        return Style(decimal, "." if decimal == "," else ",")
    if comma_decimal:
        return Style(",", "." if dot else "")
    if comma and (dot_decimal or dot):
        return Style(".", ",")
    if comma:
        raise Ambiguous(comma)
    return Style()


def number(cell: str, style: Style) -> float | None:
    """A cell as a float, None if empty; raises ValueError for text (and for nan or inf)."""
    if cell == "":
        return None
    text = cell
    if style.thousands and style.thousands in text:
        whole, mark, fraction = text.partition(style.decimal)
        if not _could_group(whole, style.thousands):
            raise ValueError(cell)
        text = whole.replace(style.thousands, "") + ("." + fraction if mark else "")
    elif style.decimal == ",":
        if "." in text:
            raise ValueError(cell)
        text = text.replace(",", ".")
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(cell)
    return value


NUMERIC = re.compile(r"^[+-]?(?:\d[\d.,]*|[.,]\d+)(?:[eE][+-]?\d+)?$")


def is_numbers(row: list[str]) -> bool:
    """Whether a row of cells is numbers (and empty cells), in any style; at least one number."""
    found = 0
    for cell in row:
        if cell == "":
            continue
        if not NUMERIC.match(cell):
            return False
        found += 1
    return found >= 1

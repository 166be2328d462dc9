"""How the page writes a small length for a student: a plain decimal with a unit, never `1.24e-09 m`.

An error against the exact solution runs from centimetres (euler-cromer at a large Δt) down to
round-off (rk4 at a small one). Written in metres, the small ones need an exponent, which a
class reads as a typo. Each is written instead with three significant digits, in the largest of
m, mm, µm, nm and pm that keeps it at 1 or more (0.1 m and up stay in metres):

    0.0124 m → 12.4 mm      1.24e-09 m → 1.24 nm      3e-16 m → less than 1 pm (round-off)
"""
from __future__ import annotations

import math
import re

UNITS = (("mm", 1e-3), ("µm", 1e-6), ("nm", 1e-9), ("pm", 1e-12))  # smaller and smaller, each with its size in m
METRES_FROM = 0.1  # m: a length this size or more is written in metres
ROUND_OFF = "less than 1\u00a0pm (round-off)"
NO_BREAK = "\u00a0"   # between a number and its unit: the caption wrapped `921` and `µm` onto two lines
# a number, one space, and the unit after it (a letter or %): `330 %`, `9.42 s`, `1e-05 N/m`
NUMBER_THEN_UNIT = re.compile(r"(\d[\d,.]*(?:e[+-]?\d+)?) (?=%|[^\W\d_])")


def length_text(metres: float, *, signed: bool = False) -> str:
    """`metres` as a plain decimal of three significant digits with its unit: `+1.24 nm`, `0.153 m`
    (a no-break space between them).
    `signed` writes a + before a positive length (an error's direction). Not finite: `not a number`."""
    if not math.isfinite(metres):
        return "not a number"
    size = abs(metres)
    if size == 0:
        return f"0{NO_BREAK}m"
    unit, scale = "m", 1.0
    if size < METRES_FROM:
        for unit, scale in UNITS:
            if round_3(size / scale) >= 1:
                break
        else:
            return ROUND_OFF
    value = round_3(size / scale)
    if value >= 1000 and unit != "m":     # 999.96 µm rounds to 1000: one unit up
        unit, scale = _larger(unit)
        value = round_3(size / scale)
    decimals = max(0, 2 - math.floor(math.log10(value)))
    sign = "−" if metres < 0 else ("+" if signed else "")
    return f"{sign}{value:.{decimals}f}{NO_BREAK}{unit}"


def units_kept(html: str) -> str:
    """The page's HTML with a no-break space between each number and its unit, outside tags, so the
    browser never wraps `330` and `%` onto two lines. The sentences come from physics/ and the
    command line prints them as they are (a console that is not UTF-8 has no no-break space)."""
    parts = re.split(r"(<[^>]*>)", html)
    return "".join(part if part.startswith("<") else NUMBER_THEN_UNIT.sub(rf"\1{NO_BREAK}", part)
                   for part in parts)


def round_3(x: float) -> float:
    """x to three significant digits."""
    return float(f"{x:.3g}")


def _larger(unit: str) -> tuple[str, float]:
    names = ["m"] + [name for name, _ in UNITS]
    sizes = [1.0] + [size for _, size in UNITS]
    i = names.index(unit) - 1
    return names[i], sizes[i]

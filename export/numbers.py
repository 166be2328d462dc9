"""How a run's numbers are written down, the same in the page's Download CSV and the command line.

Files (CSV, JSON) carry FILE_DIGITS significant digits: a double holds 15 to 17, and the last one
or two are round-off (−7.800000000000001 is −7.8). A time is on the grid of Δt, so it is written
with Δt's decimals (0.30000000000000004 s is 0.3 s when Δt = 0.1 s).
"""
from __future__ import annotations

ENERGY_KEYS = ("K", "U", "E", "W_nc")
CSV_HEADER = ["t", "x", "y", "z", "vx", "vy", "vz", "px", "py", "pz", *ENERGY_KEYS]
FILE_DIGITS = 15  # significant digits of every number in --json and --csv (a double holds 15 to 17)


def clean(x: float) -> float:
    """x to FILE_DIGITS significant digits: -7.800000000000001 → -7.8 (round-off, not information)."""
    return float(f"{float(x):.{FILE_DIGITS}g}")


def time_decimals(dt: float) -> int:
    """The decimals Δt is written with: 1 for 0.1 s, 3 for 0.005 s, 0 for 2 s."""
    text = f"{float(dt):.{FILE_DIGITS}g}"
    if "e" in text:
        mantissa, exponent = text.split("e")
        return max(0, len(mantissa.partition(".")[2]) - int(exponent))
    return len(text.partition(".")[2])


def clean_time(t: float, dt: float) -> float:
    """A time on the grid of Δt, rounded to Δt's decimals: 0.30000000000000004 → 0.3 when Δt = 0.1 s.

    Every step time n·Δt has no more decimals than Δt, so the rounding removes only round-off.
    """
    return clean(round(float(t), time_decimals(dt)))

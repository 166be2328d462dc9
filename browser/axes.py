"""Graph axes with round ticks (steps of 1, 2 or 5 × 10ⁿ) that a class can read from the back row.

vpython's graphs (flot, in "fast" mode) choose their own tick spacing from an axis's span and its
length in pixels, and one of the spacings they may choose is 2.5 × 10ⁿ, which they then print
rounded (`-1.3, -1.5, -1.8`). So the view sets each axis's ends itself, to whole steps of a round
spacing, widened by whole steps until flot's own rule picks a round spacing too.

The labels under those ticks are plain decimals, one line each at any scale (`0.04`, not vpython's
`4e-2`, which the page broke over two lines as `4e-` / `2`): PLAIN_TICKS, a script the page runs
once, has flot print every graph's ticks with the decimals of the tick spacing, and clears what
a thick curve draws outside a graph's frame.

Nothing here imports vpython: tests/test_axes.py checks the rule on many ranges, and
tests/test_tick_labels.py runs PLAIN_TICKS in Chromium's flot from 10⁻⁶ to 10⁶.
"""
from __future__ import annotations

import math

from physics.rounding import ROUND_STEPS as ROUND  # tick steps of 1, 2 or 5 × 10ⁿ

from export.plain_ticks import plain_ticks

from .clock import window

# Every graph's ticks in plain decimals, and nothing a thick curve draws outside its frame: the
# script lives in export/plain_ticks.py, which the offline page uses too.
PLAIN_TICKS = plain_ticks(clear_outside=True)


def flot_tick_step(span: float, pixels: float) -> float:
    """The tick spacing flot picks for an axis `span` long drawn over `pixels` (its own rule).

    It aims at 0.3 √pixels ticks: delta = span / (0.3 √pixels), then rounds delta to 1, 2, 2.5, 5
    or 10 × 10ⁿ (2.5 where delta/10ⁿ lies between 2.25 and 3).
    """
    delta = span / (0.3 * math.sqrt(pixels))
    decimals = -math.floor(math.log10(delta))
    magnitude = 10.0 ** -decimals
    norm = delta / magnitude
    if norm < 1.5:
        size = 1.0
    elif norm < 3:
        size = 2.5 if norm > 2.25 else 2.0
    elif norm < 7.5:
        size = 5.0
    else:
        size = 10.0
    return size * magnitude


def is_round(step: float) -> bool:
    """True for 1, 2 or 5 × 10ⁿ."""
    mantissa = step / 10.0 ** math.floor(math.log10(step) + 1e-9)
    return any(abs(mantissa - r) < 1e-6 for r in ROUND + (10.0,))


def nice_range(low: float, high: float, *, pixels: float) -> tuple[float, float]:
    """Axis ends enclosing [low, high] whose ticks flot draws at a round spacing, 3 to 7 of them.

    pixels is the axis's length on the page (the graph canvas's height for a y axis, its width
    for an x axis).
    """
    if not (math.isfinite(low) and math.isfinite(high)):
        return -1.0, 1.0
    if high - low < 1e-12 * max(1.0, abs(low), abs(high)):
        half = 0.1 * max(abs(low), 1e-3)
        low, high = low - half, high + half
    step = 10.0 ** math.floor(math.log10((high - low) / 6))
    for _ in range(12):
        for factor in ROUND:
            size = factor * step
            bottom = math.floor(low / size + 1e-9) * size
            steps = math.ceil((high - bottom) / size - 1e-9)
            for extra in range(4):  # widen by whole steps until flot's own spacing is round
                top = bottom + (steps + extra) * size
                if steps + extra <= 8 and is_round(flot_tick_step(top - bottom, pixels)):
                    return _clean(bottom), _clean(top)
        step *= 10
    return low, high


def _clean(value: float) -> float:
    """0.30000000000000004 → 0.3: an axis end is a whole number of round steps."""
    return float(f"{value:.12g}") + 0.0


class AxisFit:
    """One graph axis fitted to the values seen since the last clear: it widens, never narrows.

    `update` returns the new (low, high) when the axis must change, else None.
    """

    def __init__(self, *, pixels: float, pad: float = 0.1):
        self.pixels, self.pad = pixels, pad
        self.clear()

    def clear(self) -> None:
        self.seen = (math.inf, -math.inf)
        self.ends: tuple[float, float] | None = None

    def update(self, values) -> tuple[float, float] | None:
        finite = [float(v) for v in values if math.isfinite(v)]
        if not finite:
            return None
        low, high = min(self.seen[0], min(finite)), max(self.seen[1], max(finite))
        self.seen = (low, high)
        if self.ends is not None and self.ends[0] <= low and high <= self.ends[1]:
            return None
        margin = self.pad * (high - low)
        ends = nice_range(low - margin, high + margin, pixels=self.pixels)
        if ends == self.ends:
            return None
        self.ends = ends
        return ends


def time_axis(t: float, *, span: float, dt: float, pixels: float) -> tuple[float, float]:
    """A graph's time axis, s, for a run at time t: from 0 to just past t (at least two of dt, the
    time between the graph's points), at round ticks for an axis `pixels` long (nice_range), so a
    few Steps after Reset fill the graph instead of its first 1 %; once t reaches `span`, the last
    `span` seconds, scrolling (browser/clock.py's window)."""
    if t >= span:
        return window(t, span=span)
    return 0.0, min(span, nice_range(0.0, max(1.05 * t, 2 * dt), pixels=pixels)[1])


def data_window(points, *, dt: float, pixels: float) -> tuple[float, float] | None:
    """The time axis, s, that holds measured points [[t, position], ...] in view while they are
    shown: from the release (t = 0), or the first point if earlier, to the last point, at round
    ticks (nice_range); None without points (then the axis scrolls: time_axis)."""
    if not points:
        return None
    return nice_range(min(0.0, points[0][0]), max(points[-1][0], 2 * dt), pixels=pixels)

"""Round numbers a class can read and type: 1, 2 or 5 × 10ⁿ.

One rule for every place that rounds this way: the Δt the accuracy judgement suggests
(physics/accuracy.py), the arrows' scales (export/arrows.py), the Δt slider's values
(browser/controls.py) and the graphs' tick steps (browser/axes.py).
"""
from __future__ import annotations

import math

ROUND_STEPS = (1.0, 2.0, 5.0)   # the mantissas of a round number, times 10ⁿ


def round_down(x: float) -> float:
    """The largest 1, 2 or 5 × 10ⁿ not above x: 0.9 → 0.5, 0.013 → 0.01 (0.0 for x ≤ 0 or not finite)."""
    if not (x > 0 and math.isfinite(x)):
        return 0.0
    power = 10.0 ** math.floor(math.log10(x))
    for mantissa in reversed(ROUND_STEPS):
        if mantissa * power <= x * (1 + 1e-12):
            return float(f"{mantissa * power:.12g}")
    return float(f"{power / 2:.12g}")    # round-off put x just under a power of ten


def round_up(x: float) -> float:
    """The smallest 1, 2 or 5 × 10ⁿ at least x: 13 → 20, 0.031 → 0.05, 50 → 50 (1.0 for x ≤ 0 or not finite)."""
    if not math.isfinite(x) or x <= 0:
        return 1.0
    power = 10.0 ** math.floor(math.log10(x))
    for mantissa in ROUND_STEPS + (10.0,):
        if mantissa * power >= x * (1 - 1e-12):
            return float(f"{mantissa * power:.12g}")
    return 10 * power

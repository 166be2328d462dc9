"""The error graph's curves: for each mass, the largest |x − x_exact| over the last period, log₁₀ m.

|x − x_exact| itself falls to zero wherever the simulated curve crosses the exact one, twice a
period: on a log axis each crossing is a deep spike, and four methods' spikes made the graph busy.
The largest error over the last period T = 2π/ω (ω = √(k/m), physics/stability.py's rates) is the
error's envelope, how far the simulation has strayed: on it the methods' orders read as the gaps
between their curves, and the growth of the error as each curve's slope.

A mass with no spring from an anchor (ω = 0) has no period: its curve is |x − x_exact| itself.
"""
from __future__ import annotations

import math
from collections import deque

import numpy as np

from physics.stability import rates


def periods(model) -> list[float]:
    """Each mass's period 2π/ω at rest, s (0 where it has no spring)."""
    omega = rates(model.forces, model.state.m).omega
    return [2 * math.pi / w if w > 0 else 0.0 for w in omega]


class PeriodMax:
    """The largest |error| over the last `period` seconds, (t − period, t], of the errors added so far."""

    def __init__(self, period: float):
        self.period = period
        self.window: deque = deque()   # (t, |error|), oldest first

    def clear(self) -> None:
        self.window.clear()

    def add(self, t: float, error: float) -> float:
        """Add the error at t and return log₁₀ of the largest |error| over the last period
        (−inf if every one was 0); an unknown error (NaN: no exact value) is not added, and gives NaN."""
        if math.isnan(error):
            return math.nan
        self.window.append((t, abs(error)))
        while self.window[0][0] <= t - self.period and len(self.window) > 1:
            self.window.popleft()
        with np.errstate(divide="ignore"):
            return float(np.log10(max(size for _, size in self.window)))

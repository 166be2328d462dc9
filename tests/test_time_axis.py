"""The graphs' time axis (browser/axes.py's time_axis): it fits the steps taken after Reset, with a
round end, until the run fills the usual window; then it scrolls as before (browser/clock.py's window)."""
from __future__ import annotations

import pytest
from hypothesis import given, settings, strategies as st

from browser.axes import time_axis
from browser.clock import window


def test_three_steps_after_reset_fill_the_graph():
    # Reset and three Steps of Δt = 0.1 s: the points run to 0.3 s, on an axis to 0.5 s (not 30 s)
    assert time_axis(0.3, span=30.0, dt=0.1) == (0.0, 0.5)
    assert time_axis(0.0, span=30.0, dt=0.1) == (0.0, 0.2)   # two steps' room at t = 0
    assert time_axis(12.0, span=30.0, dt=0.1) == (0.0, 20.0)
    assert time_axis(25.0, span=30.0, dt=0.1) == (0.0, 30.0)  # never past the usual window


@settings(deadline=None)
@given(st.floats(0, 1e4), st.sampled_from([10.0, 30.0, 60.0]), st.sampled_from([1e-3, 0.01, 0.1, 1.0]))
def test_the_points_are_on_the_axis_and_fill_at_least_a_fifth_of_it(t, span, dt):
    start, end = time_axis(t, span=span, dt=dt)
    assert start <= t <= end and end - start <= span
    if t >= span:
        assert (start, end) == window(t, span=span)
    elif t > 2 * dt:
        assert t / end > 0.19


@pytest.mark.parametrize("t", [0.05, 0.7, 3.3, 29.9])
def test_the_end_is_round(t):
    end = time_axis(t, span=30.0, dt=0.01)[1]
    assert end == 30.0 or f"{end:g}".lstrip("0.").rstrip("0") in ("1", "2", "5")

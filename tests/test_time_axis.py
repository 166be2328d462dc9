"""The graphs' time axis (browser/axes.py's time_axis): it fits the steps taken after Reset, at
round ticks, until the run fills the usual window; then it scrolls as before (browser/clock.py's window)."""
from __future__ import annotations

import pytest
from hypothesis import given, settings, strategies as st

from browser.axes import flot_tick_step, is_round, time_axis
from browser.clock import window

PIXELS = 640


def test_three_steps_after_reset_fill_the_graph():
    # Reset and three Steps of Δt = 0.1 s: the points run to 0.3 s, on an axis to 0.35 s (not 30 s)
    start, end = time_axis(0.3, span=30.0, dt=0.1, pixels=440)
    assert start == 0.0 and 0.3 < end <= 0.4
    assert time_axis(25.0, span=30.0, dt=0.1, pixels=440) == (0.0, 30.0)   # never past the usual window
    assert time_axis(31.0, span=30.0, dt=0.1, pixels=440) == window(31.0, span=30.0)


@settings(deadline=None)
@given(st.floats(0, 1e4), st.sampled_from([10.0, 30.0, 60.0]), st.sampled_from([1e-3, 0.05, 0.1, 1.0]),
       st.sampled_from([440, 640, 900]))
def test_the_points_are_on_the_axis_fill_a_good_part_of_it_and_tick_round(t, span, dt, pixels):
    start, end = time_axis(t, span=span, dt=dt, pixels=pixels)
    assert start <= t <= end and end - start <= span
    if t >= span:
        assert (start, end) == window(t, span=span)
    else:
        if end < span:
            assert is_round(flot_tick_step(end - start, pixels))
        if t > 2 * dt and end < span:
            assert t / end > 0.4

"""Graph axes with round ticks (browser/axes.py): flot's own spacing rule, run on many ranges.

The page's tick labels themselves are read in Chromium by tests/test_classroom_page.py.
"""
import math

import pytest
from hypothesis import given, strategies as st

from browser.axes import AxisFit, flot_tick_step, is_round, nice_range


def test_flot_spacing_rule_gives_the_uneven_ticks_the_issue_saw():
    # regimes: -2.5 to -1.0 on a 316-px canvas: flot chose 0.25 and printed -1.3, -1.8, ...
    assert flot_tick_step(1.5, 316) == pytest.approx(0.25)
    assert not is_round(0.25) and is_round(0.2) and is_round(5e-3) and is_round(10.0)


@given(low=st.floats(-1e4, 1e4), span=st.floats(1e-4, 1e4), pixels=st.sampled_from([316, 580, 300, 700]))
def test_nice_ranges_enclose_the_values_and_flot_ticks_them_roundly(low, span, pixels):
    high = low + span
    bottom, top = nice_range(low, high, pixels=pixels)
    tolerance = 1e-9 * max(span, abs(low), abs(high))
    assert bottom <= low + tolerance and top >= high - tolerance
    step = flot_tick_step(top - bottom, pixels)
    assert is_round(step)
    assert 2 <= (top - bottom) / step <= 12
    assert top - bottom <= 12 * span + 1e-9   # not absurdly wide


def test_an_axis_fit_only_widens():
    fit = AxisFit(pixels=316)
    first = fit.update([0.0, 1.0])
    assert first is not None and first[0] <= 0.0 and first[1] >= 1.0
    assert fit.update([0.5]) is None            # inside: unchanged
    wider = fit.update([3.0])
    assert wider[1] >= 3.0 and wider[0] <= first[0]
    fit.clear()
    assert fit.update([10.0, 11.0])[0] >= 9.0   # after a clear it starts afresh

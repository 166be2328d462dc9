"""The Δt slider gives round values, 1, 2 or 5 × 10ⁿ s, and the scene's default (issue 18, item 8):
never `Δt = 0.1045 s`, after which t read `8.4645 s`."""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from browser.controls import Controls, round_slider_values, slider_range, time_decimals
from scenes import catalog
from scenes._constants import DECLARED


def is_round(x: float) -> bool:
    """1, 2 or 5 × 10ⁿ, to round-off."""
    mantissa = x / 10 ** math.floor(math.log10(x) + 1e-12)
    return any(math.isclose(mantissa, m, rel_tol=1e-9) for m in (1, 2, 5, 10))


@pytest.mark.parametrize("default", [1e-6, 3e-5, 0.001, 0.005, 0.01, 0.02, 0.06, 0.1, 0.125, 0.9, 7.0, 300.0])
def test_the_values_are_round_or_the_default_and_span_the_slider_range(default):
    values = round_slider_values("dt", default, default)
    assert values == sorted(set(values)) and default in values
    assert all(is_round(x) or x == default for x in values)
    low, high, _ = slider_range("dt", default, default)
    assert values[0] <= max(low, DECLARED["dt"].low) and values[-1] >= min(high, DECLARED["dt"].high)
    assert all(DECLARED["dt"].low <= x <= DECLARED["dt"].high for x in values)
    assert len(values) >= 3                                   # a real choice, even at the smallest Δt
    for x in values:        # t = n Δt on the page reads with Δt's decimals, never 8.4645 s
        assert time_decimals(x) <= max(2, time_decimals(default), -math.floor(math.log10(x)))


def test_a_value_set_from_outside_the_list_is_kept_so_the_slider_can_stand_there():
    values = round_slider_values("dt", 0.9, 0.1)
    assert 0.9 in values and 0.1 in values and values.count(0.9) == 1
    assert [x for x in values if x not in (0.9, 0.1)] == [0.01, 0.02, 0.05, 0.2, 0.5, 1.0, 2.0]


def test_other_constants_keep_their_continuous_slider():
    assert round_slider_values("m", 1.0, 1.0) == [] and round_slider_values("k", 25.0) == []


class FakeVpython:
    """Just enough of vpython for Controls to build its caption: every widget is a namespace."""

    def __init__(self):
        self.sliders = []
        self.scene = SimpleNamespace(append_to_caption=lambda text: None, caption="")

    def slider(self, **options):
        widget = SimpleNamespace(**options)
        self.sliders.append(widget)
        return widget

    def __getattr__(self, name):        # button, menu, wtext
        return lambda **options: SimpleNamespace(**options)


def test_the_integrators_scene_dt_slider_sends_only_round_values_or_the_default():
    setup = catalog.configure("integrators")
    vp = FakeVpython()
    controls = Controls(vp, setup=setup, view={"sliders": ["dt", "m", "k"]}, integrators=("euler", "x"),
                        integrator="euler-cromer", speed="1×")
    dt_slider = controls.sliders["dt"]
    values = round_slider_values("dt", 0.06, 0.06)
    assert (dt_slider.min, dt_slider.max, dt_slider.step) == (0, len(values) - 1, 1)
    assert values[round(dt_slider.value)] == 0.06
    for place in np.linspace(dt_slider.min, dt_slider.max, 25):   # wherever the handle is dragged
        dt_slider.bind(SimpleNamespace(value=float(place)))
    sent = [message.value for message in controls.clicks() if message.name == "dt"]
    assert len(sent) == 25 and set(sent) == set(values)
    assert all(is_round(value) or value == 0.06 for value in sent)
    m_slider = controls.sliders["m"]                               # m keeps its continuous span
    assert (m_slider.min, m_slider.max) == slider_range("m", 1.0)[:2]

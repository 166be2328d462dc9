"""The error graph's envelope (browser/error_envelope.py): the largest |x − x_exact| over the last
period, worked by hand, and each mass's period from its spring."""
import math

import pytest

from browser.error_envelope import PeriodMax, periods
from scenes import catalog


def test_the_largest_error_over_the_last_period_by_hand():
    window = PeriodMax(1.0)
    assert window.add(0.0, 0.0) == -math.inf          # exact agreement at t = 0: no point on a log axis
    assert window.add(0.5, -3e-3) == pytest.approx(math.log10(3e-3))
    assert window.add(1.0, 2e-3) == pytest.approx(math.log10(3e-3))   # 0.5 s ago is within the period
    assert window.add(1.6, 1e-3) == pytest.approx(math.log10(2e-3))   # (0.6, 1.6]: 2 mm at 1.0 s
    assert math.isnan(window.add(1.7, math.nan))                      # no exact value: no point
    assert window.add(2.65, 5e-4) == pytest.approx(math.log10(5e-4))  # (1.65, 2.65]: only this one
    window.clear()
    assert window.add(3.0, 1e-6) == pytest.approx(-6.0)


def test_without_a_period_the_curve_is_the_error_itself():
    window = PeriodMax(0.0)
    assert window.add(0.0, 1e-2) == pytest.approx(-2.0)
    assert window.add(0.1, 1e-5) == pytest.approx(-5.0)


def test_each_mass_period_is_two_pi_root_m_over_k():
    setup = catalog.configure("integrators")
    m, k = setup.values["m"], setup.values["k"]
    assert periods(setup.build()) == pytest.approx([2 * math.pi * math.sqrt(m / k)] * 4)
    assert periods(catalog.configure("drag", preset="falling, no spring").build()) == [0.0, 0.0]

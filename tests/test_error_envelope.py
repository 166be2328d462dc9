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


def test_the_error_graph_axis_spans_the_methods_not_the_first_period_from_zero():
    """integrators: in its first period each error grows from 0 at t = 0, so rk4's curve starts near
    1e-7 m and the axis ran from −8 to 2 while the curves after one period lie within −5 to 1,
    squashed into the top half. The axis is fitted to the errors over whole periods; the first
    period's points are still drawn (below the axis where they are smaller)."""
    from browser.clock import LiveRun
    from browser.graphs import Graphs
    from browser.view import DEFAULT_VIEW
    from test_trail import stand_in_vpython

    setup = catalog.configure("integrators")
    model = setup.build()
    graphs = Graphs(stand_in_vpython(), setup=setup, model=model, view={**DEFAULT_VIEW, **setup.module.VIEW})
    live = LiveRun(model, integrator="euler-cromer", sample_every=0.05)
    graphs.plot(live.restart(), live, matter=[1, 2, 3], redraw=True)
    for _ in range(12):                                            # 12 s, about 10 periods
        graphs.plot(live.advance(round(1.0 / model.dt)), live, matter=[1, 2, 3])
    period = max(periods(model))
    errors = [(t, y) for curve in graphs.curves if curve.series.kind == "error"
              for t, y in curve.line.points if math.isfinite(y)]
    whole = [y for t, y in errors if t >= period]
    low, high = graphs.error_graph.ymin, graphs.error_graph.ymax
    assert low <= min(whole) and max(whole) <= high                # every whole-period error on the axis
    assert high - low <= 1.5 * (max(whole) - min(whole)), (low, high, min(whole), max(whole))
    assert min(y for t, y in errors if t < period) < low           # the first period's start: drawn, below

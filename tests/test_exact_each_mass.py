"""In a row of masses each closed form holds until its own mass reaches its spring's anchor.

regimes with x0 = 3 m: the under-damped mass swings up past its anchor, the critically and
over-damped ones never do. Only the under-damped mass loses its exact curve, and only from that
time on, in the one rule (Model.exact_where_valid) that the report, --plot and the page use; the
page (drawn with a stand-in vpython, no browser) keeps the other two exact curves and its error
readout.
"""
import math

import numpy as np

from browser.clock import LiveRun
from browser.graphs import Graphs
from browser.view import DEFAULT_VIEW
from scenes import catalog
from test_trail import stand_in_vpython


def regimes_past_the_anchor():
    setup = catalog.configure("regimes", assignments=["x0=3"])
    return setup, setup.build()


def test_only_the_mass_that_reached_its_anchor_loses_its_exact_motion_and_only_from_then():
    setup, model = regimes_past_the_anchor()
    until = model.exact_valid_until_each(10.0)
    crossing = until[0]
    assert 0 < crossing < 10 and np.all(np.isinf(until[1:]))   # under-damped only
    assert model.exact_valid_until(10.0) == crossing             # the earliest, as before
    t = np.linspace(0.0, 10.0, 1001)
    r, v = model.exact_where_valid(t)
    before, after = t <= crossing, t > crossing
    assert np.isfinite(r[before, 0]).all() and np.isnan(r[after, 0]).all() and np.isnan(v[after, 0]).all()
    assert np.isfinite(r[:, 1:]).all() and np.isfinite(v[:, 1:]).all()


def test_the_page_keeps_the_other_masses_exact_curves_and_error_after_one_mass_crosses():
    setup, model = regimes_past_the_anchor()

    vp = stand_in_vpython()
    graphs = Graphs(vp, setup=setup, model=model, view={**DEFAULT_VIEW, **setup.module.VIEW})
    live = LiveRun(model, integrator="rk4", sample_every=0.05)
    matter = list(range(model.state.count))
    graphs.plot(live.restart(), live, matter=matter, redraw=True)
    crossing = model.exact_valid_until_each(10.0)[0]
    graphs.plot(live.advance(round(6.0 / model.dt)), live, matter=matter)
    ends = {curve.series.mass: max(point[0] for point in curve.line.points)
            for curve in graphs.curves if curve.series.kind == "exact"}
    assert ends[0] <= crossing < ends[0] + 0.05                  # stops where it crosses
    assert ends[1] == ends[2] == max(ends.values()) and math.isclose(ends[1], live.state.t, abs_tol=0.05)
    readout = graphs.error_readout(live, matter=matter)
    assert readout.startswith("largest |error| against the exact solutions = ")
    assert "under-damped" in readout and "past the anchor" in readout

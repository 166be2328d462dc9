"""The Measure panel's physics and its stopwatch, without a browser (issue 30, items 1, 3 and 6).

The equilibrium and natural length come from the forces themselves (physics/equilibrium.py):
checked against L0 + m g / k on every scene with a hanging spring, against L0 on a table, and with
a force the page has never heard of (a steady wind), which moves the equilibrium with no change
to any front end. The energy bars' parts (physics/energy.py) add up to E − W_nc, are labelled
through each force's arrow label, and a new force gets its bar. The stopwatch runs on simulated
time through pause, Step, speed changes and a restarted run.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
import pytest

from browser.energy_bars import EnergyBars
from browser.stopwatch import Stopwatch
from physics.energy import energy_parts, series
from physics.equilibrium import equilibrium, natural_length
from physics.forces import Gravity, LinearDamping, Spring
from physics.state import make_state
from scenes import catalog


@pytest.mark.parametrize("name", ["vertical", "damped", "regimes", "drag", "resonance"])
def test_a_hanging_spring_rests_L0_plus_mg_over_k_below_its_anchor(name):
    setup = catalog.configure(name)
    model = setup.build()
    v = setup.values
    centre = equilibrium(model.forces, model.state)
    anchors = model.anchors
    assert np.allclose(centre[:, 1], anchors[:, 1] - (v["L0"] + v["m"] * v["g"] / v["k"]), rtol=1e-9, atol=1e-9)
    assert np.allclose(centre[:, [0, 2]], anchors[:, [0, 2]], atol=1e-9)
    relaxed = natural_length(model.forces, model.state, centre)
    assert np.allclose(relaxed[:, 1], anchors[:, 1] - v["L0"], rtol=1e-9, atol=1e-9)


def test_on_a_table_the_equilibrium_and_the_natural_length_are_one():
    model = catalog.configure("driven").build()          # g = 0; the drive is left out: it averages to 0
    centre = equilibrium(model.forces, model.state)
    assert np.allclose(centre, [[3.0, 0.0, 0.0]], atol=1e-12)
    assert np.allclose(natural_length(model.forces, model.state, centre), centre, atol=1e-12)


def test_nothing_pulls_a_falling_ball_back_so_it_has_no_equilibrium():
    state = make_state(r=(0.0, 5.0, 0.0), m=1.0)
    assert equilibrium([Gravity(g=9.8)], state) is None
    assert natural_length([Gravity(g=9.8)], state) is None


@dataclass(frozen=True, eq=False)
class Wind:
    """A steady wind: F = F_w x̂, N. The page knows nothing of it. (Not a Force subclass, which
    would add it to every force the rest of this test process lists.)"""

    F_w: float = 2.0
    name = "wind"
    conservative = False
    uses_velocity = False

    def __call__(self, t, r, v, m):
        F = np.zeros_like(r, dtype=float)
        F[:, 0] = self.F_w
        return F


def test_a_new_force_moves_the_equilibrium_and_gets_its_name_in_the_bars():
    state = make_state(r=(0.0, -1.5, 0.0), m=2.0)
    forces = [Spring(k=20.0, L0=1.0), Gravity(g=10.0), Wind(F_w=4.0), LinearDamping(b=0.5)]
    centre = equilibrium(forces, state)[0]
    stretch = np.array([4.0, -20.0, 0.0]) / 20.0                 # k (|L| − L0) L̂ = F_wind + m g
    assert np.allclose(centre, (1.0 + np.linalg.norm(stretch)) * stretch / np.linalg.norm(stretch), rtol=1e-10)
    bars = EnergyBars(SimpleNamespace(wtext=lambda **_: SimpleNamespace(text="")),
                      model=SimpleNamespace(forces=forces), reference=centre[None])
    parts = energy_parts(state, forces, np.zeros(1), reference=centre[None])
    labels = [label for label, _ in bars.labels_and_colours(parts)]
    assert labels == ["K", "U spring", "U gravity", "−W_nc (damping, wind)", "total"]


def test_the_bars_add_up_to_the_energy_less_the_work_of_damping():
    model = catalog.configure("damped").build()
    engine = model.simulation()
    reference = equilibrium(model.forces, model.state)
    U_rest = sum(float(np.sum(f.potential_energy(reference, model.state.m))) for f in model.forces if f.conservative)
    for _ in range(5):
        engine.advance(37)
        parts = energy_parts(engine.state, model.forces, engine.work, reference=reference)
        totals = {key: float(value) for key, value in series(engine.state, model.forces, engine.work).items()}
        assert sum(part.value for part in parts) == pytest.approx(totals["E_minus_W_nc"] - U_rest, rel=1e-12)
        assert parts[0].value == pytest.approx(totals["K"], rel=1e-12)
        assert parts[-1].value == pytest.approx(-totals["W_nc"], rel=1e-12) and parts[-1].value >= 0


def test_the_stopwatch_runs_on_simulated_time():
    watch = Stopwatch()
    watch.start_stop(2.0)                 # started at t = 2 s, the run paused there
    assert watch.reading(2.0) == 0.0
    assert watch.reading(2.3) == pytest.approx(0.3)       # three Steps of 0.1 s
    assert watch.reading(6.3) == pytest.approx(4.3)       # running at 4×: t moved 4 s, the watch too
    watch.lap(5.14)
    watch.lap(8.28)
    assert watch.lap_times() == pytest.approx([3.14, 3.14])
    watch.start_stop(9.0)
    assert not watch.running and watch.reading(50.0) == pytest.approx(7.0)   # stopped: it holds
    watch.lap(60.0)
    assert len(watch.laps) == 2                                               # nothing to lap when stopped
    watch.start_stop(10.0)
    watch.run_restarted(12.0)                                                 # Reset at t = 12 s
    assert watch.reading(0.0) == pytest.approx(9.0) and watch.reading(1.0) == pytest.approx(10.0)
    watch.clear()
    assert watch.reading(3.0) == 0.0 and watch.laps == [] and not watch.running
    assert math.isfinite(watch.reading(1e9))


def test_the_graph_place_shows_each_choice_filled_with_the_run_so_far(monkeypatch):
    """Energy graph, phase space and energy bars in turn, then Reset, on stand-ins for vpython."""
    from browser.clock import LiveRun
    from browser.graphs import Graphs
    from scenes._view import DEFAULT_VIEW
    from test_trail import Shape, stand_in_vpython

    monkeypatch.setattr(Shape, "delete", lambda self: None, raising=False)   # a graph taken down
    setup = catalog.configure("damped")
    model = setup.build()
    vp = stand_in_vpython()
    graphs = Graphs(vp, setup=setup, model=model, view={**DEFAULT_VIEW, **setup.module.VIEW},
                    reference=equilibrium(model.forces, model.state))
    live = LiveRun(model, integrator="euler-cromer", sample_every=0.05)
    graphs.plot(live.restart(), live, matter=[0], redraw=True)
    graphs.plot(live.advance(40), live, matter=[0])
    assert graphs.energy_graph is not None and "smGraphTitles" in graphs.titles_text.text
    graphs.choose("phase", live)
    assert graphs.energy_graph is None and graphs.phase is not None
    (mass, exact, x, v), _ = graphs.phase.latest()
    assert (x, v) == (live.state.r[0, 1], live.state.p[0, 1] / live.state.m[0]) and not exact
    assert "v_y (simulation)" in graphs.titles_text.text
    graphs.choose("bars", live)
    graphs.bars.draw(live)
    assert graphs.phase is None and "sm-bar-value" in graphs.bars.text.text
    graphs.choose("energy", live)
    assert graphs.energy_graph is not None and not graphs.bars.text.text
    graphs.clear()
    assert not graphs.recorded

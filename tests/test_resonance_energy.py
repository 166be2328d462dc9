"""What the spikes of resonance's energy graph are, as the line under the graph says (issue 18).

Measured from a run: once the start-up transient has gone, the batch's total energy repeats with
the period π/Δω (the beat of the springs' twice-a-swing rises and falls, Δω between neighbouring
drives), and not with half of it; the line under the page's graph names that period in seconds.
"""
from __future__ import annotations

import numpy as np

from physics.recording import time_grid, trajectory
from scenes import catalog
from scenes.resonance import beat_period, energy_note


def total_energy(setup, until):
    model = setup.build()
    engine = model.simulation()
    samples = engine.run_until(until, record=time_grid(model.dt, t0=0.0, dt=model.dt))
    run = trajectory(engine, samples)
    return run.t, np.asarray(run.energy["E"]), model.dt


def shifted_difference(t, E, dt, lag, window):
    """Largest |E(t + lag) − E(t)| over the window (start, end), J."""
    n = int(round(lag / dt))
    inside = (t >= window[0]) & (t <= window[1])
    return float(np.max(np.abs(E[np.flatnonzero(inside) + n] - E[inside])))


def test_after_the_transient_the_total_energy_repeats_every_pi_over_delta_omega():
    setup = catalog.configure("resonance")
    T = beat_period(setup.values)
    assert T == np.pi / 0.5                       # the default drives are 0.5 rad/s apart
    t, E, dt = total_energy(setup, until=40.0 + T + 1.0)
    window = (40.0 - T, 40.0)                     # the transient (e^(−bt/2m), b ≥ 0.5 kg/s) has gone
    swing = float(np.ptp(E[(t >= window[0]) & (t <= window[1])]))
    assert swing > 0.05                           # J: the spikes are there to explain
    assert shifted_difference(t, E, dt, T, window) < 0.02 * swing
    assert shifted_difference(t, E, dt, T / 2, window) > 0.3 * swing


def test_the_line_under_the_graph_names_the_period_for_other_drives():
    setup = catalog.configure("resonance").with_values(omega_min=3.0, omega_max=7.0, count=9)
    assert beat_period(setup.values) == np.pi / 0.5
    assert "π/Δω = 6.28 s" in energy_note(setup) and "Δω = 0.5 rad/s" in energy_note(setup)
    setup = setup.with_values(count=5)
    assert "π/Δω = 3.14 s" in energy_note(setup) and "Δω = 1 rad/s" in energy_note(setup)

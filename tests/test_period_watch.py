"""The period timed as a run goes (issue 38): the same numbers as timing it from the kept steps.

A headless run used to keep every step it timed the period by (r, p, P_nc and W_nc of every mass:
640 kB a step at 10⁴ masses), then time the period from those rows. Now a Watch
(physics/recording.py) shows one coordinate of every mass to a CrossingMeter (physics/period.py) at
each step the run records or times, and keeps only the steps the reports read (the measuring
window and the end). These tests hold the new way to the old one bit for bit, on the traced loop
and the numpy tick, with every step kept (--csv) or not, and the meter fed in blocks to the meter
fed per mass.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from export.step_update import cleaned
from physics.equilibrium import equilibrium
from physics.period import CrossingMeter, measured_period, period_from_crossings, record_window, upward_crossings
from physics.recording import CoordinateWatch, WindowLargest, _fill, every, time_grid, trajectory
from reports import headless
from reports.json_report import _cleaned_periods
from reports.periods import period_json, periods
from scenes import catalog
from scenes._view import DEFAULT_VIEW

CASES = [("damped", {"values": dict(until=20.0)}), ("regimes", {"values": dict(until=12.0)}),
         ("driven", {"scenario": 3, "values": dict(until=15.0)}), ("pendulum", {"values": dict(until=12.0)}),
         ("integrators", {"values": dict(until=8.0)}), ("friction", {"values": dict(until=15.0)}),
         ("drag", {"values": dict(until=10.0)}),
         # 40 springs × 3 components: more than the traced loop takes, so the numpy tick steps them
         ("resonance", {"values": dict(count=20, curves=2, settle=4.0, periods=1.0, until=10.0)})]


def configured(name, options):
    setup = catalog.configure(name, scenario=options.get("scenario"))
    return setup.with_values(**options["values"]) if "values" in options else setup


def either(*schedules):
    """The schedule the runs used before: every step any of these records."""
    kept = [schedule for schedule in schedules if schedule is not None]
    return lambda done: min(schedule(done) for schedule in kept)


def periods_the_old_way(setup, *, every_step):
    """Each mass's measured period (or None) from the rows a run kept before the watch: every step,
    or the measuring window, the period's time grid and the end, with the start."""
    model = setup.build()
    engine = model.simulation(None)
    until = model.until
    window = setup.hooks.measuring(setup.values)
    if every_step:
        record = every(1)
    else:
        spacing, start = record_window(model.forces, model.state.m, model.dt, t0=model.state.t, until=until)
        timing = time_grid(spacing, t0=model.state.t, dt=model.dt, start=start)
        measuring = None if window is None else time_grid(model.dt, t0=model.state.t, dt=model.dt,
                                                          start=window[0], end=window[1])
        record = either(measuring, timing)
    traj = trajectory(engine, engine.run_until(until, record=record), with_energy=False)
    axis = "xyz".index({**DEFAULT_VIEW, **setup.hooks.view}["plot"][0])
    centre = equilibrium(model.forces, model.state)
    return [None if centre is None else measured_period(traj.t, traj.r[:, i, axis], centre=float(centre[i, axis]))
            for i in range(model.state.count)], traj


@pytest.mark.parametrize("every_step", [False, True], ids=["report", "every-step"])
@pytest.mark.parametrize("name, options", CASES, ids=[name for name, _ in CASES])
def test_the_period_timed_as_the_run_goes_is_the_one_timed_from_the_kept_steps(name, options, every_step):
    setup = configured(name, options)
    result = headless.simulate(setup, every_step=every_step, progress=None)
    old, traj = periods_the_old_way(setup, every_step=every_step)
    new = [report.measured for report in periods(result)]
    assert new == old                       # Period(measured, spread, cycles): equal floats, bit for bit
    assert any(period is not None for period in new)
    # the final state is the same run's, whatever was kept
    assert np.array_equal(result.trajectory.r[-1], traj.r[-1]) and result.trajectory.t[-1] == traj.t[-1]


@pytest.mark.parametrize("count, curves", [(20, 2), (4, 2)], ids=["numpy", "traced"])
def test_a_report_keeps_the_start_and_the_end_and_measures_its_window_as_it_goes(count, curves):
    """10⁴ masses timed at every step kept 640 kB a step; a report run keeps two steps, and
    measures the largest amplitude over the window from every step of it, bit for bit (40
    springs step in numpy, 8 in the traced loop)."""
    setup = configured("resonance", {"values": dict(count=count, curves=curves, settle=4.0, periods=1.0,
                                                    until=10.0)})
    result = headless.simulate(setup, every_step=False, progress=None)
    assert result.steps == 500 and len(result.trajectory.t) == 2          # the start and the end
    assert all(report.measured is not None for report in periods(result))
    kept = headless.simulate(setup, every_step=True, progress=None)       # every step, as --csv keeps
    assert len(kept.trajectory.t) == 501
    start, end = setup.hooks.measuring(setup.values)
    t, dt = kept.trajectory.t, setup.values["dt"]
    inside = (t >= start - 1e-9 * dt) & (t <= end + dt)
    State = type(result.model.state)
    each = setup.module.amplitude_now(result.model, State(t=t[inside], r=kept.trajectory.r[inside],
                                                           p=kept.trajectory.p[inside], m=kept.trajectory.m))
    measured = setup.module.extra_json(result)["resonance"]["amplitude_m"]
    assert np.array_equal(np.ravel(measured), each.max(axis=0))
    assert measured == setup.module.extra_json(kept)["resonance"]["amplitude_m"]


def test_a_run_that_ends_before_its_window_ends_measures_no_amplitude():
    setup = configured("resonance", {"values": dict(count=3, curves=1, settle=4.0, periods=1.0, until=10.0)})
    model = setup.build()
    window = setup.hooks.measuring(setup.values)
    short = WindowLargest(lambda state: setup.module.measure_now(model, state), window=window,
                          initial=model.state, dt=model.dt)
    model.simulation(None).run_until(window[1] - 1.5 * model.dt, watches=(short,))
    assert short.largest is not None and not short.reached
    assert setup.module.amplitudes(setup, model, short) is None
    assert setup.module.sweep(setup).amplitude.shape == (1, 3)


def test_a_watch_sees_the_start_the_kept_steps_and_the_steps_it_asks_for_in_order():
    """The traced loop with a stride hands its rows over a block at a time; the watch sees them in
    order after the start, and the steps of its own schedule too, none of them kept."""
    model = catalog.configure("damped").build()
    seen = []

    class Sink:
        def add(self, t, x):
            seen.extend(zip(np.asarray(t).tolist(), np.asarray(x)[:, 0].tolist()))

    engine = model.simulation(None)
    samples = engine.advance(400, record=every(7), watches=(CoordinateWatch(Sink(), axis=1),))
    assert [t for t, _ in seen] == [model.state.t] + samples.t.tolist()
    assert [x for _, x in seen] == [model.state.r[0, 1]] + samples.r[:, 0, 1].tolist()
    seen.clear()
    engine = model.simulation(None)
    samples = engine.advance(400, record=every(50), watches=(CoordinateWatch(Sink(), axis=1, schedule=every(3)),))
    steps = sorted({0} | set(range(3, 401, 3)) | set(range(50, 401, 50)) | {400})
    assert [t for t, _ in seen] == [engine.time_of(n) for n in steps]
    assert len(samples) == 8                      # only every 50th step kept
    seen.clear()
    engine.advance(10, watches=(CoordinateWatch(Sink(), axis=1),))     # from step 400: no start again
    assert [t for t, _ in seen] == [engine.time_of(410)]


@pytest.mark.parametrize("seed", range(6))
def test_the_meter_fed_in_blocks_gives_each_mass_its_own_crossings_and_period(seed):
    rng = np.random.default_rng(seed)
    n, count = 600, 9
    t = np.cumsum(rng.uniform(0.01, 0.03, n))
    omega = rng.uniform(0.5, 6.0, count)
    x = np.sin(np.outer(t, omega) + rng.uniform(0, 6, count)) * rng.uniform(0.1, 2, count) + 0.3
    x[rng.integers(0, n, 5), rng.integers(0, count, 5)] = rng.choice([np.nan, np.inf, -np.inf], 5)
    x[:, 0] = -0.0                                                     # never rises through 0.3
    centres = np.full(count, 0.3)
    centres[1] = np.nan                                                # a mass without an equilibrium
    meter = CrossingMeter(centres)
    cuts = np.sort(rng.choice(np.arange(1, n), 40, replace=False))
    for block in np.split(np.arange(n), cuts):
        meter.add(t[block], x[block])
    found = meter.periods()
    for i in range(count):
        whole = upward_crossings(t, x[:, i], centre=centres[i])
        assert np.array_equal(meter.times[i], whole) and meter.counts()[i] == len(whole)
        assert found[i] == meter.period(i) == period_from_crossings(whole)
    assert meter.end == t[-1] and not len(meter.times[1]) and found[3] is not None


@pytest.mark.parametrize("shape, order", [((7, 3), "F"), ((7, 3), "C"), ((7, 1), "F"), ((7,), "C")])
def test_a_recorded_row_holds_each_array_in_row_order_whatever_its_layout(shape, order):
    arrays = [np.asarray(np.arange(np.prod(shape), dtype=float).reshape(shape) * 1.5 - 4, order=order)
              for _ in range(2)]
    arrays[1] = -arrays[1]
    row = _fill(np.empty(1 + 2 * arrays[0].size), 12, arrays)
    assert row[0] == 12 and np.array_equal(row[1:], np.concatenate([a.ravel() for a in arrays]))


def test_the_periods_of_a_row_are_cleaned_as_each_alone_would_be():
    setup = configured("resonance", {"values": dict(count=7, curves=2, b=0.0, settle=2.0, periods=1.0, until=6.0)})
    reports = periods(headless.simulate(setup, every_step=False, progress=None))
    expected = [None if period_json(report) is None else cleaned(period_json(report)) for report in reports]
    assert _cleaned_periods(reports) == expected
    assert any(entry is not None for entry in expected)

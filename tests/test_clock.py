"""The view's real-time stepping, tested with a fake clock (no browser, no vpython).

Simulation time must track speed × wall time with no drift, stop while paused or hidden, never
jump after a hiccup, and Reset must restore the start exactly.
"""
import math
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from physics.simulate import run
from scenes import catalog
from scenes.clock import LiveRun, RealTimeClock, StepBudget, Trace, window


def run_frames(clock, frame_times, *, speed=1.0, running=lambda i: True, max_steps=None):
    """Feed a clock the given wall-clock instants; returns the steps per frame."""
    clock.speed = speed
    return [clock.steps_due(now=now, running=running(i), max_steps=max_steps)
            for i, now in enumerate(frame_times)]


@pytest.mark.parametrize("dt", [1e-3, 1e-4, 0.01, 0.1])
@pytest.mark.parametrize("speed", [0.25, 0.5, 1.0, 2.0, 4.0])
def test_sim_time_tracks_speed_times_wall_time_without_drift(dt, speed):
    rng = np.random.default_rng(1)
    frame_times = np.cumsum(rng.uniform(0.005, 0.045, size=3000))  # about 75 s of uneven frames
    clock = RealTimeClock(dt=dt, now=0.0)
    steps = sum(run_frames(clock, frame_times, speed=speed))
    wall = frame_times[-1]
    # Carrying the fraction of a step means the total is within one step of speed × wall time.
    assert speed * wall - dt <= steps * dt <= speed * wall + 1e-9
    assert clock.dropped == 0.0


@settings(max_examples=60, deadline=None)
@given(dt=st.sampled_from([1e-4, 1e-3, 0.01, 0.1]), speed=st.sampled_from([0.25, 0.5, 1.0, 2.0, 4.0]),
       gaps=st.lists(st.floats(0.001, 0.2), min_size=1, max_size=300))
def test_no_step_is_lost_to_rounding(dt, speed, gaps):
    clock = RealTimeClock(dt=dt, now=0.0, max_frame=0.25)
    frame_times = np.cumsum(gaps)
    steps = sum(run_frames(clock, frame_times, speed=speed))
    assert steps == math.floor(speed * frame_times[-1] / dt + 1e-6) or \
        steps == math.floor(speed * frame_times[-1] / dt + 1e-6) - 1


def test_a_hiccup_costs_a_pause_not_a_jump():
    clock = RealTimeClock(dt=1e-3, now=0.0, max_frame=0.25)
    assert clock.steps_due(now=0.02) == 20
    assert clock.steps_due(now=5.02) == 250  # five seconds late: at most max_frame is made up
    assert clock.dropped == pytest.approx(4.75)
    assert clock.steps_due(now=5.04) == 20  # and then back to normal


def test_paused_or_hidden_owes_nothing_and_resumes_without_a_jump():
    clock = RealTimeClock(dt=1e-3, now=0.0)
    frames = np.arange(1, 501) * 0.02  # 10 s at 50 frames/s
    hidden = lambda i: not 100 <= i < 400  # hidden (or paused) from 2 s to 8 s
    steps = run_frames(clock, frames, running=hidden)
    assert all(n == 0 for n in steps[100:400])
    assert steps[400] == 20  # the first frame after: one frame's worth, not six seconds'
    assert sum(steps) == pytest.approx(4000, abs=1)
    assert clock.dropped == 0.0


def test_steps_per_frame_are_capped_and_the_backlog_is_not_carried():
    clock = RealTimeClock(dt=1e-4, now=0.0)
    steps = run_frames(clock, np.arange(1, 51) * 0.02, speed=4.0, max_steps=300)
    assert steps == [300] * 50  # 800 were due each frame; the model runs slower, never races
    assert clock.dropped == pytest.approx(50 * 500 * 1e-4, abs=2e-4)


def test_speed_change_and_restart():
    clock = RealTimeClock(dt=0.01, now=0.0)
    assert clock.steps_due(now=1.0) == 25  # 1 s is more than max_frame = 0.25 s
    clock.restart(now=1.0)
    assert clock.dropped == 0.0
    clock.speed = 4.0
    assert clock.steps_due(now=1.1) == 40


def test_step_budget_follows_the_measured_cost():
    budget = StepBudget(seconds_per_frame=0.01, first_guess=1e-4)
    assert budget.max_steps == 100
    for _ in range(50):
        budget.record(steps=1000, seconds=0.02)  # 20 µs per step
    assert budget.max_steps == pytest.approx(500, rel=0.01)
    budget.record(steps=1, seconds=5.0)  # too few steps to time: ignored
    assert budget.max_steps == pytest.approx(500, rel=0.01)


def live(name, integrator="euler-cromer", **changes):
    model = catalog.configure(name).with_values(**changes).build()
    return model, LiveRun(model, integrator=integrator, sample_every=0.05)


@pytest.mark.parametrize("name", catalog.SCENE_NAMES)
def test_reset_restores_the_start_exactly(name):
    model, runner = live(name)
    runner.advance(37)
    assert runner.state.t > 0
    [first] = runner.restart()
    assert runner.state is model.state  # reassignment: the very same initial state
    assert first.t == 0.0 and np.array_equal(first.r, model.state.r)
    assert first.energy["W_nc"] == 0.0


@pytest.mark.parametrize("integrator", ["euler-cromer", "verlet", "rk4"])
def test_batches_give_the_same_motion_as_one_headless_run(integrator):
    model, runner = live("driven", integrator=integrator)
    for steps in (1, 7, 0, 50, 142):
        runner.advance(steps)
    reference = run(model.state, model.forces, dt=model.dt, until=200 * model.dt, integrator=integrator)
    assert runner.state.t == pytest.approx(200 * model.dt)
    np.testing.assert_allclose(runner.state.r, reference.r[-1], rtol=0, atol=1e-12)


@pytest.mark.parametrize("dt, per_second", [(1e-3, 20), (0.01, 20), (0.1, 10)])
def test_samples_come_every_0_05_s_or_every_step_if_dt_is_longer(dt, per_second):
    model, runner = live("vertical", dt=dt)
    samples = runner.advance(round(1.0 / dt))
    assert len(samples) == per_second
    times = np.array([s.t for s in samples])
    assert np.all(np.diff(times) >= min(0.05, dt) - 1e-9)


def test_energy_principle_holds_along_a_damped_driven_run():
    """E − W_nc stays E(0) (energy principle); a wiring slip in W_nc would break it at once."""
    model, runner = live("driven", integrator="rk4", b=2.0, x0=1.0, dt=1e-3)
    start = runner.restart()[0].energy["E_minus_W_nc"]
    samples = runner.advance(5000)
    drift = max(abs(s.energy["E_minus_W_nc"] - start) for s in samples)
    lost = max(abs(s.energy["W_nc"]) for s in samples)
    assert lost > 0.5  # damping really did work, J
    assert drift < 1e-6 * max(1.0, lost)


def test_a_blow_up_stops_the_run_with_advice():
    model, runner = live("vertical", integrator="euler")  # euler is unstable on a spring
    for _ in range(100):
        runner.advance(100)
        if runner.problem:
            break
    assert runner.problem and "euler" in runner.problem
    t = runner.state.t
    assert runner.advance(10) == [] and runner.state.t == t


def test_trace_keeps_a_bounded_window_over_a_long_run():
    trace = Trace(span=30.0)
    redraws = 0
    for frame in range(36000):  # 30 minutes of samples at 20 per second, one per frame
        t = frame * 0.05
        redraws += trace.add([(t, math.sin(t))])
        assert len(trace.points) <= 2 * 30 * 20 + 1
    assert redraws == pytest.approx(1800 / 30, abs=2)  # a redraw every 30 s of simulation time
    assert trace.points[-1][0] - trace.points[0][0] <= 60.0
    assert trace.points[0][0] >= trace.points[-1][0] - 60.0


def test_graph_window_starts_at_zero_then_scrolls():
    assert window(3.0, span=30.0) == (0.0, 30.0)
    assert window(100.0, span=30.0) == (70.0, 100.0)


def test_importing_the_view_does_not_import_vpython():
    code = ("import sys, scenes.view, scenes.clock, scenes.loopback_server; "
            "sys.exit('vpython' in sys.modules)")
    assert subprocess.run([sys.executable, "-c", code], timeout=60).returncode == 0

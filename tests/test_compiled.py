"""The compiled loop (physics/compiled.py) against the engine's numpy tick it was traced from.

The loop is written by tracing the integrators' own vector code, so it must take the very same
steps: every integrator, every force, 1-D and 3-D, a few masses, the guard at |L| = 0, blow-up.
"""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from physics.compiled import MAX_COMPONENTS, compile_loop
from physics.forces import Driving, Gravity, LinearDamping, QuadraticDrag, Spring, SpringBetween
from physics.integrators import INTEGRATORS
from physics.simulate import BlowUpError, Simulation, every, run
from physics.state import make_state

SYSTEMS = {
    # the page's Simple Example: k = 40 N/m, m = 10 kg, L0 = 1 m, hanging under gravity
    "page spring": (lambda: make_state(r=(0.3, -1.5, 0.2), v=(0.1, 0.0, 0.4), m=10.0),
                    (Spring(k=40.0, L0=1.0), Gravity(g=9.8))),
    "every force": (lambda: make_state(r=(0.3, -1.5, 0.2), v=(0.1, 0.0, 0.4), m=10.0),
                    (Spring(k=40.0, L0=1.0), Gravity(g=9.8), LinearDamping(b=2.0),
                     QuadraticDrag(C=0.5, A=0.1, rho=1.2), Driving(F0=3.0, omega=2.0))),
    "zero-length spring": (lambda: make_state(r=(1.0, 0.5, 0.0), m=2.0),
                           (Spring(k=8.0, L0=0.0, anchor=(0.0, 1.0, 0.0)),)),
    "one line (1-D)": (lambda: make_state(r=(1.7,), v=(0.2,), m=1.5),
                       (Spring(k=5.0, L0=1.0, anchor=(0.0,)), Gravity(g=9.8, direction=(-1.0,)),
                        LinearDamping(b=0.3), Driving(F0=1.0, omega=1.5, axis=(1.0,)))),
    "three masses, own k and m": (lambda: make_state(r=[(0, -1.2, 0), (1, -1.5, 0), (2, -0.8, 0.1)],
                                                     m=[1.0, 2.0, 3.0]),
                                  (Spring(k=[10.0, 20.0, 30.0], L0=1.0, anchor=[(0, 0, 0), (1, 0, 0), (2, 0, 0)]),
                                   Gravity(g=9.8))),
    "chain of two": (lambda: make_state(r=[(0, -1.1, 0), (0.1, -2.3, 0)], m=[1.0, 1.0]),
                     (Spring(k=[30.0, 0.0], L0=1.0), SpringBetween(k=20.0, L0=1.0, i=0, j=1), Gravity(g=9.8))),
}


def both_paths(system, integrator, *, dt=1e-3, steps=3000, record=None):
    """The same advance of the engine with the compiled loop and with numpy alone."""
    make, forces = SYSTEMS[system]
    engines = [Simulation(make(), forces, dt=dt, integrator=integrator, compiled=compiled)
               for compiled in (True, False)]
    samples = [engine.advance(steps, record=record) for engine in engines]
    return engines, samples


@pytest.mark.parametrize("integrator", INTEGRATORS)
@pytest.mark.parametrize("system", SYSTEMS)
def test_the_loop_takes_the_numpy_steps(system, integrator):
    (fast, slow), (fast_rows, slow_rows) = both_paths(system, integrator, record=every(1000))
    assert fast._loop is not None and slow._loop is None, "this system should trace"
    # Same IEEE operations in the same order: equal, apart from numpy's cos against math.cos.
    for a, b in ((fast.state.r, slow.state.r), (fast.state.p, slow.state.p), (fast.work, slow.work)):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12)
    assert fast.t == slow.t == 3000 * 1e-3     # t = n·Δt from the step count, on both paths
    assert list(fast_rows.t) == list(slow_rows.t) == [1000 * 1e-3, 2000 * 1e-3, 3000 * 1e-3]
    np.testing.assert_allclose(fast_rows.r, slow_rows.r, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(fast_rows.work, slow_rows.work, rtol=1e-12, atol=1e-12)
    assert fast._loop.traces == 1, "no guard should have failed"


def test_the_work_meter_runs_inside_the_loop():
    (fast, slow), _ = both_paths("every force", "rk4")
    assert "a3_0" in fast._loop.source and fast.work[0] < 0    # damping and drag took energy away
    np.testing.assert_allclose(fast.work, slow.work, rtol=1e-12)


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_run_compiled_equals_run_with_numpy(integrator):
    make, forces = SYSTEMS["every force"]
    fast = run(make(), forces, dt=1e-3, until=5.0, integrator=integrator)
    slow = run(make(), forces, dt=1e-3, until=5.0, integrator=integrator, compiled=False)
    assert fast.r.shape == slow.r.shape == (5001, 1, 3)
    np.testing.assert_allclose(fast.t, slow.t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(fast.r, slow.r, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(fast.p, slow.p, rtol=1e-12, atol=1e-12)


def test_the_pages_simple_example_by_hand():
    """Δt = 0.1 s from rest at ⟨0, −1.5, 0⟩ m (k = 40 N/m, m = 10 kg, L0 = 1 m, g = 9.8 m/s²).

    Step 1: the spring is stretched 0.5 m and pulls up 40·0.5 = 20 N, gravity pulls down 98 N,
    so F_net = ⟨0, −78, 0⟩ N, p = ⟨0, −7.8, 0⟩ kg·m/s, r_y = −1.5 + (−0.78)(0.1) = −1.578 m.
    Step 2: stretched 0.578 m, F_net = 23.12 − 98 = −74.88 N, p_y = −15.288 kg·m/s,
    r_y = −1.578 + (−1.5288)(0.1) = −1.73088 m.
    """
    _, forces = SYSTEMS["page spring"]
    engine = Simulation(make_state(r=(0.0, -1.5, 0.0), m=10.0), forces, dt=0.1)
    engine.advance(100)                       # long enough to compile; then back to the start
    assert engine._loop is not None
    engine.restart()
    engine._loop = compile_loop(engine.tick, engine._arrays(), t0=0.0, dt=0.1)
    rows = engine.advance(2, record=every(1))
    assert list(rows.t) == [0.1, 0.2]
    assert (rows.p[0, 0, 1], rows.r[0, 0, 1]) == pytest.approx((-7.8, -1.578), abs=1e-12)
    assert (rows.p[1, 0, 1], rows.r[1, 0, 1]) == pytest.approx((-15.288, -1.73088), abs=1e-12)
    source = engine._loop.source
    assert "_sqrt(" in source and "numpy" not in source and "np." not in source


def test_a_mass_on_its_anchor_falls_back_to_numpy_and_traces_again():
    """Spring asks |L| ≠ 0 before dividing by |L|: the loop checks that guard every step."""
    forces = (Spring(k=40.0, L0=1.0), Gravity(g=9.8))
    on_anchor = make_state(r=(0.0, 0.0, 0.0), v=(0.0, 0.0, 0.0), m=10.0)
    fast = Simulation(on_anchor, forces, dt=0.01)
    fast._loop = compile_loop(fast.tick, [np.array([[0.0, -1.5, 0.0]]), fast._p, fast._power, fast.work],
                              t0=0.0, dt=0.01)                 # traced away from the anchor
    fast.advance(50)
    slow = Simulation(on_anchor, forces, dt=0.01, compiled=False)
    slow.advance(50)
    np.testing.assert_allclose(fast.state.r, slow.state.r, rtol=1e-12, atol=1e-15)
    assert fast._loop.traces == 2, "the first step (F = 0 on the anchor) is numpy's, then a new trace"


@pytest.mark.filterwarnings("ignore::physics.compiled.UntracedWarning")   # its own test: test_untraced_force.py
def test_a_force_the_tracer_cannot_follow_leaves_numpy_in_charge():
    class Opaque:
        """F = −k x written with float(): the tracer cannot see through it."""
        conservative, uses_velocity = True, False

        def __call__(self, t, r, v, m):
            return -5.0 * np.array([[float(r[0, 0]), 0.0, 0.0]])

    start = make_state(r=(1.0, 0.0, 0.0), m=1.0)
    engine = Simulation(start, (Opaque(),), dt=0.01)
    assert compile_loop(engine.tick, engine._arrays(), t0=0.0, dt=0.01) is None
    traj = run(start, (Opaque(),), dt=0.01, until=math.pi / math.sqrt(5.0))
    assert traj.r[-1, 0, 0] == pytest.approx(-1.0, abs=0.02)      # half a period: x = −A


def test_too_many_masses_are_left_to_numpy():
    n = MAX_COMPONENTS // 3 + 1
    start = make_state(r=np.tile((0.0, -1.5, 0.0), (n, 1)), m=1.0)
    engine = Simulation(start, (Spring(k=1.0, L0=1.0),), dt=0.01)
    assert compile_loop(engine.tick, engine._arrays(), t0=0.0, dt=0.01) is None


@pytest.mark.parametrize("integrator", ["euler-cromer", "euler"])
def test_blow_up_is_reported_alike(integrator):
    """ω Δt = 2.5 > 2: both paths raise the same sentence at the same check."""
    start = make_state(r=(0.0, -1.5, 0.0), m=1.0)
    forces = (Spring(k=100.0, L0=1.0), Gravity(g=9.8))
    messages = []
    for compiled in (True, False):
        with pytest.raises(BlowUpError) as error:
            run(start, forces, dt=0.25, until=1e4, integrator=integrator, compiled=compiled)
        messages.append(str(error.value))
    assert messages[0] == messages[1]


@settings(max_examples=40, deadline=None)
@given(k=st.floats(1.0, 100.0), m=st.floats(0.1, 20.0), L0=st.floats(0.0, 2.0), b=st.floats(0.0, 3.0),
       x=st.floats(-2.0, 2.0), y=st.floats(-3.0, -0.2), vx=st.floats(-1.0, 1.0),
       integrator=st.sampled_from(sorted(INTEGRATORS)))
def test_any_spring_agrees(k, m, L0, b, x, y, vx, integrator):
    dt = 0.2 / math.sqrt(k / m)        # ω Δt = 0.2: stable for every method over 300 steps
    start = make_state(r=(x, y, 0.0), v=(vx, 0.0, 0.0), m=m)
    forces = (Spring(k=k, L0=L0), Gravity(g=9.8), LinearDamping(b=b))
    fast = run(start, forces, dt=dt, until=300 * dt, integrator=integrator, record_every=None)
    slow = run(start, forces, dt=dt, until=300 * dt, integrator=integrator, record_every=None, compiled=False)
    np.testing.assert_allclose(fast.r[-1], slow.r[-1], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(fast.p[-1], slow.p[-1], rtol=1e-12, atol=1e-12)


def test_a_negative_base_to_a_fractional_power_is_left_to_numpy():
    """math.pow raises where ** would give a complex number; numpy's NaN then ends the run."""
    class Strange:
        conservative, uses_velocity = True, False

        def __call__(self, t, r, v, m):
            return -(r ** 1.5)      # NaN once a component goes negative

    start = make_state(r=(1.0, 0.5, 0.2), v=(-3.0, 0.0, 0.0), m=1.0)
    for compiled in (True, False):
        with pytest.raises(BlowUpError, match="non-finite"):
            run(start, (Strange(),), dt=0.01, until=10.0, compiled=compiled)

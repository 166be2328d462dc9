"""The compiled loop for one mass (physics/compiled.py) against the numpy step it was traced from.

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
from physics.simulate import BlowUpError, run
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


def numpy_steps(state, forces, dt, steps, integrator):
    step = INTEGRATORS[integrator]
    for _ in range(steps):
        state = step(state, forces, dt)
    return state


@pytest.mark.parametrize("integrator", INTEGRATORS)
@pytest.mark.parametrize("system", SYSTEMS)
def test_the_loop_takes_the_numpy_steps(system, integrator):
    make, forces = SYSTEMS[system]
    start, dt, steps = make(), 1e-3, 3000
    loop = compile_loop(INTEGRATORS[integrator], forces, dt, start)
    assert loop is not None, "this system should trace"
    rows = []
    end = loop.advance(start, 0, steps, every=1000, total=steps, record=rows.append)
    expected = numpy_steps(start, forces, dt, steps, integrator)
    # Same IEEE operations in the same order: equal, apart from numpy's cos against math.cos.
    np.testing.assert_allclose(end.r, expected.r, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(end.p, expected.p, rtol=1e-12, atol=1e-12)
    assert end.t == pytest.approx(expected.t, abs=1e-12)
    assert [round(row[0], 9) for row in rows] == [1.0, 2.0, 3.0]
    np.testing.assert_allclose(rows[-1][1:1 + end.r.size], end.r.ravel(), rtol=0, atol=0)
    assert loop.traces == 1, "no guard should have failed"


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
    make, forces = SYSTEMS["page spring"]
    start = make_state(r=(0.0, -1.5, 0.0), m=10.0)
    loop = compile_loop(INTEGRATORS["euler-cromer"], forces, 0.1, start)
    rows = []
    loop.advance(start, 0, 2, every=1, total=2, record=rows.append)
    (t1, *_, y1, _, _, py1, _), (t2, *_, y2, _, _, py2, _) = rows
    assert (t1, py1, y1) == pytest.approx((0.1, -7.8, -1.578), abs=1e-12)
    assert (t2, py2, y2) == pytest.approx((0.2, -15.288, -1.73088), abs=1e-12)
    assert "_sqrt(" in loop.source and "numpy" not in loop.source and "np." not in loop.source


def test_a_mass_on_its_anchor_falls_back_to_numpy_and_traces_again():
    """Spring asks |L| ≠ 0 before dividing by |L|: the loop checks that guard every step."""
    forces = (Spring(k=40.0, L0=1.0), Gravity(g=9.8))
    traced_at = make_state(r=(0.0, -1.5, 0.0), m=10.0)
    loop = compile_loop(INTEGRATORS["euler-cromer"], forces, 0.01, traced_at)
    on_anchor = make_state(r=(0.0, 0.0, 0.0), v=(0.0, 0.0, 0.0), m=10.0)
    end = loop.advance(on_anchor, 0, 50, every=50, total=50, record=lambda row: None)
    expected = numpy_steps(on_anchor, forces, 0.01, 50, "euler-cromer")
    np.testing.assert_allclose(end.r, expected.r, rtol=1e-12, atol=1e-15)
    assert loop.traces == 2, "the first step (F = 0 on the anchor) is numpy's, then a new trace"


def test_a_force_the_tracer_cannot_follow_leaves_numpy_in_charge():
    class Opaque:
        """F = −k x written with float(): the tracer cannot see through it."""
        conservative, uses_velocity = True, False

        def __call__(self, t, r, v, m):
            return -5.0 * np.array([[float(r[0, 0]), 0.0, 0.0]])

    start = make_state(r=(1.0, 0.0, 0.0), m=1.0)
    assert compile_loop(INTEGRATORS["euler-cromer"], (Opaque(),), 0.01, start) is None
    traj = run(start, (Opaque(),), dt=0.01, until=math.pi / math.sqrt(5.0))
    assert traj.r[-1, 0, 0] == pytest.approx(-1.0, abs=0.02)      # half a period: x = −A


def test_too_many_masses_are_left_to_numpy():
    n = MAX_COMPONENTS // 3 + 1
    start = make_state(r=np.tile((0.0, -1.5, 0.0), (n, 1)), m=1.0)
    assert compile_loop(INTEGRATORS["euler-cromer"], (Spring(k=1.0, L0=1.0),), 0.01, start) is None


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


def test_a_big_batch_run_in_blocks_takes_the_same_steps(monkeypatch):
    """Masses that do not act on one another may be stepped a block at a time (physics.simulate)."""
    import physics.simulate as simulate
    rng = np.random.default_rng(3)
    N = 50
    start = make_state(r=np.column_stack([rng.uniform(-0.3, 0.3, N), np.full(N, -1.5), np.zeros(N)]),
                       v=rng.uniform(-0.5, 0.5, (N, 3)), m=rng.uniform(1.0, 5.0, N))
    forces = (Spring(k=rng.uniform(20, 60, N), L0=rng.uniform(0.8, 1.2, N), anchor=rng.uniform(-1, 1, (N, 3))),
              Gravity(g=9.8, direction=(0.3, -1.0, 0.2)), LinearDamping(b=rng.uniform(0, 1, N)),
              Driving(F0=1.0, omega=rng.uniform(1, 5, N), axis=(1.0, 1.0, 0.0)))
    whole = run(start, forces, dt=1e-3, until=2.0, record_every=100)
    monkeypatch.setattr(simulate, "BLOCK_NUMBERS", 36)       # blocks of 12 masses: 12, 12, 12, 12, 2
    assert simulate._in_blocks(start, forces, "euler-cromer", False)
    blocks = run(start, forces, dt=1e-3, until=2.0, record_every=100)
    assert blocks.r.shape == whole.r.shape == (21, N, 3)
    np.testing.assert_array_equal(blocks.t, whole.t)
    np.testing.assert_array_equal(blocks.r, whole.r)
    np.testing.assert_array_equal(blocks.p, whole.p)
    coupled = forces + (SpringBetween(k=1.0, L0=1.0, i=0, j=1),)
    assert not simulate._in_blocks(start, coupled, "euler-cromer", False), "a chain must stay whole"


def test_a_batch_in_blocks_blows_up_as_the_whole_batch_does(monkeypatch):
    """The earliest blow-up of any block, with the whole batch's ω in the advice."""
    import physics.simulate as simulate
    N = 40
    k = np.full(N, 40.0)
    k[25] = 90_000.0          # one stiff spring: ω Δt = 3 > 2 at Δt = 0.01 s, in the third block
    k[5] = 40_030.0           # ω Δt = 2.0007: grows more slowly, in the first block
    start = make_state(r=np.tile((0.0, -1.5, 0.0), (N, 1)), m=1.0)
    forces = (Spring(k=k, L0=1.0), Gravity(g=9.8))
    with pytest.raises(BlowUpError) as whole:
        run(start, forces, dt=0.01, until=100.0, record_every=None)
    monkeypatch.setattr(simulate, "BLOCK_NUMBERS", 30)        # blocks of 10 masses
    assert simulate._in_blocks(start, forces, "euler-cromer", False)
    with pytest.raises(BlowUpError) as blocks:
        run(start, forces, dt=0.01, until=100.0, record_every=None)
    assert str(blocks.value) == str(whole.value)
    assert "ω = 300 rad/s" in str(blocks.value)


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

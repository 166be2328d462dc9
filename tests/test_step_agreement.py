"""The optimised stepping computes the page's update, to round-off.

physics/ computes the forces with a few speed-ups (a per-mass factor times L for the spring,
constants worked out once, column-major arrays, net force summed in place, runs that record only
some steps). Here a deliberately literal version of the page's loop, one mass at a time with
np.linalg.norm, checks that every batch step agrees with it to 1e-12 (relative), and the
speed-ups that should change nothing at all are checked bit for bit.

    F = −k (|L| − L0) L̂ + m g + (−b v) + (−½ C A ρ |v| v) + F0 cos(ω t) â
    p_f = p_i + F Δt;   v_f = p_f / m;   r_f = r_i + v_f Δt
"""
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from physics.forces import Driving, Gravity, LinearDamping, QuadraticDrag, Spring, net_force
from physics.integrators import INTEGRATORS, euler_cromer
from physics.state import State, make_state


def page_loop(*, r, v, m, k, L0, anchor, g, b, C, A, rho, F0, omega, axis, dt, steps):
    """The page's loop for each mass on its own, written as plainly as possible."""
    r_final = []
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    for i in range(len(m)):
        pos, p, t = np.array(r[i], dtype=float), m[i] * np.array(v[i], dtype=float), 0.0
        for _ in range(steps):
            L = pos - anchor[i]
            vel = p / m[i]
            F = (-k[i] * (np.linalg.norm(L) - L0[i]) * L / np.linalg.norm(L)
                 + m[i] * np.array([0.0, -g, 0.0])
                 - b[i] * vel
                 - 0.5 * C[i] * A * rho * np.linalg.norm(vel) * vel
                 + F0[i] * np.cos(omega[i] * t) * axis)
            p = p + F * dt
            pos = pos + p / m[i] * dt
            t = t + dt
        r_final.append(pos)
    return np.array(r_final)


@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), count=st.integers(1, 6))
def test_batch_step_agrees_with_the_literal_page_loop(seed, count):
    rng = np.random.default_rng(seed)
    p = dict(m=rng.uniform(0.5, 10.0, count), k=rng.uniform(5.0, 60.0, count), L0=rng.uniform(0.0, 1.5, count),
             b=rng.uniform(0.0, 2.0, count), C=rng.uniform(0.0, 1.0, count), F0=rng.uniform(0.0, 3.0, count),
             omega=rng.uniform(0.5, 6.0, count))
    anchor = rng.uniform(-1.0, 1.0, (count, 3))
    r0 = anchor + rng.uniform(-2.0, 2.0, (count, 3))
    v0 = rng.uniform(-1.0, 1.0, (count, 3))
    common = dict(g=9.8, A=0.1, rho=1.2, axis=(1.0, 2.0, -0.5))
    dt, steps = 0.002, 300
    forces = (Spring(k=p["k"], L0=p["L0"], anchor=anchor), Gravity(g=common["g"]), LinearDamping(b=p["b"]),
              QuadraticDrag(C=p["C"], A=common["A"], rho=common["rho"]),
              Driving(F0=p["F0"], omega=p["omega"], axis=common["axis"]))
    state = make_state(r=r0, v=v0, m=p["m"])
    for _ in range(steps):
        state = euler_cromer(state, forces, dt)
    expected = page_loop(r=r0, v=v0, anchor=anchor, dt=dt, steps=steps, **p, **common)
    np.testing.assert_allclose(state.r, expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_memory_layout_does_not_change_a_single_bit(integrator):
    """make_state stores r and p column-major for speed; a row-major state steps identically."""
    rng = np.random.default_rng(7)
    N = 40
    forces = (Spring(k=rng.uniform(10, 50, N), L0=rng.uniform(0.5, 1.5, N)), Gravity(g=9.8),
              LinearDamping(b=0.3), QuadraticDrag(C=0.5, A=0.1, rho=1.2), Driving(F0=1.0, omega=rng.uniform(1, 5, N)))
    fast = make_state(r=rng.uniform(-2, 2, (N, 3)), v=rng.uniform(-1, 1, (N, 3)), m=rng.uniform(1, 5, N))
    assert fast.r.flags.f_contiguous and fast.p.flags.f_contiguous
    plain = State(t=fast.t, r=np.ascontiguousarray(fast.r), p=np.ascontiguousarray(fast.p), m=fast.m)
    assert plain.r.flags.c_contiguous
    step = INTEGRATORS[integrator]
    for _ in range(50):
        fast, plain = step(fast, forces, 0.01), step(plain, forces, 0.01)
    np.testing.assert_array_equal(fast.r, plain.r)
    np.testing.assert_array_equal(fast.p, plain.p)


def test_spring_with_a_mass_at_its_anchor_gives_zero_force_there_and_hookes_law_elsewhere():
    """|L| = 0 leaves L̂ undefined: that row gets F = 0, with no numpy warning, the others F = −k(|L| − L0)L̂."""
    r = np.array([[0.0, 0.0, 0.0], [0.0, -1.5, 0.0], [3.0, 4.0, 0.0]])
    spring = Spring(k=[10.0, 40.0, 2.0], L0=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        F = spring(0.0, r, np.zeros_like(r), np.ones(3))
    np.testing.assert_array_equal(F[0], 0.0)
    np.testing.assert_allclose(F[1], [0.0, 40.0 * 0.5, 0.0], rtol=1e-15)            # 0.5 m stretched, pulls up
    np.testing.assert_allclose(F[2], -2.0 * (5.0 - 1.0) * np.array([0.6, 0.8, 0.0]), rtol=1e-15)


def test_zero_length_spring_is_minus_k_l_even_at_the_anchor():
    r = np.array([[0.0, 0.0, 0.0], [0.3, -2.0, 1.0]])
    F = Spring(k=5.0, L0=0.0, anchor=(0.0, 1.0, 0.0))(0.0, r, np.zeros_like(r), np.ones(2))
    np.testing.assert_allclose(F, -5.0 * (r - [0.0, 1.0, 0.0]), rtol=1e-15)


def test_forces_return_new_writable_arrays_and_net_force_leaves_its_inputs_alone():
    r = np.array([[0.1, -1.2, 0.0], [0.0, -0.8, 0.3]])
    v, m = np.array([[0.2, 0.0, 0.0], [0.0, 1.0, 0.0]]), np.array([2.0, 3.0])
    r_before, v_before = r.copy(), v.copy()
    gravity, drive = Gravity(g=9.8), Driving(F0=2.0, omega=3.0)
    first, second = gravity(0.5, r, v, m), gravity(0.5, r, v, m)
    assert first is not second and first.flags.writeable and drive(0.5, r, v, m).flags.writeable
    forces = [gravity, Spring(k=40.0, L0=1.0), drive]
    F_net = net_force(forces, 0.5, r, v, m)
    np.testing.assert_allclose(F_net, sum(force(0.5, r, v, m) for force in forces), rtol=1e-15)
    np.testing.assert_array_equal(gravity(0.5, r, v, m), first)      # adding into the sum changed nothing
    np.testing.assert_array_equal(r, r_before)
    np.testing.assert_array_equal(v, v_before)
    np.testing.assert_array_equal(net_force([], 0.0, r, v, m), np.zeros_like(r))


def test_one_dimensional_batches_need_one_component_vectors():
    """Motion along one line: r of shape (N, 1) with 1-component anchor, direction and axis."""
    r = np.array([[-1.5], [-1.2]])
    forces = (Spring(k=40.0, L0=1.0, anchor=(0.0,)), Gravity(g=9.8, direction=(-1.0,)), Driving(F0=1.0, omega=2.0, axis=(1.0,)))
    state = make_state(r=r, m=[10.0, 5.0])
    F = net_force(forces, 0.0, state.r, state.v, state.m)
    assert F.shape == (2, 1)
    # spring 40 · 0.5 up, gravity 98 down, drive 1 along +x (here the line's direction): −77 N; mass 2: 8 − 49 + 1.
    np.testing.assert_allclose(F, [[-77.0], [-40.0]], rtol=1e-14)


def test_forces_that_do_not_use_velocity_never_read_it():
    """euler_cromer passes v = None when no force in the list uses velocity."""
    from physics.forces import SpringBetween, uses_velocity
    r, m = np.array([[0.1, -1.2, 0.0], [0.0, -2.5, 0.3]]), np.array([2.0, 3.0])
    quiet = [Spring(k=40.0, L0=1.0), SpringBetween(k=10.0, L0=1.0, i=0, j=1), Gravity(g=9.8), Driving(F0=2.0, omega=3.0)]
    assert not uses_velocity(quiet)
    np.testing.assert_array_equal(net_force(quiet, 0.4, r, None, m), net_force(quiet, 0.4, r, np.ones_like(r), m))
    assert uses_velocity(quiet + [LinearDamping(b=1.0)]) and uses_velocity([QuadraticDrag(C=1.0, A=0.1, rho=1.2)])

"""Each force against its law: direction, magnitude, Newton's third law, per-mass parameters.

Spring        F = −k (|L| − L0) L̂,  L = r − anchor         U = ½ k (|L| − L0)²
SpringBetween F_i = −k (|L| − L0) L̂ = −F_j,  L = r_i − r_j
Gravity       F = m g (−ŷ)                                  U = m g y
LinearDamping F = −b v
QuadraticDrag F = −½ C A ρ |v| v
Driving       F = F0 cos(ω t) â
"""
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from physics.forces import (Driving, Gravity, LinearDamping, QuadraticDrag, Spring, SpringBetween,
                            net_force)
from physics.simulate import run
from physics.state import make_state
from scenes import catalog

FAST = settings(max_examples=50, deadline=None)
vectors = arrays(np.float64, 3, elements=st.floats(-10.0, 10.0))
positive = st.floats(0.1, 100.0)
NO_V = np.zeros((1, 3))
ONE_KG = np.ones(1)


def force_on_one(force, r, v=NO_V, m=ONE_KG, t=0.0):
    return force(t, np.atleast_2d(r), np.atleast_2d(v), m)[0]


@FAST
@given(r=vectors, anchor=vectors, k=positive, L0=st.floats(0.0, 5.0))
def test_spring_obeys_hookes_law_in_3d(r, anchor, k, L0):
    L = r - anchor
    length = np.linalg.norm(L)
    assume(length > 1e-3)
    F = force_on_one(Spring(k=k, L0=L0, anchor=anchor), r)
    stretch = length - L0
    assert np.linalg.norm(F) == pytest.approx(k * abs(stretch), rel=1e-9, abs=1e-9)
    assert np.linalg.norm(np.cross(F, L)) <= 1e-9 * max(1.0, np.linalg.norm(F) * length)
    if abs(stretch) > 1e-6:
        # stretched: pulls back toward the anchor; compressed: pushes away from it.
        assert np.sign(F @ L) == -np.sign(stretch)


@FAST
@given(direction=vectors, anchor=vectors, k=positive, L0=st.floats(0.1, 5.0))
def test_spring_force_vanishes_at_its_relaxed_length(direction, anchor, k, L0):
    assume(np.linalg.norm(direction) > 1e-3)
    r = anchor + L0 * direction / np.linalg.norm(direction)
    np.testing.assert_allclose(force_on_one(Spring(k=k, L0=L0, anchor=anchor), r), 0, atol=1e-9 * k)


@FAST
@given(r=vectors, k=positive, L0=st.floats(0.0, 3.0), m=positive)
def test_conservative_forces_are_minus_the_gradient_of_their_potential(r, k, L0, m):
    assume(np.linalg.norm(r) > 0.1)
    m = np.array([m])
    for force in (Spring(k=k, L0=L0), Gravity(g=9.8)):
        h = 1e-6
        gradient = [(force.potential_energy(np.atleast_2d(r + h * e), m)[0]
                     - force.potential_energy(np.atleast_2d(r - h * e), m)[0]) / (2 * h)
                    for e in np.eye(3)]
        F = force_on_one(force, r, m=m)
        np.testing.assert_allclose(F, -np.array(gradient), rtol=1e-5, atol=1e-5 * (1 + np.abs(F).max()))


@FAST
@given(r_i=vectors, r_j=vectors, k=positive, L0=st.floats(0.0, 5.0))
def test_spring_between_two_masses_obeys_newtons_third_law(r_i, r_j, k, L0):
    L = r_i - r_j
    assume(np.linalg.norm(L) > 1e-3)
    r = np.stack([r_i, np.full(3, 7.0), r_j])  # mass 1 is not attached
    F = SpringBetween(k=k, L0=L0, i=0, j=2)(0.0, r, np.zeros_like(r), np.ones(3))
    np.testing.assert_array_equal(F[0], -F[2])
    np.testing.assert_array_equal(F[1], 0.0)
    np.testing.assert_allclose(F[0], force_on_one(Spring(k=k, L0=L0, anchor=r_j), r_i), rtol=1e-12, atol=1e-12)


def test_gravity_is_m_g_along_minus_y_for_every_mass():
    m = np.array([1.0, 2.5, 10.0])
    r = np.zeros((3, 3))
    F = Gravity(g=9.8)(0.0, r, r, m)
    np.testing.assert_allclose(F, [[0, -9.8, 0], [0, -24.5, 0], [0, -98.0, 0]])
    np.testing.assert_allclose(Gravity(g=1.62)(0.0, r[:1], r[:1], m[:1]), [[0, -1.62, 0]])


@FAST
@given(v=vectors, b=st.floats(0.0, 50.0))
def test_linear_damping_is_minus_b_v(v, b):
    np.testing.assert_array_equal(force_on_one(LinearDamping(b=b), np.zeros(3), v), -b * v)


@FAST
@given(v=vectors, C=positive, A=st.floats(0.01, 2.0), rho=st.floats(0.1, 2.0))
def test_quadratic_drag_opposes_v_with_magnitude_half_c_a_rho_v_squared(v, C, A, rho):
    speed = np.linalg.norm(v)
    assume(speed > 1e-3)
    F = force_on_one(QuadraticDrag(C=C, A=A, rho=rho), np.zeros(3), v)
    assert F @ v < 0
    np.testing.assert_allclose(F / np.linalg.norm(F), -v / speed, atol=1e-12)
    assert np.linalg.norm(F) == pytest.approx(0.5 * C * A * rho * speed**2, rel=1e-12)


def test_drag_and_damping_vanish_at_rest():
    for force in (QuadraticDrag(C=1.0, A=0.5, rho=1.2), LinearDamping(b=3.0)):
        np.testing.assert_array_equal(force_on_one(force, np.ones(3), np.zeros(3)), 0.0)


def test_driving_force_is_f0_cos_omega_t_along_its_unit_axis():
    drive = Driving(F0=2.0, omega=4.0, axis=(3.0, 4.0, 0.0))     # â = (0.6, 0.8, 0)
    for t in (0.0, 0.3, 1.7):
        np.testing.assert_allclose(force_on_one(drive, np.zeros(3), t=t),
                                   2.0 * np.cos(4.0 * t) * np.array([0.6, 0.8, 0.0]))


def test_net_force_is_the_sum_of_the_forces():
    forces = [Spring(k=40.0, L0=1.0), Gravity(g=9.8), LinearDamping(b=1.0),
              QuadraticDrag(C=1.0, A=0.1, rho=1.2), Driving(F0=3.0, omega=2.0)]
    r, v, m = np.array([[0.3, -1.5, 0.2], [1.0, 1.0, 1.0]]), np.array([[0.1, -2.0, 0.5], [0, 0, 1]]), np.array([10.0, 2.0])
    expected = sum(force(0.4, r, v, m) for force in forces)
    np.testing.assert_allclose(net_force(forces, 0.4, r, v, m), expected, rtol=1e-14)
    # The page's first step by hand: spring 40 · 0.5 = 20 N up, gravity 98 N down.
    np.testing.assert_allclose(net_force(forces[:2], 0.0, np.array([[0, -1.5, 0]]), NO_V, np.array([10.0])),
                               [[0, -78.0, 0]])


def test_per_mass_parameters_step_like_separate_runs():
    """Three masses with their own m, k, L0, anchor, b, C and drive, stepped as one batch, move
    exactly as three single-mass runs do."""
    per_mass = dict(m=[1.0, 2.0, 5.0], k=[10.0, 40.0, 7.0], L0=[0.0, 1.0, 0.5], b=[0.0, 0.5, 2.0],
                    C=[0.0, 0.4, 1.0], F0=[1.0, 0.0, 2.0], omega=[3.0, 1.0, 0.5])
    anchors = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 0.0], [-1.0, 0.0, 3.0]])
    r0 = anchors + np.array([[0.5, -1.0, 0.0], [0.0, -1.5, 0.3], [0.2, 0.2, -0.9]])

    def system(i=slice(None)):
        p = {key: np.asarray(value)[i] for key, value in per_mass.items()}
        forces = (Spring(k=p["k"], L0=p["L0"], anchor=anchors[i]), Gravity(g=9.8),
                  LinearDamping(b=p["b"]), QuadraticDrag(C=p["C"], A=0.1, rho=1.2),
                  Driving(F0=p["F0"], omega=p["omega"], axis=(1.0, 1.0, 0.0)))
        return make_state(r=r0[i], v=(0.1, 0.0, 0.0), m=p["m"]), forces

    batch = run(*system(), dt=0.01, until=2.0)
    for i in range(3):
        alone = run(*system(slice(i, i + 1)), dt=0.01, until=2.0)
        np.testing.assert_allclose(batch.r[:, i], alone.r[:, 0], rtol=1e-12, atol=1e-13)
        np.testing.assert_allclose(batch.p[:, i], alone.p[:, 0], rtol=1e-12, atol=1e-13)


def test_a_falling_mass_with_drag_reaches_terminal_speed():
    """No spring (k = 0), gravity and air drag: the fall speeds up until ½ C A ρ v² = m g, at
    v_t = √(2 m g / (C A ρ)) = √(2 · 1 · 9.8 / (1 · 0.5 · 1.2)) = 5.715 m/s, reached after a few
    v_t / g = 0.58 s; from rest, v(t) = v_t tanh(g t / v_t)."""
    setup = catalog.configure("vertical", assignments=["k=0", "m=1", "C=1", "A=0.5", "rho=1.2"])
    model = setup.build()
    assert model.exact is None
    trajectory = run(model.state, model.forces, dt=0.001, until=6.0)
    v_t = np.sqrt(2 * 1.0 * 9.8 / (1.0 * 0.5 * 1.2))
    vy = trajectory.v[:, 0, 1]
    assert -vy[-1] == pytest.approx(v_t, rel=5e-3)
    assert np.all(np.diff(-vy) >= 0)                          # speeds up, never overshoots
    np.testing.assert_allclose(-vy, v_t * np.tanh(9.8 * trajectory.t / v_t), atol=0.01 * v_t)

"""The page's Simple and Middling Examples, worked by hand for two steps of Δt = 0.1 s.

A 10 kg mass hangs from a 40 N/m spring (L0 = 1 m) under an anchor at the origin, y up,
g = 9.8 N/kg, released from rest at r0 = <0, −1.5, 0> m. Each step, as the page teaches:

    F_net = F_spring + F_grav (+ F_damp),  p_f = p_i + F_net Δt,  v_f = p_f / m,  r_f = r_i + v_f Δt
"""
import numpy as np
import pytest

from physics.simulate import run
from scenes import catalog

m, k, L0, g, DT = 10.0, 40.0, 1.0, 9.8, 0.1


def two_steps(scene):
    model = catalog.configure(scene).build()
    assert model.dt == DT and model.until == pytest.approx(0.2)
    trajectory = run(model.state, model.forces, dt=model.dt, until=model.until)
    assert len(trajectory.t) == 3
    return trajectory


def test_simple_example_by_hand():
    trajectory = two_steps("vertical")
    # Step 1, at rest at y = −1.5 m: the spring is stretched |L| − L0 = 1.5 − 1 = 0.5 m.
    F_net = k * 0.5 - m * g                      # 20 N up − 98 N down = −78 N
    assert F_net == pytest.approx(-78.0)
    p1 = 0 + F_net * DT                          # −7.8 kg·m/s
    v1 = p1 / m                                  # −0.78 m/s
    y1 = -1.5 + v1 * DT                          # −1.578 m
    # Step 2: stretch 1.578 − 1 = 0.578 m, spring 40 · 0.578 = 23.12 N up.
    F_net = k * (1.578 - L0) - m * g             # 23.12 − 98 = −74.88 N
    p2 = p1 + F_net * DT                         # −7.8 − 7.488 = −15.288 kg·m/s
    v2 = p2 / m                                  # −1.5288 m/s
    y2 = y1 + v2 * DT                            # −1.578 − 0.15288 = −1.73088 m
    assert (p1, y1, p2, y2) == pytest.approx((-7.8, -1.578, -15.288, -1.73088))
    np.testing.assert_allclose(trajectory.r[:, 0], [[0, -1.5, 0], [0, y1, 0], [0, y2, 0]], atol=1e-12)
    np.testing.assert_allclose(trajectory.p[:, 0], [[0, 0, 0], [0, p1, 0], [0, p2, 0]], atol=1e-12)


def test_middling_example_by_hand():
    trajectory = two_steps("damped")
    b = 1.0
    # Step 1: at rest the damping force −b v is zero, so the step is the Simple Example's.
    p1, y1 = -7.8, -1.578                        # v1 = −0.78 m/s
    # Step 2: the damping force −b v = −1 · (−0.78) = +0.78 N points up, against the motion.
    F_net = k * (1.578 - L0) - m * g - b * (p1 / m)   # 23.12 − 98 + 0.78 = −74.1 N
    assert F_net == pytest.approx(-74.1)
    p2 = p1 + F_net * DT                         # −7.8 − 7.41 = −15.21 kg·m/s
    y2 = y1 + (p2 / m) * DT                      # −1.578 − 0.1521 = −1.7301 m
    assert (p2, y2) == pytest.approx((-15.21, -1.7301))
    np.testing.assert_allclose(trajectory.r[:, 0], [[0, -1.5, 0], [0, y1, 0], [0, y2, 0]], atol=1e-12)
    np.testing.assert_allclose(trajectory.p[:, 0], [[0, 0, 0], [0, p1, 0], [0, p2, 0]], atol=1e-12)


# Exact answers at t = 0.2 s. Equilibrium: y_eq = −(L0 + m g / k) = −(1 + 98/40) = −3.45 m, so the
# mass starts x0 = −1.5 − (−3.45) = 1.95 m above it, and ω = √(k/m) = 2 rad/s.
def simple_exact(t):
    return -3.45 + 1.95 * np.cos(2.0 * t)


def middling_exact(t):
    """Under-damped: γ = b/2m = 0.05 s⁻¹, ωd = √(ω² − γ²); from rest x = x0 e^(−γt)(cos ωd t + (γ/ωd) sin ωd t)."""
    gamma = 1.0 / (2 * m)
    omega_d = np.sqrt(4.0 - gamma**2)
    return -3.45 + 1.95 * np.exp(-gamma * t) * (np.cos(omega_d * t) + gamma / omega_d * np.sin(omega_d * t))


@pytest.mark.parametrize("scene, y_exact", [("vertical", simple_exact), ("damped", middling_exact)])
def test_the_scene_knows_the_exact_answer(scene, y_exact):
    model = catalog.configure(scene).build()
    r, _ = model.exact(np.array([0.0, 0.2, 1.0]))
    np.testing.assert_allclose(r[:, 0, 1], y_exact(np.array([0.0, 0.2, 1.0])), rtol=1e-12)
    if scene == "vertical":
        assert y_exact(0.2) == pytest.approx(-1.65393, abs=1e-5)   # vs −1.73088 m by hand


@pytest.mark.parametrize("scene, y_exact", [("vertical", simple_exact), ("damped", middling_exact)])
def test_the_iteration_converges_to_the_exact_answer_in_proportion_to_dt(scene, y_exact, observed_order):
    setup = catalog.configure(scene)
    dts = [0.1, 0.05, 0.025, 0.0125, 0.00625]
    errors = []
    for dt in dts:
        model = setup.with_values(dt=dt).build()
        trajectory = run(model.state, model.forces, dt=model.dt, until=model.until)
        assert trajectory.t[-1] == pytest.approx(0.2)
        errors.append(abs(trajectory.r[-1, 0, 1] - y_exact(0.2)))
    assert errors[0] == pytest.approx(abs(-1.73088 - simple_exact(0.2)) if scene == "vertical"
                                      else abs(-1.7301 - middling_exact(0.2)), abs=1e-9)
    assert all(later < earlier for earlier, later in zip(errors, errors[1:]))
    assert observed_order(dts[1:], errors[1:]) == pytest.approx(1.0, abs=0.15)

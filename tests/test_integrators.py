"""Every integrator against the exact solution: order of convergence, mixed steppers, blow-up.

A method of order p has a global error ∝ Δt^p: halving Δt divides the error by 2 for euler and
euler-cromer, 4 for verlet and 16 for rk4. The order is fitted from four Δt values, on three
systems: the undamped vertical spring with gravity (the page's Simple Example), a strongly damped
one (where verlet's velocity predictor is what keeps it second order), and a driven damped one.
"""
import warnings

import numpy as np
import pytest

from physics.integrators import INTEGRATORS
from physics.simulate import BlowUpError, run
from scenes import catalog

ORDER_TOLERANCE = {1: 0.25, 2: 0.3, 4: 0.5}
# Δt values in the asymptotic range of each order, yet not so small that round-off shows.
DTS = {1: [0.02, 0.01, 0.005, 0.0025], 2: [0.04, 0.02, 0.01, 0.005], 4: [0.08, 0.04, 0.02, 0.01]}

SYSTEMS = {
    # m = 10 kg, k = 40 N/m, L0 = 1 m, g = 9.8 m/s², released from rest at 1.5 m: ω = 2 rad/s.
    "undamped vertical": ("vertical", None, {}),
    # b = 20 kg/s: γ = b/2m = 1 s⁻¹, half of ω, so damping dominates the velocity error.
    "damped vertical": ("damped", None, {"b": 20.0}),
    # the page's driven scenario 5: b = 2 kg/s, F0 = 2 N, ω = 4 rad/s, x0 = 1 m.
    "driven damped": ("driven", 5, {}),
}


def max_error(model, integrator, dt, until):
    """Largest distance |r − r_exact| over the run, m."""
    trajectory = run(model.state, model.forces, dt=dt, until=until, integrator=integrator)
    r_exact, _ = model.exact(trajectory.t)
    return np.max(np.linalg.norm(trajectory.r - r_exact, axis=-1))


@pytest.mark.parametrize("system", SYSTEMS)
@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_order_of_convergence(integrator, system, observed_order):
    scene, scenario, changes = SYSTEMS[system]
    model = catalog.configure(scene, scenario=scenario).with_values(**changes).build()
    assert model.exact is not None
    order = INTEGRATORS[integrator].order          # what the registry claims, measured here
    dts = DTS[order]
    errors = [max_error(model, integrator, dt, until=3.0) for dt in dts]
    assert observed_order(dts, errors) == pytest.approx(order, abs=ORDER_TOLERANCE[order]), errors


def test_every_integrator_claims_an_order_this_file_can_measure():
    assert {entry.order for entry in INTEGRATORS.values()} <= set(DTS)


def test_a_tuple_of_names_steps_each_mass_by_its_own_method(line_oscillators):
    names = tuple(INTEGRATORS)
    count = len(names)
    params = dict(m=np.linspace(1.0, 3.0, count), k=np.linspace(10.0, 40.0, count),
                  b=np.linspace(0.0, 1.5, count), x0=np.linspace(0.5, -0.5, count), v0=0.3,
                  F0=1.0, omega=3.0)
    state, forces = line_oscillators(**params)
    together = run(state, forces, dt=0.01, until=2.0, integrator=names)
    for i, name in enumerate(names):
        alone_state, alone_forces = line_oscillators(**{key: np.broadcast_to(value, count)[i]
                                                        for key, value in params.items()})
        alone = run(alone_state, alone_forces, dt=0.01, until=2.0, integrator=name)
        np.testing.assert_allclose(together.r[:, i], alone.r[:, 0], rtol=1e-12, atol=1e-14)
        np.testing.assert_allclose(together.p[:, i], alone.p[:, 0], rtol=1e-12, atol=1e-14)
    # The methods really differ, so picking the wrong row would have been caught.
    assert len({together.r[-1, i, 0] for i in range(count)}) == count


STABLE_UP_TO = {name: entry.omega_dt_limit for name, entry in INTEGRATORS.items()
                if entry.omega_dt_limit is not None}


@pytest.mark.parametrize("integrator", STABLE_UP_TO)
def test_blow_up_beyond_the_stability_limit_names_dt_and_the_limit(integrator, line_oscillators):
    """On m x'' = −k x, ω = √(k/m) = 2 rad/s; ω·Δt just above the limit grows without bound."""
    limit = STABLE_UP_TO[integrator]
    omega = 2.0
    state, forces = line_oscillators(m=1.0, k=omega**2, x0=1.0)
    span = 300 * 1.05 * limit / omega
    dt = 1.05 * limit / omega
    with pytest.raises(BlowUpError) as blown:
        run(state, forces, dt=dt, until=span, integrator=integrator)
    message = str(blown.value)
    assert f"dt = {dt:g} s" in message
    assert f"ω·dt < {limit:.3g}" in message
    assert integrator in message


@pytest.mark.parametrize("integrator", STABLE_UP_TO)
def test_no_blow_up_just_below_the_stability_limit(integrator, line_oscillators):
    limit = STABLE_UP_TO[integrator]
    omega = 2.0
    state, forces = line_oscillators(m=1.0, k=omega**2, x0=1.0)
    span = 300 * 1.05 * limit / omega
    trajectory = run(state, forces, dt=0.95 * limit / omega, until=span, integrator=integrator)
    assert np.all(np.isfinite(trajectory.r))
    assert np.max(np.abs(trajectory.r[:, 0, 0])) < 10.0


def test_euler_blows_up_at_any_dt_and_says_so(line_oscillators):
    """Euler multiplies the energy by 1 + (ω Δt)² every step: even ω·Δt = 0.5 soon explodes."""
    state, forces = line_oscillators(m=1.0, k=4.0, x0=1.0)
    with pytest.raises(BlowUpError, match="unstable on a spring at every dt"):
        run(state, forces, dt=0.25, until=300 * 0.25, integrator="euler")


def test_page_dt_is_well_inside_the_limit_and_does_not_blow_up():
    """The Simple Example, ω·Δt = 2 rad/s × 0.1 s = 0.2, for 100 periods with the page's method."""
    model = catalog.configure("vertical").build()
    trajectory = run(model.state, model.forces, dt=model.dt, until=100 * np.pi)
    assert np.all(np.isfinite(trajectory.r))


@pytest.mark.parametrize("rate", [5.0, 20.0])
def test_strong_damping_limits_euler_cromer_dt_too(rate, line_oscillators):
    """Damping is stepped explicitly as well: a step multiplies (x, v) by a matrix of trace
    2 − (ωΔt)² − bΔt/m and determinant 1 − bΔt/m, stable exactly while (ωΔt)² + 2 (b/m) Δt < 4.
    With ω = 2 rad/s and b/m = 5 or 20 s⁻¹ that limit is far below ω·Δt = 2."""
    omega = 2.0
    dt_max = (-rate + np.sqrt(rate**2 + 4 * omega**2)) / omega**2
    state, forces = line_oscillators(m=1.0, k=omega**2, b=rate, x0=1.0)
    inside = run(state, forces, dt=0.97 * dt_max, until=300 * dt_max, integrator="euler-cromer")
    assert np.max(np.abs(inside.r[:, 0, 0])) <= 1.0
    dt = 1.05 * dt_max
    with pytest.raises(BlowUpError) as blown:
        run(state, forces, dt=dt, until=300 * dt_max, integrator="euler-cromer")
    message = str(blown.value)
    assert f"dt = {dt:g} s" in message
    assert "(ω·dt)² + 2·(b/m)·dt < 4" in message and f"dt < {dt_max:.4g} s" in message


@pytest.mark.parametrize("with_energy", [False, True])
def test_a_run_that_overflows_gives_one_clear_error_and_no_numpy_warnings(with_energy, line_oscillators):
    """ω·Δt = 20: each Euler-Cromer step multiplies x by about −(ωΔt)² ≈ −400, so the state
    overflows to inf and NaN long before the 256th step, where the blow-up guard looks."""
    state, forces = line_oscillators(m=1.0, k=4.0, x0=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(BlowUpError, match="non-finite state"):
            run(state, forces, dt=10.0, until=300 * 10.0, with_energy=with_energy)


# ---- chains: the fastest normal mode sets the limit ----

def two_mass_chain(*, k1, k2, m1, m2, L0=1.0, stretch=(0.2, -0.1)):
    """anchor —k1— m1 —k2— m2, hanging along −y without gravity, both springs stretched."""
    from physics.forces import Spring, SpringBetween
    from physics.state import make_state
    y1 = -(L0 + stretch[0])
    y2 = y1 - (L0 + stretch[1])
    state = make_state(r=[[0.0, y1, 0.0], [0.0, y2, 0.0]], m=[m1, m2])
    forces = (Spring(k=[k1, 0.0], L0=L0), SpringBetween(k=k2, L0=L0, i=0, j=1))
    return state, forces


def two_mass_fastest_omega(*, k1, k2, m1, m2):
    """The larger normal-mode ω of the two-mass chain, from det(K − ω² M) = 0:

        ω⁴ − ((k1 + k2)/m1 + k2/m2) ω² + k1 k2/(m1 m2) = 0.
    """
    s = (k1 + k2) / m1 + k2 / m2
    return np.sqrt(0.5 * (s + np.sqrt(s * s - 4 * k1 * k2 / (m1 * m2))))


@pytest.mark.parametrize("k1, k2, m1, m2", [(40.0, 40.0, 10.0, 10.0), (10.0, 70.0, 2.0, 0.5), (100.0, 3.0, 1.0, 9.0)])
def test_fastest_angular_frequency_of_a_two_mass_chain_is_its_fast_normal_mode(k1, k2, m1, m2):
    from physics.stability import fastest_angular_frequency
    state, forces = two_mass_chain(k1=k1, k2=k2, m1=m1, m2=m2)
    omega = fastest_angular_frequency(forces, state.m)
    assert omega == pytest.approx(two_mass_fastest_omega(k1=k1, k2=k2, m1=m1, m2=m2), rel=1e-12)
    assert omega > max(np.sqrt(k1 / m1), np.sqrt(k2 / m2))   # faster than any lone spring


def test_equal_two_mass_chain_is_the_golden_ratio_times_sqrt_k_over_m():
    """k1 = k2 = k, m1 = m2 = m: ω² = (3 ± √5)/2 · k/m, so the fast mode is φ √(k/m), φ = 1.618…."""
    from physics.stability import fastest_angular_frequency
    state, forces = two_mass_chain(k1=40.0, k2=40.0, m1=10.0, m2=10.0)
    golden = (1 + np.sqrt(5)) / 2
    assert fastest_angular_frequency(forces, state.m) == pytest.approx(golden * 2.0, rel=1e-12)


def test_long_uniform_chain_approaches_two_sqrt_k_over_m():
    """A chain of n equal masses and springs, fixed at the top, free at the bottom: ω_max =
    2 √(k/m) sin((2n − 1)π / (2(2n + 1))), just under 2 √(k/m)."""
    from physics.forces import Spring, SpringBetween
    from physics.stability import fastest_angular_frequency
    n, k, m = 30, 40.0, 10.0
    forces = [Spring(k=[k] + [0.0] * (n - 1), L0=0.5)] + [SpringBetween(k=k, L0=0.5, i=i, j=i + 1) for i in range(n - 1)]
    expected = 2 * np.sqrt(k / m) * np.sin((2 * n - 1) * np.pi / (2 * (2 * n + 1)))
    assert fastest_angular_frequency(forces, np.full(n, m)) == pytest.approx(expected, rel=1e-12)


def test_euler_cromer_on_a_chain_is_stable_just_below_two_over_its_fastest_mode_and_not_above():
    """Euler-Cromer steps each normal mode on its own, so the chain needs ω_fast·Δt < 2. With
    k = 40 N/m and m = 10 kg, √(k/m)·Δt is only 2/φ = 1.24 at the limit: the lone-spring ω would miss it."""
    state, forces = two_mass_chain(k1=40.0, k2=40.0, m1=10.0, m2=10.0)
    omega = two_mass_fastest_omega(k1=40.0, k2=40.0, m1=10.0, m2=10.0)
    span = 400 * 2 / omega
    inside = run(state, forces, dt=0.97 * 2 / omega, until=span)
    assert np.max(np.abs(inside.r[:, :, 1])) < 5.0
    dt = 1.03 * 2 / omega
    with pytest.raises(BlowUpError) as blown:
        run(state, forces, dt=dt, until=span)
    message = str(blown.value)
    assert f"dt = {dt:g} s" in message and "ω·dt < 2" in message
    assert f"dt < {2 / omega:.4g} s" in message and f"ω = {omega:.4g} rad/s" in message

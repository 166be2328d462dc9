"""Energy: what each integrator does to E = K + U, and the energy principle E − W_nc = E(0).

On the undamped spring, with x the displacement from equilibrium and z = ω x − i v (so that
z' = iω z), one step of euler or rk4 multiplies z by a complex amplification factor R(iωΔt),
the method's update applied to z' = iω z, so the oscillation energy ½ m |z|² is
multiplied by |R|² every step: 1 + (ωΔt)² for euler (it always grows), slightly below 1 for rk4
(it slowly leaks away). euler-cromer and verlet are symplectic: their energy wobbles within a
fixed band but never drifts, however long the run.
"""
import numpy as np
import pytest

from physics.energy import kinetic, potential
from physics.integrators import INTEGRATORS
from physics.simulate import run
from scenes import catalog

# The page's Simple Example: m = 10 kg, k = 40 N/m, L0 = 1 m, g = 9.8 m/s², so ω = 2 rad/s and
# the period is π s. Equilibrium hangs L0 + m g / k = 1 + 98/40 = 3.45 m below the anchor.
OMEGA = 2.0
PERIOD = np.pi
Y_EQUILIBRIUM = -3.45


@pytest.fixture
def simple_example():
    return catalog.configure("vertical").build()


@pytest.mark.parametrize("integrator, band", [
    ("euler-cromer", lambda h: h),        # wobble ≈ ωΔt/2 of the energy
    ("verlet", lambda h: h * h / 2),      # wobble ≈ (ωΔt)²/4
], ids=["euler-cromer", "verlet"])
def test_symplectic_energy_stays_bounded_for_1000_periods(integrator, band, simple_example,
                                                          oscillation_energy):
    dt = 0.2  # ωΔt = 0.4, 16 steps per period: coarse, to keep 1,000 periods quick
    trajectory = run(simple_example.state, simple_example.forces, dt=dt, until=1000 * PERIOD,
                     integrator=integrator)
    E = oscillation_energy(trajectory, simple_example.forces, (0.0, Y_EQUILIBRIUM, 0.0))
    # Released from rest 1.95 m above equilibrium: E(0) = ½ k x0² = ½ · 40 · 1.95² = 76.05 J.
    assert E[0] == pytest.approx(0.5 * 40 * 1.95**2)
    excursion = np.abs(E - E[0]) / E[0]
    per_100 = int(round(100 * PERIOD / dt))
    first, last = excursion[:per_100].max(), excursion[-per_100:].max()
    assert 0 < first < band(OMEGA * dt)
    assert last <= 1.05 * first


@pytest.mark.parametrize("integrator, factor", [
    ("euler", lambda z: abs(1 + z) ** 2),
    ("rk4", lambda z: abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24) ** 2),
], ids=["euler", "rk4"])
def test_each_step_multiplies_the_undamped_energy_by_the_amplification_factor(
        integrator, factor, oscillation_energy):
    """L0 = 0 keeps the spring linear however far the mass swings, so the factor is exact."""
    model = catalog.configure("vertical").with_values(L0=0.0).build()
    dt = 0.1
    trajectory = run(model.state, model.forces, dt=dt, until=10 * PERIOD, integrator=integrator)
    E = oscillation_energy(trajectory, model.forces, (0.0, -98 / 40, 0.0))
    per_step = factor(1j * OMEGA * dt)
    steps = np.arange(len(E))
    np.testing.assert_allclose(E, E[0] * per_step**steps, rtol=1e-8)
    if integrator == "euler":
        assert per_step == pytest.approx(1 + (OMEGA * dt) ** 2)
        assert np.all(np.diff(E) > 0)            # grows at every step...
        assert E[-1] / E[0] > 1e5                # ...by a huge factor in 10 periods
    else:
        assert np.all(np.diff(E) < 0)            # rk4 leaks energy, slowly
        assert 0.99 < E[-1] / E[0] < 1


def energy_drift(model, integrator, dt):
    """max |E − W_nc − E(0)| over the run, J."""
    trajectory = run(model.state, model.forces, dt=dt, until=3.0, integrator=integrator,
                     with_energy=True)
    conserved = trajectory.energy["E_minus_W_nc"]
    return np.max(np.abs(conserved - conserved[0]))


@pytest.mark.parametrize("system", ["damped", "driven"])
@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_e_minus_w_nc_is_constant_to_integrator_accuracy(integrator, system):
    """Damping takes energy away and driving adds it, but E − W_nc stays E(0); the error shrinks with Δt."""
    model = catalog.configure(system, scenario=5 if system == "driven" else None).build()
    # ω and the energy scale: 2 rad/s and ½ · 40 · 1.95² = 76 J for the hanging mass;
    # 5 rad/s and ½ · 100 · 1² = 50 J for the driven one.
    omega, scale = (OMEGA, 76.05) if system == "damped" else (5.0, 50.0)
    coarse, fine = energy_drift(model, integrator, 0.01), energy_drift(model, integrator, 0.005)
    assert fine < 0.6 * coarse                   # at least first order
    if integrator != "euler":                    # whose error grows exponentially instead
        assert fine < omega * 0.005 * scale


def energy_steps(model, integrator, dt, oscillation_energy, y_equilibrium, until=5.0):
    trajectory = run(model.state, model.forces, dt=dt, until=until, integrator=integrator)
    return np.diff(oscillation_energy(trajectory, model.forces, (0.0, y_equilibrium, 0.0)))


# The Middling Example: b = 1 kg/s, so damping removes energy at the rate b v².
@pytest.mark.parametrize("integrator, dt", [
    ("euler-cromer", 0.01), ("euler-cromer", 0.04),
    ("verlet", 0.01), ("verlet", 0.05), ("rk4", 0.01), ("rk4", 0.05)])
def test_with_damping_the_energy_never_increases(integrator, dt, oscillation_energy):
    model = catalog.configure("damped").build()
    dE = energy_steps(model, integrator, dt, oscillation_energy, Y_EQUILIBRIUM)
    assert np.all(dE <= 1e-12)
    assert np.sum(dE) < -10  # and a good part of the 76 J is gone after 5 s


def test_euler_cromer_can_gain_energy_when_dt_exceeds_2b_over_k(oscillation_energy):
    """As the mass passes equilibrium one step changes E by about Δt v² (kΔt/2 − b), so
    Euler-Cromer loses energy at every step only while Δt < 2b/k (exactly: see the next test).
    For the Middling Example 2b/k = 0.05 s: at the page's own Δt = 0.1 s some steps raise E,
    a numerical artefact."""
    model = catalog.configure("damped").build()
    dE = energy_steps(model, "euler-cromer", 0.1, oscillation_energy, Y_EQUILIBRIUM)
    assert np.any(dE > 0.1)
    assert np.sum(dE) < 0  # overall the damping still wins


@pytest.mark.parametrize("m, k, b", [(10.0, 40.0, 1.0), (1.0, 1.0, 0.1), (5.0, 2.0, 0.3), (1.0, 100.0, 0.5)])
def test_euler_cromer_never_gains_energy_exactly_while_dt_is_below_2bm_over_mk_plus_b2(
        m, k, b, line_oscillators):
    """One damped Euler-Cromer step maps (x, v) linearly, so its change of E = ½kx² + ½mv² is a
    quadratic form in (x, v); working it out, that form is ≤ 0 for every state exactly while
    Δt ≤ 2bm / (mk + b²) (≈ 2b/k for light damping). Check one step from 3,600 states all round
    the energy ellipse, just inside and just outside that Δt."""
    dt_max = 2 * b * m / (m * k + b * b)
    angle = np.linspace(0, 2 * np.pi, 3600, endpoint=False)
    x0, v0 = np.cos(angle) / np.sqrt(k), np.sin(angle) / np.sqrt(m)     # E = ½ J for each
    state, forces = line_oscillators(m=m, k=k, b=b, x0=x0, v0=v0)
    step = INTEGRATORS["euler-cromer"]

    def energy_change(dt):
        after = step(state, forces, dt)
        return (kinetic(after) + potential(after, forces)) - (kinetic(state) + potential(state, forces))

    assert np.max(energy_change(0.99 * dt_max)) <= 1e-12
    assert np.max(energy_change(1.01 * dt_max)) > 0


def test_euler_gains_energy_at_turning_points_even_with_damping_and_tiny_dt(oscillation_energy):
    """At a turning point v = 0, so damping does nothing, while euler's step multiplies the
    energy by 1 + (ωΔt)²: some steps always raise E, however small Δt is. The first turning
    point after the release is at t = π/2 s."""
    model = catalog.configure("damped").build()
    dE = energy_steps(model, "euler", 0.001, oscillation_energy, Y_EQUILIBRIUM, until=2.0)
    t = 0.001 * np.arange(1, len(dE) + 1)
    assert np.any(dE[(t > 1.4) & (t < 1.7)] > 0)


def test_energy_is_measured_from_rest_only_for_a_start_at_rest_at_equilibrium():
    """resonance's row starts at rest at equilibrium: its U there is the rest energy; the Simple
    Example starts stretched, so it has none (its energies are shown as they are)."""
    from physics.energy import rest_potential

    resonance = catalog.configure("resonance").build()
    assert rest_potential(resonance.state, resonance.forces) == pytest.approx(
        float(np.sum(potential(resonance.state, resonance.forces))))
    vertical = catalog.configure("vertical").build()
    assert rest_potential(vertical.state, vertical.forces) is None

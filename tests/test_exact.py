"""The closed forms of physics.exact against runs, and their own physical properties.

m x'' + b x' + k x = F0 cos(ω t). With ω0 = √(k/m) and γ = b/2m:
under-damped (b² < 4mk) rings down, critically damped (b² = 4mk) returns fastest without
crossing, over-damped (b² > 4mk) creeps back; a driven oscillator settles to the amplitude
F0 / √((k − mω²)² + (bω)²); undriven resonance (b = 0, ω = ω0) grows as F0 t / (2 m ω0).
"""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from physics import exact
from physics.forces import Driving, Gravity, LinearDamping, Spring
from physics.integrators import INTEGRATORS
from physics.simulate import run
from physics.state import make_state
from scenes import catalog

FAST = settings(max_examples=40, deadline=None)
positive = st.floats(min_value=0.1, max_value=100.0)

# m = 1 kg, k = 1 N/m, so 4mk = 4 kg²/s² and critical damping is b = 2 kg/s.
REGIME_B = {"under-damped": 1.0, "critically damped": 2.0, "over-damped": 5.0}


def test_damping_regime_classifies_b_squared_against_4mk():
    assert exact.damping_regime(m=2.0, k=8.0, b=7.9) == "under-damped"       # 62.41 < 64
    assert exact.damping_regime(m=2.0, k=8.0, b=8.0) == "critically damped"  # 64 = 64
    assert exact.damping_regime(m=2.0, k=8.0, b=8.1) == "over-damped"        # 65.61 > 64
    assert exact.damping_regime(m=1.0, k=1.0, b=0.0) == "under-damped"


@FAST
@given(m=positive, k=positive)
def test_critical_damping_squared_is_4mk(m, k):
    b = exact.critical_damping(m=m, k=k)
    assert b**2 == pytest.approx(4 * m * k, rel=1e-12)
    assert exact.damping_regime(m=m, k=k, b=b) == "critically damped"


def regime_runs(line_oscillators, integrator, dt):
    """The three regimes side by side, released from rest at x0 = 1 m; x(t) for each, m."""
    state, forces = line_oscillators(m=1.0, k=1.0, b=list(REGIME_B.values()), x0=1.0)
    trajectory = run(state, forces, dt=dt, until=10.0, integrator=integrator)
    return trajectory.t, trajectory.r[:, :, 0]


def exact_regimes(t):
    return np.stack([exact.oscillator(t, m=1.0, k=1.0, b=b, x0=1.0)[0] for b in REGIME_B.values()],
                    axis=-1)


def test_closed_forms_of_all_three_regimes_match_a_fine_rk4_run(line_oscillators):
    assert [exact.damping_regime(m=1.0, k=1.0, b=b) for b in REGIME_B.values()] == list(REGIME_B)
    t, x = regime_runs(line_oscillators, "rk4", 0.005)
    np.testing.assert_allclose(x, exact_regimes(t), atol=1e-9)


def test_euler_cromer_approaches_all_three_regimes_as_dt_shrinks(line_oscillators, observed_order):
    dts = [0.02, 0.01, 0.005]
    errors = []
    for dt in dts:
        t, x = regime_runs(line_oscillators, "euler-cromer", dt)
        errors.append(np.max(np.abs(x - exact_regimes(t)), axis=0))
    errors = np.array(errors)
    for column, regime in enumerate(REGIME_B):
        assert observed_order(dts, errors[:, column]) == pytest.approx(1, abs=0.25), regime


def test_the_closed_forms_start_where_they_are_told():
    for b in REGIME_B.values():
        x, v = exact.oscillator(np.array([0.0]), m=1.0, k=1.0, b=b, x0=0.7, v0=-0.3, F0=0.4, omega=1.7)
        assert (x[0], v[0]) == pytest.approx((0.7, -0.3))


@pytest.mark.parametrize("integrator", INTEGRATORS)
def test_critical_and_over_damping_from_rest_never_cross_equilibrium(integrator, line_oscillators):
    t, x = regime_runs(line_oscillators, integrator, 0.01)
    assert np.all(x[:, 1:] > 0)            # critical and over-damped stay on the start side
    assert np.any(x[:, 0] < 0)             # while the under-damped one swings through


def crossings(x) -> int:
    return int(np.sum(np.signbit(x[1:]) != np.signbit(x[:-1])))


@FAST
@given(m=positive, k=positive, x0=st.floats(0.01, 10.0))
def test_exact_critical_damping_from_rest_never_crosses(m, k, x0):
    gamma = np.sqrt(k / m)  # γ = b / 2m = ω0 at critical damping
    t = np.linspace(0, 30 / gamma, 2000)
    x, _ = exact.oscillator(t, m=m, k=k, b=exact.critical_damping(m=m, k=k), x0=x0)
    assert np.all(x > 0)


@FAST
@given(m=positive, k=positive, extra=st.floats(1.0, 10.0), x0=st.floats(-10.0, 10.0),
       v0=st.floats(-100.0, 100.0))
def test_exact_critical_and_over_damping_cross_at_most_once(m, k, extra, x0, v0):
    """x = A e^(λ₊t) + B e^(λ₋t) (or (c1 + c2 t) e^(−γt)) has at most one zero, whatever x0, v0."""
    b = extra * exact.critical_damping(m=m, k=k)
    slowest = b / (2 * m) - np.sqrt(max((b / (2 * m)) ** 2 - k / m, 0.0))
    t = np.linspace(0, 25 / slowest, 4000)
    x, _ = exact.oscillator(t, m=m, k=k, b=b, x0=x0, v0=v0)
    assert crossings(x) <= 1


# (m kg, k N/m, b kg/s, F0 N, ω rad/s), each with γ = b/2m ≥ 0.5 s⁻¹ so the transient dies in 30 s.
DRIVEN = [
    (1.0, 25.0, 1.0, 1.0, 3.0),     # below resonance (ω0 = 5 rad/s)
    (1.0, 25.0, 1.0, 1.0, 5.0),     # at resonance: A = F0 / (b ω) = 0.2 m
    (2.0, 8.0, 4.0, 3.0, 6.0),      # far above resonance (ω0 = 2 rad/s)
    (0.5, 50.0, 2.0, 0.5, 9.5),     # near resonance (ω0 = 10 rad/s)
    (4.0, 100.0, 4.0, 2.0, 4.0),    # the page's driven mass, more damped
]


def test_driven_steady_state_amplitude(line_oscillators):
    m, k, b, F0, omega = (np.array(column) for column in zip(*DRIVEN))
    state, forces = line_oscillators(m=m, k=k, b=b, F0=F0, omega=omega, x0=0.2)
    trajectory = run(state, forces, dt=0.01, until=30.0, integrator="rk4")
    expected = F0 / np.sqrt((k - m * omega**2) ** 2 + (b * omega) ** 2)
    np.testing.assert_allclose(exact.steady_state_amplitude(m=m, k=k, b=b, F0=F0, omega=omega),
                               expected, rtol=1e-12)
    for i, w in enumerate(omega):
        last_periods = trajectory.t > 30.0 - 3 * 2 * np.pi / w
        measured = np.max(np.abs(trajectory.r[last_periods, i, 0]))
        assert measured == pytest.approx(expected[i], rel=5e-3), DRIVEN[i]


@pytest.mark.parametrize("scenario", [4, 5])
def test_page_driven_scenarios_settle_to_the_steady_state_amplitude(scenario):
    """m = 4 kg, k = 100 N/m, b = 2 kg/s, F0 = 2 N; ω = 5 rad/s (resonance: A = F0/bω = 0.2 m) and
    ω = 4 rad/s (A = 2/√(36² + 8²) = 0.0542 m). γ = 0.25 s⁻¹: after 40 s e^(−γt) ≈ 5·10⁻⁵.
    Run with the scene's own method and Δt (euler-cromer, 0.01 s)."""
    setup = catalog.configure("driven", scenario=scenario)
    values = setup.values
    model = setup.build()
    trajectory = run(model.state, model.forces, dt=model.dt, until=40.0)
    x = trajectory.r[:, 0, 0] - values["L0"]
    last_periods = trajectory.t > 40.0 - 3 * 2 * np.pi / values["omega"]
    expected = values["F0"] / np.hypot(values["k"] - values["m"] * values["omega"] ** 2,
                                       values["b"] * values["omega"])
    assert np.max(np.abs(x[last_periods])) == pytest.approx(expected, rel=0.01)


def test_undamped_resonance_grows_linearly():
    """The page's scenario 1: b = 0, F0 = 1 N, ω = ω0 = 5 rad/s from rest at equilibrium.
    x = F0 t sin(ω0 t) / (2 m ω0): the envelope F0 t / (2 m ω0) = t / 40 m doubles from t to 2t."""
    setup = catalog.configure("driven", scenario=1)
    model = setup.build()
    trajectory = run(model.state, model.forces, dt=model.dt, until=40.0)
    x = trajectory.r[:, 0, 0] - setup.values["L0"]
    period = 2 * np.pi / 5.0

    def envelope(t):
        return np.max(np.abs(x[(trajectory.t > t - period) & (trajectory.t <= t + 1e-9)]))

    assert envelope(40.0) / envelope(20.0) == pytest.approx(2.0, rel=0.03)
    for t in (20.0, 40.0):
        assert envelope(t) == pytest.approx(1.0 * t / (2 * 4.0 * 5.0), rel=0.03)


MOTION = dict(m=2.0, k=8.0, L0=1.0, g=9.8, b=0.0, C=0.0, F0=0.0, omega=0.0,
              drive_axis=(1.0, 0.0, 0.0), anchor=(0.0, 0.0, 0.0), r0=(0.0, -1.5, 0.0),
              v0=(0.0, 0.0, 0.0))


@pytest.mark.parametrize("change", [
    {"C": 0.5},                               # quadratic drag: no closed form
    {"v0": (0.3, 0.0, 0.0)},                  # swings sideways: a pendulum, not a line
    {"r0": (0.5, -1.5, 0.0)},                 # spring tilted, gravity pulls it off the line
    {"F0": 1.0, "omega": 2.0},                # driven along x, across the vertical spring
    {"k": 0.0},                               # no spring at all
])
def test_single_mass_motion_has_no_closed_form_off_the_line(change):
    assert exact.single_mass_motion(**{**MOTION, **change}) is None


def test_single_mass_motion_exists_on_the_line():
    assert exact.single_mass_motion(**{**MOTION, "v0": (0.0, 2.0, 0.0), "b": 0.5,
                                       "F0": 1.0, "omega": 3.0, "drive_axis": (0.0, 1.0, 0.0)})


@pytest.mark.parametrize("case", [
    # L0 = 0: the spring is linear in 3-D, so any direction works; gravity, damping and a
    # diagonal drive all at once.
    dict(L0=0.0, b=0.7, F0=1.5, omega=2.5, drive_axis=(1.0, 1.0, 1.0), anchor=(0.5, 1.0, -0.5),
         r0=(1.0, -1.5, 0.3), v0=(0.4, 0.0, -0.8)),
    # L0 > 0 with no gravity: a diagonal line through a displaced anchor, driven along it.
    # (It stays 1.5 ± 0.9 m from the anchor: the closed form holds while it never passes it.)
    dict(g=0.0, b=0.3, F0=0.8, omega=1.5, drive_axis=(1.0, 2.0, 2.0), anchor=(1.0, 2.0, 3.0),
         r0=(1.5, 3.0, 4.0), v0=(0.1, 0.2, 0.2)),
])
def test_single_mass_motion_matches_a_fine_rk4_run(case):
    p = {**MOTION, **case}
    motion = exact.single_mass_motion(**p)
    assert motion is not None
    forces = (Spring(k=p["k"], L0=p["L0"], anchor=p["anchor"]), Gravity(g=p["g"]),
              LinearDamping(b=p["b"]), Driving(F0=p["F0"], omega=p["omega"], axis=p["drive_axis"]))
    state = make_state(r=p["r0"], v=p["v0"], m=p["m"])
    trajectory = run(state, forces, dt=0.005, until=3.0, integrator="rk4")
    r, v = motion(trajectory.t)
    np.testing.assert_allclose(trajectory.r[:, 0], r, atol=1e-8)
    np.testing.assert_allclose(trajectory.v[:, 0], v, atol=1e-8)


# ---- undamped resonance: no steady state, and no numpy warning on the way ----

def test_steady_state_amplitude_is_unbounded_at_undamped_resonance_without_a_warning():
    import warnings

    omega = np.array([4.0, 5.0, 6.0])                 # ω0 = √(25/1) = 5 rad/s
    with warnings.catch_warnings():
        warnings.simplefilter("error")                # a RuntimeWarning (divide by zero) fails
        A = exact.steady_state_amplitude(m=1.0, k=25.0, b=0.0, F0=1.0, omega=omega)
        assert A[1] == np.inf
        np.testing.assert_allclose(A[[0, 2]], [1 / 9, 1 / 11])    # F0 / |k − mω²|
        assert exact.steady_state_amplitude(m=1.0, k=25.0, b=0.0, F0=-2.0, omega=5.0) == -np.inf
        assert exact.steady_state_amplitude(m=1.0, k=25.0, b=0.0, F0=0.0, omega=5.0) == 0.0  # no drive
        # the closed form itself: x = F0 t sin(ω0 t) / (2 m ω0) from rest at equilibrium
        t = np.linspace(0.0, 10.0, 101)
        x, _ = exact.oscillator(t, m=1.0, k=25.0, b=0.0, F0=1.0, omega=5.0)
        np.testing.assert_allclose(x, t * np.sin(5 * t) / 10, atol=1e-12)


@FAST
@given(b=st.floats(min_value=1e-9, max_value=20.0), omega=st.sampled_from([0.5, 2.0, 4.0, 4.5, 6.0]),
       x0=st.floats(min_value=-2.0, max_value=2.0), v0=st.floats(min_value=-5.0, max_value=5.0),
       F0=st.floats(min_value=-3.0, max_value=3.0), undamped=st.booleans())
def test_displacement_bound_is_never_exceeded(b, omega, x0, v0, F0, undamped):
    # m = 1 kg, k = 16 N/m: ω0 = 4 rad/s, so ω = 4 with b = 0 is undamped resonance. b is 0 or at
    # least 1e-9 kg/s, as every b the program takes (scenes/_constants.py): at b = 5e-324 near
    # resonance the closed form itself is inf − inf in floating point.
    b = 0.0 if undamped else b
    T = 20.0
    t = np.linspace(0.0, T, 20_001)
    x, _ = exact.oscillator(t, m=1.0, k=16.0, b=b, x0=x0, v0=v0, F0=F0, omega=omega)
    bound = exact.displacement_bound(T, m=1.0, k=16.0, b=b, x0=x0, v0=v0, F0=F0, omega=omega)
    assert np.max(np.abs(x)) <= bound * (1 + 1e-9) + 1e-12

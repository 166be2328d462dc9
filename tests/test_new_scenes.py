"""The scenes of issue 4, headless: against closed forms, invariants and the physics they claim to show.

regimes      each of the three oscillators follows its exact curve; the critical one returns fastest
drag         linear damping takes the same fraction per period, e^(−bT/2m); quadratic drag a fraction
             that shrinks with the amplitude; falling balls reach their terminal speeds
pendulum     E = K + U is conserved and the motion is genuinely 3-D
integrators  euler gains energy by exactly (1 + (ωΔt)²) per step; euler-cromer and verlet stay
             bounded; rk4 stays closest to the exact motion
resonance    the batch's steady-state amplitudes are within 1 % of F0 / √((k − mω²)² + (bω)²)
"""
import inspect

import numpy as np
import pytest

from physics.exact import critical_damping, oscillator
from physics.forces import Gravity, LinearDamping
from physics.energy import kinetic, potential
from physics.simulate import run
from physics.state import State
from scenes import SCENE_NAMES, configure, load, presets
from scenes import ConstantError, read_constants
from scenes._row import rest_length

NEW_SCENES = ["regimes", "drag", "pendulum", "integrators", "resonance"]
SINGLE_MASS_CONSTANTS = {"m", "k", "L0", "g", "b", "C", "A", "rho", "F0", "omega", "drive_axis",
                         "anchor", "r0", "v0", "dt", "until"}


def build(name, **changes):
    return configure(name).with_values(**changes).build()


def simulate(model, *, integrator="rk4", until=None, dt=None, with_energy=False):
    return run(model.state, model.forces, dt=dt or model.dt, until=model.until if until is None else until,
               integrator=model.integrators or integrator, with_energy=with_energy)


def stretch_below_equilibrium(trajectory, setup):
    """x = y_eq − y for each hanging mass: its stretch below equilibrium, (n, N) m."""
    v = setup.values
    s_eq = rest_length(L0=v["L0"], m=v["m"], k=v["k"], g=v["g"])
    return -s_eq - trajectory.r[:, :, 1]


def peaks(x):
    """Values of the local maxima of a sampled curve, each refined by the parabola through 3 samples."""
    before, here, after = x[:-2], x[1:-1], x[2:]
    inside = (here > before) & (here >= after)
    before, here, after = before[inside], here[inside], after[inside]
    return here - (after - before) ** 2 / (8 * (after - 2 * here + before))


# ---- every new scene --------------------------------------------------------------------------

@pytest.mark.parametrize("name", NEW_SCENES)
def test_scene_is_listed_and_described(name):
    module = load(name)
    assert name in SCENE_NAMES
    assert module.__doc__.strip().splitlines()[0]
    assert module.VIEW["support"] in {"ceiling", "wall"} and module.VIEW["plot"] in {"x", "y", "z", "xyz"}
    defaults = configure(name).values
    for slider in module.VIEW.get("sliders", []):      # a slider needs a number to start from
        assert isinstance(defaults[slider], (int, float)), slider


@pytest.mark.parametrize("name", NEW_SCENES)
def test_every_constant_has_unit_and_meaning_and_build_takes_them_all(name):
    module = load(name)
    constants = read_constants(module)
    assert {"m", "k", "dt", "until"} <= set(constants)
    for constant in constants.values():
        assert constant.unit and constant.meaning, constant.name
    parameters = inspect.signature(module.build).parameters
    if any(p.kind is p.VAR_KEYWORD for p in parameters.values()):   # its block lists what it shows;
        assert SINGLE_MASS_CONSTANTS <= set(configure(name).constants)   # every force's is listed too
    else:
        assert set(parameters) == set(constants)


@pytest.mark.parametrize("name", NEW_SCENES)
def test_model_shapes_agree(name):
    model = configure(name).build()
    N = model.state.count
    assert model.anchors.shape == (N, 3) and len(model.labels) == N
    if model.exact is not None:
        r, v = model.exact(np.array([0.0, model.dt]))
        assert r.shape == v.shape == (2, N, 3)
        known = np.isfinite(r[0, :, 0])
        assert np.allclose(r[0][known], model.state.r[known]) and np.allclose(v[0][known], model.state.v[known])


@pytest.mark.parametrize("name, label", [(name, label) for name in NEW_SCENES
                                         for label, _ in presets(load(name))])
def test_presets_name_real_constants_and_apply(name, label):
    setup = configure(name)
    preset = dict(presets(setup))[label]
    assert set(preset) <= set(setup.constants)
    model = setup.with_values(**preset).build()
    if "g" in preset:
        (gravity,) = [f for f in model.forces if isinstance(f, Gravity)]
        assert gravity.g == preset["g"]


@pytest.mark.parametrize("name", ["pendulum", "drag"])
def test_gravity_presets_are_moon_earth_jupiter(name):
    offered = dict(presets(load(name)))
    assert sorted(p["g"] for p in offered.values() if set(p) == {"g"}) == [1.62, 9.8, 24.79]


@pytest.mark.parametrize("name", ["regimes", "resonance"])
def test_critical_preset_gives_b_equal_two_root_mk(name):
    setup = configure(name).with_values(m=2.0, k=18.0)
    model = setup.with_preset("critical damping").build()
    (damping,) = [f for f in model.forces if isinstance(f, LinearDamping)]
    b = np.broadcast_to(damping.b, (model.state.count, 1))[:, 0]
    # regimes: the middle mass; resonance: the first row (further rows have b · b_ratio^j)
    middle = b[1] if name == "regimes" else b[:setup.values["count"]]
    assert np.allclose(middle, 2 * np.sqrt(2.0 * 18.0))   # b_c = 2√(mk) = 12 kg/s


# ---- regimes ----------------------------------------------------------------------------------

def test_regimes_are_under_critical_over_with_the_set_fractions():
    setup = configure("regimes")
    model = setup.build()
    (damping,) = [f for f in model.forces if isinstance(f, LinearDamping)]
    b_c = critical_damping(m=setup.values["m"], k=setup.values["k"])
    assert np.allclose(damping.b[:, 0], [setup.values["under_fraction"] * b_c, b_c,
                                         setup.values["over_multiple"] * b_c])
    assert [label.split(" (")[0] for label in model.labels] == ["under-damped", "critically damped", "over-damped"]


def test_regimes_reject_negative_fractions_in_one_line():
    with pytest.raises(ConstantError, match="under_fraction must be 0 or more"):
        build("regimes", under_fraction=-0.1)


def test_regimes_follow_their_exact_curves():
    setup = configure("regimes")
    model = setup.build()
    trajectory = simulate(model)
    x = stretch_below_equilibrium(trajectory, setup)
    b_c = critical_damping(m=1.0, k=16.0)
    for i, b in enumerate([0.1 * b_c, b_c, 4.0 * b_c]):   # the file's defaults, worked out here
        x_exact, _ = oscillator(trajectory.t, m=1.0, k=16.0, b=b, x0=0.5)
        assert np.max(np.abs(x[:, i] - x_exact)) < 1e-5, model.labels[i]
    r_exact, _ = model.exact(trajectory.t)
    assert np.max(np.abs(trajectory.r - r_exact)) < 1e-5


def test_page_update_converges_to_the_regimes_first_order():
    model = configure("regimes").build()
    errors = []
    for dt in (0.01, 0.005):
        trajectory = simulate(model, integrator="euler-cromer", dt=dt, until=2.0)
        r_exact, _ = model.exact(trajectory.t)
        errors.append(np.max(np.abs(trajectory.r - r_exact)))
    assert 1.7 < errors[0] / errors[1] < 2.3


def test_critical_damping_returns_fastest_and_never_crosses():
    setup = configure("regimes")
    trajectory = simulate(setup.build())
    x = stretch_below_equilibrium(trajectory, setup)
    late = trajectory.t >= 2.0
    under, critical, over = np.max(np.abs(x[late]), axis=0)
    assert critical < under and critical < over
    assert np.min(x[:, 0]) < 0            # the under-damped one overshoots
    assert np.min(x[:, 1:]) > 0           # the other two never cross equilibrium


# ---- drag -------------------------------------------------------------------------------------

def test_default_b_takes_the_same_energy_as_drag_in_the_first_period():
    setup = configure("drag")
    values = {key: setup.values[key] for key in ("m", "k", "C", "A", "rho", "x0")}
    assert setup.module.matched_b(**values) == pytest.approx(setup.values["b"], rel=0.01)


@pytest.fixture(scope="module")
def drag_peaks():
    setup = configure("drag")
    trajectory = simulate(setup.build(), dt=0.01)
    x = stretch_below_equilibrium(trajectory, setup)
    return setup.values, peaks(x[:, 0]), peaks(x[:, 1])


def test_linear_damping_takes_a_constant_fraction_per_period(drag_peaks):
    values, linear, _ = drag_peaks
    m, k, b = values["m"], values["k"], values["b"]
    gamma = b / (2 * m)
    T = 2 * np.pi / np.sqrt(k / m - gamma**2)       # the damped period
    ratios = linear[1:] / linear[:-1]
    assert len(ratios) > 20
    assert np.allclose(ratios, np.exp(-gamma * T), atol=1e-3)


def test_quadratic_drag_takes_amplitude_fast_at_first_and_slowly_later(drag_peaks):
    values, linear, quadratic = drag_peaks
    ratios = quadratic[1:] / quadratic[:-1]
    assert ratios[-5:].mean() > ratios[:5].mean() + 0.01   # less lost per period as A shrinks
    assert np.all(np.diff(ratios[::4]) > 0)
    assert quadratic[-1] > 1.3 * linear[-1]                 # so late on it has kept more
    # energy balance averaged over a period: 1/A_n = 1/A0 + (4/3)(CAρ/m) n
    n = np.arange(1, len(quadratic) + 1)
    predicted = 1 / (1 / values["x0"] + 4 / 3 * values["C"] * values["A"] * values["rho"] / values["m"] * n)
    assert np.allclose(quadratic, predicted, rtol=0.02)


def test_falling_balls_reach_their_terminal_speeds():
    setup = configure("drag")
    setup = setup.with_values(**setup.module.PRESETS["falling, no spring"])
    v = setup.values
    trajectory = simulate(setup.build(), until=8.0, dt=0.01)
    speed = -trajectory.v[:, :, 1]
    g, m, b = v["g"], v["m"], v["b"]
    v_linear = m * g / b                                           # b v_t = m g
    v_quadratic = np.sqrt(2 * m * g / (v["C"] * v["A"] * v["rho"]))  # ½ C A ρ v_t² = m g
    assert np.allclose(speed[:, 0], v_linear * (1 - np.exp(-b * trajectory.t / m)), atol=1e-6)
    assert np.allclose(speed[:, 1], v_quadratic * np.tanh(g * trajectory.t / v_quadratic), atol=1e-6)
    assert speed[-1, 1] == pytest.approx(v_quadratic, rel=0.01)


# ---- pendulum ---------------------------------------------------------------------------------

@pytest.mark.parametrize("integrator, tolerance", [("rk4", 1e-7), ("verlet", 1e-3)])
def test_spring_pendulum_conserves_energy(integrator, tolerance):
    model = configure("pendulum").build()
    trajectory = simulate(model, integrator=integrator, until=5.0, with_energy=True)
    E = trajectory.energy["E"]
    assert np.max(np.abs(E - E[0])) < tolerance * abs(E[0])
    # the energy functions agree with K + U written out by hand at the start
    state, (k, L0, g) = model.state, (30.0, 1.0, 9.8)
    stretch = np.linalg.norm(state.r[0]) - L0
    by_hand = 0.5 * 1.0 * 0.3**2 + 0.5 * k * stretch**2 + 1.0 * g * state.r[0, 1]
    assert E[0] == pytest.approx(by_hand)
    assert E[0] == pytest.approx(float(kinetic(state)[0] + potential(state, model.forces)[0]))


def test_spring_pendulum_moves_in_three_dimensions():
    trajectory = simulate(configure("pendulum").build(), until=10.0)
    path = trajectory.r[:, 0, :]
    spread = np.linalg.svd(path - path.mean(axis=0), compute_uv=False) / np.sqrt(len(path))
    assert np.all(spread > 0.02)          # no plane holds the path: every direction spans > 2 cm rms
    assert np.ptp(path[:, 2]) > 0.1


def test_spring_pendulum_in_a_plane_stays_in_it():
    trajectory = simulate(build("pendulum", v0=(0, 0, 0)), until=5.0)
    assert np.max(np.abs(trajectory.r[:, 0, 2])) == 0.0


# ---- integrators ------------------------------------------------------------------------------

def integrator_run(*, periods, **changes):
    setup = configure("integrators").with_values(**changes)
    model = setup.build()
    T = 2 * np.pi * np.sqrt(setup.values["m"] / setup.values["k"])
    return setup, model, simulate(model, until=periods * T, with_energy=False)


def test_integrators_scene_steps_each_mass_by_its_own_method():
    model = configure("integrators").build()
    assert model.integrators == ("euler", "euler-cromer", "verlet", "rk4") == model.labels
    omega = np.sqrt(25.0 / 1.0)
    assert omega * model.dt == pytest.approx(0.3)


def test_euler_gains_exactly_one_plus_omega_dt_squared_per_step():
    setup, model, trajectory = integrator_run(periods=0)
    trajectory = simulate(model, until=20 * model.dt)
    x = trajectory.r[:, :, 0] - model.anchors[:, 0] - setup.values["L0"]
    v = trajectory.v[:, :, 0]
    omega_dt_sq = setup.values["k"] / setup.values["m"] * model.dt**2
    energy = 0.5 * setup.values["k"] * x**2 + 0.5 * setup.values["m"] * v**2
    steps = np.arange(len(trajectory.t))
    assert np.allclose(energy[:, 0], energy[0, 0] * (1 + omega_dt_sq) ** steps, rtol=1e-9)


def test_after_some_periods_euler_grew_the_others_did_not_and_rk4_is_closest():
    setup, model, trajectory = integrator_run(periods=4, x0=0.05)
    x0 = setup.values["x0"]
    x = trajectory.r[:, :, 0] - model.anchors[:, 0] - setup.values["L0"]
    late = np.max(np.abs(x[-len(x) // 4:]), axis=0)
    euler, cromer, verlet, rk4 = late
    assert euler > 5 * x0                            # e^(π ω Δt) per period: about 43× in 4 periods
    assert cromer < 1.2 * x0 and verlet < 1.05 * x0 and rk4 < 1.01 * x0
    r_exact, _ = model.exact(trajectory.t)
    errors = np.max(np.linalg.norm(trajectory.r - r_exact, axis=-1), axis=0)
    assert np.argmin(errors) == 3 and errors[3] < 0.01 * x0
    assert errors[0] == np.max(errors)


def test_smaller_dt_closes_up_the_integrators():
    errors = []
    for dt in (0.06, 0.004):
        _, model, trajectory = integrator_run(periods=1, dt=dt)
        r_exact, _ = model.exact(trajectory.t)
        errors.append(np.max(np.linalg.norm(trajectory.r - r_exact, axis=-1), axis=0))
    assert np.all(errors[1] < errors[0] / 10)     # Δt 15 times smaller: every method much closer


# ---- resonance --------------------------------------------------------------------------------

def test_default_resonance_curves_are_within_one_percent():
    setup = configure("resonance")
    result = setup.module.sweep(setup)
    v = setup.values
    assert result.amplitude.shape == result.exact.shape == (v["curves"], v["count"])
    assert np.allclose(result.b, v["b"] * v["b_ratio"] ** np.arange(v["curves"]))
    omega = result.omega[None, :]
    exact = v["F0"] / np.sqrt((v["k"] - v["m"] * omega**2) ** 2 + (result.b[:, None] * omega) ** 2)
    assert np.allclose(result.exact, exact)
    assert np.all(np.abs(result.amplitude / exact - 1) < 0.01)
    peak = np.argmax(result.amplitude[0])
    assert result.omega[peak] == pytest.approx(np.sqrt(v["k"] / v["m"]))   # the peak sits at ω0


@pytest.mark.parametrize("b", [0.4, 1.5, None])
def test_resonance_sweep_within_one_percent_for_other_damping(b):
    setup = configure("resonance").with_values(b=b, curves=1, count=9, m=0.5, k=8.0, F0=0.5,
                                               omega_min=1.5, omega_max=7.0, settle=20.0, periods=1.0)
    result = setup.module.sweep(setup)
    assert np.all(np.abs(result.amplitude / result.exact - 1) < 0.01)
    if b is None:   # critical damping: b² = 4mk > 2mk, so no peak at all
        assert np.all(np.diff(result.amplitude[0]) < 0)


def test_resonance_row_follows_the_exact_driven_motion():
    model = configure("resonance").with_values(count=5).build()    # 3 curves of b: 15 springs
    trajectory = simulate(model, until=5.0)
    r_exact, _ = model.exact(trajectory.t)
    assert np.max(np.abs(trajectory.r - r_exact)) < 1e-5
    assert len(set(model.labels)) == 15


def test_resonance_extra_json_gives_grid_and_amplitudes():
    from reports import headless

    setup = configure("resonance").with_values(count=4, curves=2, settle=5.0, periods=1.0, dt=0.05,
                                               until=10.0)
    data = setup.module.extra_json(headless.simulate(setup, every_step=False, progress=None))["resonance"]
    assert data["omega_rad_per_s"] == pytest.approx([2.0, 4.0, 6.0, 8.0])
    assert data["b_kg_per_s"] == pytest.approx([0.5, 1.0])
    assert np.shape(data["amplitude_m"]) == np.shape(data["exact_amplitude_m"]) == (2, 4)
    omega, smooth = np.array(data["smooth_omega_rad_per_s"]), np.array(data["smooth_exact_amplitude_m"])
    assert smooth.shape == (2, len(omega)) and omega[0] == 2.0 and omega[-1] == 8.0
    assert smooth[0][omega == 5.0] == pytest.approx(1.0 / (0.5 * 5.0))   # F0 / (b ω0) at ω = ω0
    # the peak sits a little below ω0, at √(k/m − b²/2m²)
    assert omega[np.argmax(smooth[0])] == pytest.approx(np.sqrt(25.0 - 0.5**2 / 2), abs=0.015)


@pytest.mark.parametrize("changes, message", [
    ({"count": 2.5}, "count must be a whole number"),
    ({"curves": 0}, "curves must be a whole number"),
    ({"omega_min": 6.0, "omega_max": 3.0}, "omega_min < omega_max"),
    ({"b_ratio": 0.0}, "b_ratio must be greater than 0"),
])
def test_resonance_rejects_bad_grids_in_one_line(changes, message):
    with pytest.raises(ConstantError, match=message):
        configure("resonance").with_values(**changes).build()


# ---- where the single-mass closed form holds (L0 > 0: on its own side of the anchor) ----------

def test_driven_scenario_two_reaches_the_wall_at_exactly_a_fifth_of_pi():
    # x0 = 1 m from equilibrium, L0 = 1 m, resonance: x = cos 5t + t sin(5t)/40. For 0 < t < π/5,
    # sin 5t > 0 so x > cos 5t ≥ −1; at t = π/5, x = −1 and s = L0 + x = 0: the mass is at the wall.
    model = configure("driven", scenario=2, assignments=["L0=1"]).build()
    assert model.exact_valid_until(20.0) == pytest.approx(np.pi / 5, abs=1e-9)
    assert model.exact_valid_until(0.5) == np.inf  # not yet, if we only look up to 0.5 s
    assert "anchor" in model.exact_limit


def test_a_mass_started_above_its_anchor_falls_through_it():
    # r0 = 0.5 m above the anchor, so û = +y and s0 = 0.5 m; gravity puts equilibrium at
    # s_eq = L0 − mg/k = 1 − 2.45 = −1.45 m, and s = s_eq + (s0 − s_eq) cos(2t) first reaches 0 at
    # cos(2t) = 1.45 / 1.95.
    model = configure("vertical", assignments=["r0=0,0.5,0"]).build()
    assert model.exact_valid_until(10.0) == pytest.approx(np.arccos(1.45 / 1.95) / 2, abs=1e-9)


@pytest.mark.parametrize("scene, scenario", [("vertical", None), ("damped", None), ("driven", 3),
                                             ("driven", 4), ("driven", 5)])
def test_the_page_examples_stay_on_their_side_of_the_anchor(scene, scenario):
    model = configure(scene, scenario=scenario).build()
    t = np.linspace(0.0, 200.0, 400_001)
    r, _ = model.exact(t)
    s = np.linalg.norm(r[:, 0] - model.anchors[0], axis=-1)
    assert s.min() > 0.05 and model.exact_valid_until(200.0) == np.inf


def test_zero_length_springs_have_no_anchor_limit():
    # L0 = 0: the spring is linear in 3-D, F = −k L, so the closed form holds through the anchor.
    model = configure("vertical", assignments=["L0=0", "r0=0,0.5,0"]).build()
    assert model.exact is not None and model.exact_valid_until is None


def test_the_figure_stops_drawing_the_exact_curve_where_it_stops_holding():
    model = configure("driven", scenario=2, assignments=["L0=1"]).build()
    t = np.linspace(0.0, 2.0, 201)
    r, v = model.exact_where_valid(t)       # what --plot draws (and the page, and the report)
    holds = t <= np.pi / 5
    assert np.all(np.isfinite(r[holds])) and np.all(np.isnan(r[~holds])) and np.all(np.isnan(v[~holds]))


# ---- rows: each mass's closed form holds until that mass reaches its own anchor ----------------

def test_a_row_judges_each_mass_against_its_own_anchor():
    # regimes with x0 = 3 m: equilibrium s_eq = L0 + mg/k = 1.6125 m below each anchor. The
    # under-damped mass (b = 0.8 kg/s) swings 3 m the other way, past its anchor; the critically
    # and over-damped ones never cross equilibrium, so they stay below theirs.
    from reports import headless, json_report, text as reports_text

    setup = configure("regimes").with_values(x0=3.0)
    model = setup.build()
    each = model.exact_valid_until.each(8.0)
    s_eq = rest_length(L0=1.0, m=1.0, k=16.0, g=9.8)
    assert np.isfinite(each[0]) and list(each[1:]) == [np.inf, np.inf]
    assert model.exact_valid_until(8.0) == each[0]
    x, _ = oscillator(np.array([each[0]]), m=1.0, k=16.0, b=0.8, x0=3.0)
    assert s_eq + x[0] == pytest.approx(0.0, abs=1e-9)           # s = 0: at the anchor
    x_before, _ = oscillator(np.linspace(0.0, each[0], 10_001)[:-1], m=1.0, k=16.0, b=0.8, x0=3.0)
    assert np.all(s_eq + x_before > 0)                             # and the first time there

    result = headless.simulate(setup, progress=None)
    out = json_report.as_json(result)
    under, critical, over = out["bodies"]
    assert "exact" not in under and "anchor" in under["exact_note"]
    assert under["exact_valid_until"] == pytest.approx(each[0])
    for body in (critical, over):
        assert body["exact"]["error"]["r"] < 1e-3 and "exact_note" not in body
    assert "1 of 3 masses" in out["exact_note"] and out["exact_valid_until"] == pytest.approx(each[0])
    text = reports_text.final_report(result).split("critically damped")
    assert f"exact: none at t = 8 s: the closed form stops holding at t = {each[0]:.4g} s" in text[0]
    assert "|r − r_exact|" not in text[0] and text[1].count("|r − r_exact|") == 2


@pytest.mark.parametrize("name", ["regimes", "drag", "integrators", "resonance"])
def test_the_row_scenes_defaults_stay_on_their_side_of_the_anchor(name):
    model = build(name)
    assert model.exact_valid_until.each(model.until).tolist() == [np.inf] * model.state.count
    r, _ = model.exact(np.array([0.0, model.until]))
    known = np.isfinite(r[0, :, 0])
    assert known.all() if name != "drag" else known.tolist() == [True, False]  # quadratic drag: no closed form


def test_resonance_refuses_a_derived_b_below_the_smallest_nonzero_value():
    # b = 0.5 kg/s · 0.001^99 = 5e-298 kg/s: round-off, not a damping constant (any nonzero value
    # given must be at least 1e-9 in size). 0.5 · 0.001² = 5e-7 still is one, 0.5 · 0.001³ is not.
    with pytest.raises(ConstantError) as refused:
        build("resonance", b_ratio=1e-3, curves=100)
    message = str(refused.value)
    assert "\n" not in message
    for part in ("b = 0.5 kg/s", "b_ratio = 0.001", "100 curves", "5e-298 kg/s", "1e-09 kg/s",
                 "use b_ratio = 0.817 or more, or at most 3 curves"):
        assert part in message, message
    for works in ({"b_ratio": 0.817, "curves": 100}, {"b_ratio": 1e-3, "curves": 3},
                  {"b": 0.0, "b_ratio": 1e-3, "curves": 100}):
        build("resonance", count=2, **works)
    for refused_too in ({"b_ratio": 0.816, "curves": 100}, {"b_ratio": 1e-3, "curves": 4}):
        with pytest.raises(ConstantError, match="less than the 1e-09 kg/s a nonzero b may be"):
            build("resonance", count=2, **refused_too)


def test_resonance_measures_v_with_the_one_v_equals_p_over_m(monkeypatch):
    from physics import state as state_module
    from scenes import resonance

    calls = []
    monkeypatch.setattr(resonance, "velocity", lambda p, m: calls.append(p.shape) or state_module.velocity(p, m))
    model = build("resonance", count=2)
    assert resonance.amplitude_now(model, model.state).shape == (6,) and calls == [(6, 1)]   # v_y only


def test_the_resonance_graph_says_b_zero_has_no_steady_state_at_omega0():
    # b = 0, ω = ω0 = 5 rad/s lies on the smooth grid (2 to 8 rad/s in 401 points): no finite A there
    setup = configure("resonance").with_values(b=0.0, curves=1)
    graph = setup.module.view_graph(setup)
    (label, xs, ys, _), = graph["lines"]
    assert np.all(np.isfinite(ys)) and np.isfinite(graph["ymax"])
    assert ys[xs == 5.0] == pytest.approx(graph["ymax"])      # the line runs to the top of the graph
    assert label == "b = 0 kg/s (unbounded at ω0 = 5 rad/s: no steady state)"


def test_the_resonance_curve_is_a_size_whatever_the_sign_of_F0():
    """A = √(x² + (v/ω)²) measured from the springs is a size; the exact curve is |F0|/√(...), so a
    drive of F0 = −1 N gives the same curve as +1 N (it was drawn upside down, below 0)."""
    from scenes import resonance

    values = {**configure("resonance").values, "count": 5}
    omega = np.linspace(2.0, 8.0, 9)
    down = resonance.curve_amplitude({**values, "F0": -1.0}, b=0.5, omega=omega)
    up = resonance.curve_amplitude({**values, "F0": 1.0}, b=0.5, omega=omega)
    assert np.all(down > 0) and np.array_equal(down, up)

"""The one engine (physics/simulate.Simulation) and the one stability judgement (physics/stability.py).

Every path asks the engine for its steps, so each path is checked here against the engine itself:
the headless run, the CSV file, the browser's live run and the resonance sweep reach the same
state after the same steps. The references are independent: the page's hand-worked steps, a
plain loop of the registry's step function written here, and closed forms.
"""
import csv
import io
import math
import re

import numpy as np
import pytest

from reports import csv_file, headless
from physics.forces import Gravity, QuadraticDrag, Spring
from physics.integrators import INTEGRATORS
from physics.simulate import BlowUpError, Cancelled, Simulation, every, time_grid
from physics.stability import amplification, judge, largest_stable_dt
from physics.state import make_state
from scenes import catalog
from browser.clock import LiveRun


def page_engine(**options):
    """The page's Simple Example: m = 10 kg, k = 40 N/m, L0 = 1 m, g = 9.8 m/s², from rest at y = −1.5 m."""
    return Simulation(make_state(r=(0.0, -1.5, 0.0), m=10.0), (Spring(k=40.0, L0=1.0), Gravity(g=9.8)),
                      dt=0.1, **options)


@pytest.mark.parametrize("compiled", [True, False])
def test_the_pages_two_hand_worked_steps(compiled):
    # F_net = 40·0.5 − 98 = −78 N, p = −7.8 kg·m/s, y = −1.5 − 0.78·0.1 = −1.578 m; then
    # F_net = 40·0.578 − 98 = −74.88 N, p = −15.288 kg·m/s, y = −1.578 − 1.5288·0.1 = −1.73088 m.
    engine = page_engine(compiled=compiled)
    rows = engine.advance(2, record=every(1))
    assert list(rows.t) == [0.1, 0.2]
    assert rows.p[:, 0, 1] == pytest.approx([-7.8, -15.288], abs=1e-12)
    assert rows.r[:, 0, 1] == pytest.approx([-1.578, -1.73088], abs=1e-12)


@pytest.mark.parametrize("integrator", INTEGRATORS)
@pytest.mark.parametrize("compiled", [True, False])
def test_advance_in_pieces_equals_one_run_bit_for_bit(integrator, compiled):
    setup = catalog.configure("driven", scenario=5)          # spring, gravity, damping, driving
    model = setup.build()
    whole = model.simulation(integrator, compiled=compiled)
    whole.advance(2500)
    pieces = model.simulation(integrator, compiled=compiled)
    for size in (1, 7, 150, 1024, 300, 1018):                 # 2500 steps in uneven pieces
        pieces.advance(size)
    assert pieces.steps == whole.steps == 2500
    assert np.array_equal(pieces.state.r, whole.state.r) and np.array_equal(pieces.state.p, whole.state.p)
    assert np.array_equal(pieces.work, whole.work) and pieces.t == whole.t


def test_run_until_continues_from_any_point():
    engine = page_engine()
    engine.run_until(3.0)
    engine.run_until(7.3)
    other = page_engine()
    other.advance(73)
    assert engine.steps == 73 and np.array_equal(engine.state.r, other.state.r)


def test_restart_returns_the_exact_start():
    engine = page_engine()
    start = engine.state
    engine.advance(500)
    engine.freeze(0, "a test")
    engine.restart()
    assert engine.state is start and engine.steps == 0 and engine.t == 0.0
    assert not engine.runaways and np.all(engine.work == 0)
    again = page_engine()
    engine.advance(300)
    again.advance(300)
    assert np.array_equal(engine.state.r, again.state.r)


def test_time_is_the_step_count_times_dt_never_a_running_sum():
    engine = Simulation(make_state(r=(0.0, -1.5, 0.0), m=10.0), (Spring(k=40.0, L0=1.0), Gravity(g=9.8)),
                        dt=1e-4)
    rows = engine.advance(600_000, record=every(100_000))
    assert engine.t == 600_000 * 1e-4 == 60.0      # one rounding, not 600,000 of them
    assert list(rows.t) == [n * 100_000 * 1e-4 for n in range(1, 7)]
    summed = 0.0
    for _ in range(600_000):
        summed += 1e-4
    assert summed != engine.t      # what t = t + dt would have printed: 60.00000000086826


def test_the_work_meter_keeps_the_energy_principle():
    """E − W_nc stays at E(0) to the integrator's accuracy (damped, driven, rk4)."""
    model = catalog.configure("driven", scenario=5).build()
    engine = model.simulation("rk4")
    start = engine.energy()
    engine.advance(4000)
    now = engine.energy()
    assert now["W_nc"] != 0.0
    # the trapezoid rule for W_nc is second order: at Δt = 0.01 s its error is about 1e-4 J
    assert now["E_minus_W_nc"] == pytest.approx(start["E_minus_W_nc"], abs=1e-3)


def test_cancel_stops_at_the_next_check():
    engine = page_engine()

    def progress(done, total, t):
        engine.cancel()

    import physics.simulate
    old, physics.simulate.PROGRESS_EVERY = physics.simulate.PROGRESS_EVERY, 0.0
    try:
        with pytest.raises(Cancelled):
            engine.advance(100_000, progress=progress)
    finally:
        physics.simulate.PROGRESS_EVERY = old
    assert 0 < engine.steps < 100_000


def test_a_time_grid_records_the_first_step_at_or_after_each_time():
    engine = page_engine()
    rows = engine.advance(20, record=time_grid(0.25, t0=0.0, dt=0.1), final=False)
    assert list(np.round(rows.t, 12)) == [0.3, 0.5, 0.8, 1.0, 1.3, 1.5, 1.8, 2.0]


# ---- every path against the engine ----

def engine_after(name, steps, *, integrator=None, **values):
    model = catalog.configure(name).with_values(**values).build()
    engine = model.simulation(integrator)
    engine.advance(steps)
    return engine


def test_headless_run_is_the_engines():
    setup = catalog.configure("damped").with_values(dt=0.01, until=3.0)
    result = headless.simulate(setup, progress=None)
    engine = engine_after("damped", 300, dt=0.01)
    assert result.steps == 300
    assert np.array_equal(result.trajectory.r[-1], engine.state.r)
    assert np.array_equal(result.trajectory.p[-1], engine.state.p)
    assert result.trajectory.energy["W_nc"][-1] == pytest.approx(engine.energy()["W_nc"], rel=1e-12)


def test_csv_rows_are_the_engines(tmp_path):
    setup = catalog.configure("vertical").with_values(dt=0.01, until=1.0)
    result = headless.simulate(setup, progress=None)
    path = tmp_path / "run.csv"
    csv_file.write_csv(result, str(path))
    rows = list(csv.DictReader(io.StringIO(path.read_text())))
    engine = engine_after("vertical", 100, dt=0.01)
    last = rows[-1]
    assert float(last["y"]) == pytest.approx(engine.state.r[0, 1], rel=1e-14)
    assert float(last["py"]) == pytest.approx(engine.state.p[0, 1], rel=1e-14)


@pytest.mark.parametrize("name", ["vertical", "integrators", "resonance"])
def test_the_browsers_live_run_is_the_engines(name):
    model = catalog.configure(name).build()
    live = LiveRun(model, integrator="euler-cromer")
    for frame in (3, 17, 120, 60):          # frames of uneven length, as the clock hands them out
        live.advance(frame)
    engine = model.simulation("euler-cromer", growth_limit=1e3)
    engine.advance(200)
    assert live.state.t == engine.t
    moving = [i for i in range(model.state.count) if i not in live.runaways]   # euler may be frozen
    assert np.array_equal(live.state.r[moving], engine.state.r[moving])
    assert np.array_equal(live.state.p[moving], engine.state.p[moving])


def test_the_resonance_sweep_is_the_scenes_own_run():
    setup = catalog.configure("resonance").with_values(count=6, curves=2, settle=30.0, periods=1.0,
                                                       until=34.0)
    result = headless.simulate(setup, every_step=False, progress=None)
    swept = setup.module.sweep(setup)
    from_json = setup.module.extra_json(result)["resonance"]["amplitude_m"]
    assert np.array_equal(np.array(from_json), swept.amplitude)
    assert np.all(np.abs(swept.amplitude / swept.exact - 1) < 0.02)


# ---- the one stability judgement ----

@pytest.mark.parametrize("name", INTEGRATORS)
def test_the_judgement_finds_each_methods_undamped_limit(name):
    """The limit comes from stepping the method itself; the registry states it once, as a check."""
    limit = INTEGRATORS[name].omega_dt_limit
    found = largest_stable_dt(name, omega=2.0, rate=0.0)
    if limit is None:
        assert found == 0.0       # euler: no Δt at all keeps an undamped spring from growing
    else:
        assert found * 2.0 == pytest.approx(limit, rel=1e-6)


@pytest.mark.parametrize("omega, rate", [(2.0, 30.0), (2.0, 5.0), (0.0, 30.0), (10.0, 1.0)])
def test_euler_cromer_with_damping_is_stable_exactly_while_the_textbook_rule_holds(omega, rate):
    """(ωΔt)² + 2(b/m)Δt < 4: the root of the quadratic in Δt."""
    root = (-2 * rate + math.sqrt(4 * rate**2 + 16 * omega**2)) / (2 * omega**2) if omega else 2 / rate
    assert largest_stable_dt("euler-cromer", omega=omega, rate=rate) == pytest.approx(root, rel=1e-6)


def test_amplification_of_euler_is_the_known_factor():
    # Euler on x'' = −ω²x: ρ = √(1 + (ωΔt)²) exactly.
    assert amplification("euler", omega=2.0, rate=0.0, dt=0.1)[0] == pytest.approx(math.sqrt(1.04), rel=1e-12)


def test_strong_damping_names_the_damping_and_its_limit_in_the_browser_and_on_the_command_line():
    """The issue's case: damped, b = 400 kg/s, dt = 0.06 s. Both paths say dt < 0.0499 s."""
    setup = catalog.configure("damped").with_values(b=400.0, dt=0.06)
    model = setup.build()
    live = LiveRun(model, integrator="euler-cromer")
    for _ in range(60):
        live.advance(20)
    assert live.problem is not None
    with pytest.raises(BlowUpError) as refused:
        headless.stability_warning(model, model.methods())
    for message in (live.problem, str(refused.value)):
        limit = float(re.search(r"dt < ([0-9.]+) s necessary", message).group(1))
        assert limit == pytest.approx(0.0499, abs=5e-5) and "damping (b/m = 40 s⁻¹)" in message
        assert "dt < 1 s" not in message


def test_euler_is_warned_about_only_where_its_motion_grows():
    decays = catalog.configure("damped").with_values(b=20.0).build()     # b/m = 2 s⁻¹ > ω²Δt = 0.4 s⁻¹
    assert judge(decays.forces, decays.state.m, ("euler",), decays.dt).stable
    assert headless.stability_warning(decays, ("euler",)) is None
    grows = catalog.configure("vertical").build()
    verdict = judge(grows.forces, grows.state.m, ("euler",), grows.dt)
    assert not verdict.stable and verdict.dt_max == 0.0
    assert "unstable on a spring at every dt" in verdict.message


def test_the_drag_is_named_at_the_present_speed():
    """Quadratic drag's stiffness is ρCA|v|/m: fast enough, it alone limits Δt."""
    forces = (QuadraticDrag(C=1.0, A=1.0, rho=1.2),)
    m = np.array([1.0])
    slow = judge(forces, m, ("euler-cromer",), 0.1, v=np.array([[0.0, -1.0, 0.0]]))
    assert slow.stable                                      # rate 1.2 s⁻¹: Δt < 1.67 s
    fast = judge(forces, m, ("euler-cromer",), 0.1, v=np.array([[0.0, -50.0, 0.0]]))
    assert not fast.stable and fast.cause == "drag"         # rate 60 s⁻¹: Δt < 2/60 s
    assert "the drag (ρCA|v|/m = 60 s⁻¹ at |v| = 50 m/s) makes dt < 0.03333 s necessary" in fast.message


def test_a_message_never_names_a_limit_above_the_dt_it_complains_about():
    for b, dt in ((400.0, 0.06), (300.0, 0.1), (0.0, 1.2), (50.0, 0.9)):
        model = catalog.configure("damped").with_values(b=b, dt=dt).build()
        verdict = judge(model.forces, model.state.m, model.methods(), dt)
        assert not verdict.stable and verdict.dt_max < dt, (b, dt, verdict)


def test_an_expected_runaway_is_frozen_and_the_others_run_on():
    model = catalog.configure("integrators").build()      # euler beside three stable methods
    live = LiveRun(model, integrator="euler-cromer")
    while not live.runaways and live.state.t < 400:
        live.advance(500)
    euler = model.labels.index("euler")
    assert list(live.runaways) == [euler] and live.problem is None
    t_frozen, reason = live.runaways[euler]
    assert "euler is unstable on a spring at every dt" in reason
    frozen_at = live.state.r[euler].copy()
    live.advance(500)
    assert np.array_equal(live.state.r[euler], frozen_at)          # held where it ran away
    assert live.state.t > t_frozen and np.all(np.isfinite(live.state.r))

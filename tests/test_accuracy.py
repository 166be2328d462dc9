"""Accuracy beside stability (physics/accuracy.py): a stable but inaccurate Δt is named, with a Δt
that would do, on the command line and the page alike."""
import json
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from physics import accuracy as acc
from physics.accuracy import SUGGEST_WITHIN, WARN_ABOVE, judge_dt, percent, round_down
from physics.forces import net_force
from physics.integrators import INTEGRATORS
from reports import headless
from scenes import _catalog as catalog

ROOT = Path(__file__).resolve().parents[1]


def judged(scene, integrator=None, **values):
    model = catalog.configure(scene).with_values(**values).build()
    return model, judge_dt(model.state, model.forces, model.methods(integrator), model.dt,
                           ignore=model.may_run_away)


def test_the_issue_case_is_stable_but_warned_about_with_a_delta_t_that_would_do():
    # ω = 2 rad/s, Δt = 0.9 s: ω·Δt = 1.8 < 2, inside euler-cromer's limit, yet far off.
    model, judgement = judged("vertical", dt=0.9, until=50.0)
    assert judgement.stability.stable
    a = judgement.accuracy
    assert not a.accurate and a.error > 1.0
    assert a.window == pytest.approx(3 * 2 * math.pi / 2.0)          # three periods of √(k/m) = 2 rad/s
    assert judgement.advice.startswith("Δt = 0.9 s is stable but inaccurate here")
    assert f"Δt ≤ {a.dt_advised:g} s keeps it within 1 %" in judgement.advice
    assert "e-" not in judgement.advice and "e+" not in judgement.advice


def test_the_page_default_and_a_small_delta_t_are_silent():
    for dt in (0.1, 0.01):
        _, judgement = judged("vertical", dt=dt)
        assert judgement.stability.stable and judgement.accuracy.accurate and judgement.advice is None


@pytest.mark.parametrize("scene", ["vertical", "damped", "driven", "regimes", "drag", "pendulum",
                                   "integrators", "resonance"])
def test_every_scene_as_shipped_is_not_warned_about(scene):
    _, judgement = judged(scene)
    assert judgement.advice is None


def test_the_estimate_matches_the_error_against_the_exact_solution():
    """Step doubling estimates the error the exact solution measures (within a factor of 2), for a
    first-, second- and fourth-order method on the Simple Example."""
    for method, dt in (("euler-cromer", 0.1), ("verlet", 0.3), ("rk4", 0.6)):
        model, judgement = judged("vertical", method, dt=dt)
        steps = math.ceil(judgement.accuracy.window / dt - 1e-9)
        engine = model.simulation(method)
        from physics.simulate import every
        samples = engine.advance(steps, record=every(1))
        r_exact, _ = model.exact(samples.t)
        error = np.max(np.linalg.norm(samples.r - r_exact, axis=-1))
        size = np.max(np.linalg.norm(r_exact - model.state.r[None], axis=-1))
        assert 0.5 < judgement.accuracy.error / (error / size) < 2.0, method


@pytest.mark.parametrize("method", list(INTEGRATORS))
def test_every_method_is_warned_about_where_stable_but_inaccurate_and_its_advice_is_silent(method):
    """Strong damping (b/m = 2 s⁻¹) keeps even euler stable at these Δt; each method is warned
    about at some stable Δt, and the Δt it is told to use passes the same judgement, within 1 %."""
    warned = None
    for dt in (0.3, 0.5, 0.7, 0.9, 1.1, 1.3):
        model, judgement = judged("damped", method, b=20.0, dt=dt)
        if judgement.stability.stable and judgement.advice:
            warned = (model, judgement)
            break
    assert warned is not None, f"{method} was never warned about"
    model, judgement = warned
    advised = judgement.accuracy.dt_advised
    assert advised is not None and advised < model.dt
    assert advised == round_down(advised)                               # 1, 2 or 5 × 10ⁿ s
    _, again = judged("damped", method, b=20.0, dt=advised)
    assert again.stability.stable and again.advice is None and again.accuracy.error <= SUGGEST_WITHIN


def test_euler_on_an_undamped_spring_gets_its_growth_warning_only():
    _, judgement = judged("vertical", "euler", dt=0.01)
    assert not judgement.stability.stable and judgement.accuracy is None and judgement.advice is None
    model = catalog.configure("vertical").with_values(dt=0.01).build()
    warning = headless.stability_warning(model, ("euler",))
    assert warning.startswith("warning: expect the motion to grow") and "inaccurate" not in warning


@pytest.mark.parametrize("method", ["euler-cromer", "verlet"])
def test_a_driven_run_is_warned_about_and_its_advice_is_silent(method):
    _, judgement = judged("driven", method, b=1.0, dt=0.3)
    assert judgement.stability.stable and judgement.advice
    _, again = judged("driven", method, b=1.0, dt=judgement.accuracy.dt_advised)
    assert again.advice is None


def test_a_scene_of_several_methods_leaves_out_the_one_that_runs_away():
    # integrators: euler grows at every Δt (expected to run away); the others are judged.
    model, judgement = judged("integrators", dt=0.2)
    assert judgement.stability.stable                     # the runaway is left out of the verdict
    assert judgement.advice and "Δt = 0.2 s is stable but inaccurate" in judgement.advice


def test_a_long_row_is_judged_on_a_sample_whose_forces_are_its_own_rows():
    model = catalog.configure("resonance").with_values(count=10000).build()
    methods = model.methods()
    state, forces, sampled, ignore = acc._sample(model.state, model.forces, methods, ())
    assert state.count == acc.MAX_JUDGED and ignore == ()
    rows = np.unique(np.linspace(0, model.state.count - 1, acc.MAX_JUDGED).round().astype(int))
    for t in (0.0, 0.37):
        full = net_force(model.forces, t, model.state.r, model.state.v, model.state.m)[rows]
        assert np.array_equal(net_force(forces, t, state.r, state.v, state.m), full)
    _, shipped = judged("resonance")
    big = judge_dt(model.state, model.forces, methods, model.dt)
    assert big.advice is None and big.accuracy.error == pytest.approx(shipped.accuracy.error, rel=0.5)


def test_round_down_gives_1_2_or_5_times_a_power_of_ten():
    for value in np.geomspace(1.1e-6, 900.0, 301):
        dt = round_down(value)
        mantissa = dt / 10 ** math.floor(math.log10(dt) + 1e-9)
        assert dt <= value and dt > value / 2.5
        assert min(abs(mantissa - x) for x in (1, 2, 5)) < 1e-9
    assert round_down(0.5) == 0.5 and round_down(0.09999999999) == 0.05 and round_down(1e-3) == 1e-3


def test_percent_is_two_significant_figures_in_plain_digits():
    assert percent(33.24) == "3,300 %" and percent(0.0312) == "3.1 %" and percent(0.01) == "1 %"
    assert percent(1e-7) == "0.00001 %" and percent(1.0) == "100 %"


def cli(*args):
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *args], capture_output=True, text=True,
                          timeout=120, cwd=ROOT)


def test_the_command_line_says_it_in_one_line_on_stderr_and_in_the_json_notes():
    args = ("vertical", "--headless", "--set", "dt=0.9", "--until", "50")
    text = cli(*args)
    assert text.returncode == 0
    lines = [line for line in text.stderr.splitlines() if "inaccurate" in line]
    assert len(lines) == 1 and lines[0].startswith("warning: Δt = 0.9 s is stable but inaccurate here")
    advised = float(re.search(r"Δt ≤ ([0-9.]+) s keeps it within 1 %", lines[0]).group(1))
    out = json.loads(cli(*args, "--json").stdout)
    # the same sentence, once, among the notes (which also say why exact_valid_until is null)
    accuracy = [note for note in out["notes"] if "stable but inaccurate" in note]
    assert accuracy == [lines[0].removeprefix("warning: ")] and out["dt"] == 0.9
    quiet = cli("vertical", "--headless", "--set", f"dt={advised:g}", "--until", "50")
    assert quiet.returncode == 0 and "inaccurate" not in quiet.stderr
    quiet = json.loads(cli("vertical", "--headless", "--json").stdout)
    assert not any("inaccurate" in note for note in quiet.get("notes", []))


def test_the_page_gets_the_same_line():
    from browser.clock import LiveRun

    model = catalog.configure("vertical").with_values(dt=0.9).build()
    live = LiveRun(model, integrator="euler-cromer")
    assert live.advice == headless.stability_warning(model, model.methods()).removeprefix("warning: ")
    live.restart()
    assert live.advice is not None
    assert LiveRun(catalog.configure("vertical").build(), integrator="euler-cromer").advice is None


def test_a_long_row_with_a_force_that_declares_no_rates_is_judged():
    """A teacher's force may be any object with conservative, uses_velocity and __call__, declaring no
    rates (physics/stability.py reads them with getattr) and holding no per-mass fields; the row's
    sampling must neither ask it for rates nor take it apart as a dataclass."""
    from physics.forces import Spring
    from physics.state import make_state

    class Push:
        """F = 0.1 N along x on every mass."""
        conservative, uses_velocity = False, False

        def __call__(self, t, r, v, m):
            F = np.zeros_like(r)
            F[:, 0] = 0.1
            return F

    count = 12
    start = make_state(r=np.column_stack([np.linspace(1.0, 2.0, count), np.zeros(count), np.zeros(count)]),
                       m=1.0)
    verdict = judge_dt(start, (Spring(k=25.0), Push()), ("euler-cromer",) * count, 0.01)
    assert verdict.stability.stable and verdict.accuracy is not None

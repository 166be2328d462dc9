"""The period, measured from the motion and from the formula (issue 30, item 2): physics/period.py.

Measured as a lab does, from the upward crossings of the equilibrium: checked against closed
forms (an undamped and a damped oscillator cross their centre every 2π/ω_d exactly), against
itself fed a few samples at a time (the page) and whole (the command line), and for the motions
that do not repeat. The formula's 2π/ω_d comes from the rates the forces declare, and is given
only where a closed form covers the forces and nothing drives the motion. The command line
prints it (--headless) and writes it (--json), as a subprocess, as a user runs it.
"""
from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from physics.equilibrium import equilibrium
from physics.forces import Driving, Gravity, LinearDamping, QuadraticDrag, Spring
from physics.period import (CrossingMeter, formula_period, measured_period, period_from_crossings, record_spacing,
                            upward_crossings)
from physics.simulate import Simulation, every
from physics.state import make_state
from scenes import catalog

ROOT = Path(__file__).resolve().parent.parent


@pytest.mark.parametrize("b", [0.0, 0.3, 1.5])
def test_a_damped_swing_crosses_its_centre_every_two_pi_over_omega_d(b):
    """x = e^(−γt) cos(ω_d t + φ) is zero every π/ω_d: upward every 2π/ω_d, exactly."""
    m, k = 2.0, 50.0
    omega_d = math.sqrt(k / m - (b / (2 * m)) ** 2)
    t = np.arange(0.0, 20.0, 0.01)
    x = 0.3 * np.exp(-b / (2 * m) * t) * np.cos(omega_d * t + 0.4) - 1.2
    period = measured_period(t, x, centre=-1.2)
    assert period.measured == pytest.approx(2 * math.pi / omega_d, rel=1e-5)
    assert period.spread < 1e-4 * period.measured
    assert period.cycles == len(upward_crossings(t, x, centre=-1.2)) - 1 >= 14


def test_fed_a_few_samples_at_a_time_the_crossings_are_those_of_the_whole_record():
    t = np.arange(0.0, 30.0, 0.05)
    x = np.stack([np.sin(2.0 * t + 0.1), 0.5 + np.cos(3.1 * t)], axis=1)
    meter = CrossingMeter([0.0, 0.5])
    for chunk in np.array_split(np.arange(len(t)), 37):
        meter.add(t[chunk], x[chunk])
    for i, centre in enumerate((0.0, 0.5)):
        whole = upward_crossings(t, x[:, i], centre=centre)
        assert np.array_equal(np.array(meter.times[i]), whole)
        assert meter.period(i) == period_from_crossings(whole)


def test_a_motion_that_does_not_repeat_has_no_measured_period():
    t = np.linspace(0.0, 10.0, 1001)
    assert measured_period(t, np.exp(-t), centre=0.0) is None              # over-damped: never crosses
    short = np.linspace(0.0, 4.0, 401)                                      # one and a bit cycles of 3.14 s
    assert measured_period(short, np.sin(2.0 * short - 0.1), centre=0.0) is None


def hanging(**constants):
    m, k, b = constants.get("m", 10.0), constants.get("k", 40.0), constants.get("b", 0.0)
    forces = [Spring(k=k, L0=1.0), Gravity(g=9.8)] + ([LinearDamping(b=b)] if b else [])
    forces += [QuadraticDrag(C=constants["C"], A=1.0, rho=1.2)] if constants.get("C") else []
    forces += [Driving(F0=constants["F0"], omega=3.0, axis=(0, 1, 0))] if constants.get("F0") else []
    return make_state(r=(0.0, -1.5, 0.0), m=m), forces


@pytest.mark.parametrize("b", [0.0, 1.0, 20.0])
def test_the_formula_reads_k_and_b_over_m_from_the_forces(b):
    state, forces = hanging(b=b)
    T, why = formula_period(forces, state, closed_form=True)
    assert T[0] == pytest.approx(2 * math.pi / math.sqrt(40.0 / 10.0 - (b / 20.0) ** 2), rel=1e-14) and why == ""


def test_the_formula_is_given_only_where_it_describes_the_motion():
    state, forces = hanging(b=40.0)                        # b² = 4mk: critically damped
    assert formula_period(forces, state, closed_form=True) == (None, pytest.approx(
        "b² ≥ 4mk: the damping is too strong for the motion to swing, so it has no period"))
    state, forces = hanging(F0=5.0)
    T, why = formula_period(forces, state, closed_form=True)
    assert T is None and "drive" in why
    state, forces = hanging(C=0.5)
    T, why = formula_period(forces, state, closed_form=False)
    assert T is None and "no closed form" in why


def engine_period(method: str, dt: float):
    """The measured period of the engine's own run of a damped hanging mass, recorded as the
    command line records it, and the formula's."""
    state, forces = hanging(b=2.0)
    engine = Simulation(state, forces, dt=dt, integrator=method)
    spacing = record_spacing(forces, state.m, dt)
    samples = engine.run_until(40.0, record=every(max(1, round(spacing / dt))))
    centre = equilibrium(forces, state)[0, 1]
    return measured_period(samples.t, samples.r[:, 0, 1], centre=centre), formula_period(forces, state, closed_form=True)[0][0]


@pytest.mark.parametrize("method, dt", [("rk4", 0.01), ("verlet", 0.002)])
def test_the_engines_period_matches_the_closed_form_within_its_stated_spread(method, dt):
    """The measured period against 2π/ω_d (damped, hanging), within the spread it states."""
    state, forces = hanging(b=2.0)
    centre = equilibrium(forces, state)[0, 1]
    assert centre == pytest.approx(-(1.0 + 10.0 * 9.8 / 40.0), rel=1e-12)
    period, formula = engine_period(method, dt)
    assert period.cycles >= 10
    assert 0 < period.spread < 1e-3 * period.measured                    # a spread that means something
    assert abs(period.measured - formula) <= period.spread


def test_the_pages_method_measures_a_period_that_closes_on_the_formula_at_first_order():
    """euler-cromer damps at first order, so its period is off by more than the spread of its
    cycles at Δt = 1 ms (the page says both numbers): halving Δt halves that difference."""
    (coarse, formula), (fine, _) = engine_period("euler-cromer", 0.002), engine_period("euler-cromer", 0.001)
    assert abs(coarse.measured - formula) > coarse.spread
    assert abs(coarse.measured - formula) / abs(fine.measured - formula) == pytest.approx(2.0, rel=0.05)


def cli(*args):
    done = subprocess.run([sys.executable, "main.py", *args], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_headless_prints_the_period_and_json_writes_it():
    text = cli("damped", "--headless", "--until", "30", "--integrator", "rk4", "--set", "dt=0.01")
    line = next(line for line in text.splitlines() if line.startswith("period: "))
    out = json.loads(cli("damped", "--headless", "--until", "30", "--integrator", "rk4", "--set", "dt=0.01", "--json"))
    period = out["period"]
    assert set(period) == {"measured", "spread", "cycles", "formula"} and out["units"]["period"] == "s"
    values = catalog.configure("damped").values
    omega_d = math.sqrt(values["k"] / values["m"] - (values["b"] / (2 * values["m"])) ** 2)
    assert period["formula"] == pytest.approx(2 * math.pi / omega_d, rel=1e-12)
    assert abs(period["measured"] - period["formula"]) <= period["spread"]
    assert period["cycles"] >= 8
    assert f"over {period['cycles']} cycles" in line and "formula 2π/ω_d = 3.14257 s" in line
    for key in ("t", "steps", "dt", "integrator", "r", "p", "v", "F_net", "exact", "exact_valid_until", "energy",
                "constants", "units"):
        assert key in out                              # every key the JSON had before is still there


def test_where_the_motion_does_not_repeat_the_period_is_null_with_a_note():
    out = json.loads(cli("vertical", "--headless", "--json"))                # 0.2 s: too short a run
    assert out["period"] is None
    assert any(note.startswith("period: null, ") and "too short" in note for note in out["notes"])
    out = json.loads(cli("vertical", "--headless", "--json", "--set", "k=0", "--until", "3"))   # a fall
    assert out["period"] is None and any("no equilibrium" in note for note in out["notes"])
    out = json.loads(cli("regimes", "--headless", "--json"))
    under, critical, over = out["bodies"]
    assert under["period"]["cycles"] >= 2 and critical["period"] is None and over["period"] is None
    assert "does not repeat" in critical["period_note"]
    text = cli("driven", "--headless")
    assert "no formula: a force changes with time (a drive)" in text

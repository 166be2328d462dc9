"""Sliding friction with static sticking (physics/forces/friction.py), against its piecewise closed form.

A block on a spring (k, relaxed length L0, along x) on a table with friction, let go from rest
x0 beyond the relaxed length. With d = μ_k m g / k, each half swing is an undamped oscillation
about a centre moved by d towards the side the block comes from: a swing that starts at rest at
x_n (from the relaxed length) ends at rest at x_(n+1) = 2c − x_n, c = d·sign(x_n), half a period
π/ω later, so |x_n| = x0 − 2 n d: the peaks lose 4 d a period, on a straight line. The block
stops for good at the first turning point inside the dead band |x| ≤ μ_s m g / k, where static
friction holds it. Every integrator of the registry is held to that, at several Δt; the fast
traced loop to the numpy step, bit for bit.
"""
from __future__ import annotations

import csv
import json
import math
import os
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from physics.forces import Spring, net_force
from physics.forces.friction import Friction
from physics.integrators import INTEGRATORS
from physics.simulate import Simulation, every, trajectory
from physics.state import make_state
from test_export import run_to_end, stand_in  # noqa: F401  (stand_in is a fixture)

ROOT = Path(__file__).resolve().parent.parent

M, K, G, MU_K, MU_S, X0, L0 = 0.5, 20.0, 9.8, 0.02, 0.06, 0.5, 1.0
OMEGA = math.sqrt(K / M)
D = MU_K * M * G / K                    # the centre's shift, m
BAND = MU_S * M * G / K                 # the dead band's half width, m


def closed_form(t, *, x0=X0):
    """x(t) from the relaxed length, m, and the turning points (t_n, x_n): the piecewise closed form."""
    turns, start, x_n = [], 0.0, x0
    while abs(x_n) > BAND:                              # static friction cannot hold it: a half swing
        turns.append((start, x_n))
        x_n = 2 * math.copysign(D, x_n) - x_n
        start += math.pi / OMEGA
    turns.append((start, x_n))                          # held from here on
    x = np.full_like(t, x_n)
    for (t_n, x_n), (t_next, _) in zip(turns, turns[1:]):
        c = math.copysign(D, x_n)
        inside = (t >= t_n) & (t < t_next)
        x[inside] = c + (x_n - c) * np.cos(OMEGA * (t[inside] - t_n))
    return x, turns


def block(*, mu_k=MU_K, mu_s=MU_S, x0=X0, v0=0.0, k=K):
    """One block on a spring along x, on the table: the state and its forces."""
    state = make_state(r=[L0 + x0, 0.0, 0.0], v=[v0, 0.0, 0.0], m=M)
    return state, (Spring(k=k, L0=L0, anchor=(0.0, 0.0, 0.0)), Friction(mu_k=mu_k, mu_s=mu_s, g=G))


def run(method, dt, until=30.0, **options):
    state, forces = block(**options)
    engine = Simulation(state, forces, dt=dt, integrator=method)
    samples = engine.run_until(until, record=every(1))
    traj = trajectory(engine, samples)
    return traj.t, traj.r[:, 0, 0] - L0, traj.p[:, 0, 0], engine


# Δt for each method: euler gains energy every step (its energy grows by (ωΔt)² a step), so it
# needs a Δt small enough that friction wins; the others run at the page's Δt and below.
STEPS = {"euler-cromer": (0.01, 0.004, 0.001), "verlet": (0.01, 0.004, 0.001), "rk4": (0.01, 0.004, 0.001),
         "euler": (1e-4, 5e-5)}
CASES = [(method, dt) for method in INTEGRATORS for dt in STEPS[method]]


def test_every_integrator_has_its_steps_here():
    assert set(STEPS) == set(INTEGRATORS)


@pytest.mark.parametrize("method, dt", CASES)
def test_the_block_stops_in_the_dead_band_and_stays_there(method, dt):
    """It stops where the closed form says, within one half swing, inside |x| ≤ μ_s m g/k; from then
    on every step leaves it exactly where it is, at rest: no chatter, no creeping. (euler's own
    energy gain, about 1 + (ωΔt)² a step, over some 10⁵ steps lets it swing up to three more halves.)"""
    t, x, p, _ = run(method, dt)
    _, turns = closed_form(t)
    t_stop, x_stop = turns[-1]
    moving = np.flatnonzero(p != 0)
    stopped = moving[-1] + 1                            # the first step of the final rest
    assert stopped < len(t) - 1, "it never came to rest"
    halves = 3 if method == "euler" else 1
    assert abs(t[stopped] - t_stop) <= halves * math.pi / OMEGA + dt
    assert abs(x[stopped]) <= BAND
    assert np.all(x[stopped:] == x[stopped]) and np.all(p[stopped:] == 0)
    if method != "euler":   # it stops at the closed form's last turning point, to first order in Δt
        assert abs(x[stopped] - x_stop) <= 0.1 * D + OMEGA * dt * X0


@pytest.mark.parametrize("method, dt", CASES)
def test_the_peaks_fall_by_the_same_amount_each_half_swing(method, dt):
    """The turning points |x_n| = x0 − 2 n d, each within a few ωΔt of the swing (first order in Δt).
    euler's own growth, (ωΔt)²/2 of the swing a step, adds ω²Δt t/2 of it by the time t."""
    t, x, p, _ = run(method, dt)
    turns = [i for i in range(1, len(p)) if p[i - 1] * p[i] < 0]      # p changes sign within the step
    peaks = np.abs(x[turns])
    assert len(peaks) >= 40
    n = np.arange(1, len(peaks) + 1)
    slack = 0.6 * OMEGA * dt * X0 + (0.5 * OMEGA ** 2 * dt * t[turns] * X0 if method == "euler" else 0.0)
    misses = np.abs(peaks - (X0 - 2 * n * D))
    assert np.all(misses <= 2 * D * 0.05 + slack), np.max(misses)


@pytest.mark.parametrize("method, largest", [("euler-cromer", 2e-3), ("verlet", 2e-4), ("rk4", 1e-4)])
def test_the_motion_approaches_the_closed_form_as_dt_shrinks(method, largest):
    """x(t) against the piecewise closed form over the whole run: the error shrinks at least in
    proportion to Δt. At each turning point friction's sign flips within a step, a kink no step
    follows exactly, so even rk4 and verlet are first order there (measured: rk4 9.6e-5 m at
    Δt = 0.004 s, 2.7e-5 m at 0.001 s)."""
    errors = []
    for dt in (0.004, 0.001):
        t, x, _, _ = run(method, dt)
        errors.append(np.max(np.abs(x - closed_form(t)[0])))
    assert errors[1] < errors[0] / 4 * 1.5, errors
    assert errors[1] < largest, errors


@pytest.mark.parametrize("method", list(INTEGRATORS))
@pytest.mark.parametrize("x0", [BAND * 0.999, -BAND * 0.5, 0.0])
def test_a_block_at_rest_inside_the_dead_band_never_moves(method, x0):
    """|k x| ≤ μ_s m g: static friction balances the spring; every step leaves it exactly as it was."""
    t, x, p, _ = run(method, 0.01, until=5.0, x0=x0)
    assert np.all(x == x[0]) and np.all(p == 0)


@pytest.mark.parametrize("method", list(INTEGRATORS))
def test_a_block_pulled_just_beyond_the_dead_band_starts_towards_the_spring(method):
    """|k x| > μ_s m g: it starts to slide the way the spring pulls, with kinetic friction against it
    from the first step (F_net = −k x + μ_k m g), and stops on the other side of the relaxed length
    or short of it, never beyond where it started."""
    x0 = BAND * 1.2
    t, x, p, engine = run(method, 0.001, until=2.0, x0=x0)
    assert p[1] < 0
    if method in ("euler-cromer", "euler"):             # one kick with the force at the start
        assert p[1] == pytest.approx((-K * x0 + MU_K * M * G) * 0.001, rel=1e-9)
    assert np.all(np.abs(x) <= x0 + 1e-12) and np.all(p[-100:] == 0)


@pytest.mark.parametrize("method", list(INTEGRATORS))
def test_friction_alone_stops_a_sliding_block_and_never_reverses_it(method):
    """No spring: a block sliding at v0 slows by μ_k g until it stops, after v0/(μ_k g) and
    v0²/(2 μ_k g); within the step where it stops friction stops it, never sends it back."""
    v0, dt = 0.3, 0.01
    t, x, p, _ = run(method, dt, until=3.0, k=0.0, x0=0.0, v0=v0)
    v = p / M
    assert np.all(v >= 0)                               # never reversed
    stop = np.flatnonzero(v == 0)[0]
    assert t[stop] == pytest.approx(v0 / (MU_K * G), abs=dt)
    assert x[-1] == pytest.approx(v0 ** 2 / (2 * MU_K * G), abs=v0 * dt)
    assert np.all(x[stop:] == x[stop])
    slowing = v[1:stop] - v[:stop - 1]
    assert slowing == pytest.approx(np.full(stop - 1, -MU_K * G * dt), rel=1e-9)


def test_friction_takes_energy_counted_in_w_nc():
    """E − W_nc stays at its start (the energy principle), friction's work being −μ_k N times the
    distance slid, which the closed form gives: Σ |x_n − x_(n+1)| over the half swings."""
    t, x, p, engine = run("rk4", 0.001)
    energy = engine.energy()
    _, turns = closed_form(t)
    slid = sum(abs(a - b) for (_, a), (_, b) in zip(turns, turns[1:]))
    assert energy["W_nc"] == pytest.approx(-MU_K * M * G * slid, rel=1e-3)
    assert energy["E_minus_W_nc"] == pytest.approx(0.5 * K * X0 ** 2, rel=1e-4)
    assert energy["E"] == pytest.approx(0.5 * K * turns[-1][1] ** 2, rel=1e-3)


@pytest.mark.parametrize("method", list(INTEGRATORS))
def test_the_traced_loop_steps_friction_as_numpy_does_bit_for_bit(method):
    """The fast loop traces the law and the stop rule (their choices written `a if c else b`, with no
    guard): one trace for the whole run, and the numbers of the numpy step to the last bit."""
    state, forces = block()
    dt = 2e-4 if method == "euler" else 0.01
    with warnings.catch_warnings():
        warnings.simplefilter("error")                  # an UntracedWarning would fail here
        fast = Simulation(state, forces, dt=dt, integrator=method)
        fast.run_until(30.0)
    slow = Simulation(state, forces, dt=dt, integrator=method, compiled=False)
    slow.run_until(30.0)
    assert fast._loop is not None and fast._loop.ready and fast._loop.traces == 1
    assert np.array_equal(fast.state.r, slow.state.r) and np.array_equal(fast.state.p, slow.state.p)
    assert np.array_equal(fast.work, slow.work)


def test_static_friction_balances_the_other_forces_in_the_net_force():
    """At rest inside the dead band F_net is 0 (friction is −F_spring); beyond it, kinetic friction
    opposes the pull. What --headless prints as F_net and the arrows draw."""
    for x0, expected in ((0.01, 0.0), (0.1, -K * 0.1 + MU_K * M * G)):
        state, forces = block(x0=x0)
        F = net_force(forces, 0.0, state.r, state.v, state.m)
        assert F[0, 0] == pytest.approx(expected, abs=1e-15)


def test_friction_is_refused_where_it_cannot_be():
    with pytest.raises(ValueError, match="mu_s must be at least mu_k"):
        Friction(mu_k=0.3, mu_s=0.2, g=G)
    with pytest.raises(ValueError, match="g = 0"):
        Friction(mu_k=0.1, mu_s=0.2, g=0.0)


def main_py(*args):
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *args], capture_output=True, text=True,
                          cwd=ROOT, timeout=300, env={**os.environ, "SPRING_SCENES": ""})


def test_mu_s_below_mu_k_is_one_line():
    done = main_py("friction", "--set", "mu_s=0.01", "--headless")
    assert done.returncode == 2 and done.stdout == ""
    (line,) = done.stderr.strip().splitlines()
    assert "mu_s must be at least mu_k" in line


@pytest.mark.parametrize("scene", ["vertical", "driven", "damped", "pendulum"])
def test_a_single_mass_scene_refuses_friction_in_one_line_naming_the_scene_that_has_a_table(scene):
    """A single-mass scene has no table: its mass hangs or swings with gravity on, or lies on a
    frictionless table with g = 0 (no load). `vertical --set mu_k=0.1` used to run and report no
    exact answer while friction did nothing at all: now every such scene says so in one line."""
    done = main_py(scene, "--set", "mu_k=0.1", "--set", "mu_s=0.2", "--headless")
    assert done.returncode == 2 and done.stdout == "", done.stderr
    (line,) = done.stderr.strip().splitlines()
    assert line.startswith("error: friction needs a block sliding on a table") and "main.py friction" in line


# A quick case: μ_k = 0.3 stops the top block within 1.5 s (three half swings), so a 2 s run has it
# sliding, turning, stopped and held by static friction.
QUICK = ("friction", "--set", "mu_k=0.3", "--set", "mu_s=0.5")


@pytest.mark.parametrize("integrator", list(INTEGRATORS))
def test_the_program_with_friction_reaches_the_engines_state(integrator, stand_in, tmp_path):  # noqa: F811
    """The handed-out program writes friction's law (sliding, held, starting) and its stop rule
    after the update, and run under the stand-in vpython ends where the engine does, to round-off."""
    path = tmp_path / "friction_program.py"
    written = main_py(*QUICK, "--integrator", integrator, "--until", "2", "--vpython", str(path))
    assert written.returncode == 0, written.stderr
    program = path.read_text(encoding="utf-8")
    assert "Ffriction = -mu_k_each[i]*m*g*hat(vs)" in program and "Ffriction = -Fs" in program
    assert "if dot(ps, ps + Fs*dt) <= mu_k_each[i]*m*g*dt*mag(ps) and mag(Fs) <= mu_s_each[i]*m*g:" in program
    headless = main_py(*QUICK, "--integrator", integrator, "--set", "until=2", "--headless", "--json")
    assert headless.returncode == 0, headless.stderr
    expected = json.loads(headless.stdout)
    assert expected["bodies"][1]["p"][0] == 0.0         # the friction block is held by then
    ended = run_to_end(path, stand_in)
    for (t, r, p), body in zip(ended, expected["bodies"]):
        assert t == pytest.approx(expected["t"], rel=1e-12)
        assert np.allclose(r, body["r"], rtol=1e-12, atol=1e-12)
        assert np.allclose(p, body["p"], rtol=1e-12, atol=1e-12)


def test_the_friction_scene_shows_the_lesson(tmp_path):
    """The friction block's peaks fall on a straight line, 4 μ_k m g / k a period, to a stop in the
    dead band; the damped block's on an exponential, the same fraction a period, still swinging at
    30 s; both have halved by 12.5 s, where the two envelopes cross."""
    path = tmp_path / "friction.csv"
    done = main_py("friction", "--headless", "--csv", str(path))
    assert done.returncode == 0, done.stderr
    with path.open(newline="", encoding="utf-8") as file:
        rows = list(csv.DictReader(file))
    bodies = list(dict.fromkeys(row["body"] for row in rows))
    assert bodies == ["damping, b = 0.0555 kg/s", "friction, μ_k = 0.02"]
    period = 2 * np.pi / OMEGA
    for body, straight in zip(bodies, (False, True)):
        t = np.array([float(row["t"]) for row in rows if row["body"] == body])
        x = np.array([float(row["x"]) for row in rows if row["body"] == body]) - L0
        turns = [i for i in range(1, len(x) - 1) if (x[i] - x[i - 1]) * (x[i + 1] - x[i]) < 0]
        peaks = np.abs(x[turns])
        if straight:
            fall = np.diff(peaks) / (np.diff(t[turns]) / period)            # m a period
            assert np.allclose(fall, -4 * D, rtol=0.15), fall
            assert abs(x[-1]) <= BAND and np.all(x[-200:] == x[-1])
        else:
            ratio = peaks[1:] / peaks[:-1]
            assert np.allclose(ratio, ratio[0], rtol=0.02) and ratio[0] < 1     # the same fraction
            assert peaks[-1] > 0.15 * X0
        halved = t[turns][np.argmax(peaks < 0.5 * X0)]
        assert halved == pytest.approx(12.5, abs=period)


def test_the_friction_block_has_no_exact_answer_and_says_so_the_damped_one_has_its_own():
    """26.2 in a row: friction has no closed form, so the friction block's exact answer is null in
    --json with a note naming friction, and "none (no closed form with friction)" in the text;
    the damped block beside it keeps its closed form and its error."""
    done = main_py("friction", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    damped, sliding = json.loads(done.stdout)["bodies"]
    assert damped["exact"]["error"]["r"] < 0.05
    assert sliding["exact"] is None and sliding["exact_note"] == "no closed form with friction"
    text = main_py("friction", "--headless").stdout
    assert text.count("exact: none (no closed form with friction)") == 1 and text.count("exact: r = ") == 1

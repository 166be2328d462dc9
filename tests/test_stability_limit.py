"""Issue 28, item 6: a step exactly at a method's stability limit, ω·Δt = 2 for euler-cromer and verlet.

It was refused as "the run would blow up". It does not blow up: the step's matrix M has the
eigenvalue −1 twice, so x_n = (A + B n)(−1)ⁿ, flipping sign at every step and growing linearly
unless it starts in the one motion that repeats (physics/stability.py, at_limit). With
m = 1 kg, k = 4 N/m (ω = 2 rad/s), L0 = 0, Δt = 1 s and F0 = 0 the positions are worked by hand:

    verlet from rest at x0:          x_n = x0 (−1)ⁿ                 (Langtangen's fdm-book case)
    verlet from x0 moving at v0:     x_n = (−1)ⁿ (x0 − n v0 Δt)
    euler-cromer from rest at x0:    x_n = x0 (1 + 2n)(−1)ⁿ

(verlet: x1 = x0 + v0 Δt − ½ ω² Δt² x0 = −x0 + v0 Δt, v1 = v0 − ½ ω² Δt (x0 + x1) = −v0; so each
step maps (x, v) to (−x + vΔt, −v). euler-cromer: v1 = v0 − ω² Δt x0, x1 = x0 + v1 Δt = −3 x0 from
rest, and x_{n+1} = −2 x_n − x_{n−1} after.) The command line runs each, with one line saying
which of these it is, and the CSV holds exactly those numbers.
"""
from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from physics.integrators import INTEGRATORS  # noqa: E402
from physics.stability import Limit, at_limit, judge  # noqa: E402
from scenes import catalog  # noqa: E402

CASE = ["driven", "--set", "m=1", "--set", "k=4", "--set", "L0=0", "--set", "r0=1.2,0,0", "--set", "dt=1"]
X0, DT, STEPS = 1.2, 1.0, 20
n = np.arange(STEPS + 1)
HAND = {
    ("verlet", 0.0): X0 * (-1.0) ** n,
    ("verlet", 0.5): (-1.0) ** n * (X0 - n * 0.5 * DT),
    ("euler-cromer", 0.0): X0 * (1 + 2 * n) * (-1.0) ** n,
}


def main_py(*args, cwd=ROOT):
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=300)


@pytest.mark.parametrize("method, v0", HAND)
def test_the_csv_at_the_limit_is_the_hand_worked_sequence(method, v0, tmp_path):
    path = tmp_path / "limit.csv"
    done = main_py(*CASE, "--set", "F0=0", "--set", f"v0={v0},0,0", "--integrator", method, "--headless",
                   "--until", STEPS * DT, "--csv", path)
    assert done.returncode == 0, done.stderr
    with open(path, newline="") as file:
        x = np.array([float(row["x"]) for row in csv.DictReader(file)])
    np.testing.assert_allclose(x, HAND[method, v0], rtol=1e-13, atol=1e-13)
    line, = done.stderr.splitlines()
    start = "started from rest, as here" if v0 == 0 else "started moving, as here"
    assert line.startswith(f"warning: dt = 1 s is exactly {method}'s stability limit for the spring (ω = 2 rad/s, "
                           f"ω·dt = 2): {start}, the position flips sign at every step and "), line
    bounded = np.max(np.abs(HAND[method, v0])) == X0
    assert ("stays bounded" in line) == bounded and ("grows by the same amount every step" in line) == (not bounded)


@pytest.mark.parametrize("method", ["verlet", "euler-cromer"])
def test_the_issues_command_runs_with_one_warning(method):
    """The issue's command, with the scene's own drive F0 = 1 N at ω = 5 rad/s."""
    done = main_py(*CASE, "--integrator", method, "--headless", "--json")
    assert done.returncode == 0, done.stderr
    line, = done.stderr.splitlines()
    assert line.startswith(f"warning: dt = 1 s is exactly {method}'s stability limit for the spring")
    assert line[len("warning: "):] in json.loads(done.stdout)["notes"]


def test_what_each_method_does_at_its_limit_comes_from_its_own_step():
    """verlet's one repeating motion is rest; euler-cromer's is v0 = 2 x0/Δt, so from rest it grows;
    every other method's limit (rk4's ω·Δt = 2√2, complex eigenvalues on the unit circle) or lack of
    one (euler) is no eigenvalue of −1."""
    assert at_limit("verlet", omega=2.0, rate=0.0, dt=1.0) == Limit(from_rest=True, any_start=False)
    assert at_limit("euler-cromer", omega=2.0, rate=0.0, dt=1.0) == Limit(from_rest=False, any_start=False)
    for name, entry in INTEGRATORS.items():
        assert at_limit(name, omega=2.0, rate=0.0, dt=0.99) is None
        if entry.omega_dt_limit not in (None, 2.0):
            assert at_limit(name, omega=2.0, rate=0.0, dt=entry.omega_dt_limit / 2.0) is None


def test_euler_cromers_one_repeating_start_is_bounded():
    """The eigenvector of euler-cromer's M at the limit, v0 = 2 x0/Δt, flips without growing."""
    model = catalog.configure("driven", assignments=["m=1", "k=4", "L0=0", "F0=0", "r0=1.2,0,0", "v0=2.4,0,0",
                                                     "dt=1"]).build()
    trajectory = model.simulation("euler-cromer").run_until(20.0)
    np.testing.assert_allclose(trajectory.r[-1][0, 0], X0 * (-1.0) ** 20, rtol=1e-12)


def test_damping_at_omega_dt_2_is_past_the_limit_still():
    """With b > 0, (ω·Δt)² + 2 (b/m) Δt > 4: the motion really grows every step, and is refused."""
    model = catalog.configure("driven", assignments=["m=1", "k=4", "L0=0", "F0=0", "b=0.1", "r0=1.2,0,0",
                                                     "dt=1"]).build()
    verdict = judge(model.forces, model.state.m, ("euler-cromer",), 1.0)
    assert verdict.past_limit and not verdict.at_limit
    done = main_py(*CASE, "--set", "b=0.1", "--headless")
    assert done.returncode == 1 and "the run would blow up, past the stability limit" in done.stderr

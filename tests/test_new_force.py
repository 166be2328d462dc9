"""A new force is one declaration: the recipe of docs/architecture.md, followed from a folder of its own.

A teacher's folder (SPRING_SCENES) holds two new files and nothing else in the project changes:

    _brake.py   an eddy-current brake, F = −β v⊥, as one Force subclass: its law, its constants
                (β in kg/s, the field's direction), its rate for the stability judgement (β/m) and
                its line in the handed-out program
    brake.py    a scene that builds a Model with a spring, gravity and the brake

The brake then works headless, in --csv, in the exported program (run under the stand-in vpython
of tests/test_export.py, it reaches the engine's final state), in the stability judgement, and in
the page's parts (its slider, caption and live run; no browser is started, which keeps it cheap).
The physics is checked by hand: with no spring and no gravity, Euler-Cromer's momentum across the
field shrinks by exactly (1 − βΔt/m) each step and the part along the field stays as it was.
"""
from __future__ import annotations

import csv
import json
import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from test_export import run_to_end, stand_in  # noqa: F401  (stand_in is a fixture)

ROOT = Path(__file__).resolve().parent.parent

BRAKE = '''
"""An eddy-current brake: a magnetic field along B̂ slows a conductor moving across it."""
from dataclasses import dataclass

import numpy as np

from physics.declared import Declared
from physics.forces import Force


@dataclass(frozen=True, eq=False)
class EddyBrake(Force):
    """Eddy-current braking across a magnetic field.

    F = −β v⊥,  v⊥ = v − (v·B̂) B̂,  β in kg/s, B̂ the field's direction (no unit). Motion along the
    field is not braked.
    """

    beta: float = 0.0
    field_axis: object = (1.0, 0.0, 0.0)
    conservative = False
    uses_velocity = True
    LABEL = "eddy brake"
    CONSTANTS = {
        "beta": Declared("kg/s", 0, 1e6, symbol="β", slider_from_zero=True, default=0.0, switch=True,
                         meaning="eddy-current braking constant in F = −β v⊥"),
        "field_axis": Declared("1", -1e6, 1e6, vector=True, nonzero=True, default=(1.0, 0.0, 0.0),
                               meaning="direction of the magnetic field (a unit vector)"),
    }
    TERM = "Fbrake"
    PROGRAM = (("Fbrake = -{beta}*({v} - dot({v}, {field_axis})*{field_axis})",
                "eddy brake: F = −β v⊥, v⊥ = v − (v·B̂) B̂"),)

    def __post_init__(self):
        axis = np.asarray(self.field_axis, dtype=float)
        object.__setattr__(self, "field_axis", axis / np.sqrt(axis @ axis))

    def __call__(self, t, r, v, m):
        B = self.field_axis
        along = v[:, 0:1] * B[0] + v[:, 1:2] * B[1] + v[:, 2:3] * B[2]    # v·B̂, as dot() adds it
        return -self.beta * (v - along * B)

    def rates(self, m, speed):
        return {"damping": self.beta / m}         # at most −β v: the rate b/m of linear damping
'''

SCENE = '''
"""A mass on a spring swinging through a magnet's field: eddy-current braking."""
from physics.forces import Gravity, Spring
from physics.state import make_state

from ._brake import EddyBrake
from ._model import Model

# ---- constants: edit these (unit: meaning) ----
m = 2.0                    # kg: mass of the aluminium block
k = 30.0                   # N/m: spring constant
L0 = 0.5                   # m: relaxed length of the spring
g = 9.8                    # m/s²: strength of gravity
beta = 1.5                 # kg/s: eddy-current braking constant in F = −β v⊥
field_axis = (1, 0, 0)     # 1: direction of the magnetic field
anchor = (0, 0, 0)         # m: top end of the spring
r0 = (0.3, -1.2, 0)        # m: start position
v0 = (0.4, 0, 0.2)         # m/s: start velocity
dt = 0.01                  # s: time step Δt of the momentum update
until = 3.0                # s: question time
# ---- end of constants ----


def build(*, m, k, L0, g, beta, field_axis, anchor, r0, v0, dt, until):
    """Spring, gravity and the brake, in that order; a force whose constant is 0 is left out."""
    forces = [Spring(k=k, L0=L0, anchor=anchor)]
    if g:
        forces.append(Gravity(g=g))
    if beta:
        forces.append(EddyBrake(beta=beta, field_axis=field_axis))
    return Model(state=make_state(r=r0, v=v0, m=m), forces=tuple(forces), dt=float(dt), until=float(until),
                 anchors=[anchor], labels=("block",))


VIEW = {"support": "ceiling", "plot": "y", "sliders": ["m", "k", "beta"]}
'''


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("teacher_scenes")
    (folder / "_brake.py").write_text(textwrap.dedent(BRAKE), encoding="utf-8")
    (folder / "brake.py").write_text(textwrap.dedent(SCENE), encoding="utf-8")
    return folder


def main_py(folder: Path, *args, cwd=ROOT):
    env = {**os.environ, "SPRING_SCENES": str(folder)}
    return subprocess.run([sys.executable, str(ROOT / "main.py"), "brake", *args], capture_output=True,
                          text=True, cwd=cwd, env=env, timeout=300)


# No spring and no gravity: only the brake acts, across the field (x) on v0's y and z parts.
FREE = ("--set", "k=0", "--set", "g=0", "--set", "v0=0.4,-0.6,0.2", "--set", "r0=0,-1,0",
        "--set", "dt=0.05", "--set", "until=2")


def test_the_brake_headless_follows_the_hand_worked_steps(folder):
    done = main_py(folder, *FREE, "--headless", "--json")
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""                        # traced by the fast loop: no warning
    out = json.loads(done.stdout)
    m, beta, dt = 2.0, 1.5, 0.05
    n = out["steps"]
    assert n == 40 and out["t"] == pytest.approx(2.0)
    shrink = (1 - beta * dt / m) ** n               # p_f = p_i − β (p_i⊥/m) Δt, step after step
    assert out["p"] == pytest.approx([m * 0.4, m * -0.6 * shrink, m * 0.2 * shrink], rel=1e-12)
    # and the closed form e^(−βt/m), which the steps approach as Δt shrinks
    assert out["p"][1] == pytest.approx(m * -0.6 * math.exp(-beta * 2.0 / m), rel=0.05)
    # the brake's work is the kinetic energy it took: E − W_nc stays at its start (to the first
    # order of the page's step, whose error per unit time is about βΔt/m = 4 %)
    start = 0.5 * m * (0.4**2 + 0.6**2 + 0.2**2)
    assert out["energy"]["W_nc"] < -0.5 * start
    assert out["energy"]["E_minus_W_nc"] == pytest.approx(start, rel=beta * dt / m)
    assert out["constants"]["beta"]["unit"] == "kg/s"


def test_the_brake_in_csv_shrinks_each_step_by_the_same_factor(folder, tmp_path):
    path = tmp_path / "brake.csv"
    done = main_py(folder, *FREE, "--headless", "--csv", str(path))
    assert done.returncode == 0, done.stderr
    with path.open(newline="") as file:
        rows = list(csv.DictReader(file))
    assert len(rows) == 41
    p_y = np.array([float(row["py"]) for row in rows])
    p_x = np.array([float(row["px"]) for row in rows])
    assert np.allclose(p_y[1:] / p_y[:-1], 1 - 1.5 * 0.05 / 2.0, rtol=1e-12, atol=0)
    assert np.all(p_x == p_x[0])                    # along the field: no braking


@pytest.mark.parametrize("integrator", ["euler-cromer", "verlet", "rk4", "euler"])
def test_the_program_with_the_brake_reaches_the_engines_state(folder, integrator, stand_in, tmp_path):  # noqa: F811
    path = tmp_path / "brake_program.py"
    written = main_py(folder, "--integrator", integrator, "--until", "1", "--vpython", str(path))   # ends at 1 s
    assert written.returncode == 0, written.stderr
    text = path.read_text(encoding="utf-8")
    assert "Fbrake = -beta*(v - dot(v, field_axis)*field_axis)" in text
    assert "beta = 1.5" in text and "kg/s: eddy-current braking constant" in text
    headless = main_py(folder, "--integrator", integrator, "--set", "until=1", "--headless", "--json")
    assert headless.returncode == 0, headless.stderr
    expected = json.loads(headless.stdout)
    ((t, r, p),) = run_to_end(path, stand_in)
    assert t == pytest.approx(expected["t"], rel=1e-12)
    assert np.allclose(r, expected["r"], rtol=1e-12, atol=1e-12 * np.max(np.abs(expected["r"])))
    assert np.allclose(p, expected["p"], rtol=1e-12, atol=1e-12 * np.max(np.abs(expected["p"])))


def test_the_stability_judgement_counts_the_brake(folder):
    """Alone, the brake's rate γ = β/m limits euler-cromer to γ Δt < 2: β = 500 kg/s, m = 2 kg
    gives Δt < 0.008 s, so Δt = 0.01 s is refused before the run, naming the brake by its label and
    its own constant (not the page's damping b), and the limit."""
    done = main_py(folder, "--set", "k=0", "--set", "g=0", "--set", "beta=500", "--headless")
    assert done.returncode == 1
    (line,) = done.stderr.strip().splitlines()
    assert "the eddy brake (β/m = 250 s⁻¹)" in line and "b/m" not in line
    limit = float(line.split("dt < ")[1].split(" s")[0])
    assert limit == pytest.approx(2 / 250, rel=1e-3)
    assert main_py(folder, "--set", "k=0", "--set", "g=0", "--set", "beta=500", "--set", "dt=0.0079",
                   "--headless").returncode == 0


def test_the_brakes_constants_are_declared_by_the_force(folder):
    done = main_py(folder, "--constants")
    assert done.returncode == 0, done.stderr
    assert "kg/s" in done.stdout and "β" in done.stdout
    bad = main_py(folder, "--set", "beta=-1", "--headless")
    assert bad.returncode == 2
    (line,) = bad.stderr.strip().splitlines()
    assert "beta must be from 0 to 1e6 kg/s" in line


PAGE = '''
import json
from browser.clock import LiveRun
from browser.controls import constants_text, slider_names, slider_range, symbol
from scenes import catalog

setup = catalog.configure("brake", assignments=["until=1"])
model = setup.build()
live = LiveRun(model, integrator="euler-cromer")
live.advance(100)
print(json.dumps({"sliders": slider_names(setup, setup.module.VIEW), "beta": slider_range("beta", 1.5), "symbol": symbol("beta"),
                  "caption": constants_text(setup), "r": live.state.r[0].tolist(), "t": live.state.t}))
'''


def test_the_pages_parts_read_the_brakes_declaration(folder):
    """The page's sliders, caption and live run (browser/controls.py, browser/clock.py; no browser
    started): β's slider starts at 0 (slider_from_zero, declared by the force), the caption shows
    β with its unit, and the live run is the headless run."""
    env = {**os.environ, "SPRING_SCENES": str(folder)}
    done = subprocess.run([sys.executable, "-c", PAGE], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    page = json.loads(done.stdout)
    assert "beta" in page["sliders"] and page["beta"][0] == 0.0 and page["symbol"] == "β"
    assert "β = 1.5 kg/s" in page["caption"]
    headless = json.loads(main_py(folder, "--set", "until=1", "--headless", "--json").stdout)
    assert page["t"] == pytest.approx(headless["t"]) and page["r"] == pytest.approx(headless["r"], rel=1e-12)

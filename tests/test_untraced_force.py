"""A force the fast loop cannot trace is said, once, never passed over in silence.

physics/compiled.py traces the engine's tick on numbers that write themselves down. A force that
calls a numpy function those numbers do not know (np.tanh here) cannot be traced; the engine then
steps it with numpy, several times slower. It must say so: one UntracedWarning naming the force
and what it did, once per process, and on the command line one line on stderr.
"""
from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from physics import compiled
from physics.compiled import UntracedWarning
from physics.forces import Force, Spring
from physics.simulate import Simulation
from physics.state import make_state

ROOT = Path(__file__).resolve().parent.parent


@dataclass(frozen=True, eq=False)
class SoftWall(Force):
    """A soft wall at x = 0: F = −F_max tanh(x/a) x̂, F_max in N, a in m (not traceable: np.tanh)."""

    F_max: float = 5.0
    a: float = 0.1

    def __call__(self, t, r, v, m):
        F = np.zeros_like(r)
        F[:, 0] = -self.F_max * np.tanh(r[:, 0] / self.a)
        return F


def engine(forces, *, compiled_loop=True):
    return Simulation(make_state(r=(0.3, 0.0, 0.0), v=(0.0, 0.5, 0.0), m=1.5), forces, dt=0.01,
                      compiled=compiled_loop)


def test_an_untraceable_force_is_named_once_and_the_numpy_tick_gives_the_same_motion(monkeypatch):
    monkeypatch.setattr(compiled, "_REPORTED", set())
    forces = (Spring(k=4.0), SoftWall())
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        first, second = engine(forces), engine(forces)
        first.advance(500)
        second.advance(500)
    said = [str(w.message) for w in caught if issubclass(w.category, UntracedWarning)]
    assert len(said) == 1, said                    # two engines, one warning
    assert said[0].startswith("the force SoftWall (in __call__) cannot be traced for the fast loop")
    assert "tanh" in said[0] and "numpy" in said[0]
    plain = engine(forces, compiled_loop=False)
    plain.advance(500)
    assert np.array_equal(first.state.r, plain.state.r) and np.array_equal(first.state.p, plain.state.p)


def test_a_traceable_system_says_nothing_and_runs_the_compiled_loop(monkeypatch):
    monkeypatch.setattr(compiled, "_REPORTED", set())
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sim = engine((Spring(k=4.0),))
        sim.advance(500)
    assert not [w for w in caught if issubclass(w.category, UntracedWarning)]
    assert sim._loop is not None and sim._loop.ready


SCENE = '''
"""A mass between a spring and a soft wall."""
from dataclasses import dataclass

import numpy as np

from physics.forces import Force, Spring
from physics.state import make_state

from ._model import Model

# ---- constants: edit these (unit: meaning) ----
m = 1.5                    # kg: mass
k = 4.0                    # N/m: spring constant
dt = 0.01                  # s: time step
until = 5.0                # s: question time
# ---- end of constants ----


@dataclass(frozen=True, eq=False)
class Wall(Force):
    """F = −5 N tanh(x / 0.1 m) x̂."""

    def __call__(self, t, r, v, m):
        F = np.zeros_like(r)
        F[:, 0] = -5.0 * np.tanh(r[:, 0] / 0.1)
        return F


def build(*, m, k, dt, until):
    return Model(state=make_state(r=(0.3, 0, 0), v=(0, 0.5, 0), m=m), forces=(Spring(k=k), Wall()),
                 dt=dt, until=until)


VIEW = {"support": "wall", "plot": "x"}
'''


def test_the_command_line_says_it_in_one_line(tmp_path):
    (tmp_path / "wall.py").write_text(textwrap.dedent(SCENE), encoding="utf-8")
    done = subprocess.run([sys.executable, str(ROOT / "main.py"), "wall", "--headless"], cwd=ROOT,
                          env={**os.environ, "SPRING_SCENES": str(tmp_path)}, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert lines[0].startswith("warning: the force Wall (in __call__) cannot be traced for the fast loop")
    assert "t = 5 s" in done.stdout or "5 s" in done.stdout

"""The engine and the scenes read what a force declares, not its class (issue 16, item 1): the blow-up
check measures from the anchor a force's tether() gives, and a model refuses a start its forces'
undefined_at() names. A force that is not a Spring but declares both is followed like one.

The new force is defined in a subprocess, so that it does not join physics.forces.FORCES (every
force class ever defined) for the rest of the test session.
"""
from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np

from physics.forces import Gravity, Spring

ROOT = Path(__file__).resolve().parent.parent

LEASH = '''
from dataclasses import dataclass

import numpy as np

from physics.forces import Force
from physics.simulate import BlowUpError, Simulation
from physics.state import make_state
from scenes._model import Model


@dataclass(frozen=True, eq=False)
class Leash(Force):
    """F = −k (r − anchor)/|r − anchor|, N: a pull of k newtons towards the anchor (k in N); no
    direction at the anchor itself."""

    k: float = 1.0
    anchor: tuple = (0.0, 0.0, 0.0)
    conservative = False

    def __call__(self, t, r, v, m):
        L = r - np.asarray(self.anchor)
        return -self.k * L / np.linalg.norm(L, axis=1, keepdims=True)

    def rates(self, m, speed):
        return {"stiffness": np.full(len(m), 1.0)}

    def tether(self):
        return np.asarray(self.anchor), 0.5

    def undefined_at(self, r):
        return np.linalg.norm(r - np.asarray(self.anchor), axis=1) == 0


try:
    Model(state=make_state(r=[[0.0, 0.0, 0.0]], m=1.0), forces=(Leash(),), dt=0.1, until=1.0)
except ValueError as refused:
    print("refused:", refused)
# A mass on the leash, pushed hard from 1 m: nothing stops it but the leash's 1 N, so it runs away.
engine = Simulation(make_state(r=[[1.0, 0.0, 0.0]], m=1.0, v=[[1e3, 0.0, 0.0]]), (Leash(),), dt=1.0,
                    integrator="euler", growth_limit=10.0)
try:
    engine.advance(10_000)
except BlowUpError as problem:
    print("blew up at", engine.steps, problem)
'''


def test_a_force_that_declares_a_tether_is_judged_like_a_spring():
    run = subprocess.run([sys.executable, "-c", textwrap.dedent(LEASH)], cwd=ROOT, capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    assert lines[0].startswith("refused: a mass starts at its spring's anchor"), run.stdout
    # limit = 10 × (1 m offset + 1000 m/s ÷ 1 rad/s + 0.5 m length + 9.8 m + 1 m) ≈ 1.1e4 m: past it
    # after about 11 steps of 1000 m; the first check is at step 1024 (it is caught there, finite).
    assert lines[1].startswith("blew up at 1024 the simulation blew up by t = 1024 s (motion growing"), run.stdout


def test_a_spring_declares_its_anchor_and_length_and_where_it_has_no_direction():
    spring = Spring(k=4.0, L0=np.array([1.0, 2.0]), anchor=np.array([[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]))
    anchor, length = spring.tether()
    assert np.array_equal(anchor, [[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]) and np.array_equal(length, [[1.0], [2.0]])
    r = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])
    assert spring.undefined_at(r).tolist() == [True, False]
    assert Spring(k=4.0, L0=0.0).undefined_at(np.zeros((2, 3))).tolist() == [False, False]   # F = −k L
    assert Gravity(g=9.8).tether() is None and not Gravity(g=9.8).undefined_at(r).any()

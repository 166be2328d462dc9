"""A run that cannot end until the test lets it, for the tests that stop a run part-way.

A step count chosen to "take a while" is a guess about the computer: on a quiet, fast one a run of
10⁶ rk4 steps finished in 1.5 s, before its first progress line, and the test that meant to
interrupt it read '' instead (issue 28, item 8). A count worked out from a measured rate is the
same guess, made later. Here the length is built in, the way a teacher adds a scene: a scene
folder (SPRING_SCENES) with `held`, the page's vertical spring plus one more force, `Held`, which
pushes with 0 N and

- steps at full speed up to PACE_FROM s, so the judgement of Δt before the run (its trial runs
  reach at most 2,000 steps, physics/accuracy.py) and the cost check see an ordinary scene;
- from PACE_FROM s waits PACE s at every step, so the PACED steps that follow take more than a
  second on any computer, and the engine reports its progress (every 1,024 steps once a second has
  passed) at least once before
- HOLD_FROM s, from where every step waits until the test's gate file exists.

So a test that reads the first `running:` line knows the run is under way and cannot have ended,
whatever the computer: until it opens the gate (open_gate), the run is held inside a step. The
force calls float() on t, so the engine's fast loop cannot trace it (it would drop the waits) and
steps it with numpy, after one line `warning: ... runs with numpy` (not_progress skips it with
the progress lines).
"""
from __future__ import annotations

import os
import textwrap
from pathlib import Path

DT = 0.001                 # s: the scene's Δt
PACE_FROM = 3.0            # s: 3,000 steps, past the 2,000 of the trial runs before the run
PACE = 0.001               # s: the least each step waits from PACE_FROM on
PACED = 2_100              # steps: at least 2.1 s, so a progress line (after 1 s, at a 1,024-step mark) comes first
HOLD_FROM = PACE_FROM + PACED * DT
UNTIL = 10.0               # s: the run's end, never reached while the gate is shut

FORCE = '''
"""A force of 0 N that makes the run wait: see tests/held_run.py."""
import os
import time
from dataclasses import dataclass

import numpy as np

from physics.forces import Force

GATE = {gate!r}


@dataclass(frozen=True, eq=False)
class Held(Force):
    """F = 0 N. From t = {pace_from} s each step waits {pace} s; from t = {hold_from} s it waits until GATE exists."""

    def __call__(self, t, r, v, m):
        now = float(t)      # a plain number: the fast loop cannot trace this, so the waits stay in
        if now >= {pace_from} and not os.path.exists(GATE):   # once the gate is open, full speed
            time.sleep({pace})
            while now >= {hold_from} and not os.path.exists(GATE):
                time.sleep(0.01)
        return np.zeros_like(r)
'''

SCENE = '''
"""The vertical spring, held at t = {hold_from} s until the test lets it go on (tests/held_run.py)."""
from physics.forces import Gravity, Spring
from physics.state import make_state

from ._held import Held
from ._model import Model

# ---- constants: edit these (unit: meaning) ----
m = 10.0                   # kg: mass
k = 40.0                   # N/m: spring constant
L0 = 1.0                   # m: relaxed length of the spring
g = 9.8                    # m/s²: strength of gravity
anchor = (0, 0, 0)         # m: top end of the spring
r0 = (0, -1.5, 0)          # m: start position
v0 = (0, 0, 0)             # m/s: start velocity
dt = {dt}                  # s: time step Δt of the momentum update
until = {until}            # s: question time
# ---- end of constants ----


def build(*, m, k, L0, g, anchor, r0, v0, dt, until):
    """Spring, gravity and the held force."""
    return Model(state=make_state(r=r0, v=v0, m=m), forces=(Spring(k=k, L0=L0, anchor=anchor), Gravity(g=g), Held()),
                 dt=float(dt), until=float(until), anchors=[anchor], labels=("mass",))


VIEW = {{"support": "ceiling", "plot": "y"}}
'''


# A fit (tests/test_measured_files.py) runs the model a dozen times or more, each run past the
# record's end by up to a period: Held's pace and hold would make each run seconds long, or hold one
# for good. Its stand-in waits once per run instead: SLOW s when a run first passes SLOW_FROM, while
# the gate is shut. So the first run of the model that passes SLOW_FROM ends more than a second after
# it began, whatever the computer, and once the gate is open every run is at full speed.
SLOW_FROM = 2.05           # s: past the 2,000 steps of Δt's judgement and the cost's trial (2 s at Δt = 1 ms)
SLOW = 1.1                 # s: the wait, once per run

ONCE = '''
"""A force of 0 N that makes each run wait once: see tests/held_run.py."""
import os
import time
from dataclasses import dataclass

import numpy as np

from physics.forces import Force

GATE = {gate!r}
LAST = [0.0]      # the t of the last call: a t smaller than it is a new run


@dataclass(frozen=True, eq=False)
class Held(Force):
    """F = 0 N. A run passing t = {slow_from} s waits {slow} s there, once, until GATE exists."""

    def __call__(self, t, r, v, m):
        now = float(t)      # a plain number: the fast loop cannot trace this, so the wait stays in
        if LAST[0] < {slow_from} <= now and not os.path.exists(GATE):
            time.sleep({slow})
        LAST[0] = now
        return np.zeros_like(r)
'''


def slow_scene(folder: Path) -> tuple[dict, Path]:
    """The `held` scene with the force that waits once per run (ONCE), for a fit; returns the
    environment that finds it, and the gate file (absent: each run waits SLOW s at SLOW_FROM)."""
    env, gate = held_scene(folder)
    values = dict(gate=str(gate), slow_from=SLOW_FROM, slow=SLOW)
    (folder / "_held.py").write_text(textwrap.dedent(ONCE).format(**values), encoding="utf-8")
    return env, gate


def held_scene(folder: Path) -> tuple[dict, Path]:
    """Write the `held` scene into `folder`; returns the environment that finds it, and the gate file
    (absent: the run waits at HOLD_FROM; open_gate lets it finish)."""
    folder.mkdir(parents=True, exist_ok=True)
    gate = folder / "gate"
    values = dict(gate=str(gate), pace_from=PACE_FROM, pace=PACE, hold_from=HOLD_FROM, dt=DT, until=UNTIL)
    (folder / "_held.py").write_text(textwrap.dedent(FORCE).format(**values), encoding="utf-8")
    (folder / "held.py").write_text(textwrap.dedent(SCENE).format(**values), encoding="utf-8")
    return {**os.environ, "SPRING_SCENES": str(folder)}, gate


def open_gate(gate: Path) -> None:
    gate.write_text("go\n")


def not_progress(lines: list[str]) -> list[str]:
    """The lines that are neither progress nor the one line saying the held force runs with numpy."""
    return [line for line in lines if not line.startswith("running:")
            and not (line.startswith("warning:") and "runs with numpy" in line)]


def wait_for_progress(stream) -> list[str]:
    """Read `stream` (the run's stderr) up to its first progress line; returns the lines read, the
    last of them the progress line, or '' if the program ended first."""
    lines = []
    while not lines or not (lines[-1].startswith("running:") or lines[-1] == ""):
        lines.append(stream.readline())
    return lines

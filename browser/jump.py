"""Jump to t: the run taken to a time in one go and drawn once (the "Jump to t = [ ] s" control, key J).

A teacher types a time (the box starts at the scene's question time, `until`) and presses Jump:
the page shows where the mass is then, with the graphs and trails up to then, paused, and Step,
Run and the Measure tools go on from there. The tests use the same control to reach the t they
need instead of watching the animation get there (tests/browser_support.py's jump_to).

The jump is the real-time run without its waiting: browser/view.py asks the engine (through
LiveRun) for the steps in batches and hands every graph sample to the graphs one at a time, as the
frames of a run at 1× would have (a frame of 20 ms holds at most one sample 0.05 s apart), then
draws once. So the state and every graph point are those of a run played to that t, to the last
digit. Batches: a scene with a mass expected to run away (integrators' euler) is stepped a frame
of 1× at a time, since the page freezes a runaway between frames; any other scene in one batch
(the engine's numbers do not depend on how the steps are split).

Nothing here imports vpython.
"""
from __future__ import annotations

import math
import re

from physics.recording import steps_to_reach
from physics.run_cost import RunTooLong, check_cost

MAX_JUMP_SECONDS = 20.0     # the most computing a jump may take, by the engine's estimate: the page waits
PLOT_SECONDS = 2e-3         # s: about what one graph sample costs the page (curves, trails, axes)
NUMBER = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(?:s)?\s*$")


def jump_time(text: str, *, t0: float = 0.0) -> float:
    """The time, s, typed in the box ("2.5", "2.5 s", "1e2"); ValueError with one line if it
    cannot be one (not a number, not finite, before the run starts)."""
    found = NUMBER.match(str(text))
    if not found:
        shown = str(text).strip()[:40]
        raise ValueError(f"jump to t: '{shown}' is not a time in seconds; type a number such as 2.5")
    t = float(found.group(1))
    if not math.isfinite(t):
        raise ValueError(f"jump to t: {found.group(1)} s is not a time the run can reach; type a number such as 2.5")
    if t < t0:
        raise ValueError(f"jump to t: the run starts at t = {t0:g} s, so it cannot show t = {t:g} s")
    return t


def jump_steps(live, t: float, *, sample_every: float) -> int:
    """The step number the jump ends at: the first step at or after t (as --headless and
    run_until reach a time). Raises ValueError (one line) where getting there from t0 would take
    more than MAX_JUMP_SECONDS of computing here."""
    engine, dt = live.engine, live.model.dt
    try:
        check_cost(_FromStart(engine), until=t,
                   extra_per_step=PLOT_SECONDS * dt / sample_every, limit=MAX_JUMP_SECONDS)
    except RunTooLong as too_long:
        raise ValueError("jump to t: " + too_long.worded("t")) from None
    return steps_to_reach(t - engine.start.t, dt)


class _FromStart:
    """The engine seen from its start (check_cost reads dt, t, start and the cost per step):
    a jump's cost is judged from t0, whatever the run's t now, so the limit is the same from
    anywhere in the run."""

    def __init__(self, engine):
        self._engine = engine
        self.dt, self.start, self.t = engine.dt, engine.start, engine.start.t

    def seconds_per_step(self) -> float:
        return self._engine.seconds_per_step()


def batches(steps: int, *, dt: float, runaways_possible: bool, frame: float) -> list[int]:
    """How to split `steps` steps into the engine's batches: one, or (where a mass may run away,
    and the page freezes it between frames) one frame of `frame` seconds of 1× each."""
    if steps <= 0:
        return []
    if not runaways_possible:
        return [steps]
    size = max(1, round(frame / dt))
    whole, rest = divmod(steps, size)
    return [size] * whole + ([rest] if rest else [])

"""What a run will cost: the engine's measured seconds per step, and refusing a run too long.

A run of more than MAX_RUN_SECONDS of computing is refused before it starts. The cost of a step is
measured, not guessed: a trial copy of the engine takes steps for about TRIAL_SECONDS (the compiled
loop where it applies, numpy otherwise), so the estimate follows one mass and a big batch alike.
The refusal carries its facts; the caller words it for its users (RunTooLong.worded).
"""
from __future__ import annotations

import math
import time

from .recording import steps_to_reach

MAX_RUN_SECONDS = 60.0       # the longest run the program starts, by the engine's estimate, s
TRIAL_SECONDS = 0.02         # how long the trial that measures a step's cost runs, s


class RunTooLong(ValueError):
    """A run would take longer than MAX_RUN_SECONDS, found before any step is taken.

    Its facts are attributes (until, dt, steps, masses, seconds, limit; longest: an `until` that
    fits in SUGGESTION_MARGIN of the limit, s, or None where none is at least `shortest`, the least
    the scene accepts); str() is one sentence, and worded(until_name) the same sentence naming the
    question time as the caller lets a user set it (the command line's --until).
    """

    def __init__(self, *, until, dt, steps, masses, seconds, limit, longest, shortest=0.0):
        self.until, self.dt, self.steps, self.masses = until, dt, steps, masses
        self.seconds, self.limit, self.longest, self.shortest = seconds, limit, longest, shortest
        super().__init__(self.worded("until"))

    def worded(self, until_name: str) -> str:
        count = f"{self.steps:,} steps" if math.isfinite(self.steps) else "more than 10¹⁸ steps"
        several = self.masses > 1
        if self.longest is not None:
            advice = f"use a larger dt, or a smaller {until_name} (at most {self.longest:.6g} s with dt = {self.dt:g} s)"
        else:   # no until short enough would still be a run the scene accepts
            advice = f"use a larger dt{' or fewer masses' if several else ''}" + (
                f" (the scene needs {until_name} of at least {self.shortest:.6g} s)" if self.shortest > 0 else "")
        return (f"a run to t = {self.until:g} s with dt = {self.dt:g} s is {count} of {self.masses} "
                f"mass{'es' if several else ''}, about {_duration(self.seconds)} of computing "
                f"here, more than the {self.limit:g} s a run may take; {advice}")


SUGGESTION_MARGIN = 0.5       # a suggested until fits in half the limit: the estimate can be off by 1.6×


def check_cost(engine, *, until: float, extra_per_step: float = 0.0, limit: float = MAX_RUN_SECONDS,
               shortest: float = 0.0) -> int:
    """The number of steps from the engine's time to `until`, if they fit in `limit` seconds.

    extra_per_step is what the caller adds per step (writing rows, s). Raises RunTooLong with the
    steps and the estimated time, before any step is taken, and an `until` that fits in
    SUGGESTION_MARGIN of the limit (rounded down to two digits) if there is one of at least
    `shortest` (the least the scene accepts).
    """
    dt, start = engine.dt, engine.t
    ratio = (until - start) / dt
    n = steps_to_reach(until - start, dt) if math.isfinite(ratio) and ratio < 1e18 else math.inf
    if n * engine.start.count <= 10_000:      # a few thousand mass-steps: not worth measuring
        return n
    per_step = engine.seconds_per_step() + extra_per_step
    if n * per_step <= limit:
        return n
    longest = _two_digits_down(start + math.floor(SUGGESTION_MARGIN * limit / per_step) * dt)
    raise RunTooLong(until=until, dt=dt, steps=n, masses=engine.start.count, seconds=n * per_step,
                     limit=limit, longest=longest if longest > start and longest >= shortest else None,
                     shortest=shortest)


def _two_digits_down(x: float) -> float:
    """x rounded down to two significant digits (157.69 → 150, 1.567 → 1.5): a value to type."""
    if x <= 0 or not math.isfinite(x):
        return x
    unit = 10.0 ** (math.floor(math.log10(x)) - 1)
    return float(f"{math.floor(x / unit + 1e-9) * unit:.2g}")


def time_steps(advance, *, warm_up: int, batch: int, gives_up=()) -> float:
    """Seconds of this thread's processor time per step of advance(steps), on a trial engine.

    After a warm-up (which compiles the fast loop where it applies), batches of `batch` steps,
    doubling, for about TRIAL_SECONDS: big enough that the cost of a call is not what is
    measured, and in CPU time, so a computer busy with other programs does not inflate it. An
    exception in gives_up (the trial blew up) ends the trial with what it measured.
    """
    steps, spent = 0, 0.0
    try:
        advance(warm_up)
        while spent < TRIAL_SECONDS and steps < 1_000_000:
            begin = time.thread_time()
            advance(batch)
            spent += time.thread_time() - begin
            steps += batch
            batch *= 2
    except gives_up:
        pass
    return spent / steps if steps else 0.0


def _duration(seconds: float) -> str:
    if not math.isfinite(seconds) or seconds > 1e9:
        return "forever"
    for unit, size in (("days", 86400), ("hours", 3600), ("minutes", 60)):
        if seconds >= 2 * size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"

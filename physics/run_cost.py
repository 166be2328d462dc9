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

    Its facts are attributes (until, dt, steps, masses, seconds, limit, longest: the longest
    `until` that fits, s); str() is one sentence, and worded(until_name) the same sentence naming
    the question time as the caller lets a user set it (the command line's --until).
    """

    def __init__(self, *, until, dt, steps, masses, seconds, limit, longest):
        self.until, self.dt, self.steps, self.masses = until, dt, steps, masses
        self.seconds, self.limit, self.longest = seconds, limit, longest
        super().__init__(self.worded("until"))

    def worded(self, until_name: str) -> str:
        count = f"{self.steps:,} steps" if math.isfinite(self.steps) else "more than 10¹⁸ steps"
        return (f"a run to t = {self.until:g} s with dt = {self.dt:g} s is {count} of {self.masses} "
                f"mass{'es' if self.masses > 1 else ''}, about {_duration(self.seconds)} of computing "
                f"here, more than the {self.limit:g} s a run may take; use a larger dt, or a smaller "
                f"{until_name} (at most {self.longest:.6g} s with dt = {self.dt:g} s)")


def check_cost(engine, *, until: float, extra_per_step: float = 0.0, limit: float = MAX_RUN_SECONDS) -> int:
    """The number of steps from the engine's time to `until`, if they fit in `limit` seconds.

    extra_per_step is what the caller adds per step (writing rows, s). Raises RunTooLong with the
    steps, the estimated time and the longest `until` that fits, before any step is taken.
    """
    dt, start = engine.dt, engine.t
    ratio = (until - start) / dt
    n = steps_to_reach(until - start, dt) if math.isfinite(ratio) and ratio < 1e18 else math.inf
    if n * engine.start.count <= 10_000:      # a few thousand mass-steps: not worth measuring
        return n
    per_step = engine.seconds_per_step() + extra_per_step
    if n * per_step <= limit:
        return n
    raise RunTooLong(until=until, dt=dt, steps=n, masses=engine.start.count, seconds=n * per_step,
                     limit=limit, longest=start + math.floor(limit / per_step) * dt)


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

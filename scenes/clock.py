"""Real time for the browser view: how many fixed steps of Δt each frame runs, and what it plots.

The physics always steps with its fixed Δt. The view wants simulation time to advance at
speed × wall-clock time, whatever Δt is, so each frame asks :class:`RealTimeClock` how many steps
are due: the wall time since the last frame, times speed, divided by Δt, plus the fraction of a
step left over from the frame before. Carrying that fraction means nothing is lost to rounding, so
t does not drift from speed × wall time, at Δt = 1e-3 s or 1e-4 s alike.

Three things keep the model from jumping:

* a frame's wall time counts for at most ``max_frame`` seconds, so a hiccup (garbage collection, a
  dragged window) costs a short pause instead of a sudden leap;
* a frame runs at most ``max_steps`` steps (what the computer manages in a frame, measured by
  :class:`StepBudget`); if the physics cannot keep up, the model runs slower than real time
  instead of falling ever further behind and then racing;
* while paused, or while the page has stopped asking for updates (a background tab), no time is
  owed at all, so the model resumes exactly where it stopped.

:class:`LiveRun` steps a model in those batches and keeps, every ``sample_every`` seconds of
simulation time, a sample for the graphs. :class:`Trace` holds one graph curve's points for a
scrolling window, so a 30-minute run keeps a fixed number of points.

Nothing here imports vpython: all of it is tested with a fake clock (tests/test_clock.py).
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

import numpy as np

from physics.energy import WorkMeter, report
from physics.simulate import fastest_angular_frequency, stability_advice, stepper
from physics.state import State


class RealTimeClock:
    """Turns wall-clock time into a whole number of physics steps of Δt per frame.

    steps due = (wall time since last frame, at most max_frame) × speed / Δt + carried fraction
    """

    def __init__(self, *, dt: float, now: float, speed: float = 1.0, max_frame: float = 0.25):
        if dt <= 0:
            raise ValueError("dt must be positive")
        self.dt = float(dt)
        self.speed = float(speed)
        self.max_frame = float(max_frame)
        self._last = float(now)
        self._owed = 0.0  # fraction of a step carried to the next frame
        self.dropped = 0.0  # simulation time, s, given up to hiccups or to a slow computer

    def steps_due(self, *, now: float, running: bool = True, max_steps: int | None = None) -> int:
        """The number of steps this frame should run. Call once per frame.

        running False (paused, or the page is hidden) owes nothing for the time since the last
        frame, and keeps the carried fraction, so the model resumes without a jump.
        """
        elapsed, self._last = float(now) - self._last, float(now)
        if not running or elapsed <= 0:
            return 0
        if elapsed > self.max_frame:
            self.dropped += (elapsed - self.max_frame) * self.speed
            elapsed = self.max_frame
        self._owed += elapsed * self.speed / self.dt
        steps = math.floor(self._owed)
        if max_steps is not None and steps > max_steps:
            self.dropped += (steps - max_steps) * self.dt
            steps = max_steps
            self._owed = self._owed - math.floor(self._owed)
        else:
            self._owed -= steps
        return steps

    def restart(self, *, now: float) -> None:
        """Forget owed time, as at t = 0 (Reset, a new constant, another integrator)."""
        self._last = float(now)
        self._owed = 0.0
        self.dropped = 0.0


class StepBudget:
    """How many steps fit in one frame's share of the processor, from the measured cost per step.

    The view leaves the rest of each frame to the page's server thread and to sleep, so the page
    stays responsive even when Δt is too small for the computer to keep up in real time.
    """

    def __init__(self, *, seconds_per_frame: float = 0.015, first_guess: float = 50e-6):
        self.seconds_per_frame = seconds_per_frame
        self.seconds_per_step = first_guess

    def record(self, *, steps: int, seconds: float) -> None:
        """Blend in the cost of a batch of steps (ignoring batches too small to time)."""
        if steps >= 10 and seconds > 0:
            self.seconds_per_step = 0.8 * self.seconds_per_step + 0.2 * seconds / steps

    @property
    def max_steps(self) -> int:
        return max(1, int(self.seconds_per_frame / self.seconds_per_step))


@dataclass(frozen=True)
class Sample:
    """What the graphs show at one instant: t (s), positions r (N, 3) m, energies (J)."""

    t: float
    r: np.ndarray
    energy: dict


class LiveRun:
    """A model being stepped for the view: the state now, W_nc so far, and samples for graphs.

    Reset is reassignment: :meth:`restart` puts back the model's own initial state and a new
    work meter, so the start is restored exactly.
    """

    def __init__(self, model, *, integrator: str, sample_every: float = 0.05,
                 growth_limit: float = 1e3):
        self.model = model
        self.integrator = model.integrators or integrator
        self.step = stepper(self.integrator)
        self.sample_every = float(sample_every)
        self._uses_work = any(not force.conservative for force in model.forces)
        r0, v0 = model.state.r, model.state.v
        size = float(np.max(np.linalg.norm(r0 - model.anchors, axis=-1)))
        omega = fastest_angular_frequency(model.forces, model.state.m)
        speed = float(np.max(np.linalg.norm(v0, axis=-1)))
        self._omega = omega
        self._limit = growth_limit * (1.0 + size + (speed / omega if omega else speed))
        self.restart()

    def restart(self) -> list[Sample]:
        """Back to the model's initial state; returns the sample at t = 0."""
        self.state: State = self.model.state
        self.meter = WorkMeter(self.state, self.model.forces) if self._uses_work else None
        self.problem: str | None = None
        self._next = 1
        return [self.sample()]

    def sample(self) -> Sample:
        work = self.meter.work if self.meter else 0.0
        return Sample(t=self.state.t, r=self.state.r, energy=report(self.state, self.model.forces, work))

    def advance(self, steps: int) -> list[Sample]:
        """Take `steps` steps of Δt; returns the samples due on the way (one per sample_every).

        If the motion blows up (non-finite, or growing far beyond its start), stops and sets
        :attr:`problem` to a sentence naming Δt and the method's stability limit.
        """
        if self.problem:
            return []
        step, forces, dt, meter = self.step, self.model.forces, self.model.dt, self.meter
        state, samples = self.state, []
        next_t = self._next * self.sample_every
        for _ in range(steps):
            state = step(state, forces, dt)
            if meter:
                meter.advance(state)
            if state.t >= next_t - 1e-9 * dt:
                self.state = state
                samples.append(self.sample())
                self._next = math.floor(state.t / self.sample_every + 1e-9) + 1
                next_t = self._next * self.sample_every
        self.state = state
        if steps:
            self._check()
        return samples

    def _check(self) -> None:
        r = self.state.r
        finite = bool(np.all(np.isfinite(r)) and np.all(np.isfinite(self.state.p)))
        if finite and np.max(np.linalg.norm(r - self.model.anchors, axis=-1)) <= self._limit:
            return
        what = "non-finite state" if not finite else "motion growing without bound"
        self.problem = (f"the simulation blew up by t = {self.state.t:.4g} s ({what}): "
                        + stability_advice(self.integrator, self.model.dt, self._omega))


class Trace:
    """The points of one graph curve, kept for a scrolling window of `span` seconds.

    Points arrive in time order. Once the curve holds more than 2 × span of time, the points older
    than the last `span` seconds are dropped and :meth:`add` says the curve must be redrawn from
    :attr:`points`; otherwise the new points are simply appended. With samples every 0.05 s, a
    curve never holds more than about 2 × span × 20 points (1,200 for span = 30 s).
    """

    def __init__(self, *, span: float = 30.0):
        self.span = float(span)
        self.points: deque = deque()

    def add(self, points) -> bool:
        """Append (t, value) points; True if old points were dropped (redraw the whole curve)."""
        self.points.extend(points)
        if not self.points or self.points[-1][0] - self.points[0][0] <= 2 * self.span:
            return False
        start = self.points[-1][0] - self.span
        while self.points and self.points[0][0] < start:
            self.points.popleft()
        return True

    def clear(self) -> None:
        self.points.clear()


def window(t: float, *, span: float) -> tuple[float, float]:
    """The graph's time axis, s: [0, span] at first, then the last `span` seconds, scrolling."""
    start = max(0.0, t - span)
    return start, start + span

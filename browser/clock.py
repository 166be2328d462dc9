"""Real time for the browser view: how many fixed steps of Δt each frame runs, and what it plots.

The physics always steps with its fixed Δt. The view wants simulation time to advance at
speed × wall-clock time, whatever Δt is, so each frame asks :class:`RealTimeClock` how many steps
are due: the wall time since the last frame, times speed, divided by Δt, plus whatever was owed
from the frames before (at least the fraction of a step left over). Carrying what is owed means
nothing is lost to rounding or to a late frame, so t does not drift from speed × wall time, at
Δt = 1e-3 s or 1e-4 s alike.

What keeps the model from jumping:

* a pause longer than ``long_pause`` seconds (5 s), of this program or of the page (a background
  tab the browser has frozen, a laptop that slept), is skipped instead of made up, so the model
  resumes where it stopped; shorter hiccups (garbage collection, a busy computer, a page slow to
  draw) are made up over the next frames;
* a frame runs at most ``max_steps`` steps (what the computer manages in a frame, measured by
  :class:`StepBudget`), and at most ``max_behind`` seconds stay owed: if the physics cannot keep
  up, the model runs slower than real time instead of falling ever further behind and then racing;
* while paused nothing is owed at all, so Run continues from the state on the screen.

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

from physics.accuracy import judge_dt
from physics.energy import series
from physics.recording import Samples
from physics.simulate import BlowUpError, time_grid
from physics.stability import judge, rates
from physics.state import State
from scenes._view import MAX_DRAWN_MASSES


SLOWEST = 1 / 60             # the page must manage at least 1 s of simulated time per minute


def check_live_cost(model, integrator=None) -> None:
    """Refuse, with one line, a scene the page cannot show: too many masses to draw, or steps so
    dear that a simulated second takes more than a minute (physics.simulate's measured cost).

    Raises ValueError; the browser and the notebook call this before anything is drawn.
    """
    count = model.state.count
    if count > MAX_DRAWN_MASSES:
        raise ValueError(f"{count:,} masses are more than the {MAX_DRAWN_MASSES:,} the page can draw; "
                         f"use fewer (count, curves), or run it headless")
    seconds = model.simulation(integrator).seconds_per_step() / model.dt   # computing per simulated s
    if seconds > 1 / SLOWEST:
        raise ValueError(f"each simulated second takes about {seconds:.3g} s of computing here "
                         f"(dt = {model.dt:g} s, {count:,} masses), so the page would crawl; use a "
                         f"larger dt or fewer masses, or run it headless")


class RealTimeClock:
    """Turns wall-clock time into a whole number of physics steps of Δt per frame.

    steps owed += (wall time since the last frame) × speed / Δt
    steps due   = the whole part of the steps owed, at most max_steps

    Whatever is not run this frame stays owed, up to ``max_behind`` seconds of wall time (the
    rest is given up and counted in :attr:`dropped`). A gap longer than ``long_pause`` seconds,
    between two frames or since the page last spoke, is skipped and counted in :attr:`skipped`.

    Why 5 s: a page is slow, not gone, while it speaks every few seconds. Software rendering on a
    busy computer answered only every 0.5–5 s in our measurements (docs/long_run.md), and browsers
    wake a background tab's timers once a second; the model keeps real time through both, so the
    t the page shows when it next draws is the real-time one. A tab the browser has frozen goes
    quiet for good: the model runs on for at most 5 s, then waits.
    """

    def __init__(self, *, dt: float, now: float, speed: float = 1.0, long_pause: float = 5.0,
                 max_behind: float = 2.0):
        if dt <= 0:
            raise ValueError("dt must be positive")
        self.dt = float(dt)
        self.speed = float(speed)
        self.long_pause = float(long_pause)
        self.max_behind = float(max_behind)
        self.restart(now=now)

    def steps_due(self, *, now: float, running: bool = True, quiet: float = 0.0,
                  max_steps: int | None = None) -> int:
        """The number of steps this frame should run. Call once per frame.

        running  False while paused: nothing is owed for the time since the last frame.
        quiet    seconds since the page last asked for an update (0 if unknown).
        """
        elapsed, self._last = float(now) - self._last, float(now)
        if elapsed <= 0:
            return 0
        if not running or elapsed > self.long_pause or quiet > self.long_pause:
            if running:
                self.skipped += elapsed
            self._forgive()
            return 0
        self._owed += elapsed * self.speed / self.dt
        steps = math.floor(self._owed)
        if max_steps is not None:
            steps = min(steps, max_steps)
        self._owed -= steps
        excess = math.floor(self._owed - self.max_behind * self.speed / self.dt)
        if excess > 0:
            self._owed -= excess
            self.dropped += excess * self.dt
        return steps

    def _forgive(self) -> None:
        """Forget the whole steps owed, keeping the fraction (lost to no rounding)."""
        whole = math.floor(self._owed)
        self.dropped += whole * self.dt
        self._owed -= whole

    @property
    def behind(self) -> float:
        """Simulation time, s, owed but not yet run."""
        return self._owed * self.dt

    def restart(self, *, now: float) -> None:
        """Forget owed time, as at t = 0 (Reset, a new constant, another integrator)."""
        self._last = float(now)
        self._owed = 0.0  # steps owed: the fraction carried from frame to frame, and any backlog
        self.dropped = 0.0  # simulation time, s, given up because the computer could not keep up
        self.skipped = 0.0  # wall time, s, of long pauses passed over without catching up


class StepBudget:
    """How many steps fit in one frame's share of the processor, from the measured cost per step.

    The view leaves the rest of each frame to the page's server thread and to sleep, so the page
    stays responsive even when Δt is too small for the computer to keep up in real time.

    The cost per step is a running average over batches of at least ``MIN_STEPS`` steps; smaller
    frames are added up until they make one, so the estimate keeps moving however few steps a
    frame runs. One batch can raise the estimate by at most ``MAX_RISE`` times: a frame stalled by
    something else (another program, garbage collection, a page slow to draw) then costs a few
    frames of caution instead of capping the model far below real time for good.
    """

    MIN_STEPS = 10
    MAX_RISE = 4.0

    def __init__(self, *, seconds_per_frame: float = 0.015, first_guess: float = 50e-6):
        self.seconds_per_frame = seconds_per_frame
        self.seconds_per_step = first_guess
        self._steps, self._seconds = 0, 0.0  # small batches added up until MIN_STEPS

    def record(self, *, steps: int, seconds: float) -> None:
        """Blend in the cost of a batch of steps (small batches are added up first)."""
        if steps <= 0 or seconds <= 0:
            return
        self._steps += steps
        self._seconds += seconds
        if self._steps < self.MIN_STEPS:
            return
        cost = min(self._seconds / self._steps, self.MAX_RISE * self.seconds_per_step)
        self.seconds_per_step = 0.8 * self.seconds_per_step + 0.2 * cost
        self._steps, self._seconds = 0, 0.0

    @property
    def max_steps(self) -> int:
        return max(1, int(self.seconds_per_frame / self.seconds_per_step))


@dataclass(frozen=True)
class Sample:
    """What the graphs show at one instant: t (s), positions r (N, 3) m, energies (J), momenta p."""

    t: float
    r: np.ndarray
    energy: dict
    p: np.ndarray = None


class LiveRun:
    """A model being stepped for the view by the engine (physics/simulate.py), with graph samples.

    The engine owns the state, W_nc and the blow-up check; this adds the view's pieces: a sample
    for the graphs every ``sample_every`` seconds of simulation time, and :attr:`problem`, the
    sentence that stopped the run, and :attr:`advice`, the line saying that Δt is stable but
    inaccurate (None when it is fine). Reset is reassignment: :meth:`restart` puts back the model's
    exact initial state.

    Runaways: where masses are stepped by different integrators side by side (the `integrators`
    scene), a mass whose method is unstable at this Δt (euler at every Δt) is expected to run away.
    Once it is farther than ``runaway_reach`` metres from its anchor the engine freezes it there
    (at rest) and names it in :attr:`runaways` as {mass index: (t in s, reason sentence)}, while
    the other masses run on; the whole run stops (:attr:`problem`) only if a mass not expected to
    run away blows up. :attr:`may_run_away` lists the masses expected to (Model.expected_runaways).
    """

    def __init__(self, model, *, integrator: str, sample_every: float = 0.05,
                 growth_limit: float = 1e3):
        self.model = model
        self.sample_every = float(sample_every)
        r0, v0 = model.state.r, model.state.v
        size = float(np.max(np.linalg.norm(r0 - model.anchors, axis=-1)))
        omega = float(np.max(rates(model.forces, model.state.m).omega))
        speed = float(np.max(np.linalg.norm(v0, axis=-1)))
        self.runaway_reach = 3.0 * (size + (speed / omega if omega else speed))
        self.may_run_away = model.expected_runaways(model.methods(integrator))
        self.engine = model.simulation(integrator, growth_limit=growth_limit,
                                       may_run_away=self.may_run_away)
        # Δt judged once per run (stability and accuracy, physics/accuracy.py): the page's one line
        self.advice = judge_dt(model.state, model.forces, self.engine.methods, model.dt,
                               ignore=self.may_run_away).advice
        self.restart()

    @property
    def state(self) -> State:
        return self.engine.state

    @property
    def runaways(self) -> dict:
        return self.engine.runaways

    def restart(self) -> list[Sample]:
        """Back to the model's initial state; returns the sample at t = 0."""
        self.engine.restart()
        self.problem: str | None = None
        self._grid = time_grid(self.sample_every, t0=self.model.state.t, dt=self.model.dt)
        self.before = None   # the state at the start of the last step (the description's step)
        return [self.sample()]

    def sample(self) -> Sample:
        state = self.engine.state
        return Sample(t=state.t, r=state.r, energy=self.engine.energy(), p=state.p)

    def advance(self, steps: int) -> list[Sample]:
        """Take `steps` steps of Δt; returns the samples due on the way (one per sample_every).

        If the motion blows up (non-finite, or growing far beyond its start), stops and sets
        :attr:`problem` to the engine's sentence naming Δt and what limits it.
        """
        if self.problem or steps <= 0:
            return []
        try:
            samples = self._advance_keeping_before(steps)
        except BlowUpError as error:
            self.problem = str(error)
            return []
        self._freeze_runaways()
        energy = series(State(t=samples.t, r=samples.r, p=samples.p, m=samples.m),
                        self.model.forces, samples.work)
        return [Sample(t=float(t), r=samples.r[n], p=samples.p[n],
                       energy={key: float(values[n]) for key, values in energy.items()})
                for n, t in enumerate(samples.t)]


    def _advance_keeping_before(self, steps: int) -> Samples:
        """The engine's `steps` steps, the last one apart, so that :attr:`before` is the state at
        its start: the page describes the last step in words (export/description.py) as Step
        writes it out. The samples are those one call would record."""
        engine = self.engine
        head = engine.advance(steps - 1, record=self._grid, final=False) if steps > 1 else None
        now = engine.state
        self.before = State(t=now.t, r=np.array(now.r), p=np.array(now.p), m=now.m)   # a copy: the engine steps on
        tail = engine.advance(1, record=self._grid, final=False)
        if head is None or not len(head.t):
            return tail
        if not len(tail.t):
            return head
        return Samples(t=np.concatenate([head.t, tail.t]), r=np.concatenate([head.r, tail.r]),
                       p=np.concatenate([head.p, tail.p]), work=np.concatenate([head.work, tail.work]), m=tail.m)

    def _freeze_runaways(self) -> None:
        """Have the engine freeze, at rest where they are, expected runaways that went too far."""
        r, engine = self.engine.state.r, self.engine
        for i in self.may_run_away:
            if i in engine.runaways:
                continue
            finite = bool(np.all(np.isfinite(r[i])))
            if finite and np.linalg.norm(r[i] - self.model.anchors[i]) <= self.runaway_reach:
                continue
            name = engine.methods[i]
            verdict = judge(self.model.forces, self.model.state.m, engine.methods, self.model.dt,
                            ignore=[j for j in range(len(r)) if j != i])
            engine.freeze(i, f"{name} ran away at t = {engine.t:.3g} s (its swing grew past "
                             f"{self.runaway_reach:.2g} m): {verdict.message}")


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

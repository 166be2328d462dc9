"""The engine: the one loop that steps the physics, for every path.

The page's program is a loop: work out F_net, update p, then r, then t, and repeat. Here that loop
is :class:`Simulation`, and it is the only one in the project: the command line's runs, the step
table, CSV files and figures, the browser's live run and the notebook, the resonance sweep and
the benchmarks all ask it for steps. It owns

    the state        r and p of every mass, and the step count n (so t = t0 + n·Δt exactly:
                     time is never a running sum t = t + Δt, which drifts by round-off)
    the tick         one step of the chosen integrator (physics/integrators.py), and the work
                     meter W_nc = ∫ P_nc dt (trapezoid rule) where a force is not conservative
    the recording    which steps to keep: every step, every n-th, a time grid, or only the end
    the checks       every CHUNK steps: a state that stopped being finite, or a mass far beyond
                     any size its motion could reach, is a blow-up; physics/stability.py says why
    the run's cost   an estimate of its seconds, so a run too long is refused before it starts

`advance(steps)` and `run_until(t)` continue from wherever the engine is; `restart()` goes back to
the exact initial state (reassignment, nothing recomputed).

Speed. numpy pays about a microsecond per call whatever the array's size, so a single mass stepped
with numpy is slower than plain Python floats. For systems of up to 32 masses the engine traces
its own tick once and runs it as a loop over floats (physics/compiled.py): the same arithmetic,
several times faster. Bigger batches stay in numpy, where each call does a lot of work; there
r and p are laid out column by column ("Fortran" order, physics.state.make_state), which keeps each
component contiguous, so the per-mass columns (k, m, |L| of shape (N, 1)) broadcast against (N, 3)
at full speed. Shapes, indexing and results are the same in either layout. The figures and how
they were measured are in docs/performance.md.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from .compiled import MAX_COMPONENTS, MAX_TRACES, compile_loop
from .energy import nonconservative_power, report, series, work_step
from .forces import QuadraticDrag, Spring
from .integrators import DEFAULT_INTEGRATOR, INTEGRATORS, methods_for
from .stability import fastest_angular_frequency, judge
from .state import State, velocity

CHUNK = 1024                 # steps between two checks for blow-up, cancellation and progress
PROGRESS_EVERY = 1.0         # s of computing between two progress reports
COMPILE_FROM_STEPS = 100     # shorter advances are not worth tracing and compiling a loop for


class BlowUpError(RuntimeError):
    """The state became non-finite or grew without bound: Δt is too large for this method.

    t is the time of the check that found it, in s.
    """

    t: float = math.nan


class Cancelled(RuntimeError):
    """The run was cancelled (Simulation.cancel) before it finished."""


def steps_to_reach(until: float, dt: float) -> int:
    """Number of steps of dt that reaches time `until` (rounding up, forgiving round-off)."""
    return max(0, math.ceil(until / dt - 1e-9))


# ---- what to record: a schedule says which step number is recorded next ----

def every(n: int):
    """Record every n-th step (n = 1: every step)."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError("record_every must be a whole number ≥ 1, or None for the final state only")
    n = int(n)
    return lambda done: (done // n + 1) * n


def time_grid(spacing: float, *, t0: float, dt: float, start: float = 0.0, end: float = math.inf):
    """Record the first step at or after each time start, start + spacing, ... up to end, s.

    spacing ≤ dt records every step from start to end.
    """
    def after(done):
        t = t0 + done * dt
        if t >= end:
            return math.inf
        grid = start if t < start else start + (math.floor((t - start) / spacing + 1e-9) + 1) * spacing
        return max(done + 1, steps_to_reach(min(grid, end) - t0, dt))
    return after


@dataclass
class Samples:
    """Recorded steps: t (n,) s, r and p (n, N, D) in m and kg·m/s, W_nc so far (n, N) J."""

    t: np.ndarray
    r: np.ndarray
    p: np.ndarray
    work: np.ndarray
    m: np.ndarray

    @property
    def v(self) -> np.ndarray:
        return velocity(self.p, self.m)

    def __len__(self) -> int:
        return len(self.t)


class Simulation:
    """A system of masses being stepped: the engine (see the module's docstring).

    state      the initial state (t0, r, p, m)
    forces     the forces summed into F_net
    dt         the fixed time step Δt, s
    integrator one name from physics.integrators.INTEGRATORS, or one name per mass
    may_run_away  masses the scene expects to run away (euler beside the others): such a mass is
               frozen at rest where it blew up, named in :attr:`runaways`, and the others run on
    growth_limit  how many times the starting size of the motion a mass may stray from its
               anchor before the run counts as blown up
    compiled   False keeps to the numpy tick (for comparison; the results are the same)
    """

    def __init__(self, state: State, forces, *, dt: float, integrator=DEFAULT_INTEGRATOR,
                 may_run_away=(), growth_limit: float = 1e6, compiled: bool = True):
        if not (math.isfinite(dt) and dt > 0):
            raise ValueError(f"dt must be a finite time greater than 0 s (got {dt!r})")
        self.start = state
        self.forces = tuple(forces)
        self.dt = float(dt)
        self.methods = methods_for(integrator, state.count)
        self.metered = any(not force.conservative for force in self.forces)
        self.may_run_away = frozenset(int(i) for i in may_run_away)
        self.compiled = compiled
        self._seconds_per_step = None
        springs = [force for force in self.forces if isinstance(force, Spring)]
        self._anchor = np.broadcast_to(springs[0].anchor, state.r.shape) if springs else None
        self._limit = _motion_scale(state, springs, fastest_angular_frequency(self.forces, state.m)) * growth_limit
        self.restart()

    # ---- where the engine is ----

    def restart(self) -> None:
        """Back to the exact initial state: step 0, W_nc = 0, nothing frozen."""
        self.steps = 0
        self._r, self._p = self.start.r, self.start.p
        self.work = np.zeros(self.start.count)
        self._power = (nonconservative_power(self.start, self.forces) if self.metered
                       else np.zeros(self.start.count))
        self.runaways: dict[int, tuple[float, str]] = {}
        self._step = _stepper(self.methods, frozen=())
        self._loop = None
        self._loop_failed = False
        self._cancelled = False

    @property
    def t(self) -> float:
        """t = t0 + n·Δt, s, from the whole number of steps taken."""
        return self.time_of(self.steps)

    def time_of(self, step: int) -> float:
        return self.start.t + step * self.dt

    @property
    def state(self) -> State:
        if self.steps == 0 and self._r is self.start.r and self._p is self.start.p:
            return self.start          # after restart(): the very initial state, reassigned
        return State(t=self.t, r=self._r, p=self._p, m=self.start.m)

    def energy(self) -> dict:
        """K, U, E, W_nc and E − W_nc of the system now, J (numbers)."""
        return report(self.state, self.forces, self.work)

    def cancel(self) -> None:
        """Ask a running advance() to stop at its next check; it raises Cancelled."""
        self._cancelled = True

    def freeze(self, index: int, reason: str) -> None:
        """Hold mass `index` at rest where it is from now on, and name it in runaways (t, reason)."""
        if index in self.runaways:
            return
        self.runaways[index] = (self.t, reason)
        r, p = self._r.copy(order="F"), self._p.copy(order="F")
        p[index] = 0.0
        self._r, self._p = r, p
        self.work = self.work.copy()
        self._power = self._power.copy()
        self._power[index] = 0.0
        self._step = _stepper(self.methods, frozen=tuple(sorted(self.runaways)))
        self._loop, self._loop_failed = None, False

    # ---- stepping ----

    def run_until(self, t: float, **options) -> Samples:
        """Advance to the first step at or after time t, s (see advance)."""
        return self.advance(steps_to_reach(t - self.t, self.dt), **options)

    def advance(self, steps: int, *, record=None, final: bool = True, progress=None) -> Samples:
        """Take `steps` steps of Δt from where the engine is, and return the steps recorded.

        record    a schedule (every(n), time_grid(...)) of the step numbers to record, or None
        final     also record the last step of this call
        progress  called as progress(done, total, t) about once a second on long runs

        Raises BlowUpError (the state is kept at the check that found it) or Cancelled.
        """
        steps = int(steps)
        target = self.steps + steps
        rows = _Rows(self)
        schedule = record if record is not None else (lambda done: math.inf)
        mark = self._next_mark(schedule, self.steps, target, final)
        reported, last = time.monotonic(), None

        def on_record(done, values=None, arrays=None):
            rows.add(done, values=values, arrays=arrays)
            return self._next_mark(schedule, done, target, final)

        with np.errstate(over="ignore", invalid="ignore"):
            while self.steps < target:
                if self._cancelled:
                    self._cancelled = False
                    raise Cancelled(f"cancelled at t = {self.t:g} s")
                stop = min(target, self.steps + CHUNK)
                mark = self._ticks(stop, mark, on_record, compile_ok=steps >= COMPILE_FROM_STEPS)
                rows.flush()
                self._check()
                if progress is not None and time.monotonic() - reported >= PROGRESS_EVERY:
                    progress(self.steps - (target - steps), steps, self.t)
                    reported, last = time.monotonic(), self.steps
        if progress is not None and last is not None and last != target:   # end where it ended
            progress(steps, steps, self.t)
        return rows.samples()

    @staticmethod
    def _next_mark(schedule, done: int, target: int, final: bool):
        mark = schedule(done)
        return min(mark, target) if final else mark

    def _arrays(self) -> list:
        return [self._r, self._p, self._power, self.work]

    def _set(self, arrays) -> None:
        self._r, self._p, self._power, self.work = (np.asfortranarray(a) if a.ndim == 2 else a
                                                    for a in arrays)

    def tick(self, t, t_next, r, p, power, work):
        """One step: the integrator's update of r and p, then W_nc by the trapezoid rule.

        t is the time at the start of the step and t_next = t + Δt at its end (both from the step
        count). The same function runs on floats (numpy) and on traced numbers (the compiled loop).
        """
        new = self._step(State(t=t, r=r, p=p, m=self.start.m), self.forces, self.dt)
        if not self.metered:
            return new.r, new.p, power, work
        power_next = nonconservative_power(State(t=t_next, r=new.r, p=new.p, m=self.start.m), self.forces)
        return new.r, new.p, power_next, work_step(work, power, power_next, self.dt)

    def _ticks(self, stop: int, mark, on_record, *, compile_ok: bool):
        """Tick up to step number `stop`, recording at the marks; returns the next mark."""
        if self.compiled and compile_ok and self._loop is None and not self._loop_failed:
            self._loop = compile_loop(self.tick, self._arrays(), t0=self.start.t, dt=self.dt)
            self._loop_failed = self._loop is None
        loop = self._loop
        while self.steps < stop:
            if loop is not None and loop.ready:
                done, mark, arrays = loop.advance(self._arrays(), self.steps, stop, mark,
                                                  lambda done, values: on_record(done, values=values))
                self._set(arrays)
                self.steps = done
                if done == stop:
                    break
            # One numpy tick: the loop stopped short (a guard), or there is none.
            self._set(self.tick(self.time_of(self.steps), self.time_of(self.steps + 1), *self._arrays()))
            self.steps += 1
            if self.steps == mark:
                mark = on_record(self.steps, arrays=self._arrays())
            if loop is not None and loop.traces < MAX_TRACES:
                loop.retrace(self._arrays(), step=self.steps)
        return mark

    def _check(self) -> None:
        """Freeze or stop masses that blew up: non-finite, or beyond the limit from their anchor."""
        r, p = self._r, self._p
        bad = ~(np.all(np.isfinite(r), axis=1) & np.all(np.isfinite(p), axis=1))
        if self._anchor is not None:
            with np.errstate(invalid="ignore"):
                bad |= np.linalg.norm(np.nan_to_num(r - self._anchor), axis=1) > self._limit
        if not bad.any():
            return
        rows = [int(i) for i in np.flatnonzero(bad) if int(i) not in self.runaways]
        if not rows:
            return
        reason = self.blow_up_message(rows)
        if all(i in self.may_run_away for i in rows):
            for i in rows:
                self.freeze(i, reason)
                self._r[i] = np.nan_to_num(self._r[i], nan=0.0, posinf=self._limit, neginf=-self._limit)
            return
        error = BlowUpError(reason)
        error.t = self.t
        raise error

    def blow_up_message(self, rows) -> str:
        """The sentence for masses `rows` that blew up: when, how, and what Δt would be stable."""
        finite = bool(np.all(np.isfinite(self._r[rows])) and np.all(np.isfinite(self._p[rows])))
        how = "motion growing without bound" if finite else "non-finite state"
        v = np.nan_to_num(velocity(self._p, self.start.m), nan=0.0, posinf=0.0, neginf=0.0)
        methods = tuple(self.methods[i] for i in rows)
        verdict = judge(self.forces, self.start.m, self.methods, self.dt, v=v)
        drag = any(isinstance(force, QuadraticDrag) and np.any(force.C * force.A * force.rho > 0)
                   for force in self.forces)
        advice = (verdict.message if verdict.message and verdict.method in methods else
                  f"dt = {self.dt:g} s, but the drag (its rate ρCA|v|/m grows with the speed) outgrew what "
                  f"{methods[0]} can follow at this dt; try a smaller dt, or less drag" if drag else
                  f"dt = {self.dt:g} s; try a smaller dt")
        return f"the simulation blew up by t = {self.t:.4g} s ({how}): {advice}"

    # ---- what a run will cost ----

    def seconds_per_step(self) -> float:
        """What one step costs on this computer, s: measured on a trial copy of this engine.

        The trial takes the same path as a real run (the compiled loop where it applies, or numpy)
        for about TRIAL_SECONDS of processor time, so the estimate follows the real cost of one
        mass and of a big batch alike. Measured once per engine.
        """
        if self._seconds_per_step is None:
            trial = Simulation(self.state, self.forces, dt=self.dt, integrator=self.methods,
                               compiled=self.compiled, growth_limit=math.inf)
            compiles = self.compiled and self.start.r.size <= MAX_COMPONENTS
            # Batches big enough that the cost of a call is not what is measured, timed in this
            # thread's CPU time, so a computer busy with other programs does not inflate it.
            steps, spent, batch = 0, 0.0, CHUNK if compiles else 1
            try:
                trial.advance(COMPILE_FROM_STEPS if compiles else 1)     # warm up (and compile)
                while spent < TRIAL_SECONDS and steps < 1_000_000:
                    begin = time.thread_time()
                    trial.advance(batch)
                    spent += time.thread_time() - begin
                    steps += batch
                    batch *= 2
            except (BlowUpError, ArithmeticError):
                pass
            self._seconds_per_step = spent / steps if steps else 0.0
        return self._seconds_per_step


MAX_RUN_SECONDS = 60.0       # the longest run the program starts, by the engine's estimate, s
TRIAL_SECONDS = 0.02         # how long the trial that measures a step's cost runs, s


class RunTooLong(ValueError):
    """A run would take longer than MAX_RUN_SECONDS: a one-line message naming what would fit."""


SUGGESTION_MARGIN = 0.5       # a suggested --until fits in half the limit: the estimate can be off by 1.6×


def check_cost(engine: Simulation, *, until: float, extra_per_step: float = 0.0,
               limit: float = MAX_RUN_SECONDS, until_name: str = "--until", shortest: float = 0.0) -> int:
    """The number of steps from the engine's time to `until`, if they fit in `limit` seconds.

    extra_per_step is what the caller adds per step (writing rows, s). Raises RunTooLong naming
    the steps and the estimated time, before any step is taken, with an `until` that fits in
    SUGGESTION_MARGIN of the limit (rounded down to two digits) if there is one of at least
    `shortest` (the least the scene accepts), else only a larger dt.
    """
    dt, start = engine.dt, engine.t
    ratio = (until - start) / dt
    n = steps_to_reach(until - start, dt) if math.isfinite(ratio) and ratio < 1e18 else math.inf
    if n * engine.start.count <= 10_000:      # a few thousand mass-steps: not worth measuring
        return n
    per_step = engine.seconds_per_step() + extra_per_step
    if n * per_step <= limit:
        return n
    count = f"{n:,} steps" if math.isfinite(n) else "more than 10¹⁸ steps"
    longest = _two_digits_down(start + math.floor(SUGGESTION_MARGIN * limit / per_step) * dt)
    several = engine.start.count > 1
    if longest > start and longest >= shortest:
        advice = f"use a larger dt, or a smaller {until_name} (at most {longest:.6g} s with dt = {dt:g} s)"
    else:   # no until short enough would still be a run the scene accepts
        advice = f"use a larger dt{' or fewer masses' if several else ''}" + (
            f" (the scene needs {until_name} of at least {shortest:.6g} s)" if shortest > start else "")
    raise RunTooLong(
        f"a run to t = {until:g} s with dt = {dt:g} s is {count} of {engine.start.count} "
        f"mass{'es' if several else ''}, about {_duration(n * per_step)} of computing "
        f"here, more than the {limit:g} s a run may take; {advice}")


def _two_digits_down(x: float) -> float:
    """x rounded down to two significant digits (157.69 → 150, 1.567 → 1.5): a value to type."""
    if x <= 0 or not math.isfinite(x):
        return x
    unit = 10.0 ** (math.floor(math.log10(x)) - 1)
    return float(f"{math.floor(x / unit + 1e-9) * unit:.2g}")


def _duration(seconds: float) -> str:
    if not math.isfinite(seconds) or seconds > 1e9:
        return "forever"
    for unit, size in (("days", 86400), ("hours", 3600), ("minutes", 60)):
        if seconds >= 2 * size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"


class _Rows:
    """The steps recorded during one advance: flat rows of floats, packed into arrays a chunk at a time."""

    def __init__(self, engine: Simulation):
        self.engine = engine
        self.steps: list[int] = []
        self.rows: list = []           # this chunk's rows: every component of r, p, P_nc, W_nc
        self.blocks: list[np.ndarray] = []

    def add(self, done, *, values=None, arrays=None):
        self.steps.append(done)
        self.rows.append(values if values is not None else
                         np.concatenate([np.asarray(a, dtype=float).ravel() for a in arrays]))
        if len(self.rows) >= CHUNK:
            self.flush()

    def flush(self):
        if self.rows:
            self.blocks.append(np.array(self.rows, dtype=float))
            self.rows = []

    def samples(self) -> Samples:
        self.flush()
        start = self.engine.start
        size, count = start.r.size, start.count
        flat = np.concatenate(self.blocks) if self.blocks else np.empty((0, 2 * size + 2 * count))
        return Samples(t=self.engine.start.t + np.array(self.steps, dtype=float) * self.engine.dt,
                       r=flat[:, :size].reshape((-1,) + start.r.shape),
                       p=flat[:, size:2 * size].reshape((-1,) + start.r.shape),
                       work=flat[:, 2 * size + count:], m=start.m)


def _stepper(methods, *, frozen):
    """The step of every mass: one integrator, or one per mass; frozen masses stay where they are.

    Several methods side by side step the whole state with each method and keep mass i's row
    from its own method, which is right only for masses that do not act on each other.
    """
    names = sorted(set(methods))
    if len(names) == 1 and not frozen:
        return INTEGRATORS[names[0]].step
    rows = {name: [i for i, method in enumerate(methods) if method == name] for name in names}

    def step(state: State, forces, dt: float) -> State:
        new_r, new_p = state.r.copy(), state.p.copy()
        for name in names:
            moved = INTEGRATORS[name].step(state, forces, dt)
            new_r[rows[name]] = moved.r[rows[name]]
            new_p[rows[name]] = moved.p[rows[name]]
        for i in frozen:
            new_r[i], new_p[i] = state.r[i], state.p[i]
        return replace(state, t=state.t + dt, r=new_r, p=new_p)
    return step


def _motion_scale(state: State, springs, omega: float) -> float:
    """A generous size of the motion (m): start offset, speed/ω, and the spring's own length."""
    if not springs or omega == 0:
        return math.inf
    spring = springs[0]
    offset = np.max(np.linalg.norm(state.r - spring.anchor, axis=-1))
    speed = np.max(np.linalg.norm(state.v, axis=-1))
    return float(offset + speed / omega + np.max(spring.L0) + 9.8 / omega**2 + 1.0)


# ---- a whole run, for tests, benchmarks and sweeps ----

@dataclass
class Trajectory:
    """Samples of a run: t (n,), r and p (n, N, 3); energy (dict of (n,) arrays, J) if asked for."""

    t: np.ndarray
    r: np.ndarray
    p: np.ndarray
    m: np.ndarray
    energy: dict | None = None
    work: np.ndarray | None = None

    @property
    def v(self) -> np.ndarray:
        return velocity(self.p, self.m)

    @property
    def final(self) -> State:
        """The last recorded state, ready to run on."""
        return State(t=float(self.t[-1]), r=np.asfortranarray(self.r[-1]), p=np.asfortranarray(self.p[-1]),
                     m=self.m)


def trajectory(engine: Simulation, samples: Samples, *, with_energy: bool = True) -> Trajectory:
    """A Trajectory of the engine's start and these samples (energy of every sample, J)."""
    start = engine.start
    t = np.concatenate([[start.t], samples.t])
    r = np.concatenate([start.r[None], samples.r])
    p = np.concatenate([start.p[None], samples.p])
    work = np.concatenate([np.zeros((1, start.count)), samples.work])
    energy = (series(State(t=t, r=r, p=p, m=start.m), engine.forces, work) if with_energy else None)
    return Trajectory(t=t, r=r, p=p, m=start.m, energy=energy, work=work)


def run(state: State, forces, *, dt: float, until: float, integrator=DEFAULT_INTEGRATOR,
        with_energy: bool = False, growth_limit: float = 1e6, record_every: int | None = 1,
        compiled: bool = True) -> Trajectory:
    """Step from state.t to `until` with fixed dt, recording the start and every `record_every`
    steps (and always the last); None records only the start and the end.

    Raises BlowUpError if the state stops being finite, or any mass strays more than
    `growth_limit` times the starting size of the motion from its spring's anchor.
    """
    engine = Simulation(state, forces, dt=dt, integrator=integrator, growth_limit=growth_limit,
                        compiled=compiled)
    schedule = None if record_every is None else every(record_every)
    samples = engine.run_until(until, record=schedule)
    return trajectory(engine, samples, with_energy=with_energy)

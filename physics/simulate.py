"""The engine: the one loop that steps the physics, for every path.

The page's program is a loop: work out F_net, update p, then r, then t, and repeat. Here that loop
is :class:`Simulation`, and it is the only one in the project: the command line's runs, the step
table, CSV files and figures, the browser's live run and the notebook, the resonance sweep and
the benchmarks all ask it for steps. It owns

    the state        r and p of every mass, and the step count n (so t = t0 + n·Δt exactly:
                     time is never a running sum t = t + Δt, which drifts by round-off)
    the tick         one step of the chosen integrator (physics/integrators.py), then each force's
                     stop rule where one has one (static friction holds a mass, Force.stop), and
                     the work meter W_nc = ∫ P_nc dt (trapezoid rule) where a force is not
                     conservative
    the recording    which steps to keep: every step, every n-th, a time grid, or only the end
                     (the schedules and the recorder are in physics/recording.py)
    the checks       every CHUNK steps: a state that stopped being finite, or a mass far beyond
                     any size its motion could reach, is a blow-up; physics/stability.py says why
    the run's cost   an estimate of its seconds, so a run too long is refused before it starts
                     (measured on a trial engine; physics/run_cost.py)

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
from dataclasses import replace

import numpy as np

from .motion_axes import columns, cut, moving_axes, put_back
from .compiled import MAX_COMPONENTS, MAX_TRACES, compile_loop
from .energy import nonconservative_power, report, work_step
from .forces import settle
from .integrators import DEFAULT_INTEGRATOR, INTEGRATORS, methods_for
from .stability import fastest_angular_frequency, judge, rates
from .state import State, velocity
# What a run records and what it costs live beside the engine; their names are the engine's API too.
from .recording import Recorder, Samples, Trajectory, every, steps_to_reach, time_grid, trajectory  # noqa: F401
from .run_cost import MAX_RUN_SECONDS, TRIAL_SECONDS, RunTooLong, check_cost, time_steps  # noqa: F401

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
    cut_axes   False steps all three axes even where the motion uses fewer (for comparison; the
               results are the same, bit for bit: physics/motion_axes.py)
    """

    def __init__(self, state: State, forces, *, dt: float, integrator=DEFAULT_INTEGRATOR,
                 may_run_away=(), growth_limit: float = 1e6, compiled: bool = True, cut_axes: bool = True):
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
        # what each force declares (physics/forces/base.py's Force.tether); a plain callable declares nothing
        tethers = [tether() for tether in (getattr(force, "tether", None) for force in self.forces) if tether]
        tethers = [tether for tether in tethers if tether is not None]
        self._anchor = np.broadcast_to(tethers[0][0], state.r.shape) if tethers else None
        self._limit = _motion_scale(state, tethers, fastest_angular_frequency(self.forces, state.m)) * growth_limit
        # the axes the motion uses, and the forces cut to them (None: every axis; physics/motion_axes.py)
        self.cut_axes = cut_axes
        self.axes = moving_axes(state.r, state.p, self.forces) if cut_axes else None
        self._stepped_forces = self.forces if self.axes is None else cut(self.forces, self.axes)
        self._columns = None if self.axes is None else columns(self.axes)    # their index, worked out once
        self._stops = any(getattr(force, "stops", False) for force in self.forces)
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
        recorder = Recorder(self, record, target=target, final=final)
        report = _Progress(progress, total=steps, first=self.steps)
        with np.errstate(over="ignore", invalid="ignore"):
            while self.steps < target:         # a chunk of steps at a time, then the checks
                self._stop_if_cancelled()
                self._ticks(min(target, self.steps + CHUNK), recorder, compile_ok=steps >= COMPILE_FROM_STEPS)
                recorder.flush()
                self._check()
                report.now(self.steps, self.t)
        report.end(self.steps, self.t)
        return recorder.samples()

    def _stop_if_cancelled(self) -> None:
        if self._cancelled:
            self._cancelled = False
            raise Cancelled(f"cancelled at t = {self.t:g} s")

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
        pick, whole_r, whole_p = self._columns, r, p
        if pick is not None:              # only the axes the motion uses; the others stay as they are
            r, p = r[:, pick], p[:, pick]
        new = self._step(State(t=t, r=r, p=p, m=self.start.m), self._stepped_forces, self.dt)
        if self._stops:                   # a force's stop rule (static friction) has the last word
            r_f, p_f = settle(self._stepped_forces, t=t, r=r, p=p, m=self.start.m, dt=self.dt,
                              r_f=new.r, p_f=new.p)
            new = State(t=new.t, r=r_f, p=p_f, m=new.m)
        if self.metered:
            power_next = nonconservative_power(State(t=t_next, r=new.r, p=new.p, m=self.start.m),
                                               self._stepped_forces)
            power, work = power_next, work_step(work, power, power_next, self.dt)
        if pick is None:
            return new.r, new.p, power, work
        return put_back(whole_r, pick, new.r), put_back(whole_p, pick, new.p), power, work

    def _ticks(self, stop: int, recorder: Recorder, *, compile_ok: bool) -> None:
        """Tick up to step number `stop`, recording the steps the recorder marks."""
        if self.compiled and compile_ok and self._loop is None and not self._loop_failed:
            self._loop = compile_loop(self.tick, self._arrays(), t0=self.start.t, dt=self.dt)
            self._loop_failed = self._loop is None
        loop = self._loop
        while self.steps < stop:
            if loop is not None and loop.ready:
                done, arrays = loop.advance(self._arrays(), self.steps, stop, recorder)
                self._set(arrays)
                self.steps = done
                if done == stop:
                    break
            # One numpy tick: the loop stopped short (a guard), or there is none.
            self._set(self.tick(self.time_of(self.steps), self.time_of(self.steps + 1), *self._arrays()))
            self.steps += 1
            if self.steps == recorder.mark:
                recorder.record(self.steps, arrays=self._arrays())
            if loop is not None and loop.traces < MAX_TRACES:
                loop.retrace(self._arrays(), step=self.steps)

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
        # a drag is a rate that grows with the speed: the forces' declared drag at a speed of 1 m/s,
        # named by the force and its own constants (physics/stability.py Part)
        drag = [part for part in rates(self.forces, self.start.m, v=np.ones_like(self._p)).parts
                if part.kind == "drag" and np.any(part.value > 0)]
        named = " and ".join(f"the {part.label} (its rate {part.words} grows with the speed)" for part in drag)
        advice = (verdict.message if verdict.message and verdict.method in methods else
                  f"dt = {self.dt:g} s, but {named} outgrew what {methods[0]} can follow at this dt; try a "
                  f"smaller dt, or less {drag[0].label}" if drag else
                  f"dt = {self.dt:g} s; try a smaller dt")
        return f"the simulation blew up by t = {self.t:.4g} s ({how}): {advice}"

    # ---- what a run will cost ----

    def seconds_per_step(self) -> float:
        """What one step costs on this computer, s: measured once, on a trial copy of this engine
        that takes the same path as a real run (physics/run_cost.py)."""
        if self._seconds_per_step is None:
            trial = Simulation(self.state, self.forces, dt=self.dt, integrator=self.methods,
                               compiled=self.compiled, growth_limit=math.inf, cut_axes=self.cut_axes)
            compiles = self.compiled and self.start.r.size <= MAX_COMPONENTS
            self._seconds_per_step = time_steps(trial.advance, warm_up=COMPILE_FROM_STEPS if compiles else 1,
                                                batch=CHUNK if compiles else 1,
                                                gives_up=(BlowUpError, ArithmeticError))
        return self._seconds_per_step


class _Progress:
    """Calls progress(done, total, t) about every PROGRESS_EVERY seconds of a long advance, and at
    its end if it reported on the way (so the last report is where it ended)."""

    def __init__(self, progress, *, total: int, first: int):
        self.progress, self.total, self.first = progress, total, first
        self.reported, self.last = time.monotonic(), None

    def now(self, steps: int, t: float) -> None:
        if self.progress is not None and time.monotonic() - self.reported >= PROGRESS_EVERY:
            self.progress(steps - self.first, self.total, t)
            self.reported, self.last = time.monotonic(), steps

    def end(self, steps: int, t: float) -> None:
        if self.progress is not None and self.last is not None and self.last != steps:
            self.progress(self.total, self.total, t)


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


def _motion_scale(state: State, tethers, omega: float) -> float:
    """A generous size of the motion (m): start offset from the first tether's anchor, speed/ω, and
    its length."""
    if not tethers or omega == 0:
        return math.inf
    anchor, length = tethers[0]
    offset = np.max(np.linalg.norm(state.r - anchor, axis=-1))
    speed = np.max(np.linalg.norm(state.v, axis=-1))
    return float(offset + speed / omega + np.max(length) + 9.8 / omega**2 + 1.0)


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

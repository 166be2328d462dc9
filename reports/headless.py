"""Running a scene without a browser: the run a headless report describes.

A headless run is the page's loop and nothing else: build the scene's model from its constants,
repeat the momentum update every Δt until the question time, and keep what the reports need.
Before any step, :func:`plan` checks the run's cost on this computer once (the engine's own
measured cost), and :func:`stability_warning` judges Δt once; :func:`simulate` checks, as it
starts, that a scene that measures in a window (resonance) is run to the window's end. :func:`simulate` then runs the plan and returns a
:class:`Result`, which the reports write down: reports/text.py (the final state as text),
reports/json_report.py (one JSON object), reports/csv_file.py (one row per step) and
reports/step_table.py (the first few updates by hand). Nothing here imports vpython or matplotlib.
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from typing import Optional, TextIO

import numpy as np

from physics.accuracy import judge_dt
from physics.integrators import describe
from physics.period import record_window
from physics.recording import CoordinateWatch, Trajectory, WindowLargest, every, steps_to_reach, time_grid, trajectory
from physics.run_cost import RunTooLong, check_cost
from physics.simulate import BlowUpError, Simulation
from physics.stability import REFUSED, judge
from export.step_update import number
from scenes import ConstantError, Model, Setup

from .periods import Timing, timing

# A run is refused before it starts if the engine estimates it longer than MAX_RUN_SECONDS
# (physics.run_cost.check_cost); each row of a CSV file or figure adds ROW_SECONDS to that.
ROW_SECONDS = 25e-6           # s per row: csv.writer measured 24.6 s for 1,000,001 rows here


class TooManySteps(ConstantError):
    """until / dt asks for more steps than a headless run takes: a one-line message with the count."""


@dataclass(frozen=True)
class Result:
    """A finished headless run: the scene's setup and model, the method of each mass, the
    recorded steps (every step, or only the start and the end), the count, and what the run
    looked at as it went without keeping it: the crossings its period is timed by, and the
    largest of the scene's measure over its measuring window (None where it has none)."""

    setup: Setup
    model: Model
    methods: tuple[str, ...]     # the method of each mass (physics.integrators.methods_for)
    trajectory: Trajectory
    steps: int
    timing: Timing
    measured: Optional[WindowLargest] = None

    @property
    def integrator(self) -> str:
        """The method in words: 'rk4', or one name per mass ('euler, euler-cromer, ...')."""
        return describe(self.methods)

    @property
    def labels(self) -> tuple[str, ...]:
        return tuple(self.model.labels)

    def exact_valid_until(self) -> float:
        """When the closed form stops holding (for a row, the first mass's), s: math.inf if it
        holds up to the final time."""
        return float(np.min(self.exact_valid_until_each()))

    def exact_valid_until_each(self) -> np.ndarray:
        """When each mass's closed form stops holding, (N,) s: math.inf where it holds to the end."""
        return self.model.exact_valid_until_each(float(self.trajectory.t[-1]))

    def exact(self) -> Optional[tuple[np.ndarray, np.ndarray]]:
        """(r, v) of the closed form at the final time, shape (N, 3) each, or None where unknown.

        A mass whose closed form stopped holding before the final time gets NaN ("not known"),
        as one with no closed form does (exact_notes says why); None if every mass's stopped.
        """
        exact = self.model.exact_where_valid([self.trajectory.t[-1]])
        if exact is None or (self.exact_valid_until_each() < self.trajectory.t[-1]).all():
            return None
        return exact[0][0], exact[1][0]

    def exact_notes(self) -> list[Optional[str]]:
        """For each mass, why it has no exact value at the final time though a closed form exists,
        or None (it has one, or there is no closed form at all)."""
        if self.model.exact is None:
            return [None] * len(self.trajectory.m)
        return [None if t_break >= self.trajectory.t[-1] else
                f"the closed form stops holding at t = {number(t_break, 4)} s, {self.model.exact_limit}"
                for t_break in self.exact_valid_until_each()]

    def exact_note(self) -> Optional[str]:
        """Why a scene with a closed form gives no exact value at the final time, or None.

        For several masses: how many of them have none, and from when (exact_notes, mass by mass).
        """
        notes = self.exact_notes()
        stopped = [note for note in notes if note]
        if not stopped:
            return None
        if len(notes) == 1:
            return stopped[0]
        return (f"the closed form stops holding for {len(stopped)} of {len(notes)} masses, the first at "
                f"t = {number(self.exact_valid_until(), 4)} s, {self.model.exact_limit}")


# ---- the plan: checked once, before any step ----

@dataclass(frozen=True)
class Plan:
    """A headless run checked before it starts: the configured scene (with the `until` that is run),
    its model, the engine at its start, the time to run to, what to record (None: the end only),
    what the run times its period by and the watch that shows it the steps, and the scene's
    measure over its window (None where it has none)."""

    setup: Setup
    model: Model
    engine: Simulation
    until: float
    record: object
    timing: Timing
    watches: tuple
    measured: Optional[WindowLargest] = None


def plan(setup: Setup, *, model: Optional[Model] = None, integrator: Optional[str] = None,
         until: Optional[float] = None, every_step: bool = True) -> Plan:
    """Check a run of `setup` to `until` (default: its question time) once, before any step.

    every_step  record every step (for --csv and --plot); else only the end. Either way the run
                looks at the motion as it goes, without keeping it: often enough to time its
                period (physics/period.py's record_window, reports/periods.py's timing), and at
                every step of the window a scene measures in (resonance: the largest amplitude
                of each spring, the scene's measure_now; physics/recording.py's WindowLargest)
    Raises TooManySteps if the run would take longer than MAX_RUN_SECONDS on this computer (the
    engine's own measured cost, plus ROW_SECONDS for each row recorded), naming the count and the
    longest --until that fits. (That the run reaches the end of the scene's measuring window is
    checked by simulate, as it starts.)
    """
    model = model if model is not None else setup.build()
    engine = model.simulation(integrator)
    until = model.until if until is None else until
    if "until" in setup.values and setup.values["until"] != until:  # report the until that was run
        setup = setup.with_values(until=float(until))
    window = setup.hooks.measuring(setup.values)
    try:
        check_cost(engine, until=until, extra_per_step=(model.state.count if every_step else 0) * ROW_SECONDS,
                   shortest=0.0 if window is None else window[1])
    except RunTooLong as problem:
        raise TooManySteps(problem.worded("--until")) from None
    # the motion, often enough to time its crossings of the centre (the period, reports/periods.py),
    # and the scene's measure over its window: looked at as the run goes, not kept (every step of
    # 10⁴ masses would be 640 kB a step)
    period = record_window(model.forces, model.state.m, model.dt, t0=model.state.t, until=until)
    timed = None if period is None else time_grid(period[0], t0=model.state.t, dt=model.dt, start=period[1])
    if every_step:           # every step is kept, and so shown to the watches already
        record, timed = every(1), None
    else:
        record = None
    measure = setup.hooks.measure_now
    largest = None if window is None or measure is None else WindowLargest(
        lambda state: measure(model, state), window=window, initial=model.state, dt=model.dt, ask=not every_step)
    timed_by = timing(setup, model)
    watches = (CoordinateWatch(timed_by.meter, axis=timed_by.axis, schedule=timed),) + \
        (() if largest is None else (largest,))
    return Plan(setup=setup, model=model, engine=engine, until=until, record=record, timing=timed_by,
                watches=watches, measured=largest)


def _check_window(run: Plan) -> None:
    """ConstantError if the run ends before the scene's measuring window does (resonance)."""
    window = run.setup.hooks.measuring(run.setup.values)
    if window is not None and window[1] > run.until:
        raise ConstantError(
            f"the scene measures from t = {number(window[0])} s to {number(window[1])} s (settle, then "
            f"{number(run.setup.values['periods'])} periods of the slowest drive), after the run ends at "
            f"t = {number(run.until)} s; set until to at least {number(window[1])} s, or a smaller settle")


# ---- the run ----

def simulate(setup: Setup, *, model: Optional[Model] = None, integrator: Optional[str] = None,
             until: Optional[float] = None, every_step: bool = True, progress="stderr",
             checked: Optional[Plan] = None) -> Result:
    """Run a configured scene (scenes.Setup) from its start to `until` (default: its question time).

    `checked` is the run's :func:`plan`, if the caller made it already (then the other arguments
    but `progress` are its own); else it is made here, with the same checks. Runs that take more
    than a second or so write their progress to the stream `progress` (standard error by default;
    None: silently). Raises ConstantError if the run ends before the scene's measuring window,
    and physics.simulate.BlowUpError when Δt is too large for the method.
    """
    run = checked if checked is not None else plan(setup, model=model, integrator=integrator, until=until,
                                                   every_step=every_step)
    _check_window(run)
    stream = sys.stderr if progress == "stderr" else progress     # looked up now, not at import
    printer = None if stream is None else _ProgressLine(stream)
    try:
        samples = run.engine.run_until(run.until, record=run.record, progress=printer, watches=run.watches)
    finally:   # on a terminal the line is redrawn in place: end it, so what follows starts a line
        if printer is not None:
            printer.end()
    return Result(setup=run.setup, model=run.model, methods=tuple(run.engine.methods),
                  trajectory=trajectory(run.engine, samples), steps=run.engine.steps, timing=run.timing,
                  measured=run.measured)


class _ProgressLine:
    """progress(done, total, t) for the engine: a line on `stream` (one line, redrawn, on a terminal);
    end() finishes a redrawn line, whether the run ended, failed or was interrupted."""

    def __init__(self, stream: TextIO):
        self.stream, self.open = stream, False
        self.tty = hasattr(stream, "isatty") and stream.isatty()

    def __call__(self, done: int, total: int, t: float) -> None:
        line = f"running: {done:,} of {total:,} steps ({100 * done // total} %), t = {number(t)} s"
        self.open = self.tty   # before the line: a Ctrl-C just after it is written must still end it
        print(("\r" + line) if self.tty else line, end="" if self.tty else "\n", file=self.stream, flush=True)

    def end(self) -> None:
        if self.open:
            self.open = False
            print(file=self.stream, flush=True)


def stop_note(model: Model, *, until: float) -> Optional[str]:
    """A note when `until` is not a whole number of steps: the run goes on to the next multiple of Δt."""
    dt, start = model.dt, model.state.t
    n = steps_to_reach(until - start, dt)
    stop = start + n * dt
    if math.isclose(stop, until, rel_tol=1e-9, abs_tol=1e-12 * dt):
        return None
    return (f"note: until = {number(until)} s is not a multiple of dt = {number(dt)} s; "
            f"the run stopped at {n}·dt = {number(stop)} s")


def stability_warning(model: Model, methods) -> Optional[str]:
    """Judge Δt once before a run (physics.accuracy.judge_dt, stability and accuracy at once):
    None if the motion will neither grow nor stray far from the real one.

    Past a method's stability limit (a smaller Δt would be stable) the run would only print
    nonsense, so this raises BlowUpError with the reason, and the command line exits with status
    1. A method that grows at every Δt (euler on an undamped spring) gets a warning and runs: that
    growth is what the page shows it for. Only where the motion really grows: euler on a spring
    damped strongly enough decays, and gets no such warning. A stable Δt that is inaccurate gets
    the accuracy verdict's one line, naming a Δt that would do. The masses a scene expects to run
    away (euler beside the other methods) are left out of that judgement and judged on their own,
    for their warning.
    """
    methods = tuple(methods)
    judgement = judge_dt(model.state, model.forces, methods, model.dt, ignore=model.may_run_away)
    verdicts = [judgement.stability]
    if model.may_run_away:
        others = [i for i in range(model.state.count) if i not in set(model.may_run_away)]
        verdicts.append(judge(model.forces, model.state.m, methods, model.dt, v=model.state.v, ignore=others))
    for verdict in verdicts:
        if verdict.past_limit:
            raise BlowUpError(f"{REFUSED}: {verdict.message}")
        if verdict.at_limit:   # exactly at the limit: it runs, and the sentence says what it does
            return f"warning: {verdict.message}"
        if not verdict.stable:
            return f"warning: expect the motion to grow: {verdict.message}"
    return f"warning: {judgement.advice}" if judgement.advice else None

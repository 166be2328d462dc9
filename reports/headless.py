"""Running a scene without a browser, and writing down what it found.

A headless run is the page's loop and nothing else: build the scene's model from its constants,
repeat the momentum update every Δt until the question time, and report the final state

    t = 0.2 s
    r = < 0, -1.73088, 0 > m
    p = < 0, -15.288, 0 > kg·m/s

in Matter & Interactions vector notation, with the energy and, where a closed form exists, the
exact answer and the error of the iteration. The same run can be written as one JSON object, as a
CSV file with one row per step, or as a step table: the first few iterations, each showing

    F_net,  p_f = p_i + F_net Δt,  v_f = p_f / m,  r_f = r_i + v_f Δt

which is exactly the arithmetic a student does by hand. Nothing here imports vpython or matplotlib.
"""
from __future__ import annotations

import csv
import json
import math
import sys
from dataclasses import dataclass

import numpy as np

from physics.accuracy import judge_dt
from physics.forces import net_force
from physics.integrators import INTEGRATORS, describe
from physics.simulate import BlowUpError, RunTooLong, check_cost, every, steps_to_reach, time_grid, trajectory
from physics.stability import judge
from physics.state import velocity
from export.files import STDOUT, atomic_file
from export.csv_rows import ROWS_PER_BLOCK, csv_field, format_numbers
from export.numbers import CSV_HEADER, ENERGY_KEYS, clean_time, time_decimals
from export.step_update import NO_VALUE, SIGNIFICANT, number, update_force, vector  # noqa: F401 (used by tests)
from export.step_update import cleaned as _cleaned
from scenes import ConstantError

UNITS = {"t": "s", "dt": "s", "r": "m", "v": "m/s", "p": "kg·m/s", "F_net": "N", "energy": "J",
         "exact_valid_until": "s"}


# A run is refused before it starts if the engine estimates it longer than MAX_RUN_SECONDS
# (physics.simulate.check_cost); each row of a CSV file or figure adds ROW_SECONDS to that.
ROW_SECONDS = 25e-6           # s per row: csv.writer measured 24.6 s for 1,000,001 rows here
MAX_TABLE_ROWS = 10_000        # rows of the step table (steps × masses)


class TooManySteps(ConstantError):
    """until / dt asks for more steps than a headless run takes: a one-line message with the count."""


# ---- numbers and vectors as a student writes them ----

# ---- the run ----

@dataclass(frozen=True)
class Result:
    """A finished headless run: the scene's setup and model, the method used, the steps taken and
    the recorded ones (every step, or the start and the end)."""

    setup: object
    model: object
    methods: tuple      # the method of each mass (physics.integrators.methods_for)
    trajectory: object  # physics.simulate.Trajectory
    steps: int

    @property
    def integrator(self) -> str:
        """The method in words: 'rk4', or one name per mass ('euler, euler-cromer, ...')."""
        return describe(self.methods)

    @property
    def labels(self) -> tuple:
        return tuple(self.model.labels)

    def exact_valid_until(self) -> float:
        """When the closed form stops holding (for a row, the first mass's), s: math.inf if it
        holds up to the final time."""
        return float(np.min(self.exact_valid_until_each()))

    def exact_valid_until_each(self) -> np.ndarray:
        """When each mass's closed form stops holding, (N,) s: math.inf where it holds to the end."""
        return self.model.exact_valid_until_each(float(self.trajectory.t[-1]))

    def exact(self):
        """(r, v) of the closed form at the final time, shape (N, 3) each, or None where unknown.

        A mass whose closed form stopped holding before the final time gets NaN ("not known"),
        as one with no closed form does (exact_notes says why); None if every mass's stopped.
        """
        exact = self.model.exact_where_valid([self.trajectory.t[-1]])
        if exact is None or (self.exact_valid_until_each() < self.trajectory.t[-1]).all():
            return None
        return exact[0][0], exact[1][0]

    def exact_notes(self) -> list:
        """For each mass, why it has no exact value at the final time though a closed form exists,
        or None (it has one, or there is no closed form at all)."""
        if self.model.exact is None:
            return [None] * len(self.trajectory.m)
        return [None if t_break >= self.trajectory.t[-1] else
                f"the closed form stops holding at t = {number(t_break, 4)} s, {self.model.exact_limit}"
                for t_break in self.exact_valid_until_each()]

    def exact_note(self) -> str | None:
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


def shortest_until(setup) -> float:
    """The least `until` the scene accepts, s: the end of its measuring window (resonance), else 0."""
    window = getattr(setup.module, "measure_window", None)
    return float(window(setup.values)[1]) if window is not None else 0.0


def step_count(engine, *, until: float, rows_per_step: float = 0.0, shortest: float = 0.0) -> int:
    """How many steps of Δt the engine (physics.simulate.Simulation) takes to `until`, if it fits in time.

    Raises TooManySteps, before any step is taken, when the run would take longer than
    MAX_RUN_SECONDS on this computer (the engine's own measured cost, plus ROW_SECONDS for each
    row written), naming the count and the longest --until that fits. The engine measures its
    cost once, so asking again for the same engine costs nothing.
    """
    try:
        return check_cost(engine, until=until, extra_per_step=rows_per_step * ROW_SECONDS, shortest=shortest)
    except RunTooLong as problem:
        raise TooManySteps(problem.worded("--until")) from None


def simulate(setup, *, model=None, integrator: str | None = None, until: float | None = None,
             every_step: bool = True, progress="stderr", engine=None) -> Result:
    """Run a configured scene (scenes._catalog.Setup) from its start to `until` (default: its question time).

    every_step  record every step (for --csv and --plot); else only the end, and the window a
                scene measures in (resonance: the steady-state amplitudes)
    Runs that take more than a second or so write their progress to the stream `progress`
    (standard error by default; None: silently). Raises TooManySteps past MAX_RUN_SECONDS, before any step is taken, and
    physics.simulate.BlowUpError when Δt is too large for the method. `engine` is the model's
    engine at its start, if the caller already made one (and checked its cost with step_count).
    """
    model = model if model is not None else setup.build()
    engine = engine if engine is not None else model.simulation(integrator)
    until = model.until if until is None else until
    if "until" in setup.values and setup.values["until"] != until:  # report the until that was run
        setup = setup.with_values(until=float(until))
    step_count(engine, until=until, rows_per_step=model.state.count if every_step else 0,
               shortest=shortest_until(setup))
    window = getattr(setup.module, "measure_window", None)
    if window is not None and window(setup.values)[1] > until:
        start, end = window(setup.values)
        raise ConstantError(
            f"the scene measures from t = {number(start)} s to {number(end)} s (settle, then "
            f"{number(setup.values['periods'])} periods of the slowest drive), after the run ends at "
            f"t = {number(until)} s; set until to at least {number(end)} s, or a smaller settle")
    if every_step:
        record = every(1)
    else:
        record = None if window is None else time_grid(
            model.dt, t0=model.state.t, dt=model.dt, **dict(zip(("start", "end"), window(setup.values))))
    stream = sys.stderr if progress == "stderr" else progress     # looked up now, not at import
    printer = _progress_printer(stream)
    try:
        samples = engine.run_until(until, record=record, progress=printer)
    finally:   # on a terminal the line is redrawn in place: end it, so what follows starts a line
        if printer is not None:
            printer.end()
    return Result(setup=setup, model=model, methods=engine.methods,
                  trajectory=trajectory(engine, samples), steps=engine.steps)


class _ProgressLine:
    """progress(done, total, t) for the engine: a line on `stream` (one line, redrawn, on a terminal);
    end() finishes a redrawn line, whether the run ended, failed or was interrupted."""

    def __init__(self, stream):
        self.stream, self.open = stream, False
        self.tty = hasattr(stream, "isatty") and stream.isatty()

    def __call__(self, done, total, t):
        line = f"running: {done:,} of {total:,} steps ({100 * done // total} %), t = {number(t)} s"
        print(("\r" + line) if self.tty else line, end="" if self.tty else "\n", file=self.stream, flush=True)
        self.open = self.tty

    def end(self):
        if self.open:
            self.open = False
            print(file=self.stream, flush=True)


def _progress_printer(stream):
    return None if stream is None else _ProgressLine(stream)


def stop_note(model, *, until: float) -> str | None:
    """A note when `until` is not a whole number of steps: the run goes on to the next multiple of Δt."""
    dt, start = model.dt, model.state.t
    n = steps_to_reach(until - start, dt)
    stop = start + n * dt
    if math.isclose(stop, until, rel_tol=1e-9, abs_tol=1e-12 * dt):
        return None
    return (f"note: until = {number(until)} s is not a multiple of dt = {number(dt)} s; "
            f"the run stopped at {n}·dt = {number(stop)} s")


def stability_warning(model, methods) -> str | None:
    """Judge Δt before a run (physics.accuracy.judge_dt, stability and accuracy at once): None if
    the motion will neither grow nor stray far from the real one.

    Past a method's stability limit (a smaller Δt would be stable) the run would only print
    nonsense, so this raises BlowUpError with the reason, and the command line exits with status
    1. A method that grows at every Δt (euler on an undamped spring) gets a warning and runs: that
    growth is what the page shows it for. Only where the motion really grows: euler on a spring
    damped strongly enough decays, and gets no such warning. A stable Δt that is inaccurate gets
    the accuracy verdict's one line, naming a Δt that would do.
    """
    judgement = judge_dt(model.state, model.forces, methods, model.dt, ignore=model.may_run_away)
    for verdict in (judgement.stability,
                    judge(model.forces, model.state.m, methods, model.dt, v=model.state.v)):
        if verdict.past_limit:
            raise BlowUpError(f"the run would blow up, past the stability limit: {verdict.message}")
        if not verdict.stable:
            return f"warning: expect the motion to grow: {verdict.message}"
    return f"warning: {judgement.advice}" if judgement.advice else None


def with_warning(out: dict, warning: str | None) -> dict:
    """The JSON `out` with the run's warning (stability_warning) added to its "notes" list."""
    if warning:
        out.setdefault("notes", []).append(warning.removeprefix("warning: "))
    return out


def plural(count: int, noun: str) -> str:
    return f"{count} {noun}{'' if count == 1 else 's'}"


def integrator_json(methods):
    """The JSON key "integrator": one name when every mass uses it, else the list of names per mass."""
    return methods[0] if len(set(methods)) == 1 else list(methods)


def method_name(integrator) -> str:
    """The JSON "integrator" (a name or a list of names) in words."""
    return describe([integrator] if isinstance(integrator, str) else integrator)


# ---- text ----

def final_report(result: Result) -> str:
    """The final time and state in M&I vector notation, energy, and the exact answer where known."""
    traj, model = result.trajectory, result.model
    t, r, p, m = traj.t[-1], traj.r[-1], traj.p[-1], traj.m
    v = velocity(p, m)
    F_net = net_force(model.forces, t, r, v, m)
    exact, notes = result.exact(), result.exact_notes()
    lines = [f"{result.setup.name}: {plural(result.steps, 'step')} of dt = {number(model.dt)} s "
             f"with {result.integrator}",
             f"t = {number(t)} s"]
    single = len(m) == 1
    for i, label in enumerate(result.labels):
        indent = "" if single else "  "
        if not single:
            lines.append(f"{label}, m = {number(m[i])} kg:")
        lines += [f"{indent}r = {vector(r[i], 'm')}",
                  f"{indent}v = {vector(v[i], 'm/s')}",
                  f"{indent}p = {vector(p[i], 'kg·m/s')}",
                  f"{indent}F_net = {vector(F_net[i], 'N')} (at t = {number(t)} s)"]
        if exact is not None and np.all(np.isfinite(exact[0][i])):
            r_exact, v_exact = exact[0][i], exact[1][i]
            lines += [f"{indent}exact: r = {vector(r_exact, 'm')}, v = {vector(v_exact, 'm/s')}",
                      f"{indent}error: |r − r_exact| = {number(np.linalg.norm(r[i] - r_exact), 4)} m, "
                      f"|v − v_exact| = {number(np.linalg.norm(v[i] - v_exact), 4)} m/s"]
        elif notes[i] and not single:
            lines.append(f"{indent}exact: none at t = {number(t)} s: {notes[i]}")
    if single and result.exact_note():
        lines.append(f"exact: none at t = {number(t)} s: {result.exact_note()}")
    if traj.energy is not None:
        e = {key: values[-1] for key, values in traj.energy.items()}
        lines.append(f"energy: K = {number(e['K'])} J, U = {number(e['U'])} J, E = {number(e['E'])} J, "
                     f"W_nc = {number(e['W_nc'])} J, E − W_nc = {number(e['E_minus_W_nc'])} J "
                     f"({number(traj.energy['E_minus_W_nc'][0])} J at the start)")
    extra = getattr(result.setup.module, "extra_text", None)  # a scene's own results: resonance's curves
    if extra is not None:
        lines.append(extra(result))
    return "\n".join(lines)


def constants_report(setup) -> str:
    """Each constant of a configured scene: `k = 40 N/m   spring constant (stiffness)`."""
    from scenes import format_value

    rows = [(f"{name} = {format_value(setup.values[name], constant.unit)}", constant.meaning)
            for name, constant in setup.constants.items()]
    width = max(len(left) for left, _ in rows)
    lines = [f"{left:<{width}}   {meaning}" for left, meaning in rows]
    m, k, dt = (setup.values.get(name) for name in ("m", "k", "dt"))
    if all(isinstance(x, (int, float)) for x in (m, k)) and k > 0:   # worked out from the values in use
        omega0 = math.sqrt(k / m)
        lines.append(f"so: ω0 = √(k/m) = {number(omega0, 4)} rad/s, T = 2π/ω0 = {number(2 * math.pi / omega0, 4)} s"
                     + (f", ω0·dt = {number(omega0 * dt, 4)}" if isinstance(dt, (int, float)) else ""))
    return "\n".join(lines)


# ---- JSON ----

def _plain(value):
    """A constant's value as JSON: numbers, lists for vectors, None for derived ones."""
    if isinstance(value, (tuple, list, np.ndarray)):
        return [float(x) for x in value]
    if isinstance(value, (int, float, np.floating)):
        return float(value)
    return value


def as_json(result: Result) -> dict:
    """One JSON-ready dict: t, steps, dt, integrator, r, p, v (single mass: 3 numbers each), and more.

    Multi-mass scenes give r, p, v as one 3-vector per mass and add "bodies". "exact" holds the
    closed form at the final time and the size of the error, where a closed form exists. Where
    it stopped holding before the final time, "exact" is left out and "exact_note" says why, with
    "exact_valid_until" the time it stopped holding, s (null, with a line in "notes", where it
    holds to the end or there is no closed form). F_net is the net force at the final time. In a row each mass is judged on its own:
    a body whose closed form stopped holding has no "exact" but its own "exact_note" and
    "exact_valid_until", and the top-level ones count such masses and give the first time. A scene
    module may add its own keys with a function extra_json(result) -> dict.
    """
    traj, model, setup = result.trajectory, result.model, result.setup
    r, p, m = traj.r[-1], traj.p[-1], traj.m
    v = velocity(p, m)
    single = len(m) == 1
    pick = (lambda a: a[0].tolist()) if single else (lambda a: a.tolist())
    F_net = net_force(model.forces, traj.t[-1], r, v, m)   # at the final time, as --headless prints it
    out = {
        "scene": setup.name,
        "t": float(traj.t[-1]),
        "steps": result.steps,
        "dt": float(model.dt),
        "integrator": integrator_json(result.methods),
        "r": pick(r), "p": pick(p), "v": pick(v), "F_net": pick(F_net),
    }
    exact = result.exact()
    known = [exact is not None and bool(np.all(np.isfinite(exact[0][i]))) for i in range(len(m))]
    if single and known[0]:
        out["exact"] = _exact_entry(r[0], v[0], exact[0][0], exact[1][0])
    if result.exact_note():  # a closed form exists, but stopped holding before the final time
        out["exact_note"] = result.exact_note()
        out["exact_valid_until"] = result.exact_valid_until()
    else:  # every key of "units" is present: null, with a note saying why
        out["exact_valid_until"] = None
        out.setdefault("notes", []).append(
            "exact_valid_until: null, " + ("the closed form holds up to the final time" if model.exact is not None
                                           else "this scene has no closed form"))
    if not single:
        notes, valid_until = result.exact_notes(), result.exact_valid_until_each()
        out["bodies"] = [
            {"label": label, "m": float(m[i]), "r": r[i].tolist(), "p": p[i].tolist(), "v": v[i].tolist(),
             "F_net": F_net[i].tolist(),
             **({"exact": _exact_entry(r[i], v[i], exact[0][i], exact[1][i])} if known[i] else {}),
             **({"exact_note": notes[i], "exact_valid_until": float(valid_until[i])} if notes[i] else {})}
            for i, label in enumerate(result.labels)]
    if traj.energy is not None:
        out["energy"] = {key: float(values[-1]) for key, values in traj.energy.items()}
    out["constants"] = {name: {"value": _plain(setup.values[name]), "unit": c.unit, "meaning": c.meaning}
                        for name, c in setup.constants.items()}
    out["units"] = UNITS
    extra = getattr(setup.module, "extra_json", None)  # a scene's own results, e.g. a resonance curve
    if extra is not None:
        out.update(extra(result))
    out = _cleaned(out)
    out["t"] = clean_time(traj.t[-1], model.dt)
    return out


def to_json(out: dict) -> str:
    """`out` as strict JSON (no NaN or Infinity, which strict parsers reject).

    A number with no finite value (an overflow, an undefined quantity) becomes null, and a
    "notes" list names each such place and why, so no reader mistakes it for an answer.
    """
    places = []

    def finite(value, place):
        if isinstance(value, dict):
            return {key: finite(item, f"{place}.{key}" if place else key) for key, item in value.items()}
        if isinstance(value, (list, tuple)):
            return [finite(item, f"{place}[{n}]") for n, item in enumerate(value)]
        if isinstance(value, float) and not math.isfinite(value):
            places.append(place)
            return None
        return value

    clean = finite(out, "")
    if places:
        clean.setdefault("notes", []).extend(
            f"{place}: null, no finite value (it overflowed or is undefined at this time)" for place in places)
    return json.dumps(clean, ensure_ascii=False, allow_nan=False)


def _exact_entry(r, v, r_exact, v_exact) -> dict:
    return {"r": r_exact.tolist(), "v": v_exact.tolist(),
            "error": {"r": float(np.linalg.norm(r - r_exact)), "v": float(np.linalg.norm(v - v_exact))}}


# ---- CSV ----

def write_csv(result: Result, path: str) -> int:
    """One row per step (per mass): t, r, v, p, then the system's K, U, E, W_nc in J; returns rows written.

    Multi-mass scenes add a `body` column with each mass's label; the energy columns are totals.
    path "-" writes to standard output. A file that cannot be written raises OutputError; the
    rows go to a temporary file that replaces `path` only when complete (see atomic_file).
    """
    if path == STDOUT:
        return _write_rows(result, sys.stdout)
    with atomic_file(path, what="CSV file") as temporary:
        with open(temporary, "w", newline="", encoding="utf-8") as handle:
            return _write_rows(result, handle)


def _write_rows(result: Result, handle) -> int:
    traj = result.trajectory
    v = traj.v
    single = len(traj.m) == 1
    header = CSV_HEADER + ([] if single else ["body"])
    csv.writer(handle).writerow(header)
    # The rows a block of steps at a time (export/csv_rows.py): the same text as csv.writer
    # writing clean_time(t, Δt), then clean() of r, v, p and the energies, for each row.
    decimals = time_decimals(result.model.dt)
    count = len(traj.m)
    after = [("" if traj.energy else ",,,,") + ("" if single else "," + csv_field(label)) + "\r\n"
             for label in result.labels]
    columns = 10 + (len(ENERGY_KEYS) if traj.energy else 0)
    block = max(1, ROWS_PER_BLOCK // count)
    for start in range(0, len(traj.t), block):
        steps = slice(start, start + block)
        t = np.array([round(t, decimals) for t in traj.t[steps].tolist()])
        values = np.empty((len(t), count, columns))
        values[:, :, 0] = t[:, None]
        values[:, :, 1:4], values[:, :, 4:7], values[:, :, 7:10] = traj.r[steps], v[steps], traj.p[steps]
        for j, key in enumerate(ENERGY_KEYS if traj.energy else ()):
            values[:, :, 10 + j] = traj.energy[key][steps][:, None]
        handle.write(format_numbers(values.reshape(-1, columns), after=after))
    return len(traj.t) * count


# ---- the step table ----

def step_table(setup, *, model=None, integrator: str | None = None, steps: int) -> dict:
    """The first `steps` iterations: for each step and mass, t_f, F_net, p_f, v_f and r_f.

    F_net is the force the method used for its momentum update, so p_f = p_i + F_net Δt holds on
    every row: for euler-cromer (the page) and euler it is F(t_i, r_i, v_i), for the other methods
    the average force (p_f − p_i)/Δt of the step.
    """
    model = model if model is not None else setup.build()
    rows_asked = steps * model.state.count
    if rows_asked > MAX_TABLE_ROWS:
        rows = f" of {model.state.count} masses, {rows_asked:,} rows," if model.state.count > 1 else ""
        raise TooManySteps(
            f"--steps {steps:,}{rows} is more than the {MAX_TABLE_ROWS:,} rows the step table shows "
            f"(it is for checking by hand); use --headless --csv FILE for every step of a long run")
    engine = model.simulation(integrator)
    dt = model.dt
    traj = trajectory(engine, engine.advance(steps, record=every(1)), with_energy=False)
    v = traj.v
    rows = []
    for n in range(1, len(traj.t)):
        F_net = update_force(model.forces, engine.methods, t_i=traj.t[n - 1], r_i=traj.r[n - 1],
                             p_i=traj.p[n - 1], p_f=traj.p[n], m=traj.m, dt=dt)
        for i, label in enumerate(model.labels):
            rows.append({"step": n, "body": label, "t": clean_time(traj.t[n], dt), "F_net": _cleaned(F_net[i].tolist()),
                         "p_f": _cleaned(traj.p[n, i].tolist()), "v_f": _cleaned(v[n, i].tolist()),
                         "r_f": _cleaned(traj.r[n, i].tolist())})
    uniform = len(set(engine.methods)) == 1
    return {"scene": setup.name, "integrator": integrator_json(engine.methods),
            "dt": float(dt), "m": _cleaned(traj.m.tolist()),
            "start": {"t": clean_time(traj.t[0], dt), "r": _cleaned(traj.r[0].tolist()),
                      "p": _cleaned(traj.p[0].tolist()), "v": _cleaned(v[0].tolist())},
            "units": {"t": "s", "F_net": "N", "p_f": "kg·m/s", "v_f": "m/s", "r_f": "m"},
            "rule": (INTEGRATORS[engine.methods[0]].rule if uniform else
                     "F_net = (p_f − p_i)/Δt, the average force each mass's method used"),
            "rows": rows}


def format_step_table(table: dict) -> str:
    """The step table as aligned text with units in the header, vectors in < > notation."""
    labels = list(dict.fromkeys(row["body"] for row in table["rows"]))
    multi = len(labels) > 1
    lines = [f"{table['scene']}: first {plural(len({row['step'] for row in table['rows']}), 'step')} of "
             f"Δt = {number(table['dt'])} s with {method_name(table['integrator'])}",
             "each step: " + table["rule"],
             "t is the time at the end of the step, when p_f, v_f and r_f hold"]
    start = table["start"]
    for i, label in enumerate(labels or ["mass"]):
        name = f", {label}" if multi else ""
        lines.append(f"start{name}, m = {number(table['m'][i])} kg: t = {number(start['t'])} s, "
                     f"r = {vector(start['r'][i], 'm')}, p = {vector(start['p'][i], 'kg·m/s')}, "
                     f"v = {vector(start['v'][i], 'm/s')}")
    header = ["step"] + (["body"] if multi else []) + \
        [f"{key} ({unit})" for key, unit in table["units"].items()]
    body = [[str(row["step"])] + ([row["body"]] if multi else []) + [number(row["t"])] +
            [vector(row[key]) for key in ("F_net", "p_f", "v_f", "r_f")] for row in table["rows"]]
    widths = [max(len(line[c]) for line in [header] + body) for c in range(len(header))]
    for line in [header] + body:
        lines.append("  ".join(cell.ljust(width) for cell, width in zip(line, widths)).rstrip())
    return "\n".join(lines)

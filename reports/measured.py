"""The command line's reports on measured data: --data (with --fit, --plot, --json), --mystery and
--show-answer. The reading, comparing and fitting are in lab/; this module says what came out.
"""
from __future__ import annotations

import os
import secrets
import shlex
import sys

import numpy as np

from export.files import OutputError, check_writable, write_text
from export.lines import one_line
from export.numbers import clean
from lab import compare, mystery, readers
from export.palette import BLUE as DATA_COLOUR, VERMILION as MODEL_COLOUR
from reports import plotting
from reports.json_report import to_json


def measured_value(estimate) -> str:
    """`54.997 ± 0.003 N/m` (lab/compare.py's Estimate says itself so, on the page too)."""
    return str(estimate)


UNTRUSTED = 3       # exit status of a fit whose numbers cannot be trusted (its first line says why)


def _given(args) -> set:
    return {assignment.partition("=")[0].strip() for assignment in args.assignments}


class _FitProgress:
    """progress(line) for a fit that takes more than a second: a line on standard error (redrawn in
    place on a terminal), ended by end()."""

    def __init__(self, stream=None):
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.open = False

    def __call__(self, line: str) -> None:
        self.open = self.tty
        print(("\r" + line) if self.tty else line, end="" if self.tty else "\n", file=self.stream, flush=True)

    def end(self) -> None:
        if self.open:
            self.open = False
            print(file=self.stream, flush=True)


def run_data(args, setup) -> int:
    """--data FILE: read it, compare (and fit), then print text or JSON and draw --plot. Exit status
    3 where the fit's numbers cannot be trusted (the first line says why)."""
    coordinate = compare.coordinate_of(setup, args.coordinate)
    measured = readers.read(args.data, column=args.data_column, run=args.run, coordinate=coordinate)
    if args.plot is not None:
        check_writable(args.plot, what="figure", overwrite=args.overwrite)
        from reports import plotting

        plotting.check_format(args.plot)
    names = args.fit.split(",") if args.fit else ()
    given = _given(args)
    progress = _FitProgress()
    try:
        result = compare.compare(setup, measured.t, measured.position, integrator=args.integrator,
                                 coordinate=coordinate, fit=names, sign=args.data_sign,
                                 choose=args.integrator is None and "dt" not in given, given=given,
                                 own_step=measured.own_step, lines=measured.lines, progress=progress)
    finally:
        progress.end()
    misfit = [f"note: {result.misfit}"] if result.misfit and result.trust is None else []
    for note in result.notes + misfit:
        print(one_line(note), file=sys.stderr)
    if args.plot is not None:
        plot(result, measured, args.plot)
    if args.json:
        print(to_json(as_json(result, measured)))
    else:
        print(text(result, measured))
    return UNTRUSTED if result.trust is not None and not result.trust.trusted else 0


def text(result, measured) -> str:
    """One line each: the file and what was read, every fitted value, the offsets, the RMS residual,
    and which way the data's axis was taken; first of all, for a fit that cannot be trusted, why."""
    lines = [one_line(f"data: {measured.path}: {measured.choice}")]
    if result.trust is not None and not result.trust.trusted:
        lines.insert(0, result.trust.sentence)
    for name, estimate in result.fitted.items():
        where = (f"  (where the mass was let go, along {result.coordinate}; --set r0 gives it instead)"
                 if name == compare.RELEASE and result.release_fitted else "")
        lines.append(f"{name} = {measured_value(estimate)}{where}")
    lines.append(f"t_offset = {measured_value(result.t_offset)}  (the data's clock at the model's t = 0)")
    lines.append(f"position_offset = {measured_value(result.position_offset)}  (the data's reading "
                 f"where the model's {result.coordinate} = 0)")
    lines.append(f"RMS residual = {result.rms:.3g} m ({result.rms * 1000:.3g} mm) over "
                 f"{result.points} points")
    lines.append(f"data_sign = {result.sign:+d}  ({result.sign_said})")     # last: the lines above keep their places
    return "\n".join(lines)


def _entry(estimate) -> dict:
    return {"value": clean(estimate.value), "uncertainty": clean(estimate.uncertainty), "unit": estimate.unit}


def as_json(result, measured) -> dict:
    """The comparison as one JSON object. Keys kept from the first version: scene, data, data_read,
    coordinate, data_sign, dt, integrator, fit, rms_residual, rms_residual_unit, data_points; added:
    trusted (null without --fit) and trust_reason, model_chosen_by, dt_halved_moves (each fitted
    constant's move at Δt/2, in its unit), engine_runs, release_fitted, data_sign_known, left_out
    (the file's lines left out as drop-outs)."""
    fit = {name: _entry(estimate) for name, estimate in result.fitted.items()}
    fit["t_offset"] = _entry(result.t_offset)
    fit["position_offset"] = _entry(result.position_offset)
    model = result.setup
    trust = result.trust
    lines = measured.lines if measured.lines is not None else np.arange(1, len(measured.t) + 1)
    return {"scene": model.name, "data": measured.path, "data_read": measured.choice,
            "coordinate": result.coordinate, "data_sign": result.sign, "dt": model.values.get("dt"),
            "integrator": model.build().methods(result.integrator)[0], "fit": fit,
            "rms_residual": clean(result.rms), "rms_residual_unit": "m", "data_points": result.points,
            "trusted": None if trust is None else trust.trusted,
            "trust_reason": None if trust is None or trust.trusted else trust.sentence,
            "model_chosen_by": result.settings.chosen_by if result.settings else "user",
            "dt_halved_moves": {name: clean(move) for name, move in result.moves.items()},
            "engine_runs": result.runs, "release_fitted": result.release_fitted,
            "data_sign_known": not result.sign_open,
            "left_out": [int(lines[i]) for i in result.left_out]}


def plot(result, measured, path: str) -> None:
    """The measured points, the model's curve through them, and the residuals below, to `path`."""
    from reports.plotting import _pyplot

    plt = _pyplot()
    t_offset, offset = result.t_offset.value, result.position_offset.value
    smooth = np.linspace(result.t[0], result.t[-1], max(2000, 4 * result.points))
    run = compare.ModelRun(result.setup, integrator=result.integrator, axis=compare.AXES[result.coordinate],
                           until=float(smooth[-1] - t_offset) + 1.0)
    curve = result.sign * run.at(smooth - t_offset)[0] + offset
    fig, (ax, ax_res) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, height_ratios=(3, 1))
    ax.plot(result.t, result.data, "o", ms=3, color=DATA_COLOUR, label=f"measured ({os.path.basename(measured.path)})")
    ax.plot(smooth, curve, "-", lw=1.5, color=MODEL_COLOUR, label="model")
    fitted = ", ".join(f"{n} = {e.value:.4g} {e.unit}" for n, e in result.fitted.items())
    untrusted = ("\nthese numbers cannot be trusted (the report says why)"
                 if result.trust is not None and not result.trust.trusted else "")
    ax.set_title(f"{result.setup.name}{': ' + fitted if fitted else ''}\nRMS residual {result.rms:.3g} m over "
                 f"{result.points} points{untrusted}", fontsize="medium")
    ax.set_ylabel(f"position {result.coordinate} (m, the data's zero)")
    ax.legend(loc="best", fontsize="small")
    ax.grid(alpha=0.3)
    ax_res.plot(result.t, result.residual * 1000, ".", ms=3, color=DATA_COLOUR)
    ax_res.axhline(0.0, color="black", lw=0.8)
    ax_res.set_ylabel("data − model (mm)")
    ax_res.set_xlabel("t (s, the data's clock)")
    ax_res.grid(alpha=0.3)
    fig.tight_layout()
    plotting.save_figure(fig, path)


# ---- the mystery spring ----


def _sets(args) -> str:
    """The --set options given, to repeat with --show-answer (the answer depends on them)."""
    return "".join(f" --set {shlex.quote(assignment)}" for assignment in args.assignments)


def run_mystery(args, setup) -> int:
    """--mystery FILE [--seed N]: write the run, say what the students are told, keep the answer."""
    path = args.mystery
    if os.path.lexists(path) and not args.overwrite:
        raise OutputError(f"--mystery {path!r}: the file exists; give a new name, or add --overwrite to "
                          f"replace it")
    check_writable(path, what="mystery file", overwrite=args.overwrite)
    seed = args.seed if args.seed is not None else secrets.randbelow(9000) + 1000
    run = mystery.make(setup, seed=seed, given=_given(args),
                       coordinate=compare.coordinate_of(setup, args.coordinate))
    write_text(path, mystery.text(run), what="mystery file", overwrite=args.overwrite)
    r0 = run.known.get("r0", (None, ""))[0]
    start = f", released from rest at r0 = {tuple(r0)} m" if r0 is not None else ""
    print(f"wrote {path}: {len(run.t)} samples at {run.rate} per second (Vernier CSV) of a spring with "
          f"m = {run.known['m'][0]:g} kg{start}; {' and '.join(run.answer)} are the mystery "
          f"(seed {seed}: python main.py {setup.name} --show-answer --seed {seed}{_sets(args)} prints them)",
          file=sys.stderr)
    return 0


def show_answer(args, setup) -> int:
    """--show-answer --seed N: the constants the mystery file with that seed was made with."""
    run = mystery.make(setup, seed=args.seed, given=_given(args),
                       coordinate=compare.coordinate_of(setup, args.coordinate))
    print(mystery.answer_line(run, args.seed))
    return 0

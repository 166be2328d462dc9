"""The period of each mass of a headless run, for the text and JSON reports.

The run sees the motion often enough to time it (reports/headless.py's plan), and its
CrossingMeter gathers the crossings as it goes (:func:`timing`); the period is measured as a lab
measures it, from the upward crossings of the equilibrium along the scene's graphed coordinate,
and set beside the formula's 2π/ω_d where a closed form covers the motion (physics/period.py,
physics/equilibrium.py). Where either has no value, a sentence says why.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from physics.equilibrium import equilibrium
from physics.period import CrossingMeter, Period, formula_period, why_none
from scenes._view import DEFAULT_VIEW

if TYPE_CHECKING:
    from .headless import Result


class PeriodReport(NamedTuple):
    """One mass's period: measured (or None, and why), the formula's (or None, and why), and what
    was timed: `axis` ("x", "y" or "z") rising through `centre`, m."""

    measured: Period | None
    formula: float | None
    measured_note: str
    formula_note: str
    axis: str
    centre: float | None


@dataclass(frozen=True)
class Timing:
    """What a headless run times its period by: `axis` of r (0, 1, 2), each mass's centre along it
    (its equilibrium, (N,) m; None where nothing pulls the masses back), and the CrossingMeter that
    gathers the upward crossings of the centre as the run goes, from the start on (a
    physics/recording.py CoordinateWatch shows it the steps)."""

    axis: int
    centre: np.ndarray | None
    meter: CrossingMeter


def timing(setup, model) -> Timing:
    """The Timing of a run of this scene: its graphed coordinate, the equilibrium along it, and a
    meter that has seen nothing yet."""
    view = {**DEFAULT_VIEW, **(setup.hooks.view or {})}
    axis = "xyz".index(view["plot"][0])
    centre = equilibrium(model.forces, model.state)
    centre = None if centre is None else np.asarray(centre[:, axis], dtype=float)
    meter = CrossingMeter(np.full(model.state.count, np.nan) if centre is None else centre)
    return Timing(axis=axis, centre=centre, meter=meter)


def periods(result: Result) -> list[PeriodReport]:
    """Each mass's PeriodReport, from the crossings the run saw."""
    model, timed = result.model, result.timing
    meter, count, axis = timed.meter, model.state.count, "xyz"[timed.axis]
    covered = False if model.exact is None else np.isfinite(model.exact_where_valid([0.0])[0][0]).all(axis=-1)
    formula, why = formula_period(model.forces, model.state, closed_form=covered)
    # lists, not numpy scalars, for a loop over 10⁴ masses
    centres = [None] * count if timed.centre is None else timed.centre.tolist()
    formulas = [None] * count if formula is None else [T if math.isfinite(T) else None for T in formula.tolist()]
    swings = np.broadcast_to(covered, (count,)).tolist()
    found = meter.periods() if timed.centre is not None else [None] * count
    crossings, end = meter.counts().tolist(), meter.end
    return [PeriodReport(
        measured=measured, formula=T,
        measured_note="" if measured is not None else why_none(middle, crossings=crossings[i], end=end),
        formula_note="" if T is not None else why if formula is None else (
            "b² ≥ 4mk: the damping is too strong for it to swing" if swings[i]
            else "no closed form covers this mass's forces"),
        axis=axis, centre=middle)
        for i, (measured, T, middle) in enumerate(zip(found, formulas, centres))]


def period_text(report: PeriodReport) -> str:
    """`T = 3.1364 ± 0.0001 s over 9 cycles (y rising through -3.45 m); formula 2π/ω_d = 3.1416 s`."""
    from export.step_update import number

    if report.measured is not None:
        T = report.measured
        said = (f"T = {number(T.measured, 6)} ± {number(T.spread, 2)} s over {T.cycles} cycles "
                f"({report.axis} rising through {number(report.centre, 4)} m)")
    else:
        said = f"none measured: {report.measured_note}"
    if report.formula is not None:
        return f"{said}; formula 2π/ω_d = {number(report.formula, 6)} s"
    return f"{said}; no formula: {report.formula_note}"


def period_json(report: PeriodReport) -> dict | None:
    """{"measured": s, "spread": s, "cycles": n, "formula": s or None}, or None where none was measured."""
    if report.measured is None:
        return None
    T = report.measured
    return {"measured": T.measured, "spread": T.spread, "cycles": T.cycles, "formula": report.formula}

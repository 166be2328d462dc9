"""The period of each mass of a headless run, for the text and JSON reports.

The run records the motion often enough to time it (reports/headless.py's plan); the period is
measured as a lab measures it, from the upward crossings of the equilibrium along the scene's
graphed coordinate, and set beside the formula's 2π/ω_d where a closed form covers the motion
(physics/period.py, physics/equilibrium.py). Where either has no value, a sentence says why.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from physics.equilibrium import equilibrium
from physics.period import Period, formula_period, measured_period, why_no_period
from scenes._view import DEFAULT_VIEW

from .headless import Result


@dataclass(frozen=True)
class PeriodReport:
    """One mass's period: measured (or None, and why), the formula's (or None, and why), and what
    was timed: `axis` ("x", "y" or "z") rising through `centre`, m."""

    measured: Period | None
    formula: float | None
    measured_note: str
    formula_note: str
    axis: str
    centre: float | None


def periods(result: Result) -> list[PeriodReport]:
    """Each mass's PeriodReport, from the run's recorded motion."""
    model, traj = result.model, result.trajectory
    view = {**DEFAULT_VIEW, **(result.setup.hooks.view or {})}
    axis = "xyz".index(view["plot"][0])
    centre = equilibrium(model.forces, model.state)
    covered = False if model.exact is None else np.isfinite(model.exact_where_valid([0.0])[0][0]).all(axis=-1)
    formula, why = formula_period(model.forces, model.state, closed_form=covered)
    reports = []
    for i in range(len(traj.m)):
        x = traj.r[:, i, axis]
        middle = None if centre is None else float(centre[i, axis])
        measured = None if middle is None else measured_period(traj.t, x, centre=middle)
        T = None if formula is None or not np.isfinite(formula[i]) else float(formula[i])
        reports.append(PeriodReport(
            measured=measured, formula=T,
            measured_note="" if measured is not None else why_no_period(traj.t, x, centre=middle),
            formula_note="" if T is not None else why if formula is None else (
                "b² ≥ 4mk: the damping is too strong for it to swing" if covered is not False
                and np.broadcast_to(covered, (len(traj.m),))[i] else "no closed form covers this mass's forces"),
            axis="xyz"[axis], centre=middle))
    return reports


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

"""The fit itself: least squares from the best start, the values at the end with their standard
uncertainties, and how far they move when Δt is halved.

The values are the fitted constants, t_offset, the linear ones (r0's component, where fitted) and
position_offset. Standard uncertainties come from the Jacobian J of the model at the fit: the
covariance is s² (JᵀJ)⁻¹ with s² = Σ residual² / (N − number of values), as for any least-squares
fit with independent noise of the same size on every point. At the end every value is one column
of J (the release too), so its uncertainty holds whether least squares or the linear algebra found
it. Values the data cannot tell apart (a change of one undone by a change of another) are refused
with one line instead of a meaningless fit.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from scenes._constants import DECLARED

from .least_squares import least_squares
from .model_run import FitError

CONDITION_LIMIT = 1e8             # beyond this the fitted values cannot be told apart
BUDGET = 40                       # engine runs a fit of two constants may take
OFFSETS = ("t_offset", "position_offset")


@dataclass
class Fitted:
    """The fit's end: every value (names: the fitted constants, "t_offset", the linear ones,
    "position_offset") with its standard uncertainty, the data as compared, the model there and the
    Jacobian of the model (one column per value)."""

    names: list
    values: np.ndarray
    sigma: np.ndarray
    model: np.ndarray
    residual: np.ndarray
    jacobian: np.ndarray
    sign: int
    problem: object
    at_edge: list = field(default_factory=list)
    settled: bool = True            # least squares stopped because it converged, not for its budget

    @property
    def cost(self) -> float:
        return float(self.residual @ self.residual)

    def value(self, name: str) -> float:
        return float(self.values[self.names.index(name)])

    def uncertainty(self, name: str) -> float:
        return float(self.sigma[self.names.index(name)])


def bounds(names):
    """Each fitted constant's declared range, and none for t_offset."""
    low = np.array([(DECLARED[name].low if name in DECLARED else -np.inf) for name in names] + [-np.inf])
    high = np.array([(DECLARED[name].high if name in DECLARED else np.inf) for name in names] + [np.inf])
    return low, high


def descend(problem, constants, t_offset, *, budget=BUDGET):
    """(constants, t_offset, Σ residual², converged): least squares from this start, within `budget`
    runs of the engine. Never worse than the start: the lowest cost seen is kept."""
    low, high = bounds(problem.nonlinear)
    theta, cost, converged = least_squares(problem, np.array([*constants, t_offset]), low, high, budget=budget)
    return tuple(theta[:-1]), float(theta[-1]), cost, converged


def linear_values(problem, constants, t_offset, sign):
    """(the linear constants' values, position_offset, the sign) solved at these constants."""
    residual, beta, m0, changes = problem.solve(constants, t_offset, sign)
    if problem.mode == "scale":
        # data = a·m₀ + c with m₀ = e + f·d: the release r0 = base + f (s·a − 1); see lab/problem.py
        (name,) = problem.linear
        run = problem.columns(constants, t_offset)[0]
        moved = problem.copy(mode="lines")
        d = moved.columns(constants, t_offset)[1][0]
        X = np.column_stack([np.ones_like(d), d])
        (e, f), *_ = np.linalg.lstsq(X, run, rcond=None)
        left = run - X @ np.array([e, f])
        if np.max(np.abs(left)) > 1e-6 * max(float(np.ptp(run)), 1e-300):
            return None                     # not a swing about a fixed point here: fit as "lines"
        a, c = beta
        release = problem.base[name] + f * (sign * a - 1.0)
        return {name: float(release)}, float(c + a * e - sign * e), sign
    if problem.mode == "lines":
        found = {name: float(problem.base[name] + sign * u) for name, u in zip(problem.linear, beta[:-1])}
        return found, float(beta[-1]), sign
    return {}, float(beta[-1]), sign


def finish(problem, constants, t_offset, sign) -> Fitted:
    """The values at the fit, their uncertainties and the model's Jacobian (see the module's
    docstring). The runs are made again from the fitted release (one run more than the constants),
    so every column is the model's own derivative there."""
    found = linear_values(problem, constants, t_offset, sign)
    if found is None:
        raise _NotScale()
    release, offset, sign = found
    final = problem.copy(mode="lines" if problem.linear else "offset", base=release, sign=sign)
    tau = final.t - t_offset
    m0, changes = final.columns(constants, t_offset)
    model = sign * m0 + offset
    residual = final.y - model
    names = [*final.nonlinear, "t_offset", *final.linear, "position_offset"]
    J = np.empty((len(tau), len(names)))
    for j, value in enumerate(constants):
        h = 1e-6 * max(abs(value), 1e-3)
        moved = np.array(constants, dtype=float)
        moved[j] += h
        J[:, j] = sign * (final.columns(moved, t_offset)[0] - m0) / h
    h = 1e-7 * max(final.span, 1e-3)
    later = final.columns(constants, t_offset, tau=tau - h)[0]
    earlier = final.columns(constants, t_offset, tau=tau + h)[0]
    p = len(constants)
    J[:, p] = sign * (later - earlier) / (2 * h)          # d model / d t_offset = −s · model'(τ)
    for j, change in enumerate(changes):
        J[:, p + 1 + j] = sign * change
    J[:, -1] = 1.0
    values = np.array([*constants, t_offset, *release.values(), offset], dtype=float)
    sigma = _uncertainties(J, residual, names)
    fitted = Fitted(names=names, values=values, sigma=sigma, model=model, residual=residual, jacobian=J,
                    sign=sign, problem=final)
    fitted.at_edge = _at_edge(fitted, problem.nonlinear)
    return fitted


class _NotScale(Exception):
    """The release does not only scale the swing at these constants: fit again with two runs each."""


def _uncertainties(J, residual, names):
    """σ of every value: √diag(s² (JᵀJ)⁻¹), the columns scaled first; FitError where values cannot be
    told apart (the Jacobian's condition number above CONDITION_LIMIT) or one changes nothing."""
    scale = np.linalg.norm(J, axis=0)
    if np.any(~(scale > 0)) or not np.all(np.isfinite(J)):
        stuck = [names[j] for j in np.flatnonzero(~(scale > 0))]
        raise FitError(f"the data cannot fix {', '.join(stuck)}: changing it does not change the model "
                       f"at the data's times")
    _, singular, directions = np.linalg.svd(J / scale, full_matrices=False)
    condition = singular[0] / singular[-1] if singular[-1] > 0 else math.inf
    if condition > CONDITION_LIMIT:
        together = np.abs(directions[-1])         # the change of values that changes nothing
        tied = [names[j] for j in np.flatnonzero(together > 0.1 * together.max())]
        constants = [name for name in tied if name not in OFFSETS] or tied
        offsets = [name.replace("_", " ") for name in tied if name in OFFSETS and name not in constants]
        also = f" (with the {' and '.join(offsets)})" if offsets else ""
        listed = ", ".join(constants[:-1]) + " and " + constants[-1] if len(constants) > 1 else constants[0]
        raise FitError(f"{listed} cannot be told apart from this data{also} (the fit's Jacobian has condition "
                       f"number {condition:.1e}): a change of one can be undone by a change of the "
                       f"other{'s' if len(tied) > 2 else ''}; set "
                       f"{'it' if len(constants) == 1 else 'all but one of them'} with --set")
    dof = len(residual) - J.shape[1]
    s2 = float(residual @ residual) / dof if dof > 0 else math.nan
    covariance = np.linalg.pinv((J / scale).T @ (J / scale)) / np.outer(scale, scale) * s2
    return np.sqrt(np.maximum(np.diag(covariance), 0.0))


def _at_edge(fitted: Fitted, names) -> list:
    """The fitted constants that ended at the edge of their declared range and would go beyond it:
    one Gauss-Newton step from the fit, free of the range, moves them out by more than 0.1σ."""
    step, *_ = np.linalg.lstsq(fitted.jacobian, fitted.residual, rcond=None)
    found = []
    for j, name in enumerate(names):
        if name not in DECLARED:
            continue
        value, sigma, free = fitted.values[j], fitted.sigma[j], fitted.values[j] + step[j]
        low, high = DECLARED[name].low, DECLARED[name].high
        near = 1e-6 * max(abs(value), 1e-9) + 0.01 * sigma
        if (value - low <= near and free < low - 0.1 * sigma) or (high - value <= near and free > high + 0.1 * sigma):
            found.append(name)
    return found


def moves_at_half_dt(fitted: Fitted, dt: float) -> dict:
    """How far each value moves when the model's Δt is halved: one Gauss-Newton step from the fit,
    with the model run again at Δt/2 (one run), name → the move in the value's own unit."""
    final = fitted.problem
    constants = fitted.values[:len(final.nonlinear)]
    t_offset = fitted.value("t_offset")
    m0 = final.columns(constants, t_offset, dt=dt / 2)[0]
    model = fitted.sign * m0 + fitted.value("position_offset")
    step, *_ = np.linalg.lstsq(fitted.jacobian, (final.y - model) - fitted.residual, rcond=None)
    return dict(zip(fitted.names, (float(x) for x in step)))

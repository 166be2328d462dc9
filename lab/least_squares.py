"""Least squares for the fit (lab/fit.py): scipy's least_squares, within a budget of engine runs, and
Newton's method on the time offset alone (numpy only, for a comparison without --fit).

`problem` (lab/problem.py) has residuals(theta) (data − model at every point, the linear unknowns
solved for each theta) and jacobian(theta); theta is the fitted constants, then t_offset.
"""
from __future__ import annotations

import numpy as np


class MissingScipy(Exception):
    """--fit without scipy installed: main.py and the page say this one line."""

    def __init__(self):
        super().__init__("--fit needs scipy, which is not installed; install it with "
                         "python -m pip install scipy (everything else runs without it)")


class _Spent(Exception):
    """The fit's budget of engine runs is spent: the lowest cost seen so far is the answer."""


def least_squares(problem, theta, low, high, *, budget: int):
    """(theta, Σ residual², converged): the theta within [low, high] that minimises Σ residual², by
    scipy.optimize.least_squares (trust-region reflective, the columns scaled by the Jacobian so a
    constant in N/m and an offset in s take comparable steps), from `theta`. It stops when `budget`
    more runs of the engine are spent, at the lowest cost seen. scipy is optional for the project
    and imported here only, when a fit is asked for; without it MissingScipy says what to install."""
    try:
        from scipy.optimize import least_squares as scipy_least_squares
    except ImportError:
        raise MissingScipy() from None
    theta = np.array(theta, dtype=float)
    inside = 1e-9 * np.maximum(np.abs(theta), 1.0)          # strictly inside, as trf starts
    theta = np.clip(theta, low + inside, high - inside)     # an infinite bound stays infinite
    limit = problem.runs.count + budget

    def within(function):
        def call(x):
            if problem.runs.count >= limit:
                raise _Spent()
            return function(x)
        return call

    problem.best = (np.inf, None)
    first = problem.residuals(theta)
    converged = False
    try:
        with np.errstate(all="ignore"):
            solution = scipy_least_squares(within(problem.residuals), theta, jac=within(problem.jacobian),
                                           bounds=(low, high), method="trf", x_scale="jac", ftol=1e-12,
                                           xtol=1e-12, gtol=None, max_nfev=100)
        converged = solution.status > 0
    except _Spent:
        pass
    cost, best = problem.best
    if best is None:
        return theta, float(first @ first), False
    return best, cost, converged


def offset_only(problem, t_offset: float, iterations: int = 20) -> float:
    """Newton's method on t_offset alone (numpy only), the linear unknowns solved at each step, from
    the grid's start: the best t_offset for the constants as set."""
    step = 1e-6 * max(problem.span, 1e-3)

    def cost(x):
        residual = problem.residuals(np.array([x]))
        return float(residual @ residual)

    here = cost(t_offset)
    for _ in range(iterations):
        before, after = cost(t_offset - step), cost(t_offset + step)
        slope, curvature = (after - before) / (2 * step), (after - 2 * here + before) / step ** 2
        if not curvature > 0:
            break
        move = -slope / curvature
        for scale in (1.0, 0.5, 0.25, 0.1):
            trial = cost(t_offset + scale * move)
            if trial <= here:
                break
        else:
            break
        t_offset, here = t_offset + scale * move, trial
        if abs(scale * move) <= 1e-12 * max(problem.span, 1.0):
            break
    return t_offset

"""Least squares for the fit (lab/compare.py): scipy's least_squares, and Gauss-Newton on the offsets alone.

`problem` has residuals(theta) (data − model at every point) and jacobian(theta) (d residual / d
theta, one column per value); theta is the fitted constants, then t_offset and position_offset.
"""
from __future__ import annotations

import numpy as np


def offsets_only(problem, theta, iterations: int = 30):
    """Gauss-Newton on the two offsets alone (numpy only), from the grid search's start."""
    theta = np.array(theta, dtype=float)
    p = len(problem.names)
    for _ in range(iterations):
        residual = problem.residuals(theta)
        _, slope = problem.model(theta)
        J = np.column_stack([-slope, np.ones_like(slope)])
        step, *_ = np.linalg.lstsq(J, -residual, rcond=None)
        trial = theta.copy()
        trial[p:] += step
        if np.sum(problem.residuals(trial) ** 2) > np.sum(residual ** 2):
            step = step / 4
            trial = theta.copy()
            trial[p:] += step
            if np.sum(problem.residuals(trial) ** 2) > np.sum(residual ** 2):
                break
        theta = trial
        if np.all(np.abs(step) <= 1e-12 * (1 + np.abs(theta[p:]))):
            break
    return theta


class MissingScipy(Exception):
    """--fit without scipy installed: main.py and the page say this one line."""

    def __init__(self):
        super().__init__("--fit needs scipy, which is not installed; install it with "
                         "python -m pip install scipy (everything else runs without it)")


def least_squares(problem, theta, low, high):
    """(theta, Σ residual²): the theta within [low, high] that minimises Σ problem.residuals(theta)²,
    by scipy.optimize.least_squares (trust-region reflective, the columns scaled by the Jacobian so
    a constant in N/m and an offset in s take comparable steps). scipy is optional for the project
    and imported here only, when a fit is asked for; without it MissingScipy says what to install.
    """
    try:
        from scipy.optimize import least_squares as scipy_least_squares
    except ImportError:
        raise MissingScipy() from None
    theta = np.array(theta, dtype=float)
    inside = 1e-9 * np.maximum(np.abs(theta), 1.0)          # strictly inside, as trf starts
    theta = np.clip(theta, low + inside, high - inside)     # an infinite bound stays infinite
    with np.errstate(all="ignore"):
        solution = scipy_least_squares(problem.residuals, theta, jac=problem.jacobian, bounds=(low, high),
                                       method="trf", x_scale="jac", ftol=1e-10, xtol=1e-10, gtol=1e-10,
                                       max_nfev=200)
    return solution.x, float(2 * solution.cost)

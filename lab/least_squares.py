"""Least squares for the fit (lab/compare.py): Levenberg-Marquardt, and Gauss-Newton on the offsets alone.

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


MAX_ITERATIONS = 60               # Levenberg-Marquardt steps at most (a fit from the start takes 3 to 8)


def least_squares(problem, theta, low, high):
    """(theta, Σ r²): the theta within [low, high] that minimises Σ problem.residuals(theta)², by
    Levenberg-Marquardt.

    Each step solves (ĴᵀĴ + λ I) δ = −Ĵᵀ r for the columns of J scaled to unit length (Ĵ), so a
    constant in N/m and an offset in s take comparable steps; a step that lowers Σ r² is taken and
    λ shrinks tenfold (towards Gauss-Newton), one that does not is refused and λ grows tenfold
    (towards a short step downhill). A step is clipped to the bounds. It stops when Σ r² falls by
    less than a part in 10¹⁰, when the full Gauss-Newton step would take less than that off it (no
    further run of the engine), or when no step lowers it any more.

    Why not scipy.optimize.least_squares (which the fit used before): the problem has two to five
    values and starts near the answer, which plain Levenberg-Marquardt handles in a few steps,
    and importing scipy.optimize took 0.33 s, a third of the whole `--fit` command (docs/performance.md).
    """
    theta = np.clip(np.array(theta, dtype=float), low, high)
    residual = problem.residuals(theta)
    cost, damping = float(residual @ residual), 1e-3
    with np.errstate(all="ignore"):
        for _ in range(MAX_ITERATIONS):
            theta, residual, fallen = _step(problem, theta, residual, cost, damping, low, high)
            if fallen is None:
                break
            damping, before, cost = fallen[0], cost, float(residual @ residual)
            if before - cost <= 1e-10 * before:
                break
    return theta, cost


def _step(problem, theta, residual, cost, damping, low, high):
    """One Levenberg-Marquardt step from theta: (theta, residual, (λ,)) after a step that lowers
    the cost, or (theta, residual, None) where none does (λ grown past 10¹⁰)."""
    J = problem.jacobian(theta)
    scale = np.linalg.norm(J, axis=0)
    scale[~(scale > 0)] = 1.0
    A, gradient = (J / scale).T @ (J / scale), (J / scale).T @ residual
    try:     # what the Gauss-Newton step would take off the cost: converged when that is nothing
        if float(gradient @ np.linalg.lstsq(A, gradient, rcond=None)[0]) <= 1e-10 * cost:
            return theta, residual, None
    except np.linalg.LinAlgError:
        pass
    while damping < 1e10:
        try:
            step = -np.linalg.solve(A + damping * np.eye(len(A)), gradient) / scale
        except np.linalg.LinAlgError:
            step = np.full(len(A), np.nan)
        trial = np.clip(theta + step, low, high)
        if np.all(np.isfinite(trial)) and np.any(trial != theta):
            moved = problem.residuals(trial)
            if float(moved @ moved) < cost:
                return trial, moved, (max(damping / 10, 1e-9),)
        damping *= 10
    return theta, residual, None

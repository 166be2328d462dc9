"""The residuals data − model as a function of the values fitted, with every value the model is linear
in solved exactly for each candidate (variable projection).

The measured file has its own clock and zero, and its axis may point either way, so

    data(t) ≈ s · model(t − t_offset; constants) + position_offset,      s = +1 or −1.

position_offset enters linearly: for any constants and t_offset it is solved exactly. So is the
release point r0 (its component along the compared coordinate) wherever the motion is linear in it,
as it is for a spring with damping, gravity and a drive (checked on the first run, not assumed):
then model(r0) = m₀ + (r0 − r0ᵦ)·d, with m₀ the run from r0ᵦ and d the change per metre, and

    lines   data − s·m₀ = (s·(r0 − r0ᵦ))·d + position_offset           two runs per candidate
    scale   data = a·m₀ + c                                             one run per candidate

where `scale` holds when m₀ is itself a swing about a fixed point (m₀ = e + f·d: a free spring,
with or without gravity): the release only scales the swing, and s is folded into a. Without a
linear release (r0 as set, or a motion not linear in it) the mode is `offset`: data − s·m₀ = c.

What is left to the least squares (lab/fit.py) is the constants the motion is not linear in (k, b,
...) and t_offset: few values, each valley found from a start near the truth (lab/start.py).
"""
from __future__ import annotations

import math

import numpy as np

from .model_run import FitError

LINEAR_CHECK = 1e-7          # relative departure from a straight line in r0 still counted as linear


class Problem:
    """data − model for one comparison (see the module's docstring).

    runs      lab/model_run.py's Runs (the engine's runs, counted)
    t, y      the data: time from the first point, s (its clock is t + t_first), and position, m
    nonlinear the constants fitted by least squares
    linear    the constants solved exactly (RELEASE, or none)
    base      name → value of every linear constant's run (the start)
    step      name → the linear constant's change between its two runs
    mode      "scale", "lines" or "offset"
    sign      +1 or −1: the data's axis (unused in "scale" mode, where a's sign holds it)
    dt        the model's Δt, s (None: the scene's)
    """

    def __init__(self, runs, t, y, *, nonlinear, linear=(), base=None, step=None, mode="offset", sign=1,
                 dt=None):
        self.runs, self.t, self.y = runs, np.asarray(t, dtype=float), np.asarray(y, dtype=float)
        self.nonlinear, self.linear = list(nonlinear), list(linear)
        self.base, self.step = dict(base or {}), dict(step or {})
        self.mode, self.sign, self.dt = mode, sign, dt
        self.span = float(self.t[-1] - self.t[0]) if len(self.t) else 0.0
        self.scale = float(np.ptp(self.y)) or 1.0
        self.best = (math.inf, None)          # (cost, values): the lowest cost seen by residuals()
        self.reach = 0.0                      # s a run goes beyond what is asked (a period: the starts' grid)

    def copy(self, **changes) -> "Problem":
        """The same problem with some of its parts changed (t and y together)."""
        parts = dict(t=self.t, y=self.y, nonlinear=self.nonlinear, linear=self.linear, base=self.base,
                     step=self.step, mode=self.mode, sign=self.sign, dt=self.dt)
        parts.update(changes)
        made = Problem(self.runs, parts.pop("t"), parts.pop("y"), **parts)
        made.reach = self.reach
        return made

    # ---- the model's columns ----

    def _run(self, values: dict, end: float, dt=None):
        """The run of `values` reaching model time `end`, s (a little beyond, so that a fit's small
        moves of t_offset reuse it)."""
        dt = dt or self.dt
        return self.runs.get(values, max(end, 0.0) + 0.05 * self.span + self.reach + 2 * (dt or 0.0) + 1e-6,
                             dt=dt)

    def values(self, constants, moved: str | None = None) -> dict:
        """The values of a run: the nonlinear constants, and each linear one at its base (`moved` one
        step beyond it)."""
        values = dict(zip(self.nonlinear, (float(c) for c in constants)))
        values.update(self.base)
        if moved is not None:
            values[moved] = self.base[moved] + self.step[moved]
        return values

    def columns(self, constants, t_offset, *, dt=None, tau=None):
        """(m₀, [d per linear constant]) at model times τ (default: the data's, t − t_offset)."""
        tau = self.t - t_offset if tau is None else tau
        end = float(np.max(tau))
        m0 = self._run(self.values(constants), end, dt).at(tau)[0]
        if self.mode != "lines":
            return m0, []
        return m0, [(self._run(self.values(constants, name), end, dt).at(tau)[0] - m0) / self.step[name]
                    for name in self.linear]

    def design(self, m0, changes, sign):
        """(X, z): the linear unknowns' columns and what they fit, for the data's axis `sign`."""
        ones = np.ones_like(m0)
        if self.mode == "scale":
            return np.stack([m0, ones], axis=-1), self.y + 0 * m0
        return np.stack([*changes, ones], axis=-1), self.y - sign * m0

    def solve(self, constants, t_offset, sign=None):
        """(residual, linear unknowns, m₀, changes) at these constants and t_offset."""
        sign = self.sign if sign is None else sign
        m0, changes = self.columns(constants, t_offset)
        X, z = self.design(m0, changes, sign)
        beta, *_ = np.linalg.lstsq(X, z, rcond=None)
        return z - X @ beta, beta, m0, changes

    # ---- for the least squares: [constants..., t_offset] → residuals ----

    def residuals(self, theta):
        theta = np.asarray(theta, dtype=float)
        try:
            residual = self.solve(theta[:-1], theta[-1])[0]
        except FitError:     # a trial the model cannot run (it blew up): far worse than any other
            return np.full(len(self.t), 10.0 * self.scale)
        cost = float(residual @ residual)
        if cost < self.best[0]:
            self.best = (cost, theta.copy())
        return residual

    def jacobian(self, theta):
        """d residual / d theta by differences: one set of runs per constant (the linear unknowns
        solved again for each, so this is the derivative of what least squares minimises), and the
        time offset's without a run (the same runs read a little earlier and later)."""
        theta = np.asarray(theta, dtype=float)
        base = self.residuals(theta)
        J = np.empty((len(self.t), len(theta)))
        for j in range(len(theta) - 1):
            h = 1e-6 * max(abs(theta[j]), 1e-3)
            moved = theta.copy()
            moved[j] += h
            J[:, j] = (self.residuals(moved) - base) / h
        h = 1e-7 * max(self.span, 1e-3)
        later, earlier = theta.copy(), theta.copy()
        later[-1] += h
        earlier[-1] -= h
        J[:, -1] = (self.residuals(later) - self.residuals(earlier)) / (2 * h)
        return J

    # ---- the start: many time offsets at once, each with its linear unknowns solved ----

    def costs(self, constants, t_offsets, *, points: int = 600):
        """Σ residual² for each t_offset in `t_offsets` (on at most `points` of the data, evenly
        spread) with each sign: {sign: array}. One set of runs serves them all."""
        t_offsets = np.asarray(t_offsets, dtype=float)
        every = max(1, len(self.t) // points)
        t, y = self.t[::every], self.y[::every]
        end = float(t[-1] - np.min(t_offsets))
        runs = [self._run(self.values(constants), end)]
        if self.mode == "lines":
            runs += [self._run(self.values(constants, name), end) for name in self.linear]
        found = {}
        block = max(1, 4_000_000 // max(len(t), 1))
        for sign in ((1,) if self.mode == "scale" else (1, -1)):
            parts = []
            for start in range(0, len(t_offsets), block):
                tau = t[None, :] - t_offsets[start:start + block, None]
                m0 = runs[0].roughly(tau)
                changes = [(run.roughly(tau) - m0) / self.step[name] for run, name in zip(runs[1:], self.linear)]
                ones = np.ones_like(m0)
                if self.mode == "scale":
                    X, z = np.stack([m0, ones], axis=-1), np.broadcast_to(y, m0.shape)
                else:
                    X, z = np.stack([*changes, ones], axis=-1), y[None, :] - sign * m0
                parts.append(_batched_cost(X, z))
            found[sign] = np.concatenate(parts)
        return found, len(t)


def _batched_cost(X, z):
    """min over β of |z − Xβ|² for each row of a batch: X (G, n, q), z (G, n)."""
    XtX = np.einsum("gnq,gnr->gqr", X, X)
    Xtz = np.einsum("gnq,gn->gq", X, z)
    q = X.shape[-1]
    ridge = 1e-12 * np.trace(XtX, axis1=1, axis2=2)[:, None, None] * np.eye(q) + 1e-300 * np.eye(q)
    beta = np.linalg.solve(XtX + ridge, Xtz[..., None])[..., 0]
    residual = z - np.einsum("gnq,gq->gn", X, beta)
    return np.einsum("gn,gn->g", residual, residual)


def linear_mode(problem, constants, name: str) -> str:
    """How the release `name` enters the model at these constants: "scale", "lines", or "" where the
    motion is not linear in it (three runs: at its base, and one and two steps beyond)."""
    base, step = problem.base[name], problem.step[name]
    tau = np.linspace(0.0, problem.span, 4001)
    values = problem.values(constants)
    m = [problem._run({**values, name: base + n * step}, problem.span).at(tau)[0] for n in range(3)]
    change = m[1] - m[0]
    size = float(np.max(np.abs(change)))
    if not size > 0 or np.max(np.abs(m[2] - 2 * m[1] + m[0])) > LINEAR_CHECK * size:
        return ""
    if np.ptp(m[0]) < 0.01 * size:       # the base run hardly swings: it cannot carry the scale
        return "lines"
    X = np.column_stack([np.ones_like(change), change])
    coefficients, *_ = np.linalg.lstsq(X, m[0], rcond=None)
    left = m[0] - X @ coefficients
    return "scale" if np.max(np.abs(left)) <= LINEAR_CHECK * float(np.ptp(m[0])) else "lines"

"""The state of N point masses: what changes in time.

Variables
    t   time, s
    r   positions, shape (N, 3), m
    p   momenta, shape (N, 3), kg·m/s
Parameters carried with the state
    m   masses, shape (N,), kg

Velocity is never stored: it is derived from momentum in exactly one place, :func:`velocity`,
as v = p / m.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class State:
    """Time, positions and momenta of N point masses (plus their masses)."""

    t: float
    r: np.ndarray
    p: np.ndarray
    m: np.ndarray

    @property
    def v(self) -> np.ndarray:
        """Velocities v = p / m, shape (N, 3), m/s."""
        return velocity(self.p, self.m)

    @property
    def count(self) -> int:
        """Number of masses N."""
        return self.r.shape[0]


def velocity(p: np.ndarray, m: np.ndarray) -> np.ndarray:
    """v = p / m for every mass: p has shape (N, D), or (n, N, D) for n samples; m has shape (N,)."""
    return p / m[:, None]


def make_state(*, r, v=None, m, t: float = 0.0) -> State:
    """A state from positions r (m), velocities v (m/s, default rest) and masses m (kg).

    r and v may be one 3-vector (a single mass) or an (N, 3) array; m a number or an (N,) array.
    Momentum is computed as p = m v. (The arrays are laid out column by column, for speed: see
    physics/simulate.py.)
    """
    r = np.array(np.atleast_2d(np.asarray(r, dtype=float)), order="F")
    v = np.zeros_like(r) if v is None else np.broadcast_to(np.asarray(v, dtype=float), r.shape).copy(order="F")
    m = np.broadcast_to(np.asarray(m, dtype=float), r.shape[:1]).copy()
    if np.any(m <= 0):
        raise ValueError("every mass m must be positive")
    return State(t=float(t), r=r, p=m[:, None] * v, m=m)

"""Sums along the rows of (N, D) arrays: one vector per mass, in D = 1, 2 or 3 components.

A row's components are added in the order of its axes, x then y then z, so a row whose other
components are exactly 0 gives the same sum, bit for bit, as its nonzero components alone: the
engine relies on this when it steps only the axes a motion uses (physics/motion_axes.py).
"""
from __future__ import annotations

import numpy as np


def magnitude(vectors: np.ndarray) -> np.ndarray:
    """|a| of each row of an (N, D) array, shape (N, 1): √(a_x² + a_y² + a_z²)."""
    return np.sqrt(row_dot(vectors, vectors))[..., None]


def row_dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a · b of each row, shape (N,): a_x b_x + a_y b_y + a_z b_z, added in that order.

    The same sums as (a * b).sum(axis=-1) bit for bit, one column at a time: a sum along the
    short last axis of column-major arrays is several times slower in numpy.
    """
    total = a[..., 0] * b[..., 0]
    for i in range(1, a.shape[-1]):
        total += a[..., i] * b[..., i]
    return total

"""Points far off the data's swing (a motion detector's drop-out: a reading of 8 m in a swing of
±0.3 m), named and left out of the comparison.

    gross        before anything is fitted: a point further from the median of its ten neighbours
                 than three times their middle spread plus twelve times the noise, and than half the
                 data's swing (a smooth swing never gets that far from its own neighbours)
    in_residual  after the fit: a point whose residual stands more than 6 times the residual's robust
                 scatter (1.4826 × the median absolute deviation) from the median of its six
                 neighbours' residuals, which white noise passes once in five hundred million points;
                 a model that misses leaves a smooth residual, whose points stand with their
                 neighbours, so a misfit is never taken for drop-outs

More than MOST of the points (or more than 20) far off their neighbours is a file to check, not
drop-outs: refused; as many far off the fit is a fit that misses, which its verdict says (lab/trust.py).
"""
from __future__ import annotations

import numpy as np

from . import swing
from .model_run import FitError

MOST = 0.01          # fraction of the points that may be left out


def _refuse_if_many(found, count: int):
    if len(found) > max(MOST * count, 1) and len(found) > 3 or len(found) > 20:
        raise FitError(f"{len(found)} of the {count} points lie far off the data's swing; that is more than "
                       f"drop-outs of a sensor: check the file (its column and units) before comparing")
    return found


def gross(t, y) -> np.ndarray:
    """Indices of the points far off their neighbours (see the module's docstring)."""
    y = np.asarray(y, dtype=float)
    count = len(y)
    if count < 12:
        return np.array([], dtype=int)
    sigma = swing.noise(y)
    padded = np.pad(y, 5, mode="reflect")
    windows = np.lib.stride_tricks.sliding_window_view(padded, 11)
    neighbours = np.delete(windows, 5, axis=1)
    middle = np.median(neighbours, axis=1)
    spread = np.percentile(neighbours, 80, axis=1) - np.percentile(neighbours, 20, axis=1)
    half = (np.percentile(y, 99) - np.percentile(y, 1)) / 2
    far = np.abs(y - middle) > np.maximum(3 * spread + 12 * sigma, 0.5 * half)
    return _refuse_if_many(np.flatnonzero(far), count)


def in_residual(residual) -> np.ndarray:
    """Indices of the points whose residual is more than 6 robust σ (see the module's docstring)."""
    residual = np.asarray(residual, dtype=float)
    if len(residual) < 12:
        return np.array([], dtype=int)
    windows = np.lib.stride_tricks.sliding_window_view(np.pad(residual, 3, mode="reflect"), 7)
    apart = residual - np.median(np.delete(windows, 3, axis=1), axis=1)
    scale = 1.4826 * float(np.median(np.abs(apart - np.median(apart))))
    if not scale > 0:
        return np.array([], dtype=int)
    found = np.flatnonzero((np.abs(apart) > 6 * scale * 1.08)        # 1.08: the neighbours' median's own scatter
                           & (np.abs(residual - np.median(residual)) > 6 * scale))
    many = len(found) > max(MOST * len(residual), 1) and len(found) > 3 or len(found) > 20
    return np.array([], dtype=int) if many else found     # many: a misfit, which the verdict names

"""Whether a fit's numbers can be trusted, and if not, one sentence saying why.

A fit is flagged when

    the residual is not noise  its RMS is more than twice the noise its own point-to-point scatter
                               estimates (a model that misses leaves a smooth residual), or what is
                               left of it beyond that noise, √(RMS² − scatter²), is more than a tenth
                               of the data's half swing (the model misses; noisy data alone do not
                               count: their σ says so)
    the sign is open           both ways of the data's axis fit about equally well (within a χ² of 4)
                               and give constants more than σ apart
    no swing to speak of       the model's swing over the data, √Σ(model − its mean)², is less than
                               SWING_SEEN times the noise (the data hardly show a swing), or the
                               fitted spring swings with fewer than 4 samples a period
    a constant at an edge      it ended at the edge of its declared range and would go beyond it
    the fit did not settle     least squares stopped for its budget of engine runs, still moving
    Δt moves the answer        halving the model's Δt moves a fitted constant by more than its σ

The command line prints the sentence first, before the figures, and ends with exit status 3; JSON has
"trusted": false and the reason; the page shows the sentence in place of the ± figures.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

NOT_NOISE = 2.0          # RMS over the residual's own scatter above which the residual is not noise
MISS = 0.1               # RMS as a fraction of the data's half swing above which the model misses
SIGN_TIE = 4.0           # χ² within which both signs fit "about equally well"
NOISE_FREE = 1e-6        # RMS, as a fraction of the half swing, below which a residual is round-off
SWING_SEEN = 20.0        # the model's swing over the data, in units of the noise, that counts as seen


@dataclass(frozen=True)
class Trust:
    """trusted, the reasons it is not (each a few words, joined into one sentence), and where the
    model's Δt moves the answer, what the command line would set instead (advice) and a Δt that
    would do (smaller_dt, s; the page offers its own controls for it)."""

    trusted: bool = True
    reasons: tuple = ()
    advice: str = ""
    smaller_dt: float = math.nan

    @property
    def said(self) -> str:
        """`these numbers cannot be trusted: halving Δt = 0.1 s moves k by 12σ, ...` (no advice)"""
        return "" if self.trusted else "these numbers cannot be trusted: " + "; ".join(self.reasons)

    @property
    def sentence(self) -> str:
        """said, with the command line's advice in brackets at the end."""
        return self.said + (f" ({self.advice})" if self.said and self.advice else "")


def scatter(residual) -> float:
    """The noise the residual's point-to-point differences estimate, m: RMS(Δr)/√2 (white noise of σ
    gives σ; a smooth misfit gives much less than its RMS)."""
    residual = np.asarray(residual, dtype=float)
    if len(residual) < 3:
        return math.nan
    return float(np.sqrt(np.mean(np.diff(residual) ** 2) / 2))


def residual_said(residual, data) -> str:
    """Why the residual is not noise, in a few words, or ""."""
    residual = np.asarray(residual, dtype=float)
    rms = float(np.sqrt(np.mean(residual ** 2)))
    half = float(np.ptp(data)) / 2
    if not rms > NOISE_FREE * half:
        return ""
    noise = scatter(residual)
    beyond = math.sqrt(max(rms ** 2 - noise ** 2, 0.0))
    if beyond > MISS * half:
        return f"the model misses by {beyond / half:.0%} of the data's half swing"
    if rms > NOT_NOISE * noise:
        return (f"the residual is not noise (its RMS, {_length(rms)}, is {rms / noise:.2g} times the "
                f"{_length(noise)} its point-to-point scatter shows)")
    return ""


def _length(metres: float) -> str:
    """A length to 2 significant digits in mm or m: `1.9 mm`, `0.21 m`, `3e-07 m`."""
    if 1e-4 <= metres < 1.0:
        return f"{metres * 1000:.2g} mm"
    return f"{metres:.2g} m"


def swing_said(model, residual, samples_per_period: float) -> str:
    """Why the data show no swing to fit, in a few words, or ""."""
    if samples_per_period < 4:
        return (f"the fitted spring swings with {samples_per_period:.2g} samples a period, fewer than the 4 "
                f"a swing needs to be seen in the data")
    noise = float(np.sqrt(np.mean(np.asarray(residual) ** 2)))
    seen = float(np.sqrt(np.sum((model - np.mean(model)) ** 2)))
    if noise > 0 and seen < SWING_SEEN * noise:
        return f"the data hardly show a swing (it stands {seen / noise:.2g} times above the noise over the record)"
    return ""


def judge(*, residual, data, model=None, samples_per_period: float = math.inf, at_edge=(),
          sign_open: str = "", moves: dict | None = None, sigma: dict | None = None, dt: float = math.nan,
          advice: str = "", smaller_dt: float = math.nan, settled: bool = True, runs: int = 0) -> Trust:
    """The verdict on a fit (see the module's docstring). model: the model at the data's times;
    samples_per_period: of the fitted spring's swing; moves and sigma: each fitted constant's move at
    Δt/2 and its σ; advice: what to set instead."""
    reasons = []
    said = residual_said(residual, data)
    if said:
        reasons.append(said)
    seen = swing_said(data - residual if model is None else model, residual, samples_per_period)
    if seen:
        reasons.append(seen)
    if sign_open:
        reasons.append(sign_open)
    for name in at_edge:
        reasons.append(f"{name} ended at the edge of its range")
    if not settled:
        reasons.append(f"the fit had not settled after {runs} runs of the model")
    far = {name: abs(move) / sigma[name] for name, move in (moves or {}).items()
           if sigma and sigma.get(name, 0) > 0 and abs(move) > sigma[name]}
    if far:
        moved = ", ".join(f"{name} by {ratio:.2g}σ" for name, ratio in far.items())
        reasons.append(f"halving Δt = {dt:.3g} s moves {moved}, so the model's own error is in them")
    else:
        advice, smaller_dt = "", math.nan
    return Trust(trusted=not reasons, reasons=tuple(reasons), advice=advice, smaller_dt=smaller_dt)

"""What the offline page needs to judge a set-up as the command line judges it, as data.

A set-up on the offline page (a link `vertical.html#m=1&k=120&dt=0.5`, a slider, a preset) is
judged as `--set` judges it, and refused in the command line's words, with the file's own set-up
run instead. Nothing of the judgement is written again in the page's script; it comes from the
Python declarations in three forms:

- each constant's declaration (scenes/_constants.py DECLARED: its range, unit and words), which
  the page checks a value against as check_value does (Settable.as_data);
- each force's rates and rules as lines of the program the page runs (export/program_page.py's
  check section, from each force's PROGRAM_RATES and RULES): the program itself works out, before
  it draws anything, each mass's k, b/m and drag rate, and refuses a rule it breaks, in the rule's
  own sentence;
- the stability judgement of physics/stability.py as a table (:func:`stability_data`): a method's
  largest stable Δt depends on ω and γ only through ω·Δt and γ·Δt, so it is L(θ)/√(ω² + γ²) with θ
  = atan2(γ, ω), and L is tabulated here by physics/stability.py's own largest_stable_dt (the
  method's step, bisected); with the verdict's sentences (physics/stability.py's CAUSES,
  PAST_LIMIT, EVERY_DT and each method's limit_rule), which the page fills with its numbers.

Between two points of the table the page interpolates; the table is meant to be fine enough that
the limit it names agrees with the command line's to its 4 printed digits. No test checks that
now: the page's refusals' browser test was cut unfinished at issue 41 (its closing note).
"""
from __future__ import annotations

import functools
import math

import numpy as np

from physics.stability import (BISECTIONS, CAUSES, EVERY_DT, PAST_LIMIT, REFUSED, amplification, _grows,
                               limit_rule)

ANGLES = 1025                 # points of the table over θ from 0 (a spring alone) to π/2 (damping alone)
GROWTH_DECADES = (-4, 2)      # ω·Δt over which a method that grows at every Δt has its growth tabulated
GROWTH_PER_DECADE = 100


def largest_stable_steps(method: str, angles: np.ndarray) -> np.ndarray:
    """L(θ): the largest stable Δt·√(ω² + γ²) of `method` on x'' = −ω² x − γ x' with ω = cos θ and
    γ = sin θ, each angle at once: physics/stability.py's largest_stable_dt (the same bisection of
    the method's own step, from 1e-6 to 100 over the larger rate), for a whole array of angles."""
    omega, rate = np.cos(angles), np.sin(angles)
    omega[np.isclose(angles, math.pi / 2, atol=1e-15)] = 0.0
    scale = np.maximum(omega, rate)
    low, high = 1e-6 / scale, 100.0 / scale

    def stable(dt):
        radius = _amplifications(method, omega, rate, dt)
        return np.array([_grows(g, d * s) is False for g, d, s in zip(radius, dt, scale)])

    at_low, at_high = stable(low), stable(high)
    for _ in range(BISECTIONS):
        middle = np.sqrt(low * high)
        ok = stable(middle)
        low, high = np.where(ok, middle, low), np.where(ok, high, middle)
    limit = np.where(at_high, np.inf, np.where(at_low, low, 0.0))
    return limit * np.hypot(omega, rate)


def _amplifications(method: str, omega, rate, dt) -> np.ndarray:
    """ρ(M) for each (ω, γ, Δt): physics/stability.py's amplification, one Δt per pair (the
    dimensionless pair (ω·Δt, γ·Δt) is what it depends on, so each is stepped at Δt = 1)."""
    return amplification(method, omega=omega * dt, rate=rate * dt, dt=1.0)


def growth_table(method: str) -> list[float] | None:
    """For a method that grows at every Δt on an undamped spring (euler): ρ − 1 per step against
    ω·Δt on a logarithmic grid (GROWTH_DECADES), for the warning's "grows about 1.98 % each step";
    None for the others."""
    if largest_stable_steps(method, np.array([0.0]))[0] != 0.0:
        return None
    steps = np.logspace(*GROWTH_DECADES, (GROWTH_DECADES[1] - GROWTH_DECADES[0]) * GROWTH_PER_DECADE + 1)
    return [float(x) for x in amplification(method, omega=steps, rate=np.zeros_like(steps), dt=1.0) - 1.0]


def stability_data(methods) -> dict:
    """See _stability_data: worked out once a process for each set of methods (the local page's
    Download offline page writes many pages)."""
    return _stability_data(tuple(sorted(methods)))


@functools.lru_cache(maxsize=8)
def _stability_data(methods: tuple) -> dict:
    """The stability judgement of each method the page may use, for the page's script: the table
    L(θ) (inf where any Δt is stable), the growth table of a method that grows at every Δt, the
    method's own rules (limit_rule) and the verdict's sentences."""
    angles = np.linspace(0.0, math.pi / 2, ANGLES)
    tables = {}
    for method in methods:
        limit = largest_stable_steps(method, angles)
        tables[method] = {"limit": [None if not math.isfinite(x) else float(x) for x in limit],
                          "growth": growth_table(method),
                          "rules": {cause: limit_rule(method, cause)
                                    for cause in ("spring", "damping", "drag", "spring and damping",
                                                  "spring and drag", "damping and drag",
                                                  "spring and damping and drag")}}
    return {"methods": tables, "angles": ANGLES, "growth_decades": list(GROWTH_DECADES),
            "growth_per_decade": GROWTH_PER_DECADE, "refused": REFUSED, "causes": CAUSES,
            "past_limit": PAST_LIMIT, "every_dt": EVERY_DT}

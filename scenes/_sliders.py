"""Which constants get a slider, the span and steps of each slider, and how a constant is written.

Every front end that offers a constant to move (the page in the browser, and any page written out
for use without Python) reads these, so a slider is the same wherever it appears. Plain arithmetic
on the declarations in scenes/_constants.py: nothing here imports vpython.
"""
from __future__ import annotations

import math

from physics.rounding import ROUND_STEPS

from ._constants import DECLARED

def slider_names(setup, view: dict, forces=None) -> list[str]:
    """The constants that get a slider, in the order of the scene's constants (its block).

    Each force declares the constants it offers a slider for (`slider=True` in its CONSTANTS:
    "a slider when on"): k, b, C, F0, ω, μ_k get one wherever their force is on, that is in the
    scene's model (`forces`; built from `setup` when not given). So damping's b gets one in
    `vertical` once a preset or --set switches damping on, and a new force's constant gets one in
    every scene with no other edit. A scene adds its own with VIEW["sliders"] (m, x0, Δt, or a
    force's constant it offers while that force is off: the pendulum's b), and a teacher's older
    scene may still name some in VIEW["sliders_when_on"] (a slider where the value is not 0).

    Only plain numbers get one (a vector, or None meaning "derived", does not). Every front end
    that offers sliders (the page, the offline page) calls this one function.
    """
    if forces is None:
        forces = setup.build().forces
    chosen = {name for force in forces for name, declared in getattr(type(force), "CONSTANTS", {}).items()
              if declared.slider}
    chosen |= set(view.get("sliders") or ())
    chosen |= {name for name in view.get("sliders_when_on") or () if setup.values.get(name)}
    return [name for name in setup.constants if name in chosen
            and isinstance(setup.values[name], (int, float)) and not isinstance(setup.values[name], bool)]


def slider_range(name: str, value: float, default: float | None = None) -> tuple[float, float, float]:
    """(min, max, step) around a constant's default: from a tenth of it (or 0) to three times it.

    Constants that must stay positive (m, k, dt, ...) start at a tenth; those where 0 means "off"
    (b, F0, ω, C, g, x0: slider_from_zero in scenes/_constants.py) start at 0. A value outside that range (set by a preset or --set) widens
    it, to one and a half times the value.
    """
    default = value if default is None or not isinstance(default, (int, float)) else default
    declared = DECLARED.get(name)
    low = 0.0 if declared is not None and declared.slider_from_zero else 0.1 * abs(default)
    high = 3.0 * abs(default) if default else 1.0
    low = min(low, value)
    high = max(high, 1.5 * value)
    step = 10 ** math.floor(math.log10((high - low) / 200))
    return low, high, step


def round_slider_values(name: str, value: float, default: float | None = None) -> list[float]:
    """The values a slider with round steps offers (slider_round in scenes/_constants.py: Δt), in
    order; [] for a constant whose slider is continuous.

    Every 1, 2 or 5 × 10ⁿ from slider_range's span (a tenth to three times the default), rounded
    out to such values at both ends, plus the scene's default and the value now (a preset's or
    --set's), so the slider can stand where the run is: Δt = 0.06 s gives 0.005, 0.01, 0.02,
    0.05, 0.06, 0.1, 0.2 s.
    """
    declared = DECLARED.get(name)
    if declared is None or not declared.slider_round or not value > 0:
        return []
    default = float(default) if isinstance(default, (int, float)) and default > 0 else value
    low, high, _ = slider_range(name, value, default)
    low = max(low, declared.low)
    rounds = [float(f"{mantissa * 10.0 ** power:.12g}")
              for power in range(math.floor(math.log10(low)), math.ceil(math.log10(high)) + 1)
              for mantissa in ROUND_STEPS]
    first = max(x for x in rounds if x <= low)       # the span, widened to round values at both ends
    last = min(x for x in rounds if x >= high)
    return sorted({x for x in rounds if first <= x <= last and declared.low <= x <= declared.high} |
                  {default, value})


def symbol(name: str) -> str:
    """How the page writes a constant: ω for omega, ρ for rho (declared in scenes/_constants.py)."""
    declared = DECLARED.get(name)
    return declared.symbol if declared is not None and declared.symbol else name

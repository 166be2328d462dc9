"""What a constant may be: its unit, symbol and range, declared once beside what uses it.

A force declares the constants of its law (physics/forces/: Spring's k and L0, LinearDamping's
b); the scenes declare the rest (m, Δt, a row's spacing) in scenes/_constants.py's DECLARED, which
reads the forces' declarations too. Plain data: numbers and words, no numpy.
"""
from __future__ import annotations

import re
from dataclasses import dataclass


def _short(x: float) -> str:
    """1e+06 -> 1e6, 1e-06 -> 1e-6, 0.5 -> 0.5: a bound as a teacher writes it."""
    return re.sub(r"e([+-])0*(\d)", lambda m: "e" + ("-" if m[1] == "-" else "") + m[2], f"{x:g}")


@dataclass(frozen=True)
class Declared:
    """One constant, as every scene has it: its unit and symbol, and what values it may take.

    unit      its SI unit ("1" for a pure number), as the scene files' comments write it
    symbol    how the page writes it (ω, ρ); "" means its name
    vector    three numbers (a position, a velocity, a direction) rather than one
    low, high every number it (or each component) may take lies from `low` to `high`; `above_low`
              leaves `low` itself out (m > 0). Wide for teaching, narrow enough that the products
              the forces take, m·g, k·(|L| − L0), b·v, ½ρCA|v|², stay far from floating-point
              overflow (10³⁰⁸) and Δt far from round-off (10⁻¹⁶ of t).
    whole     a whole number (a count); `nonzero`: a vector of non-zero length (a direction)
    note      added to the range in the message
    none      what None means, where a scene file may write it instead of a number ("" if it may not)
    meaning   what it is, in a few words, where a program or a list names it without a scene's comment
    slider    a slider when on: wherever its force is on (in the scene's model), the page offers a
              slider for it (scenes/_sliders.py slider_names): k, b, C, F0, ω, μ_k. A new force's
              constant declared so gets its slider in every scene with no other edit
    slider_from_zero  a slider for it starts at 0, where 0 switches its force off (b, F0, ω, ...);
              otherwise at a tenth of its default (m, k, Δt must stay positive)
    slider_round  a slider for it gives only round values, 1, 2 or 5 × 10ⁿ, and the scene's
              default (Δt: so that t reads 0.1, 0.2, 0.3 s, not 8.4645 s)
    numerical  how a run is computed (Δt, the question time), not the physical case: a scenario
              preset, which sets its whole case, leaves it as chosen
    default   a force's constant: the value a scene with no line for it takes (None: it has none)
    switch    the default switches its force off (b = 0: no damping; F0 = 0: no drive)
    """

    unit: str
    low: float
    high: float
    symbol: str = ""
    vector: bool = False
    above_low: bool = False
    whole: bool = False
    nonzero: bool = False
    note: str = ""
    none: str = ""
    slider: bool = False
    slider_from_zero: bool = False
    slider_round: bool = False
    numerical: bool = False
    meaning: str = ""
    default: object = None
    switch: bool = False

    def allows(self, value) -> bool:
        numbers = value if isinstance(value, tuple) else (value,)
        inside = all((x > self.low if self.above_low else x >= self.low) and x <= self.high
                     and (not self.whole or x == int(x)) for x in numbers)
        return inside and (not self.nonzero or max(abs(x) for x in numbers) >= NONZERO)

    @staticmethod
    def too_small(value) -> bool:
        """Whether a number is nonzero but below SMALLEST in size: round-off, not a value to
        compute with (k = 1e-320 N/m makes the stretch m·g/k overflow)."""
        numbers = value if isinstance(value, tuple) else (value,)
        return any(0 < abs(x) < SMALLEST for x in numbers)

    def words(self, unit: str = "", *, vector: bool = False) -> str:
        """`from 0 to 1e6 N/m`, `greater than 0 and at most 1e6 kg`, `a whole number from 2 to 10000`."""
        unit = f" {unit}" if unit and unit != "1" else ""
        low, high = _short(self.low), _short(self.high)
        span = (f"greater than {low} and at most {high}{unit}" if self.above_low
                else f"from {low} to {high}{unit}")
        if self.whole:
            span = f"a whole number {span}"
        if vector:
            span = f"three numbers, each {span}"
            if self.nonzero:
                span += f", not all near 0 (the largest at least {_short(NONZERO)})"
        return f"{span} ({self.note})" if self.note else span


NONZERO = 1e-6  # a direction's largest component must be at least this, so its length is not round-off
SMALLEST = 1e-9  # any number given is 0 or at least this in size

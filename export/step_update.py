"""One step of the momentum update written out with its numbers, as the page's notation has it.

    F_net = < 0, -78, 0 > N
    p_f = p_i + F_net Δt = < 0, 0, 0 > + < 0, -7.8, 0 >
        = < 0, -7.8, 0 > kg·m/s
    v_f = p_f / m = < 0, -0.78, 0 > m/s
    r_f = r_i + v_f Δt = < 0, -1.5, 0 > + < 0, -0.078, 0 >
        = < 0, -1.578, 0 > m

The command line's step table (`--steps`, reports/headless.py) and the page's Step read-out
(browser/) both write numbers through :func:`number` and :func:`vector`, after the same rounding
to 15 significant digits (:func:`cleaned`), so the two agree digit for digit.
"""
from __future__ import annotations

import math
import re
import textwrap

import numpy as np

from physics.forces import net_force
from physics.integrators import INTEGRATORS
from physics.state import velocity

from .number_blocks import clean_array, float_block
from .numbers import clean, clean_time

SIGNIFICANT = 6
RULE_WIDTH = 90      # characters a line of the rule in words takes before it wraps
NO_VALUE = "(no value)"  # what a quantity that overflowed or is undefined prints instead of inf or nan


def number(x: float, digits: int = SIGNIFICANT) -> str:
    """x to `digits` significant figures, with no '-0'; NO_VALUE for inf and nan."""
    if not math.isfinite(float(x)):
        return NO_VALUE
    text = f"{float(x):.{digits}g}"
    return "0" if text in ("-0", "0", "-0.0") else text


def vector(v, unit: str = "", digits: int = SIGNIFICANT) -> str:
    """`< 0, -1.73088, 0 > m`: components far below the vector's size (round-off) show as 0."""
    v = np.asarray(v, dtype=float)
    size = float(np.max(np.abs(v))) if v.size else 0.0
    shown = np.where(np.abs(v) < 1e-12 * size, 0.0, v)
    text = "< " + ", ".join(number(c, digits) for c in shown) + " >"
    return f"{text} {unit}".rstrip()


def cleaned(value):
    """Every float in a JSON-ready structure to 15 significant digits (export/numbers.py's clean).

    A list of floats (or of lists of floats) is cleaned as one array (export/number_blocks.py).
    """
    if isinstance(value, float):
        return clean(value) if math.isfinite(value) else value
    if isinstance(value, dict):
        return {key: cleaned(item) for key, item in value.items()}
    if isinstance(value, list):
        block = float_block(value)
        if block is not None:
            return clean_array(block).tolist()
        return [cleaned(item) for item in value]
    return value


def update_force(forces, methods, *, t_i: float, r_i, p_i, p_f, m, dt: float) -> np.ndarray:
    """The F_net each mass's method used for its momentum update, (N, 3) N, so p_f = p_i + F_net Δt.

    Euler-Cromer (the page) and Euler kick once, with the force at the start of the step,
    F(t_i, r_i, v_i); the other methods' F_net is their average force (p_f − p_i)/Δt.
    """
    at_start = np.array([INTEGRATORS[name].kicks_once for name in methods])[:, None]
    F_start = net_force(forces, t_i, r_i, velocity(p_i, m), m)
    return np.where(at_start, F_start, (np.asarray(p_f) - np.asarray(p_i)) / dt)


def shown(v, unit: str = "") -> str:
    """A vector as the step table writes it: rounded to 15 digits, then to SIGNIFICANT."""
    return vector(cleaned(np.asarray(v, dtype=float).tolist()), unit)


STEP_SLOTS = ("t", "F_net", "p_i", "impulse", "p_f", "v_f", "r_i", "drift", "r_f")
SLOT = re.compile(r"\{(" + "|".join(STEP_SLOTS) + r")\}")


def step_layout(method: str) -> tuple[list[str], str]:
    """One mass's step as the page writes it, with a {slot} where each number goes, and the
    velocity the method moves the mass with ("v_f" or "v_i": the `drift` slot is that velocity Δt).

    The slots (STEP_SLOTS) are t (s), F_net (the force of the update, N), p_i, impulse (F_net Δt),
    p_f, v_f (p_f / m), r_i, drift and r_f: :func:`step_lines` fills them here, and the offline page
    (export/offline_page.py) fills the same layout in the browser.
    """
    kicks_once = INTEGRATORS[method].kicks_once
    lines = [f"t = {{t}} s, {method}:",
             *textwrap.wrap(INTEGRATORS[method].rule, RULE_WIDTH, break_on_hyphens=False),
             ("F_net = " if kicks_once else "F_net = (p_f − p_i)/Δt, its average force = ") + "{F_net} N",
             "p_f = p_i + F_net Δt = {p_i} + {impulse}",
             "    = {p_f} kg·m/s",
             "v_f = p_f / m = {v_f} m/s"]
    if method == "euler-cromer":
        return lines + ["r_f = r_i + v_f Δt = {r_i} + {drift}", "    = {r_f} m"], "v_f"
    if method == "euler":
        return lines + ["r_f = r_i + v_i Δt = {r_i} + {drift}", "    = {r_f} m"], "v_i"
    return lines + ["r_f = {r_f} m (from r_i = {r_i} m, as the rule above says)"], "v_f"


def step_lines(*, method: str, dt: float, t_f: float, m: float, F_net, p_i, p_f, r_i, r_f) -> list[str]:
    """One mass's step, in words and numbers: F_net, then p_f, v_f and r_f as the method finds them.

    F_net, p_f, v_f and r_f are written as `--steps` writes them, digit for digit.
    """
    layout, drift = step_layout(method)
    v = {"v_f": velocity(np.asarray(p_f, float)[None], np.array([m]))[0],
         "v_i": velocity(np.asarray(p_i, float)[None], np.array([m]))[0]}
    values = {"t": number(clean_time(t_f, dt)), "F_net": shown(F_net), "p_i": shown(p_i),
              "impulse": shown(np.asarray(F_net, float) * dt), "p_f": shown(p_f), "v_f": shown(v["v_f"]),
              "r_i": shown(r_i), "drift": shown(v[drift] * dt), "r_f": shown(r_f)}
    return [SLOT.sub(lambda slot: values[slot[1]], line) for line in layout]

"""The resonance curve: steady-state amplitude against driving frequency, for a row of driven springs.

A row of identical damped springs hangs from the ceiling; each is driven by F = F0 cos(ω t) (up and
down) at its own ω, from omega_min on the left to omega_max on the right. After the start-up
transient has died away (it decays like e^(−bt/2m)), each mass swings at its driving frequency
with the steady-state amplitude

    A(ω) = F0 / √((k − m ω²)² + (b ω)²)

largest near ω0 = √(k/m), and the smaller b, the taller and narrower the peak. With b² ≥ 2mk there
is no peak at all (the preset "critical damping", b = 2√(mk), shows this).

:func:`sweep` runs the whole batch, one oscillator per (b, ω) pair, as ONE state of N masses stepped
together in numpy (the forces take per-mass b and ω), and measures each amplitude over the last few
periods of the slowest oscillator. The view shows the row for the first b; :func:`extra_json` gives
the measured and exact curves for headless --json.
"""
from typing import NamedTuple

import numpy as np

from physics.exact import critical_damping, steady_state_amplitude
from physics.forces import Driving, Gravity, LinearDamping, Spring
from physics.integrators import INTEGRATORS
from physics.simulate import steps_to_reach
from physics.state import make_state

from .constants import DECLARED, ConstantError
from .model import Model
from .row import anchors_in_a_row, exact_row, start_positions

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
m = 1.0                    # kg: mass of each block
k = 25.0                   # N/m: spring constant of each spring (ω0 = √(k/m) = 5 rad/s)
L0 = 1.0                   # m: relaxed length of each spring
g = 9.8                    # m/s²: strength of gravity, acting along −y (it only moves the equilibrium)
F0 = 1.0                   # N: driving force amplitude in F = F0 cos(ω t), up and down
b = 0.5                    # kg/s: damping constant of the row shown (None: critical, b = 2√(mk))
b_ratio = 2.0              # 1: each further resonance curve has b times this
curves = 3                 # 1: number of resonance curves (damping constants b, b·ratio, b·ratio², …)
omega_min = 2.0            # rad/s: driving angular frequency of the leftmost spring
omega_max = 8.0            # rad/s: driving angular frequency of the rightmost spring
count = 25                 # 1: number of springs in the row (driving frequencies per curve)
spacing = 0.4              # m: distance between neighbouring anchors along x
settle = 40.0              # s: time for the transient to die away before measuring
periods = 3.0              # 1: periods of the slowest driving frequency over which to measure
dt = 0.02                  # s: time step Δt
until = 50.0               # s: how long the row runs in the view and headless
# ---- end of constants ----

DRIVE_AXIS = (0.0, 1.0, 0.0)   # F0 cos(ω t) acts up and down, along the springs
SMOOTH_POINTS = 401            # ω values on which extra_json gives the exact curves as lines
SWEEP_INTEGRATOR = "rk4"       # fourth order, so amplitude errors stay far below 1 % at the default Δt


class Sweep(NamedTuple):
    """A measured resonance curve per damping constant.

    omega      driving angular frequencies, (count,) rad/s
    b          damping constants, (curves,) kg/s
    amplitude  measured steady-state amplitudes, (curves, count) m
    exact      F0 / √((k − mω²)² + (bω)²), (curves, count) m
    """

    omega: np.ndarray
    b: np.ndarray
    amplitude: np.ndarray
    exact: np.ndarray


def _whole(name, value, least):
    if value != int(value) or value < least:
        raise ConstantError(f"{name} must be a whole number, {least} or more (got {value:g})")
    return int(value)


def frequency_grid(*, omega_min, omega_max, count) -> np.ndarray:
    """count driving angular frequencies evenly spaced from omega_min to omega_max, rad/s."""
    count = _whole("count", count, 2)
    if not 0 < omega_min < omega_max:
        raise ConstantError(f"need 0 < omega_min < omega_max (got {omega_min:g} and {omega_max:g} rad/s)")
    return np.linspace(omega_min, omega_max, count)


def damping_values(*, m, k, b, b_ratio, curves) -> np.ndarray:
    """b, b·ratio, b·ratio², … (curves of them), kg/s; b = None means critical, 2√(mk)."""
    if b_ratio <= 0:
        raise ConstantError(f"b_ratio must be greater than 0 (got {b_ratio:g})")
    b = critical_damping(m=m, k=k) if b is None else b
    values = b * b_ratio ** np.arange(_whole("curves", curves, 1), dtype=float)
    largest = DECLARED["b"].high
    if not values[-1] <= largest:  # b·ratio^(curves − 1) must stay a damping constant b may be
        raise ConstantError(f"b_ratio = {b_ratio:g} over {curves:g} curves makes the last b = "
                            f"{values[-1]:.3g} kg/s, more than the {largest:g} kg/s b may be; "
                            f"use a smaller b_ratio or fewer curves")
    return values


def _driven_row(*, m, k, L0, g, F0, b, omega, spacing):
    """Anchors, start positions (at rest at equilibrium) and forces of one driven spring per ω."""
    anchors = anchors_in_a_row(count=len(omega), spacing=spacing)
    r0 = start_positions(anchors=anchors, L0=L0, m=m, k=k, g=g, x0=0.0)
    forces = [Spring(k=k, L0=L0, anchor=anchors), LinearDamping(b=b),
              Driving(F0=F0, omega=omega, axis=DRIVE_AXIS)]
    if g:
        forces.append(Gravity(g=g))
    return anchors, r0, tuple(forces)


def sweep(*, m, k, L0, g, F0, b, b_ratio, curves, omega_min, omega_max, count, settle, periods, dt,
          **_view_only) -> Sweep:
    """Run every (b, ω) oscillator together to steady state and measure its amplitude.

    One state holds curves × count masses; each step is one numpy update of all of them. After
    `settle`, each amplitude is the largest value over `periods` periods of the slowest drive
    (2π/omega_min) of

        A = √(x² + (v/ω)²),   x = y − y_eq the displacement from equilibrium, v its velocity,

    which for a steady swing x = A cos(ωt − δ) equals A at every instant (cos² + sin² = 1), so
    the answer does not depend on catching the sampled peak; any transient left makes it wobble.
    """
    if settle < 0 or periods <= 0:
        raise ConstantError(f"need settle ≥ 0 s and periods > 0 (got {settle:g} s and {periods:g})")
    omega = frequency_grid(omega_min=omega_min, omega_max=omega_max, count=count)
    b_each = damping_values(m=m, k=k, b=b, b_ratio=b_ratio, curves=curves)
    omega_all, b_all = np.tile(omega, len(b_each)), np.repeat(b_each, len(omega))
    _, r0, forces = _driven_row(m=m, k=k, L0=L0, g=g, F0=F0, b=b_all, omega=omega_all, spacing=0.0)
    y_eq = r0[:, 1]
    step = INTEGRATORS[SWEEP_INTEGRATOR]
    state = make_state(r=r0, m=m)
    for _ in range(steps_to_reach(settle, dt)):
        state = step(state, forces, dt)
    amplitude = np.zeros(len(omega_all))
    for _ in range(steps_to_reach(periods * 2 * np.pi / omega_min, dt)):
        state = step(state, forces, dt)
        x, v = state.r[:, 1] - y_eq, state.v[:, 1]
        amplitude = np.maximum(amplitude, np.sqrt(x**2 + (v / omega_all) ** 2))
    if not np.all(np.isfinite(amplitude)):
        raise ConstantError(f"the resonance sweep blew up: dt = {dt:g} s is too large for ω up to "
                            f"{max(omega_max, np.sqrt(k / m)):.3g} rad/s")
    shape = (len(b_each), len(omega))
    exact = steady_state_amplitude(m=m, k=k, b=b_all, F0=F0, omega=omega_all)
    return Sweep(omega=omega, b=b_each, amplitude=amplitude.reshape(shape), exact=exact.reshape(shape))


def build(*, m, k, L0, g, F0, b, b_ratio, curves, omega_min, omega_max, count, spacing, settle,
          periods, dt, until):
    """The row shown: one driven, damped spring per ω of the grid, all with the first b."""
    omega = frequency_grid(omega_min=omega_min, omega_max=omega_max, count=count)
    b_row = damping_values(m=m, k=k, b=b, b_ratio=b_ratio, curves=curves)[0]
    anchors, r0, forces = _driven_row(m=m, k=k, L0=L0, g=g, F0=F0, b=b_row, omega=omega, spacing=spacing)
    return Model(
        state=make_state(r=r0, m=m),
        forces=forces,
        dt=float(dt),
        until=float(until),
        exact=exact_row(anchors=anchors, r0=r0, m=m, k=k, L0=L0, g=g, b=b_row, F0=F0, omega=omega,
                        drive_axis=DRIVE_AXIS),
        anchors=anchors,
        labels=tuple(f"ω = {w:.3g} rad/s" for w in omega),
    )


def extra_json(setup) -> dict:
    """The resonance curves for headless --json: the ω grid, and measured and exact amplitudes per b.

    The exact curves are also given on a fine grid ("smooth_..."), for drawing them as lines.
    """
    v = setup.values
    result = sweep(**v)
    smooth = np.linspace(v["omega_min"], v["omega_max"], SMOOTH_POINTS)
    return {"resonance": {
        "omega_rad_per_s": result.omega.tolist(),
        "b_kg_per_s": result.b.tolist(),
        "amplitude_m": result.amplitude.tolist(),
        "exact_amplitude_m": result.exact.tolist(),
        "smooth_omega_rad_per_s": smooth.tolist(),
        "smooth_exact_amplitude_m": [steady_state_amplitude(m=v["m"], k=v["k"], b=b_j, F0=v["F0"], omega=smooth).tolist()
                                     for b_j in result.b],
    }}


CURVE_COLOURS = [(0.1, 0.3, 0.9), (0.85, 0.1, 0.1), (0.1, 0.6, 0.1), (0.6, 0.2, 0.8), (0.5, 0.5, 0.5)]
ROW_COLOUR = (1.0, 0.55, 0.1)  # the live dots: the row shown in 3-D (orange)


def view_graph(setup) -> dict:
    """The page's resonance graph (scenes/view.py): amplitude against driving frequency.

    For each b: the exact A(ω) = F0/√((k − mω²)² + (bω)²) as a line, and the amplitudes :func:`sweep`
    measured in its numpy batch as dots of the same colour. On top, the row shown in 3-D (the first
    b): each spring's A = √(x² + (v/ω)²) at this instant, as orange dots that wobble while the
    start-up transient lasts and settle onto the first curve as it dies away (like e^(−bt/2m)).
    """
    v = setup.values
    result = sweep(**v)
    smooth = np.linspace(v["omega_min"], v["omega_max"], SMOOTH_POINTS)
    lines, dots = [], []
    for j, b_j in enumerate(result.b):
        colour = CURVE_COLOURS[j % len(CURVE_COLOURS)]
        exact = steady_state_amplitude(m=v["m"], k=v["k"], b=b_j, F0=v["F0"], omega=smooth)
        lines.append((f"b = {b_j:.3g} kg/s", smooth, exact, colour))
        dots.append(("", result.omega, result.amplitude[j], colour))
    top = float(max(np.max(line[2]) for line in lines))
    omega = result.omega

    def live(model, state):
        x = state.r[:, 1] - model.state.r[:, 1]   # the row starts at rest at equilibrium
        return omega, np.sqrt(x**2 + (state.v[:, 1] / omega) ** 2)

    return {"title": f"Amplitude: lines exact, dots measured after {v['settle']:g} s",
            "xtitle": "driving angular frequency ω (rad/s)", "ytitle": "amplitude A (m)",
            "xmin": float(v["omega_min"]), "xmax": float(v["omega_max"]), "ymin": 0.0, "ymax": 1.15 * top,
            "lines": lines, "dots": dots,
            "live": live, "live_label": "3-D row, now", "live_colour": ROW_COLOUR}


PRESETS = {"critical damping": {"b": None}}

# The resonance curve itself is sweep(); the row's 25 exact curves would only crowd the graph.
VIEW = {"support": "ceiling", "plot": "y", "trail": False, "exact": False, "sliders": ["b", "F0", "m", "k"]}

"""Linear damping versus quadratic air drag: two identical balls on springs, released together.

Both balls (a volleyball: 0.27 kg, radius 0.1 m) hang on identical springs and start from the same
stretch. The left one feels linear damping, the right one the air drag of the page:

    linear     F = −b v                  the amplitude shrinks by the same FACTOR every period,
                                         e^(−bT/2m), whatever the amplitude: an exponential decay;
    quadratic  F = −½ C A ρ |v| v        the force grows as speed squared, so a large swing loses
                                         amplitude fast and a small one hardly at all: the amplitude
                                         falls like 1/(1/A0 + (4/3)(CAρ/m) n) after n periods.

b is matched so that both lose the same energy in their first period: per period linear damping
takes π b ω A² and quadratic drag (8/3)(½CAρ) ω² A³, equal when b = (8/3π)(½CAρ) ω A0.
The linear one has its exact curve (physics.exact.oscillator); quadratic drag has no closed form,
so its exact entries are NaN, meaning "not known".

With k = 0 (the preset "falling, no spring") the balls fall instead, and each reaches its terminal
speed, where drag balances gravity: v_t = m g / b for linear damping, v_t = √(2 m g / (C A ρ)) for
quadratic drag, approached as v_t (1 − e^(−bt/m)) and v_t tanh(g t / v_t).
"""
import numpy as np

from physics.forces import Gravity, LinearDamping, QuadraticDrag, Spring
from physics.state import make_state

from ._model import Model
from ._row import anchors_in_a_row, exact_row, row_anchors, row_loop, row_starts, start_positions

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
m = 0.27                   # kg: mass of each ball (a volleyball)
k = 10.0                   # N/m: spring constant of each spring
L0 = 1.0                   # m: relaxed length of each spring
g = 9.8                    # m/s²: strength of gravity, acting along −y (it only moves the equilibrium)
b = 0.0229                 # kg/s: linear damping constant of the left ball, in F = −b v
C = 0.47                   # 1: drag coefficient of the right ball (a sphere), in F = −½ C A ρ |v| v
A = 0.0314                 # m²: cross-section area of the right ball, π r²
rho = 1.2                  # kg/m³: density of air at room temperature
x0 = 0.5                   # m: start stretch below equilibrium, the same for both
spacing = 1.0              # m: distance between the two anchors along x
dt = 0.005                 # s: time step Δt of the momentum update
until = 30.0               # s: how long to run
# ---- end of constants ----

MENU_ORDER = 5               # where it stands in --list and the page's scene menu

PRESETS = {
    "falling, no spring": {"k": 0.0, "b": 0.153},
}
# The docstring's first line tells of springs; a case with these constants is told this way instead.
SUMMARIES = [
    ({"k": 0.0}, "Linear damping versus quadratic air drag: two identical balls, on no spring (k = 0), "
                 "fall side by side, each toward its terminal speed."),
]


def matched_b(*, m, k, C, A, rho, x0) -> float:
    """b = (8/3π)(½CAρ) ω0 x0: the linear damping that takes the same energy in the first period, kg/s."""
    return 8.0 / (3.0 * np.pi) * 0.5 * C * A * rho * np.sqrt(k / m) * x0


def build(*, m, k, L0, g, b, C, A, rho, x0, spacing, dt, until):
    """Two hanging balls: linear damping on the left, quadratic drag on the right."""
    anchors = anchors_in_a_row(count=2, spacing=spacing)
    r0 = start_positions(anchors=anchors, L0=L0, m=m, k=k, g=g, x0=x0)
    forces = [
        Spring(k=k, L0=L0, anchor=anchors),
        LinearDamping(b=np.array([b, 0.0])),
        QuadraticDrag(C=np.array([0.0, C]), A=A, rho=rho),
    ]
    if g:
        forces.append(Gravity(g=g))
    return Model(
        state=make_state(r=r0, m=m),
        forces=tuple(forces),
        dt=float(dt),
        until=float(until),
        **exact_row(forces=forces, r0=r0, m=m),
        anchors=anchors,
        labels=(f"linear, b = {b:.3g} kg/s", f"quadratic, ½CAρ = {0.5 * C * A * rho:.3g} kg/m"),
        per_mass=row_loop(count=2).then(row_anchors(row_loop(count=2), count=2), row_starts(k=k)),
    )


# The quadratic ball's exact entries are NaN (no closed form): headless and --plot skip them, but the
# browser graphs would be sent NaN, so the browser shows no exact curves here.
VIEW = {"support": "ceiling", "plot": "y", "trail": False, "exact": False, "sliders": ["m", "x0"]}

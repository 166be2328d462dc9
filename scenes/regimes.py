"""The page's damping figure: under-, critically and over-damped oscillators released side by side.

Three identical masses hang on identical springs and start from the same stretch, at rest. Only the
damping constant b in F = −b v differs. Critical damping is b_c = 2√(mk) (b² = 4mk):

- under-damped (b < b_c): still oscillates, inside an envelope e^(−bt/2m);
- critically damped (b = b_c): the fastest return to equilibrium without crossing it;
- over-damped (b > b_c): no oscillation, but a slow creep back, slower the larger b.

The middle oscillator's b is a constant, critical by default (8 kg/s = 2√(mk) for the default m and
k), so a teacher can slide it through the three regimes. b = None means "critical for whatever m
and k are", and the preset "critical damping" sets b = 2√(mk) for the m and k of the moment
(scenes/_catalog.py). The other two are fixed
fractions and multiples of b_c. Each curve has its exact solution from physics.exact.oscillator.
"""
import numpy as np

from physics.exact import critical_damping, damping_regime
from physics.forces import Gravity, LinearDamping, Spring
from physics.state import make_state

from ._constants import ConstantError
from ._model import Model
from ._row import MassList, anchors_in_a_row, exact_row, row_anchors, row_loop, row_starts, start_positions

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
m = 1.0                    # kg: mass of each block
k = 16.0                   # N/m: spring constant of each spring
L0 = 1.0                   # m: relaxed length of each spring
g = 9.8                    # m/s²: strength of gravity, acting along −y (it only moves the equilibrium)
b = 8.0                    # kg/s: damping of the middle oscillator, critical 2√(mk) (None: recompute that)
under_fraction = 0.1       # 1: b of the under-damped one, as a fraction of 2√(mk)
over_multiple = 4.0        # 1: b of the over-damped one, as a multiple of 2√(mk)
x0 = 0.5                   # m: start stretch below equilibrium, the same for all three
spacing = 1.0              # m: distance between neighbouring anchors along x
dt = 0.01                  # s: time step Δt of the momentum update
until = 8.0                # s: how long to run
# ---- end of constants ----

MENU_ORDER = 4               # where it stands in --list and the page's scene menu



def damping_constants(*, m, k, b, under_fraction, over_multiple) -> np.ndarray:
    """b of the three oscillators, kg/s: under_fraction·b_c, b (or b_c), over_multiple·b_c."""
    for name, value in (("under_fraction", under_fraction), ("over_multiple", over_multiple)):
        if value < 0:
            raise ConstantError(f"{name} must be 0 or more (got {value:g}): a negative b would feed energy in")
    b_c = critical_damping(m=m, k=k)
    return np.array([under_fraction * b_c, b_c if b is None else b, over_multiple * b_c])


def damping_list(*, b) -> MassList:
    """damping_constants as the program writes it, with b_c = 2√(mk) as critical_damping works it out."""
    middle = "b_c" if b is None else "b"
    return MassList("b", whole=f"[under_fraction*b_c, {middle}, over_multiple*b_c]",
                    before=(("b_c = 2*sqrt(m*k)", "kg/s: critical damping, 2√(mk)"),))


def build(*, m, k, L0, g, b, under_fraction, over_multiple, x0, spacing, dt, until):
    """Three hanging oscillators, identical but for their damping constants."""
    b_each = damping_constants(m=m, k=k, b=b, under_fraction=under_fraction, over_multiple=over_multiple)
    anchors = anchors_in_a_row(count=3, spacing=spacing)
    # x0 is a stretch below equilibrium: along û = −y that is +x0.
    r0 = start_positions(anchors=anchors, L0=L0, m=m, k=k, g=g, x0=x0)
    loop = row_loop(count=3)
    per_mass = loop.then(row_anchors(loop, count=3), row_starts(k=k), damping_list(b=b))
    forces = [Spring(k=k, L0=L0, anchor=anchors), LinearDamping(b=b_each)]
    if g:
        forces.append(Gravity(g=g))
    return Model(
        state=make_state(r=r0, m=m),
        forces=tuple(forces),
        dt=float(dt),
        until=float(until),
        **exact_row(forces=forces, r0=r0, m=m),
        anchors=anchors,
        labels=tuple(f"{damping_regime(m=m, k=k, b=b_i)} (b = {b_i:.3g} kg/s)" for b_i in b_each),
        per_mass=per_mass,
    )


# hold: all three settle within a few seconds; a scrolling graph would leave only flat lines.
VIEW = {"support": "ceiling", "plot": "y", "trail": False, "exact": True, "sliders": ["m", "x0"],
        "hold": True}

"""Friction against damping: the same spring on an air track with damping, and on a table with sliding friction.

Two identical blocks on identical horizontal springs start from the same stretch and swing side
by side. The bottom one slides on a table: kinetic friction F = −μ_k N v̂ (N = m g) is the same size
whatever the speed, so it takes the same AMOUNT off every swing,

    4 μ_k m g / k  per period      (each half swing is an undamped oscillation about a centre
                                    moved by ±μ_k m g/k, towards the side the block comes from)

and the peaks fall on a straight line until the block stops, somewhere in the dead band
|x| ≤ μ_s m g/k around the relaxed length, where static friction holds it for good. The top one
rides an air track with linear damping F = −b v, which grows with the speed, so it takes the same
FRACTION off every swing: the peaks fall on an exponential, e^(−bt/2m), and never quite reach 0.

b is chosen so that both swings have halved at the same time, 12.5 s (b = 2 m ln 2 / 12.5 s =
0.0555 kg/s for the default m, k, μ_k and x0): before then damping takes more (a fraction of a big
swing is a lot), after it friction does (the same amount of a small swing is a lot), and the
friction block stops at about 25 s while the damped one swings on. The friction curve is drawn on
top. The damped block has its exact curve (physics.exact.oscillator); the friction block has none
(each half swing has one, but the whole run does not), so its exact entries are NaN, "not known".
"""
from physics.forces import LinearDamping, Spring
from physics.forces.friction import Friction
from physics.state import make_state

from ._model import Model
from ._row import anchors_in_a_row, exact_row, row_anchors, row_loop, row_starts, start_positions

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
m = 0.5                    # kg: mass of each block (a lab cart)
k = 20.0                   # N/m: spring constant of each spring
L0 = 1.0                   # m: relaxed length of each spring
g = 9.8                    # m/s²: strength of gravity: the load N = m g on the table (the table holds the block up)
mu_k = 0.02                # 1: kinetic friction coefficient of the bottom block, F = −μ_k N v̂
mu_s = 0.06                # 1: static friction coefficient of the bottom block (at rest it stays while |kx| ≤ μ_s N)
b = 0.0555                 # kg/s: linear damping constant of the top block, F = −b v
x0 = 0.5                   # m: start stretch beyond the relaxed length, the same for both
spacing = 0.8              # m: distance between the two springs, down the wall
dt = 0.01                  # s: time step Δt of the momentum update
until = 30.0               # s: how long to run
# ---- end of constants ----

MENU_ORDER = 5.5               # where it stands in --list and the page's scene menu

ALONG_WALL = (0.0, -1.0, 0.0)   # the springs, one above the other on the wall
OUT_OF_WALL = (1.0, 0.0, 0.0)   # each sticks out of it along x
_ROW = row_loop(count=2)


def build(*, m, k, L0, g, mu_k, mu_s, b, x0, spacing, dt, until):
    """Two horizontal springs: linear damping on the top block, sliding friction on the bottom one."""
    anchors = anchors_in_a_row(count=2, spacing=spacing, along=ALONG_WALL)
    r0 = start_positions(anchors=anchors, direction=OUT_OF_WALL, L0=L0, m=m, k=k, g=0.0, x0=x0)
    forces = (Spring(k=k, L0=L0, anchor=anchors),
              Friction(mu_k=[0.0, mu_k], mu_s=[0.0, mu_s], g=g),
              LinearDamping(b=[b, 0.0]))
    return Model(
        state=make_state(r=r0, m=m),
        forces=forces,
        dt=float(dt),
        until=float(until),
        **exact_row(forces=forces, r0=r0, m=m),
        anchors=anchors,
        labels=(f"damping, b = {b:.3g} kg/s", f"friction, μ_k = {mu_k:.3g}"),
        per_mass=_ROW.then(row_anchors(_ROW, count=2, along=ALONG_WALL), row_starts(direction=OUT_OF_WALL, k=k)),
    )


# The friction block's exact entries are NaN (no closed form): the browser shows no exact curves here.
# hold: the graph keeps the whole 30 s from the release, so both envelopes show from their start.
VIEW = {"support": "wall", "plot": "x", "trail": False, "exact": False, "hold": True,
        "sliders": ["x0"], "arrows": ("p", "F_net")}

"""Four ways to step one spring: euler, euler-cromer, verlet and rk4 side by side with the exact motion.

Four identical masses on identical springs (on a wall, no gravity, no damping) start from the same
stretch. Each is advanced by a different integrator with the same Δt (physics/integrators.py):

- euler moves the mass with the OLD velocity, r_f = r_i + v_i Δt: every step multiplies the energy
  by about 1 + (ω Δt)², so the swing grows by about e^(π ω Δt) each period, at every Δt;
- euler-cromer is the page's update, r_f = r_i + v_f Δt: its energy wobbles but stays bounded;
- verlet (second order) wobbles much less; rk4 (fourth order) stays on the exact curve.

The exact motion is x(t) = x0 cos(ω t), with ω = √(k/m). The default Δt makes ω Δt = 0.3 so that the
difference shows within a few periods; shrink dt and the four curves close up.
"""
from physics.forces import Spring
from physics.state import make_state

from ._model import Model
from ._row import anchors_in_a_row, exact_row, row_anchors, row_loop, row_starts, start_positions

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
m = 1.0                    # kg: mass of each block
k = 25.0                   # N/m: spring constant of each spring
L0 = 1.0                   # m: relaxed length of each spring
x0 = 0.15                  # m: start stretch beyond the relaxed length, the same for all four
spacing = 0.6              # m: distance between neighbouring anchors, down the wall
dt = 0.06                  # s: time step Δt, the same for all four
until = 3.0                # s: how long to run
# ---- end of constants ----

MENU_ORDER = 7               # where it stands in --list and the page's scene menu

METHODS = ("euler", "euler-cromer", "verlet", "rk4")
ALONG_WALL = (0.0, -1.0, 0.0)   # the anchors go down the wall
OUT_OF_WALL = (1.0, 0.0, 0.0)   # the springs stick out of it
_ROW = row_loop(count=len(METHODS))


def build(*, m, k, L0, x0, spacing, dt, until):
    """Four horizontal springs on a wall, each stepped by its own integrator."""
    anchors = anchors_in_a_row(count=len(METHODS), spacing=spacing, along=ALONG_WALL)
    r0 = start_positions(anchors=anchors, direction=OUT_OF_WALL, L0=L0, m=m, k=k, g=0.0, x0=x0)
    forces = (Spring(k=k, L0=L0, anchor=anchors),)
    return Model(
        state=make_state(r=r0, m=m),
        forces=forces,
        dt=float(dt),
        until=float(until),
        **exact_row(forces=forces, r0=r0, m=m),
        anchors=anchors,
        labels=METHODS,
        integrators=METHODS,
        may_run_away=(METHODS.index("euler"),),
        per_mass=_ROW.then(row_anchors(_ROW, count=len(METHODS), along=ALONG_WALL),
                           row_starts(direction=OUT_OF_WALL, k=k)),
    )


# A short window: over 30 s the four curves (period 1.26 s) merged into one band. Beside it, each
# method's error on a log scale over 30 s: its order and how it grows.
VIEW = {"support": "wall", "plot": "x", "trail": False, "exact": True, "sliders": ["m", "dt"], "window": 8.0,
        "error": 30.0}

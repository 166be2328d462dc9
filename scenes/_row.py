"""A row of independent oscillators side by side: where their springs are fixed, where each mass
rests, and their exact motion.

Scenes that compare oscillators (the damping regimes, two drag laws, four integrators, a resonance
sweep) give every mass its own spring and anchor. The masses never act on each other, so each one
moves like the single mass of the page, and the row's exact motion is the single-mass closed form
(physics.exact.single_mass_motion) for each mass, stacked.

Each spring points from its anchor along a unit vector û (straight down for a hanging spring,
along +x for a spring on a wall). With gravity g along −y, the spring's length at equilibrium is

    s_eq = L0 + m g (ĝ·û) / k

and a mass started at s_eq + x0 along û, with its velocity along û, stays on that line.
"""
from __future__ import annotations

import numpy as np

from physics.exact import single_mass_motion

DOWN = (0.0, -1.0, 0.0)
GRAVITY_DIRECTION = np.array([0.0, -1.0, 0.0])


def anchors_in_a_row(*, count: int, spacing: float, along=(1.0, 0.0, 0.0)) -> np.ndarray:
    """count anchors `spacing` metres apart along a direction, centred on the origin, (count, 3) m."""
    along = np.asarray(along, dtype=float)
    offsets = (np.arange(count) - 0.5 * (count - 1)) * spacing
    return offsets[:, None] * along[None, :]


def rest_length(*, L0, m, k, g, direction=DOWN) -> float:
    """s_eq = L0 + m g (ĝ·û) / k: the spring's length where the mass hangs still, m.

    With k = 0 there is no spring to balance gravity, and the start is measured from L0.
    """
    if k == 0:
        return L0
    return L0 + m * g * float(GRAVITY_DIRECTION @ np.asarray(direction, dtype=float)) / k


def start_positions(*, anchors, direction=DOWN, L0, m, k, g, x0) -> np.ndarray:
    """Each mass x0 beyond its equilibrium along û: r = anchor + (s_eq + x0) û, (N, 3) m.

    x0 may be one number or one per mass.
    """
    u = np.asarray(direction, dtype=float)
    s = rest_length(L0=L0, m=m, k=k, g=g, direction=u) + np.asarray(x0, dtype=float)
    return np.asarray(anchors, dtype=float) + np.reshape(s, (-1, 1)) * u[None, :]


def exact_row(*, anchors, r0, m, k, L0, g, b=0.0, F0=0.0, omega=0.0, drive_axis=DOWN):
    """t -> (r, v) of shape (len(t), N, 3) for the row, from the single-mass closed form.

    Every parameter may be one number or one value per mass. The masses start at rest at r0.
    Returns None if any mass has no closed form.
    """
    anchors, r0 = np.asarray(anchors, dtype=float), np.asarray(r0, dtype=float)
    count = len(anchors)
    b, F0, omega = (np.broadcast_to(np.asarray(x, dtype=float), (count,)) for x in (b, F0, omega))
    def motion(i):
        return single_mass_motion(m=m, k=k, L0=L0, g=g, b=b[i], C=0.0, F0=F0[i], omega=omega[i],
                                  drive_axis=drive_axis, anchor=anchors[i], r0=r0[i], v0=(0, 0, 0))
    if motion(0) is None:      # the same forces for every mass: one without a closed form, all
        return None
    motions = []

    def exact(t):
        if not motions:        # worked out when first asked for: a big batch may never need it
            motions.extend(motion(i) for i in range(count))
        rs, vs = zip(*(each(t) for each in motions))
        return np.stack(rs, axis=1), np.stack(vs, axis=1)
    return exact

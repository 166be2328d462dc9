"""Where the masses would rest: the equilibrium, and the springs' natural length, from the forces.

Equilibrium. A mass at rest stays at rest where the forces on it cancel:

    F_net(r, v = 0) = 0

found here by Newton's method on the forces themselves (physics.forces.net_force, with v = 0),
from where the masses start: r ← r − J⁺ F_net(r), with J = ∂F_net/∂r by finite differences and J⁺
its least-squares inverse, so a direction in which no force pulls (across a relaxed spring, along
a table) keeps the starting value. Velocity forces (damping, drag) are zero at rest; a force that
changes with time at fixed r and v (a drive) averages to zero over its cycle and is left out, so
the equilibrium is the centre the motion swings about. For a mass hanging on a vertical spring
this is L0 + m g / k below the anchor; a force added later needs nothing here.

Natural length. A force that ties each mass to a fixed point declares it (Force.tether(): the
anchor and the length L0); the spring is relaxed at L0 from its anchor, along the line from the
anchor to the equilibrium (or to the start, where they coincide).

Nothing here imports a front end: the page's lines, the reports and the offline page read these.
"""
from __future__ import annotations

import numpy as np

from .forces import net_force
from .state import State

ITERATIONS = 50
TOLERANCE = 1e-10       # |F_net| this small, relative to the forces' own size, is equilibrium


def steady_forces(forces, state: State) -> list:
    """The forces that do not change with time at the starting r and v (all but a drive)."""
    v = state.v
    kept = []
    for force in forces:
        at = [np.asarray(force(t, state.r, v, state.m), dtype=float) for t in (0.0, 0.37, 1.91)]
        if all(np.allclose(at[0], other, rtol=1e-12, atol=0.0) for other in at[1:]):
            kept.append(force)
    return kept


def equilibrium(forces, state: State) -> np.ndarray | None:
    """Where each mass rests, (N, D) m: F_net = 0 with v = 0 (the time-independent forces), by
    Newton's method from the starting positions. None where there is none (nothing pulls a mass
    back: a falling ball) or Newton's method does not settle.

    Each mass's own D × D block of J first (every mass nudged along one axis at once: 2D force
    evaluations a step, for a row of 39 springs as for one); where a force joins masses and that
    does not settle, the whole J.
    """
    forces = steady_forces(forces, state)
    r0 = np.array(state.r, dtype=float)
    rest = np.zeros_like(r0)
    m = state.m

    def F(position):
        return np.asarray(net_force(forces, 0.0, position, rest, m), dtype=float)

    # the size of the forces themselves (a mass that starts at equilibrium has F_net = 0 already)
    scale = max([float(np.max(np.abs(force(0.0, r0, rest, m)))) for force in forces] + [1e-300])
    h = 1e-6 * max(float(np.max(np.abs(r0))), 1.0)
    for jacobian in (_each_mass, _whole):
        r = r0.copy()
        for _ in range(ITERATIONS):
            residual = F(r)
            if not np.all(np.isfinite(residual)):
                break
            if float(np.max(np.abs(residual))) <= TOLERANCE * scale:
                # round-off left by Newton's steps is no place: 2.6e-20 m is 0 m
                return np.where(np.abs(r) < 1e-12 * max(float(np.max(np.abs(r))), 1.0), 0.0, r)
            move = jacobian(F, r, h, residual)
            if move is None:
                return None           # no force depends on where the mass is: no equilibrium
            r = r + move
    return None


def _each_mass(F, r, h, residual):
    """Newton's move −J⁺F with each mass's own block of J = ∂F_i/∂r_i, (N, D) m."""
    count, dims = r.shape
    J = np.empty((count, dims, dims))
    for a in range(dims):          # ∂F_i/∂r_i,a for every mass at once, by central differences
        step = np.zeros_like(r)
        step[:, a] = h
        J[:, :, a] = (F(r + step) - F(r - step)) / (2 * h)
    if not np.any(np.abs(J) > 0):
        return None
    return np.stack([np.linalg.lstsq(J[i], -residual[i], rcond=1e-12)[0] for i in range(count)])


def _whole(F, r, h, residual):
    """Newton's move −J⁺F with the whole J = ∂F/∂r (masses joined by springs), (N, D) m."""
    J = np.empty((r.size, r.size))
    for n in range(r.size):
        step = np.zeros(r.size)
        step[n] = h
        J[:, n] = (F(r + step.reshape(r.shape)) - F(r - step.reshape(r.shape))).ravel() / (2 * h)
    if not np.any(np.abs(J) > 0):
        return None
    return np.linalg.lstsq(J, -residual.ravel(), rcond=1e-12)[0].reshape(r.shape)


def natural_length(forces, state: State, centre: np.ndarray | None = None) -> np.ndarray | None:
    """Where each mass would be with its spring at its natural length L0, (N, D) m: L0 from the
    anchor, along the line from the anchor to `centre` (the equilibrium; the start if None or at
    the anchor). None where no force ties a mass to a fixed point (Force.tether())."""
    for force in forces:
        tether = getattr(force, "tether", lambda: None)()   # a plain callable ties nothing
        if tether is None:
            continue
        anchor, L0 = tether
        r = np.array(state.r if centre is None else centre, dtype=float)
        anchor = np.broadcast_to(np.asarray(anchor, dtype=float), r.shape)
        towards = r - anchor
        length = np.linalg.norm(towards, axis=-1, keepdims=True)
        start = np.asarray(state.r, dtype=float) - anchor
        towards = np.where(length > 0, towards, start)
        length = np.linalg.norm(towards, axis=-1, keepdims=True)
        if not np.all(length > 0):
            return None
        L0 = np.broadcast_to(np.asarray(L0, dtype=float).reshape(-1, 1), (len(r), 1))
        return anchor + L0 * towards / length
    return None

"""Energy of the masses, and the work done on them by non-conservative forces.

    K = Σ |p|² / 2m                       kinetic energy, J
    U = Σ over conservative forces of U   spring ½k(|L| − L0)² and gravity m g h, J
    E = K + U                             mechanical energy, J
    P_nc = Σ F_nc · v                     power of damping, drag and driving, W
    W_nc(t) = ∫ P_nc dt                   their work since the start, J

The energy principle says E(t) − W_nc(t) stays equal to E(0): damping and drag only take energy
away (P_nc ≤ 0), a driving force may add it. A numerical run keeps E − W_nc constant only to the
accuracy of its integrator, which makes it a good check on the integrator.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .rows import row_dot
from .state import State, velocity

SERIES_BLOCK = 1 << 16       # numbers of r in one block of samples whose energies are worked out at once


def kinetic(state: State) -> np.ndarray:
    """K = |p|² / 2m for each mass, J."""
    return row_dot(state.p, state.p) / (2.0 * state.m)


def potential(state: State, forces) -> np.ndarray:
    """U of every conservative force, for each mass, J."""
    U = np.zeros(state.r.shape[:-1])
    for force in forces:
        if force.conservative:
            U = U + force.potential_energy(state.r, state.m)
    return U


def nonconservative_power(state: State, forces) -> np.ndarray:
    """P_nc = F_nc · v for each mass: the rate at which damping, drag and driving do work, W."""
    v = velocity(state.p, state.m)
    F_nc = np.zeros_like(state.r)
    for force in forces:
        if not force.conservative:
            F_nc += force(state.t, state.r, v, state.m)
    return row_dot(F_nc, v)


def work_step(work, power_before, power_after, dt: float):
    """W_nc after one more step, by the trapezoid rule: W + ½ (P_before + P_after) Δt, J."""
    return work + 0.5 * (power_after + power_before) * dt


def report(state: State, forces, work) -> dict:
    """K, U, E and E − W_nc summed over all masses, J (numbers)."""
    return {key: float(value) for key, value in series(state, forces, work).items()}


def series(state: State, forces, work) -> dict:
    """K, U, E, W_nc and E − W_nc summed over the masses, J, for one state or many samples.

    For many samples, r and p are (n, N, 3) and work (n, N): each value is then an (n,) array,
    worked out a block of samples at a time (each sample's sums are the same numbers, but no
    temporary array is as big as the whole run: 475 samples of 10⁴ masses took five times longer).
    """
    r = np.asarray(state.r)
    if r.ndim < 3 or r.size <= SERIES_BLOCK:
        return _series(state, forces, work)
    rows = max(1, SERIES_BLOCK // r[0].size)
    t = np.broadcast_to(state.t, (len(r),))
    parts = [_series(State(t=t[i:i + rows], r=r[i:i + rows], p=state.p[i:i + rows], m=state.m), forces,
                     work[i:i + rows]) for i in range(0, len(r), rows)]
    return {key: np.concatenate([part[key] for part in parts]) for key in parts[0]}


def _series(state: State, forces, work) -> dict:
    K = np.sum(kinetic(state), axis=-1)
    U = np.sum(potential(state, forces), axis=-1)
    W = np.sum(work, axis=-1)
    return {"K": K, "U": U, "E": K + U, "W_nc": W, "E_minus_W_nc": K + U - W}


def rest_potential(state: State, forces, *, rtol: float = 1e-9) -> float | None:
    """Σ U, J, if the masses start at rest at equilibrium, else None.

    At rest: every p = 0. At equilibrium: the conservative forces (springs, gravity) cancel on
    every mass, Σ F_c = 0. Energies measured from this U are the energy of the oscillation alone
    (a row of springs driven from rest, as in `resonance`), not a large constant m g h offset.
    """
    if np.any(state.p != 0):
        return None
    v = velocity(state.p, state.m)
    pulls = [force(state.t, state.r, v, state.m) for force in forces if force.conservative]
    if not pulls:
        return None
    scale = max(float(np.max(np.abs(pull))) for pull in pulls)
    if float(np.max(np.abs(np.sum(pulls, axis=0)))) > rtol * max(scale, 1e-300):
        return None
    return float(np.sum(potential(state, forces)))


@dataclass(frozen=True)
class EnergyPart:
    """One bar of an energy bar chart, J, summed over the masses: K, one force's U, or the energy
    the non-conservative forces took (−W_nc); `force` is the force whose U it is (else None)."""

    kind: str          # "K", "U" or "taken"
    value: float
    force: object = None


def energy_parts(state: State, forces, work, *, reference=None) -> list[EnergyPart]:
    """The energy split as PhET's bar chart splits it, J, summed over the masses:

        K                    kinetic
        U of each force      each conservative force's potential energy (spring, gravity, ...),
                             less its value at `reference` ((N, D) m, the equilibrium) if given
        −W_nc                the energy the non-conservative forces took (damping, drag,
                             friction; a drive that adds energy makes it negative)

    Their sum is E − W_nc (less U at the reference), which stays level wherever the energy
    principle holds: K + ΣU − W_nc = E(0) − W_nc(0).
    """
    parts = [EnergyPart("K", float(np.sum(kinetic(state))))]
    for force in forces:
        if force.conservative:
            U = float(np.sum(force.potential_energy(state.r, state.m)))
            if reference is not None:
                U -= float(np.sum(force.potential_energy(np.asarray(reference, dtype=float), state.m)))
            parts.append(EnergyPart("U", U, force))
    parts.append(EnergyPart("taken", -float(np.sum(work))))
    return parts

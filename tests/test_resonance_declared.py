"""resonance reads k and ω from what its forces declare (Force.CONSTANTS, program_values), not by
the forces' classes or their place in the list (issue 16: no isinstance chains in the front ends)."""
from __future__ import annotations

import dataclasses

import numpy as np

from physics.forces import Driving, Spring
from scenes import configure, resonance


def _model(**values):
    return configure("resonance").with_values(**values).build()


class _SpringOfItsOwn:
    """A spring of no class of ours (not a physics.forces.Spring, not even a Force subclass, so
    it is not registered among the project's forces): it declares k, anchor and L0 as a Force does."""

    CONSTANTS = Spring.CONSTANTS

    def __init__(self, spring: Spring):
        self._spring = spring

    def program_values(self) -> dict:
        return self._spring.program_values()

    def __call__(self, t, r, v, m):
        return self._spring(t, r, v, m)


def test_graphed_springs_are_chosen_by_the_declared_k_and_omega():
    model = _model(count=9, curves=3)
    chosen = resonance.graphed(model)
    k, m = model.forces[0].k, model.state.m.ravel()
    omega = np.asarray(model.forces[2].omega, dtype=float).ravel()
    rows = resonance.rows(model)
    for j, i in enumerate(chosen):      # in row j, the spring driven nearest ω0 = √(k/m)
        in_row = np.flatnonzero(rows == j)
        assert i in in_row
        assert abs(omega[i] - np.sqrt(k / m[i])) == min(abs(omega[in_row] - np.sqrt(k / m[in_row])))
    # The same choice whatever class declares k and wherever the forces stand in the list.
    others = [force for force in model.forces if not isinstance(force, Spring)]
    moved = dataclasses.replace(model, forces=tuple(reversed(others)) + (_SpringOfItsOwn(model.forces[0]),))
    assert resonance.graphed(moved) == chosen


def test_amplitudes_read_the_declared_omega_wherever_the_driving_force_stands():
    model = _model(count=5, curves=2)
    state = dataclasses.replace(model.state, p=model.state.p + 0.3)
    expected = resonance.amplitude_now(model, state)
    moved = dataclasses.replace(model, forces=tuple(reversed(model.forces)))
    assert not isinstance(moved.forces[2], Driving)
    assert np.array_equal(resonance.amplitude_now(moved, state), expected)
    assert resonance.declared_per_mass(moved, "omega").shape == (10,)

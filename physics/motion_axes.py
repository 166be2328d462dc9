"""The axes a motion uses: the engine steps only those, with the same numbers to the last bit.

A mass hanging on a vertical spring, released from rest below its anchor, moves along y alone:
its x and z stay where they started for ever. Stepping them anyway costs two thirds of the work
of every step (on 10⁴ masses the arrays are three times as long; in the traced loop of one mass,
three times as many lines). So the engine asks, once at the start, which axes the motion can use,
and steps a copy of the system cut to those axes (physics/simulate.py's tick puts the others back,
unchanged).

When an axis may be left out. Every force declares its vectors (physics/forces/base.py's
Force.VECTORS): a "point" it pulls towards or pushes from along r − point (a spring's anchor), a
"direction" it pushes along (gravity's), and otherwise it pushes only along v. Axis i may be left
out when, for every mass,

    p_i = +0             it does not move along i now,
    point_i = r_i        every point sits level with it along i (so L_i = r_i − point_i = +0),
    direction_i = 0      no direction has a part along i.

A "surface" (friction's mask of the axes along a table, 1 or 0 each) says nothing about which axes
move: the force pushes only along v within them, so it is cut with the others and never keeps an
axis in the step.

Then every force's part along i is a signed zero (a number per mass times +0), so p_i stays +0
and r_i stays r_i, step after step, whatever the integrator: the axis never moves. (Only once
the motion has blown up to inf does stepping every axis turn r_i into NaN, as inf × 0; the run
stops there with the same message either way.)

Why the numbers are the same, bit for bit. Each component of a step is worked out from the same
component of its inputs (the integrators and the forces are elementwise), except the lengths
and dot products of rows, and those add their terms in axis order (physics/rows.py), where adding
an exact +0 changes nothing. A force that declares no VECTORS (None, the default: a new force
may push along any axis) keeps all three axes; so does a motion with a −0.0 in the way (r_i = −0
would become +0 after one step of the whole system).
"""
from __future__ import annotations

import copy

import numpy as np


def moving_axes(r: np.ndarray, p: np.ndarray, forces) -> tuple[int, ...] | None:
    """The axes the motion of this state under these forces can use, or None where it may use
    all of them (then cutting saves nothing, or some force does not declare its vectors)."""
    if r.ndim != 2 or any(getattr(force, "VECTORS", None) is None for force in forces):
        return None
    still = np.all((p == 0) & ~np.signbit(p), axis=0) & ~np.any((r == 0) & np.signbit(r), axis=0)
    for force in forces:
        for name, kind in force.VECTORS.items():
            if kind == "surface":        # the axes it acts along: within them it pushes only along v
                continue
            vector = np.broadcast_to(getattr(force, name), r.shape)
            still &= np.all(vector == r, axis=0) if kind == "point" else np.all(vector == 0, axis=0)
    axes = tuple(int(i) for i in np.flatnonzero(~still))
    if len(axes) == r.shape[1]:
        return None
    return axes or (0,)          # nothing moves at all: one axis stands for the rest


def cut(forces, axes) -> tuple:
    """Copies of the forces with each declared vector cut to these axes."""
    pick = columns(axes)
    cut_forces = []
    for force in forces:
        cut_force = copy.copy(force)
        for name in force.VECTORS:
            object.__setattr__(cut_force, name, np.asarray(getattr(force, name))[..., pick])
        cut_forces.append(cut_force)
    return tuple(cut_forces)


def columns(axes) -> slice | list:
    """Index of the axes' columns: a slice where they are neighbours (a view of the array, no copy)."""
    axes = list(axes)
    if axes == list(range(axes[0], axes[-1] + 1)):
        return slice(axes[0], axes[-1] + 1)
    return axes


def put_back(whole: np.ndarray, pick, part: np.ndarray) -> np.ndarray:
    """A new array like `whole`, with `part` in the columns `pick` (columns(axes)) and whole's others."""
    out = whole.copy(order="K")       # one copy of the whole is cheaper than picking its other columns
    out[..., pick] = part
    return out

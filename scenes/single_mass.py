"""One mass on a spring, with every force of the page available: the build function the
single-mass scenes share.

Every single-mass scene accepts m, k, L0, g, b, C, A, rho, F0, omega, drive_axis, anchor, r0, v0,
dt and until. A force whose constant is 0 is left out, so one scene can pose any of the usual
homework variants (a mass falling with drag is k = 0, C > 0).
"""
from __future__ import annotations

import numpy as np

from physics.exact import single_mass_motion
from physics.forces import Driving, Gravity, LinearDamping, QuadraticDrag, Spring
from physics.state import make_state

from .model import Model


def forces_for(*, k, L0, anchor, g, b, C, A, rho, F0, omega, drive_axis) -> tuple:
    """The forces that are switched on (non-zero constants), in the order the page adds them."""
    forces = [Spring(k=k, L0=L0, anchor=anchor)]
    if g:
        forces.append(Gravity(g=g))
    if b:
        forces.append(LinearDamping(b=b))
    if C and A and rho:
        forces.append(QuadraticDrag(C=C, A=A, rho=rho))
    if F0:
        forces.append(Driving(F0=F0, omega=omega, axis=drive_axis))
    return tuple(forces)


def build_single_mass(*, m, k, L0, g, b, C, A, rho, F0, omega, drive_axis, anchor, r0, v0, dt,
                      until, label="mass", **_scene_specific) -> Model:
    """A Model of one mass from the shared single-mass constants (units as in the scene files)."""
    forces = forces_for(k=k, L0=L0, anchor=anchor, g=g, b=b, C=C, A=A, rho=rho, F0=F0,
                        omega=omega, drive_axis=drive_axis)
    motion = single_mass_motion(m=m, k=k, L0=L0, g=g, b=b, C=C * A * rho, F0=F0, omega=omega,
                                drive_axis=drive_axis, anchor=anchor, r0=r0, v0=v0)

    def exact(t):
        r, v = motion(t)
        return r[:, None, :], v[:, None, :]

    return Model(
        state=make_state(r=r0, v=v0, m=m),
        forces=forces,
        dt=float(dt),
        until=float(until),
        exact=exact if motion else None,
        anchors=np.atleast_2d(np.asarray(anchor, dtype=float)),
        labels=(label,),
    )

"""One mass on a spring, with every known force available: the build function the single-mass
scenes share.

A single-mass scene takes m, r0, v0, dt and until, and the constants of every force
(physics/forces/: each force's CONSTANTS); its constants block lists those it shows, and any other
force's constants keep their declared defaults, which switch that force off (b = 0, mu_k = 0), so
`--set mu_k=0.2` works in every such scene. A force whose switch is at its default is left out, so
one scene can pose any of the usual homework variants (a mass falling with drag is k = 0, C > 0).

The closed form (physics.exact.single_mass_motion) is used only where it covers every force
present (each force's closed_form()); otherwise the model has none, and says which force has none.
It follows the mass along the line of its spring. With a relaxed length L0 > 0 it holds only while
the mass stays on its own side of the anchor: see :class:`AnchorCrossing`.
"""
from __future__ import annotations

import math

import numpy as np

from physics.exact import single_mass_motion
from physics.forces import closed_form_terms, switched_on
from physics.state import make_state

from ._model import Model


def forces_for(**constants) -> tuple:
    """The forces the constants switch on, in the order they were defined, the page's first
    (spring, gravity, damping, drag, driving; physics.forces.switched_on: each force's switched_on
    reads its own constants)."""
    return switched_on(**constants)


class AnchorCrossing:
    """The first time the exact motion reaches the spring's anchor: where its closed form stops holding.

    Along the line through the anchor, with s the mass's distance from the anchor on its starting
    side, the spring force is −k(|s| − L0) sign(s). The closed form uses −k(s − L0), the same law
    only while s > 0. Once the exact motion reaches s = 0 (a resonance swinging wider than L0, or a
    mass started above its anchor that falls through it), the real spring flips over and pushes the
    other way, and the closed form no longer describes the mass.

    Called with a time T, returns the first time up to T at which s = 0, s (math.inf if s stays
    positive all the way to T). s(t) is sampled SAMPLES_PER_PERIOD times per period of the fastest
    rate in the motion (√(k/m), ω, b/m) and the first sign change bisected; a graze shallower than
    the sampling can resolve (about 1e-4 of the amplitude) goes unnoticed. The time checked so far
    is remembered, so asking again for a later T only samples the new stretch.
    """

    SAMPLES_PER_PERIOD = 200
    MAX_SAMPLES = 10_000_000   # per call: a very long horizon is sampled more coarsely
    CHUNK = 100_000

    def __init__(self, motion, *, anchor, r0, m, k, b, F0, omega):
        rate = max(math.sqrt(k / m), omega if F0 else 0.0, b / m)   # the fastest in the motion, 1/s
        anchor = np.asarray(anchor, dtype=float)
        u = np.asarray(r0, dtype=float) - anchor
        u = u / np.linalg.norm(u)
        self._s = lambda t: (motion(t)[0] - anchor) @ u    # m, distance from the anchor along û
        self._step = 2.0 * math.pi / rate / self.SAMPLES_PER_PERIOD
        self._checked = 0.0
        self._crossing = math.inf

    def __call__(self, T: float) -> float:
        step = max(self._step, (T - self._checked) / self.MAX_SAMPLES)
        while math.isinf(self._crossing) and self._checked < T:
            end = min(T, self._checked + step * self.CHUNK)
            t = np.linspace(self._checked, end, max(2, math.ceil((end - self._checked) / step) + 1))
            below = np.flatnonzero(self._s(t) <= 0.0)
            if below.size:
                self._crossing = self._bisect(t[max(below[0] - 1, 0)], t[below[0]])
            self._checked = end
        return self._crossing if self._crossing <= T else math.inf

    def _bisect(self, before: float, after: float) -> float:
        """The time of s = 0 between `before` (s > 0) and `after` (s ≤ 0), to round-off."""
        for _ in range(60):
            middle = 0.5 * (before + after)
            if middle in (before, after):
                break
            if self._s(np.array([middle]))[0] <= 0.0:
                after = middle
            else:
                before = middle
        return after


ANCHOR_LIMIT = ("when the mass reaches its spring's anchor; past the anchor a spring with L0 > 0 "
                "flips over, which the closed form does not follow")


def build_single_mass(*, m, r0, v0, dt, until, anchor, label="mass", **constants) -> Model:
    """A Model of one mass from its constants (units as in the scene files): m, r0, v0, dt, until
    and the anchor the view draws the spring from, and every force's constants by name."""
    forces = forces_for(anchor=anchor, **constants)
    terms, no_closed_form = closed_form_terms(forces)
    motion = None if terms is None else single_mass_motion(m=m, r0=r0, v0=v0, **terms)

    def exact(t):
        r, v = motion(t)
        return r[:, None, :], v[:, None, :]

    crossing = None
    if motion and terms["L0"] > 0:
        crossing = AnchorCrossing(motion, anchor=anchor, r0=r0, m=m, k=terms["k"], b=terms.get("b", 0.0),
                                  F0=terms.get("F0", 0.0), omega=terms.get("omega", 0.0))

    return Model(
        state=make_state(r=r0, v=v0, m=m),
        forces=forces,
        dt=float(dt),
        until=float(until),
        exact=exact if motion else None,
        anchors=np.atleast_2d(np.asarray(anchor, dtype=float)),
        labels=(label,),
        exact_valid_until=crossing,
        exact_limit=ANCHOR_LIMIT if crossing else "",
        no_closed_form=no_closed_form,
    )

"""A row of independent oscillators side by side: where their springs are fixed, where each mass
rests, and their exact motion.

Scenes that compare oscillators (the damping regimes, two drag laws, four integrators, a resonance
sweep) give every mass its own spring and anchor. The masses never act on each other, so each one
moves like the single mass of the page, and the row's exact motion is the single-mass closed form
(physics.exact.single_mass_motion) for each mass, stacked. With L0 > 0 each mass's closed form
holds until that mass reaches its own anchor (:class:`EachMassValidity`).

Each spring points from its anchor along a unit vector û (straight down for a hanging spring,
along +x for a spring on a wall). With gravity g along −y, the spring's length at equilibrium is

    s_eq = L0 + m g (ĝ·û) / k

and a mass started at s_eq + x0 along û, with its velocity along û, stays on that line.

The rules that place a row (anchors `spacing` apart, each mass x0 beyond its equilibrium) are
also declared here as data for the handed-out program (:class:`MassList`, :class:`MassLoop`):
plain text naming the scene's constants, written beside the function that works the same values
out with the same arithmetic, so the program builds its lists as the scene's build does. A scene
hands them to its Model (Model.per_mass); export/ writes them without knowing any scene.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from physics.exact import Role, displacement_bound, row_motion, single_mass_motion
from physics.forces import closed_form_terms

from ._single_mass import ANCHOR_LIMIT, AnchorCrossing

DOWN = (0.0, -1.0, 0.0)
GRAVITY_DIRECTION = np.array([0.0, -1.0, 0.0])


def anchors_in_a_row(*, count: int, spacing: float, along=(1.0, 0.0, 0.0)) -> np.ndarray:
    """count anchors `spacing` metres apart along a direction, centred on the origin, (count, 3) m."""
    along = np.asarray(along, dtype=float)
    offsets = (np.arange(count) - 0.5 * (count - 1)) * spacing
    return offsets[:, None] * along[None, :]


@dataclass(frozen=True)
class MassList:
    """One list of the program with a value per mass, as the scene's build works it out.

    name     the model's quantity it holds: "anchor", "r0", or a force's constant ("b", "omega")
    comment  the program's comment on the line that makes each value
    each     one mass's value, inside the loop over the masses (MassLoop.index names it), or
    whole    the whole list at once, before the loop
    before   (code, comment) lines it needs before the loop: `s_eq = L0 + m*g/k`
    keep     a name the value is kept in first, for the lists after it (`a`, the anchor)
    All text names the scene's constants, as its constants block does.
    """

    name: str
    comment: str = ""
    each: str = ""
    whole: str = ""
    before: tuple = ()
    keep: str = ""


@dataclass(frozen=True)
class MassLoop:
    """The scene's lists of one value per mass: the loop over the masses and the lists it fills.

    loop     the for line(s), `for i in range(3):` or a row per b and a column per ω
    index    the loop's index inside, for a mass's place in its row (`i`, `col`)
    lists    the MassList of each quantity, in the order they are made
    per_row  where there are rows: the constant that gives a row's length (`count`)
    """

    loop: tuple
    index: str
    lists: tuple
    per_row: str = ""

    def then(self, *lists: MassList) -> "MassLoop":
        """The same loop with more lists (a scene's own, after the row's)."""
        return MassLoop(self.loop, self.index, self.lists + tuple(lists), self.per_row)


def row_loop(*, count: int, count_name: str = "", rows_name: str = "") -> MassLoop:
    """The loop over a row of count masses (`for i in range(count)`), or over rows of them, one
    row per value of the constant rows_name (`for row in range(curves): for col in range(count)`)."""
    counted = count_name or str(count)
    if rows_name:
        return MassLoop((f"for row in range({rows_name}):", f"    for col in range({counted}):"), "col", (),
                        per_row=count_name)
    return MassLoop((f"for i in range({counted}):",), "i", ())


def row_anchors(loop: MassLoop, *, count: int, count_name: str = "", along=(1.0, 0.0, 0.0),
                row_depth: float = 0.0) -> MassList:
    """anchors_in_a_row as a list of the program: (i − (count − 1)/2)·spacing along ±x, ±y or ±z,
    and (rows) each row row_depth m behind the one before, along −z."""
    along = np.asarray(along, dtype=float)
    axis = int(np.flatnonzero(along)[0])
    centre = f"0.5*({count_name} - 1)" if count_name else _number(0.5 * (count - 1))
    i = loop.index
    parts = ["0", "0", "0"]
    parts[axis] = f"({i} - {centre})*spacing" if along[axis] > 0 else f"({centre} - {i})*spacing"
    rows = len(loop.loop) > 1
    if rows:
        parts[2] = "-row" if row_depth == 1 else f"-row*{_number(row_depth)}"
    sign = "+" if along[axis] > 0 else "−"
    comment = (f"m: rows along {sign}{'xyz'[axis]}, spacing apart, one behind another" if rows
               else f"m: a row along {sign}{'xyz'[axis]}, spacing apart")
    return MassList("anchor", comment, each="vector(" + ", ".join(parts) + ")", keep="a")


def row_starts(*, direction=DOWN, k, x0_name: str = "x0") -> MassList:
    """start_positions as a list of the program: a + (s_eq + x0) û from each anchor a, with s_eq
    written out where the spring hangs (û = −y, k > 0), else the relaxed length L0."""
    u = "vector(" + ", ".join(_number(c) for c in direction) + ")"
    stretch = f" + {x0_name}" if x0_name else ""
    if tuple(direction) == DOWN and k:
        equilibrium = ("s_eq = L0 + m*g/k", "m: length of each spring at equilibrium, where k (s_eq − L0) = m g")
        each = f"a + (s_eq{stretch})*{u}" if stretch else f"a + s_eq*{u}"
        return MassList("r0", "m: " + ("x0 below" if stretch else "at rest at") + " equilibrium", each=each,
                        before=(equilibrium,))
    return MassList("r0", "m: " + ("x0 beyond" if stretch else "at") + " the relaxed length",
                    each=f"a + (L0{stretch})*{u}")


def _number(x: float) -> str:
    """A half or a unit component as the program writes it: 1, -0.5, 0 (exact for these)."""
    return f"{float(x) + 0.0:g}"


def rest_length(*, L0, m, k, g, direction=DOWN) -> float:
    """s_eq = L0 + m g (ĝ·û) / k: the spring's length where the mass hangs still, m.

    direction û may be one unit vector or one per mass, (N, 3) (then s_eq is (N,)). With k = 0
    there is no spring to balance gravity, and the start is measured from L0.
    """
    if k == 0:
        return L0
    return L0 + m * g * (np.asarray(direction, dtype=float) @ GRAVITY_DIRECTION) / k


def start_positions(*, anchors, direction=DOWN, L0, m, k, g, x0) -> np.ndarray:
    """Each mass x0 beyond its equilibrium along û: r = anchor + (s_eq + x0) û, (N, 3) m.

    x0 may be one number or one per mass.
    """
    u = np.asarray(direction, dtype=float)
    s = rest_length(L0=L0, m=m, k=k, g=g, direction=u) + np.asarray(x0, dtype=float)
    return np.asarray(anchors, dtype=float) + np.reshape(s, (-1, 1)) * u[None, :]


class EachMassValidity:
    """When each mass's closed form stops holding: the first time, up to a horizon T, at which its
    exact motion reaches its spring's anchor (scenes/_single_mass.py's AnchorCrossing, mass by mass).

    Called with T, it gives the earliest of them (math.inf if every mass stays on its side up to T):
    Model.exact_valid_until's answer.
    each(T) gives one time per mass, (N,) s, for reports that judge each mass on its own: a mass
    whose closed form still holds keeps its exact answer though another's stopped.

    Searching the motion for the anchor costs thousands of samples per mass, so it is done only
    for the masses that could get there: may_reach(T) says which, from a bound on the swing
    (physics.exact.displacement_bound); the rest stay on their side up to T.
    """

    def __init__(self, *, crossing_of, may_reach):
        self._crossing_of = crossing_of  # i -> AnchorCrossing of mass i, or None (no closed form)
        self._may_reach = may_reach      # T -> (N,) bool
        self._crossings = {}             # made when first needed, kept: each remembers how far it looked

    def each(self, T: float) -> np.ndarray:
        may_reach = self._may_reach(T)
        times = np.full(len(may_reach), math.inf)
        for i in np.flatnonzero(may_reach):
            if i not in self._crossings:
                self._crossings[i] = self._crossing_of(i)
            if self._crossings[i] is not None:
                times[i] = self._crossings[i](T)
        return times

    def __call__(self, T: float) -> float:
        return float(self.each(T).min())


def exact_row(*, forces, r0, m) -> dict:
    """The row's closed form, as the Model takes it: exact, exact_valid_until and exact_limit.

    As for a single mass (scenes/_single_mass.py), the closed form's parameters come from the
    forces themselves, each force's closed_form() by role (physics/exact.py Role: the spring's k,
    L0 and anchors, gravity's g, the damping's b, the drive's F0, ω and axis), so a row names no
    force's constant and a new force with a closed form is read as ours are. m, k, L0 and g are
    the row's (one value each); b, F0 and ω may be one value per mass (resonance: one b per row).

    exact is t -> (r, v) of shape (len(t), N, 3), the single-mass closed form of every mass at once
    (physics.exact.row_motion), NaN ("not known") for a mass that has none: one on which a force
    acts that the closed form does not cover (quadratic drag; each force's closed_form() and
    acts_on() say); None if no mass has one, with no_closed_form naming such a force. The masses
    start at rest at r0. With L0 > 0 each mass's closed form holds until it reaches its anchor
    (:class:`EachMassValidity`); with L0 = 0 the spring is linear in 3-D and it always holds.
    """
    r0 = np.asarray(r0, dtype=float)
    count = len(r0)
    uncovered = [force for force in forces if force.closed_form() is None]
    acting = [force.acts_on(count) for force in uncovered]
    covered = ~np.any(acting, axis=0) if uncovered else np.ones(count, bool)
    # each mass's reason, where a force the closed form does not cover acts on it: "no closed form with drag"
    each = {"no_closed_form_each": tuple(next((f"no closed form with {force.LABEL or type(force).__name__}"
                                               for force, on in zip(uncovered, acting) if on[i]), "")
                                         for i in range(count))} if uncovered else {}
    terms, why = closed_form_terms([force for force in forces if force.closed_form() is not None])
    row = None if terms is None else _row_terms(terms, count)
    if row is None:        # two forces hold one role, or the springs differ from mass to mass
        return {"exact": None, "no_closed_form": why or "no closed form for springs that differ from mass to mass",
                **each}
    k, L0, g, b, F0, omega, drive_axis, anchors = row
    known, exact = row_motion(m=m, k=k, L0=L0, g=g, b=b, C=np.zeros(count), F0=F0, omega=omega,
                              drive_axis=drive_axis, anchors=anchors, r0=r0, v0=(0.0, 0.0, 0.0), covered=covered)
    if not known.any():    # named only where such a force acts on every mass (not drag on one ball of two)
        why = next((f"no closed form with {force.LABEL or type(force).__name__}" for force in uncovered
                    if force.acts_on(count).all()), "")
        return {"exact": None, "no_closed_form": why, **each}

    if L0 == 0:
        return {"exact": exact, **each}

    def crossing(i):
        if not known[i]:
            return None
        each = single_mass_motion(m=m, k=k, L0=L0, g=g, b=b[i], C=0.0, F0=F0[i], omega=omega[i],
                                  drive_axis=drive_axis, anchor=anchors[i], r0=r0[i], v0=(0, 0, 0))
        return AnchorCrossing(each, anchor=anchors[i], r0=r0[i], m=m, k=k, b=b[i], F0=F0[i], omega=omega[i])

    # Along each spring's line û: the start s0 from the anchor, the equilibrium s_eq, the drive's part.
    s0 = np.linalg.norm(r0 - anchors, axis=1)
    u = (r0 - anchors) / s0[:, None]
    s_eq = rest_length(L0=L0, m=m, k=k, g=g, direction=u)
    drive_u = F0 * (u @ (np.asarray(drive_axis, dtype=float) / np.linalg.norm(drive_axis)))

    def may_reach(T):
        # s = s_eq + x reaches the anchor (s = 0) only if |x| can grow to s_eq by T
        return displacement_bound(T, m=m, k=k, b=b, x0=s0 - s_eq, v0=0.0, F0=drive_u, omega=omega) >= s_eq
    return {"exact": exact, "exact_valid_until": EachMassValidity(crossing_of=crossing, may_reach=may_reach),
            "exact_limit": ANCHOR_LIMIT, **each}


def _row_terms(terms: dict, count: int):
    """The closed form's terms for a row of `count` masses: k, L0 and g one number each (None where
    they differ from mass to mass), b, F0 and ω one per mass (count,), the drive's direction and
    the anchors (count, 3). A term no force gives is not there: 0 (and the drive along −y)."""
    def one(role):
        values = np.ravel(np.asarray(terms.get(role, 0.0), dtype=float))
        return float(values[0]) if np.all(values == values[0]) else None

    def each(role):
        return np.broadcast_to(np.ravel(np.asarray(terms.get(role, 0.0), dtype=float)), (count,))

    k, L0, g = one(Role.STIFFNESS), one(Role.NATURAL_LENGTH), one(Role.GRAVITY)
    if None in (k, L0, g):
        return None
    anchors = np.broadcast_to(np.asarray(terms.get(Role.ANCHOR, (0.0, 0.0, 0.0)), dtype=float), (count, 3))
    return (k, L0, g, each(Role.DAMPING), each(Role.DRIVE_AMPLITUDE), each(Role.DRIVE_FREQUENCY),
            terms.get(Role.DRIVE_AXIS, DOWN), anchors)

"""What every force declares beside its law: the Force base class, and the sum F_net.

A force is a small frozen object holding its parameters; calling it gives the force on every mass:

    F = force(t, r, v, m)        t in s, r in m (N, 3), v in m/s (N, 3), m in kg (N,)

Beside that law, one class declares everything else about the force (see :class:`Force`), and
every front end reads those declarations: nothing else in the project chooses by the kind of a
force or names its constants.
"""
from __future__ import annotations

import operator

import numpy as np

from ..declared import Declared
from ..rows import row_dot
from ..state import velocity
from .declarations import DeclarationError, check_forces, closed_form_problem


def _per_mass(value) -> np.ndarray | float:
    """A scalar parameter, or an (N,) array reshaped to (N, 1) so it multiplies (N, 3) rows."""
    array = np.asarray(value, dtype=float)
    return float(array) if array.ndim == 0 else array.reshape(-1, 1)


def _new_like(r: np.ndarray) -> np.ndarray:
    """An empty array laid out like r, of floats (or of traced numbers, see physics/compiled.py)."""
    return np.empty_like(r, dtype=np.result_type(r, float))


def _unit(vector) -> np.ndarray:
    vector = np.asarray(vector, dtype=float)
    length = np.linalg.norm(vector)
    if length == 0:
        raise ValueError("a direction must not be the zero vector")
    return vector / length


def _column(value, count: int) -> np.ndarray:
    """A parameter as one number per mass, (count,)."""
    return np.broadcast_to(np.asarray(value, dtype=float).reshape(-1, 1), (count, 1))[:, 0]


def where(condition, a, b):
    """np.where(condition, a, b), which the fast loop can also trace (physics/compiled.py).

    On numbers it is np.where. On traced numbers (arrays of objects) each element becomes the
    loop's `a if condition else b`, with no guard: a force may choose between two values at every
    step (friction: moving or at rest) and the traced loop still runs on through either.
    """
    condition = np.asarray(condition)
    if condition.dtype != object:
        return np.where(condition, a, b)
    condition, a, b = np.broadcast_arrays(condition, np.asarray(a, dtype=object), np.asarray(b, dtype=object))
    chosen = [c.choose(x, y) if hasattr(c, "choose") else (x if c else y)
              for c, x, y in zip(condition.ravel(), a.ravel(), b.ravel())]
    return np.array(chosen, dtype=object).reshape(condition.shape)


_RELATIONS = {"<": operator.lt, "<=": operator.le, ">": operator.gt, ">=": operator.ge, "==": operator.eq}


def compare(a, relation: str, b):
    """a < b, a <= b, a > b, a >= b or a == b elementwise (relation one of those), which the fast loop
    can trace: on traced numbers an array of traced truths for `where`, not a guard (numpy's own
    comparison of object arrays asks each element for a bool, which the trace records as a guard)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype == object or b.dtype == object:
        return np.frompyfunc(_RELATIONS[relation], 2, 1)(a, b)
    return _RELATIONS[relation](a, b)


FORCES: list[type] = []     # every force class, in the order defined (ours, then any a scene brings)


class Force:
    """What every force declares, beside its law (its __call__).

    LABEL      its name on an arrow, an energy bar and in notes: "spring", "drag"
    CONSTANTS  the constants of its law, by the name the scenes and the program give them, each
               with its unit, range, meaning and default (physics/declared.py; scenes/_constants.py's
               DECLARED reads them). A constant declared `switch=True` switches the force off at its
               default (b = 0: no damping); a scene without a line for it has the force off.
    TIED       groups of constants the motion depends on only in one combination, each with why
               (("m", "k"), "the motion depends on k/m, ..."): a fit of two of a group is refused
    TERM       the program's name for the force: Fspring, Fdamping
    PROGRAM    its line(s) in the program, (code, comment) pairs; the code names the constants
               and {t}, {r}, {v}, {m} (time, position, velocity and mass as the program spells
               them) in braces, filled in by export/ with str.format
    conservative, uses_velocity   whether it has a potential energy (potential_energy), whether it
               reads v; a force that is not conservative is metered in W_nc (physics/energy.py)
    responds   its law also reads F_rest, the sum of the other forces (static friction balances
               them): it is called as force(t, r, v, m, F_rest=...) after the others, and alone
               (F_rest=None) where only its part along v matters (the work meter)
    VECTORS    its vectors by attribute: "point" where it pushes along r − point (a spring from
               its anchor), "direction" where it pushes along it (gravity), "surface" for a mask
               of the axes it acts along (it pushes only along v within them); else it pushes only
               along v, with numbers per mass. None (the default): it may push along any axis.
               The engine steps only the axes a motion uses (physics/motion_axes.py) where all say so.
    rates()    what it adds to the stability judgement (physics/stability.py)
    RATE_WORDS how the stability message writes each rate it adds, by its own constant
               ({"drag": "ρCA|v|/m"}); where it says nothing, rate_words() works it out from its
               one constant in kg/s ("c/m") or N/m ("√(k/m)"), so the message names the force's
               own constant: "the eddy brake (c/m = 40 s⁻¹)"
    closed_form()  its terms in the closed form (physics/exact.py), or None where that does not
               cover it: a model with such a force has no exact solution, and says so by LABEL
    CLOSED_FORM  the constant of CONSTANTS that holds each of its roles in the closed form, by the
               role (physics/exact.py Role: {Role.STIFFNESS: "k"}): how the program's exact curve
               finds the constants it writes (closed_form_constants)
    stop()     its stop rule, where it has one (static friction): applied by the engine after
               every step, and written in the program after the update (STOP lines)
    SINGLE_MASS  whether a single-mass scene takes it, switched on by its constants (True); False
               for a force that needs a scene of its own (friction needs a table): --constants and
               --forces then leave it out of those scenes, and its switched_on says why in one line

    A class that subclasses Force is known by that alone (FORCES), wherever it is defined.
    """

    LABEL = ""
    CONSTANTS: dict[str, Declared] = {}
    TIED: tuple[tuple[tuple[str, ...], str], ...] = ()
    TERM = ""
    PROGRAM: tuple[tuple[str, str], ...] = ()
    STOP: tuple[tuple[str, str], ...] = ()
    CLOSED_FORM: dict[str, str] = {}
    RATE_WORDS: dict[str, str] = {}
    SINGLE_MASS = True
    conservative = False
    uses_velocity = False
    responds = False
    VECTORS: dict[str, str] | None = None

    def __init_subclass__(cls, **options):
        super().__init_subclass__(**options)
        FORCES.append(cls)

    # ---- made from a scene's constants ----

    @classmethod
    def switched_on(cls, **constants):
        """This force made from a scene's constants (by the names in CONSTANTS), or None where it is
        off: one of its switches is at its default (b = 0), or the scene poses no such force (it
        gives none of its constants, or the force declares none). A switch the scene does not give
        is at its default."""
        declared = cls.CONSTANTS
        if not declared or not any(name in constants for name in declared):
            return None
        values = {name: constants.get(name, declaration.default) for name, declaration in declared.items()}
        if any(declaration.switch and values[name] == declaration.default
               for name, declaration in declared.items()):
            return None
        missing = [name for name, value in values.items() if value is None]
        if missing:
            raise ValueError(f"the {cls.LABEL or cls.__name__} force needs {', '.join(missing)}: "
                             f"add a line for it to the scene's constants")
        return cls.from_constants(**values)

    @classmethod
    def from_constants(cls, **values):
        """The force from its constants' values (by default the fields of the same names)."""
        return cls(**values)

    def program_values(self) -> dict:
        """The values of CONSTANTS this force holds, by name: a number, or an (N,) or (N, 3) array
        of one per mass. Raises ValueError where the program cannot write the force as it is."""
        return {name: getattr(self, name) for name in self.CONSTANTS}

    def program(self) -> tuple[tuple[str, str], ...]:
        """Its PROGRAM lines, as they apply to this force (Spring: a shorter law where L0 = 0)."""
        return self.PROGRAM

    # ---- what the engine and the judgements read ----

    def rates(self, m: np.ndarray, speed: np.ndarray) -> dict:
        """What the force adds to the stability judgement (physics/stability.py), per mass, at the
        present speeds |v| (m/s): any of

            "stiffness"  k, N/m: a spring from a fixed anchor (ω² = Σk/m)
            "joint"      (i, j, k): a spring of k N/m between masses i and j
            "damping"    γ = b/m, s⁻¹: a force near −γ m v, the same at every speed
            "drag"       γ, s⁻¹: the slope of a force that grows with speed, at the present speed

        A force that only adds to the motion without multiplying it (gravity, driving, friction)
        adds nothing: {}.
        """
        return {}

    @classmethod
    def rate_words(cls, kind: str) -> str:
        """How the stability message writes the rate of `kind` ("stiffness", "damping", "drag") this
        force adds: RATE_WORDS[kind] where declared, else from its one constant of the rate's unit
        (a damping's in kg/s: "c/m"; a stiffness's in N/m: "√(k/m)"), else γ (√(k/m) for a stiffness)."""
        if kind in cls.RATE_WORDS:
            return cls.RATE_WORDS[kind]
        unit = {"damping": "kg/s", "drag": "kg/s", "stiffness": "N/m"}.get(kind)
        own = [declared.symbol or name for name, declared in cls.CONSTANTS.items() if declared.unit == unit]
        if len(own) == 1:
            return f"√({own[0]}/m)" if kind == "stiffness" else f"{own[0]}/m"
        return "√(k/m)" if kind == "stiffness" else "γ"

    def closed_form(self) -> dict | None:
        """What this force adds to the closed form m x'' + b x' + k x = F0 cos(ω t) under gravity
        (physics/exact.py), by the closed form's names (k, L0, anchor, g, b, F0, omega,
        drive_axis), or None where no closed form covers it (the default: a new force has none
        until one is written, so a model with it reports no exact answer rather than a wrong one)."""
        return None

    def acts_on(self, count: int) -> np.ndarray:
        """Which of `count` masses the force acts on, (N,) bool: every one, unless its constants
        are one per mass and zero for some (drag on one ball of two)."""
        return np.ones(count, dtype=bool)

    def stop(self, *, t, r, p, m, F_rest, dt, r_f, p_f):
        """The stop rule: the step's end (r_f, p_f) as the force lets it stand, given the start of
        the step (t, r, p), the mass m, and F_rest, the net force of every other force at the
        start. The default lets every step stand."""
        return r_f, p_f

    @property
    def stops(self) -> bool:
        """Whether the force has a stop rule (it overrides stop)."""
        return type(self).stop is not Force.stop

    def tether(self):
        """(anchor, length) in m where the force ties each mass to a fixed point, None where it ties
        none: the engine counts a mass far beyond its tether's reach as blown up."""
        return None

    def undefined_at(self, r: np.ndarray) -> np.ndarray:
        """Which masses sit where the law has no value, (N,) bool: a scene refuses to start there."""
        return np.zeros(len(r), dtype=bool)


def declared_constants() -> dict[str, Declared]:
    """Every force's CONSTANTS, by name. Raises DeclarationError (one line naming the force and the
    fix) where a force's declarations cannot be used, two forces declare one name differently, or
    a force module could not be imported (physics/forces/declarations.py)."""
    check_forces(FORCES)
    declared: dict[str, Declared] = {}
    for cls in FORCES:
        for name, declaration in cls.CONSTANTS.items():
            declared.setdefault(name, declaration)
    return declared


def closed_form_constants(forces) -> dict[str, str]:
    """The constant that holds each role of the closed form (physics/exact.py Role) among these
    forces (a model's, or classes), from each one's CLOSED_FORM: {"b": "b", "k": "k", ...}. A role
    is one force's: where two of them hold one (damping's b and a brake's c), neither is named, and
    the model has no closed form (closed_form_terms says so)."""
    check_forces(FORCES)
    held: dict[str, list[str]] = {}
    for cls in {force if isinstance(force, type) else type(force): None for force in forces}:
        for role, name in getattr(cls, "CLOSED_FORM", {}).items():
            held.setdefault(role, []).append(name)
    return {role: names[0] for role, names in held.items() if len(names) == 1}


def closed_form_terms(forces) -> tuple[dict | None, str]:
    """The closed form's parameters from the forces (each one's closed_form(), by role), and "";
    or None and why not: the first force it does not cover ("no closed form with drag"), or two
    forces holding one role ("no closed form with both damping and eddy brake: each is its b").
    Raises DeclarationError where a force's closed_form() and CLOSED_FORM disagree."""
    terms, holder = {}, {}
    for force in forces:
        own = force.closed_form() if hasattr(force, "closed_form") else None
        label = getattr(force, "LABEL", "") or type(force).__name__
        if own is None:
            return None, f"no closed form with {label}"
        problem = closed_form_problem(force, own)
        if problem:
            raise DeclarationError(problem)
        for role, value in own.items():
            if role in terms:
                return None, (f"no closed form with both {holder[role]} and {label}: each is the closed "
                              f"form's {role}, which one force holds")
            terms[role], holder[role] = value, label
    return terms, ""


def switched_on(**constants) -> tuple:
    """Every known force the constants switch on, in the order the forces were defined (the page's
    own first: spring, gravity, damping, drag, driving): what a single-mass scene is made of."""
    check_forces(FORCES)
    forces = (cls.switched_on(**constants) for cls in FORCES)
    return tuple(force for force in forces if force is not None)


def uses_velocity(forces) -> bool:
    """Whether any force in the list depends on v (damping, drag). If none does, the integrators
    may pass v = None."""
    return any(force.uses_velocity for force in forces)


def net_force(forces, t, r, v, m) -> np.ndarray:
    """F_net = the sum of every force in the list, shape (N, 3), N (zero for an empty list): in the
    list's order, then each force that responds to the others (static friction) with their sum."""
    F_net = None
    responding = []
    for force in forces:
        if getattr(force, "responds", False):
            responding.append(force)
            continue
        F = force(t, r, v, m)
        if F_net is None:
            F_net = F          # each force returns a new array, so we may add into it
        else:
            F_net += F
    if F_net is None:
        F_net = np.zeros_like(r, dtype=np.result_type(r, float))
    for force in responding:
        F_net += force(t, r, v, m, F_rest=F_net.copy())
    return F_net


def forces_each(forces, t, r, v, m) -> list[np.ndarray]:
    """Each force on every mass, in the list's order, (N, 3) N each, as net_force adds them up (a
    force that responds to the others given their sum): what the arrows of each force draw."""
    values = {id(force): force(t, r, v, m) for force in forces if not getattr(force, "responds", False)}
    rest = sum(values.values(), np.zeros_like(r, dtype=float))
    for force in forces:
        if getattr(force, "responds", False):
            values[id(force)] = force(t, r, v, m, F_rest=rest)
            rest = rest + values[id(force)]
    return [values[id(force)] for force in forces]


def settle(forces, *, t, r, p, m, dt, r_f, p_f):
    """The step's end (r_f, p_f) after every force's stop rule (Force.stop), each given the net
    force of the others at the start of the step: what the engine does after each step."""
    for force in forces:
        if getattr(force, "stops", False):
            v = velocity(p, m)
            F_rest = net_force([other for other in forces if other is not force], t, r, v, m)
            r_f, p_f = force.stop(t=t, r=r, p=p, m=m, F_rest=F_rest, dt=dt, r_f=r_f, p_f=p_f)
    return r_f, p_f


__all__ = ["Force", "FORCES", "Declared", "DeclarationError", "closed_form_constants", "closed_form_terms", "compare",
           "declared_constants", "forces_each", "net_force", "settle", "switched_on", "uses_velocity", "where",
           "row_dot"]

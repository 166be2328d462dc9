"""The page's forces: a spring, gravity, linear damping, quadratic air drag and a driving force.

Each is a pure function of (t, r, v, m) returning an (N, 3) array, in N:

    F = force(t, r, v, m)        t in s, r in m (N, 3), v in m/s (N, 3), m in kg (N,)

The net force is the sum over a list of forces (:func:`net_force`). Conservative forces also give
their potential energy per mass; the others are counted in the non-conservative work W_nc
(see physics/energy.py). Parameters may be one number for all masses or one value per mass
(an (N,) array, or (N, 3) for anchors), which is how a batch of oscillators is stepped at once.

Every call returns a new array laid out like r (net_force adds into the first one). Anything
that does not change in time, such as g times the direction of gravity, is worked out once when
the force is made. A force whose uses_velocity is False never reads v, so a step may pass
v = None.
For motion along one line, give r the shape (N, 1) and the forces 1-component vectors:
Spring(anchor=(0.0,)), Gravity(direction=(-1.0,)), Driving(axis=(1.0,)).

Each force is one declaration (a subclass of physics/forces/base.py's Force): beside its law it
gives its label, the constants of that law with their units, ranges and defaults (CONSTANTS, which
scenes/_constants.py's DECLARED reads), the rates the stability judgement needs (rates, read by
physics/stability.py), its terms in the closed form (closed_form, read by the scenes' builders)
and its line in the handed-out VPython program (PROGRAM, plain text that export/ fills in with the
program's names). Nothing else in the project chooses by the kind of force; docs/architecture.md
gives the recipe for a new one, and physics/forces/friction.py is one in a module of its own.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..declared import Declared
from ..exact import Role
from ..rows import magnitude
from .base import Force, _column, _new_like, _per_mass, _unit


@dataclass(frozen=True, eq=False)
class Spring(Force):
    """Hooke's law for a spring from a fixed anchor to each mass, in 3-D.

    F = −k (|L| − L0) L̂,  with L = r − anchor
    k in N/m (stiffness), L0 in m (relaxed length), anchor in m. U = ½ k (|L| − L0)², in J.
    """

    k: object = 0.0
    L0: object = 0.0
    anchor: object = (0.0, 0.0, 0.0)
    conservative = True
    uses_velocity = False
    LABEL = "spring"
    TIED = ((("m", "k"), "the motion depends on k/m, not on k and m apart (gravity gives every mass the same g)"),)
    CONSTANTS = {
        "k": Declared("N/m", 0, 1e6, meaning="spring constant", default=0.0, slider=True),
        "L0": Declared("m", 0, 1e4, meaning="relaxed length of the spring", default=0.0),
        "anchor": Declared("m", -1e4, 1e4, vector=True, meaning="fixed end of the spring", default=(0.0, 0.0, 0.0)),
    }
    TERM = "Fspring"
    VECTORS = {"anchor": "point"}
    CLOSED_FORM = {Role.STIFFNESS: "k", Role.NATURAL_LENGTH: "L0", Role.ANCHOR: "anchor"}
    PROGRAM = (("L = {r} - {anchor}", "the spring, from its fixed end to the mass"),
               ("Fspring = {k}*({L0}/mag(L) - 1)*L", "Hooke's law: F = −k (|L| − L0) L̂, written k (L0/|L| − 1) L"))
    LINEAR = (("L = {r} - {anchor}", "the spring, from its fixed end to the mass"),
              ("Fspring = -{k}*L", "Hooke's law with L0 = 0: F = −k L"))

    def __post_init__(self):
        object.__setattr__(self, "k", _per_mass(self.k))
        object.__setattr__(self, "L0", _per_mass(self.L0))
        # column-major like r (see physics/simulate.py), so that r − anchor runs at full speed
        object.__setattr__(self, "anchor", np.asfortranarray(self.anchor, dtype=float))
        # With L0 = 0 the law is simply F = −k L (a linear spring, no direction needed).
        object.__setattr__(self, "_zero_length", bool(np.all(self.L0 == 0)))

    def stretch(self, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """L = r − anchor and its length |L| (shape (N, 1))."""
        L = r - self.anchor
        return L, magnitude(L)

    def __call__(self, t, r, v, m):
        k, L0 = self.k, self.L0
        if self._zero_length:
            return -k * (r - self.anchor)
        L, length = self.stretch(r)
        if length.all():
            # F = −k (|L| − L0) L̂ = k (L0/|L| − 1) L
            return (k * (L0 / length - 1.0)) * L
        # At |L| = 0 the direction L̂ is undefined, so F = 0 there.
        stretched = length > 0
        safe = np.where(stretched, length, 1.0)
        return np.where(stretched, (k * (L0 / safe - 1.0)) * L, 0.0)

    def potential_energy(self, r, m):
        """U = ½ k (|L| − L0)² for each mass, J."""
        _, length = self.stretch(r)
        return (0.5 * self.k * (length - self.L0) ** 2)[..., 0]

    def rates(self, m, speed):
        return {"stiffness": _column(self.k, len(m))}

    def closed_form(self):
        return {"k": self.k, "L0": self.L0, "anchor": self.anchor}

    def tether(self):
        return self.anchor, self.L0

    def undefined_at(self, r):               # L̂ at the anchor; F = −k L (L0 = 0) has no L̂ to lose
        return (self.stretch(r)[1][:, 0] == 0) & (not self._zero_length)

    def program_values(self):
        values = {"k": self.k, "anchor": self.anchor}
        if not self._zero_length:
            values["L0"] = self.L0
        return values

    def program(self):
        return self.LINEAR if self._zero_length else self.PROGRAM


@dataclass(frozen=True, eq=False)
class SpringBetween(Force):
    """Hooke's law for a spring joining mass i to mass j (for chains).

    F_i = −k (|L| − L0) L̂,  F_j = −F_i,  with L = r_i − r_j
    k in N/m, L0 in m. U = ½ k (|L| − L0)², in J, shared half and half between the two masses.
    """

    k: float
    L0: float
    i: int
    j: int
    conservative = True
    uses_velocity = False
    LABEL = "spring"

    def _stretch(self, r):
        L = r[self.i] - r[self.j]
        return L, np.sqrt(L @ L)

    def __call__(self, t, r, v, m):
        L, length = self._stretch(r)
        pull = -self.k * (length - self.L0) * L / length if length > 0 else np.zeros_like(L)
        F = np.zeros_like(r)
        F[self.i] += pull
        F[self.j] -= pull
        return F

    def rates(self, m, speed):
        return {"joint": (self.i, self.j, self.k)}

    def program_values(self):
        raise ValueError("the program cannot write a spring between two masses yet")

    def potential_energy(self, r, m):
        L = r[..., self.i, :] - r[..., self.j, :]     # r may hold many samples: (n, N, 3)
        length = np.sqrt(np.sum(L * L, axis=-1))
        U = np.zeros(r.shape[:-1])
        U[..., [self.i, self.j]] += (0.25 * self.k * (length - self.L0) ** 2)[..., None]
        return U


@dataclass(frozen=True, eq=False)
class Gravity(Force):
    """Uniform gravity near the Earth's surface.

    F = m g ĝ,  with g the magnitude in m/s² (9.8 on Earth) acting along ĝ = −y by default.
    U = m g h with h = −ĝ·r the height, in J.
    """

    g: float = 9.8
    direction: object = (0.0, -1.0, 0.0)
    conservative = True
    uses_velocity = False
    LABEL = "gravity"
    CONSTANTS = {"g": Declared("m/s²", 0, 1e3, note="it is a magnitude; gravity acts along −y",
                               slider_from_zero=True, meaning="strength of gravity, along −y",
                               default=0.0, switch=True)}
    TERM = "Fgravity"
    VECTORS = {"direction": "direction", "g_vector": "direction"}
    CLOSED_FORM = {Role.GRAVITY: "g"}
    PROGRAM = (("Fgravity = {m}*vector(0, -{g}, 0)", "gravity: F = m g, down (−y)"),)

    def __post_init__(self):
        object.__setattr__(self, "direction", _unit(self.direction))
        object.__setattr__(self, "g_vector", self.g * self.direction)   # g ĝ, m/s²

    def __call__(self, t, r, v, m):
        # F = m g ĝ for every mass, written straight into a new array laid out like r
        return np.multiply(m[:, None], self.g_vector, out=_new_like(r))

    def potential_energy(self, r, m):
        """U = m g h, with h measured up from the origin, J."""
        return -m * self.g * (r @ self.direction)

    def closed_form(self):
        return {"g": self.g} if np.array_equal(self.direction, (0.0, -1.0, 0.0)) else None

    def program_values(self):
        if not np.array_equal(self.direction, (0.0, -1.0, 0.0)):
            raise ValueError("the program writes gravity along −y only")
        return {"g": self.g}


@dataclass(frozen=True, eq=False)
class LinearDamping(Force):
    """Linear (viscous) damping.

    F = −b v,  b in kg/s (N per m/s). Always opposite v; it removes energy at the rate b|v|².
    """

    b: object = 0.0
    conservative = False
    uses_velocity = True
    LABEL = "damping"
    TIED = ((("m", "b"), "the motion depends on b/m, not on b and m apart"),)
    CONSTANTS = {"b": Declared("kg/s", 0, 1e6, none="critical damping, b = 2√(mk)", slider=True, slider_from_zero=True,
                               meaning="linear damping constant in F = −b v", default=0.0, switch=True)}
    TERM = "Fdamping"
    VECTORS = {}
    CLOSED_FORM = {Role.DAMPING: "b"}
    PROGRAM = (("Fdamping = -{b}*{v}", "linear damping: F = −b v"),)

    def __post_init__(self):
        object.__setattr__(self, "b", _per_mass(self.b))
        object.__setattr__(self, "_minus_b", -self.b)      # −b once, not at every call

    def __call__(self, t, r, v, m):
        return self._minus_b * v

    def rates(self, m, speed):
        return {"damping": _column(self.b, len(m)) / m}      # F = −b v = −(b/m) m v

    def closed_form(self):
        return {"b": self.b}


@dataclass(frozen=True, eq=False)
class QuadraticDrag(Force):
    """Quadratic air drag.

    F = −½ C A ρ |v| v,  with C the drag coefficient (no unit), A the cross-section area in m²
    and ρ the air density in kg/m³. Always opposite v, zero at rest, growing as speed squared.
    """

    C: object = 0.0
    A: object = 0.0
    rho: object = 0.0
    conservative = False
    uses_velocity = True
    LABEL = "drag"
    TIED = ((("C", "A", "rho"), "drag depends on the product C·A·ρ only"),)
    CONSTANTS = {
        "C": Declared("1", 0, 100, slider=True, slider_from_zero=True, meaning="drag coefficient in F = −½ C A ρ |v| v",
                      default=0.0, switch=True),
        "A": Declared("m²", 0, 1e3, meaning="cross-section area of the mass, for drag", default=0.0, switch=True),
        "rho": Declared("kg/m³", 0, 1e5, symbol="ρ", meaning="air density, for drag", default=0.0, switch=True),
    }
    TERM = "Fdrag"
    VECTORS = {}
    RATE_WORDS = {"drag": "ρCA|v|/m"}     # its rate at the present speed, for the stability message
    PROGRAM = (("Fdrag = -0.5*{C}*{A}*{rho}*mag({v})*{v}", "air drag: F = −½ C A ρ |v|² v̂ = −½ C A ρ |v| v"),)

    def __post_init__(self):
        for name in ("C", "A", "rho"):
            object.__setattr__(self, name, _per_mass(getattr(self, name)))

    def __call__(self, t, r, v, m):
        speed = magnitude(v)
        return -0.5 * self.C * self.A * self.rho * speed * v

    def acts_on(self, count):
        return _column(self.C * self.A * self.rho, count) != 0

    def rates(self, m, speed):
        # the slope of ½ C A ρ |v| v with respect to v is ρ C A |v|
        return {"drag": _column(self.C * self.A * self.rho, len(m)) * speed / m}


@dataclass(frozen=True, eq=False)
class Driving(Force):
    """A sinusoidal driving force.

    F = F0 cos(ω t) â,  F0 in N (amplitude), ω in rad/s (angular frequency, not Hz: f = ω / 2π),
    â a unit vector (x by default). F0 and ω may be per mass, to sweep a batch of frequencies.
    """

    F0: object = 0.0
    omega: object = 0.0
    axis: object = (1.0, 0.0, 0.0)
    conservative = False
    uses_velocity = False
    LABEL = "driving"
    TIED = ((("m", "F0"), "the motion depends on F0/m, not on F0 and m apart"),)
    CONSTANTS = {
        "F0": Declared("N", -1e6, 1e6, slider=True, slider_from_zero=True, meaning="driving force amplitude in F = F0 cos(ω t)",
                       default=0.0, switch=True),
        "omega": Declared("rad/s", 0, 1e4, symbol="ω", slider=True, slider_from_zero=True,
                          meaning="driving angular frequency ω (rad/s, not Hz; f = ω / 2π)", default=0.0),
        "drive_axis": Declared("1", -1e6, 1e6, vector=True, nonzero=True,
                               meaning="direction of the driving force", default=(1.0, 0.0, 0.0)),
    }
    TERM = "Fdrive"
    VECTORS = {"axis": "direction"}
    CLOSED_FORM = {Role.DRIVE_AMPLITUDE: "F0", Role.DRIVE_FREQUENCY: "omega", Role.DRIVE_AXIS: "drive_axis"}
    PROGRAM = (("Fdrive = {F0}*cos({omega}*{t})*{drive_axis}", "driving: F = F0 cos(ω t) along drive_axis"),)

    def __post_init__(self):
        object.__setattr__(self, "F0", _per_mass(self.F0))
        object.__setattr__(self, "omega", _per_mass(self.omega))
        object.__setattr__(self, "axis", _unit(self.axis))

    def __call__(self, t, r, v, m):
        # F = F0 cos(ω t) â for every mass, written into a new array laid out like r
        return np.multiply(self._amplitude_at(t), self.axis, out=_new_like(r))

    def _amplitude_at(self, t):
        """F0 cos(ω t), shape (N, 1) or a number, N.

        rk4 asks for the same t up to five times a step (its two half-step slopes, and the end of
        the step again for the work meter and the next step's first slope), so the last few values
        are kept by t: the same numbers, one cosine of every phase per distinct t.
        """
        if type(t) is not float or not isinstance(self.omega, np.ndarray):
            return self.F0 * np.cos(self.omega * t)
        recent = self.__dict__.get("_recent", ())
        for t_kept, value in recent:
            if t_kept == t:
                return value
        value = self.F0 * np.cos(self.omega * t)
        self.__dict__["_recent"] = (recent + ((t, value),))[-4:]   # replaced whole: safe across threads
        return value

    @classmethod
    def from_constants(cls, *, F0, omega, drive_axis):
        return cls(F0=F0, omega=omega, axis=drive_axis)

    def program_values(self):
        return {"F0": self.F0, "omega": self.omega, "drive_axis": self.axis}

    def closed_form(self):
        return {"F0": self.F0, "omega": self.omega, "drive_axis": self.axis}



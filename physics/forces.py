"""Forces on N point masses. Each is a pure function of (t, r, v, m) returning an (N, 3) array, in N.

A force is a small frozen object holding its parameters; calling it gives the force on every mass:

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

Each force is one declaration (a subclass of :class:`Force`): beside its law it gives the constants
of that law with their units and ranges (CONSTANTS, which scenes/_constants.py's DECLARED reads),
the rates the stability judgement needs (:meth:`Force.rates`, read by physics/stability.py), and
its line in the handed-out VPython program (PROGRAM, plain text that export/ fills in with the
program's names). Nothing else in the project chooses by the kind of force; docs/architecture.md
gives the recipe for a new one, and tests/test_new_force.py adds one from a folder of its own.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .declared import Declared
from .rows import magnitude


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


FORCES: list[type] = []     # every force class, in the order defined (ours, then any a scene brings)


class Force:
    """What every force declares, beside its law (its __call__).

    CONSTANTS  the constants of its law, by the name the scenes and the program give them, each
               with its unit, range and meaning (scenes/_constants.py's DECLARED reads them)
    TERM       the program's name for the force: Fspring, Fdamping
    PROGRAM    its line(s) in the program, (code, comment) pairs; the code names the constants
               and {t}, {r}, {v}, {m} (time, position, velocity and mass as the program spells
               them) in braces, filled in by export/ with str.format
    conservative, uses_velocity   whether it has a potential energy, whether it reads v
    VECTORS    its vectors by attribute: "point" where it pushes along r − point (a spring from
               its anchor), "direction" where it pushes along it (gravity); else it pushes only
               along v, with numbers per mass. None (the default): it may push along any axis.
               The engine steps only the axes a motion uses (physics/motion_axes.py) where all say so.

    A class that subclasses Force is known by that alone (FORCES), wherever it is defined.
    """

    CONSTANTS: dict[str, Declared] = {}
    TERM = ""
    PROGRAM: tuple[tuple[str, str], ...] = ()
    conservative = False
    uses_velocity = False
    VECTORS: dict[str, str] | None = None

    def __init_subclass__(cls, **options):
        super().__init_subclass__(**options)
        FORCES.append(cls)

    def rates(self, m: np.ndarray, speed: np.ndarray) -> dict:
        """What the force adds to the stability judgement (physics/stability.py), per mass, at the
        present speeds |v| (m/s): any of

            "stiffness"  k, N/m: a spring from a fixed anchor (ω² = Σk/m)
            "joint"      (i, j, k): a spring of k N/m between masses i and j
            "damping"    γ = b/m, s⁻¹: a force near −γ m v, the same at every speed
            "drag"       γ, s⁻¹: the slope of a force that grows with speed, at the present speed

        A force that only adds to the motion without multiplying it (gravity, driving) adds
        nothing: {}.
        """
        return {}

    def tether(self):
        """(anchor, length) in m where the force ties each mass to a fixed point, None where it ties
        none: the engine counts a mass far beyond its tether's reach as blown up."""
        return None

    def undefined_at(self, r: np.ndarray) -> np.ndarray:
        """Which masses sit where the law has no value, (N,) bool: a scene refuses to start there."""
        return np.zeros(len(r), dtype=bool)

    def program_values(self) -> dict:
        """The values of CONSTANTS this force holds, by name: a number, or an (N,) or (N, 3) array
        of one per mass. Raises ValueError where the program cannot write the force as it is."""
        return {name: getattr(self, name) for name in self.CONSTANTS}

    def program(self) -> tuple[tuple[str, str], ...]:
        """Its PROGRAM lines, as they apply to this force (Spring: a shorter law where L0 = 0)."""
        return self.PROGRAM


def _column(value, count: int) -> np.ndarray:
    """A parameter as one number per mass, (count,)."""
    return np.broadcast_to(np.asarray(value, dtype=float).reshape(-1, 1), (count, 1))[:, 0]


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
    CONSTANTS = {
        "k": Declared("N/m", 0, 1e6, meaning="spring constant"),
        "L0": Declared("m", 0, 1e4, meaning="relaxed length of the spring"),
        "anchor": Declared("m", -1e4, 1e4, vector=True, meaning="fixed end of the spring"),
    }
    TERM = "Fspring"
    VECTORS = {"anchor": "point"}
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

    @classmethod
    def switched_on(cls, *, k, L0, anchor, **_others):
        """The spring of the single-mass scenes' constants (always there: k = 0 is a spring of no stiffness)."""
        return cls(k=k, L0=L0, anchor=anchor)

    def rates(self, m, speed):
        return {"stiffness": _column(self.k, len(m))}

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
    CONSTANTS = {"g": Declared("m/s²", 0, 1e3, note="it is a magnitude; gravity acts along −y",
                               slider_from_zero=True, meaning="strength of gravity, along −y")}
    TERM = "Fgravity"
    VECTORS = {"direction": "direction", "g_vector": "direction"}
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

    @classmethod
    def switched_on(cls, *, g, **_others):
        return cls(g=g) if g else None

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
    CONSTANTS = {"b": Declared("kg/s", 0, 1e6, none="critical damping, b = 2√(mk)", slider_from_zero=True,
                               meaning="linear damping constant in F = −b v")}
    TERM = "Fdamping"
    VECTORS = {}
    PROGRAM = (("Fdamping = -{b}*{v}", "linear damping: F = −b v"),)

    def __post_init__(self):
        object.__setattr__(self, "b", _per_mass(self.b))
        object.__setattr__(self, "_minus_b", -self.b)      # −b once, not at every call

    def __call__(self, t, r, v, m):
        return self._minus_b * v

    @classmethod
    def switched_on(cls, *, b, **_others):
        return cls(b=b) if b else None

    def rates(self, m, speed):
        return {"damping": _column(self.b, len(m)) / m}      # F = −b v = −(b/m) m v


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
    CONSTANTS = {
        "C": Declared("1", 0, 100, slider_from_zero=True, meaning="drag coefficient"),
        "A": Declared("m²", 0, 1e3, meaning="cross-section area, for drag"),
        "rho": Declared("kg/m³", 0, 1e5, symbol="ρ", meaning="air density, for drag"),
    }
    TERM = "Fdrag"
    VECTORS = {}
    PROGRAM = (("Fdrag = -0.5*{C}*{A}*{rho}*mag({v})*{v}", "air drag: F = −½ C A ρ |v|² v̂ = −½ C A ρ |v| v"),)

    def __post_init__(self):
        for name in ("C", "A", "rho"):
            object.__setattr__(self, name, _per_mass(getattr(self, name)))

    def __call__(self, t, r, v, m):
        speed = magnitude(v)
        return -0.5 * self.C * self.A * self.rho * speed * v

    @classmethod
    def switched_on(cls, *, C, A, rho, **_others):
        return cls(C=C, A=A, rho=rho) if C and A and rho else None

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
    CONSTANTS = {
        "F0": Declared("N", -1e6, 1e6, slider_from_zero=True, meaning="driving force amplitude in F = F0 cos(ω t)"),
        "omega": Declared("rad/s", 0, 1e4, symbol="ω", slider_from_zero=True,
                          meaning="driving angular frequency ω (rad/s, not Hz)"),
        "drive_axis": Declared("1", -1e6, 1e6, vector=True, nonzero=True,
                               meaning="direction of the driving force (a unit vector)"),
    }
    TERM = "Fdrive"
    VECTORS = {"axis": "direction"}
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
    def switched_on(cls, *, F0, omega, drive_axis, **_others):
        return cls(F0=F0, omega=omega, axis=drive_axis) if F0 else None

    def program_values(self):
        return {"F0": self.F0, "omega": self.omega, "drive_axis": self.axis}


# The page's forces, in the order it adds them: what the single-mass scenes switch on from their
# constants (each class's switched_on gives the force, or None where its constant is 0).
PAGE_FORCES = (Spring, Gravity, LinearDamping, QuadraticDrag, Driving)


def declared_constants() -> dict[str, Declared]:
    """Every force's CONSTANTS, by name. Raises ValueError where two forces declare one name differently."""
    declared: dict[str, Declared] = {}
    for cls in FORCES:
        for name, declaration in cls.CONSTANTS.items():
            if declared.setdefault(name, declaration) != declaration:
                raise ValueError(f"two forces declare the constant {name} differently ({cls.__name__} is one)")
    return declared


def uses_velocity(forces) -> bool:
    """Whether any force in the list depends on v (damping, drag). If none does, the integrators
    may pass v = None."""
    return any(force.uses_velocity for force in forces)


def net_force(forces, t, r, v, m) -> np.ndarray:
    """F_net = the sum of every force in the list, shape (N, 3), N (zero for an empty list)."""
    F_net = None
    for force in forces:
        F = force(t, r, v, m)
        if F_net is None:
            F_net = F          # each force returns a new array, so we may add into it
        else:
            F_net += F
    return np.zeros_like(r) if F_net is None else F_net

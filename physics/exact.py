"""Exact (closed-form) solutions for the linear cases: the oracle the integrators are tested against.

The damped, driven oscillator, for the displacement x from equilibrium:

    m x'' + b x' + k x = F0 cos(ω t),     x(0) = x0,  x'(0) = v0

With ω0 = √(k/m) and γ = b / 2m, its motion is a transient (the free motion) plus a steady state:

- under-damped  (b² < 4mk): x_h = e^(−γt) (c1 cos ωd t + c2 sin ωd t),  ωd = √(ω0² − γ²)
- critical      (b² = 4mk): x_h = e^(−γt) (c1 + c2 t)            fastest return, never crosses twice
- over-damped   (b² > 4mk): x_h = A e^(λ₊t) + B e^(λ₋t),  λ± = −γ ± √(γ² − ω0²)
- steady state: x_p = F0 cos(ω t − δ) / √((k − mω²)² + (bω)²),  tan δ = bω / (k − mω²)
- undamped resonance (b = 0, ω = ω0): x_p = F0 t sin(ω0 t) / (2 m ω0), growing linearly in t, so
  there is no steady-state amplitude (:func:`steady_state_amplitude` gives inf there).

The free motion never gains energy (dE/dt = −b v² ≤ 0), which bounds the whole swing:
:func:`displacement_bound`.

Gravity only shifts the equilibrium of a spring by m g / k; :func:`single_mass_motion` applies that
shift for a mass moving along one line, and gives None where no closed form holds (quadratic drag,
motion off the line of the spring, k = 0).

Every formula works elementwise on arrays: :func:`oscillator` takes one value per mass of b, x0,
v0, F0, ω (and m, k), and picks each element's damping regime, and undamped resonance, by masks,
so a row of 10⁴ springs is one call; :func:`row_motion` is :func:`single_mass_motion` for a whole
row, each mass on its own line. One mass is the same code on arrays of one element.
"""
from __future__ import annotations

import numpy as np

class Role:
    """The closed form's parameters, by role: the keywords of single_mass_motion and row_motion.

    Each force's closed_form() gives the values of its roles by these keys, and its CLOSED_FORM
    names the constant that holds each (physics/forces/base.py closed_form_constants): the
    program's exact curve (export/exact_curve.py) finds its constants by role, never by name.
    """

    STIFFNESS = "k"               # N/m, in −k (|L| − L0) L̂
    NATURAL_LENGTH = "L0"         # m, the spring's relaxed length
    ANCHOR = "anchor"             # m, the spring's fixed end
    GRAVITY = "g"                 # m/s², along −y
    DAMPING = "b"                 # kg/s, in −b v
    DRIVE_AMPLITUDE = "F0"        # N, in F0 cos(ω t)
    DRIVE_FREQUENCY = "omega"     # rad/s, ω in F0 cos(ω t)
    DRIVE_AXIS = "drive_axis"     # the driving force's direction


ROLES = tuple(value for name, value in vars(Role).items() if name.isupper())

CRITICAL_RTOL = 1e-9        # b² within this fraction of 4mk is critical damping (damping_regime)
RESONANCE_RTOL = 1e-12      # ω within this fraction of ω0, with b = 0, is undamped resonance


def damping_regime(*, m: float, k: float, b: float, rtol: float = CRITICAL_RTOL) -> str:
    """'under-damped' if b² < 4mk, 'critically damped' if b² = 4mk (within rtol), else 'over-damped'."""
    critical, under = _regimes(m=m, k=k, b=b, rtol=rtol)
    return "critically damped" if critical else "under-damped" if under else "over-damped"


def _regimes(*, m, k, b, rtol: float = CRITICAL_RTOL):
    """Elementwise masks (critical, under) of b² = 4mk (within rtol) and b² < 4mk: damping_regime's
    test for every element of arrays of m, k and b at once. Neither: over-damped."""
    b = np.asarray(b, dtype=float)
    critical = 4.0 * np.asarray(m, dtype=float) * k
    at_critical = np.abs(b * b - critical) <= rtol * np.maximum(critical, 1e-300)
    return at_critical, ~at_critical & (b * b < critical)


# _regimes' test as a program writes it (export/exact_curve.py's branches, a row's labels): each
# regime with its condition in {b}, {m} and {k}, in the order tried; the last holds otherwise.
REGIME_TESTS = (("critically damped", "abs({b}**2 - 4*{m}*{k}) <= " + repr(CRITICAL_RTOL) + "*4*{m}*{k}"),
                ("under-damped", "{b}**2 < 4*{m}*{k}"),
                ("over-damped", ""))


def regime_lines(*, b: str, m: str, k: str) -> list[str]:
    """damping_regime as lines of a program (Python and Web VPython alike) that set `regime`, for
    the program's names of b, m and k: `if abs(b**2 - 4*m*k) <= ...:` / `regime = "critically damped"` ..."""
    lines = []
    for n, (regime, test) in enumerate(REGIME_TESTS):
        lines.append(f"{'if' if n == 0 else 'elif'} {test.format(b=b, m=m, k=k)}:" if test else "else:")
        lines.append(f'    regime = "{regime}"')
    return lines


def critical_damping(*, m: float, k: float) -> float:
    """b = 2√(mk), the damping constant of critical damping, kg/s."""
    return 2.0 * np.sqrt(m * k)


def undamped_resonance(*, m, k, b, omega):
    """Whether b = 0 and ω = ω0 = √(k/m) (to round-off), elementwise: undamped resonance."""
    omega0 = np.sqrt(k / m)
    return (np.asarray(b) == 0) & (np.abs(np.asarray(omega) - omega0) <= RESONANCE_RTOL * omega0)


def steady_state_amplitude(*, m, k, b, F0, omega):
    """A = F0 / √((k − mω²)² + (bω)²), m. Works elementwise on arrays of b, F0 and ω (a resonance curve).

    At undamped resonance (b = 0, ω = ω0) there is no steady state: the swing grows as
    F0 t / (2 m ω0) for ever, and A is ±math.inf there (the sign of F0; 0 if F0 = 0). Whoever
    shows A must say so in words.
    """
    F0 = np.asarray(F0, dtype=float)
    unbounded = undamped_resonance(m=m, k=k, b=b, omega=omega)
    with np.errstate(divide="ignore", invalid="ignore"):   # only where unbounded: settled just below
        A = F0 / np.hypot(k - m * omega**2, b * omega)   # hypot: no underflow of (bω)² for a tiny b
    return np.where(unbounded, np.where(F0 == 0, 0.0, np.copysign(np.inf, F0)), A)[()]


def displacement_bound(T, *, m, k, b, x0, v0, F0, omega):
    """A size |x(t)| never exceeds for 0 ≤ t ≤ T, m, for the oscillator of :func:`oscillator`
    (b ≥ 0, k > 0). Works elementwise on arrays of b, x0, v0, F0 and ω.

    x = x_h + x_p. The free motion x_h loses energy to damping and never gains any
    (dE/dt = −b v² ≤ 0 for E = ½ m v² + ½ k x²), so ½ k x_h² ≤ E(0): |x_h| ≤ √(x_h0² + (v_h0/ω0)²),
    with x_h0 = x0 − x_p(0) and v_h0 = v0 − v_p(0). The steady state swings within |A|; at undamped
    resonance it grows, |x_p| ≤ |F0| T / (2 m ω0).
    """
    omega0 = np.sqrt(k / m)
    resonant = undamped_resonance(m=m, k=k, b=b, omega=omega)
    A = np.where(resonant, 0.0, steady_state_amplitude(m=m, k=k, b=b, F0=F0, omega=omega))
    delta = np.arctan2(b * omega, k - m * omega**2)
    xp0, vp0 = A * np.cos(delta), A * omega * np.sin(delta)   # x_p(0), v_p(0); 0 at undamped resonance
    free = np.hypot(x0 - xp0, (v0 - vp0) / omega0)
    forced = np.where(resonant, np.abs(F0) * T / (2.0 * m * omega0), np.abs(A))
    return (free + forced)[()]


def _elementwise(regimes, t, **parameters):
    """x(t), v(t) from the closed form of each element's case, on arrays of t and the parameters
    broadcast together: `regimes` pairs a case's formula with the mask, over the parameters, of the
    elements it holds for (a damping regime, undamped resonance). Each formula sees only its own
    elements, as one mass at a time would (all of them at once where one case holds for all); an
    element no mask covers stays 0."""
    t = np.asarray(t, dtype=float)
    parameters = dict(zip(parameters, np.broadcast_arrays(*(np.asarray(value, dtype=float)
                                                            for value in parameters.values()))))
    shape = np.broadcast_shapes(t.shape, *(value.shape for value in parameters.values()))
    x, v = np.zeros(shape), np.zeros(shape)
    for formula, mask in regimes(**parameters):
        if mask.all():
            x[...], v[...] = formula(t, **parameters)
        elif mask.any():
            mask = np.broadcast_to(mask, shape)
            x[mask], v[mask] = formula(np.broadcast_to(t, shape)[mask],
                                       **{name: np.broadcast_to(value, shape)[mask]
                                          for name, value in parameters.items()})
    return x, v


def _steady_state(t, *, m, k, b, F0, omega):
    """x_p(t), v_p(t): the particular solution driven by F0 cos(ω t); 0 where F0 = 0."""
    def regimes(*, m, k, b, F0, omega):
        resonant = undamped_resonance(m=m, k=k, b=b, omega=omega)
        return (_growing, (F0 != 0) & resonant), (_swinging, (F0 != 0) & ~resonant)
    return _elementwise(regimes, t, m=m, k=k, b=b, F0=F0, omega=omega)


def _growing(t, *, m, k, b, F0, omega):
    """Undamped resonance: x_p = F0 t sin(ω0 t) / (2 m ω0)."""
    omega0 = np.sqrt(k / m)
    growth = F0 / (2.0 * m * omega0)
    return (growth * t * np.sin(omega0 * t),
            growth * (np.sin(omega0 * t) + omega0 * t * np.cos(omega0 * t)))


def _swinging(t, *, m, k, b, F0, omega):
    """The steady state x_p = A cos(ω t − δ), tan δ = bω / (k − mω²)."""
    A = steady_state_amplitude(m=m, k=k, b=b, F0=F0, omega=omega)
    delta = np.arctan2(b * omega, k - m * omega**2)
    phase = omega * t - delta
    return A * np.cos(phase), -A * omega * np.sin(phase)


def _free_motion(t, *, m, k, b, x0, v0):
    """x_h(t), v_h(t): the undriven motion from x0, v0, each element in its own damping regime."""
    def regimes(*, m, k, b, x0, v0):
        critical, under = _regimes(m=m, k=k, b=b)
        return (_under_damped, under), (_critically_damped, critical), (_over_damped, ~(critical | under))
    return _elementwise(regimes, t, m=m, k=k, b=b, x0=x0, v0=v0)


def _under_damped(t, *, m, k, b, x0, v0):
    """x_h = e^(−γt) (c1 cos ωd t + c2 sin ωd t), ωd = √(ω0² − γ²)."""
    gamma = b / (2.0 * m)
    omega_d = np.sqrt(k / m - gamma**2)
    c1, c2 = x0, (v0 + gamma * x0) / omega_d
    decay, cos, sin = np.exp(-gamma * t), np.cos(omega_d * t), np.sin(omega_d * t)
    x = decay * (c1 * cos + c2 * sin)
    v = decay * ((c2 * omega_d - gamma * c1) * cos - (c1 * omega_d + gamma * c2) * sin)
    return x, v


def _critically_damped(t, *, m, k, b, x0, v0):
    """x_h = e^(−γt) (c1 + c2 t)."""
    gamma = b / (2.0 * m)
    c1, c2 = x0, v0 + gamma * x0
    decay = np.exp(-gamma * t)
    return decay * (c1 + c2 * t), decay * (c2 - gamma * (c1 + c2 * t))


def _over_damped(t, *, m, k, b, x0, v0):
    """x_h = A e^(λ₊t) + B e^(λ₋t),  λ± = −γ ± √(γ² − ω0²)."""
    gamma = b / (2.0 * m)
    mu = np.sqrt(gamma**2 - k / m)
    lam_plus, lam_minus = -gamma + mu, -gamma - mu
    A = (v0 - lam_minus * x0) / (lam_plus - lam_minus)
    B = x0 - A
    e_plus, e_minus = np.exp(lam_plus * t), np.exp(lam_minus * t)
    return A * e_plus + B * e_minus, A * lam_plus * e_plus + B * lam_minus * e_minus


def oscillator(t, *, m, k, b=0.0, x0=0.0, v0=0.0, F0=0.0, omega=0.0):
    """Exact x(t) in m and v(t) in m/s of m x'' + b x' + k x = F0 cos(ω t), x(0) = x0, x'(0) = v0.

    x is the displacement from equilibrium. Needs m > 0 and k > 0 when F0 ≠ 0. Works elementwise:
    t and each parameter may be an array, broadcast together as numpy does (t of shape (T, 1) with
    parameters of shape (N,) gives (T, N): N oscillators at once, each in its own damping regime).
    """
    t = np.asarray(t, dtype=float)
    xp0, vp0 = _steady_state(0.0, m=m, k=k, b=b, F0=F0, omega=omega)      # x_p(0), v_p(0)
    xp, vp = _steady_state(t, m=m, k=k, b=b, F0=F0, omega=omega)
    xh, vh = _free_motion(t, m=m, k=k, b=b, x0=x0 - xp0, v0=v0 - vp0)
    return xh + xp, vh + vp


def lengths(vectors) -> np.ndarray:
    """|a| = √(a·a) of each row of an (N, 3) array, (N,) (of one 3-vector: a number): what np.linalg.norm gives for each row
    alone, bit for bit (numpy's dot of each row; a sum along the rows rounds differently)."""
    return np.sqrt(_dots(vectors, vectors))


def _dots(a, b) -> np.ndarray:
    """a·b of each row of a and b ((N, 3) or one 3-vector), (N,): numpy's dot of each pair of rows."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return np.matmul(a[..., None, :], b[..., :, None])[..., 0, 0]


def single_mass_motion(*, m, k=0.0, L0=0.0, g=0.0, b=0.0, C=0.0, F0=0.0, omega=0.0, drive_axis=(1.0, 0.0, 0.0),
                       anchor=(0.0, 0.0, 0.0), r0, v0):
    """The exact motion of one mass on a spring, or None where no closed form applies: row_motion
    for a row of one mass. A term left out is not there (no gravity, no damping, no drive): the
    forces' closed_form() give the terms present (physics/forces/).

    Returns a function t -> (r, v), arrays of shape (len(t), 3) in m and m/s. It is valid while
    the mass stays on its side of the anchor (the spring never turns inside out).
    """
    known, motion = row_motion(m=m, k=k, L0=L0, g=g, b=b, C=C, F0=F0, omega=omega, drive_axis=drive_axis,
                               anchors=np.reshape(np.asarray(anchor, dtype=float), (1, 3)),
                               r0=np.reshape(np.asarray(r0, dtype=float), (1, 3)), v0=v0)
    if not known[0]:
        return None

    def one_mass(t):
        r, v = motion(t)
        return r[:, 0], v[:, 0]
    return one_mass


def row_motion(*, m, k, L0, g, b, C, F0, omega, drive_axis, anchors, r0, v0, covered=True):
    """The exact motion of a row of masses, each on its own spring from its own anchor, all at once.

    A closed form exists for a mass when its motion stays on one straight line through its anchor
    (the spring, v0, gravity and the driving force all along it; or any direction when L0 = 0, since
    then the spring is linear in 3-D), with no quadratic drag (C = 0) and k > 0. Along that line the
    spring force is −k(s − L0) for the coordinate s from the anchor, so with gravity the equilibrium
    sits at s_eq = L0 + m g (ĝ·û) / k and x = s − s_eq obeys the oscillator equation of
    :func:`oscillator`.

    anchors and r0 are (N, 3) m; v0 (m/s) and b, C, F0, ω one value or one per mass; m, k, L0, g
    and the drive's direction are the row's. `covered` (one value or one per mass) is False for a
    mass on which a force acts that the closed form does not cover (quadratic drag, friction). Returns (known, motion): which masses have a closed
    form, (N,) bool, and t -> (r, v) of shape (len(t), N, 3) in m and m/s, NaN ("not known") for a
    mass that has none. Each mass's is valid while it stays on its side of its anchor.
    """
    r0 = np.asarray(r0, dtype=float)
    count = len(r0)
    anchors, v0 = (np.broadcast_to(np.asarray(a, dtype=float), (count, 3)) for a in (anchors, v0))
    b, C, F0, omega = (np.broadcast_to(np.asarray(x, dtype=float), (count,)) for x in (b, C, F0, omega))
    # the drive's unit direction, for the masses it drives (none where F0 = 0)
    drive = np.asarray(drive_axis, dtype=float)
    unit = drive / lengths(drive) if np.any(F0 != 0) else np.zeros(3)
    drive = np.where((F0 != 0)[:, None], unit, 0.0)
    known = (C == 0) & (k > 0) & np.broadcast_to(np.asarray(covered, dtype=bool), (count,))
    if known.any():
        line = _in_3d if L0 == 0 else _on_lines
        known, parameters, place = line(known, m=m, k=k, L0=L0, g=g, b=b, F0=F0, omega=omega, drive=drive,
                                        anchors=anchors, r0=r0, v0=v0)

    def motion(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        r, v = np.full((len(t), count, 3), np.nan), np.full((len(t), count, 3), np.nan)
        if known.any():
            r[:, known], v[:, known] = place(*oscillator(t[:, None, None], m=m, k=k, **parameters))
        return r, v
    return known, motion


GRAVITY = np.array([0.0, -1.0, 0.0])   # gravity along −y, as physics.forces.Gravity


def _in_3d(known, *, m, k, L0, g, b, F0, omega, drive, anchors, r0, v0):
    """L0 = 0: each component is its own oscillator about anchor + m g / k. The row_motion masses
    that have a closed form, the oscillator's parameters for them ((n, 3) each), and the function
    that turns its x, v into r, v."""
    r_eq = anchors[known] + m * (g * GRAVITY) / k
    parameters = dict(b=b[known, None], x0=r0[known] - r_eq, v0=v0[known], F0=F0[known, None] * drive[known],
                      omega=omega[known, None])
    return known, parameters, lambda x, v: (r_eq + x, v)


def _on_lines(known, *, m, k, L0, g, b, F0, omega, drive, anchors, r0, v0):
    """L0 > 0: each mass along its spring's line û from its anchor, where v0, gravity and the drive
    lie on that line. As _in_3d, with the oscillator's parameters (n, 1) each."""
    s0_vec = r0 - anchors
    s0 = lengths(s0_vec)
    known = known & (s0 != 0)
    u = s0_vec[known] / s0[known, None]
    (v0_u, v0_on), (g_u, g_on), (drive_u, drive_on) = (
        _along(vector, u) for vector in (v0[known], g * GRAVITY, drive[known]))
    on_line = v0_on & g_on & drive_on
    known[known] = on_line
    u, v0_u, g_u, drive_u = u[on_line], v0_u[on_line], g_u[on_line], drive_u[on_line]
    s_eq = L0 + m * g_u / k
    parameters = dict(b=b[known, None], x0=(s0[known] - s_eq)[:, None], v0=v0_u[:, None],
                      F0=(F0[known] * drive_u)[:, None], omega=omega[known, None])
    anchor = anchors[known]
    return known, parameters, lambda x, v: (anchor + (s_eq[:, None] + x) * u, v * u)


def _along(vector, u):
    """The part of each vector (one, or one per row of u) along the unit rows u, and whether the
    vector lies on that line."""
    vector = np.broadcast_to(np.asarray(vector, dtype=float), u.shape)
    component = _dots(vector, u)
    off_line = vector - component[:, None] * u
    return component, lengths(off_line) <= 1e-12 * np.maximum(1.0, lengths(vector))

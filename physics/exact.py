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
"""
from __future__ import annotations

import math

import numpy as np



def damping_regime(*, m: float, k: float, b: float, rtol: float = 1e-9) -> str:
    """'under-damped' if b² < 4mk, 'critically damped' if b² = 4mk (within rtol), else 'over-damped'."""
    critical = 4.0 * m * k
    if abs(b * b - critical) <= rtol * max(critical, 1e-300):
        return "critically damped"
    return "under-damped" if b * b < critical else "over-damped"


def critical_damping(*, m: float, k: float) -> float:
    """b = 2√(mk), the damping constant of critical damping, kg/s."""
    return 2.0 * np.sqrt(m * k)


def undamped_resonance(*, m, k, b, omega):
    """Whether b = 0 and ω = ω0 = √(k/m) (to round-off), elementwise: undamped resonance."""
    omega0 = np.sqrt(k / m)
    return (np.asarray(b) == 0) & (np.abs(np.asarray(omega) - omega0) <= 1e-12 * omega0)


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


def _steady_state(t, *, m, k, b, F0, omega):
    """x_p(t), v_p(t): the particular solution driven by F0 cos(ω t)."""
    if F0 == 0:
        zero = np.zeros_like(t)
        return zero, zero
    omega0 = np.sqrt(k / m)
    if undamped_resonance(m=m, k=k, b=b, omega=omega):
        # Undamped resonance: x_p = F0 t sin(ω0 t) / (2 m ω0).
        growth = F0 / (2.0 * m * omega0)
        return (growth * t * np.sin(omega0 * t),
                growth * (np.sin(omega0 * t) + omega0 * t * np.cos(omega0 * t)))
    A = steady_state_amplitude(m=m, k=k, b=b, F0=F0, omega=omega)
    delta = np.arctan2(b * omega, k - m * omega**2)
    phase = omega * t - delta
    return A * np.cos(phase), -A * omega * np.sin(phase)


def _free_motion(t, *, m, k, b, x0, v0):
    """x_h(t), v_h(t): the undriven motion from x0, v0 in the right damping regime."""
    gamma = b / (2.0 * m)
    omega0_sq = k / m
    regime = damping_regime(m=m, k=k, b=b)
    decay = np.exp(-gamma * t)
    if regime == "under-damped":
        omega_d = np.sqrt(omega0_sq - gamma**2)
        c1, c2 = x0, (v0 + gamma * x0) / omega_d
        cos, sin = np.cos(omega_d * t), np.sin(omega_d * t)
        x = decay * (c1 * cos + c2 * sin)
        v = decay * ((c2 * omega_d - gamma * c1) * cos - (c1 * omega_d + gamma * c2) * sin)
        return x, v
    if regime == "critically damped":
        c1, c2 = x0, v0 + gamma * x0
        return decay * (c1 + c2 * t), decay * (c2 - gamma * (c1 + c2 * t))
    mu = np.sqrt(gamma**2 - omega0_sq)
    lam_plus, lam_minus = -gamma + mu, -gamma - mu
    A = (v0 - lam_minus * x0) / (lam_plus - lam_minus)
    B = x0 - A
    e_plus, e_minus = np.exp(lam_plus * t), np.exp(lam_minus * t)
    return A * e_plus + B * e_minus, A * lam_plus * e_plus + B * lam_minus * e_minus


def oscillator(t, *, m, k, b=0.0, x0=0.0, v0=0.0, F0=0.0, omega=0.0):
    """Exact x(t) in m and v(t) in m/s of m x'' + b x' + k x = F0 cos(ω t), x(0) = x0, x'(0) = v0.

    x is the displacement from equilibrium. Needs m > 0 and k > 0 when F0 ≠ 0.
    """
    t = np.asarray(t, dtype=float)
    xp, vp = _steady_state(np.append(0.0, t), m=m, k=k, b=b, F0=F0, omega=omega)   # at 0, then at t
    xh, vh = _free_motion(t, m=m, k=k, b=b, x0=x0 - xp[0], v0=v0 - vp[0])
    return xh + xp[1:].reshape(t.shape), vh + vp[1:].reshape(t.shape)


def _length(vector: np.ndarray) -> float:
    """|a| = √(a·a) of one vector, m: what np.linalg.norm works out for it, without its overhead
    (a closed form per mass, for 10⁴ masses, asks for it 10⁵ times)."""
    return math.sqrt(vector @ vector)


def _along(vector, u):
    """The part of vector along unit u, and whether vector lies on that line."""
    vector = np.asarray(vector, dtype=float)
    component = float(vector @ u)
    off_line = vector - component * u
    return component, bool(_length(off_line) <= 1e-12 * max(1.0, _length(vector)))


def single_mass_motion(*, m, k, L0, g, b, C, F0, omega, drive_axis, anchor, r0, v0):
    """The exact motion of one mass on a spring, or None where no closed form applies.

    A closed form exists when the motion stays on one straight line through the anchor (the spring,
    v0, gravity and the driving force all along it; or any direction when L0 = 0, since then the
    spring is linear in 3-D), with no quadratic drag (C = 0) and k > 0. Along that line the spring
    force is −k(s − L0) for the coordinate s from the anchor, so with gravity the equilibrium sits at
    s_eq = L0 + m g (ĝ·û) / k and x = s − s_eq obeys the oscillator equation of :func:`oscillator`.

    Returns a function t -> (r, v), arrays of shape (len(t), 3) in m and m/s. It is valid while
    the mass stays on its side of the anchor (the spring never turns inside out).
    """
    if C != 0 or k <= 0:
        return None
    anchor, r0, v0 = (np.asarray(a, dtype=float) for a in (anchor, r0, v0))
    g_vec = g * np.array([0.0, -1.0, 0.0])        # gravity along −y, as physics.forces.Gravity
    drive = np.asarray(drive_axis, dtype=float)
    drive = drive / _length(drive) if F0 != 0 else np.zeros(3)
    if L0 == 0:
        def motion_3d(t):
            # Each component is its own oscillator about anchor + m g / k.
            t = np.atleast_1d(np.asarray(t, dtype=float))
            r_eq = anchor + m * g_vec / k
            xs, vs = zip(*(oscillator(t, m=m, k=k, b=b, x0=(r0 - r_eq)[i], v0=v0[i],
                                      F0=F0 * drive[i], omega=omega) for i in range(3)))
            return r_eq + np.stack(xs, axis=-1), np.stack(vs, axis=-1)
        return motion_3d
    s0_vec = r0 - anchor
    s0 = _length(s0_vec)
    if s0 == 0:
        return None
    u = s0_vec / s0
    parts = [_along(vec, u) for vec in (v0, g_vec, drive)]
    if not all(on_line for _, on_line in parts):
        return None
    (v0_u, _), (g_u, _), (drive_u, _) = parts
    s_eq = L0 + m * g_u / k

    def motion(t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        x, v = oscillator(t, m=m, k=k, b=b, x0=s0 - s_eq, v0=v0_u, F0=F0 * drive_u, omega=omega)
        return anchor + np.outer(s_eq + x, u), np.outer(v, u)
    return motion

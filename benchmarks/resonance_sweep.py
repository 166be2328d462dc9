"""Part 3: a resonance curve, 1,000 driving frequencies at once, against scipy's solve_ivp.

The driven scene's oscillator (m = 4 kg, k = 100 N/m, so ω0 = √(k/m) = 5 rad/s, F0 = 1 N) with
linear damping b is driven at ω from 0.5 ω0 to 2 ω0. Each mass starts at rest at equilibrium and
runs for 60 s. The free motion (transient) dies as e^(−γt) with γ = b / 2m, so 60 s must be many
times 1/γ; what is left is the steady state x = A cos(ωt − δ) with

    A = F0 / √((k − mω²)² + (bω)²)          (physics.exact.steady_state_amplitude)

In the steady state x² + (v/ω)² = A² at every instant, so we measure A without sampling bias as
√(x² + (v/ω)²), averaged over the last 10 s; its spread over that window shows what is left of
the transient.

All 1,000 frequencies are one batch: physics.forces.Driving takes a per-mass ω, and
physics.simulate.run steps it (recording only the final state until the window starts,
then every step). We step with rk4
at Δt = 0.05 s (ω Δt ≤ 0.5): four force evaluations per step, but far fewer steps than
Euler-Cromer needs for the same accuracy (the full run shows euler-cromer and verlet at
Δt = 0.01 s next to it; part 4 shows why). solve_ivp (RK45, rtol 1e-6) solves
the same equation one frequency at a time; we time a subset and scale it up, and say so.
"""
from __future__ import annotations

import numpy as np

from physics.exact import steady_state_amplitude
from physics.forces import Driving, LinearDamping, Spring
from physics.simulate import run
from physics.state import make_state

from .common import best_of, table, timed, verdict

m = 4.0          # kg
k = 100.0        # N/m
L0 = 1.0         # m, the spring lies along x from an anchor at the origin
F0 = 1.0         # N
omega0 = np.sqrt(k / m)    # rad/s
duration = 60.0  # s of simulated time per frequency
window = 10.0    # s: the amplitude is measured over the last 10 s
integrator = "rk4"
dt = 0.05        # s


def frequencies(count: int = 1000) -> np.ndarray:
    """Driving angular frequencies ω from 0.5 ω0 to 2 ω0, rad/s."""
    return np.linspace(0.5 * omega0, 2.0 * omega0, count)


def exact_amplitudes(omega, b) -> np.ndarray:
    return steady_state_amplitude(m=m, k=k, b=b, F0=F0, omega=omega)


def batch_sweep(omega, b, *, dims: int = 3, method: str = integrator, step_dt: float = dt):
    """Steady-state amplitudes (m) and their relative spread over the window, all ω in one batch.

    b may be one number or one value per mass (kg/s).
    """
    N = len(omega)
    if dims == 3:
        r = np.tile([L0, 0.0, 0.0], (N, 1))
        axis, anchor = (1.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    else:
        r, axis, anchor = np.full((N, 1), L0), (1.0,), (0.0,)
    forces = (Spring(k=k, L0=L0, anchor=anchor), LinearDamping(b=b), Driving(F0=F0, omega=omega, axis=axis))
    state = make_state(r=r, m=m)
    # physics.simulate.run, with its blow-up guard: to the start of the window keeping only the
    # final state, then every step of the window.
    settled = run(state, forces, dt=step_dt, until=duration - window, integrator=method, record_every=None)
    measured = run(settled.final, forces, dt=step_dt, until=duration, integrator=method)
    x = measured.r[1:, :, 0] - L0
    v = measured.v[1:, :, 0]
    samples = np.sqrt(x * x + (v / omega) ** 2)
    amplitude = samples.mean(axis=0)
    return amplitude, (samples.max(axis=0) - samples.min(axis=0)) / amplitude


def scipy_amplitude(omega: float, b: float, *, method: str = "RK45", rtol: float = 1e-6) -> float:
    """The same amplitude from solve_ivp for one ω: x'' = (F0 cos ωt − k x − b x') / m."""
    from scipy.integrate import solve_ivp

    def slopes(t, y):
        x, v = y
        return [v, (F0 * np.cos(omega * t) - k * x - b * v) / m]

    t_eval = np.linspace(duration - window, duration, 201)
    solution = solve_ivp(slopes, (0.0, duration), [0.0, 0.0], method=method, rtol=rtol, t_eval=t_eval)
    x, v = solution.y
    return float(np.mean(np.sqrt(x * x + (v / omega) ** 2)))


def main(settings) -> dict:
    omega = frequencies(1000)
    b = 2.0
    gamma = b / (2 * m)
    print(f"Part 3: resonance sweep, {len(omega)} frequencies ω = {omega[0]:g}…{omega[-1]:g} rad/s, "
          f"m = {m:g} kg, k = {k:g} N/m (ω0 = {omega0:g} rad/s), F0 = {F0:g} N, b = {b:g} kg/s, "
          f"{duration:g} s each")
    print(f"transient decay time 1/γ = 2m/b = {1 / gamma:g} s; e^(−γ·{duration - window:g} s) = "
          f"{np.exp(-gamma * (duration - window)):.1e} of it is left when measuring starts")
    rows, results = [], {}
    exact = exact_amplitudes(omega, b)
    for dims in (3, 1):
        (amplitude, spread), seconds = best_of(settings.pick(2, 1), batch_sweep, omega, b, dims=dims)
        error = float(np.max(np.abs(amplitude / exact - 1)))
        results[dims] = (seconds, error)
        rows.append([f"physics batch, {integrator} Δt = {dt:g} s, {dims}-D", f"{seconds:.2f} s",
                     f"{error * 100:.3f} %", f"{np.max(spread):.1e}"])
    subset = settings.pick(50, 10)
    picked = omega[:: len(omega) // subset][:subset]
    if not settings.quick:
        for method in ("euler-cromer", "verlet"):
            (amplitude, spread), seconds = timed(batch_sweep, omega, b, method=method, step_dt=0.01)
            rows.append([f"physics batch, {method} Δt = 0.01 s, 3-D", f"{seconds:.2f} s",
                         f"{np.max(np.abs(amplitude / exact - 1)) * 100:.3f} %", f"{np.max(spread):.1e}"])
    scipy_amps, scipy_seconds = timed(lambda: np.array([scipy_amplitude(w, b) for w in picked]))
    scipy_error = float(np.max(np.abs(scipy_amps / exact_amplitudes(picked, b) - 1)))
    scipy_total = scipy_seconds * len(omega) / subset
    rows.append([f"solve_ivp RK45 rtol 1e-6, loop (timed {subset}, ×{len(omega) // subset})",
                 f"{scipy_total:.1f} s", f"{scipy_error * 100:.3f} %", "-"])
    print(table(["method", "CPU time, 1000 ω", "max |A/A_exact − 1|", "spread in window"], rows))
    speedup = scipy_total / results[3][0]
    print(f"speed-up of the 3-D batch over the solve_ivp loop: {speedup:.0f}× (1-D: "
          f"{scipy_total / results[1][0]:.0f}×); target ≥ 100×: {verdict(speedup >= 100)}")
    print(f"amplitude within 1 % of the closed form: {results[3][1] * 100:.3f} % -> {verdict(results[3][1] <= 0.01)}")
    other_b = np.repeat([1.0, 5.0], len(omega))
    (amplitude, _), seconds = timed(batch_sweep, np.tile(omega, 2), other_b)
    errors = np.abs(amplitude / exact_amplitudes(np.tile(omega, 2), other_b) - 1).reshape(2, -1).max(axis=1)
    print(f"other damping, one batch of {len(other_b)} ({seconds:.2f} s): max error b = 1 kg/s (1/γ = 8 s): "
          f"{errors[0] * 100:.3f} %, b = 5 kg/s (1/γ = 1.6 s): {errors[1] * 100:.3f} %")
    return {"batch_seconds": results[3][0], "batch_error": results[3][1], "scipy_seconds": scipy_total,
            "scipy_error": scipy_error, "speedup": speedup}

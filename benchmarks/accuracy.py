"""Part 4: accuracy per cost. The error after 10 periods against the CPU time it took.

The page's hanging mass (k = 40 N/m, m = 10 kg, L0 = 1 m, g = 9.8 m/s², released from rest
1.5 m below the anchor) moves along y about the equilibrium L0 + m g / k below the anchor, with
period T = 2π √(m/k) = π s. physics.exact.single_mass_motion gives r(t) exactly, so the error is
|r − r_exact| at t = 10 T, in m.

Each of this project's integrators runs at Δt = T/n for several n (a method of order q gains q
decades of accuracy per decade of cost), through physics.simulate.run (for one mass, the compiled
float loop of physics/compiled.py) and, for comparison, through the numpy tick
(simulate.run(compiled=False)). scipy's solve_ivp (RK45 and DOP853, adaptive steps) runs at
several rtol on the same equations r' = p/m, p' = F_net, with the same physics force functions
on the right-hand side, so it pays what the numpy tick pays for one force evaluation.
CPU time is time.process_time(), so waiting for the other core does not count.
"""
from __future__ import annotations

import math
import os
import tempfile
import time

import numpy as np

from physics.exact import single_mass_motion
from physics.forces import net_force
from physics.integrators import INTEGRATORS
from physics.simulate import run
from physics.state import make_state, velocity
from scenes._single_mass import forces_for

from .common import table

k, m, L0, g = 40.0, 10.0, 1.0, 9.8
r0 = (0.0, -1.5, 0.0)
period = 2 * math.pi * math.sqrt(m / k)   # s
t_end = 10 * period                        # s
# The committed figure in docs/ is rewritten only on request (UPDATE_DOCS=1), so running the
# benchmarks leaves the checkout as it was; otherwise the plot goes to the temporary folder.
PLOT = (os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "docs", "accuracy_per_cost.png")
        if os.environ.get("UPDATE_DOCS") == "1"
        else os.path.join(tempfile.gettempdir(), "accuracy_per_cost.png"))


def _system():
    forces = forces_for(k=k, L0=L0, anchor=(0, 0, 0), g=g, b=0, C=0, A=0, rho=0, F0=0, omega=0,
                        drive_axis=(1, 0, 0))
    exact = single_mass_motion(m=m, k=k, L0=L0, g=g, b=0, C=0, F0=0, omega=0, drive_axis=(1, 0, 0),
                               anchor=(0, 0, 0), r0=r0, v0=(0, 0, 0))
    return make_state(r=r0, m=m), forces, exact(t_end)[0][0]


def cpu_seconds(function, minimum: float = 0.05):
    """(result, CPU seconds per call), repeating short calls until they add up to `minimum`."""
    calls, start = 0, time.process_time()
    while True:
        result = function()
        calls += 1
        spent = time.process_time() - start
        if spent >= minimum:
            return result, spent / calls


def integrator_error(name: str, per_period: int):
    """(error m, CPU s through simulate.run, CPU s of the same run through the numpy tick, compiled=False)."""
    state, forces, r_exact = _system()
    dt = period / per_period

    def project_run(compiled=True):
        return run(state, forces, dt=dt, until=t_end, integrator=name, record_every=None,
                   growth_limit=math.inf,              # euler grows 10⁷-fold at T/10: report it
                   compiled=compiled).r[-1, 0]

    def numpy_steps():
        return project_run(compiled=False)

    r, seconds = cpu_seconds(project_run)
    r_numpy, numpy_seconds = cpu_seconds(numpy_steps)
    if not np.allclose(r, r_numpy, rtol=1e-12, atol=1e-12):
        raise RuntimeError(f"{name}: simulate.run and its numpy tick disagree: {r} against {r_numpy}")
    return float(np.linalg.norm(r - r_exact)), seconds, numpy_seconds


def scipy_error(method: str, rtol: float):
    from scipy.integrate import solve_ivp

    state, forces, r_exact = _system()
    mass = state.m

    def slopes(t, y):
        r, p = y[:3].reshape(1, 3), y[3:].reshape(1, 3)
        v = velocity(p, mass)
        return np.concatenate([v[0], net_force(forces, t, r, v, mass)[0]])

    y0 = np.concatenate([state.r[0], state.p[0]])
    solution, seconds = cpu_seconds(
        lambda: solve_ivp(slopes, (0.0, t_end), y0, method=method, rtol=rtol, atol=rtol * 1e-2))
    return float(np.linalg.norm(solution.y[:3, -1] - r_exact)), seconds, solution.nfev, None


def measure(settings):
    """Rows (method, setting, error m, CPU s, force evaluations, CPU s of the numpy step or None)."""
    per_period = settings.pick([10, 20, 50, 100, 200, 500, 1000, 2000], [10, 30, 100])
    evaluations = {"euler": 1, "euler-cromer": 1, "verlet": 2, "rk4": 4}
    rows = []
    for name in INTEGRATORS:
        for n in per_period:
            error, seconds, numpy_seconds = integrator_error(name, n)
            rows.append((name, f"Δt = T/{n}", error, seconds, evaluations[name] * 10 * n, numpy_seconds))
    rtols = settings.pick([1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12], [1e-3, 1e-6, 1e-9])
    for method in ("RK45", "DOP853"):
        for rtol in rtols:
            error, seconds, nfev, _ = scipy_error(method, rtol)
            rows.append((f"solve_ivp {method}", f"rtol = {rtol:.0e}", error, seconds, nfev, None))
    return rows


def plot(rows, path: str = PLOT) -> str | None:
    """A log-log plot of error against CPU time, one line per method; None without matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    figure, axes = plt.subplots(figsize=(7.5, 5.0))
    for method in dict.fromkeys(row[0] for row in rows):
        mine = [row for row in rows if row[0] == method]
        errors = [max(row[2], 1e-16) for row in mine]
        line, = axes.loglog([row[3] for row in mine], errors, "o-", label=method)
        if mine[0][5] is not None:
            axes.loglog([row[5] for row in mine], errors, ":", color=line.get_color(), alpha=0.6)
    axes.set_xlabel("CPU time for 10 periods (s)")
    axes.set_ylabel("position error |r − r_exact| at t = 10 T (m)")
    axes.set_title("Accuracy per cost: hanging mass, k = 40 N/m, m = 10 kg, T = π s\n"
                   "solid: simulate.run (compiled float loop); dotted: simulate.run(compiled=False), the numpy tick", fontsize=10)
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    figure.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def cheapest_below(rows, tolerance: float):
    """For each method, the least CPU time that reaches an error ≤ tolerance (None if never)."""
    best = {}
    for method, _, error, seconds, *_ in rows:
        if error <= tolerance and (best.get(method) is None or seconds < best[method]):
            best[method] = seconds
        best.setdefault(method, None)
    return best


def main(settings) -> dict:
    print(f"Part 4: accuracy per cost, hanging mass (k = {k:g} N/m, m = {m:g} kg), error at "
          f"t = 10 T = {t_end:.4f} s, CPU time by time.process_time()")
    rows = measure(settings)
    print(table(["method", "setting", "error (m)", "CPU time", "force evaluations", "CPU, numpy tick"],
                [[a, b, f"{e:.2e}", f"{s * 1e3:.2f} ms", f"{n:,}", "-" if u is None else f"{u * 1e3:.2f} ms"]
                 for a, b, e, s, n, u in rows]))
    for tolerance in (1e-3, 1e-6):
        best = cheapest_below(rows, tolerance)
        print(f"cheapest CPU time to reach error ≤ {tolerance:g} m: " + ", ".join(
            f"{method} {'-' if s is None else f'{s * 1e3:.1f} ms'}" for method, s in best.items()))
    path = plot(rows)
    print(f"plot saved to {os.path.relpath(path)}" if path else "matplotlib not installed: no plot")
    return {"rows": rows, "plot": path}

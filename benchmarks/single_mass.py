"""Part 1: one mass, the page's 3-D gravity spring, stepped 10⁶ times at Δt = 1e-4 s.

Every loop below computes the same Euler-Cromer (momentum) update,

    L = r − anchor;  F = −k (|L| − L0) L̂ + m g;  p = p + F Δt;  r = r + (p/m) Δt

so they must agree on the final position to round-off. We compare this project's stepping
(physics.simulate.run with the scene's forces, which runs one mass through the float loop that
physics/compiled.py writes from the vector code; and the numpy step function on its own) with the
way classroom programs are written (vpython's vector class), with plain floats, and with naive
numpy (3,) arrays.
"""
from __future__ import annotations

import math

import numpy as np

from physics.integrators import euler_cromer
from physics.simulate import run
from physics.state import make_state
from scenes.single_mass import forces_for

from .common import best_of, table, timed, verdict
from .page_vector import load_vector

# The page's Simple Example (scenes/vertical.py), stepped finely.
k = 40.0            # N/m
m = 10.0            # kg
L0 = 1.0            # m
g = 9.8             # m/s², along −y
r0 = (0.0, -1.5, 0.0)   # m, from rest
anchor = (0.0, 0.0, 0.0)
dt = 1e-4           # s


def page_style_loop(steps: int):
    """The classroom program, with vpython's vector (no canvas is created)."""
    vector, mag, norm, _ = load_vector()
    pos = vector(*r0)
    p = vector(0, 0, 0)
    top = vector(*anchor)
    g_vec = vector(0, -g, 0)
    t = 0
    for _ in range(steps):
        L = pos - top
        F = -k * (mag(L) - L0) * norm(L) + m * g_vec
        p = p + F * dt
        pos = pos + p / m * dt
        t = t + dt
    return (pos.x, pos.y, pos.z)


def plain_float_loop(steps: int):
    """The same update written out in floats, one component at a time."""
    x, y, z = r0
    px = py = pz = 0.0
    for _ in range(steps):
        Lx, Ly, Lz = x - anchor[0], y - anchor[1], z - anchor[2]
        length = math.sqrt(Lx * Lx + Ly * Ly + Lz * Lz)
        pull = -k * (length - L0) / length
        px += pull * Lx * dt
        py += (pull * Ly - m * g) * dt
        pz += pull * Lz * dt
        x += px / m * dt
        y += py / m * dt
        z += pz / m * dt
    return (x, y, z)


def numpy_vector_loop(steps: int):
    """The page's loop with numpy (3,) arrays in place of vectors: the naive translation."""
    pos = np.array(r0)
    p = np.zeros(3)
    top = np.array(anchor)
    g_vec = np.array([0.0, -g, 0.0])
    for _ in range(steps):
        L = pos - top
        F = -k * (np.linalg.norm(L) - L0) * L / np.linalg.norm(L) + m * g_vec
        p = p + F * dt
        pos = pos + p / m * dt
    return tuple(pos)


def _scene():
    forces = forces_for(k=k, L0=L0, anchor=anchor, g=g, b=0, C=0, A=0, rho=0, F0=0, omega=0,
                        drive_axis=(1, 0, 0))
    return make_state(r=r0, m=m), forces


def project_step_loop(steps: int):
    """The numpy step function (physics.integrators.euler_cromer) in a bare loop, nothing recorded."""
    state, forces = _scene()
    for _ in range(steps):
        state = euler_cromer(state, forces, dt)
    return tuple(state.r[0])


def project_run(steps: int):
    """physics.simulate.run: the compiled float loop, recording every step, watching for blow-up."""
    state, forces = _scene()
    trajectory = run(state, forces, dt=dt, until=steps * dt)
    return tuple(trajectory.r[-1, 0])


def project_run_final_only(steps: int):
    """physics.simulate.run(record_every=None): the same steps, keeping only the final state."""
    state, forces = _scene()
    trajectory = run(state, forces, dt=dt, until=steps * dt, record_every=None)
    return tuple(trajectory.r[-1, 0])


def project_run_numpy(steps: int):
    """physics.simulate.run(compiled=False): every step a call of the numpy step function."""
    state, forces = _scene()
    trajectory = run(state, forces, dt=dt, until=steps * dt, record_every=None, compiled=False)
    return tuple(trajectory.r[-1, 0])


LOOPS = {
    "page-style (vpython vector)": page_style_loop,
    "plain floats": plain_float_loop,
    "numpy (3,) arrays": numpy_vector_loop,
    "project: euler_cromer numpy step loop": project_step_loop,
    "project: simulate.run, compiled=False": project_run_numpy,
    "project: simulate.run": project_run,
    "project: simulate.run, final only": project_run_final_only,
}
PROJECT = "project: simulate.run"
PAGE = "page-style (vpython vector)"

_reference = {}


def page_steps_per_second(steps: int = 200_000) -> float:
    """The page-style loop's speed in steps/s, measured once per process (the run's reference)."""
    if steps not in _reference:
        _, seconds = best_of(3, page_style_loop, steps)
        _reference[steps] = steps / seconds
    return _reference[steps]


def main(settings) -> dict:
    steps = settings.pick(1_000_000, 100_000)
    _, _, _, kind = load_vector()
    print(f"Part 1: one mass (k = {k:g} N/m, m = {m:g} kg, L0 = {L0:g} m, g = {g:g} m/s², "
          f"from {r0} m), Δt = {dt:g} s, {steps:,} steps")
    print(f"vpython vector loaded from {kind}, without importing vpython (no canvas, no server)")
    results = {}
    for name, loop in LOOPS.items():
        final, seconds = timed(loop, steps)
        results[name] = (final, seconds)
    page_final, page_seconds = results[PAGE]
    page_rate = steps / page_seconds
    _reference[steps] = page_rate
    rows = []
    for name, (final, seconds) in results.items():
        diff = max(abs(a - b) for a, b in zip(final, page_final))
        rows.append([name, f"{seconds:.2f} s", f"{steps / seconds / 1e6:.3f}",
                     f"{page_seconds / seconds:.2f}×", f"{final[1]:.9f}", f"{diff:.1e}"])
    print(table(["loop", "CPU time", "M steps/s (CPU)", "vs page", "final y (m)", "|Δr| vs page (m)"], rows))
    worst = max(max(abs(a - b) for a, b in zip(f, page_final)) for f, _ in results.values())
    print(f"all loops agree on the final position to {worst:.1e} m (required ≤ 1e-9 m): "
          f"{'yes' if worst <= 1e-9 else 'NO'}")
    project_ratio = page_seconds / results[PROJECT][1]
    print(f"target 'never slower than the page-style loop' (ratio ≥ 1), {PROJECT} recording "
          f"every step: {project_ratio:.2f}× "
          f"-> {verdict(project_ratio >= 1)}; aim 2×: {verdict(project_ratio >= 2)}")
    return {"steps": steps, "page_rate": page_rate, "worst_difference": worst,
            "project_ratio": project_ratio,
            "rates": {name: steps / seconds for name, (_, seconds) in results.items()}}

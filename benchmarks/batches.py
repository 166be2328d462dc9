"""Part 2: many independent oscillators stepped together, one numpy array of N rows.

Each row is the page's hanging mass with its own k, m and L0 (per-mass force parameters), all
advanced by the same Euler-Cromer step through physics.simulate.run (the engine). The cost of a
step is mostly fixed Python/numpy overhead at small N (where the engine runs its traced float loop)
and memory traffic at large N, so oscillator-steps per second grow with N until the arrays stop
fitting in cache. These are internal-API figures (no user command steps 10⁶ oscillators); the
reference is the page-style loop of part 1 (one mass, vpython's vector), in the same process.

1-D batches keep r with shape (N, 1): the forces then need 1-component anchors and directions
(Spring(anchor=(0.0,)), Gravity(direction=(-1.0,))); with the default 3-component ones numpy
cannot broadcast (N, 1) against (N, 3), and we report that.
"""
from __future__ import annotations

import numpy as np

from physics.forces import Gravity, Spring
from physics.simulate import Simulation, run
from physics.state import make_state

from .common import resource, table, timed, verdict
from .single_mass import page_steps_per_second

dt = 1e-4   # s, as in part 1 (the cost of a step does not depend on Δt)
g = 9.8     # m/s²


def batch(N: int, dims: int, *, seed: int = 1):
    """N hanging masses with per-mass k (20–60 N/m), m (5–15 kg), L0 (0.8–1.2 m): (state, forces)."""
    rng = np.random.default_rng(seed)
    k = rng.uniform(20.0, 60.0, N)
    m = rng.uniform(5.0, 15.0, N)
    L0 = rng.uniform(0.8, 1.2, N)
    if dims == 3:
        r = np.column_stack([rng.uniform(-0.3, 0.3, N), np.full(N, -1.5), np.zeros(N)])
        forces = (Spring(k=k, L0=L0, anchor=(0.0, 0.0, 0.0)), Gravity(g=g))
    else:
        r = np.full((N, 1), -1.5)
        forces = (Spring(k=k, L0=L0, anchor=(0.0,)), Gravity(g=g, direction=(-1.0,)))
    return make_state(r=r, m=m), forces


def step_many(state, forces, steps: int):
    """The project's stepping: physics.simulate.run, keeping only the final state."""
    return run(state, forces, dt=dt, until=state.t + steps * dt, record_every=None).final


def check_rows_match_single_masses(dims: int, steps: int = 200) -> float:
    """Largest |Δr| (m) between rows of a batch and the same masses stepped one at a time."""
    state, forces = batch(50, dims)
    spring = forces[0]
    end = step_many(state, forces, steps)
    worst = 0.0
    for i in (0, 17, 49):
        one = make_state(r=state.r[i], m=state.m[i])
        single = (Spring(k=float(spring.k[i, 0]), L0=float(spring.L0[i, 0]), anchor=spring.anchor), forces[1])
        worst = max(worst, float(np.max(np.abs(step_many(one, single, steps).r[0] - end.r[i]))))
    return worst


def check_default_1d() -> str:
    """What happens with r of shape (N, 1) and the forces' default 3-component anchor/direction."""
    state = make_state(r=np.full((4, 1), -1.5), m=np.full(4, 10.0))
    try:
        Simulation(state, (Spring(k=40.0, L0=1.0), Gravity(g=g)), dt=dt, compiled=False).advance(1)
    except ValueError as error:
        return f"fails with ValueError ({error})"
    return "works"


def page_faults() -> int:
    """Minor page faults of this process so far: each is a fresh page the OS had to hand over
    (0 where there is no resource module to count them: Windows, where the table says n/a)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt if resource is not None else 0


def rate(N: int, dims: int, seconds_wanted: float):
    """(oscillator-steps/s, steps, seconds, page faults per step) for one batch, with steps chosen
    to last ~seconds_wanted."""
    state, forces = batch(N, dims)
    state = step_many(state, forces, 2)                   # warm up: first-touch of the arrays
    _, probe = timed(step_many, state, forces, 10)
    steps = int(min(200_000, max(10, seconds_wanted / (probe / 10))))
    faults = page_faults()
    end, seconds = timed(step_many, state, forces, steps)
    faults = (page_faults() - faults) / steps
    if not np.all(np.isfinite(end.r)):
        raise RuntimeError(f"batch N={N} {dims}-D blew up")
    return N * steps / seconds, steps, seconds, faults


def main(settings) -> dict:
    sizes = [1, 10, 100, 1_000, 10_000, 100_000, 1_000_000]
    seconds_wanted = settings.pick(1.5, 0.3)
    page = page_steps_per_second()
    print(f"Part 2: batches of N oscillators (per-mass k, m, L0), euler-cromer, Δt = {dt:g} s; "
          f"reference: page-style loop {page / 1e6:.3f} M steps/s")
    print(f"1-D with the default 3-component anchor: {check_default_1d()}; "
          "with anchor=(0.0,) and direction=(-1.0,) it works")
    for dims in (3, 1):
        print(f"batch rows equal single-mass runs ({dims}-D, 200 steps): "
              f"max |Δr| = {check_rows_match_single_masses(dims):.1e} m")
    rows, results = [], {}
    for dims in (3, 1):
        for N in sizes:
            per_second, steps, seconds, faults = rate(N, dims, seconds_wanted)
            results[(dims, N)] = per_second
            rows.append([f"{dims}-D", f"{N:,}", f"{steps:,}", f"{seconds:.2f} s",
                         f"{per_second / 1e6:.2f}", f"{per_second / page:.1f}×", f"{faults:,.0f}" if resource is not None else "n/a"])
    print(table(["shape", "N", "steps", "CPU time", "M osc-steps/s", "vs page", "page faults/step"], rows))
    print("page faults: new memory the OS zeroes for numpy's temporary arrays when the C allocator has "
          "handed the last ones back (it depends on the allocator's history, not on the physics)")
    big = [results[(dims, N)] / page for dims in (3, 1) for N in sizes if N >= 10_000]
    print(f"target ≥ 100× the page-style loop at N ≥ 10⁴: worst {min(big):.0f}× -> {verdict(min(big) >= 100)}")
    return {"page_rate": page, "rates": results, "worst_ratio_large": min(big)}

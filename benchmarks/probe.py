"""Jobs the benchmarks time inside a tree of the project, each in a process of its own.

    python PATH/TO/benchmarks/probe.py JOB [ARGS]      (run from the tree to be measured)

The job imports the physics of the folder it is run from (the working folder goes first on
sys.path), not of the folder this file is in: `python -m benchmarks --against REF` runs this one
file in this tree and in REF's, so both are timed by the same code. It uses only what every
release since the forces became declarations has (scenes.configure, Model.simulation,
Simulation.advance, physics.simulate.run), and prints one line of JSON:

    {"cpu": s, "value": x, "unit": "..."}      cpu: this process's CPU time for the job alone
                                               (no start-up), value: the job's own figure

Jobs:
    batch N DIMS STEPS      N hanging masses (per-mass k, m, L0) stepped STEPS times in DIMS = 1 or 3
                            dimensions with Euler-Cromer, only the final state kept (part 2)
    stepping N STEPS        the resonance scene's batch of N driven springs, STEPS rk4 steps, no
                            recording: the stepping alone (part 7's internal figure)
    allocation N STEPS      the same batch loop under tracemalloc: the most memory it held at once
                            beyond what it started with (value, bytes), and the minor page faults
                            of the process during the loop ("faults": memory touched for the first
                            time, 4 kB each)
"""
from __future__ import annotations

import json
import os
import sys
import time

sys.path.insert(0, os.getcwd())      # the tree being measured, before this file's own folder

try:
    import resource                  # POSIX: minor page faults
except ImportError:
    resource = None


def minor_faults() -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt if resource is not None else 0


def batch(count: int, dims: int, steps: int) -> dict:
    import numpy as np
    from physics.forces import Gravity, Spring
    from physics.simulate import run
    from physics.state import make_state

    rng = np.random.default_rng(1)
    k, m, L0 = rng.uniform(20.0, 60.0, count), rng.uniform(5.0, 15.0, count), rng.uniform(0.8, 1.2, count)
    if dims == 3:
        r = np.column_stack([rng.uniform(-0.3, 0.3, count), np.full(count, -1.5), np.zeros(count)])
        forces = (Spring(k=k, L0=L0, anchor=(0.0, 0.0, 0.0)), Gravity(g=9.8))
    else:
        r = np.full((count, 1), -1.5)
        forces = (Spring(k=k, L0=L0, anchor=(0.0,)), Gravity(g=9.8, direction=(-1.0,)))
    state, dt = make_state(r=r, m=m), 1e-4
    start = time.process_time()
    run(state, forces, dt=dt, until=steps * dt, record_every=None)
    cpu = time.process_time() - start
    return {"cpu": cpu, "value": count * steps / cpu, "unit": "mass-steps/s"}


def resonance_engine(count: int):
    """The resonance scene's batch of `count` springs (one b, count driving frequencies), warmed up."""
    from scenes import configure

    engine = configure("resonance", assignments=[f"count={count}", "curves=1"]).build().simulation(None)
    engine.advance(2)
    return engine


def stepping(count: int, steps: int) -> dict:
    engine = resonance_engine(count)
    start = time.process_time()
    engine.advance(steps)
    cpu = time.process_time() - start
    return {"cpu": cpu, "value": count * steps / cpu, "unit": "mass-steps/s"}


def allocation(count: int, steps: int) -> dict:
    import tracemalloc

    engine = resonance_engine(count)
    tracemalloc.start()
    before, faults = tracemalloc.get_traced_memory()[0], minor_faults()
    start = time.process_time()
    engine.advance(steps)
    cpu = time.process_time() - start
    held = tracemalloc.get_traced_memory()[1] - before
    return {"cpu": cpu, "value": held, "unit": "bytes", "faults": minor_faults() - faults}


JOBS = {"batch": batch, "stepping": stepping, "allocation": allocation}


if __name__ == "__main__":
    job, *numbers = sys.argv[1:]
    print(json.dumps(JOBS[job](*(int(number) for number in numbers))))

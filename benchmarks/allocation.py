"""Part 12: the memory a run allocates per step, kept flat as the step count grows (issue 38).

A run of 10⁴ masses that keeps something of every step grows by megabytes a second, and the
system time of touching new memory (page faults) shows up in every figure: the resonance command
of 93afe2d kept all of r, p, P_nc and W_nc of every step to time the period, 640 kB a step, and
cost 1.7× the CPU of the release before. Two figures, each step count in a process of its own:

* **The batch loop** (internal API, benchmarks/probe.py allocation): the resonance scene's 10⁴
  driven springs, STEPS rk4 steps of `Simulation.advance` with nothing recorded. Under tracemalloc,
  the most memory the loop held at once beyond what it started with (the tick's temporaries), and
  the minor page faults of the loop: memory it touched for the first time, a page each. Target:
  flat, less than 1 % of the state (r and p of 10⁴ masses, 480 kB) touched a step beyond the
  shortest run's, and the same memory held at every step count.
* **The command**: `python main.py resonance --headless --json --set count=10000 --set curves=1
  --set settle=1 --set periods=1 --until T` for T = 5 … 40 s (250 … 2,000 steps; the amplitudes
  measured from 1 s to 4.1 s), as a process: its minor page faults, and the memory it touched per
  step beyond the shortest run's, (faults(T) − faults(5 s)) × page size / (steps − 250). It keeps
  the crossing times the period is timed by (10 bytes each, about 160 a step here) and sorts them
  at the end, so it grows by a few kB a step. Target: under a twentieth of one kept step of every
  mass (r, p, P_nc, W_nc: 640 kB at 10⁴ masses), the memory per step of 93afe2d.
"""
from __future__ import annotations

import json
import subprocess
import sys

from .common import ROOT, resource, table, verdict
from .against import PROBE

COUNT = 10_000
FLAT = 0.01                              # of the state (r and p of every mass), a step: still flat
KEPT = 0.05                              # of a kept step of every mass, a step: the command's target
DT = 0.02                                # s, the scene's Δt


def command(until: float, count: int) -> list[str]:
    return ["main.py", "resonance", "--headless", "--json", "--set", f"count={count}", "--set", "curves=1",
            "--set", "settle=1", "--set", "periods=1", "--until", f"{until:g}"]


def command_faults(until: float, count: int) -> int:
    """Minor page faults of one run of the command (a process of its own)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_minflt
    subprocess.run([sys.executable, *command(until, count)], cwd=ROOT, check=True, capture_output=True, timeout=1800)
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_minflt - before


def loop_memory(steps: int, count: int) -> dict:
    """benchmarks/probe.py allocation in a process of its own: held bytes, faults, CPU s."""
    done = subprocess.run([sys.executable, PROBE, "allocation", str(count), str(steps)], cwd=ROOT, check=True,
                          capture_output=True, text=True, timeout=1800)
    return json.loads(done.stdout.strip().splitlines()[-1])


def main(settings) -> dict:
    if resource is None:
        print("part 12 skipped: page faults need the resource module (POSIX)")
        return {}
    page = resource.getpagesize()
    count = settings.pick(COUNT, 2_000)
    state, kept = count * 2 * 3 * 8, count * 8 * 8          # r and p; r, p, P_nc and W_nc (3-D)
    print(f"Part 12: memory per step, {count:,} driven springs (resonance), each step count a process of its own")
    loops = {steps: loop_memory(steps, count) for steps in settings.pick((250, 500, 1000, 2000), (250, 1000))}
    first = min(loops)
    loop_step = {steps: (figure["faults"] - loops[first]["faults"]) * page / (steps - first)
                 for steps, figure in loops.items() if steps != first}
    print(table(["the batch loop (internal API)", "held at most (tracemalloc)", "touched (page faults)",
                 "touched a step beyond the shortest"],
                [[f"{steps:,} steps", f"{figure['value'] / 1e6:.2f} MB", f"{figure['faults'] * page / 1e6:.2f} MB",
                  f"{loop_step[steps] / 1e3:.2f} kB" if steps in loop_step else ""] for steps, figure in loops.items()]))
    runs = {until: command_faults(until, count) for until in settings.pick((5.0, 10.0, 20.0, 40.0), (5.0, 20.0))}
    shortest = min(runs)
    command_step = {until: (faults - runs[shortest]) * page / (round(until / DT) - round(shortest / DT))
                    for until, faults in runs.items() if until != shortest}
    print(f"the command: python {' '.join(command(shortest, count)).replace(f'--until {shortest:g}', '--until T')}")
    print(table(["T", "steps", "touched (page faults)", "touched a step beyond the shortest"],
                [[f"{until:g} s", f"{round(until / DT):,}", f"{faults * page / 1e6:.1f} MB",
                  f"{command_step[until] / 1e3:.2f} kB" if until in command_step else ""]
                 for until, faults in runs.items()]))
    held = [figure["value"] for figure in loops.values()]
    flat = max(loop_step.values()) < FLAT * state and max(held) - min(held) < FLAT * state
    small = max(command_step.values()) < KEPT * kept
    print(f"target: the loop flat, under {FLAT * state / 1e3:.1f} kB a step touched (1 % of r and p) and the "
          f"same memory held at every step count (within {FLAT * state / 1e3:.1f} kB): "
          f"{max(loop_step.values()) / 1e3:.2f} kB, {(max(held) - min(held)) / 1e3:.1f} kB -> {verdict(flat)}")
    print(f"target: the command under {KEPT * kept / 1e3:.0f} kB a step (a twentieth of one kept step of every mass, "
          f"{kept / 1e3:.0f} kB): at most {max(command_step.values()) / 1e3:.2f} kB -> {verdict(small)}")
    return {"loop": loops, "command_faults": runs, "loop_per_step": loop_step, "command_per_step": command_step,
            "flat": flat, "small": small}

"""Part 9: friction in the fast loop. `main.py friction --headless` for 10⁶ steps against `main.py
damped --headless` for 10⁶ steps, as processes, in turn, in one run.

Target: friction's within 1.5× damped's CPU time. Friction's law and its stop rule are traced into
the compiled loop like every other force (their choices written `a if c else b`, no guard), so the
friction scene's two blocks, one sliding and one damped, cost about what damped's one hanging mass
does: both are a loop over floats (physics/compiled.py). Each command is timed whole (start-up,
imports, the run, the report); the CPU time of the child is quoted, since the wall time of a shared
machine says more about the other work on it.
"""
from __future__ import annotations

import statistics

from .common import process_time, table, verdict

STEPS = 1_000_000
TARGET = 1.5
# 10⁶ steps of each scene's own Δt (friction 0.01 s, damped 0.1 s)
FRICTION = ["main.py", "friction", "--headless", "--until", str(STEPS * 0.01)]
DAMPED = ["main.py", "damped", "--headless", "--until", str(STEPS * 0.1)]


def main(settings) -> dict:
    repeats = settings.pick(5, 2)
    friction, damped = [], []
    for _ in range(repeats):          # in turn, so a busy spell of the machine falls on both
        friction.append(process_time(FRICTION)[1])
        damped.append(process_time(DAMPED)[1])
    ratios = [a / b for a, b in zip(friction, damped)]
    ratio = statistics.median(ratios)
    print(f"part 9: friction against damped, {STEPS:,} steps each, CPU s of the whole process "
          f"(median of {repeats}, run in turn)")
    print(table(["command", "CPU s"], [
        ["python " + " ".join(FRICTION), f"{statistics.median(friction):.2f}"],
        ["python " + " ".join(DAMPED), f"{statistics.median(damped):.2f}"],
    ]))
    print(f"friction / damped = {ratio:.2f} (each pair: {', '.join(f'{r:.2f}' for r in ratios)}); "
          f"target at most {TARGET}: {verdict(ratio <= TARGET)}")
    return {"ratio": ratio}

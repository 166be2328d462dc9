"""Part 7: fitting k and b to 1,000 measured points, `main.py damped --data FILE --fit k,b`, as processes.

The file is the engine's own run (rk4, Δt = 1 ms) at 50 samples a second for 20 s, with 2 mm of
noise, written as Vernier CSV into a temporary folder. Each command is timed whole (start-up,
reading, every run of the engine the fit asks for, output), median of 3, next to two references
from the same run: `main.py damped --headless` (start-up and one short run) and the same --data
without --fit (the two offsets only). Target: under 2 s for two constants and 1,000 points.
"""
from __future__ import annotations

import json
import os
import statistics
import tempfile

import numpy as np

from .common import load_average, process_time, table, verdict

POINTS, RATE = 1000, 50.0
TARGET = 2.0   # s


def write_data(folder: str) -> str:
    from lab.compare import ModelRun
    from lab.formats import vernier
    from scenes import catalog

    truth = catalog.configure("damped", assignments=["k=55", "b=2.5", "dt=0.001"])
    run = ModelRun(truth, integrator="rk4", axis=1, until=POINTS / RATE + 1.0)
    t = np.arange(POINTS) / RATE
    y = run.at(t)[0] + 1.2 + np.random.default_rng(0).normal(0.0, 0.002, POINTS)
    path = os.path.join(folder, "measured.csv")
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(vernier(t + 3.0, y))
    return path


def main(settings) -> dict:
    repeats = settings.pick(3, 1)
    with tempfile.TemporaryDirectory() as folder:
        data = write_data(folder)
        commands = [
            ("`main.py damped --headless` (reference)", ["main.py", "damped", "--headless"]),
            ("`--data FILE`, offsets only", ["main.py", "damped", "--data", data]),
            ("**`--data FILE --fit k,b`** (dt = 0.1 s, the scene's)", ["main.py", "damped", "--data", data, "--fit", "k,b", "--json"]),
            ("`--data FILE --fit k,b --set dt=0.01`", ["main.py", "damped", "--data", data, "--fit", "k,b", "--set", "dt=0.01", "--json"]),
            ("**`--data FILE --fit k,b --set dt=0.001`**", ["main.py", "damped", "--data", data, "--fit", "k,b", "--set", "dt=0.001", "--json"]),
            ("`--data FILE --fit k,b --integrator rk4 --set dt=0.001`",
             ["main.py", "damped", "--data", data, "--fit", "k,b", "--integrator", "rk4", "--set", "dt=0.001", "--json"]),
        ]
        print(f"Part 7: fitting k and b to {POINTS:,} points (median of {repeats} processes each)")
        rows, figures = [], {}
        reference = None
        for label, arguments in commands:
            runs = [process_time(arguments) for _ in range(repeats)]
            load = load_average()
            wall = statistics.median(r[0] for r in runs)
            cpu = statistics.median(r[1] for r in runs)
            reference = reference or (wall, cpu)
            found = ""
            if "--json" in arguments:
                out = json.loads(runs[-1][2])
                k, b = out["fit"]["k"], out["fit"]["b"]
                found = (f"k = {k['value']:.4f} ± {k['uncertainty']:.4f}, b = {b['value']:.4f} ± "
                         f"{b['uncertainty']:.4f}")
            rows.append([label, f"{wall:.2f} s", f"{cpu:.2f} s", f"{wall / reference[0]:.1f}×", f"{cpu / reference[1]:.1f}×", load, found])
            figures[label] = (wall, cpu)
    print(table(["command", "wall", "CPU", "vs ref. (wall)", "vs ref. (CPU)", "load", "fit (truth k = 55, b = 2.5)"], rows))
    wall, cpu = (max(figure[n] for label, figure in figures.items() if label.startswith("**")) for n in (0, 1))
    print(f"target: two constants to {POINTS:,} points under {TARGET:g} s: CPU {cpu:.2f} s {verdict(cpu < TARGET)}; "
          f"wall {wall:.2f} s {verdict(wall < TARGET)} (wall time grows with the machine's load average, "
          f"{load_average()} now)")
    return figures

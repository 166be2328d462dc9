"""Part 8: fitting k and b, `main.py damped --data FILE --fit k,b --set m=M`, as processes, on 10³, 10⁴
and 2·10⁵ points: wall and CPU time, and the engine runs the fit took (its JSON's "engine_runs").

Each file is the closed-form damped oscillator (physics/exact.py) of a classroom spring (0.5 kg,
20 N/m, b = 0.002 kg/s so that the swing lasts the longest record) with 1 mm of noise, at 50 samples a
second (10³ and 10⁴ points) and 200 a second (2·10⁵ points: 1,000 s), written into a temporary folder.
The program chooses the model's integrator and Δt itself, as a class's command does. Each command is
timed whole (start-up, reading, every run of the engine, output), median of 3 (1 for 2·10⁵), next to
a reference from the same run: `main.py damped --headless` (start-up and one short run). Targets: at
most 40 engine runs for two constants; the times are reported, not targets.
"""
from __future__ import annotations

import json
import os
import statistics
import tempfile

import numpy as np

from .common import load_average, process_time, table

M, K, B = 0.5, 20.0, 0.002
SIZES = ((1_000, 50.0), (10_000, 50.0), (200_000, 200.0))
RUNS_TARGET = 40


def write_data(folder: str, points: int, rate: float) -> str:
    from physics.exact import oscillator

    t = np.arange(points) / rate
    x, _ = oscillator(t, m=M, k=K, b=B, x0=0.1, v0=0.0)
    y = 0.6 + x + np.random.default_rng(points).normal(0.0, 0.001, points)
    path = os.path.join(folder, f"measured-{points}.csv")
    with open(path, "w", encoding="utf-8") as handle:
        handle.write("t (s),y (m)\n" + "".join(f"{a:.4f},{b:.5f}\n" for a, b in zip(t + 2.0, y)))
    return path


def main(settings) -> dict:
    repeats = settings.pick(3, 1)
    sizes = SIZES if not settings.quick else SIZES[:2]
    rows, figures = [], {}
    with tempfile.TemporaryDirectory() as folder:
        reference = statistics.median(process_time(["main.py", "damped", "--headless"])[0] for _ in range(repeats))
        rows.append(["`main.py damped --headless` (reference)", f"{reference:.2f} s", "", "1.0×", "", "", ""])
        print(f"Part 8: fitting k and b (the program's own choice of model) to 10³-2·10⁵ points, "
              f"median of {repeats} processes")
        for points, rate in sizes:
            data = write_data(folder, points, rate)
            arguments = ["main.py", "damped", "--data", data, "--fit", "k,b", "--set", f"m={M}", "--json"]
            runs = [process_time(arguments, timeout=1800) for _ in range(repeats if points < 100_000 else 1)]
            wall = statistics.median(r[0] for r in runs)
            cpu = statistics.median(r[1] for r in runs)
            out = json.loads(runs[-1][2])
            k, b = out["fit"]["k"], out["fit"]["b"]
            found = (f"k = {k['value']:.6f} ± {k['uncertainty']:.1g}, b = {b['value']:.5f} ± {b['uncertainty']:.1g}; "
                     f"{out['integrator']} at dt = {out['dt']:g} s")
            rows.append([f"`--data FILE --fit k,b --set m={M}`, {points:,} points", f"{wall:.2f} s", f"{cpu:.2f} s",
                         f"{wall / reference:.1f}×", str(out["engine_runs"]), load_average(), found])
            figures[points] = {"wall": wall, "cpu": cpu, "runs": out["engine_runs"], "trusted": out["trusted"]}
    print(table(["command", "wall", "CPU", "vs ref. (wall)", "engine runs", "load",
                 f"fit (truth k = {K:g}, b = {B:g})"], rows))
    most = max(figure["runs"] for figure in figures.values())
    print(f"target: at most {RUNS_TARGET} engine runs for two constants: most {most} "
          f"({'met' if most <= RUNS_TARGET else 'NOT met'})")
    return figures

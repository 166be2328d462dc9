"""Part 7: speed where the work is (issue 16): --csv against the page's loop, and the resonance batch.

Two of the user's commands, each a whole process (start-up, imports and output included), CPU
time (user + system of the child), median of several runs:

    python main.py vertical --headless --csv FILE --set dt=1e-4 --until 100    every one of 10⁶ rows
    python -m benchmarks.page_vector --steps 1000000                           the page's own loop

The target: writing the rows is at least as fast as the page's loop over the same steps
(ratio ≥ 1, the page loop's CPU time / the command's). The file must have one row per step.

    python main.py resonance --headless --json --set count=10000 --set curves=1

steps 10⁴ driven, damped springs with rk4 (2,500 steps of Δt = 0.02 s): the figure is rk4
mass-steps per CPU second of the whole process (10⁴ × 2,500 / CPU s), target ≥ 10⁷. Beside it,
labelled "internal API, no user path", the same batch stepped in this process by the engine
(Simulation.advance, no start-up, no recording), and the page's loop rate (part 1) as the reference.
--quick writes 10⁵ rows and sweeps 2,000 frequencies.
"""
from __future__ import annotations

import os
import statistics
import tempfile

from scenes import configure

from .common import process_time, table, timed, verdict
from .single_mass import command, page_command, page_steps_per_second

MASS_STEPS_TARGET = 1e7      # rk4 mass-steps per CPU second at 10⁴ masses (issue 16)
STEPPING_SHARE = 0.5         # whole process / stepping alone: what start-up, recording and output may cost
RESONANCE_STEPS = 2_500      # t = 0 … 50 s at Δt = 0.02 s, the scene's defaults


def median_cpu(arguments, repeats: int) -> tuple[float, float]:
    """(median wall s, median CPU s) of `python <arguments>`."""
    runs = [process_time(arguments) for _ in range(repeats)]
    return statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)


def resonance_command(count: int) -> list[str]:
    return ["main.py", "resonance", "--headless", "--json", "--set", f"count={count}", "--set", "curves=1"]


def engine_rate(count: int, steps: int) -> float:
    """rk4 mass-steps per CPU second of the resonance batch in this process (internal API)."""
    model = configure("resonance", assignments=[f"count={count}", "curves=1"]).build()
    engine = model.simulation(None)
    engine.advance(2)
    _, seconds = timed(engine.advance, steps)
    return count * steps / seconds


def main(settings) -> dict:
    steps = settings.pick(1_000_000, 100_000)
    repeats = settings.pick(3, 1)
    count = settings.pick(10_000, 2_000)
    print(f"Part 7: speed where the work is: --csv of {steps + 1:,} rows against the page's loop of "
          f"{steps:,} steps, and the resonance batch of {count:,} masses; processes, median of {repeats}, CPU time")
    page_wall, page_cpu = median_cpu(page_command(steps), repeats)
    with tempfile.TemporaryDirectory(prefix="bench-csv-") as folder:
        path = os.path.join(folder, "vertical.csv")
        csv_wall, csv_cpu = median_cpu(command(steps, "--csv", path), repeats)
        with open(path, newline="") as file:
            rows = sum(1 for _ in file) - 1
    if rows != steps + 1:
        raise RuntimeError(f"the CSV file has {rows:,} rows, not {steps + 1:,}")
    res_wall, res_cpu = median_cpu(resonance_command(count), repeats)
    mass_steps = count * RESONANCE_STEPS
    inside = engine_rate(count, settings.pick(300, 100))
    page = page_steps_per_second()
    print(table(["command", "wall", "CPU", "figure"], [
        [" ".join(["python", *page_command(steps)]) + "   (reference)", f"{page_wall:.2f} s", f"{page_cpu:.2f} s", "1.00×"],
        [" ".join(["python", *command(steps, "--csv", "TMP/vertical.csv")]) + f"   ({rows:,} rows)",
         f"{csv_wall:.2f} s", f"{csv_cpu:.2f} s", f"{page_cpu / csv_cpu:.2f}× the page (CPU)"],
        [" ".join(["python", *resonance_command(count)]), f"{res_wall:.2f} s", f"{res_cpu:.2f} s",
         f"{mass_steps / res_cpu / 1e6:.2f} M rk4 mass-steps/s ({page_cpu / steps * mass_steps / res_cpu:.0f}× "
         "the page's loop per mass-step)"],
        [f"internal API, no user path: the same {count:,} masses, Simulation.advance", "-", "-",
         f"{inside / 1e6:.2f} M rk4 mass-steps/s ({inside / page:.0f}× the page-style loop in this process)"],
    ]))
    print(f"target: --csv at least as fast as the page's loop (CPU): {page_cpu / csv_cpu:.2f}× -> "
          f"{verdict(page_cpu / csv_cpu >= 1)}")
    print(f"target: ≥ {MASS_STEPS_TARGET / 1e6:g} M rk4 mass-steps/s at 10⁴ masses: whole process "
          f"{mass_steps / res_cpu / 1e6:.2f} M -> {verdict(count >= 10_000 and mass_steps / res_cpu >= MASS_STEPS_TARGET)}; "
          f"stepping alone {inside / 1e6:.2f} M -> {verdict(count >= 10_000 and inside >= MASS_STEPS_TARGET)}")
    share = mass_steps / res_cpu / inside
    print(f"target proposed in its place: the whole command at least {STEPPING_SHARE:g} of the stepping's own "
          f"rate: {share:.2f} -> {verdict(share >= STEPPING_SHARE)}")
    return {"page_cpu": page_cpu, "csv_cpu": csv_cpu, "resonance_cpu": res_cpu,
            "mass_steps_per_second": mass_steps / res_cpu, "engine_rate": inside}

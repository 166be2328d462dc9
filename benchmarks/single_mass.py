"""Part 1: one mass, the page's 3-D gravity spring, 10⁶ steps at Δt = 1e-4 s, as a user runs it.

First the commands, each a whole process (start-up, imports and output included), median of
several runs, wall time and CPU time (the machine is shared: CPU time hardly changes when other
work takes turns on the cores, wall time does):

    python main.py vertical --headless --json --set dt=1e-4 --until 100     the student's command
    python main.py vertical --headless --csv FILE --set dt=1e-4 --until 100 every row written
    python -m benchmarks.page_vector --steps 1000000                        the page's own loop

The last one is the reference: the page's program with vpython's vector (benchmarks/page_vector.py),
Euler-Cromer in momentum form,

    L = r − anchor;  F = −k (|L| − L0) L̂ + m g;  p = p + F Δt;  r = r + (p/m) Δt

so all of them must end at the same position to round-off, and we check that they do.

Second, rows labelled "internal API, no user path": the engine (physics.simulate.Simulation)
called in this process without start-up or output, and a loop in plain floats, the most a
traced Python loop could reach. No user runs these; they show where a command's time goes.
"""
from __future__ import annotations

import json
import math
import os
import statistics
import tempfile

from physics.simulate import Simulation, every
from physics.state import make_state
from scenes._single_mass import forces_for

from .common import process_time, table, timed, verdict
from .page_vector import L0, anchor, dt, g, k, load_vector, m, page_style_loop, r0

TARGET, AIM = 2.0, 10.0     # the command against the page's loop, as processes (issue 9)
AGREE = 1e-9                # m: every way of stepping must end here to round-off


def command(steps: int, *output) -> list[str]:
    """`main.py vertical --headless ... --set dt=1e-4 --until T` for `steps` steps."""
    return ["main.py", "vertical", "--headless", *output, "--set", f"dt={dt:g}", "--until", f"{steps * dt:g}"]


def page_command(steps: int) -> list[str]:
    return ["-m", "benchmarks.page_vector", "--steps", str(steps)]


def median_run(arguments, repeats: int):
    """(median wall s, median CPU s, stdout of the last run) of `python <arguments>`.

    A run that fails (the command refuses a run its cost estimate finds too long, say, which a
    busy machine can cause) is reported and run again, up to `repeats` more times in all.
    """
    runs, failures = [], 0
    while len(runs) < repeats:
        try:
            runs.append(process_time(arguments))
        except RuntimeError as error:
            failures += 1
            print(f"  FAILED ({failures}): {error}")
            if failures > repeats:
                raise
    return statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs), runs[-1][2]


def csv_rows(path: str) -> tuple[int, list[float]]:
    """(data rows, the last row's x, y, z) of a CSV file the command wrote."""
    with open(path) as file:
        header = file.readline().rstrip("\n").split(",")
        count, last = 0, None
        for last in file:
            count += 1
    values = dict(zip(header, last.rstrip("\n").split(",")))
    return count, [float(values[axis]) for axis in "xyz"]


def process_rows(steps: int, repeats: int):
    """The three commands, timed as processes. Returns (rows, figures)."""
    page_wall, page_cpu, out = median_run(page_command(steps), repeats)
    page_r = json.loads(out)["r"]
    json_wall, json_cpu, out = median_run(command(steps, "--json"), repeats)
    answer = json.loads(out)
    if answer["steps"] != steps:
        raise RuntimeError(f"the command took {answer['steps']} steps, not {steps}")
    with tempfile.TemporaryDirectory(prefix="bench-csv-") as folder:
        path = os.path.join(folder, "vertical.csv")
        csv_wall, csv_cpu, _ = median_run(command(steps, "--csv", path), max(1, repeats - 2))
        rows_written, csv_r = csv_rows(path)
    if rows_written != steps + 1:
        raise RuntimeError(f"the CSV file has {rows_written:,} rows, not {steps + 1:,} (t = 0 and every step)")
    difference = {name: max(abs(a - b) for a, b in zip(r, page_r))
                  for name, r in (("json", answer["r"]), ("csv", csv_r))}
    rows = [
        [" ".join(["python", *page_command(steps)]) + "   (reference)", page_wall, page_cpu, 0.0],
        [" ".join(["python", *command(steps, "--json")]), json_wall, json_cpu, difference["json"]],
        [" ".join(["python", *command(steps, "--csv", "TMP/vertical.csv")]) + f"   ({rows_written:,} rows)",
         csv_wall, csv_cpu, difference["csv"]],
    ]
    table_rows = [[name, f"{wall:.2f} s", f"{cpu:.2f} s", f"{page_wall / wall:.2f}×", f"{page_cpu / cpu:.2f}×",
                   f"{diff:.1e}"] for name, wall, cpu, diff in rows]
    figures = {"page_wall": page_wall, "page_cpu": page_cpu, "json_wall": json_wall, "json_cpu": json_cpu,
               "csv_wall": csv_wall, "csv_cpu": csv_cpu, "worst_difference": max(difference.values()),
               "final_y": answer["r"][1]}
    return table_rows, figures


# ---- internal API, no user path ----

def _engine(**options) -> Simulation:
    forces = forces_for(k=k, L0=L0, anchor=anchor, g=g, b=0, C=0, A=0, rho=0, F0=0, omega=0,
                        drive_axis=(1, 0, 0))
    return Simulation(make_state(r=r0, m=m), forces, dt=dt, **options)


def engine_final_only(steps: int, *, compiled: bool = True):
    """Simulation.advance(steps), keeping only the final state: the traced loop (or the numpy tick)."""
    engine = _engine(compiled=compiled)
    engine.advance(steps)
    return tuple(engine.state.r[0])


def engine_every_step(steps: int):
    """Simulation.advance(steps) recording every step (what --csv asks the engine for)."""
    engine = _engine()
    samples = engine.advance(steps, record=every(1))
    return tuple(samples.r[-1, 0])


def plain_float_loop(steps: int):
    """The same update written out in floats: what a loop traced into floats could reach at best."""
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


INTERNAL = {
    "page-style loop (vpython vector), in this process": page_style_loop,
    "plain floats, in this process": plain_float_loop,
    "Simulation.advance, final state only": engine_final_only,
    "Simulation.advance, every step recorded": engine_every_step,
    "Simulation.advance, compiled=False (numpy tick)": lambda steps: engine_final_only(steps, compiled=False),
}
PAGE = "page-style loop (vpython vector), in this process"


def internal_rows(steps: int):
    results = {name: timed(loop, steps) for name, loop in INTERNAL.items()}
    page_final, page_seconds = results[PAGE]
    rows = [[name, f"{seconds:.3f} s", f"{steps / seconds / 1e6:.3f}", f"{page_seconds / seconds:.2f}×",
             f"{max(abs(a - b) for a, b in zip(final, page_final)):.1e}"]
            for name, (final, seconds) in results.items()]
    worst = max(max(abs(a - b) for a, b in zip(final, page_final)) for final, _ in results.values())
    return rows, worst, steps / page_seconds


_reference = {}


def page_steps_per_second(steps: int = 200_000) -> float:
    """The page-style loop's speed in steps/s (CPU), measured once per process: part 2's reference."""
    if steps not in _reference:
        _, seconds = timed(page_style_loop, steps)
        _reference[steps] = steps / seconds
    return _reference[steps]


def main(settings) -> dict:
    steps = settings.pick(1_000_000, 100_000)
    repeats = settings.pick(5, 3)
    kind = load_vector()[3]
    print(f"Part 1: one mass (k = {k:g} N/m, m = {m:g} kg, L0 = {L0:g} m, g = {g:g} m/s², from {r0} m), "
          f"Δt = {dt:g} s, {steps:,} steps; vpython's vector from {kind} (no canvas, no server)")
    print(f"Commands as processes, median of {repeats} runs (the CSV command: {max(1, repeats - 2)}); "
          "'vs page' = the page loop's time / the command's")
    if settings.quick:
        print("--quick: 10⁵ steps, so start-up (about 0.3 s) is most of each command; the targets are for 10⁶")
    rows, figures = process_rows(steps, repeats)
    print(table(["command", "wall", "CPU", "vs page (wall)", "vs page (CPU)", "|Δr| vs page (m)"], rows))
    wall_ratio = figures["page_wall"] / figures["json_wall"]
    cpu_ratio = figures["page_cpu"] / figures["json_cpu"]
    print(f"target: the --json command ≥ {TARGET:g}× faster than the page's loop as a process: "
          f"wall {wall_ratio:.2f}× -> {verdict(wall_ratio >= TARGET)}, CPU {cpu_ratio:.2f}× -> "
          f"{verdict(cpu_ratio >= TARGET)}; aim {AIM:g}×: wall {verdict(wall_ratio >= AIM)}, "
          f"CPU {verdict(cpu_ratio >= AIM)}")
    internal, worst, page_rate = internal_rows(steps)
    _reference[steps] = page_rate
    print("\ninternal API, no user path (in this process, CPU time, nothing printed or written):")
    print(table(["internal API, no user path", "CPU", "M steps/s", "vs page", "|Δr| vs page (m)"], internal))
    worst = max(worst, figures["worst_difference"])
    print(f"every row ends at the page's position to {worst:.1e} m (required ≤ {AGREE:g} m): "
          f"{'yes' if worst <= AGREE else 'NO'}")
    return {"steps": steps, **figures, "wall_ratio": wall_ratio, "cpu_ratio": cpu_ratio,
            "page_rate": page_rate, "worst_difference": worst}

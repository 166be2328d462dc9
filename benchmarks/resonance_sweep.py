"""Part 3: a resonance curve of 1,000 driving frequencies, the user's command against scipy's solve_ivp.

    python main.py resonance --headless --json --set count=1000 --set curves=1

runs the resonance scene: 1,000 driven, damped springs (one per ω from omega_min to omega_max),
stepped together as one batch by the engine from t = 0 to the scene's `until`, and prints every
measured steady-state amplitude (resonance.amplitude_m) beside the closed form
(resonance.exact_amplitude_m),

    A(ω) = F0 / √((k − mω²)² + (bω)²)

It is timed as a whole process (start-up, imports and output included), median of several runs.
Every measured amplitude must be within 1 % of the closed form, and the command must run ONE
simulation: the scene's batch is the sweep. We check that by running the command once more with
physics.simulate.Simulation.advance wrapped to count the mass-steps of every engine.

The reference is the way one would do it with scipy: a loop of solve_ivp (RK45, rtol 1e-6), one
call per ω, over the same equation m x'' = F0 cos ωt − k x − b x' (x from equilibrium, gravity only
moves the equilibrium), from rest at equilibrium over the same 0 … `until`, with the constants
read from the command's own JSON. Its amplitude is measured as the scene measures its own: the
largest √(x² + (v/ω)²) over the measuring window. It runs in this process (scipy's import is
not counted: that favours the reference); --quick times a subset of the frequencies and scales
the time up, and says so.
"""
from __future__ import annotations

import json
import statistics
import subprocess
import sys

import numpy as np

from .common import ROOT, process_time, table, timed, verdict

COMMAND = ["main.py", "resonance", "--headless", "--json", "--set", "count=1000", "--set", "curves=1"]
TARGET = 100.0      # × faster than the solve_ivp loop (issue 9)
TOLERANCE = 0.01    # every amplitude within 1 % of the closed form

# Run the command with every engine's steps counted: id(engine) -> [masses, steps].
COUNTING = """
import atexit, json, runpy, sys
import physics.simulate as simulate
engines = {}
advance = simulate.Simulation.advance
def counted(self, steps, **options):
    before = self.steps
    try:
        return advance(self, steps, **options)
    finally:
        engines.setdefault(id(self), [self.start.count, 0])[1] += self.steps - before
simulate.Simulation.advance = counted
atexit.register(lambda: print("ENGINES " + json.dumps(list(engines.values())), file=sys.stderr))
sys.argv = ["main.py"] + sys.argv[1:]
runpy.run_path("main.py", run_name="__main__")
"""


def engines_stepped() -> list[tuple[int, int]]:
    """(masses, steps) of every engine the command advanced, in the order they were made."""
    completed = subprocess.run([sys.executable, "-c", COUNTING, *COMMAND[1:]], cwd=ROOT,
                               capture_output=True, text=True, timeout=300)
    line = next((line for line in completed.stderr.splitlines() if line.startswith("ENGINES ")), None)
    if completed.returncode != 0 or line is None:
        raise RuntimeError(f"the counting run failed: {completed.stderr.strip().splitlines()[-1:]}")
    return [tuple(engine) for engine in json.loads(line[len("ENGINES "):])]


def scipy_amplitude(omega: float, *, m: float, k: float, b: float, F0: float, until: float,
                    window: tuple[float, float], dt: float) -> float:
    """Steady-state amplitude from solve_ivp for one ω, measured over the scene's window, m."""
    from scipy.integrate import solve_ivp

    def slopes(t, y):
        x, v = y
        return [v, (F0 * np.cos(omega * t) - k * x - b * v) / m]

    t_eval = np.arange(window[0], min(window[1], until) + dt / 2, dt)
    solution = solve_ivp(slopes, (0.0, until), [0.0, 0.0], method="RK45", rtol=1e-6, t_eval=t_eval)
    x, v = solution.y
    return float(np.max(np.sqrt(x * x + (v / omega) ** 2)))


def main(settings) -> dict:
    repeats = settings.pick(3, 1)
    print(f"Part 3: resonance sweep, `python {' '.join(COMMAND)}` as a process (median of {repeats}), "
          "against a solve_ivp loop over the same oscillators")
    runs = [process_time(COMMAND) for _ in range(repeats)]
    wall, cpu = statistics.median(r[0] for r in runs), statistics.median(r[1] for r in runs)
    answer = json.loads(runs[-1][2])
    values = {name: entry["value"] for name, entry in answer["constants"].items()}
    sweep = answer["resonance"]
    omega = np.array(sweep["omega_rad_per_s"])
    (b,) = sweep["b_kg_per_s"]
    measured, exact = np.array(sweep["amplitude_m"][0]), np.array(sweep["exact_amplitude_m"][0])
    error = float(np.max(np.abs(measured / exact - 1)))
    window = (values["settle"], values["settle"] + values["periods"] * 2 * np.pi / values["omega_min"])
    print(f"the scene: {len(omega)} springs, ω = {omega[0]:g}…{omega[-1]:g} rad/s, m = {values['m']:g} kg, "
          f"k = {values['k']:g} N/m, b = {b:g} kg/s, F0 = {values['F0']:g} N, {answer['integrator']} "
          f"Δt = {answer['dt']:g} s, t = 0…{values['until']:g} s ({answer['steps']:,} steps), amplitudes "
          f"measured over t = {window[0]:g}…{window[1]:.4g} s")
    engines = engines_stepped()
    full = [(masses, steps) for masses, steps in engines if steps == answer["steps"]]
    trials = [(masses, steps) for masses, steps in engines if steps != answer["steps"]]
    print(f"engines the command stepped: {len(full)} to the end ({', '.join(f'{a:,} masses × {s:,} steps' for a, s in full)})"
          + (f", and {len(trials)} short trial run(s) of the cost estimate "
             f"({sum(a * s for a, s in trials):,} mass-steps)" if trials else "")
          + f" -> one simulation per command: {verdict(len(full) == 1 and full[0][0] == len(omega))}")

    subset = settings.pick(len(omega), 50)
    picked = np.linspace(0, len(omega) - 1, subset).round().astype(int)
    constants = dict(m=values["m"], k=values["k"], b=b, F0=values["F0"], until=values["until"],
                     window=window, dt=answer["dt"])
    scipy_amps, scipy_cpu = timed(lambda: np.array([scipy_amplitude(w, **constants) for w in omega[picked]]))
    scipy_total = scipy_cpu * len(omega) / subset
    scipy_error = float(np.max(np.abs(scipy_amps / exact[picked] - 1)))
    scaled = "" if subset == len(omega) else f" (timed {subset}, scaled ×{len(omega) / subset:g})"
    print(table(["", "wall", "CPU", "max |A/A_exact − 1|"], [
        [f"python {' '.join(COMMAND)}", f"{wall:.2f} s", f"{cpu:.2f} s", f"{error:.3%}"],
        [f"solve_ivp RK45 rtol 1e-6, a loop over {len(omega)} ω, in this process{scaled}", "-",
         f"{scipy_total:.1f} s", f"{scipy_error:.3%}"],
    ]))
    speedup = scipy_total / cpu
    print(f"target: the command ≥ {TARGET:g}× faster than the solve_ivp loop (CPU, the command's whole "
          f"process against the loop alone): {speedup:.0f}× -> {verdict(speedup >= TARGET)}")
    print(f"target: every amplitude within {TOLERANCE:.0%} of the closed form: worst {error:.3%} "
          f"-> {verdict(error <= TOLERANCE)}")
    return {"wall": wall, "cpu": cpu, "error": error, "scipy_cpu": scipy_total, "scipy_error": scipy_error,
            "speedup": speedup, "engines": engines}

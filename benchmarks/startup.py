"""Part 6: start-up. How long `python main.py vertical --headless` takes, next to a bare `python -c pass`.

Each command runs as a subprocess (median of 5, with a timeout; a child that hangs is killed).
`python -X importtime` then lists every module the headless run imports: vpython must not be
one of them, since importing it alone takes longer than the whole 0.5 s budget (and creating a
canvas would start a server).
"""
from __future__ import annotations

import os
import statistics
import subprocess
import sys

from .common import ROOT, process_time, verdict

HEADLESS = ["main.py", "vertical", "--headless"]
TIMEOUT = 60.0   # s for one child process


def wall_time(arguments) -> tuple[float, float]:
    """(wall s, CPU s) of one `python <arguments>` run from the project folder; raises if it fails."""
    seconds, cpu, _ = process_time(arguments, timeout=TIMEOUT)
    return seconds, cpu


def imported_modules(arguments) -> list[tuple[str, float]]:
    """(module, cumulative import time in s) for every module `python -X importtime` reports."""
    completed = subprocess.run([sys.executable, "-X", "importtime", *arguments], cwd=ROOT,
                               capture_output=True, text=True, timeout=TIMEOUT)
    modules = []
    for line in completed.stderr.splitlines():
        if line.startswith("import time:") and "|" in line and "cumulative" not in line:
            _, cumulative, name = line[len("import time:"):].split("|")
            modules.append((name.strip(), int(cumulative) / 1e6))
    return modules


def main(settings) -> dict:
    repeats = 5
    if not os.path.exists(os.path.join(ROOT, "main.py")):
        print("Part 6: start-up skipped: main.py does not exist yet")
        return {"skipped": True}
    print(f"Part 6: start-up, median wall time of {repeats} runs each")
    bare_runs = [wall_time(["-c", "pass"]) for _ in range(repeats)]
    headless_runs = [wall_time(HEADLESS) for _ in range(repeats)]
    bare, bare_cpu = (statistics.median(column) for column in zip(*bare_runs))
    headless, headless_cpu = (statistics.median(column) for column in zip(*headless_runs))
    print(f"python -c pass:                     {bare * 1e3:7.1f} ms wall, {bare_cpu * 1e3:6.1f} ms CPU")
    print(f"python {' '.join(HEADLESS)}: {headless * 1e3:7.1f} ms wall, {headless_cpu * 1e3:6.1f} ms CPU  "
          f"({headless / bare:.1f}× the bare interpreter)")
    print(f"target < 0.5 s: {verdict(headless < 0.5)}")
    modules = imported_modules(HEADLESS)
    top_level = {}
    for name, seconds in modules:
        if "." not in name.strip():
            top_level[name.strip()] = seconds
    slowest = sorted(top_level.items(), key=lambda item: -item[1])[:6]
    print("slowest top-level imports: " + ", ".join(f"{name} {s * 1e3:.0f} ms" for name, s in slowest))
    vpython_loaded = any(name == "vpython" or name.startswith("vpython.") for name, _ in modules)
    print(f"vpython imported by the headless run: {'YES' if vpython_loaded else 'no'}")
    return {"bare": bare, "headless": headless, "headless_cpu": headless_cpu, "vpython": vpython_loaded, "slowest": slowest}

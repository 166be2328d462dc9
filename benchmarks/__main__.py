"""Run the benchmarks: `python -m benchmarks [--quick] [--only NAME ...] [--list] [--against REF]`.

Part 5 (a scene left running in headless Chromium for 10 minutes) is a separate command, since it
takes minutes of wall time and needs Chromium and Playwright: `python -m benchmarks.long_run`.
Figures and how to read them: docs/performance.md; the log of every run: benchmarks/results/.

Parts 1, 3 and 6 time the user's commands (`python main.py ...`) as whole processes; figures
of the engine called in-process are labelled "internal API, no user path". Every figure is
compared with a reference measured in the same run (the page's vpython-vector loop as a process,
a bare interpreter, scipy), so the ratios mean something even on a busy machine. The full run
takes about 5 minutes on 2 cores (a solve_ivp loop over 1,000 frequencies is a minute of it);
--quick about a minute.

`--against REF` compares this tree with REF (a commit, branch or tag) instead: each benchmark's
jobs run on both trees in turn, and a table gives each ratio with its spread, marking any figure
more than 10 % worse (benchmarks/against.py).
"""
from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time

from . import (accuracy, allocation, against, batches, fit, fit_coverage, friction, resonance_sweep, single_mass,
               startup, where_the_work_is)
from .common import Settings, load_average

BENCHMARKS = {
    "single-mass": (single_mass, "part 1: `main.py vertical` 10⁶ steps (--json, --csv) against the page's loop, "
                                 "as processes"),
    "batches": (batches, "part 2: N = 1…10⁶ oscillators in one array, 1-D and 3-D (internal API)"),
    "resonance": (resonance_sweep, "part 3: `main.py resonance` with 1,000 frequencies against solve_ivp"),
    "accuracy": (accuracy, "part 4: error after 10 periods against CPU time, with a plot"),
    "startup": (startup, "part 6: wall time of `python main.py vertical --headless`"),
    "csv-batch": (where_the_work_is, "part 7: --csv of 10⁶ rows against the page's loop, and "
                                     "`main.py resonance` at 10⁴ masses in rk4 mass-steps/s"),
    "fit": (fit, "part 8: `main.py damped --data FILE --fit k,b --set m=M` on 10³, 10⁴ and 2·10⁵ points, "
                 "as processes: time and engine runs"),
    "friction": (friction, "part 9: `main.py friction` 10⁶ steps against `main.py damped` 10⁶ steps, as processes"),
    "fit-coverage": (fit_coverage, "part 10: the fit's σ against the truth on 400 closed-form records over the "
                                   "whole range (in this process)"),
    "allocation": (allocation, "part 12: memory the resonance batch loop and command allocate per step, flat "
                               "as the step count grows"),
}
# Not in the full run: minutes of wall time in headless Chromium. Run it as its own command.
SEPARATE = {
    "python -m benchmarks.long_run": "part 5: a scene in headless Chromium for 10 min (--minutes, --scene, "
                                     "--set dt=0.0001, --source DIR): t shown against wall time, memory, "
                                     "CPU per wall second; see --help",
    "python -m benchmarks.first_frame": "part 9: time to the first drawn frame, the offline page (--html, from "
                                        "file://) against the local page, in one Chromium; and the file's size",
}


def machine() -> str:
    """CPU model, core count, Python and numpy versions: what the figures were measured on."""
    import numpy

    model = platform.processor() or "unknown CPU"
    try:
        lscpu = subprocess.run(["lscpu"], capture_output=True, text=True, timeout=10).stdout
        model = next(line.split(":", 1)[1].strip() for line in lscpu.splitlines() if line.startswith("Model name"))
    except (OSError, subprocess.SubprocessError, StopIteration):
        pass
    return (f"{model}, {os.cpu_count()} cores, Python {platform.python_version()}, numpy {numpy.__version__}, "
            f"{platform.system()} {platform.release()}")


def parse_arguments(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m benchmarks", description=__doc__.splitlines()[0],
        epilog="Part 5, the page left running in headless Chromium, is a separate command: "
               "python -m benchmarks.long_run --help. Figures: docs/performance.md.")
    parser.add_argument("--quick", action="store_true", help="fewer steps and repeats: about a minute in all")
    parser.add_argument("--only", metavar="NAME", action="append", choices=list(BENCHMARKS),
                        help="run only this benchmark (repeatable): " + ", ".join(BENCHMARKS))
    parser.add_argument("--list", action="store_true", help="list the benchmarks and exit")
    parser.add_argument("--against", metavar="REF",
                        help="compare this tree with REF (a commit, branch or tag), checked out into a temporary "
                             "worktree: each benchmark's jobs on both trees in turn, each ratio with its spread, "
                             "any figure more than 10%% worse marked")
    parser.add_argument("--repeats", metavar="N", type=int,
                        help="with --against: runs of each job on each tree (default 5, --quick 3)")
    arguments = parser.parse_args(argv)
    if arguments.repeats is not None and (arguments.against is None or arguments.repeats < 1):
        parser.error("--repeats needs --against, and a whole number of 1 or more")
    return arguments


def main(argv=None) -> int:
    arguments = parse_arguments(argv)
    if arguments.list:
        for name, (_, summary) in BENCHMARKS.items():
            print(f"{name:12s} {summary}")
        print("run on its own (not part of the full run):")
        for command, summary in SEPARATE.items():
            print(f"  {command}  {summary}")
        return 0
    settings = Settings(quick=arguments.quick)
    chosen = arguments.only or list(BENCHMARKS)
    print(f"machine: {machine()}")
    print(f"command: python -m benchmarks {' '.join(argv if argv is not None else sys.argv[1:])}".rstrip())
    print(f"load average at start: {load_average()} (other work on the machine slows every figure; "
          "the ratios within one run are fairer)")
    start, cpu_start = time.perf_counter(), time.process_time()
    if arguments.against is not None:
        try:
            against.compare(chosen, settings, arguments.against,
                            repeats=arguments.repeats or settings.pick(5, 3))
        except against.AgainstError as problem:
            print(f"error: {problem}", file=sys.stderr)
            return 2
        print(f"\ntotal wall time {time.perf_counter() - start:.0f} s")
        return 0
    for name in chosen:
        print()
        module, _ = BENCHMARKS[name]
        try:
            module.main(settings)
        except ImportError as error:
            print(f"{name} skipped: {error} (pip install -r requirements-bench.txt)")
    print(f"\ntotal wall time {time.perf_counter() - start:.0f} s, CPU time of this process "
          f"{time.process_time() - cpu_start:.0f} s; load average at the end: {load_average()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

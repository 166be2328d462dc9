"""Small helpers shared by the benchmarks: timing, tables, and the run's settings."""
from __future__ import annotations

import os
import subprocess
import sys
import time
from dataclasses import dataclass

try:
    import resource           # POSIX: the CPU time of finished child processes, page faults
except ImportError:           # Windows has no resource module: a child's CPU time is taken as its wall time
    resource = None

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@dataclass(frozen=True)
class Settings:
    """How long the run may take: quick (about 30 s in all) or full (a few minutes)."""

    quick: bool = False

    def pick(self, full, quick):
        """The full-run value, or the quick one."""
        return quick if self.quick else full


def timed(function, *args, clock=time.process_time, **kwargs):
    """(result, seconds) of one call, measured with `clock`.

    The default is this process's CPU time, not wall time: the machine may be shared, and CPU
    time hardly changes when another program takes turns on the same core. numpy runs these
    element-wise loops on one thread, so on an idle machine the two agree.
    """
    start = clock()
    result = function(*args, **kwargs)
    return result, clock() - start


def _children_cpu() -> float:
    """CPU s of the finished child processes so far (0 without the resource module: see process_time)."""
    if resource is None:
        return 0.0
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def load_average(every: bool = False) -> str:
    """The machine's load average over 1 minute (every: 1, 5 and 15), or "n/a" where the system
    keeps none (Windows)."""
    try:
        loads = os.getloadavg()
    except (AttributeError, OSError):
        return "n/a"
    return " ".join(f"{x:.2f}" for x in loads) if every else f"{loads[0]:.1f}"


def process_time(arguments, *, timeout: float = 300.0) -> tuple[float, float, str]:
    """(wall s, CPU s, stdout) of one `python <arguments>` run from the project folder, as a user
    runs it: start-up, imports and output included. Raises RuntimeError if it fails.

    The CPU time (user + system of the child) hardly changes when other work shares the machine;
    the wall time does. subprocess.run kills the child if it outlasts `timeout`. Without the
    resource module (Windows) the CPU time given is the wall time.
    """
    cpu_before = _children_cpu()
    start = time.perf_counter()
    completed = subprocess.run([sys.executable, *arguments], cwd=ROOT, capture_output=True,
                               text=True, timeout=timeout)
    seconds = time.perf_counter() - start
    if completed.returncode != 0:
        raise RuntimeError(f"python {' '.join(arguments)} exited with {completed.returncode}: "
                           f"{completed.stderr.strip().splitlines()[-1:]}")
    return seconds, (_children_cpu() - cpu_before) if resource is not None else seconds, completed.stdout


def table(headers, rows) -> str:
    """A plain-text table with right-aligned columns (cells are already formatted strings)."""
    cells = [list(map(str, headers))] + [[str(c) for c in row] for row in rows]
    widths = [max(len(row[i]) for row in cells) for i in range(len(headers))]
    lines = ["  ".join(cell.rjust(width) for cell, width in zip(row, widths)) for row in cells]
    lines.insert(1, "  ".join("-" * width for width in widths))
    return "\n".join(lines)


def verdict(holds: bool) -> str:
    return "holds" if holds else "does NOT hold yet"

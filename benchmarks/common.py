"""Small helpers shared by the benchmarks: timing, tables, and the run's settings."""
from __future__ import annotations

import time
from dataclasses import dataclass


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


def best_of(repeats: int, function, *args, clock=time.process_time, **kwargs):
    """(result, seconds) of the fastest of `repeats` calls: the least disturbed by other work."""
    best = None
    for _ in range(repeats):
        result, seconds = timed(function, *args, clock=clock, **kwargs)
        if best is None or seconds < best[1]:
            best = (result, seconds)
    return best


def table(headers, rows) -> str:
    """A plain-text table with right-aligned columns (cells are already formatted strings)."""
    cells = [list(map(str, headers))] + [[str(c) for c in row] for row in rows]
    widths = [max(len(row[i]) for row in cells) for i in range(len(headers))]
    lines = ["  ".join(cell.rjust(width) for cell, width in zip(row, widths)) for row in cells]
    lines.insert(1, "  ".join("-" * width for width in widths))
    return "\n".join(lines)


def verdict(holds: bool) -> str:
    return "holds" if holds else "does NOT hold yet"

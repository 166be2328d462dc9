"""A headless run as a CSV file (`--headless --csv FILE`): one row per step, and per mass.

    t,x,y,z,vx,vy,vz,px,py,pz,K,U,E,W_nc

in s, m, m/s, kg·m/s and J (export/numbers.py's CSV_HEADER), the numbers as the page's own
Download CSV writes them (export/csv_rows.py).
"""
from __future__ import annotations

import sys
from typing import Callable

import numpy as np

from export.csv_rows import ROWS_PER_BLOCK, csv_field, number_rows
from export.number_blocks import rounded_times
from export.files import STDOUT, atomic_file
from export.numbers import CSV_HEADER, ENERGY_KEYS, time_decimals
from physics.state import velocity

from .headless import Result


def write_csv(result: Result, path: str) -> int:
    """One row per step (per mass): t, r, v, p, then the system's K, U, E, W_nc in J; returns rows written.

    Multi-mass scenes add a `body` column with each mass's label; the energy columns are totals.
    path "-" writes to standard output. A file that cannot be written raises OutputError; the
    rows go to a temporary file that replaces `path` only when complete (see atomic_file).
    """
    if path == STDOUT:
        return _write_rows(result, lambda text: sys.stdout.write(text.decode("utf-8")))
    with atomic_file(path, what="CSV file", record=False) as temporary:   # known by its header
        with open(temporary, "wb") as handle:      # UTF-8 bytes, "\r\n" as csv.writer ends rows
            return _write_rows(result, handle.write)


def _write_rows(result: Result, write: Callable[[bytes], object]) -> int:
    """Write the header and the rows, as UTF-8 bytes, with `write`; returns the rows written."""
    traj = result.trajectory
    single = len(traj.m) == 1
    header = CSV_HEADER + ([] if single else ["body"])
    write((",".join(map(csv_field, header)) + "\r\n").encode("utf-8"))
    # The rows a block of steps at a time (export/csv_rows.py): the same text as csv.writer
    # writing clean_time(t, Δt), then clean() of r, v, p and the energies, for each row.
    decimals = time_decimals(result.model.dt)
    count = len(traj.m)
    after = [("" if traj.energy else ",,,,") + ("" if single else "," + csv_field(label)) + "\r\n"
             for label in result.labels]
    columns = 10 + (len(ENERGY_KEYS) if traj.energy else 0)
    block = max(1, ROWS_PER_BLOCK // count)
    for start in range(0, len(traj.t), block):
        steps = slice(start, start + block)
        t = rounded_times(traj.t[steps], decimals)
        values = np.empty((len(t), count, columns))
        values[:, :, 0] = t[:, None]
        values[:, :, 1:4], values[:, :, 7:10] = traj.r[steps], traj.p[steps]
        values[:, :, 4:7] = velocity(traj.p[steps], traj.m)      # a block at a time: no v of the whole run
        for j, key in enumerate(ENERGY_KEYS if traj.energy else ()):
            values[:, :, 10 + j] = traj.energy[key][steps][:, None]
        write(number_rows(values.reshape(-1, columns), after=after))
    return len(traj.t) * count

"""What a run keeps: which steps to record, the recorded steps, and a whole run's trajectory.

The engine (physics/simulate.py) steps; this module holds what it records. A schedule says which
step number is recorded next (every n-th step, or the first step at or after each time of a
grid); the recorder keeps those steps as flat rows of floats, packed into arrays a block at a
time; Samples are what one advance() recorded, and a Trajectory is a run from its start with the
energy of every sample.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from .energy import series
from .state import State, velocity

BLOCK = 1024                 # recorded rows packed into one array at a time
PREPARED_NUMBERS = 1 << 26   # the most numbers (512 MB) a recording keeps in an array made beforehand


def steps_to_reach(until: float, dt: float) -> int:
    """Number of steps of dt that reaches time `until` (rounding up, forgiving round-off)."""
    return max(0, math.ceil(until / dt - 1e-9))


# ---- what to record: a schedule says which step number is recorded next ----

class every:
    """Record every n-th step (n = 1: every step): a schedule whose next mark is done + n, which
    the traced loop (physics/compiled.py) works out itself, with no call per step."""

    def __init__(self, n: int):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ValueError("record_every must be a whole number ≥ 1, or None for the final state only")
        self.stride = int(n)

    def __call__(self, done: int) -> int:
        return (done // self.stride + 1) * self.stride


def time_grid(spacing: float, *, t0: float, dt: float, start: float = 0.0, end: float = math.inf):
    """Record the first step at or after each time start, start + spacing, ... up to end, s.

    spacing ≤ dt records every step from start to end.
    """
    def after(done):
        t = t0 + done * dt
        if t >= end:
            return math.inf
        grid = start if t < start else start + (math.floor((t - start) / spacing + 1e-9) + 1) * spacing
        return max(done + 1, steps_to_reach(min(grid, end) - t0, dt))
    return after


@dataclass
class Samples:
    """Recorded steps: t (n,) s, r and p (n, N, D) in m and kg·m/s, W_nc so far (n, N) J."""

    t: np.ndarray
    r: np.ndarray
    p: np.ndarray
    work: np.ndarray
    m: np.ndarray
    rows: np.ndarray | None = field(default=None, repr=False, compare=False)
    # the recorded rows (step number, r, p, P_nc, W_nc) of which r, p and work are views, after
    # a free first row: trajectory() puts the start there instead of copying every sample

    @property
    def v(self) -> np.ndarray:
        return velocity(self.p, self.m)

    def __len__(self) -> int:
        return len(self.t)


class Recorder:
    """The steps recorded during one advance: which step is due next (`mark`, from the schedule),
    and the recorded rows of floats (the step number, then the values), packed into arrays a
    block at a time.

    schedule  step number done -> the next step number to record (every(n), time_grid(...)), or None
    target    the step number the advance ends at; with `final` it is recorded too
    stride    n for every(n), whose marks the traced loop works out itself (and caps at `last`,
              the target if `final`); 0 for other schedules, which it asks through record()
    """

    def __init__(self, engine, schedule=None, *, target: float = math.inf, final: bool = True):
        self.engine = engine
        self.schedule = schedule if schedule is not None else (lambda done: math.inf)
        self.target, self.final = target, final
        self.last = target if final else math.inf
        self.stride = schedule.stride if isinstance(schedule, every) else 0
        start = engine.start
        self.width = 1 + 2 * start.r.size + 2 * start.count
        self.rows: list[float] = []    # this block's rows, flat: the step number, every component of r, p, P_nc, W_nc
        self.blocks: list[np.ndarray] = []
        # every(n) knows how many rows it will keep: they go straight into one array, after a free
        # first row (Samples.rows), with no array per block to copy again at the end
        self.filled = 0
        self.buffer = np.empty((1 + self._expected(engine.steps), self.width))
        self.mark = self._next(engine.steps)

    def _expected(self, done: int) -> int:
        """How many rows the schedule keeps from step `done` to the target (0 if unknown or too many):
        every(n) works it out; another schedule (a time grid) is asked, up to as many rows as fit."""
        n, target, most = self.stride, self.target, PREPARED_NUMBERS // self.width
        if not math.isfinite(target):
            return 0
        if n:
            count = int(target) // n - done // n + (1 if self.final and int(target) % n else 0)
        else:
            count, mark = 0, self._next(done)
            while mark <= target and count <= most:
                count, mark = count + 1, (self._next(mark) if mark < target else math.inf)
        return count if 0 < count <= most else 0

    def _next(self, done: int):
        mark = self.schedule(done)
        return min(mark, self.target) if self.final else mark

    def record(self, done, *, values=None, arrays=None):
        """Keep step number `done` (its values flattened, or its arrays); returns the next mark."""
        self.add(done, values=values, arrays=arrays)
        self.mark = self._next(done)
        return self.mark

    def add(self, done, *, values=None, arrays=None):
        if values is None:             # the numpy tick's arrays, maybe of 10⁴ masses
            self.flush()
            if not self.blocks and self.filled + 1 < len(self.buffer):   # straight into the row made for it
                self.filled += 1
                _fill(self.buffer[self.filled], done, arrays)
            else:
                self._keep(_fill(np.empty((1, self.width)), done, arrays))
            return
        self.rows.append(done)
        self.rows.extend(values)
        if len(self.rows) >= BLOCK * self.width:
            self.flush()

    def flush(self):
        if self.rows:
            self._keep(np.fromiter(self.rows, dtype=float, count=len(self.rows)).reshape(-1, self.width))
            self.rows.clear()          # the same list: the traced loop may hold its extend

    def _keep(self, block: np.ndarray) -> None:
        end = 1 + self.filled + len(block)
        if not self.blocks and end <= len(self.buffer):
            self.buffer[end - len(block):end] = block
            self.filled += len(block)
        else:
            self.blocks.append(block)

    def samples(self) -> Samples:
        self.flush()
        start = self.engine.start
        if self.blocks:
            rows = np.empty((1 + self.filled + sum(map(len, self.blocks)), self.width))
            rows[1:1 + self.filled] = self.buffer[1:1 + self.filled]
            np.concatenate(self.blocks, out=rows[1 + self.filled:])
        else:
            rows = self.buffer[:1 + self.filled]
        r, p, work = _columns(rows[1:], start)
        return Samples(t=start.t + rows[1:, 0] * self.engine.dt, r=r, p=p, work=work, m=start.m, rows=rows)


def _fill(row: np.ndarray, done: int, arrays) -> np.ndarray:
    """Row (or a (1, width) block) = the step number, then every component of the arrays in order."""
    flat, offset = row.reshape(-1), 1
    flat[0] = done
    for a in arrays:
        size = np.size(a)
        flat[offset:offset + size].reshape(np.shape(a))[...] = a    # one pass, whatever a's layout
        offset += size
    return row


def _columns(rows: np.ndarray, start: State):
    """r, p (n, N, D) and W_nc (n, N) of recorded rows, as views."""
    size, count = start.r.size, start.count
    return (rows[:, 1:1 + size].reshape((-1,) + start.r.shape),
            rows[:, 1 + size:1 + 2 * size].reshape((-1,) + start.r.shape), rows[:, 1 + 2 * size + count:])


@dataclass
class Trajectory:
    """Samples of a run: t (n,), r and p (n, N, 3), W_nc (n, N); where the forces are given, the
    energy of every sample (a dict of (n,) arrays, J), worked out when first asked for, or of a
    few samples alone (energy_at: a report of the start and the end needs no more)."""

    t: np.ndarray
    r: np.ndarray
    p: np.ndarray
    m: np.ndarray
    forces: tuple | None = None
    work: np.ndarray | None = None

    @functools.cached_property
    def energy(self) -> dict | None:
        return self.energy_at(slice(None))

    def energy_at(self, samples) -> dict | None:
        """K, U, E, W_nc and E − W_nc of these samples (an index, a list or a slice), J; None
        without forces. The same numbers as those samples of `energy`."""
        if self.forces is None:
            return None
        if "energy" in self.__dict__:
            return {key: values[samples] for key, values in self.energy.items()}
        return series(State(t=self.t[samples], r=self.r[samples], p=self.p[samples], m=self.m), self.forces,
                      self.work[samples])

    @property
    def v(self) -> np.ndarray:
        return velocity(self.p, self.m)

    @property
    def final(self) -> State:
        """The last recorded state, ready to run on."""
        return State(t=float(self.t[-1]), r=np.asfortranarray(self.r[-1]), p=np.asfortranarray(self.p[-1]),
                     m=self.m)


def trajectory(engine, samples: Samples, *, with_energy: bool = True) -> Trajectory:
    """A Trajectory of the engine's start and these samples (energy of every sample, J)."""
    start = engine.start
    t = np.concatenate([[start.t], samples.t])
    rows = samples.rows
    if rows is not None and len(rows) == len(samples) + 1 and rows.shape[1] == 1 + 2 * start.r.size + 2 * start.count:
        # the start goes in the recorded rows' free first row: no copy of a run's every sample
        size = start.r.size
        rows[0, :1 + 2 * size] = np.concatenate([[0.0], start.r.ravel(), start.p.ravel()])
        rows[0, 1 + 2 * size:] = 0.0
        r, p, work = _columns(rows, start)
    else:
        r = np.concatenate([start.r[None], samples.r])
        p = np.concatenate([start.p[None], samples.p])
        work = np.concatenate([np.zeros((1, start.count)), samples.work])
    return Trajectory(t=t, r=r, p=p, m=start.m, forces=engine.forces if with_energy else None, work=work)

"""What a run keeps: which steps to record, the recorded steps, and a whole run's trajectory.

The engine (physics/simulate.py) steps; this module holds what it records. A schedule says which
step number is recorded next (every n-th step, or the first step at or after each time of a
grid); the recorder keeps those steps as flat rows of floats, packed into arrays a block at a
time; Samples are what one advance() recorded, and a Trajectory is a run from its start with the
energy of every sample. A Watch is shown those steps, and steps it asks for, without keeping them:
what a run measures as it goes (the period's crossings, a scene's largest amplitude), so that a
run of 10⁴ masses keeps no more memory at its ten-thousandth step than at its first.
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
WATCHED_NUMBERS = 1 << 17    # numbers a Watch gathers (1 MB) before passing them on


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


class Watch:
    """What a run looks at as it goes without keeping it: the period's crossings (CoordinateWatch),
    a scene's largest amplitude over its window (WindowLargest). Keeping every step of 10⁴ masses
    to look at it afterwards is 640 kB of new memory a step.

    A watch is shown the start of a run (when the run starts at step 0), then, in order, every
    step the run records and every step any of the run's watches asks for by its `schedule`
    (None: none besides the recorded ones): one at a time as see(t, r, p), t in s and r, p (N, D)
    the positions and momenta then, or a block at a time as see_block(t (n,), r, p (n, N, D)).
    The arrays are the run's own and change after the call: a watch copies what it keeps.
    flush() comes at the end of every advance.
    """

    schedule = None

    def see(self, t: float, r: np.ndarray, p: np.ndarray) -> None:
        raise NotImplementedError

    def see_block(self, t: np.ndarray, r: np.ndarray, p: np.ndarray) -> None:
        for n in range(len(t)):
            self.see(float(t[n]), r[n], p[n])

    def flush(self) -> None:
        pass


class CoordinateWatch(Watch):
    """One coordinate of every mass, passed on a block of samples at a time as sink.add(t, x), t (n,)
    s and x (n, N): what physics/period.py's CrossingMeter times the period by. The arrays passed
    are reused for the next block: a sink copies what it keeps.

    axis      which component of r: 0, 1 or 2 (x, y, z)
    schedule  the steps it asks for besides the recorded ones (time_grid(...)), or None
    """

    def __init__(self, sink, *, axis: int, schedule=None):
        self.sink, self.axis, self.schedule = sink, int(axis), schedule
        self._t = self._x = None
        self._seen = 0

    def see(self, t, r, p) -> None:
        x = r[..., self.axis]
        if self._x is None:               # made once, on the first sample: the same arrays all run
            self._x = np.empty((max(1, WATCHED_NUMBERS // max(1, len(x))), len(x)))
            self._t = np.empty(len(self._x))
        elif self._seen == len(self._x):
            self.flush()
        self._t[self._seen] = t
        self._x[self._seen] = x
        self._seen += 1

    def see_block(self, t, r, p) -> None:
        self.flush()
        self.sink.add(t, r[..., self.axis])

    def flush(self) -> None:
        if self._seen:
            self.sink.add(self._t[:self._seen], self._x[:self._seen])
            self._seen = 0


class WindowLargest(Watch):
    """The largest value of quantity(state) for each mass over a window of a run, from `start` (to
    round-off) to one step after `end`, s: a scene's measurement (resonance: the largest amplitude
    A = √(x² + (v/ω)²) of each spring once the transient has died away). It asks for every step
    of the window (unless `ask` is False: a run that records every step shows it every step
    anyway); `largest` is (N,) (None until a step of the window is shown), and `last` the time of
    the last step shown, s.
    """

    def __init__(self, quantity, *, window: tuple[float, float], initial: State, dt: float, ask: bool = True):
        """quantity(state) -> (N,); window (start, end), s; the run's initial state and Δt, s."""
        self.quantity, self.m, self.dt = quantity, initial.m, float(dt)
        self.start, self.end = float(window[0]), float(window[1])
        self.schedule = time_grid(dt, t0=initial.t, dt=dt, start=self.start, end=self.end) if ask else None
        self.largest, self.last = None, None

    def see(self, t, r, p) -> None:
        self.last = t
        if self.start - 1e-9 * self.dt <= t <= self.end + self.dt:
            value = self.quantity(State(t=t, r=r, p=p, m=self.m))
            self.largest = np.array(value, dtype=float) if self.largest is None else \
                np.maximum(self.largest, value, out=self.largest)

    @property
    def reached(self) -> bool:
        """Whether the run was shown the end of the window (else `largest` is not the window's)."""
        return self.largest is not None and self.last is not None and self.last >= self.end


class Recorder:
    """The steps recorded during one advance: which step is due next (`mark`, from the schedule),
    and the recorded rows of floats (the step number, then the values), packed into arrays a
    block at a time.

    schedule  step number done -> the next step number to record (every(n), time_grid(...)), or None
    target    the step number the advance ends at; with `final` it is recorded too
    watches   Watches shown the start (at step 0), every recorded step and every step their own
              schedules ask for, none of which is kept unless recorded
    stride    n for every(n), whose marks the traced loop works out itself (and caps at `last`,
              the target if `final`); 0 for other schedules, which it asks through record()
    """

    def __init__(self, engine, schedule=None, *, target: float = math.inf, final: bool = True, watches=()):
        self.engine = engine
        self.schedule = schedule if schedule is not None else (lambda done: math.inf)
        self.target, self.final = target, final
        self.last = target if final else math.inf
        self.watches = tuple(watches)
        own = [watch.schedule for watch in self.watches if watch.schedule is not None]   # steps only watched
        self.stride = schedule.stride if isinstance(schedule, every) and not own else 0
        self._watched = (lambda done: math.inf) if not own else (lambda done: min(ask(done) for ask in own))
        start = engine.start
        self.width = 1 + 2 * start.r.size + 2 * start.count
        self.rows: list[float] = []    # this block's rows, flat: the step number, every component of r, p, P_nc, W_nc
        self.blocks: list[np.ndarray] = []
        # every(n) knows how many rows it will keep: they go straight into one array, after a free
        # first row (Samples.rows), with no array per block to copy again at the end
        self.filled = 0
        self.buffer = np.empty((1 + self._expected(engine.steps), self.width))
        # the next step kept in full, and the next step only the watches see
        self.kept, self.watched = self._next(engine.steps), self._watched(engine.steps)
        self.mark = min(self.kept, self.watched)
        if engine.steps == 0:
            for watch in self.watches:
                watch.see(start.t, start.r, start.p)

    def _expected(self, done: int) -> int:
        """How many rows the schedule keeps from step `done` to the target (0 if unknown or too many):
        every(n) works it out; another schedule (a time grid) is asked, up to as many rows as fit."""
        target, most = self.target, PREPARED_NUMBERS // self.width
        if not math.isfinite(target):
            return 0
        if isinstance(self.schedule, every):
            n = self.schedule.stride
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
        """Step number `done` is marked (its values flattened, or its arrays): the watches see it,
        and it is kept where the schedule records it. Returns the next mark."""
        if self.watches:
            if self.stride:
                self.flush()              # rows the traced loop kept on its own are seen first
            t, (r, p) = self.engine.time_of(done), _state_arrays(self.engine, values, arrays)
            for watch in self.watches:
                watch.see(t, r, p)
        if self.stride or done == self.kept:      # with a stride every mark is kept
            self.add(done, values=values, arrays=arrays)
            self.kept = self._next(done)
        if done == self.watched:
            self.watched = self._watched(done)
        self.mark = min(self.kept, self.watched)
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
            block = np.fromiter(self.rows, dtype=float, count=len(self.rows)).reshape(-1, self.width)
            self.rows.clear()          # the same list: the traced loop may hold its extend
            if self.stride and self.watches:     # kept by the traced loop, not yet seen
                start = self.engine.start
                r, p, _ = _columns(block, start)
                for watch in self.watches:
                    watch.see_block(start.t + block[:, 0] * self.engine.dt, r, p)
            self._keep(block)

    def _keep(self, block: np.ndarray) -> None:
        end = 1 + self.filled + len(block)
        if not self.blocks and end <= len(self.buffer):
            self.buffer[end - len(block):end] = block
            self.filled += len(block)
        else:
            self.blocks.append(block)

    def samples(self) -> Samples:
        self.flush()
        for watch in self.watches:
            watch.flush()
        start = self.engine.start
        if self.blocks:
            rows = np.empty((1 + self.filled + sum(map(len, self.blocks)), self.width))
            rows[1:1 + self.filled] = self.buffer[1:1 + self.filled]
            np.concatenate(self.blocks, out=rows[1 + self.filled:])
        else:
            rows = self.buffer[:1 + self.filled]
        r, p, work = _columns(rows[1:], start)
        return Samples(t=start.t + rows[1:, 0] * self.engine.dt, r=r, p=p, work=work, m=start.m, rows=rows)


def _state_arrays(engine, values, arrays) -> tuple[np.ndarray, np.ndarray]:
    """r and p (N, D) of a marked step, from the traced loop's flat values (r's components, then
    p's, row by row) or the numpy tick's arrays (r, p first)."""
    if arrays is not None:
        return arrays[0], arrays[1]
    shape = engine.start.r.shape
    size = shape[0] * shape[1]
    return (np.asarray(values[:size], dtype=float).reshape(shape),
            np.asarray(values[size:2 * size], dtype=float).reshape(shape))


def _fill(row: np.ndarray, done: int, arrays) -> np.ndarray:
    """Row (or a (1, width) block) = the step number, then every component of the arrays in order."""
    flat, offset = row.reshape(-1), 1
    flat[0] = done
    for a in arrays:
        size = np.size(a)
        part = flat[offset:offset + size].reshape(np.shape(a))
        if part.ndim == 2:        # column by column: r and p are column-major, the row is not, and
            for j in range(part.shape[1]):      # one pass of (N, 3) runs 3-number inner loops
                part[:, j] = a[:, j]            # (3× slower at 10⁴ masses)
        else:
            part[...] = a
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

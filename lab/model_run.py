"""The engine's run of one set of constants along one coordinate, readable at any time, and the runs a
comparison asks for, each made once and counted.

The model compared with measured data is the engine's own run (physics.simulate.Simulation) with the
chosen integrator and Δt: at the engine's step times it is exactly the engine's positions, and between
two steps a cubic Hermite curve through the two positions and velocities. That curve is much closer to
the engine than the engine is to the exact motion (its error is of order Δt⁴, the integrator's of
order Δt), and it lets the data keep their own sample times, so one run per set of constants serves
every time offset.
"""
from __future__ import annotations

import math
import time
from collections import OrderedDict

import numpy as np

from . import LabError
from physics.rounding import round_up
from physics.simulate import BlowUpError, every, steps_to_reach, trajectory

AXES = {"x": 0, "y": 1, "z": 2}
RELEASE = "r0"                    # the start position; a fit takes its component along the compared coordinate
MAX_STEPS_PER_RUN = 2_000_000     # a fit runs the engine dozens of times: each run stays this short


class FitError(LabError):
    """A comparison or fit that cannot be made: one line saying why and what to do."""


def constants_said(setup, names=None) -> str:
    """`k = 40 N/m, b = 1 kg/s, m = 10 kg`: the constants a run was made with (a blow-up says them)."""
    names = names or [name for name, value in setup.values.items() if isinstance(value, (int, float))
                      and name in setup.constants and setup.constants[name].unit not in ("1", "s")][:4]
    return ", ".join(f"{n} = {setup.values[n]:.4g} {setup.constants[n].unit}" for n in names
                     if n in setup.values and isinstance(setup.values[n], (int, float)))


def with_fitted(setup, values: dict, axis: int):
    """The scene with fitted values set: r0 (RELEASE, a vector) takes its component along the
    compared coordinate from `values` and keeps the others (where the scene works r0 out from other
    constants, from the start position it builds)."""
    changes = dict(values)
    if RELEASE in changes:
        r0 = setup.values[RELEASE]
        r0 = [float(x) for x in (r0 if isinstance(r0, tuple) else setup.build().state.r[0])]
        r0[axis] = float(changes[RELEASE])
        changes[RELEASE] = tuple(r0)
    return setup.with_values(**changes)


def too_long(span: float, dt: float, what: str) -> str:
    """One line: a model run of `span` s at Δt `dt` is more steps than a fit may take, and the
    smallest round Δt that is not."""
    least = round_up(span / MAX_STEPS_PER_RUN)
    return (f"{what} {span:.4g} s, which is {span / dt:,.0f} steps of dt = {dt:.3g} s, more than the "
            f"{MAX_STEPS_PER_RUN:,} a run of the model may take; use dt = {least:.3g} s or more, or a "
            f"shorter stretch of the data")


class ModelRun:
    """The engine's run of one set of constants, along one coordinate, readable at any time.

    r(τ) and dr/dτ at model times τ: the engine's step values, joined by cubic Hermite curves
    through each step's position and velocity; before τ = 0 the mass is held at its start.
    """

    def __init__(self, setup, *, integrator, axis: int, until: float, spacing: float = 0.0, progress=None):
        """spacing: keep the engine's values every stride = spacing // Δt steps (every step if that
        is 0): the engine still takes every step, but reading out every one costs more than taking
        it. A cubic through values h = stride·Δt apart is off by h⁴/384 · |d⁴r/dt⁴| at most, far
        below a measurement's noise when h is a quarter of the data's sample interval."""
        model = setup.build()
        if model.state.count != 1:
            raise FitError(f"scene {setup.name!r} has {model.state.count} masses; measured data is "
                           f"compared with a scene of one mass (vertical, damped, driven)")
        if until / model.dt > MAX_STEPS_PER_RUN:
            raise FitError(too_long(until, model.dt, "the model must run"))
        engine = model.simulation(integrator)
        stride = max(1, int(spacing / engine.dt))
        steps = stride * math.ceil(max(steps_to_reach(until - engine.t, engine.dt), 2) / stride)
        try:
            samples = engine.advance(steps, record=every(stride), progress=progress)
        except BlowUpError as problem:
            raise FitError(f"the model blew up with {constants_said(setup)}: {problem}") from None
        path = trajectory(engine, samples, with_energy=False)
        self.dt = engine.dt * stride        # s between the values kept
        self.step = engine.dt               # s: the engine's Δt
        self.end = float(path.t[-1])
        self.r = path.r[:, 0, axis]
        self.v = path.v[:, 0, axis]
        self.methods = tuple(engine.methods)

    def roughly(self, tau: np.ndarray) -> np.ndarray:
        """r at model times τ by straight lines between the values kept (held at the start before
        τ = 0): a few times cheaper than at(), and close enough for a start's search."""
        tau = np.asarray(tau, dtype=float)
        return np.interp(tau.ravel(), self.dt * np.arange(len(self.r)), self.r).reshape(tau.shape)

    def at(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(r, dr/dτ) at model times τ (any shape), s: m and m/s."""
        tau = np.asarray(tau, dtype=float)
        held = tau < 0
        x = np.clip(tau, 0.0, self.end) / self.dt
        i = np.minimum(np.floor(x).astype(int), len(self.r) - 2)
        s = x - i
        r0, r1, v0, v1 = self.r[i], self.r[i + 1], self.v[i] * self.dt, self.v[i + 1] * self.dt
        s2, s3 = s * s, s * s * s
        r = (2 * s3 - 3 * s2 + 1) * r0 + (s3 - 2 * s2 + s) * v0 + (3 * s2 - 2 * s3) * r1 + (s3 - s2) * v1
        slope = ((6 * s2 - 6 * s) * r0 + (3 * s2 - 4 * s + 1) * v0 + (6 * s - 6 * s2) * r1
                 + (3 * s2 - 2 * s) * v1) / self.dt
        return np.where(held, self.r[0], r), np.where(held, 0.0, slope)


class Runs:
    """The engine runs of one comparison: each set of constants (and Δt) run once, kept for reuse
    (the last few), and counted. `progress(line)` hears about the fit once a second after its first."""

    KEEP = 8

    def __init__(self, setup, *, integrator, axis: int, spacing: float, progress=None):
        self.setup, self.integrator, self.axis, self.spacing = setup, integrator, axis, spacing
        self.count = 0
        self.progress = progress
        self.began = self.said = time.monotonic()
        self._kept: OrderedDict = OrderedDict()

    def get(self, values: dict, until: float, dt: float | None = None) -> ModelRun:
        """The run with `values` set (and Δt `dt`, if given) reaching model time `until`, s."""
        key = (tuple(sorted((name, float(value)) for name, value in values.items())), dt)
        run = self._kept.get(key)
        if run is not None and run.end >= until:
            self._kept.move_to_end(key)
            return run
        setup = with_fitted(self.setup, values, self.axis)
        if dt is not None:
            setup = setup.with_values(dt=dt)
        run = ModelRun(setup, integrator=self.integrator, axis=self.axis, until=until, spacing=self.spacing)
        self.count += 1
        self._kept[key] = run
        while len(self._kept) > self.KEEP:
            self._kept.popitem(last=False)
        now = time.monotonic()
        if self.progress is not None and now - self.began > 1.0 and now - self.said >= 1.0:
            self.said = now
            self.progress(f"fitting: {self.count} runs of the model so far ({now - self.began:.0f} s)")
        return run

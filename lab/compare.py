"""The model against a measured run: the offsets, the RMS residual, and a least-squares fit.

The measured file has its own clock and its own zero, so every comparison fits two offsets,

    data(t) ≈ sign · model(t − t_offset) + position_offset,

where t_offset is the data's clock reading at the model's t = 0 (the release) and position_offset
the data's reading where the model's coordinate is 0. The sign is −1 where the data's axis points
the other way from the model's (a motion detector above the mass measures downward; a video's y
axis points down): both signs are tried and the one that matches better is kept, or --data-sign
says which. Before its release the model's mass is
held still at its start position. `--fit k,b` fits named constants too, by least squares
(scipy.optimize.least_squares, optional: only --fit needs scipy; lab/least_squares.py).

The model is the engine's own run (physics.simulate.Simulation) with the chosen integrator and Δt:
at the engine's step times it is exactly the engine's positions, and between two steps a cubic
Hermite curve through the two positions and velocities. That curve is much closer to the engine
than the engine is to the exact motion (its error is of order Δt⁴, the integrator's of order Δt),
and it lets the data keep its own sample times, so one run per set of constants serves every t_offset.

Standard uncertainties come from the Jacobian J of the residuals at the fit: the covariance is
s² (JᵀJ)⁻¹ with s² = Σ residual² / (N − number of fitted values), as for any least-squares fit with
independent noise of the same size on every point. Constants that the data cannot tell apart
(k and m: x(t) depends on k/m only) are refused with one line instead of a meaningless fit.
"""
from __future__ import annotations

import math
from itertools import combinations
from dataclasses import dataclass, field

import numpy as np

from . import LabError, start as start_search
from .least_squares import MissingScipy, least_squares, offsets_only
from physics.forces import FORCES
from physics.simulate import BlowUpError, every, steps_to_reach, trajectory
from scenes import ConstantError, check_value
from scenes._constants import DECLARED

AXES = {"x": 0, "y": 1, "z": 2}
RELEASE = "r0"                    # --fit r0: the start position's component along the compared coordinate
MAX_STEPS_PER_RUN = 2_000_000     # a fit runs the engine dozens of times: each run stays this short
SIGN_MARGIN = 0.5                 # the data's axis is taken as reversed where that halves the misfit
CONDITION_LIMIT = 1e8             # beyond this the fitted values cannot be told apart
# Constants that enter the motion only in a combination, as each force declares them (TIED in
# physics/forces/): fitting two of a group is meaningless.
TIED = [(set(pair), why) for force in FORCES for names, why in force.TIED for pair in combinations(names, 2)]


class FitError(LabError):
    """A comparison or fit that cannot be made: one line saying why and what to do."""


@dataclass(frozen=True)
class Estimate:
    """A fitted value with its standard uncertainty, in `unit`."""

    value: float
    uncertainty: float
    unit: str

    def __str__(self) -> str:
        """`54.997 ± 0.003 N/m`: the uncertainty to two significant digits, the value to the same place."""
        value, sigma, unit = self.value, self.uncertainty, self.unit
        if not (math.isfinite(sigma) and sigma > 0):
            return f"{value:.6g} {unit}"
        decimals = max(0, 1 - math.floor(math.log10(sigma)))
        return f"{value:.{decimals}f} ± {sigma:.{decimals}f} {unit}"


@dataclass
class Comparison:
    """The measured points (t, data: the file's clock, s, and zero, m) against the model there (m)."""

    t: np.ndarray
    data: np.ndarray
    model: np.ndarray
    coordinate: str
    fitted: dict = field(default_factory=dict)      # name → Estimate, for --fit NAMES
    t_offset: Estimate | None = None
    position_offset: Estimate | None = None
    setup: object = None                            # the scene with the fitted values set
    notes: list = field(default_factory=list)
    sign: int = 1                                   # −1: the data's axis points the other way
    slow_dt: tuple = ()                             # (Δt, the data's sample interval, a smaller Δt), s,
                                                    # where the model's Δt is longer than the interval

    @property
    def sign_said(self) -> str:
        """Which way the data's axis was taken to point, in words."""
        c = self.coordinate
        if self.sign > 0:
            return f"the data's axis points the model's way: the model's {c} is compared with the data"
        way = "down" if c == "y" else "the other way"
        return f"the data's axis points {way}: the model is compared with −{c}"

    @property
    def residual(self) -> np.ndarray:
        return self.data - self.model

    @property
    def rms(self) -> float:
        return float(np.sqrt(np.mean(self.residual ** 2)))

    @property
    def points(self) -> int:
        return len(self.t)

    @property
    def misfit(self) -> str:
        """Where the model misses the data by more than a tenth of its half swing, why the ± mean little."""
        half = float(np.ptp(self.data)) / 2
        return "" if not self.rms > 0.1 * half else (
            f"the model misses by {self.rms / half:.0%} of the data's half swing ({half:.3g} m), so the ± "
            f"figures mean little; check the data's units and the constants not fitted (r0 sets the swing's size)")


class ModelRun:
    """The engine's run of one set of constants, along one coordinate, readable at any time.

    r(τ) and dr/dτ at model times τ: the engine's step values, joined by cubic Hermite curves
    through each step's position and velocity; before τ = 0 the mass is held at its start.
    """

    def __init__(self, setup, *, integrator, axis: int, until: float, spacing: float = 0.0):
        """spacing: keep the engine's values every stride = spacing // Δt steps (every step if that
        is 0): the engine still takes every step, but reading out every one costs more than taking
        it. A cubic through values h = stride·Δt apart is off by h⁴/384 · |d⁴r/dt⁴| at most, far
        below a measurement's noise when h is a quarter of the data's sample interval."""
        model = setup.build()
        if model.state.count != 1:
            raise FitError(f"scene {setup.name!r} has {model.state.count} masses; measured data is "
                           f"compared with a scene of one mass (vertical, damped, driven)")
        if until / model.dt > MAX_STEPS_PER_RUN:
            raise FitError(f"the data span {until:.4g} s, which is {until / model.dt:,.0f} steps of "
                           f"dt = {model.dt:g} s per run of the model, more than the {MAX_STEPS_PER_RUN:,} "
                           f"a fit may take; use a larger dt or a shorter stretch of data")
        engine = model.simulation(integrator)
        stride = max(1, int(spacing / engine.dt))
        steps = stride * math.ceil(steps_to_reach(until - engine.t, engine.dt) / stride)
        try:
            samples = engine.advance(steps, record=every(stride))
        except BlowUpError as problem:
            raise FitError(f"the model blew up with {_constants_said(setup)}: {problem}") from None
        path = trajectory(engine, samples, with_energy=False)
        self.dt = engine.dt * stride        # s between the values kept
        self.end = float(path.t[-1])
        self.r = path.r[:, 0, axis]
        self.v = path.v[:, 0, axis]

    def at(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(r, dr/dτ) at model times τ, s: m and m/s."""
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


def coordinate_of(setup, asked: str | None = None) -> str:
    """The coordinate compared: `asked` (--coordinate), else the one the scene plots (vertical: y;
    driven: x)."""
    if asked:
        return asked
    plotted = setup.hooks.view.get("plot", "y")
    return plotted if plotted in AXES else "y"


def _constants_said(setup, names=None) -> str:
    names = names or ("k", "b", "m")
    return ", ".join(f"{n} = {setup.values[n]:.6g} {setup.constants[n].unit}" for n in names
                     if n in setup.values and isinstance(setup.values[n], (int, float)))


def check_names(setup, names) -> list[str]:
    """The constants --fit may fit: numbers of the scene (not dt or until), none tied to another."""
    names = [name.strip() for name in names if name.strip()]
    if not names:
        raise FitError("--fit needs the names of constants to fit, e.g. --fit k,b")
    for name in names:
        if name not in setup.constants:
            raise FitError(f"--fit {name}: scene {setup.name!r} has no constant {name!r} "
                           f"(python main.py {setup.name} --constants lists them)")
        if name == RELEASE and isinstance(setup.values[name], tuple):
            pass          # its component along the compared coordinate: where the mass was let go
        elif name in ("dt", "until") or not isinstance(setup.values[name], (int, float)) \
                or DECLARED[name].vector or DECLARED[name].whole:
            raise FitError(f"--fit {name}: only a physical constant with one number (k, b, m, g, ...) "
                           f"can be fitted")
        if names.count(name) > 1:
            raise FitError(f"--fit names {name!r} twice")
    for group, why in TIED:
        if group <= set(names):
            pair = " and ".join(sorted(group))
            raise FitError(f"--fit {','.join(names)}: {pair} cannot be told apart from a measured "
                           f"position: {why}; set one with --set (weigh the mass: --set m=...) and fit the other")
    return names


def with_fitted(setup, values: dict, axis: int):
    """The scene with fitted values set: r0 (RELEASE, a vector) takes its component along the
    compared coordinate from `values`, and keeps the others."""
    changes = dict(values)
    if RELEASE in changes:
        r0 = [float(x) for x in setup.values[RELEASE]]
        r0[axis] = float(changes[RELEASE])
        changes[RELEASE] = tuple(r0)
    return setup.with_values(**changes)


def _value(setup, name: str, axis: int) -> float:
    """A fitted constant's value as set: r0's component along the compared coordinate."""
    value = setup.values[name]
    return float(value[axis] if isinstance(value, tuple) else value)


class _Problem:
    """The residuals data − model as a function of [fitted constants..., t_offset, position_offset]."""

    def __init__(self, setup, t, y, *, names, integrator, axis):
        self.setup, self.t, self.y = setup, t, y
        self.names, self.integrator, self.axis = names, integrator, axis
        self._runs: dict = {}
        self._jacobian = None
        gaps = np.diff(t)
        self.spacing = float(np.min(gaps)) / 4 if len(gaps) else 0.0   # s: see ModelRun

    def run(self, constants, until: float) -> ModelRun:
        key = tuple(float(c) for c in constants)
        cached = self._runs.get(key)
        if cached is None or cached.end < until:
            for name, value in zip(self.names, key):
                try:
                    check_value(name, value, self.setup.constants[name].unit)
                except ConstantError as problem:
                    raise FitError(f"the fit went out of range: {problem}") from None
            if len(self._runs) > 8:
                self._runs.clear()
            cached = ModelRun(with_fitted(self.setup, dict(zip(self.names, key)), self.axis), integrator=self.integrator, axis=self.axis,
                              until=max(until, 0.0) + 2 * self.setup.values.get("dt", 0.01), spacing=self.spacing)
            self._runs[key] = cached
        return cached

    def model(self, theta):
        p = len(self.names)
        tau = self.t - theta[p]
        return self.run(theta[:p], float(tau[-1])).at(tau)

    def residuals(self, theta):
        r, _ = self.model(theta)
        return r + theta[-1] - self.y

    def jacobian(self, theta):
        """d residual / d theta: the constants' columns by forward differences (one engine run each),
        the offsets' from the model's slope (d/dt_offset = −model'(τ), d/dposition_offset = 1).
        The last one is kept: the fit's final step and the uncertainties ask for the same theta."""
        key = tuple(float(x) for x in theta)
        if self._jacobian is None or self._jacobian[0] != key:
            self._jacobian = (key, self._columns(theta))
        return self._jacobian[1]

    def _columns(self, theta):
        p = len(self.names)
        J = np.empty((len(self.t), p + 2))
        base, slope = self.model(theta)
        for j in range(p):
            h = 1e-6 * max(abs(theta[j]), 1e-3)
            moved = np.array(theta, dtype=float)
            moved[j] += h
            J[:, j] = (self.model(moved)[0] - base) / h
        J[:, p] = -slope
        J[:, p + 1] = 1.0
        return J


def compare(setup, t, y, *, integrator=None, coordinate="y", fit=(), sign=None) -> Comparison:
    """The scene against the measured points t (s), y (m): offsets, RMS, and the fitted constants.

    fit   names of constants to fit (check_names); empty compares with the constants as set.
    sign  +1 or −1: the data's axis points the model's way or the other (--data-sign); None fits
          each way whose start is not clearly worse, and keeps −1 only where it halves the misfit.
    Raises FitError (one line) for a fit that cannot be made.
    """
    t, data = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    if sign not in (None, 1, -1):
        raise FitError(f"--data-sign {sign}: give 1 (the data's axis points the model's way) or -1 (the other way)")
    y = data
    names = check_names(setup, fit) if fit else []
    if len(t) < len(names) + 4:
        raise FitError(f"{len(t)} points cannot fix {len(names) + 2} values (the constants and two offsets)")
    m = float(setup.values.get("m", 1.0))
    problem = _Problem(setup, t, y, names=names, integrator=integrator, axis=AXES[coordinate])

    def start_from(omega):
        """A start near the data's own swing at angular frequency omega, so the fit finds it."""
        start = [_value(setup, name, AXES[coordinate]) for name in names]
        for j, name in enumerate(names):
            if name == "k" and omega:
                start[j] = m * omega ** 2
            elif name == "m" and omega and setup.values.get("k"):
                start[j] = setup.values["k"] / omega ** 2
            elif name == "b":
                start[j] = start_search.decay(t, y, m) or start[j]
        if RELEASE in names:
            j = names.index(RELEASE)
            start[j] = start_search.release(problem, start, j, t, y)
        return start

    candidates = start_search.frequencies(t, y) if {"k", "m"} & set(names) else []
    starts = _within_range(setup, names, [(start_from(None), None)]
                           + [(start_from(omega), omega) for omega in candidates])
    still = problem.run(starts[0][0], 1.0)
    if np.ptp(still.r) <= 1e-12 * (1.0 + np.max(np.abs(still.r))):
        raise FitError(f"the model's {coordinate} does not move in scene {setup.name!r}, so there is nothing "
                       f"to compare; choose the coordinate that moves with --coordinate")
    best = {}
    for way in (1, -1) if sign is None else (sign,):     # the data's axis up, then down
        for start, omega in starts:       # the constants as set, or a candidate frequency: the best match
            t_offset, position_offset, cost = start_search.start_offsets(problem, start, t, way * data)
            if way not in best or cost < best[way][0]:
                best[way] = (cost, start, omega, t_offset, position_offset)
    lowest = min(found[0] for found in best.values())
    fitted = {}
    for way, (cost, *begin) in best.items():    # each way whose start is not clearly worse, fitted
        if cost <= lowest / SIGN_MARGIN:
            problem.y = way * data
            try:
                fitted[way] = _fit_from(problem, setup, *begin)
            except FitError as problem_found:
                fitted[way] = problem_found
    sign = _better_way(fitted)
    if isinstance(fitted[sign], FitError):
        raise fitted[sign]
    theta = fitted[sign][0]
    y = problem.y = sign * data
    J = problem.jacobian(theta)
    residual = problem.residuals(theta)
    scale = np.linalg.norm(J, axis=0)
    if np.any(scale == 0) or not np.all(np.isfinite(J)):
        stuck = [(names + ["t_offset", "position_offset"])[j] for j in np.flatnonzero(~(scale > 0))]
        raise FitError(f"the data cannot fix {', '.join(stuck)}: changing it does not change the model "
                       f"at the data's times")
    _, singular, directions = np.linalg.svd(J / scale, full_matrices=False)
    condition = singular[0] / singular[-1] if singular[-1] > 0 else math.inf
    if condition > CONDITION_LIMIT:
        together = np.abs(directions[-1])         # the change of values that changes nothing
        tied = [(names + ["t_offset", "position_offset"])[j] for j in np.flatnonzero(together > 0.1 * together.max())]
        raise FitError(f"{' and '.join(tied)} cannot be told apart from this data (the fit's Jacobian has "
                       f"condition number {condition:.1e}): a change of one can be undone by a change of "
                       f"the other{'s' if len(tied) > 2 else ''}; set {'it' if len(tied) == 1 else 'all but one'} "
                       f"with --set")
    dof = len(t) - len(theta)
    s2 = float(residual @ residual) / dof if dof > 0 else math.nan
    covariance = np.linalg.pinv((J / scale).T @ (J / scale)) / np.outer(scale, scale) * s2
    sigma = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    fitted = {name: Estimate(float(theta[j]), float(sigma[j]), setup.constants[name].unit)
              for j, name in enumerate(names)}
    final = with_fitted(setup, {name: float(theta[j]) for j, name in enumerate(names)}, AXES[coordinate])
    model = sign * (problem.residuals(theta) + y)
    notes, slow_dt = [], ()
    interval = float(np.median(np.diff(t)))
    dt = float(final.values.get("dt", 0.0))
    if dt > interval:
        slow_dt = (dt, interval, f"{10 ** math.floor(math.log10(interval / 10)):g}")    # a round Δt under it
        notes.append(f"note: the model's dt = {dt:g} s is longer than the data's sample interval "
                     f"{interval:.3g} s, so the integrator's own error is in the comparison; a smaller dt "
                     f"(--set dt={slow_dt[2]}) follows the real motion more closely")
    return Comparison(t=t, data=data, model=model, coordinate=coordinate, fitted=fitted,
                      t_offset=Estimate(float(theta[-2]), float(sigma[-2]), "s"),
                      position_offset=Estimate(sign * float(theta[-1]), float(sigma[-1]), "m"),
                      setup=final, notes=notes, sign=sign, slow_dt=slow_dt)


def _within_range(setup, names, starts) -> list:
    """The starts whose every value lies in its declared range. If the start from the constants as
    set (b from the data's decay) or from the data's strongest frequency lies outside (a swing at a
    kilohertz on a 10 kg mass asks for k = 4e8 N/m: the data's units are not what the file says, or
    the scene's m is not the mass used), FitError says which constant, the value, its range and what
    to check; another frequency's start outside is a weaker peak's, and is dropped."""
    strongest = starts[1][1] if len(starts) > 1 else None
    kept = []
    for start, omega in starts:
        wrong = [(name, value) for name, value in zip(names, start) if not DECLARED[name].allows(value)]
        if not wrong:
            kept.append((start, omega))
        elif omega is None or omega == strongest:
            raise FitError(_outside_said(setup, *wrong[0], omega))
    return kept


def _outside_said(setup, name, value, omega) -> str:
    """One line: the value the data suggest for `name` (k, m from the swing's ω; b from its decay),
    its declared range, and what to check."""
    unit, values = setup.constants[name].unit, setup.values
    how = {"k": f"a swing at ω = {omega or 0:.4g} rad/s with m = {values.get('m', 1.0):.4g} kg (k = m ω²)",
           "m": f"a swing at ω = {omega or 0:.4g} rad/s with k = {values.get('k', 0.0):.4g} N/m (m = k / ω²)"}
    other = "k" if name == "m" else "m"
    return (f"--fit {name}: {how.get(name, 'how fast the data swing dies away')} suggests {name} = "
            f"{value:.3g} {unit}, outside its range ({DECLARED[name].words(unit)}); check the data's units "
            f"(time in s, position in m) and the scene's {other} (--set {other}=...)")


def _fit_from(problem, setup, start, omega, t_offset, position_offset):
    """(theta, Σ residual²): the offsets, then the constants, fitted from a start (problem.y is the
    data as compared)."""
    names = problem.names
    # k and m may move a factor of 10 from the data's own frequency: further is a swing the data
    # does not show, and a stiff spring there would cost the fit minutes of tiny steps.
    reach = {j: (start[j] / 10, start[j] * 10) for j, name in enumerate(names)
             if name in ("k", "m") and omega and start[j] > 0}
    theta = offsets_only(problem, np.array([*start, t_offset, position_offset]))
    if names:
        low = np.array([DECLARED[name].low for name in names] + [-np.inf, -np.inf])
        high = np.array([DECLARED[name].high for name in names] + [np.inf, np.inf])
        for j, (lo, hi) in reach.items():
            low[j], high[j] = max(low[j], lo), min(high[j], hi)
        try:
            theta, _ = least_squares(problem, theta, low, high)
        except MissingScipy as missing:
            raise FitError(str(missing)) from None
        if not np.all(np.isfinite(theta)):
            raise FitError("the fit did not converge to finite values; check the constants set with --set")
        for j, (lo, hi) in reach.items():
            if not lo * 1.001 < theta[j] < hi / 1.001:
                raise FitError(f"the fit of {names[j]} ran to {theta[j]:.4g} {setup.constants[names[j]].unit}, "
                               f"ten times from what the data's frequency suggests ({start[j]:.4g}): the data "
                               f"show too little of the swing to fit it; check --set m, r0 and the column read")
    residual = problem.residuals(theta)
    return theta, float(residual @ residual)


def _better_way(fitted: dict) -> int:
    """+1 or −1: the data's axis the model's way unless reversed fits clearly better (SIGN_MARGIN),
    or the only way tried or that could be fitted."""
    cost = {way: (math.inf if isinstance(found, FitError) else found[1]) for way, found in fitted.items()}
    if 1 not in cost:
        return -1
    return -1 if -1 in cost and cost[-1] < SIGN_MARGIN * cost[1] else 1

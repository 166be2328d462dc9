"""The model against a measured run: the offsets, the RMS residual, and a least-squares fit.

The measured file has its own clock and its own zero, so every comparison fits two offsets,

    data(t) ≈ sign · model(t − t_offset) + position_offset,

where t_offset is the data's clock reading at the model's t = 0 (the release) and position_offset
the data's reading where the model's coordinate is 0. The sign is −1 where the data's axis points
the other way from the model's (a motion detector above the mass measures downward; a video's y
axis points down): both signs are tried, or --data-sign says which. Before its release the model's
mass is held still at its start position. `--fit k,b` fits named constants too, and the release
point with them unless it is given (lab/names.py).

One job a module:

    lab/names.py         which constants may be fitted, and whether the release is fitted with them
    lab/swing.py         the data's own swing: noise, frequency, decay, a held start
    lab/settings.py      the model's integrator and Δt (chosen so that its own error stays out)
    lab/model_run.py     the engine's runs, read at the data's times, counted
    lab/problem.py       data − model, with everything linear in it solved exactly
    lab/start.py         the starts: constants matched to the data's swing, the best t_offset and sign
    lab/fit.py           least squares from the best start, the uncertainties, the Δt/2 check
    lab/outliers.py      sensor drop-outs named and left out
    lab/trust.py         whether the numbers can be trusted, in one sentence
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import outliers as outlier_rows, swing as data_swing
from .fit import BUDGET, Fitted, _NotScale, descend, finish, moves_at_half_dt
from .least_squares import MissingScipy, offset_only
from .model_run import (AXES, MAX_STEPS_PER_RUN, RELEASE, FitError, ModelRun, Runs,  # noqa: F401 (ModelRun:
                        constants_said, too_long, with_fitted)                   # the reports' plot reads it)
from .names import check_names, with_release
from .problem import Problem, linear_mode
from .settings import ModelSettings, best_method, choose_dt, order_of, suggest_dt
from .start import matched, offsets
from .trust import SIGN_TIE, Trust, judge
from physics.integrators import DEFAULT_INTEGRATOR
from physics.stability import rates

SIGN_MARGIN = 0.5                 # without a fit, the data's axis is taken as reversed where that halves the misfit
HALVINGS = 2                      # times a chosen Δt is halved again after the fit, at most


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
        if decimals > 12 or abs(value) >= 1e9:
            return f"{value:.6g} ± {sigma:.2g} {unit}"
        return f"{value:.{decimals}f} ± {sigma:.{decimals}f} {unit}"

    @property
    def plain(self) -> str:
        """The value alone, to the digits its uncertainty allows (for a fit that cannot be trusted)."""
        return str(self).split(" ± ")[0] + ("" if " ± " not in str(self) else f" {self.unit}")


@dataclass
class Comparison:
    """The measured points (t, data: the file's clock, s, and zero, m) against the model there (m)."""

    t: np.ndarray
    data: np.ndarray
    model: np.ndarray
    coordinate: str
    fitted: dict = field(default_factory=dict)      # name → Estimate, for --fit NAMES (and r0)
    t_offset: Estimate | None = None
    position_offset: Estimate | None = None
    setup: object = None                            # the scene with the fitted values (and Δt) set
    notes: list = field(default_factory=list)
    sign: int = 1                                   # −1: the data's axis points the other way
    slow_dt: tuple = ()                             # (Δt, the data's sample interval, a smaller Δt), s,
                                                    # where the model's Δt is longer than the interval
    trust: Trust | None = None                      # a fit's verdict (None: nothing was fitted)
    settings: ModelSettings | None = None           # the model's integrator and Δt, and who chose them
    moves: dict = field(default_factory=dict)       # fitted constant → its move at Δt/2, in its unit
    runs: int = 0                                   # engine runs the comparison took
    release_fitted: bool = False                    # r0 was added to the fit (not given with --set)
    sign_open: bool = False                         # both signs fit alike (with the same constants)
    left_out: tuple = ()                            # indices of the points left out (sensor drop-outs)

    @property
    def sign_said(self) -> str:
        """Which way the data's axis was taken to point, in words."""
        c = self.coordinate
        if self.sign_open:
            return (f"either way fits alike: with r0 fitted, a reversed axis is the same swing let go on the "
                    f"other side; the model's {c} is compared with the data")
        if self.sign > 0:
            return f"the data's axis points the model's way: the model's {c} is compared with the data"
        way = "down" if c == "y" else "the other way"
        return f"the data's axis points {way}: the model is compared with −{c}"

    @property
    def integrator(self) -> str | None:
        return self.settings.integrator if self.settings else None

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


def coordinate_of(setup, asked: str | None = None) -> str:
    """The coordinate compared: `asked` (--coordinate), else the one the scene plots (vertical: y;
    driven: x)."""
    if asked:
        return asked
    plotted = setup.hooks.view.get("plot", "y")
    return plotted if plotted in AXES else "y"


def _value(setup, name: str, axis: int) -> float:
    """A fitted constant's value as set: r0's component along the compared coordinate (as built,
    where the scene works r0 out)."""
    value = setup.values[name]
    if name == RELEASE and not isinstance(value, tuple):
        return float(setup.build().state.r[0][axis])
    return float(value[axis] if isinstance(value, tuple) else value)


def _check_points(count: int, names) -> None:
    values = len(names) + 2
    need = values + 6
    if count < need:
        what = "the two offsets" if not names else f"{', '.join(names)} and the two offsets"
        raise FitError(f"the data have {count} points, too few to fix {what}: at least {need} are needed")


def compare(setup, t, y, *, integrator=None, coordinate="y", fit=(), sign=None, choose=False, given=(),
            own_step=None, lines=None, progress=None) -> Comparison:
    """The scene against the measured points t (s), y (m): offsets, RMS, and the fitted constants.

    fit       names of constants to fit (lab/names.py); empty compares with the constants as set
    sign      +1 or −1: the data's axis points the model's way or the other (--data-sign); None tries both
    choose    the fit chooses the model's integrator and Δt (neither --integrator nor --set dt given)
    given     the constants the user set (--set): the release is fitted unless it is among them
    own_step  the data are this program's own --csv run, made at this Δt (lab/readers.py)
    lines     each point's line in the file, to name a point left out
    progress  progress(line) about once a second on a fit longer than a second
    Raises FitError (one line) for a comparison or fit that cannot be made.
    """
    t, data = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    if sign not in (None, 1, -1):
        raise FitError(f"--data-sign {sign}: give 1 (the data's axis points the model's way) or -1 (the other way)")
    names = check_names(setup, fit) if fit else []
    names, added = with_release(setup, names, set(given)) if names else ([], False)
    _check_points(len(t), names)
    if names:
        try:
            import scipy.optimize  # noqa: F401 (only the fit needs it)
        except ImportError:
            raise FitError(str(MissingScipy())) from None
    axis = AXES[coordinate]
    first = float(t[0])
    left_out = outlier_rows.gross(t, data)
    kept = np.setdiff1d(np.arange(len(t)), left_out)
    if names:
        return _fit(setup, t, data, kept, first, names=names, added=added, axis=axis, coordinate=coordinate,
                    integrator=integrator, sign=sign, choose=choose, own_step=own_step, progress=progress,
                    lines=lines)
    return _offsets(setup, t, data, kept, first, axis=axis, coordinate=coordinate, integrator=integrator,
                    sign=sign, lines=lines)


def _period(setup, t, y) -> float:
    """The swing's period, s: the data's strongest frequency, else the model's own (declared rates)."""
    found = data_swing.frequencies(t, y)
    if found:
        return 2 * math.pi / found[0]
    omega = float(rates(setup.build().forces, setup.build().state.m).omega[0])
    return 2 * math.pi / omega if omega > 0 else max(float(t[-1] - t[0]), 1e-3)


def _spacing(t) -> float:
    gaps = np.diff(t)
    return float(np.min(gaps)) / 4 if len(gaps) else 0.0


def _slow_dt(setup, dt, t) -> tuple:
    """(Δt, the data's sample interval, a round smaller Δt) where Δt is clearly longer than the
    interval (by more than a thousandth), else ()."""
    interval = float(np.median(np.diff(t)))
    if not dt > 1.001 * interval:
        return ()
    return (dt, interval, f"{10 ** math.floor(math.log10(interval / 10)):g}")


def _slow_dt_note(slow) -> str:
    dt, interval, smaller = slow
    return (f"note: the model's dt = {dt:.3g} s is longer than the data's sample interval {interval:.3g} s, so "
            f"the integrator's own error is in the comparison; a smaller dt (--set dt={smaller}) follows the "
            f"real motion more closely")


def _offsets(setup, t, data, kept, first, *, axis, coordinate, integrator, sign, lines) -> Comparison:
    """The comparison with the constants as set: t_offset and position_offset only (numpy only)."""
    tt, y = t[kept] - first, data[kept]
    runs = Runs(setup, integrator=integrator, axis=axis, spacing=_spacing(tt))
    problem = Problem(runs, tt, y, nonlinear=[], mode="offset")
    period = _period(setup, tt, y)
    problem.reach = 1.1 * period
    _check_length(problem, period, float(setup.values["dt"]))
    still = problem.columns((), 0.0, tau=np.linspace(0.0, max(problem.span, 1.0), 200))[0]
    if np.ptp(still) <= 1e-12 * (1.0 + np.max(np.abs(still))):
        raise FitError(f"the model's {coordinate} does not move in scene {setup.name!r}, so there is nothing "
                       f"to compare; choose the coordinate that moves with --coordinate")
    starts = offsets(problem, (), period=period, sign=sign, longest=MAX_STEPS_PER_RUN * float(setup.values["dt"]))
    by_sign = {start.sign: start for start in starts}
    chosen = sign if sign is not None else (
        -1 if by_sign[-1].cost < SIGN_MARGIN * by_sign[1].cost else 1)
    problem.sign = chosen
    t_offset = offset_only(problem, by_sign[chosen].t_offset)
    fitted = finish(problem, (), t_offset, chosen)
    model = np.full(len(t), np.nan)
    model[kept] = fitted.model
    notes = _left_out_note(t, data, np.setdiff1d(np.arange(len(t)), kept), lines)
    slow = _slow_dt(setup, float(setup.values.get("dt", 0.0)), tt)
    if slow:
        notes.append(_slow_dt_note(slow))
    settings = ModelSettings(integrator=integrator, dt=float(setup.values.get("dt", math.nan)), chosen_by="user")
    return Comparison(t=t[kept], data=y, model=fitted.model, coordinate=coordinate, fitted={},
                      t_offset=Estimate(first + t_offset, fitted.uncertainty("t_offset"), "s"),
                      position_offset=Estimate(fitted.value("position_offset"),
                                               fitted.uncertainty("position_offset"), "m"),
                      setup=setup, notes=notes, sign=chosen, slow_dt=slow, settings=settings, runs=runs.count,
                      left_out=tuple(int(i) for i in np.setdiff1d(np.arange(len(t)), kept)))


def _left_out_note(t, data, rows, lines=None) -> list:
    """A note naming the points left out: each by its line in the file (where known), time and value."""
    if not len(rows):
        return []
    shown = ", ".join((f"line {lines[i]} " if lines is not None else "") + f"(t = {t[i]:.4g} s, {data[i]:.3g} m)"
                      for i in rows[:5])
    more = f" and {len(rows) - 5} more" if len(rows) > 5 else ""
    return [f"note: {len(rows)} point{'s' if len(rows) > 1 else ''} far off the data's swing left out "
            f"(a sensor drop-out?): {shown}{more}"]


def _settings(setup, *, integrator, choose, own_step) -> ModelSettings:
    """Who chooses the model's integrator and Δt (lab/settings.py): the data (this program's own run),
    the fit, or the user (--integrator, --set dt, or the page's menu and slider)."""
    model = setup.build()
    if choose and own_step:
        return ModelSettings(integrator=model.methods(None)[0], dt=float(own_step), chosen_by="data")
    if choose and model.integrators is None:
        return ModelSettings(integrator=best_method(), dt=math.nan, chosen_by="fit")
    return ModelSettings(integrator=model.methods(integrator)[0], dt=float(setup.values["dt"]), chosen_by="user")


def _fit(setup, t, data, kept, first, *, names, added, axis, coordinate, integrator, sign, choose, own_step,
         progress, lines) -> Comparison:
    """The comparison with `names` fitted (see the module's docstring for the steps and their modules)."""
    settings = _settings(setup, integrator=integrator, choose=choose, own_step=own_step)
    tt, y = t[kept] - first, data[kept]
    noise = data_swing.noise(y)
    held = data_swing.held(tt, y, noise)         # where a record that starts with the mass held lets it go
    swing = data_swing.damped(tt, y, start=held)
    period = 2 * math.pi / swing.omega if swing else _period(setup, tt, y)
    runs = Runs(setup, integrator=settings.integrator, axis=axis, spacing=_spacing(tt), progress=progress)
    release = RELEASE in names
    nonlinear = [name for name in names if name != RELEASE]
    as_set = tuple(_value(setup, name, axis) for name in nonlinear)
    start_constants = [as_set]
    if swing and nonlinear:    # the swing's own frequency and decay, then the spectrum's other peaks (a
        # drive's and the free swing's), whose decay is not known: damped at 2 and at 10 % of critical
        others = [omega for omega in data_swing.frequencies(tt[tt >= held], y[tt >= held])
                  if abs(omega - swing.omega) > 0.05 * swing.omega][:1]
        for omega, decay in [(swing.omega, swing.decay)] + [(omega, ratio * omega) for omega in others
                                                             for ratio in (0.02, 0.1)]:
            found = matched(setup, nonlinear, as_set, omega=omega, decay=decay, axis=axis)
            if found and all(not np.allclose(found, other, rtol=0.02) for other in start_constants):
                start_constants.append(found)
    base = {RELEASE: _value(setup, RELEASE, axis)} if release else {}
    step = {RELEASE: max(float(np.ptp(y)) / 100, 1e-4)} if release else {}
    problem = Problem(runs, tt, y, nonlinear=nonlinear, linear=list(base), base=base, step=step, mode="offset")
    problem.reach = 1.1 * period
    scene_dt = float(setup.values["dt"])
    if settings.chosen_by == "fit":
        estimate = min(noise, swing.rms) if swing else noise
        main = start_constants[1] if len(start_constants) > 1 else start_constants[0]   # the swing's own
        chosen = choose_dt(problem, main, order=order_of(settings.integrator, DEFAULT_INTEGRATOR),
                           period=period, noise=estimate, scene_dt=scene_dt)
        settings.dt, settings.error, settings.target = chosen.dt, chosen.error, chosen.target
    problem.dt = settings.dt
    _check_length(problem, period, settings.dt)
    if release:
        mode = linear_mode(problem, start_constants[-1 if len(start_constants) < 2 else 1], RELEASE)
        if mode:
            problem.mode = mode
        else:          # the motion is not linear in the release: least squares fits it with the rest
            problem = problem.copy(nonlinear=[*nonlinear, RELEASE], linear=[], base={}, step={})
            start_constants = [(*constants, base[RELEASE]) for constants in start_constants]
    fitted, sign_open, sign_said = _descend_from_starts(problem, start_constants, period=period, sign=sign,
                                                        held=held)
    problem = fitted.problem
    moves, ratio = _moves(fitted, settings)
    halvings = 0
    while settings.chosen_by == "fit" and ratio > 1 / 3 and halvings < HALVINGS:
        halvings += 1
        settings.dt /= 2
        fitted = _moved(fitted, moves, dt=settings.dt)
        moves, ratio = _moves(fitted, settings)
    wild = outlier_rows.in_residual(fitted.residual)
    if len(wild):
        keep = np.setdiff1d(np.arange(len(fitted.residual)), wild)
        kept = kept[keep]
        fitted = _again(fitted, keep=keep)
        moves, ratio = _moves(fitted, settings)
    constants = [name for name in fitted.names if name in names]
    sigma = {name: fitted.uncertainty(name) for name in constants}
    move_said = {name: moves[name] for name in constants} if settings.chosen_by != "data" else {}
    advice, smaller_dt = _advice(settings, moves, sigma)
    values = {name: fitted.value(name) for name in constants}
    trust = judge(residual=fitted.residual, data=fitted.problem.y, model=fitted.model,
                  samples_per_period=_samples_per_period(setup, values, axis, fitted.problem.t),
                  at_edge=fitted.at_edge, sign_open=sign_said, moves=move_said, sigma=sigma, dt=settings.dt,
                  advice=advice, smaller_dt=smaller_dt, settled=fitted.settled, runs=runs.count)
    final = with_fitted(setup, values, axis).with_values(dt=settings.dt)
    left = np.setdiff1d(np.arange(len(t)), kept)
    notes = _left_out_note(t, data, left, lines) + [_settings_note(settings, noise=_noise_of(fitted),
                                                                   ratio=ratio)]
    estimates = {name: Estimate(values[name], sigma[name], setup.constants[name].unit)
                 for name in [*[n for n in names if n != RELEASE], *([RELEASE] if release else [])]}
    return Comparison(t=t[kept], data=data[kept], model=fitted.model, coordinate=coordinate, fitted=estimates,
                      t_offset=Estimate(first + fitted.value("t_offset"), fitted.uncertainty("t_offset"), "s"),
                      position_offset=Estimate(fitted.value("position_offset"),
                                               fitted.uncertainty("position_offset"), "m"),
                      setup=final, notes=notes, sign=fitted.sign, slow_dt=_slow_dt(setup, settings.dt, tt),
                      trust=trust, settings=settings, moves={name: moves[name] for name in constants},
                      runs=runs.count, release_fitted=added, sign_open=sign_open,
                      left_out=tuple(int(i) for i in left))


def _samples_per_period(setup, values, axis, t) -> float:
    """How many of the data's samples the fitted spring's natural period spans (declared rates)."""
    model = with_fitted(setup, values, axis).build()
    omega = float(rates(model.forces, model.state.m).omega[0])
    interval = float(np.median(np.diff(t)))
    return 2 * math.pi / (omega * interval) if omega > 0 and interval > 0 else math.inf


def _check_length(problem, period, dt) -> None:
    """The data's span (and a period before them) must be a run the engine may take (one line if not,
    whose suggested Δt is one this check accepts)."""
    needed = 1.05 * problem.span + 1.1 * period + 0.05 * problem.span
    if needed / dt > MAX_STEPS_PER_RUN:
        raise FitError(too_long(needed, dt, f"the data span {problem.span:.4g} s: a run of the model over "
                                            f"them and a period before is"))


def _descend_from_starts(problem, start_constants, *, period, sign, held=0.0):
    """(Fitted, sign_open, why the sign is open or ""): least squares from the best start of each
    sign not clearly worse than the other, never ending worse than any start (lab/start.py)."""
    tried = []
    longest = MAX_STEPS_PER_RUN * problem.dt
    for constants in start_constants:
        try:
            found = offsets(problem, constants, period=period, sign=sign, longest=longest, held=held)
        except FitError:     # a start the model cannot run at this Δt (it blows up): not a start
            continue
        for start in found:
            residual = problem.solve(constants, start.t_offset, start.sign)[0]
            tried.append((float(residual @ residual), start))
    if not tried:
        raise FitError(f"the model blew up from every start the fit tried ({constants_said(problem.runs.setup)}); "
                       f"set a smaller dt, or the constants not fitted with --set")
    tried.sort(key=lambda pair: pair[0])
    lowest = tried[0][0]
    by_sign = {}
    for cost, start in tried:
        by_sign.setdefault(start.sign, (cost, start))
    chosen = [by_sign[way] for way in sorted(by_sign, key=lambda way: by_sign[way][0])
              if by_sign[way][0] <= lowest / SIGN_MARGIN or by_sign[way][0] == lowest]
    if problem.mode == "scale":
        chosen = chosen[:1]
    results = {}
    for cost, start in chosen:
        if results:      # the other way of the axis: only where its start is as low as the fit's end
            done = min(found.cost for found in results.values())
            points = len(problem.t)
            if cost > done + SIGN_TIE * done / max(points - len(problem.nonlinear) - 3, 1):
                continue
        way = problem.copy(sign=start.sign)
        # two runs a candidate where the release does not only scale the swing: a budget that allows it
        budget = max(BUDGET * (1 if problem.mode == "scale" else 2) - problem.runs.count - 6, 24)
        constants, t_offset, found, converged = descend(way, start.constants, start.t_offset, budget=budget)
        best = min([(found, constants, t_offset)] +
                   [(c, s.constants, s.t_offset) for c, s in tried if s.sign == start.sign])
        results[start.sign] = _finish(way, best[1], best[2], start.sign)
        results[start.sign].settled = converged or best[0] < found
    order = sorted(results, key=lambda way: results[way].cost)
    fitted = results[order[0]]
    if problem.mode == "scale":
        return fitted, sign is None, ""
    if len(order) < 2 or sign is not None:
        return fitted, False, ""
    other = results[order[1]]
    s2 = fitted.cost / max(len(fitted.residual) - len(fitted.names), 1)
    if other.cost - fitted.cost > SIGN_TIE * s2:
        return fitted, False, ""
    apart = [name for name in fitted.problem.nonlinear
             if abs(fitted.value(name) - other.value(name)) > max(fitted.uncertainty(name), other.uncertainty(name))]
    if not apart:
        plus = results.get(1, fitted)
        return plus, True, ""
    differ = ", ".join(f"{name} = {fitted.value(name):.4g} or {other.value(name):.4g}" for name in apart)
    return fitted, False, f"both ways of the data's axis fit alike, with {differ} (--data-sign says which)"


def _finish(problem, constants, t_offset, sign) -> Fitted:
    """finish(), and where the release turns out not to only scale the swing, the fit again with two
    runs a candidate."""
    try:
        return finish(problem, constants, t_offset, sign)
    except _NotScale:
        lines = problem.copy(mode="lines")
        constants, t_offset, _, _ = descend(lines, constants, t_offset, budget=12)
        return finish(lines, constants, t_offset, sign)


def _again(fitted, *, dt=None, keep=None) -> Fitted:
    """The fit again from where it ended: at a new Δt, or on the points `keep` only."""
    problem = fitted.problem
    changes = {}
    if dt is not None:
        changes["dt"] = dt
    if keep is not None:
        changes.update(t=problem.t[keep], y=problem.y[keep])
    problem = problem.copy(**changes)
    p = len(problem.nonlinear)
    constants, t_offset, settled = tuple(fitted.values[:p]), fitted.value("t_offset"), True
    if problem.nonlinear:
        constants, t_offset, _, settled = descend(problem, constants, t_offset, budget=12)
    again = _finish(problem, constants, t_offset, fitted.sign)
    again.settled = settled and fitted.settled
    return again


def _moved(fitted, moves, *, dt) -> Fitted:
    """The fit at Δt/2 from the Gauss-Newton step moves_at_half_dt already took there (the fit's valley
    hardly moves: no new least squares), its values and uncertainties worked out again at that Δt."""
    problem = fitted.problem.copy(dt=dt)
    p = len(problem.nonlinear)
    constants = tuple(fitted.values[j] + moves[name] for j, name in enumerate(fitted.names[:p]))
    moved = _finish(problem, constants, fitted.value("t_offset") + moves["t_offset"], fitted.sign)
    moved.settled = fitted.settled
    return moved


def _moves(fitted, settings):
    """Each value's move at Δt/2, and the largest move of a fitted constant in its σ (0 where the data
    are the program's own run: its model error is in the data too; NaN where a run at Δt/2 would be
    longer than a run may be)."""
    if settings.chosen_by == "data":
        return {name: 0.0 for name in fitted.names}, 0.0
    if (1.05 * fitted.problem.span + fitted.problem.reach) / (settings.dt / 2) > MAX_STEPS_PER_RUN:
        return {name: math.nan for name in fitted.names}, math.nan
    moves = moves_at_half_dt(fitted, settings.dt)
    ratios = [abs(moves[name]) / fitted.uncertainty(name) for name in fitted.problem.nonlinear + fitted.problem.linear
              if fitted.uncertainty(name) > 0]
    return moves, max(ratios, default=0.0)


def _noise_of(fitted) -> float:
    return float(np.sqrt(np.mean(fitted.residual ** 2)))


def _advice(settings, moves, sigma) -> tuple[str, float]:
    """(what the command line would set instead, a Δt that would do, s), for a model whose Δt moves
    the answer by more than σ."""
    ratios = [abs(moves[name]) / sigma[name] for name in sigma if sigma[name] > 0 and math.isfinite(moves[name])]
    worst = max(ratios, default=0.0)
    if worst <= 1:
        return "", math.nan
    smaller = suggest_dt(settings.dt, worst, order_of(settings.integrator, DEFAULT_INTEGRATOR))
    if settings.chosen_by == "fit":
        return f"the finest Δt tried was {settings.dt:.3g} s", smaller
    return (f"Δt = {smaller:.3g} s or the rk4 method would do; leave out --set dt and --integrator and the "
            f"fit chooses", smaller)


def _length(metres: float) -> str:
    if 1e-4 <= metres < 1.0:
        return f"{metres * 1000:.2g} mm"
    if 1e-7 <= metres < 1e-4:
        return f"{metres * 1e6:.2g} µm"
    return f"{metres:.2g} m"


def _settings_note(settings, *, noise, ratio) -> str:
    """One line saying which integrator and Δt the fit's model ran with, and why they can be trusted."""
    method = settings.integrator or "the scene's integrator"
    if settings.chosen_by == "data":
        return (f"note: the data are this program's own run at dt = {settings.dt:.6g} s, so the model runs the "
                f"same way ({method}); --integrator or --set dt chooses another")
    moved = (f"halving it moves no fitted value by more than {ratio:.2g}σ" if ratio <= 1 else
             f"halving it moves a fitted value by {ratio:.2g}σ" if ratio > 1 else
             "a run at half that Δt would be too long to check how far halving it moves the values")
    if settings.chosen_by == "fit":
        return (f"note: the fit chose {method} at dt = {settings.dt:.3g} s: its own error, about "
                f"{_length(settings.error)}, is under a tenth of the data's noise ({_length(noise)}); {moved}")
    return f"note: the model runs {method} at dt = {settings.dt:.3g} s, as set; {moved}"

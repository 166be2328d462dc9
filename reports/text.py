"""The command line's reports as text: the final state of a run, a scene's constants and presets,
and the list of scenes.

The final state is written in Matter & Interactions vector notation,

    t = 0.2 s
    r = < 0, -1.73088, 0 > m
    p = < 0, -15.288, 0 > kg·m/s

with the energy and, where a closed form exists, the exact answer and the error of the iteration,
and the period measured from the motion beside the formula's (reports/periods.py).
"""
from __future__ import annotations

import math

import numpy as np

from physics.forces import net_force
from physics.stability import rates
from physics.state import velocity
from export.step_update import number, vector
from scenes import ConstantError, Setup, catalog, format_value

from .forces_report import forces_line
from .headless import Result
from .periods import period_text, periods


def plural(count: int, noun: str) -> str:
    return f"{count} {noun}{'' if count == 1 else 's'}"


def final_report(result: Result) -> str:
    """The final time and state in M&I vector notation, energy, and the exact answer where known."""
    traj, model = result.trajectory, result.model
    t, m = traj.t[-1], traj.m
    lines = [f"{result.setup.name}: {plural(result.steps, 'step')} of dt = {number(model.dt)} s "
             f"with {result.integrator}",
             f"t = {number(t)} s"]
    lines += [f"added force {name}: F = {text} N" for name, text in result.setup.written]
    extra_text = result.setup.hooks.extra_text  # a scene's own results first (resonance's amplitude
    if extra_text is not None:                  # table), then each of its masses
        lines.append(extra_text(result))
    reports = periods(result)
    lines += _masses(result, reports)
    if len(m) == 1 and result.exact_note():
        lines.append(f"exact: none at t = {number(t)} s: {result.exact_note()}")
    elif len(m) == 1 and model.no_closed_form:
        lines.append(f"exact: none ({model.no_closed_form})")
    energy = traj.energy_at([0, -1])                # the start's and the end's alone
    if energy is not None:
        e = {key: values[-1] for key, values in energy.items()}
        lines.append(f"energy: K = {number(e['K'])} J, U = {number(e['U'])} J, E = {number(e['E'])} J, "
                     f"W_nc = {number(e['W_nc'])} J, E − W_nc = {number(e['E_minus_W_nc'])} J "
                     f"({number(energy['E_minus_W_nc'][0])} J at the start)")
    if len(m) == 1:
        lines.append(f"period: {period_text(reports[0])}")
    return "\n".join(lines)


def _masses(result: Result, reports) -> list[str]:
    """Each mass's r, v, p and F_net at the final time, its exact answer and error where known,
    and (several masses) its period."""
    traj, model = result.trajectory, result.model
    t, r, p, m = traj.t[-1], traj.r[-1], traj.p[-1], traj.m
    v = velocity(p, m)
    F_net = net_force(model.forces, t, r, v, m)
    exact, notes = result.exact(), result.exact_notes()
    single = len(m) == 1
    indent = "" if single else "  "
    lines = []
    for i, label in enumerate(result.labels):
        if not single:
            lines.append(f"{label}, m = {number(m[i])} kg:")
        lines += [f"{indent}r = {vector(r[i], 'm')}",
                  f"{indent}v = {vector(v[i], 'm/s')}",
                  f"{indent}p = {vector(p[i], 'kg·m/s')}",
                  f"{indent}F_net = {vector(F_net[i], 'N')} (at t = {number(t)} s)"]
        if exact is not None and np.all(np.isfinite(exact[0][i])):
            r_exact, v_exact = exact[0][i], exact[1][i]
            lines += [f"{indent}exact: r = {vector(r_exact, 'm')}, v = {vector(v_exact, 'm/s')}",
                      f"{indent}error: |r − r_exact| = {number(np.linalg.norm(r[i] - r_exact), 4)} m, "
                      f"|v − v_exact| = {number(np.linalg.norm(v[i] - v_exact), 4)} m/s"]
        elif notes[i] and not single:
            lines.append(f"{indent}exact: none at t = {number(t)} s: {notes[i]}")
        elif model.no_closed_form_each and model.no_closed_form_each[i] and not single:
            lines.append(f"{indent}exact: none ({model.no_closed_form_each[i]})")
        if not single:
            lines.append(f"{indent}period: {period_text(reports[i])}")
    return lines


def constants_report(setup: Setup) -> str:
    """Each constant of a configured scene: `k = 40 N/m   spring constant (stiffness)`, every force's
    it accepts among them, on or off; then ω0 and the forces on and off (reports/forces_report.py)."""
    rows = [(f"{name} = {format_value(setup.values[name], constant.unit)}", constant.meaning)
            for name, constant in setup.constants.items()]
    width = max(len(left) for left, _ in rows)
    lines = [f"{left:<{width}}   {meaning}" for left, meaning in rows]
    try:
        model = setup.build()
    except (ValueError, ConstantError):   # the physics refuses these constants: the run says why
        model = None
    omega0, dt = natural_frequency(model), setup.values.get("dt")
    if omega0 is not None:                      # worked out from the values in use
        lines.append(f"so: ω0 = √(k/m) = {number(omega0, 4)} rad/s, T = 2π/ω0 = {number(2 * math.pi / omega0, 4)} s"
                     + (f", ω0·dt = {number(omega0 * dt, 4)}" if isinstance(dt, (int, float)) else ""))
    if model is not None:
        lines.append(forces_line(setup, model))
    return "\n".join(lines)


def natural_frequency(model) -> float | None:
    """ω0 = √(k/m) in rad/s of the model's masses, from the stiffness the forces declare
    (physics.stability.rates), where every mass has the same one; None where they differ, where no
    spring holds them, or where there is no model (the physics refused its constants)."""
    if model is None:
        return None
    omega = rates(model.forces, model.state.m).omega
    if not np.all(np.isfinite(omega)) or np.any(omega <= 0) or np.ptp(omega) > 1e-12 * omega.max():
        return None
    return float(omega[0])


def presets_report(setup: Setup) -> str:
    """The scene's presets with what each changes, for --constants: `critical damping   b = 2√(mk) = 40 kg/s`."""
    options = catalog.presets(setup)
    if not options:
        return "presets: none for this scene"
    width = max(len(label) for label, _ in options)
    lines = ["presets (--preset NAME):"]
    named = dict(catalog.presets(setup, whole=False))   # a scenario's own changes; it sets its whole case
    for label, overrides in options:
        changes = []
        for name, value in named[label].items():
            unit = setup.constants[name].unit
            if value is None:  # critical damping, from the m and k set now
                value = catalog.resolve({**setup.values, name: None})[name]
                changes.append(f"{name} = 2√(mk) = {format_value(value, unit)}")
            else:
                changes.append(f"{name} = {format_value(value, unit)}")
        rest = "; m, k and the rest of its case from the scene file" if len(overrides) > len(named[label]) else ""
        lines.append(f"  {label:<{width}}   {', '.join(changes)}{rest}")
    return "\n".join(lines)


def list_scenes() -> tuple[str, list[str]]:
    """Each scene with its one-line description, and its numbered scenarios if it has any; and
    what is wrong with each scene file that is not valid Python or was left out (read from the
    files as text: no scene runs)."""
    names = list(catalog.SCENE_NAMES)
    width = max(len(name) for name in names)
    lines, problems = [], list(catalog.SKIPPED.values())
    for name in names:
        try:
            summary, labels = catalog.describe(name)
        except ConstantError as problem:
            problems.append(str(problem))
            continue
        lines.append(f"{name:<{width}}  {summary}")
        for n, label in enumerate(labels, start=1):
            lines.append(f"{'':<{width}}    --scenario {n}: {label}")
    return "\n".join(lines), problems

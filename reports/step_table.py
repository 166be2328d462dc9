"""The step table (`--steps N`): the first few iterations, each as a student works it by hand,

    F_net,  p_f = p_i + F_net Δt,  v_f = p_f / m,  r_f = r_i + v_f Δt

with the numbers written as the page's Step read-out writes them (export/step_update.py).
"""
from __future__ import annotations

from typing import Optional

from physics.integrators import INTEGRATORS, describe
from physics.recording import every, trajectory
from export.numbers import clean_time
from export.step_update import cleaned, number, update_force, vector
from scenes import Model, Setup

from .headless import TooManySteps
from .json_report import integrator_json
from .text import plural

MAX_TABLE_ROWS = 10_000        # rows of the step table (steps × masses)


def step_table(setup: Setup, *, model: Optional[Model] = None, integrator: Optional[str] = None,
               steps: int) -> dict:
    """The first `steps` iterations: for each step and mass, t_f, F_net, p_f, v_f and r_f.

    F_net is the force the method used for its momentum update, so p_f = p_i + F_net Δt holds on
    every row: for euler-cromer (the page) and euler it is F(t_i, r_i, v_i), for the other methods
    the average force (p_f − p_i)/Δt of the step.
    """
    model = model if model is not None else setup.build()
    rows_asked = steps * model.state.count
    if rows_asked > MAX_TABLE_ROWS:
        rows = f" of {model.state.count} masses, {rows_asked:,} rows," if model.state.count > 1 else ""
        raise TooManySteps(
            f"--steps {steps:,}{rows} is more than the {MAX_TABLE_ROWS:,} rows the step table shows "
            f"(it is for checking by hand); use --headless --csv FILE for every step of a long run")
    engine = model.simulation(integrator)
    dt = model.dt
    traj = trajectory(engine, engine.advance(steps, record=every(1)), with_energy=False)
    v = traj.v
    rows = []
    for n in range(1, len(traj.t)):
        F_net = update_force(model.forces, engine.methods, t_i=traj.t[n - 1], r_i=traj.r[n - 1],
                             p_i=traj.p[n - 1], p_f=traj.p[n], m=traj.m, dt=dt)
        for i, label in enumerate(model.labels):
            rows.append({"step": n, "body": label, "t": clean_time(traj.t[n], dt), "F_net": cleaned(F_net[i].tolist()),
                         "p_f": cleaned(traj.p[n, i].tolist()), "v_f": cleaned(v[n, i].tolist()),
                         "r_f": cleaned(traj.r[n, i].tolist())})
    uniform = len(set(engine.methods)) == 1
    return {"scene": setup.name, "integrator": integrator_json(engine.methods),
            "dt": float(dt), "m": cleaned(traj.m.tolist()),
            "start": {"t": clean_time(traj.t[0], dt), "r": cleaned(traj.r[0].tolist()),
                      "p": cleaned(traj.p[0].tolist()), "v": cleaned(v[0].tolist())},
            "units": {"t": "s", "F_net": "N", "p_f": "kg·m/s", "v_f": "m/s", "r_f": "m"},
            "rule": (INTEGRATORS[engine.methods[0]].rule if uniform else
                     "F_net = (p_f − p_i)/Δt, the average force each mass's method used"),
            "rows": rows}


def method_name(integrator) -> str:
    """The JSON "integrator" (a name or a list of names) in words."""
    return describe([integrator] if isinstance(integrator, str) else integrator)


def format_step_table(table: dict) -> str:
    """The step table as aligned text with units in the header, vectors in < > notation."""
    labels = list(dict.fromkeys(row["body"] for row in table["rows"]))
    multi = len(labels) > 1
    lines = [f"{table['scene']}: first {plural(len({row['step'] for row in table['rows']}), 'step')} of "
             f"Δt = {number(table['dt'])} s with {method_name(table['integrator'])}",
             "each step: " + table["rule"],
             "t is the time at the end of the step, when p_f, v_f and r_f hold"]
    start = table["start"]
    for i, label in enumerate(labels or ["mass"]):
        name = f", {label}" if multi else ""
        lines.append(f"start{name}, m = {number(table['m'][i])} kg: t = {number(start['t'])} s, "
                     f"r = {vector(start['r'][i], 'm')}, p = {vector(start['p'][i], 'kg·m/s')}, "
                     f"v = {vector(start['v'][i], 'm/s')}")
    header = ["step"] + (["body"] if multi else []) + \
        [f"{key} ({unit})" for key, unit in table["units"].items()]
    body = [[str(row["step"])] + ([row["body"]] if multi else []) + [number(row["t"])] +
            [vector(row[key]) for key in ("F_net", "p_f", "v_f", "r_f")] for row in table["rows"]]
    widths = [max(len(line[c]) for line in [header] + body) for c in range(len(header))]
    for line in [header] + body:
        lines.append("  ".join(cell.ljust(width) for cell, width in zip(line, widths)).rstrip())
    return "\n".join(lines)

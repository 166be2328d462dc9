"""What the offline page's tools need from Python, as data: the period and the equilibrium of the
file's own set-up, and the colours, names and sizes the local page's tools draw with.

The page's script (export/offline_tools.js) draws the energy graph, phase space, energy bars, the
error read-out, a Step as vector addition and the Measure panel's lines from the numbers the
program reports (export/program_page.py). What cannot be worked out in the program the page runs
is worked out here, once, when the file is written, for its own set-up:

- the period, measured from the engine's run over the page's graph window (physics/period.py:
  upward crossings of the equilibrium), beside the formula's 2π/ω_d;
- each mass's equilibrium (physics/equilibrium.py: F_net = 0 by Newton's method).

The run that measures the period is the one costly step of writing a page. It is held to what a
headless run may take (physics/run_cost.py's check_cost, the command line's own limit) and to
PERIOD_SECONDS of it: past that the period is measured over a shorter window, and where not even
two cycles fit, the page says why there is none.
"""
from __future__ import annotations

import numpy as np

from physics.energy import rest_potential
from physics.equilibrium import equilibrium
from physics.period import formula_period, measured_period, record_spacing, why_no_period
from physics.recording import steps_to_reach
from physics.run_cost import RunTooLong, check_cost
from physics.simulate import BlowUpError, every, trajectory

from .arrows import STEP_APART, STEP_ASIDE
from .palette import (ARROW_COLOURS, BLACK, BLUE, BLUISH_GREEN, ENERGY_COLOURS, REDDISH_PURPLE, SKY_BLUE, VERMILION, energy_label,
                      mass_colours)
from .step_update import number

STEP_MASSES = 4                # masses whose Step is written out, as on the local page (browser/view.py)
PERIOD_SECONDS = 2.0           # s of computing the period's run may take (at most the command line's limit)
SAMPLE_EVERY = 0.05            # s of simulated time between the graphs' points, as on the local page
ENERGY_KEYS = ("K", "U", "E", "E_minus_W_nc")
LINE_COLOURS = {"natural": SKY_BLUE, "equilibrium": BLUISH_GREEN, "marker": VERMILION}   # as the local page's
LINE_HALF_LENGTH = 2.6         # × the masses' radius: each line reaches this far either side of its mass
# the page's layout: two columns (the view and its controls, the graphs) from this window width, px
TWO_COLUMNS_FROM, VIEW_SHARE, LEGEND_PX = 900, 0.55, 30
TICK_ROOM = 36                 # px right of a graph: half its last tick label (22 px text in projector mode)


def measured(model, *, view: dict, integrator: str | None) -> dict:
    """The period and the equilibrium of the file's own set-up, worked out by the physics the local
    page uses (physics/period.py, physics/equilibrium.py): each mass's equilibrium, and a line per
    mass (at most STEP_MASSES) giving its period measured over the page's window (or as much of it
    as PERIOD_SECONDS of computing reach) beside 2π/ω_d, or why there is none."""
    centre = equilibrium(model.forces, model.state)
    axis = "xyz".index(view["plot"][0])
    covered = False if model.exact is None else np.isfinite(model.exact_where_valid([0.0])[0][0]).all(axis=-1)
    formula, formula_why = formula_period(model.forces, model.state, closed_form=covered)
    wanted = end = max(view["window"], model.until)
    every_s = record_spacing(model.forces, model.state.m, model.dt)   # s between samples
    traj, why = None, ""
    if centre is None or every_s is None:
        why = "nothing pulls the mass back to an equilibrium, so the motion does not repeat"
    else:
        engine = model.simulation(integrator)
        try:
            end = _affordable(engine, end)
            samples = engine.advance(steps_to_reach(end - model.state.t, model.dt),
                                     record=every(max(1, int(every_s / model.dt))))
            traj = trajectory(engine, samples, with_energy=False)
        except RunTooLong as problem:
            why = f"not measured when the file was written: {problem.worded('until')}"
        except BlowUpError as problem:
            why = f"the run blew up ({problem})"
    shortened = (f" (measured over {number(end)} s, not {number(wanted)} s: at dt = {number(model.dt)} s a longer "
                 f"run would take more than {PERIOD_SECONDS:g} s of computing when the file was written)"
                 if traj is not None and end < wanted else "")
    lines = []
    for i in range(min(model.state.count, STEP_MASSES)):
        head = f"{model.labels[i]}: " if model.state.count > 1 else ""
        if traj is not None:
            x = traj.r[:, i, axis]
            found = measured_period(traj.t, x, centre=float(centre[i, axis]))
            said = (f"T = {number(found.measured)} ± {number(found.spread, 2)} s over {found.cycles} cycles"
                    if found is not None else "no period: " + why_no_period(traj.t, x, centre=float(centre[i, axis])))
            said += shortened
        else:
            said = "no period: " + why
        if formula is not None and np.isfinite(formula[i]):
            said += f"; 2π/ω_d = {number(formula[i])} s"
        lines.append(head + said)
    return {"equilibrium": None if centre is None else centre.tolist(), "axis": axis,
            "period": lines, "window": end, "formula_note": formula_why if formula is None else ""}


def _affordable(engine, end: float) -> float:
    """The end of the period's run: `end`, or the latest t that PERIOD_SECONDS of computing reach
    (check_cost's suggestion, from the engine's own measured cost). RunTooLong where not even
    that is a run the command line would start."""
    try:
        check_cost(engine, until=end, limit=PERIOD_SECONDS)
        return end
    except RunTooLong as problem:
        if problem.longest is None:
            check_cost(engine, until=end)          # the command line's own limit, in its words
            raise
        return problem.longest


def tools_data(model, *, view: dict, scales, written_model) -> dict:
    """The colours, names and sizes the page's tools draw with (as the local page's: browser/graphs.py,
    energy_bars.py, reference_lines.py, arrows3d.py), for the page's script (offline_tools.js)."""
    axis = "xyz".index(view["plot"][0])
    from_rest = rest_potential(model.state, model.forces) is not None
    anchors = np.broadcast_to(model.anchors, model.state.r.shape)
    offsets = model.state.r - anchors
    lengths = np.linalg.norm(offsets, axis=1)
    natural = None if not np.all(lengths > 0) else [
        {"anchor": [float(c) for c in a], "direction": [float(c) for c in d / size]}
        for a, d, size in zip(anchors, offsets, lengths)]
    taken = [force.LABEL for force in written_model.forces if not force.conservative]
    return {
        "axis": axis, "axis_name": "xyz"[axis], "sample_every": SAMPLE_EVERY,
        "colours": [list(c) for c in mass_colours(model, view)],
        "exact": bool(view["exact"]) and model.exact is not None and len(view["plot"]) == 1,
        "energy": {"keys": list(ENERGY_KEYS), "colours": {key: list(ENERGY_COLOURS[key]) for key in ENERGY_KEYS},
                   "labels": {key: energy_label(key, from_rest=from_rest) for key in ENERGY_KEYS},
                   "from_rest": from_rest, "per_mass": model.integrators is not None},
        "bars": {"K": list(VERMILION), "U": [list(BLUE), list(SKY_BLUE), list(BLUISH_GREEN)],
                 "taken": list(REDDISH_PURPLE), "total": list(BLACK), "taken_by": ", ".join(taken) or "none"},
        "step": {"p_unit": scales.p_unit, "aside": STEP_ASIDE, "apart": STEP_APART,
                 "colours": {kind: list(ARROW_COLOURS[kind]) for kind in ("p_i", "F_net", "p")}},
        "lines": {"colours": {kind: list(c) for kind, c in LINE_COLOURS.items()}, "half_length": LINE_HALF_LENGTH,
                  "natural": natural},
        "two_columns_from": TWO_COLUMNS_FROM, "view_share": VIEW_SHARE, "legend_px": LEGEND_PX,
        "tick_room": TICK_ROOM,
    }

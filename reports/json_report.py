"""A headless run as one JSON object (`--headless --json`), and the strict JSON every report prints.

Numbers carry 15 significant digits (export/numbers.py's clean): −7.800000000000001 is −7.8. A
number with no finite value is null, with a line in "notes" naming the place, so no reader takes
an overflow for an answer. Both passes work on whole arrays of numbers at once, so a run of 10⁴
masses writes its JSON in a fraction of a second.
"""
from __future__ import annotations

import json
from typing import Optional

import numpy as np

from physics.exact import lengths
from physics.forces import net_force
from physics.state import velocity
from export.number_blocks import clean_array, float_block
from export.numbers import clean_time
from export.step_update import cleaned

from .headless import Result
from .periods import period_json, periods

UNITS = {"t": "s", "dt": "s", "r": "m", "v": "m/s", "p": "kg·m/s", "F_net": "N", "energy": "J",
         "exact_valid_until": "s"}


def integrator_json(methods):
    """The JSON key "integrator": one name when every mass uses it, else the list of names per mass."""
    return methods[0] if len(set(methods)) == 1 else list(methods)


def with_warning(out: dict, warning: Optional[str]) -> dict:
    """The JSON `out` with the run's warning (headless.stability_warning) added to its "notes" list."""
    if warning:
        out.setdefault("notes", []).append(warning.removeprefix("warning: "))
    return out


def as_json(result: Result) -> dict:
    """One JSON-ready dict: t, steps, dt, integrator, r, p, v (single mass: 3 numbers each), and more.

    Multi-mass scenes give r, p, v as one 3-vector per mass and add "bodies". "exact" holds the
    closed form at the final time and the size of the error, where a closed form exists. Where
    it stopped holding before the final time, "exact" is left out and "exact_note" says why, with
    "exact_valid_until" the time it stopped holding, s (null, with a line in "notes", where it
    holds to the end or there is no closed form). Where a force present has no closed form
    (friction, drag), "exact" is null and that line names the force: "no closed form with drag".
    F_net is the net force at the final time. In a row each mass is judged on its own: a body
    whose closed form stopped holding has no "exact" but its own "exact_note" and
    "exact_valid_until", and the top-level ones count such masses and give the first time.
    "period" is the period measured from the motion and the formula's (reports/periods.py), per
    body in a row. "forces_added" lists the forces --force wrote (name, force as written, unit N). A scene may add its own keys with a function extra_json(result) -> dict
    (scenes/_hooks.py).
    """
    traj, model, setup = result.trajectory, result.model, result.setup
    single = len(traj.m) == 1
    state = _final_state(result)
    pick = (lambda a: a[0]) if single else (lambda a: a)
    out = {
        "scene": setup.name,
        "t": float(traj.t[-1]),
        "steps": result.steps,
        "dt": float(model.dt),
        "integrator": integrator_json(result.methods),
        **{key: pick(state[key]) for key in ("r", "p", "v", "F_net")},
    }
    entries = _exact_entries(result)
    if single and (entries[0] is not None or model.no_closed_form):
        out["exact"] = entries[0]          # null where a force present has no closed form
    _exact_validity(out, result)
    bodies = None if single else _bodies(result, state, entries)   # cleaned already, array by array
    if bodies is not None:
        out["bodies"] = bodies
    final_energy = traj.energy_at([-1])            # the last sample's alone, not the whole run's
    if final_energy is not None:
        out["energy"] = {key: float(values[0]) for key, values in final_energy.items()}
    _periods(out, result)
    out["constants"] = {name: {"value": _plain(setup.values[name]), "unit": c.unit, "meaning": c.meaning}
                        for name, c in setup.constants.items()}
    if setup.written:    # --force: each added force as written (its value is in N)
        out["forces_added"] = [{"name": name, "force": text, "unit": "N"} for name, text in setup.written]
    out["units"] = {**UNITS, "period": "s"} if "period" in out else UNITS
    # to 15 digits, all but what is so already: the final state and the bodies, array by array
    out = {key: value if key in _CLEANED else cleaned(value) for key, value in out.items()}
    if setup.hooks.extra_json is not None:  # a scene's own results, e.g. a resonance curve
        out.update(cleaned(setup.hooks.extra_json(result)))
    out["t"] = clean_time(traj.t[-1], model.dt)
    return out


_CLEANED = ("r", "p", "v", "F_net", "bodies")


def _periods(out: dict, result: Result) -> None:
    """"period": {"measured", "spread", "cycles", "formula"} (s, s, count, s or null) for one
    mass, null with a note where the motion gives none; several masses: each body has its own
    "period", and "period_note" where it is null or has no formula."""
    reports = periods(result)
    if len(reports) == 1:
        out["period"] = period_json(reports[0])
        if out["period"] is None:
            out.setdefault("notes", []).append(f"period: null, {reports[0].measured_note}")
        elif reports[0].formula is None:
            out.setdefault("notes", []).append(f"period.formula: null, {reports[0].formula_note}")
        return
    for body, report in zip(out["bodies"], reports):
        body["period"] = None if period_json(report) is None else cleaned(period_json(report))
        note = report.measured_note if report.measured is None else report.formula_note if report.formula is None else ""
        if note:
            body["period_note"] = note   # the keys as_json's own steps give to 15 digits already


def _final_state(result: Result) -> dict:
    """r, p, v and F_net at the final time, each a list with one 3-vector per mass, to 15 digits."""
    traj = result.trajectory
    r, p, m = traj.r[-1], traj.p[-1], traj.m
    v = velocity(p, m)
    F_net = net_force(result.model.forces, traj.t[-1], r, v, m)   # at the final time, as --headless prints it
    return {key: clean_array(value).tolist() for key, value in (("r", r), ("p", p), ("v", v), ("F_net", F_net))}


def _exact_validity(out: dict, result: Result) -> None:
    """"exact_note" and "exact_valid_until" where the closed form stopped holding, else a null
    "exact_valid_until" (every key of "units" is present) with a note saying why."""
    if result.exact_note():
        out["exact_note"] = result.exact_note()
        out["exact_valid_until"] = result.exact_valid_until()
    else:
        out["exact_valid_until"] = None
        model = result.model
        out.setdefault("notes", []).append(
            "exact_valid_until: null, " + ("the closed form holds up to the final time" if model.exact is not None
                                           else model.no_closed_form or "this scene has no closed form"))


def _bodies(result: Result, state: dict, entries: list) -> list[dict]:
    """One entry per mass of a row: its label, m, r, p, v, F_net, and its exact answer or why not."""
    m = clean_array(result.trajectory.m).tolist()
    notes, valid_until = result.exact_notes(), clean_array(result.exact_valid_until_each()).tolist()
    r, p, v, F_net = (state[key] for key in ("r", "p", "v", "F_net"))
    bodies = [{"label": label, "m": m[i], "r": r[i], "p": p[i], "v": v[i], "F_net": F_net[i]}
              for i, label in enumerate(result.labels)]
    reasons = result.model.no_closed_form_each or ("",) * len(bodies)
    for body, entry, note, until, reason in zip(bodies, entries, notes, valid_until, reasons):
        if entry is not None:
            body["exact"] = entry
        elif reason:              # a force on this mass has no closed form: null, and which
            body.update(exact=None, exact_note=reason, exact_valid_until=None)
        if note:
            body.update(exact_note=note, exact_valid_until=until)
    return bodies


def _exact_entries(result: Result) -> list[Optional[dict]]:
    """For each mass, its closed form's r and v at the final time and the size of the error, to
    15 digits; None where it has none (no closed form, or it stopped holding)."""
    traj = result.trajectory
    exact = result.exact()
    count = len(traj.m)
    known = np.zeros(count, dtype=bool) if exact is None else np.isfinite(exact[0]).all(axis=1)
    if not known.any():
        return [None] * count
    r_exact, v_exact = exact
    r, v = traj.r[-1], velocity(traj.p[-1], traj.m)
    # |r − r_exact| and |v − v_exact| of each mass (numpy's norm of each, bit for bit); 0 where unknown
    errors = np.where(known[:, None], np.stack([lengths(r - r_exact), lengths(v - v_exact)], axis=1), 0.0)
    r_exact, v_exact, errors = (clean_array(a).tolist() for a in (r_exact, v_exact, errors))
    return [{"r": r_exact[i], "v": v_exact[i], "error": {"r": errors[i][0], "v": errors[i][1]}} if known_i else None
            for i, known_i in enumerate(known.tolist())]


def _plain(value):
    """A constant's value as JSON: numbers, lists for vectors, None for derived ones."""
    if isinstance(value, (tuple, list, np.ndarray)):
        return [float(x) for x in value]
    if isinstance(value, (int, float, np.floating)):
        return float(value)
    return value


def to_json(out: dict) -> str:
    """`out` as strict JSON (no NaN or Infinity, which strict parsers reject).

    A number with no finite value (an overflow, an undefined quantity) becomes null, and a
    "notes" list names each such place and why, so no reader mistakes it for an answer. Only
    then is `out` walked (a long list of numbers as one array): most runs have no such number.
    """
    try:
        return json.dumps(out, ensure_ascii=False, allow_nan=False)
    except ValueError:   # a number with no finite value: find each one
        pass
    places = []
    clean = _finite(out, "", places)
    if places:
        clean.setdefault("notes", []).extend(
            f"{place}: null, no finite value (it overflowed or is undefined at this time)" for place in places)
    return json.dumps(clean, ensure_ascii=False, allow_nan=False)


def _finite(value, place: str, places: list):
    """`value` with each non-finite float replaced by None, and its place added to `places`."""
    if isinstance(value, dict):
        return {key: _finite(item, f"{place}.{key}" if place else key, places) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        block = float_block(value)
        if block is not None:
            bad = ~np.isfinite(block)
            if not bad.any():
                return value if isinstance(value, list) else list(value)
            places += [place + "".join(f"[{n}]" for n in index) for index in zip(*np.nonzero(bad))]
            return np.where(bad, None, block.astype(object)).tolist()
        return [_finite(item, f"{place}[{n}]", places) for n, item in enumerate(value)]
    if isinstance(value, float) and not np.isfinite(value):
        places.append(place)
        return None
    return value

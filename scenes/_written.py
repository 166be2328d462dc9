"""Forces written as expressions (physics/forces/written.py), added to a scene's model: what
`--force "push=vector(2, 0, 0)"` and the pages' "Add a force" box give a Setup.

A written force is kept in the Setup as text, (name, expression), never as code; each build reads
it by the grammar (physics/expression.py) and makes the force from the constants of the moment, so
a slider that moves k moves the k the force reads. The forces go after the scene's own, in the
order given; the model then has no closed form ("no closed form with push"), and a force with no
value where the mass starts (NaN or infinite at t = 0) is refused in one line.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from physics.expression import CONSTANT_NAMES, ExpressionError, check_force_name, parse
from physics.forces.written import WrittenForce
from physics.state import velocity

from ._model import Model


def parse_force_option(text: str) -> tuple[str, str]:
    """`push=vector(2, 0, 0)` as (name, expression), both checked by the grammar; ExpressionError
    (one line) otherwise."""
    name, equals, expression = str(text).partition("=")
    if not equals:
        raise ExpressionError(f"--force needs NAME=EXPRESSION, like --force \"push=vector(2, 0, 0)\" (got {text!r})")
    name = check_force_name(name)
    return name, parse(expression).text


def check_written(written, *, labels=()) -> tuple[tuple[str, str], ...]:
    """The written forces, each read by the grammar (ExpressionError, naming the force, otherwise),
    with names unlike each other's and the scene's own forces' `labels`."""
    checked, taken = [], list(labels)
    for name, text in written:
        name = check_force_name(name, taken=taken)
        try:
            checked.append((name, parse(text).text))
        except ExpressionError as problem:
            raise ExpressionError(f"the force {name}: {problem}") from None
        taken.append(name)
    return tuple(checked)


def scene_constants(values: dict, model: Model | None = None) -> dict[str, float]:
    """The constants a written force may read (k, b, g, dt) that this scene has as one number: not
    one a force of the model holds with other values (a row's b, one per mass)."""
    found = {name: float(values[name]) for name in CONSTANT_NAMES
             if isinstance(values.get(name), (int, float)) and not isinstance(values.get(name), bool)}
    for force in model.forces if model is not None else ():
        try:
            held = force.program_values()
        except ValueError:
            continue
        for name, value in held.items():
            if name in found and not np.all(np.asarray(value, dtype=float) == found[name]):
                del found[name]
    return found


def add_written(model: Model, written, values: dict) -> Model:
    """The model with the written forces after its own: no closed form, named by the first of
    them. Raises ExpressionError (a ValueError) where a force cannot be read or has no value where
    the masses start, naming it."""
    if not written:
        return model
    written = check_written(written, labels=[getattr(force, "LABEL", "") for force in model.forces])
    constants = scene_constants(values, model)
    forces = []
    for name, text in written:
        law = parse(text)
        missing = sorted(law.names & set(CONSTANT_NAMES) - set(constants))
        if missing:
            raise ExpressionError(f"the force {name} reads {', '.join(missing)}, which this scene does not have as "
                                  f"one number (it has {', '.join(constants) or 'none of k, b, g, dt'})")
        force = WrittenForce(name, law, constants)
        _check_start(force, model)
        forces.append(force)
    return add_forces(model, forces)


def add_forces(model: Model, forces) -> Model:
    """The model with these forces after its own, and no closed form (named by the first of them)."""
    return dataclasses.replace(model, forces=tuple(model.forces) + tuple(forces), exact=None,
                               exact_valid_until=None, exact_limit="", no_closed_form_each=(),
                               no_closed_form=f"no closed form with {forces[0].LABEL}")


def _check_start(force: WrittenForce, model: Model) -> None:
    """The force where the masses start, at t0: a number, or ExpressionError naming it."""
    state = model.state
    F = force(state.t, state.r, velocity(state.p, state.m), state.m)
    if not np.all(np.isfinite(F)):
        where = "where the mass starts" if state.count == 1 else "where the masses start"
        raise ExpressionError(f"the force {force.name} has no value at t = 0 {where} (it divides by zero or "
                              f"grows past any number there): change it, or start the mass elsewhere")

"""The lists of one value per mass, for a program with several masses.

A scene that builds its masses by a rule from its constants (a row of anchors `spacing` apart,
each mass x0 beyond its equilibrium, b from 2√(mk), ω from omega_min to omega_max) declares that
rule as data on its Model (Model.per_mass: scenes/_row.py's MassLoop of MassList). This module
writes those lists with the scene's own for loop, so a teacher can change the constants they are
built from; it knows no scene and runs nothing. Any other list is written out value by value: by
name where a value is the scene's constant of that name, else as a number cleaned of round-off
(15 digits), one a line where it is long.
"""
from __future__ import annotations

import re

import numpy as np

from physics.exact import Role
from scenes import DECLARED

from .lines import COMMENT, CONSTANT_COLUMN, commented, listed, number, vector
from .numbers import clean
from .program_answer import labelled

LABELLED = 6               # more masses than this: no labels on their curves (as the page's legend)


def masses(setup, model, constants, methods) -> tuple[list[str], set[str]]:
    """The lines that make the lists of one value per mass, and the scene's constants they use."""
    if constants.count == 1:
        return [], set()
    lines, written = _declared_lists(model.per_mass, constants)
    used = _names(lines, setup.values)
    for name, values in constants.per_mass.items():
        if name not in written:
            items = [_spelled(setup.values, name, x, used) for x in values]
            lines += listed(constants.list_name(name), items, constants.comment(name, per_mass=True))
    if len(set(methods)) > 1:
        lines += listed("method", [f'"{x}"' for x in methods], "the integrator of each mass")
    if constants.count <= LABELLED:
        lines += listed("labels", [f'"{label}"' for label in model.labels], "what each mass shows")
    return lines, used


def _declared_lists(per_mass, constants) -> tuple[list[str], set[str]]:
    """The scene's declared lists (those the program has one value per mass of), and their names."""
    if per_mass is None:
        return [], set()
    lists = [rule for rule in per_mass.lists if rule.name in constants.per_mass]
    looped = [rule for rule in lists if rule.each]
    before, inside = [], []
    for rule in lists:
        before += [commented(code, comment) for code, comment in rule.before if commented(code, comment) not in before]
        if rule.whole:
            before.append(commented(f"{constants.list_name(rule.name)} = {rule.whole}",
                                    constants.comment(rule.name, per_mass=True)))
    indent = "    " * len(per_mass.loop)
    for rule in per_mass.lists if looped else ():
        list_name = constants.list_name(rule.name)
        if rule.keep:           # kept for the lists after it, appended where it differs between masses
            inside.append(indent + commented(f"{rule.keep} = {rule.each}", rule.comment))
            inside += [indent + f"{list_name}.append({rule.keep})"] if rule in looped else []
        elif rule in looped:
            inside.append(indent + commented(f"{list_name}.append({rule.each})", rule.comment))
    empty = [commented(f"{constants.list_name(rule.name)} = []", constants.comment(rule.name, per_mass=True),
                       width=CONSTANT_COLUMN) for rule in looped]
    loop = list(per_mass.loop) if looped else []
    return before + empty + loop + inside, {rule.name for rule in lists}


def _names(lines, values) -> set[str]:
    """The scene's constants that these lines' code (not their comments) names."""
    code = " ".join(line.partition(COMMENT)[0].partition(" # ")[0] for line in lines)
    return set(re.findall(r"[A-Za-z_]\w*", code)) & {name for name, value in values.items() if value is not None}


def _spelled(values, name: str, x, used: set[str]) -> str:
    """One value of a written-out list: the scene's constant's name where it has that value."""
    if np.ndim(x):
        return vector(clean(c) for c in x)
    same = values.get(name) is not None and np.ndim(values[name]) == 0 and float(values[name]) == x
    if same:
        used.add(name)
    return name if same else number(clean(x))


def anchor(constants) -> str:
    """The spring's fixed end, which the helix is drawn from, by its role in the closed form as the
    spring declares it (physics/forces/ CLOSED_FORM, ProgramConstants.roles): no front end names a
    force's constant."""
    return constants.roles.get(Role.ANCHOR, Role.ANCHOR)


def mass_count(constants) -> str:
    """How the program counts its masses: the length of one of its lists."""
    for name in ("r0", anchor(constants), *constants.per_mass):
        if name in constants.per_mass:
            return f"len({constants.list_name(name)})"
    return str(constants.count)


def which_mass(model, constants) -> str:
    """What the answer names each mass by: its label, or the values that set it apart."""
    if model.state.count <= LABELLED:
        return 'labels[i] + ":"'
    shown = [name for name, values in constants.per_mass.items() if values.ndim == 1]
    if not shown:
        return '"mass", i, ":"'
    parts = []
    for k, name in enumerate(shown):
        declared = DECLARED.get(name)
        unit = f" {declared.unit}" if declared and declared.unit != "1" else ""
        parts.append(labelled((declared.symbol if declared else "") or name, constants.name(name), unit,
                              last=k == len(shown) - 1))
    return ", ".join(parts)

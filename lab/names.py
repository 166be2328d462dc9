"""Which constants --fit may fit, and whether the release point is fitted with them.

A position record fixes some constants only in combinations: x(t) depends on k/m, not on k and m
apart. Each force declares the groups of its constants that enter only so (TIED in physics/forces/),
and a fit of two of a group is refused with one line.

A real record's release point is unknown, so `--fit NAMES` fits it too (r0's component along the
compared coordinate) unless the user gave it: --set r0, or --set of a constant that only moves the
start (driven's x0), found by building the scene with it changed: the start moves, the forces do not.
"""
from __future__ import annotations

import dataclasses
from itertools import combinations

import numpy as np

from physics.forces import FORCES, declared_constants
from scenes._constants import DECLARED

from .model_run import RELEASE, FitError


def tied() -> list[tuple[set, str]]:
    """Constants that enter the motion only in a combination, as each force declares them (TIED):
    pairs of a group, with why. Read when a fit is asked for, after the declarations are checked."""
    declared_constants()
    return [(set(pair), why) for force in FORCES for names, why in force.TIED for pair in combinations(names, 2)]


def check_names(setup, names) -> list[str]:
    """The constants --fit may fit: numbers of the scene (not dt or until), none tied to another."""
    names = [name.strip() for name in names if name.strip()]
    if not names:
        raise FitError("--fit needs the names of constants to fit, e.g. --fit k,b")
    for name in names:
        if name not in setup.constants:
            raise FitError(f"--fit {name}: scene {setup.name!r} has no constant {name!r} "
                           f"(python main.py {setup.name} --constants lists them)")
        if name == RELEASE:
            pass          # its component along the compared coordinate: where the mass was let go
        elif name in ("dt", "until") or not isinstance(setup.values[name], (int, float)) \
                or DECLARED[name].vector or DECLARED[name].whole:
            raise FitError(f"--fit {name}: only a physical constant with one number (k, b, m, g, ...) "
                           f"can be fitted")
        if names.count(name) > 1:
            raise FitError(f"--fit names {name!r} twice")
    for group, why in tied():
        if group <= set(names):
            pair = " and ".join(sorted(group))
            raise FitError(f"--fit {','.join(names)}: {pair} cannot be told apart from a measured "
                           f"position: {why}; set one with --set (weigh the mass: --set m=...) and fit the other")
    return names


def _forces_alike(one, other) -> bool:
    if len(one) != len(other):
        return False
    for a, b in zip(one, other):
        if type(a) is not type(b):
            return False
        if dataclasses.is_dataclass(a):
            for item in dataclasses.fields(a):
                if not np.array_equal(np.asarray(getattr(a, item.name)), np.asarray(getattr(b, item.name))):
                    return False
    return True


def release_given(setup, given) -> bool:
    """Whether the user gave the release point: --set r0, or --set of a constant that moves only the
    start (see the module's docstring). `given` names the constants set with --set."""
    if RELEASE in given:
        return True
    if RELEASE not in setup.constants:
        return True             # a scene with no start position to fit
    model = setup.build()
    for name in given:
        if name not in setup.constants or name == "dt":
            continue
        default = setup.constants[name].value
        if default == setup.values[name]:
            continue
        try:
            other = setup.with_values(**{name: default}).build()
        except (ValueError, TypeError):
            continue
        moved = not np.array_equal(other.state.r, model.state.r)
        if moved and _forces_alike(other.forces, model.forces):
            return True
    return False


def with_release(setup, names, given) -> tuple[list[str], bool]:
    """(the names fitted, whether the release was added to them): RELEASE is added to a fit unless
    the user gave it, or the fit names it already."""
    if not names or RELEASE in names or release_given(setup, given):
        return list(names), False
    return [*names, RELEASE], True

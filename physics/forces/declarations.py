"""What a force declares, checked: a mistake is one line naming the force and the fix.

A contributor adds a force by writing one class (docs/architecture.md, "Adding a force"). Nothing
about its declarations is worked out when the module is imported: a table built at import from a
wrong declaration would end every command, --list included, in a traceback. Instead the commands
that use the forces (every scene's constants, the closed form, the program, --forces) ask
check_forces() first, and a mistake is one line, as any other bad input is:

    the friction force (physics/forces/friction.py, Friction): its constant mu_k declares a range
    but no default; give it one, like default=0.0 (with switch=True where that switches it off)

A force module that cannot even be imported (a typo, a NameError) is named the same way, with its
file and line, and the other forces and the scenes that do not need it are not held up by it
until a command needs the forces. Plain Python: no numpy needed to check a declaration.
"""
from __future__ import annotations

import math
import os
import sys
import traceback
from numbers import Real

from ..declared import Declared


class DeclarationError(ValueError):
    """A force's declaration that cannot be used: one line naming the force and what to fix."""


BROKEN: list[str] = []     # a line for each force module that could not be imported (physics/forces/__init__.py)
_CHECKED: dict[tuple, str | None] = {}     # what the forces were when last checked -> the first problem


def broken_module(path: str, problem: BaseException) -> str:
    """The line naming a force module that could not be imported: its file, the line that failed
    (where the traceback reaches the file) and the error."""
    line = None
    if isinstance(problem, SyntaxError):
        line = problem.lineno
    else:
        lines = [frame.lineno for frame in traceback.extract_tb(problem.__traceback__)
                 if os.path.abspath(frame.filename) == os.path.abspath(path)]
        line = lines[-1] if lines else None
    what = " ".join(f"{type(problem).__name__}: {problem}".split())
    return (f"the force module {_shown(path)} cannot be imported ({f'line {line}: ' if line else ''}{what}); "
            f"fix it, or move it out of physics/forces/")


def named(cls) -> str:
    """How a message names a force: its LABEL and where its class is, `the friction force
    (physics/forces/friction.py, Friction)`."""
    module = sys.modules.get(cls.__module__)
    place = _shown(module.__file__) if getattr(module, "__file__", None) else cls.__module__
    label = cls.LABEL if isinstance(getattr(cls, "LABEL", ""), str) and cls.LABEL else cls.__name__
    return f"the {label} force ({place}, {cls.__name__})"


def _shown(path: str) -> str:
    try:
        relative = os.path.relpath(path)
    except (OSError, ValueError):
        return path
    return path if relative.startswith(os.pardir) else relative


def check_forces(forces) -> None:
    """Raise DeclarationError, one line, for the first force module that could not be imported or
    the first force whose declarations cannot be used; the answer is kept until the forces change."""
    key = (len(BROKEN), tuple(id(cls) for cls in forces))
    if key not in _CHECKED:
        problems = list(BROKEN) + [problem for cls in forces for problem in class_problems(cls)]
        problems += _shared_names(forces)
        _CHECKED.clear()
        _CHECKED[key] = problems[0] if problems else None
    if _CHECKED[key]:
        raise DeclarationError(_CHECKED[key])


def class_problems(cls) -> list[str]:
    """What is wrong with one force class's declarations, each a whole line (none: it is fine)."""
    who = named(cls)
    declared = getattr(cls, "CONSTANTS", {})
    if not isinstance(declared, dict):
        return [f"{who}: CONSTANTS must be a dict of its constants' names to Declared(...), not a "
                f"{type(declared).__name__}"]
    problems = [f"{who}: {problem}" for name, declaration in declared.items()
                for problem in constant_problems(name, declaration)]
    problems += [f"{who}: {problem}" for problem in _role_problems(cls, declared)]
    problems += [f"{who}: {problem}" for problem in _tied_problems(cls, declared)]
    return problems[:1]


def constant_problems(name, declaration) -> list[str]:
    """What is wrong with one constant's declaration (a force's constant: it needs a default)."""
    if not isinstance(name, str) or not name.isidentifier():
        return [f"the constant {name!r} needs a name a program can use (letters, digits and _), like 'c'"]
    if not isinstance(declaration, Declared):
        return [f"its constant {name} must be declared as Declared(unit, low, high, ...), not {declaration!r}"]
    if not isinstance(declaration.unit, str) or not declaration.unit.strip():
        return [f"its constant {name} has no unit; give its SI unit first, like Declared(\"kg/s\", 0, 1e6, ...) "
                f"(\"1\" for a pure number)"]
    if not all(isinstance(x, Real) and not isinstance(x, bool) and math.isfinite(x)
               for x in (declaration.low, declaration.high)) or declaration.low > declaration.high:
        return [f"its constant {name} needs a range of two finite numbers, low then high, like "
                f"Declared(\"{declaration.unit}\", 0, 1e6, ...) (got {declaration.low!r} to {declaration.high!r})"]
    if declaration.default is None:
        return [f"its constant {name} declares a range but no default; give it one, like default=0.0 "
                f"(with switch=True where that value switches the force off)"]
    if not _fits(declaration, declaration.default):
        return [f"the default of its constant {name}, {declaration.default!r}, is not "
                f"{declaration.words(declaration.unit, vector=declaration.vector)}; give a default inside its range"]
    if not isinstance(declaration.meaning, str) or not declaration.meaning.strip():
        return [f"its constant {name} has no meaning; add meaning=\"...\" (what it is, in a few words: "
                f"--constants, --forces and the program's comments print it)"]
    if declaration.slider and declaration.vector:
        return [f"its constant {name} is a vector, which no slider can move; leave slider out"]
    return []


def _fits(declaration: Declared, value) -> bool:
    if declaration.vector:
        return (isinstance(value, tuple) and len(value) == 3 and all(isinstance(x, Real) for x in value)
                and declaration.allows(tuple(float(x) for x in value)))
    return isinstance(value, Real) and not isinstance(value, bool) and declaration.allows(float(value))


def _role_problems(cls, declared: dict) -> list[str]:
    """CLOSED_FORM: a role of the closed form (physics/exact.py Role) for each constant that holds
    one, a constant of its own, and no constant holding two roles."""
    from ..exact import ROLES

    roles = getattr(cls, "CLOSED_FORM", {})
    if not isinstance(roles, dict):
        return [f"CLOSED_FORM must be a dict of roles to its constants' names, like {{Role.DAMPING: \"c\"}}"]
    problems = []
    for role, name in roles.items():
        if role not in ROLES:
            problems.append(f"CLOSED_FORM gives {role!r}, which is not a role of the closed form; the roles "
                            f"are physics/exact.py Role's: {', '.join(ROLES)}")
        elif name not in declared:
            problems.append(f"CLOSED_FORM gives the closed form's {role} to {name!r}, which is not one of its "
                            f"CONSTANTS ({', '.join(declared) or 'none'}); name one of them")
    holders = list(roles.values())
    twice = sorted({name for name in holders if holders.count(name) > 1})
    if twice:
        problems.append(f"CLOSED_FORM gives its constant {twice[0]} two roles of the closed form; a constant "
                        f"holds one role")
    from .base import Force

    written = any("closed_form" in vars(kind) for kind in cls.__mro__ if kind not in (Force, object))
    if written and not roles:
        problems.append("its closed_form() is written, but CLOSED_FORM names no constant for its roles; add "
                        "CLOSED_FORM = {Role.DAMPING: \"c\"} (physics/exact.py Role), one entry per term it gives")
    if roles and not written:
        problems.append("CLOSED_FORM names roles of the closed form, but its closed_form() is not written; "
                        "write it, returning its terms by role ({Role.DAMPING: self.c}), or leave CLOSED_FORM out")
    return problems


def _tied_problems(cls, declared: dict) -> list[str]:
    """TIED: groups of at least two names, each with why (lab/names.py reads them)."""
    tied = getattr(cls, "TIED", ())
    shape = isinstance(tied, tuple) and all(
        isinstance(entry, tuple) and len(entry) == 2 and isinstance(entry[1], str)
        and isinstance(entry[0], tuple) and len(entry[0]) >= 2 and all(isinstance(n, str) for n in entry[0])
        for entry in tied)
    if not shape:
        return ["TIED must be a tuple of ((names, ...), why) pairs, like ((\"m\", \"c\"), \"the motion "
                "depends on c/m only\"),"]
    return []


def _shared_names(forces) -> list[str]:
    """A constant two forces declare differently: they would fight over one name."""
    first: dict[str, type] = {}
    for cls in forces:
        declared = getattr(cls, "CONSTANTS", {})
        if not isinstance(declared, dict):
            continue
        for name, declaration in declared.items():
            other = first.setdefault(name, cls)
            if other is not cls and other.CONSTANTS[name] != declaration:
                return [f"{named(cls)} declares a constant {name}, as {named(other)} does, but differently; "
                        f"give it a name of its own, or the very same declaration"]
    return []


def closed_form_problem(force, terms: dict) -> str:
    """Where a force's closed_form() gives terms its CLOSED_FORM does not name (the program's exact
    curve could not find their constants), the line that says so; "" where they agree."""
    roles = set(getattr(type(force), "CLOSED_FORM", {}))
    given = set(terms)
    if given == roles:
        return ""
    missing = sorted(given - roles)
    if missing:
        return (f"{named(type(force))}: closed_form() gives the closed form's {', '.join(missing)}, but CLOSED_FORM "
                f"names no constant for {'it' if len(missing) == 1 else 'them'}; add it, like "
                f"CLOSED_FORM = {{Role.DAMPING: \"c\"}} (physics/exact.py Role)")
    extra = sorted(roles - given)
    return (f"{named(type(force))}: CLOSED_FORM names {', '.join(extra)}, which closed_form() does not give; "
            f"give them in closed_form(), or leave them out of CLOSED_FORM")

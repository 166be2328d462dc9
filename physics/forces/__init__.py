"""Forces on N point masses, one declaration each: the base class, the page's forces, and any other
force module in this folder.

Each force is a pure function of (t, r, v, m) returning an (N, 3) array, in N; beside its law its
class declares everything else about it (base.py's Force: label, constants, program line, energy,
stability rate, closed form, stop rule). Adding a force is adding a module to this folder, like
friction.py: every module here is imported with the package, so its force is known (FORCES) to the
single-mass scenes, --set, the page and the program without a list to edit. The page's own forces
(page.py) come first, in the order the page adds them: spring, gravity, damping, drag, driving.
Nothing about them is worked out here: a module that cannot be imported, or a force whose
declarations cannot be used, is one line at the first command that needs the forces
(declarations.py), never a traceback at import.
"""
from __future__ import annotations

import importlib
import os
import pkgutil

from .base import (FORCES, DeclarationError, Force, closed_form_constants, closed_form_terms, compare,  # noqa: F401
                   declared_constants, forces_each, net_force, settle, switched_on, uses_velocity, where)
from .declarations import BROKEN, broken_module
from .page import Driving, Gravity, LinearDamping, QuadraticDrag, Spring, SpringBetween  # noqa: F401

for _module in pkgutil.iter_modules(__path__):
    if _module.name not in ("base", "page", "declarations"):
        try:
            importlib.import_module(f"{__name__}.{_module.name}")
        except Exception as _problem:   # named in one line by the first command that needs the forces
            BROKEN.append(broken_module(os.path.join(__path__[0], _module.name + ".py"), _problem))

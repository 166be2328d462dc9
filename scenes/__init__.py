"""Scenes: the page's examples as data, one file per scene (constants, a build function, what to draw).

A scene file is found by its name (scenes/_catalog.py); the files starting with "_" are what the
scenes share: the Model they build (_model.py), what each constant may be (_constants.py), the
presets and configuring a scene (_catalog.py), and the builders of one mass (_single_mass.py) and
of a row of masses (_row.py). Importing this package, or any scene, never imports vpython.
"""
from ._constants import (DECLARED, Constant, ConstantError, check_value, format_value,
                         parse_assignments, read_constants)
from ._model import Model
from . import _catalog as catalog
from ._catalog import (CRITICAL_DAMPING, DEFAULT_SCENE, GRAVITY_PRESETS, SCENE_NAMES, Setup, configure,
                       find_preset, load, presets, resolve, scenarios, summary)

"""The list of scenes, and turning a scene name plus overrides into a ready Model.

Importing a scene module never imports vpython; the browser view is separate (scenes/view.py).
"""
from __future__ import annotations

import difflib
import importlib
from dataclasses import dataclass

from .constants import ConstantError, Constant, parse_assignments, read_constants
from .model import Model

SCENE_NAMES = ["vertical", "damped", "driven", "regimes", "drag", "pendulum", "integrators", "resonance"]
DEFAULT_SCENE = "vertical"


def load(name: str):
    """The scene module called `name`, or ConstantError with the closest name."""
    if name not in SCENE_NAMES:
        close = difflib.get_close_matches(name, SCENE_NAMES, n=1, cutoff=0.5)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise ConstantError(f"unknown scene {name!r}{hint} (run 'python main.py --list' to see them)")
    return importlib.import_module(f"scenes.{name}")


def summary(module) -> str:
    """The first line of a scene's docstring: its one-line description."""
    return (module.__doc__ or "").strip().splitlines()[0]


def scenarios(module) -> list:
    """The scene's numbered scenarios as (label, overrides), possibly empty."""
    return list(getattr(module, "SCENARIOS", []))


@dataclass(frozen=True)
class Setup:
    """A scene with its constants resolved: module, constants (with units), chosen values."""

    name: str
    module: object
    constants: dict[str, Constant]
    values: dict

    def build(self) -> Model:
        return self.module.build(**self.values)

    def with_values(self, **changes) -> "Setup":
        return Setup(self.name, self.module, self.constants, {**self.values, **changes})


def configure(name: str, *, assignments=(), scenario: int | None = None) -> Setup:
    """Defaults from the scene file, then the scenario's changes, then `--set NAME=VALUE` ones."""
    module = load(name)
    constants = read_constants(module)
    values = {key: constant.value for key, constant in constants.items()}
    if scenario is not None:
        options = scenarios(module)
        if not options:
            raise ConstantError(f"scene {name!r} has no scenarios")
        if not 1 <= scenario <= len(options):
            raise ConstantError(f"scenario {scenario} is out of range: scene {name!r} has scenarios 1 to {len(options)}")
        values.update(options[scenario - 1][1])
    values.update(parse_assignments(assignments, constants))
    return Setup(name, module, constants, values)

"""The scenes, their presets, and turning a scene name plus overrides into a ready Model.

A scene is any module in this folder whose name does not start with "_" (those are the shared
builders), plus any in the folders named by the environment variable SPRING_SCENES (separated
like PATH): a teacher's own scenes, kept outside the project. Nothing lists them by hand; a scene
may set MENU_ORDER (a number; lower comes first, default 100) to place itself in --list and in the
page's scene menu. Importing a scene module never imports vpython; the browser is separate.

A preset is a named set of constant changes, kept as data: `(label, {name: value})`. The same
list feeds the command line (`--preset NAME`) and the page's preset menu. Every scene offers the
ones that make sense for it:

- "Moon gravity", "Earth gravity", "Jupiter gravity" (g = 1.62, 9.8, 24.79 m/s²), where gravity is
  switched on (a horizontal scene on a table has g = 0 and gets none);
- "critical damping", b = 2√(mk) for the m and k of the moment, where the scene has b and k;
- "scenario N: ..." for each of the scene's numbered SCENARIOS (the page's driven examples);
- then the scene's own PRESETS, which may also replace one of the above by using its label.

In a preset, b = None means "critical": :func:`resolve` turns it into 2√(mk) once m and k are known.
"""
from __future__ import annotations

import difflib
import importlib
import importlib.util
import os
import pkgutil
import sys
from dataclasses import dataclass
from pathlib import Path

from physics.exact import critical_damping

from ._constants import ConstantError, Constant, check_value, parse_assignments, read_constants
from ._model import Model

DEFAULT_SCENE = "vertical"
EXTRA_FOLDERS = "SPRING_SCENES"   # environment variable: more folders of scenes, like PATH


def _discover() -> list[str]:
    """Every scene's name, in menu order: this folder's modules and those of SPRING_SCENES."""
    here = Path(__file__).parent
    found = {info.name: None for info in pkgutil.iter_modules([str(here)]) if not info.name.startswith("_")}
    for folder in filter(None, os.environ.get(EXTRA_FOLDERS, "").split(os.pathsep)):
        for path in sorted(Path(folder).glob("[!_]*.py")):
            if path.stem not in found:
                found[path.stem] = path
    for name, path in found.items():
        if path is not None and f"scenes.{name}" not in sys.modules:   # a teacher's own scene file
            spec = importlib.util.spec_from_file_location(f"scenes.{name}", path)
            module = importlib.util.module_from_spec(spec)
            sys.modules[spec.name] = module
            spec.loader.exec_module(module)
    order = {name: getattr(importlib.import_module(f"scenes.{name}"), "MENU_ORDER", 100) for name in found}
    return sorted(found, key=lambda name: (order[name], name))


SCENE_NAMES = _discover()

GRAVITY_PRESETS = {                # m/s², the strength of gravity at the surface
    "Moon gravity": {"g": 1.62},
    "Earth gravity": {"g": 9.8},
    "Jupiter gravity": {"g": 24.79},
}
CRITICAL_DAMPING = "critical damping"


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


def presets(scene) -> list[tuple[str, dict]]:
    """The scene's presets in menu order, as (label, overrides); `scene` is a module or a Setup."""
    module = getattr(scene, "module", scene)
    defaults = {name: constant.value for name, constant in read_constants(module).items()}
    found = {}
    if defaults.get("g"):  # gravity is switched on, so its strength matters
        found.update(GRAVITY_PRESETS)
    if "b" in defaults and "k" in defaults:
        found[CRITICAL_DAMPING] = {"b": None}
    for number, (label, overrides) in enumerate(scenarios(module), start=1):
        found[f"scenario {number}: {label}"] = overrides
    found.update(getattr(module, "PRESETS", {}))
    return [(label, dict(overrides)) for label, overrides in found.items()]


def find_preset(scene, name: str) -> tuple[str, dict]:
    """The preset called `name` (any case; a unique beginning such as "moon" or "scenario 3" is enough).

    Raises ConstantError naming the closest preset and listing them all.
    """
    options = presets(scene)
    labels = [label for label, _ in options]
    wanted = name.strip().casefold()
    exact = [option for option in options if option[0].casefold() == wanted]
    starts = [option for option in options if option[0].casefold().startswith(wanted)] if wanted else []
    if exact or len(starts) == 1:
        return (exact or starts)[0]
    scene_name = getattr(scene, "name", None) or getattr(scene, "__name__", "").rpartition(".")[2]
    if not options:
        raise ConstantError(f"scene {scene_name!r} has no presets")
    if len(starts) > 1:
        raise ConstantError(f"preset {name!r} could be any of {', '.join(repr(o[0]) for o in starts)}; "
                            f"give more of its name")
    folded = {label.casefold(): label for label in labels}
    close = difflib.get_close_matches(wanted, list(folded), n=1, cutoff=0.5)
    hint = f"; did you mean {folded[close[0]]!r}?" if close else ""
    raise ConstantError(f"unknown preset {name!r} for scene {scene_name!r}{hint} "
                        f"(presets: {', '.join(repr(label) for label in labels)})")


def resolve(values: dict) -> dict:
    """The values with b = None ("critical") replaced by b = 2√(mk) for their m and k, kg/s."""
    if "b" in values and values["b"] is None and "m" in values and "k" in values:
        return {**values, "b": float(critical_damping(m=values["m"], k=values["k"]))}
    return values


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
        return Setup(self.name, self.module, self.constants, resolve({**self.values, **changes}))

    def with_preset(self, name: str) -> "Setup":
        """These values with the preset's changes (critical damping from the m and k set now)."""
        return self.with_values(**find_preset(self, name)[1])


def configure(name: str, *, assignments=(), scenario: int | None = None, preset: str | None = None) -> Setup:
    """Defaults from the scene file, then the scenario's changes, the preset's, and `--set NAME=VALUE` ones.

    A preset's b = None (critical damping) is worked out last, from the final m and k.
    """
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
    if preset is not None:
        values.update(find_preset(module, preset)[1])
    values.update(parse_assignments(assignments, constants))
    for key, value in values.items():  # the file's own values and the presets' obey the same ranges
        check_value(key, tuple(value) if isinstance(value, list) else value, constants[key].unit)
    return Setup(name, module, constants, resolve(values))

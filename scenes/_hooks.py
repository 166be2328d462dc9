"""What a scene file may give beyond its constants and build, read once when the scene is configured.

Every scene has VIEW (what to draw, scenes/_view.py). A scene may also define these functions,
which the front ends call instead of probing the module for them:

    measure_window(values) -> (start, end)   s: the window a headless run measures in (resonance:
                                             the steady-state amplitudes), given the scene's
                                             constants; a run must reach `end`
    measure_now(model, state) -> (N,)        what the scene measures at each step of that window;
                                             a headless run keeps the largest of each mass over
                                             the window (reports' Result.measured), not the steps
    extra_json(result) -> dict               the scene's own keys in `--headless --json`, from the
                                             finished run (reports' Result: setup, model,
                                             trajectory, measured)
    extra_text(result) -> str                the scene's own lines at the end of `--headless`
    view_graph(setup) -> dict                the page's own graph (browser/graphs.py)

and, as data, LAB: what the lab does with the scene's constants when it is compared with a real
spring (lab/), e.g. LAB = {"fit": ("k", "b"), "hidden": ("k", "b")}: the constants the page's Fit
button fits unless --fit names others, and those a mystery spring hides from the class.

:class:`SceneHooks` holds them, None where the scene defines none; ``Setup.hooks``
(scenes/_catalog.py) is filled in from the module once. A name that is there but not a function
(or, for VIEW, not a dict) is an error naming the scene file.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Optional, Protocol

from ._constants import ConstantError, shown_path


class MeasureWindow(Protocol):
    def __call__(self, values: Mapping[str, Any]) -> tuple[float, float]: ...


class MeasureNow(Protocol):
    def __call__(self, model: Any, state: Any) -> Any: ...


class ExtraJson(Protocol):
    def __call__(self, result: Any) -> dict: ...


class ExtraText(Protocol):
    def __call__(self, result: Any) -> str: ...


HOOKS = ("measure_window", "measure_now", "extra_json", "extra_text", "view_graph")


@dataclass(frozen=True)
class SceneHooks:
    """The scene's VIEW (as its file gives it) and its optional functions, None where it has none."""

    view: Mapping[str, Any] = field(default_factory=dict)
    measure_window: Optional[MeasureWindow] = None
    measure_now: Optional[MeasureNow] = None
    extra_json: Optional[ExtraJson] = None
    extra_text: Optional[ExtraText] = None
    view_graph: Optional[Callable[[Any], dict]] = None
    lab: Mapping[str, Any] = field(default_factory=dict)

    @classmethod
    def of(cls, module) -> "SceneHooks":
        """The hooks `module` defines: raises ConstantError for one that is not a function."""
        where = (shown_path(module.__file__) if getattr(module, "__file__", None)
                 else getattr(module, "__name__", "the scene file"))
        view = vars(module).get("VIEW", {})
        if not isinstance(view, Mapping):
            raise ConstantError(f"{where}: VIEW must be a dict, like VIEW = {{\"plot\": \"y\"}}")
        found = {name: vars(module).get(name) for name in HOOKS}
        for name, hook in found.items():
            if hook is not None and not callable(hook):
                raise ConstantError(f"{where}: {name} must be a function (see scenes/_hooks.py)")
        lab = vars(module).get("LAB", {})
        if not isinstance(lab, Mapping):
            raise ConstantError(f"{where}: LAB must be a dict, like LAB = {{\"fit\": (\"k\", \"b\")}}")
        return cls(view=view, lab=lab, **found)

    def measuring(self, values: Mapping[str, Any]) -> Optional[tuple[float, float]]:
        """The measuring window (start, end), s, for these constants; None if the scene has none."""
        if self.measure_window is None:
            return None
        start, end = self.measure_window(values)
        return float(start), float(end)

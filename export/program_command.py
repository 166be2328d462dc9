"""The command that shows a program's case on the simulator's page, for the program's header.

`python main.py driven --preset "scenario 4" --integrator verlet`: a preset where one gives some
of the changed constants, and --set NAME=VALUE for the others, checked by configuring the scene
again from exactly these options.
"""
from __future__ import annotations

from scenes import ConstantError, catalog

from .lines import number


def command(setup, model, integrator) -> str:
    """The command line that shows this case on the page: `python main.py driven --preset "scenario 4"
    --integrator verlet`, with a preset where one gives some of the changed constants, and
    --set NAME=VALUE for the others (checked: it configures exactly these values)."""
    best = _options(setup, None)
    for label, _ in catalog.presets(setup):   # a preset where it needs no more options than --set alone
        options = _options(setup, label)
        if options is not None and (best is None or len(options) <= len(best)) and not (
                best and best[0].startswith("--preset") and len(options) == len(best)):
            best = options
    if best is None:   # cannot happen for a scene configured from the command line or the page
        best = [f"--set {name}={_set_value(value)}" for name, value in setup.values.items()]
    if model.methods(integrator) != model.methods():
        best.append(f"--integrator {integrator}")
    return " ".join(["python main.py", setup.name, *best])


def _options(setup, preset: str | None) -> list[str] | None:
    """[--preset ..., --set ...] giving setup's values from `preset`, or None if they cannot."""
    try:
        if preset is not None:
            preset = _short_label(setup, preset)
        start = catalog.configure(setup.name, preset=preset).values
        sets = [f"{name}={_set_value(value)}" for name, value in setup.values.items()
                if value is not None and value != start.get(name)]
        if catalog.configure(setup.name, preset=preset, assignments=sets).values != setup.values:
            return None
        for text in list(sets):   # b = 52.76… that the preset works out from m and k is left to it
            fewer = [other for other in sets if other != text]
            if catalog.configure(setup.name, preset=preset, assignments=fewer).values == setup.values:
                sets = fewer
    except (ConstantError, ValueError):
        return None
    quoted = f'"{preset}"' if preset is not None and " " in preset else preset
    return ([f"--preset {quoted}"] if preset is not None else []) + [f"--set {text}" for text in sets]


def _short_label(setup, label: str) -> str:
    """"scenario 4" for "scenario 4: as 3, with F0 = 2 N", where --preset finds it by that much."""
    short = label.partition(":")[0]
    try:
        return short if catalog.find_preset(setup, short)[0] == label else label
    except ConstantError:
        return label


def _set_value(value) -> str:
    """A value as --set reads it: 2.5, or 0,-1.5,0 for a vector."""
    def exact(x):   # as short as number() writes it, unless that is not quite the value (17.400000000000002)
        return number(x) if float(number(x)) == float(x) else repr(float(x))
    return ",".join(exact(x) for x in value) if isinstance(value, (tuple, list)) else exact(value)

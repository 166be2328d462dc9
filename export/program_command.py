"""The program's header: the scene's description with this case's numbers, and the command that
shows the case on the simulator's page.

`python main.py driven --preset "scenario 4" --integrator verlet`: a preset where one gives some
of the changed constants, and --set NAME=VALUE for the others, checked by configuring the scene
again from exactly these options.

The description is the first line of the scene's docstring, written for the scene as shipped: "a
10 kg mass hangs on a 40 N/m spring". Where this case changed a constant whose shipped value the
line gives with its unit ("10 kg" for m), the line gives this case's value instead ("17.4 kg"). A scene may tell a case that changes what it
is (drag with k = 0: no springs) by a line of its own (its SUMMARIES).
"""
from __future__ import annotations

import math
import re

from scenes import ConstantError, catalog, summary

from .lines import number
from .step_update import number as rounded

DESCRIBED_DIGITS = 4        # significant digits of a changed value in the description: b = 52.76 kg/s
STALE_NOTE = "# (Some numbers in that line are the scene's as shipped; this case's constants are below.)"


def description(setup) -> list[str]:
    """The header's description: `# vertical: ... a 17.4 kg mass ...`, with this case's values where
    the line names a changed constant's shipped value with its unit; and STALE_NOTE below it where
    a number of a changed constant's unit is left that no constant accounts for ("released at
    1.5 m" when r0 changed)."""
    text = case_summary(setup)
    shipped = catalog.configure(setup.name).values
    changed = {name for name, value in setup.values.items() if value != shipped.get(name)}
    stale = False
    for match in reversed(list(_quantities(text, setup))):
        value, unit = float(match["value"]), match["unit"]
        named = [name for name, constant in setup.constants.items() if constant.unit == unit
                 and _scalar(shipped.get(name)) and math.isclose(float(shipped[name]), value, rel_tol=1e-12)]
        if len(named) == 1 and named[0] in changed:
            new = f"{rounded(setup.values[named[0]], DESCRIBED_DIGITS)} {unit}"
            text = text[:match.start()] + new + text[match.end():]
        elif len(named) != 1 and any(setup.constants[name].unit == unit for name in changed):
            stale = True   # a number no single constant accounts for, of a unit whose constants changed
    return [f"# {setup.name}: {text}", *([STALE_NOTE] if stale else [])]


def case_summary(setup) -> str:
    """The line that tells this case: the first of the scene's SUMMARIES (constants, line) whose
    constants this case has ("on no spring" for drag with k = 0), else its docstring's first line."""
    for values, text in getattr(setup.module, "SUMMARIES", []):
        if all(setup.values.get(name) == value for name, value in values.items()):
            return text
    return summary(setup.module)


def _quantities(text: str, setup):
    """The numbers with a unit of the scene's constants in `text`: "10 kg", "40 N/m", "1.5 m"."""
    units = sorted({constant.unit for constant in setup.constants.values() if constant.unit not in ("", "1")},
                   key=len, reverse=True)
    if not units:
        return iter(())
    pattern = (r"(?<![\w.])(?P<value>-?\d+(?:\.\d+)?(?:e[-+]?\d+)?) (?P<unit>"
               + "|".join(re.escape(unit) for unit in units) + r")(?![\w/²³·])")
    return re.finditer(pattern, text)


def _scalar(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


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
    best += [force_option(name, text) for name, text in setup.written]
    return " ".join(["python main.py", setup.name, *best])


def force_option(name: str, text: str) -> str:
    """--force "push=vector(2, 0, 0)": a written force as the command line takes it (the grammar
    has no quote, $ or \\, so double quotes keep it whole in any shell)."""
    return f'--force "{name}={text}"'


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

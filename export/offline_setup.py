"""What the offline page may change, and the set-up its programs are written for.

The page runs the handed-out Web VPython program and changes a set-up by writing new values into
its constants block (export/offline_page.js). A constant is offered (a slider, a preset, or a value
from the address `vertical.html#k=60&dt=0.05`) only over a span where writing its new value gives
the very program the writer would write for it, apart from what only frames the picture (the
sphere's size, the support, the arrows' scales): :func:`settable` finds that out from the writer
itself. The exact curve's cases are branches of the program and the masses' labels expressions of
the constants (export/exact_curve.py, scenes/_row.py labels_list), so a value moves nothing else.

A force switched off in the file (pendulum's b = 0) has no lines in its program. Where a slider
the local page shows (scenes/_sliders.py's slider_names, for the file's values or a preset's) would
switch it on, the page's programs are written with it on (:func:`page_setup`) and the page writes
the file's 0 back into the constant's line: at 0 the force's lines add exactly nothing, so the
file's own set-up runs as `--headless` runs it.

A preset is a set of values (:func:`preset_data`): the scene's own presets and scenarios
(scenes/_catalog.py presets), with the sliders the local page shows for them; one this file cannot
run says which command writes a file that can. Critical damping is b = 2√(mk) for the m and k of
the moment, written into b's line as the handed-out program writes it (program_constants.critical_line).
"""
from __future__ import annotations

from dataclasses import dataclass

from scenes import DECLARED, catalog
from scenes._sliders import round_slider_values, slider_names, slider_range, symbol

from .lines import ProgramError
from .program_constants import ProgramConstants, critical_line
from .vpython_program import program
from physics.declared import SMALLEST
from physics.exact import Role

# What only frames the picture: the writer chooses it from the motion, and a constant moved on the
# page keeps the file's (the local page also keeps its arrow scales through a run).
FRAMING = ("radius = ", "box(", "pscale = ", "Fscale = ")


@dataclass(frozen=True)
class Settable:
    """A constant the page may change: the value its line holds in the page's programs (written),
    the file's own value (own: 0 where the programs hold a force switched on for its slider), the
    scene's default, and the span this file can run (file_low to file_high)."""

    name: str
    written: float
    own: float
    scene_default: float
    file_low: float
    file_high: float

    def as_data(self) -> dict:
        declared = DECLARED[self.name]
        unit = declared.unit
        return {"written": self.written, "own": self.own, "scene_default": self.scene_default, "unit": unit,
                "symbol": symbol(self.name), "low": declared.low, "high": declared.high,
                "above_low": declared.above_low, "whole": declared.whole, "words": declared.words(unit),
                "file_low": self.file_low, "file_high": self.file_high}


def code(text: str, skip: str) -> list[str]:
    """A program's code to compare: its lines without comments, framing, or the line of `skip`."""
    lines = []
    for line in text.splitlines():
        line = line.split(" # ", 1)[0].rstrip()
        if line.lstrip().startswith("#") or line.startswith(FRAMING) or line.startswith(f"{skip} = "):
            continue
        lines.append(line)
    return lines


def _program(setup, integrator, scales=None) -> str:
    return program(setup, integrator=integrator, web=True, arrows=(), page=True, header=False, scales=scales)


def _same_program(setup, name: str, value: float, base: list[str], integrator, scales=None) -> bool | None:
    """Whether the program for setup with name = value is `base` but for that constant's line;
    None where the physics refuses the value here (a force's rule, μ_s below μ_k: the page judges
    that itself, in the command line's words)."""
    try:
        changed = setup.with_values(**{name: value})
        changed.build()
    except ValueError:
        return None
    try:
        text = _program(changed, integrator, scales)
    except (ValueError, ProgramError):
        return False
    return code(text, name) == base


def _probes(value: float, end: float) -> list[float]:
    """Values from `end` back towards `value` to try where the physics refuses `end` (a rule that
    ties two constants: μ_s ≥ μ_k), so the program's lines at that side can still be compared."""
    return [end + (value - end) * fraction for fraction in (0.0, 0.5, 0.9, 0.99)]


def settable(setup, *, integrator=None, own=None, also=None, scales=None) -> list[Settable]:
    """The constants the page may change and the span of each: every plain number (not a count)
    whose line in the constants block can take the ends of its slider's span (a tenth to three
    times the scene's value, or from 0: scenes/_sliders.py's slider_range) and give the program
    the writer writes for them. From 0, a force's constant switches the force off; its line then
    adds exactly nothing, so the file's program runs it unchanged (probed just above 0). `own`:
    the file's own set-up where `setup` has forces switched on for their sliders (page_setup);
    `also`: more values of a constant to offer where the program takes them (its presets');
    `scales`: the arrows' scales, which only frame the picture (the probes need not choose them)."""
    own = own or setup
    text = _program(setup, integrator, scales)
    found = []
    for name, constant in setup.constants.items():
        value = setup.values[name]
        if not isinstance(value, (int, float)) or isinstance(value, bool) or DECLARED[name].whole:
            continue
        if not any(line.startswith(f"{name} = ") for line in text.splitlines()):
            continue
        mine = float(own.values[name])
        default = constant.value if isinstance(constant.value, (int, float)) else mine
        values = round_slider_values(name, mine, default)
        low, high = (values[0], values[-1]) if values else slider_range(name, mine, default)[:2]
        base = code(text, name)

        def takes(end):
            return _takes(setup, name, value, _probe(name, end, high), base, integrator, scales)
        if not all(takes(end) is not None for end in (low, high) if end != value):
            continue
        declared = DECLARED[name]
        widest = [declared.high, max(declared.low, SMALLEST) if declared.above_low else declared.low]
        for extra in sorted({float(x) for x in (also or {}).get(name, ()) if not low <= x <= high}) + widest:
            took = takes(extra)
            if took is not None:   # the span this file runs reaches it (the declared range's end where it can)
                reach = extra if took == _probe(name, extra, high) else took
                low, high = min(low, reach), max(high, reach)
        found.append(Settable(name, float(value), mine, float(default), float(low), float(high)))
    return found


def _probe(name: str, x: float, high: float) -> float:
    """Where to try x: at 0 a force's switch (b, F0, C: switch or slider from 0, DECLARED) takes
    its force's lines out of the writer's program, while the page's keeps them, adding exactly
    nothing; so such a 0 is tried just above it. Any other value is tried as it is."""
    declared = DECLARED[name]
    return high * 1e-3 if x == 0 and (declared.switch or declared.slider_from_zero) else x


def _takes(setup, name, value, end, base, integrator, scales=None) -> float | None:
    """The value, `end` or the nearest towards `value` the physics allows where it refuses `end`
    itself, for which the program is the file's but for the constant's line; None if none is."""
    for probe in _probes(value, end):
        verdict = _same_program(setup, name, probe, base, integrator, scales)
        if verdict is not None:
            return probe if verdict else None
    return None


def switched_off(setup, names) -> dict[str, float]:
    """The constants among `names` at 0 that switch a force off (a switch, or a slider from 0) in
    `setup`, each with a value just above 0 that switches it on: a thousandth of its slider's span."""
    found = {}
    for name in names:
        value = setup.values.get(name)
        declared = DECLARED.get(name)
        if declared is None or value != 0 or not (declared.switch or declared.slider_from_zero):
            continue
        default = setup.constants[name].value if name in setup.constants else None
        found[name] = slider_range(name, 0.0, default if isinstance(default, (int, float)) else None)[1] * 1e-3
    return found


def page_setup(setup, view: dict):
    """The set-up the page's programs are written for: `setup`, with each force that a slider of the
    file's set-up or of a preset's would switch on from 0 switched on (switched_off); the page
    writes the file's 0 back into the line."""
    names = set(slider_names(setup, view))
    for label, _ in catalog.presets(setup, whole=False):
        try:
            names |= set(slider_names(setup.with_preset(label), view))
        except ValueError:
            continue
    probes = switched_off(setup, sorted(names))
    if not probes:
        return setup
    switched = setup.with_values(**probes)
    try:
        switched.build()
        _program(switched, None)
    except (ValueError, ProgramError):
        return setup
    return switched


def sliders(setup, view: dict, offered: dict[str, Settable]) -> dict[str, dict]:
    """The page's sliders: the local page's (scenes/_sliders.py), for the constants this file can
    change: the slider names of the file's set-up, and of every preset's."""
    names = list(slider_names(setup, view))
    for label, _ in catalog.presets(setup, whole=False):
        try:
            names += [name for name in slider_names(setup.with_preset(label), view) if name not in names]
        except ValueError:
            continue
    made = {}
    for name in names:
        if name not in offered:
            continue
        value, default = offered[name].own, offered[name].scene_default
        values = round_slider_values(name, value, default)
        low, high, step = slider_range(name, value, default)
        made[name] = {"values": values or None, "low": low, "high": high, "step": step}
    return made


def preset_values(setup) -> dict[str, list[float]]:
    """The numbers the scene's presets give each constant: values the page should take (settable's
    `also`)."""
    values = {}
    for _, changes in catalog.presets(setup, whole=False):
        for name, value in changes.items():
            if isinstance(value, (int, float)) and not isinstance(value, bool):
                values.setdefault(name, []).append(float(value))
    return values


def preset_data(setup, view: dict, offered: dict[str, Settable], command: str) -> list[dict]:
    """The scene's presets as the page offers them: each one's label, the values it sets (a number,
    or {"expression": ...} for critical damping, worked out by the program from m and k), the
    sliders the local page shows for it, and, where this file cannot run it, why not (`why`), with
    the command that writes a file that can."""
    found = []
    model = setup.build()
    constants = ProgramConstants(setup, model.state.count, model.forces)
    damping = constants.roles.get(Role.DAMPING)   # the constant a preset of critical damping works out (b = None)
    for label, changes in catalog.presets(setup, whole=False):
        values, why = {}, ""
        for name, value in changes.items():
            if name == damping and value is None and name in offered:
                values[name] = {"expression": critical_line(constants)}
            elif name in offered and isinstance(value, (int, float)) and \
                    offered[name].file_low <= value <= offered[name].file_high:
                values[name] = float(value)
            elif value != setup.values.get(name):
                why = (f"this file cannot set {name} = {value}; write a file with it: "
                       f"{command} --preset {label.split(':')[0]!r}")
                break
        try:
            shown = slider_names(setup.with_preset(label), view)
        except ValueError as problem:
            why = why or str(problem)
            shown = []
        found.append({"label": label, "values": values, "sliders": [name for name in shown if name in offered],
                      "why": why})
    return found

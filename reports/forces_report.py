"""--forces, and the forces line of --constants: every force a scene accepts, switched on or off.

Read from the forces' own declarations (physics/forces/): each one's LABEL, the law its docstring
opens with, its constants (the names --set takes, with their units and the scene's values) and
which of them a slider moves while the force is on. A force is on where it is in the scene's model;
a single-mass scene accepts every force a constant can switch on (Force.SINGLE_MASS), so a force
added in a new module is listed with no edit here.

    forces in vertical (on: in this run; off: --set switches it on):
      spring   on   F = −k (|L| − L0) L̂     k = 40 N/m (slider), L0 = 1 m, anchor = < 0, 0, 0 > m
      damping  off  F = −b v                 b = 0 kg/s (slider when on)
"""
from __future__ import annotations

import inspect

from physics.forces import FORCES, Force
from scenes import Setup, format_value


def accepted(setup: Setup, model) -> list[tuple[type, bool]]:
    """(force class, on) for every force the scene accepts, in the order the forces were declared:
    the forces in its model (on), and, where a single-mass scene takes every force's constants,
    the others it can switch on (off)."""
    on = list(dict.fromkeys(type(force) for force in model.forces if isinstance(force, Force)))
    switchable = [cls for cls in FORCES if cls.SINGLE_MASS and cls.CONSTANTS]     # a constant switches it on
    takes_all = all(name in setup.values for cls in switchable for name in cls.CONSTANTS)
    known = [cls for cls in FORCES if cls in on or (takes_all and cls in switchable)]
    return [(cls, cls in on) for cls in known] + [(cls, True) for cls in on if cls not in FORCES]


def law(cls) -> str:
    """The law a force's docstring opens with (its first line that starts with F), up to its comma:
    `F = −b v`; else the docstring's first line."""
    lines = [line.strip() for line in (inspect.getdoc(cls) or "").splitlines()]
    found = next((line for line in lines if line.startswith("F")), lines[0] if lines else "")
    return found.split("  ")[0].rstrip(",")


def label(cls) -> str:
    return cls.LABEL or cls.__name__


def forces_line(setup: Setup, model) -> str:
    """The line of --constants naming the forces on and off: `forces: spring, gravity on; damping,
    drag, driving off (--set switches one on; --forces lists their constants)`."""
    found = accepted(setup, model)
    on = [label(cls) for cls, is_on in found if is_on]
    off = [label(cls) for cls, is_on in found if not is_on]
    text = f"forces: {', '.join(on) or 'none'} on"
    if off:
        text += f"; {', '.join(off)} off (--set switches one on; --forces lists their constants)"
    return text


def _constant(setup: Setup, name: str, declared, *, on: bool) -> str:
    """`k = 40 N/m (slider)`: a constant with the scene's value; one the scene's build works out
    for itself (a row's anchors, resonance's ω per spring) is `anchor in m: the scene's own`."""
    shown = f"{name} ({declared.symbol})" if declared.symbol and declared.symbol != name else name
    if name not in setup.values:
        unit = f" in {declared.unit}" if declared.unit != "1" else ""
        return f"{shown}{unit}: the scene's own"
    text = f"{shown} = {format_value(setup.values[name], declared.unit)}"
    if declared.slider and name in setup.constants:
        text += " (slider)" if on else " (slider when on)"
    return text


def forces_report(setup: Setup, model) -> str:
    """--forces: one line per force the scene accepts, on or off, with its law and constants, and the
    forces kept for scenes of their own (friction, which needs a table)."""
    found = accepted(setup, model)
    rows = [(label(cls), "on" if is_on else "off", law(cls),
             ", ".join(_constant(setup, name, declared, on=is_on) for name, declared in cls.CONSTANTS.items())
             + ("" if cls.closed_form is not Force.closed_form else "; no closed form"))
            for cls, is_on in found]
    widths = [max(len(row[i]) for row in rows) for i in range(3)] if rows else [0, 0, 0]
    lines = [f"forces in {setup.name} (on: in this run; off: --set switches it on):"]
    lines += [f"  {name:<{widths[0]}}  {state:<{widths[1]}}  {text:<{widths[2]}}  {constants}".rstrip()
              for name, state, text, constants in rows]
    own = [label(cls) for cls in FORCES if not cls.SINGLE_MASS and cls not in {cls for cls, _ in found}]
    if own:
        lines.append(f"in scenes of their own: {', '.join(own)}")
    return "\n".join(lines)

"""The handed-out program's momentum and net-force arrows, as the page draws them.

The program (export/vpython_program.py) gets, after its objects, the two scales (the page's, from
export/arrows.py, written in a comment) and an arrow per mass for p and for F_net in the page's
colours (export/palette.py); and, in its loop right after each mass's update, the lines that move
them:

    pscale = 1/20          # m per kg·m/s: an arrow 1 m long is 20 kg·m/s
    parrow = arrow(pos=pos, axis=pscale*p, color=vector(0.95, 0.88, 0.2), shaftwidth=0.2*radius)
    ...
        parrow.pos = pos
        parrow.axis = pscale*p                  # the momentum just updated

F_net's arrow shows Fnet, the net force the update just used. The arrows only read the state, so
the program's arithmetic stays the engine's. Only p and F_net are written: the page's other
arrows (each force, F∥ and F⊥) are for the page.
"""
from __future__ import annotations

from .arrows import choose_scales
from .lines import commented
from .palette import ARROW_COLOURS

WRITTEN = ("p", "F_net")   # the arrows a program draws


def _colour(rgb) -> str:
    return "vector(" + ", ".join(f"{c:g}" for c in rgb) + ")"


def _names(kind: str) -> tuple[str, str, str]:
    """(arrow variable, scale variable, what it points along) for p or F_net."""
    return ("parrow", "pscale", "p") if kind == "p" else ("Farrow", "Fscale", "Fnet")


def setup_lines(model, *, shown, integrator: str | None, single: bool) -> list[str]:
    """The scales and the arrows, made where each mass starts (after the program's objects)."""
    kinds = [kind for kind in WRITTEN if kind in shown]
    if not kinds:
        return []
    scales = choose_scales(model, integrator=integrator)
    lines = ["", "# ---- the arrows: p and F_net at fixed scales, as on the page ----"]
    if "p" in kinds:
        lines.append(commented(f"pscale = 1/{scales.p_unit:g}",
                               f"m per kg·m/s: an arrow 1 m long is {scales.p_unit:g} kg·m/s"))
    if "F_net" in kinds:
        lines.append(commented(f"Fscale = 1/{scales.F_unit:g}", f"m per N: an arrow 1 m long is {scales.F_unit:g} N"))
    for kind in kinds:
        arrow, scale, along = _names(kind)
        start = f"{scale}*p" if kind == "p" else "vector(0, 0, 0)"   # F_net: from the first update on
        colour = _colour(ARROW_COLOURS[kind])
        if single:
            lines.append(f"{arrow} = arrow(pos=pos, axis={start}, color={colour}, shaftwidth=0.2*radius)")
        else:
            start = start.replace("*p", "*p[i]")
            lines += [f"{arrow}s = []", "for i in range(len(pos)):",
                      f"    {arrow}s.append(arrow(pos=pos[i], axis={start}, color={colour}, shaftwidth=0.2*radius))"]
    return lines


def loop_lines(*, shown, single: bool) -> list[str]:
    """Each arrow moved to its mass and its quantity, right after the mass's update."""
    i = "" if single else "[i]"
    lines = []
    for kind in WRITTEN:
        if kind in shown:
            arrow, scale, along = _names(kind)
            name = f"{arrow}{'' if single else 's[i]'}"
            quantity = f"p{i}" if kind == "p" else "Fnet"
            lines += [f"{name}.pos = pos{i}",
                      commented(f"{name}.axis = {scale}*{quantity}",
                                "the momentum just updated" if kind == "p" else "the net force the update used")]
    return lines

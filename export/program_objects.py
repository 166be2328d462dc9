"""What a program draws: the support, a helix per spring, a sphere per mass, the position graph,
in the palette the page uses (export/palette.py)."""
from __future__ import annotations

import numpy as np

from .lines import commented, listed, number
from .palette import CURVE_COLOURS, MASS_COLOURS, mass_colours, shade, simulation_width
from .program_masses import LABELLED, anchor, mass_count


def objects(model, view, constants, single: bool) -> list[str]:
    """The support box, a helix per spring, a sphere per mass and the position graph."""
    anchors = np.broadcast_to(model.anchors, model.state.r.shape)
    points = [anchors, model.state.r]
    if model.exact is not None:   # where the masses go over the first 20 s, as the page frames it
        points.append(np.reshape(model.exact(np.linspace(0.0, 20.0, 401))[0], (-1, 3)))
    points = np.concatenate(points)
    points = points[np.all(np.isfinite(points), axis=1)]
    size = max(float(np.max(points.max(axis=0) - points.min(axis=0))), 1e-3)
    gaps = [np.linalg.norm(a - b) for j, a in enumerate(anchors) for b in anchors[j + 1:]]
    radius = min([0.08 * size] + [0.3 * gap for gap in gaps if gap > 0])
    thick = 0.4 * radius
    low, high = points.min(axis=0) - 2 * radius, points.max(axis=0) + 2 * radius
    centre = 0.5 * (low + high)
    if view["support"] == "wall":
        x = float(anchors[:, 0].min())
        box = (f"box(pos=vector({_round(x - thick / 2)}, {_round(centre[1])}, {_round(centre[2])}), "
               f"size=vector({_round(thick)}, {_round(high[1] - low[1])}, {_round(2 * radius)}), color=color.gray(0.6))")
    else:
        y = float(anchors[:, 1].max())
        box = (f"box(pos=vector({_round(centre[0])}, {_round(y + thick / 2)}, {_round(centre[2])}), "
               f"size=vector({_round(high[0] - low[0])}, {_round(thick)}, {_round(2 * radius)}), color=color.gray(0.6))")
    n = constants.name
    axes = list(view["plot"])
    graph = f"graph(title=\"Position\", xtitle=\"t (s)\", ytitle=\"{', '.join(axes)} (m)\")"
    lines = [commented(f"radius = {_round(radius)}", "m: size of the sphere (display only)"),
             commented(box, "the support")]
    colour = _colour(MASS_COLOURS[0])
    if single:
        axis_curves = [f"gcurve(color={_colour(shade(MASS_COLOURS[0], k))}, width={number(simulation_width(0, 1))}, "
                  f"label=\"{axis}\")" for k, axis in enumerate(axes)]
        lines += [f"spring = helix(pos=anchor, axis=r0 - anchor, radius=0.45*radius, thickness=0.12*radius, "
                  f"coils={view['coils']})",
                  f"ball = sphere(pos=r0, radius=radius, color={colour}"
                  + (", make_trail=True, retain=300)" if view.get("trail") else ")"),
                  commented("pos = r0", "m: position of the mass"),
                  commented(f"p = {n('m')}*v0", "kg·m/s: its momentum"),
                  graph]
        if len(axes) > 1:
            lines += [f"position = [{axis_curves[0]},"] + [f"            {curve}," for curve in axis_curves[1:-1]] + [
                      f"            {axis_curves[-1]}]"]
        else:
            lines.append(commented(f"position = {axis_curves[0]}", "the simulation: thick"))
        return lines
    count = model.state.count
    coils = max(4, min(view["coils"], round(4 * view["coils"] / count)))
    labelled = count <= LABELLED
    palette, each, which = _palette(constants.setup, model, view)
    widths = [simulation_width(i, count, crowded=not labelled) for i in range(count)]
    width = number(widths[0]) if len(set(widths)) == 1 else "widths[i]"
    lines += listed("colours", [_colour(c) for c in palette], f"the palette: one colour {which}")
    if len(set(widths)) > 1:
        lines += listed("widths", [_round(w) for w in widths],
                        "px: each curve wider than the next, so both show where they meet")
    lines += [graph,
              commented("pos = []", "m: position of each mass"),
              commented("p = []", "kg·m/s: momentum of each mass"),
              "springs = []", "balls = []", commented("position = []", "each mass's curve"),
              f"for i in range({mass_count(constants)}):",
              f"    pos.append({n('r0')})",
              f"    p.append({n('m')}*{n('v0')})",
              f"    springs.append(helix(pos={n(anchor(constants))}, axis={n('r0')} - {n(anchor(constants))}, "
              f"radius=0.45*radius, "
              f"thickness=0.12*radius, coils={coils}))",
              f"    balls.append(sphere(pos={n('r0')}, radius=radius, color={each}))",
              f"    position.append(gcurve(color={each}, width={width}"
              + (", label=labels[i]))" if labelled else "))")]
    return lines


def _palette(setup, model, view) -> tuple[list, str, str]:
    """(the colours the program lists, how mass i picks its colour, what a colour stands for), as
    export/palette.py's mass_colours colours the masses on the page: mass i in MASS_COLOURS[i], or
    (resonance) each row of springs in its b's CURVE_COLOURS[row]; the palettes repeat past their end."""
    wanted = [tuple(c) for c in mass_colours(model, view)]
    row = model.per_mass.per_row if model.per_mass is not None else ""   # a row's length, by name
    count, per_row = len(wanted), setup.values.get(row) if row else None
    choices = [(MASS_COLOURS, "i", count, "per mass")]
    if _whole(per_row) and count % int(per_row) == 0:
        choices.append((CURVE_COLOURS, f"i // {row}", count // int(per_row), "per row of b"))
    for palette, index, groups, which in choices:
        group = (lambda i: i) if index == "i" else (lambda i: i // int(per_row))
        if [palette[group(i) % len(palette)] for i in range(count)] == wanted:
            repeat = " % len(colours)" if groups > len(palette) else ""
            return list(palette[:groups]), f"colours[{index}{repeat}]", which
    return wanted, "colours[i]", "per mass"


def _colour(rgb) -> str:
    """A palette colour (export/palette.py) as the program writes it: vector(1, 0.55, 0.1)."""
    return "vector(" + ", ".join(_round(c) for c in rgb) + ")"


def _round(x: float) -> str:
    """A display size, to 3 significant figures (the physics numbers are written exactly)."""
    return number(float(f"{float(x):.3g}"))


def _whole(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool) and float(x).is_integer() and x >= 1

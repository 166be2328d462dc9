"""Energy bars, as PhET's Energy screen draws them: K, each force's U, and what damping took.

One bar per part of the energy (physics/energy.py's energy_parts), moving with the run:

    K                 kinetic energy
    U spring, ...     each conservative force's potential energy, measured from the equilibrium
                      (physics/equilibrium.py), so the bars stay the size of the swing rather
                      than of a large m g h
    −W_nc (damping)   the energy the non-conservative forces took (W_nc from the engine's meter),
                      named after the forces present that do that work
    total             their sum, E − W_nc: level wherever the energy principle holds

Each force is named by its arrow label (export/arrows.py's force_name), so a new force, friction
say, gets its bar or its name in −W_nc with no change here. The bars are HTML (18 px text, 22 px
in projector mode), written into a wtext that the page's script (browser/page_layout.py) moves into
the graph place beside the position graph; their scale only widens (browser/axes.py's AxisFit), so
a bar that shrinks is seen to shrink. Each bar's value is written beside it in J.
"""
from __future__ import annotations

import html

import numpy as np

from export.arrows import force_name
from export.palette import BLACK, BLUE, BLUISH_GREEN, REDDISH_PURPLE, SKY_BLUE, VERMILION
from physics.energy import energy_parts

from .axes import AxisFit
from .readout import NO_BREAK

BAR_PIXELS = 360            # px: the bars' span, for the round ends of their scale
K_COLOUR, TAKEN_COLOUR, TOTAL_COLOUR = VERMILION, REDDISH_PURPLE, BLACK
U_COLOURS = (BLUE, SKY_BLUE, BLUISH_GREEN)   # one per force with a potential energy, in the forces' order


def css(rgb) -> str:
    return "#" + "".join(f"{round(255 * c):02x}" for c in rgb)


def energy_text(value: float) -> str:
    """A bar's value: four significant digits and its unit, `−12.34 J`."""
    return f"{value + 0.0:.4g}".replace("-", "−") + f"{NO_BREAK}J"   # + 0.0: −0 J reads 0 J


class EnergyBars:
    """The bars of one scene, drawn while chosen in the graph place (Measure panel's graph menu).

    vp         the vpython module
    model      the scene's Model: its forces, and its equilibrium as the zero of each U
    reference  where the masses rest, (N, D) m, or None (each U as its law puts its zero)
    """

    def __init__(self, vp, *, model, reference):
        self.forces, self.reference = model.forces, reference
        self.text = vp.wtext(text="")      # the page's script moves it beside the graphs
        self.fit = AxisFit(pixels=BAR_PIXELS, pad=0.0)
        self.shown = False
        taken = sorted({force_name(force) for force in model.forces if not force.conservative})
        self.taken_label = "−W_nc" + (f" ({', '.join(taken)})" if taken else "")

    def labels_and_colours(self, parts) -> list[tuple[str, tuple]]:
        named, u = [], 0
        for part in parts:
            if part.kind == "K":
                named.append(("K", K_COLOUR))
            elif part.kind == "U":
                named.append((f"U {force_name(part.force)}", U_COLOURS[u % len(U_COLOURS)]))
                u += 1
            else:
                named.append((self.taken_label, TAKEN_COLOUR))
        return named + [("total", TOTAL_COLOUR)]

    def show(self, shown: bool) -> None:
        self.shown = shown
        if not shown:
            self.text.text = ""

    def clear(self) -> None:
        """A new run: the scale starts again from its first values."""
        self.fit.clear()

    def draw(self, live) -> None:
        """The bars for the run's state now (nothing while not chosen)."""
        if not self.shown:
            return
        parts = energy_parts(live.state, self.forces, live.engine.work, reference=self.reference)
        values = [part.value for part in parts]
        values.append(sum(values))
        self.fit.update([0.0] + values)
        low, high = self.fit.ends or (0.0, 1.0)
        self.text.text = bars_html(list(zip(self.labels_and_colours(parts), values)), low=low, high=high,
                                   measured_from=self.reference is not None, t=float(live.state.t))


def bars_html(bars, *, low: float, high: float, measured_from: bool, t: float) -> str:
    """The bars as HTML: a row each of label, bar (from the zero line) and value, and the scale."""
    span = (high - low) or 1.0
    zero = 100.0 * (0.0 - low) / span
    rows = []
    for (label, colour), value in bars:
        width = 100.0 * abs(value) / span
        start = zero if value >= 0 else zero - width
        bar = (f"<div class='sm-bar' style='left:{start:.2f}%; width:{width:.2f}%; background:{css(colour)}'></div>"
               if np.isfinite(value) else "")
        rows.append(f"<tr><td class='sm-bar-label'>{html.escape(label)}</td>"
                    f"<td class='sm-bar-cell'><div class='sm-bar-zero' style='left:{zero:.2f}%'></div>{bar}</td>"
                    f"<td class='sm-bar-value' data-joules='{value!r}'>{energy_text(value)}</td></tr>")
    title = "<b>Energy</b>" + (", U measured from equilibrium" if measured_from else "")
    scale = f"bars from {energy_text(low)} to {energy_text(high)}, at t = {t:.4g}{NO_BREAK}s"
    return (f"<div class='sm-bars'><div class='sm-bars-title'>{title}</div>"
            f"<table class='sm-bars-table'>{''.join(rows)}</table>"
            f"<div class='sm-bars-scale'>{scale}</div></div>")

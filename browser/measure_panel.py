"""The Measure panel: a lab's tools on the page, in one panel that is closed at first.

    stopwatch   Start/Stop (key S), Lap (L), Clear (C), on simulated time (browser/stopwatch.py)
    period      hidden until its check box is ticked (a class measures it first): the period
                measured from the motion and the formula's 2π/ω_d (physics/period.py)
    lines       natural length, equilibrium and a marker line dragged in the 3-D view
                (browser/reference_lines.py)
    graph       what the graph place under the position graph shows: the energy graph, phase
                space (browser/phase_space.py) or energy bars (browser/energy_bars.py)

and a line saying that a click on any graph reads a point off it, and a second click the
difference (browser/graph_reading.py). Every control queues a message (browser/messages.py) for
the frame loop, as the others do.

The panel's controls are vpython widgets like every other; the page's script gathers them, between
two markers, into one block that the Measure button opens and closes in the browser (and in a
notebook), so the page is no busier than before until a teacher opens it. The keys work while the
panel is open.
"""
from __future__ import annotations

import math

from physics.period import MIN_CYCLES

from .messages import (ChooseGraph, ClearStopwatch, LapStopwatch, ShowLine, ShowPeriod, StartStopwatch)
from .readout import NO_BREAK
from .reference_lines import LINE_NAMES

GRAPH_CHOICES = {"energy graph": "energy", "phase space": "phase", "energy bars": "bars"}
LAPS_SHOWN = 4            # the last few laps; a long list would fill the panel

# Gathers the widgets between each pair of markers into a block of class sm-measure (once per build
# of the controls; a notebook keeps the captions of the scenes it stopped), and opens or closes it
# with its Measure button; window.smMeasureOpen keeps the choice across scenes. Run from the end
# marker's wtext (jQuery runs scripts in the HTML it inserts), and again a few times in the next
# seconds: the widgets were not always all on the page yet when it first ran. The page's layout
# (browser/page_layout.py) calls it too.
GATHER = """<script>(function () {
  window.smMeasure = function (button, open) {
    var box = button && button.__smPanel;
    if (!box) return;
    if (open === undefined) open = box.style.display === 'none';
    window.smMeasureOpen = !!open;
    box.style.display = open ? 'block' : 'none';
    button.textContent = open ? 'Measure \\u25be' : 'Measure \\u25b8';
    button.setAttribute('aria-expanded', open ? 'true' : 'false');
  };
  window.smGather = function () { document.querySelectorAll('.sm-measure-start').forEach(function (start) {
    if (start.dataset.gathered) return;
    var first = start.closest('span[id]') || start, last = first.nextSibling;
    while (last && !(last.querySelector && last.querySelector('.sm-measure-end'))) last = last.nextSibling;
    if (!last) return;
    start.dataset.gathered = '1';
    var box = document.createElement('div');
    box.className = 'sm-measure';
    first.parentNode.insertBefore(box, first.nextSibling);
    while (box.nextSibling && box.nextSibling !== last) box.appendChild(box.nextSibling);
    var button = first.querySelector('.sm-measure-toggle');
    button.__smPanel = box;
    window.smMeasure(button, !!window.smMeasureOpen);
  }); };
  // now, and again shortly: vpython may not have put every widget on the page yet
  window.smGather();
  [100, 500, 2000, 6000].forEach(function (ms) { setTimeout(window.smGather, ms); });
})();</script>"""

TOGGLE = ("<button class='sm-measure-toggle' type='button' aria-expanded='false' "
          "onclick='window.smMeasure && window.smMeasure(this)'>Measure \u25b8</button>"
          "<span class='sm-measure-start'></span>")


class MeasurePanel:
    """The Measure panel's controls and read-outs, for one build of the page's controls.

    vp          the vpython module
    put         queues a message for the frame loop
    period      whether the period is shown (its check box ticked)
    lines       the lines of the 3-D view shown now (browser/reference_lines.py's LINES)
    graph       what the graph place shows now: "energy", "phase" or "bars"
    """

    def __init__(self, vp, put, *, period: bool, lines, graph: str):
        caption = vp.scene.append_to_caption
        vp.wtext(text="").text = TOGGLE
        caption("stopwatch ")
        self.start_button = vp.button(text="Start (S)", bind=lambda _: put(StartStopwatch()))
        caption(" ")
        vp.button(text="Lap (L)", bind=lambda _: put(LapStopwatch()))
        caption(" ")
        vp.button(text="Clear (C)", bind=lambda _: put(ClearStopwatch()))
        caption("  ")
        self.stopwatch_text = vp.wtext(text="")
        caption("\n")
        self.period_box = vp.checkbox(text="period ", checked=period, bind=lambda box: put(ShowPeriod(box.checked)))
        self.period_text = vp.wtext(text="")
        caption("\nlines: ")
        self.line_boxes = {}
        for kind, name in LINE_NAMES.items():
            label = name + (" (click or drag it in the picture)" if kind == "marker" else "") + "  "
            self.line_boxes[kind] = vp.checkbox(text=label, checked=kind in lines,
                                                bind=lambda box, kind=kind: put(ShowLine(kind, box.checked)))
        caption("\ngraph ")
        chosen = next(label for label, kind in GRAPH_CHOICES.items() if kind == graph)
        vp.menu(choices=list(GRAPH_CHOICES), selected=chosen,
                bind=lambda menu: put(ChooseGraph(GRAPH_CHOICES.get(menu.selected, "energy"))))
        caption("  <i>Click a graph to read a point; click a second point for the difference.</i>")
        vp.wtext(text="").text = "<span class='sm-measure-end'></span>" + GATHER

    def show_stopwatch(self, *, reading: float, running: bool, laps: list[float], decimals: int) -> None:
        """The stopwatch's reading and its last laps, and Start or Stop on its button."""
        text = f"<b class='sm-stopwatch'>{reading:.{decimals}f}{NO_BREAK}s</b>"
        if laps:
            shown = laps[-LAPS_SHOWN:]
            first = len(laps) - len(shown) + 1
            text += "   laps: " + ", ".join(f"{first + n}: {lap:.{decimals}f}{NO_BREAK}s"
                                             for n, lap in enumerate(shown))
        if self.stopwatch_text.text != text:
            self.stopwatch_text.text = text
        label = "Stop (S)" if running else "Start (S)"
        if self.start_button.text != label:
            self.start_button.text = label

    def show_period(self, text: str) -> None:
        if self.period_text.text != text:
            self.period_text.text = text


def seconds(value: float, digits: int = 5) -> str:
    return f"{value:.{digits}g}{NO_BREAK}s"


def with_spread(value: float, spread: float) -> str:
    """`3.13634 ± 0.000088 s`: the spread to two significant digits, the value to the same decimal
    place (at least four significant digits), both plain decimals."""
    if not spread > 0:
        return f"{value:.6g} ± 0{NO_BREAK}s"
    place = 1 - math.floor(math.log10(spread))          # decimals of the spread's second digit
    place = max(place, 3 - math.floor(math.log10(abs(value))) if value else place)
    decimals = max(0, place)
    return f"{value:.{decimals}f} ± {spread:.{max(0, 1 - math.floor(math.log10(spread)))}f}{NO_BREAK}s"


def period_text(period, *, crossings: int, formula: float | None, why: str, axis: str, centre: float) -> str:
    """One mass's period for the panel: measured (mean ± spread over the cycles so far, from the
    upward crossings of its equilibrium; physics/period.py) and the formula's, or why not."""
    if period is not None:
        said = (f"T = {with_spread(period.measured, period.spread)} over {period.cycles} cycles "
                f"({axis} rising through {centre:.4g}{NO_BREAK}m)".replace("-", "−"))
    elif centre != centre:   # nan: no equilibrium
        said = "T: none, the motion has no equilibrium to swing about"
    else:
        said = (f"T: needs {MIN_CYCLES} whole cycles ({crossings} of the {MIN_CYCLES + 1} upward crossings "
                f"of {axis} = {centre:.4g}{NO_BREAK}m so far)".replace("-", "−"))
    if formula is not None and formula == formula:
        said += f"; formula 2π/ω<sub>d</sub> = {seconds(formula)}"
    else:
        said += f"; no formula: {why}" if why else ""
    return said

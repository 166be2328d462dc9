"""Phase space: velocity against position of the scene's coordinate, as myPhysicsLab plots it.

An undamped oscillator traces an ellipse (½ m v² + ½ k x² = E), damping makes it spiral in to the
equilibrium, a drive pulls it out to the ellipse of its steady swing. Each mass's simulated
curve is drawn thick in its colour, and the closed form's, where one exists, thin and dark on top
(as on the position graph), over the last three periods of the slowest spring (the last 30 s of a
fast swing were a solid ring). The graph takes the place
of the energy graph when chosen in the Measure panel (browser/measure_panel.py).
"""
from __future__ import annotations

import numpy as np

from export.palette import EXACT_COLOUR, EXACT_WIDTH, simulation_width
from physics.stability import rates

from .axes import AxisFit
from .clock import Trace


CYCLES = 3           # the curves keep this many periods of the slowest spring: older loops would fill the graph
SHORTEST = 2.0       # s: the least they keep


def phase_span(model, window: float) -> float:
    """How many seconds of motion the curves keep: CYCLES periods of the slowest spring (2π/√(k/m)),
    between SHORTEST and the graphs' window."""
    omega = rates(model.forces, model.state.m).omega
    slowest = float(np.min(omega[omega > 0])) if np.any(omega > 0) else 0.0
    return window if not slowest else min(window, max(SHORTEST, CYCLES * 2 * np.pi / slowest))


class PhaseSpace:
    """v against x of one coordinate, for the graphed masses, over the last `span` seconds.

    vp       the vpython module
    model    the scene's Model (labels, closed form)
    graphed  the masses shown (Graphs.graphed)
    colours  each mass's colour (export/palette.py's mass_colours)
    axis     the coordinate, 0, 1 or 2 for x, y, z
    span     s of motion kept; size: (width, height) px, as the other graphs
    """

    def __init__(self, vp, *, model, graphed, colours, axis: int, span: float, size, canvas_height: float,
                 exact: bool):
        self.vp, self.axis, self.graphed = vp, axis, list(graphed)
        span = phase_span(model, span)
        name = "xyz"[axis]
        width, height = size
        self.graph = vp.graph(title="Phase space", xtitle=f"{name} (m)", ytitle=f"v_{name} (m/s)",
                              width=width, height=height, align="left", fast=True)
        self.x_fit, self.v_fit = AxisFit(pixels=width), AxisFit(pixels=canvas_height)
        self.curves = []     # (gcurve, Trace of (t, x, v), mass, exact?)
        count = len(self.graphed)
        for n, i in enumerate(self.graphed):
            label = f"v_{name} {model.labels[i]}" if count > 1 else f"v_{name} (simulation)"
            line = vp.gcurve(graph=self.graph, label=label if count <= 6 else "", color=vp.vector(*colours[i]),
                             width=simulation_width(n, count, crowded=count > 6))
            self.curves.append((line, Trace(span=span), i, False))
        if exact:
            for n, i in enumerate(self.graphed):
                line = vp.gcurve(graph=self.graph, label="exact" if n == 0 else "", color=vp.vector(*EXACT_COLOUR),
                                 width=EXACT_WIDTH)
                self.curves.append((line, Trace(span=span), i, True))

    def plot(self, samples, live, *, redraw: bool = False) -> None:
        """Add the samples' (x, v) to each curve, and the closed form's beside them."""
        from .graphs import replace_points

        if not samples and not redraw:
            return
        t = np.array([s.t for s in samples])
        x = np.array([s.r[:, self.axis] for s in samples]).reshape(len(samples), -1)
        v = np.array([s.p[:, self.axis] / live.state.m for s in samples]).reshape(len(samples), -1)
        exact = live.model.exact_where_valid(t) if len(t) and any(e for *_, e in self.curves) else None
        shown = []
        for line, trace, i, is_exact in self.curves:
            if is_exact:
                xs, vs = (exact[0][:, i, self.axis], exact[1][:, i, self.axis]) if exact is not None else ((), ())
            else:
                xs, vs = x[:, i], v[:, i]
                if i in live.runaways:
                    continue
            points = [[float(a), float(b), float(c)] for a, b, c in zip(t, xs, vs)
                      if np.isfinite(b) and np.isfinite(c)]
            shown += points
            if trace.add(points) or redraw:
                replace_points(line, [[b, c] for _, b, c in trace.points])
            elif points:
                line.plot([[b, c] for _, b, c in points])
        for fit, values, end in ((self.x_fit, [p[1] for p in shown], "x"), (self.v_fit, [p[2] for p in shown], "y")):
            ends = fit.update(values)
            if ends is not None:
                setattr(self.graph, f"{end}min", ends[0])
                setattr(self.graph, f"{end}max", ends[1])

    def latest(self) -> list:
        """The last (x, v) point of each curve, for the tests: [(mass, exact?, x, v), ...]."""
        return [(i, e, trace.points[-1][1], trace.points[-1][2]) for _, trace, i, e in self.curves if trace.points]

    def clear(self) -> None:
        from .graphs import replace_points

        self.x_fit.clear()
        self.v_fit.clear()
        for line, trace, *_ in self.curves:
            trace.clear()
            replace_points(line, [])

    def take_down(self) -> None:
        self.graph.delete()

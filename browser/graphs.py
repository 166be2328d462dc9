"""The page's graphs: position and energy against time, the scene's own graph, and the CSV of them.

Position: the simulation thick in each mass's colour, the exact solution thin and dark on top
(export/palette.py, shared with --plot). Energy: K, U, E and E − W_nc, measured from rest at
equilibrium where the run starts there, or each mass's own E where masses use different
integrators. Their time axis first fits the run so far (a few Steps after Reset fill the graph;
browser/axes.py's time_axis), then scrolls through the last VIEW["window"] seconds (browser/clock.py's
Trace and window) and widen their y axes to round ticks (browser/axes.py).

A scene may add its own graph with ``view_graph(setup)`` returning a dict: title, xtitle, ytitle
(with units), xmin/xmax/ymin/ymax, "lines" and "dots" as lists of (label, xs, ys, j), drawn in the
palette's curve_colour(j), and optionally "live": a function (model, state) -> (xs, ys) drawn as
dots in LIVE_COLOUR that follow the run (scenes/resonance.py draws its resonance curves this way).
Each mass's curves have its colour from export/palette.py's mass_colours, as its sphere has.
"""
from __future__ import annotations

import csv
import io
import math
import time
from collections import deque
from dataclasses import dataclass

import numpy as np

from export.numbers import CSV_HEADER, ENERGY_KEYS, clean, clean_time
from export.palette import BLUE as DATA_COLOUR  # the measured points, as in --data --plot
from export.palette import (ENERGY_COLOURS, EXACT_COLOUR, EXACT_WIDTH, LIVE_COLOUR, curve_colour, energy_label,
                            mass_colours, shade, simulation_width)
from physics.energy import kinetic, potential, rest_potential
from physics.state import State, velocity

from .axes import AxisFit, data_window, nice_range, time_axis
from .energy_bars import EnergyBars
from .phase_space import PhaseSpace
from .error_envelope import PeriodMax, periods
from .clock import Trace, window
from .page_layout import NOTE_MARK
from .readout import length_text

SAMPLE_EVERY = 0.05       # s of simulation time between graph points
LEGEND_MASSES = 6         # more masses than this: no legend entry per mass
GRAPH_SIZE = (580, 290)   # px
NARROW_GRAPH_WIDTH = 440  # px: three graphs side by side fit a 1400-px window (a projector's 1440 × 900)
GRAPH_CANVAS_HEIGHT = GRAPH_SIZE[1] + 26  # px: vpython adds room for the title; flot spaces ticks by this
LIVE_EVERY = 0.5          # s of wall time between redraws of a scene graph's live dots
HELD = ("position", "exact")   # the kinds of curve a time axis held over measured points keeps whole
ENERGY_KINDS = ("energy", "mass_energy")
PLACES = ("energy", "phase", "bars")   # what the graph place under the position graph may show


@dataclass(frozen=True)
class Series:
    """What one curve of the graphs plots, one value per sample:

    kind   "position": coordinate `axis` (0, 1, 2 for x, y, z) of mass `mass`, m;
           "exact": the same from the closed form; "error": log₁₀ of the largest |x − x_exact| of
           that mass over the last period (browser/error_envelope.py);
           "energy": the system's energy `key` (K, U, E or E_minus_W_nc), J;
           "mass_energy": mass `mass`'s own E = K + U, J
    """

    kind: str
    mass: int | None = None
    axis: int | None = None
    key: str | None = None


@dataclass
class Curve:
    """One curve on the page: its vpython gcurve (line), the points it keeps (trace), what it plots."""

    line: object
    trace: Trace
    series: Series


class Graphs:
    """The graphs of one scene, empty at t = 0, and the samples they show (for Download CSV).

    vp      the vpython module
    setup   the scene as configured (setup.hooks.view_graph, if the scene has one)
    model   the Model built from it
    view    the scene's VIEW merged with the defaults (plot, exact, window)
    """

    def __init__(self, vp, *, setup, model, view: dict, place: str = "energy", reference=None):
        self.vp, self.setup = vp, setup
        self.span = float(view["window"])
        self.spacing = max(model.dt, SAMPLE_EVERY)   # s between graph points
        self.axes = ["xyz".index(axis) for axis in view["plot"]]
        self.position_fit = AxisFit(pixels=GRAPH_CANVAS_HEIGHT)
        self.energy_fit = AxisFit(pixels=GRAPH_CANVAS_HEIGHT)
        self.recorded: deque = deque()  # the samples the graphs show, for Download CSV
        self.curves: list[Curve] = []  # every curve of the graphs, and what it plots
        self.colours = mass_colours(model, view)  # each mass's, as in the 3-D view
        # the masses the position graph shows (VIEW["graphed"]: resonance's few chosen springs)
        self.graphed = list(view["graphed"](model)) if view.get("graphed") else list(range(model.state.count))
        # VIEW["hold"]: the graphs stop at the end of their window instead of scrolling
        self.hold = bool(view.get("hold"))
        has_own = setup.hooks.view_graph is not None
        self.size = (NARROW_GRAPH_WIDTH if has_own else GRAPH_SIZE[0], GRAPH_SIZE[1])
        # The scene's own graph is made first and filled at once, so it comes first on the page
        # (vpython places a graph when its first points arrive).
        self.scene_graph, self.scene_series, self.live_dots, self.live_points = None, [], None, None
        self.live_drawn = -math.inf
        if has_own:
            self._build_scene_graph(setup.hooks.view_graph(setup))
        self.position_graph = self._build_position_graph(model)
        self.data_dots, self.data_values = None, []   # measured points (show_data), on top of the curves
        self.beside_values = []     # y values of a curve drawn beside ours (keep_on_axis): the run before a force
        self.exact_labels: dict = {}   # the exact curves' legend entries, while a run has no closed form
        self.held = None    # (start, end), s: the position graph's time axis held over the measured points
        self.exact_curves = bool(view["exact"]) and model.exact is not None
        self.show_exact = self.exact_curves
        if self.show_exact:
            self._add_exact_curves(model)
        # VIEW["error"]: each mass's error envelope over that many seconds (integrators: each method's order)
        self.error_span = float(view["error"]) if view.get("error") and self.exact_curves else None
        self.error_fit = AxisFit(pixels=GRAPH_CANVAS_HEIGHT)
        self.error_windows = [PeriodMax(period) for period in periods(model)]
        self.error_graph = self._build_error_graph(model) if self.error_span else None
        # What the energy graph shows, so that it tells the story (what would fill it otherwise):
        # one method per mass: each mass's own E = K + U (summed, euler's runaway would swamp it);
        # a system that starts at rest at equilibrium: energies measured from there (else a large
        # constant m g h would flatten every curve).
        self.per_mass_energy = bool(model.integrators)
        self.energy_offset = 0.0 if self.per_mass_energy else (rest_potential(model.state, model.forces) or 0.0)
        self.energy_note = view.get("energy_note")  # VIEW["energy_note"]: a line under the energy graph
        # The graph place under the position graph (Measure panel): the energy graph, phase
        # space or energy bars, one at a time.
        self.place = place if place in PLACES else "energy"
        self.energy_graph = self._build_energy_graph(model, setup) if self.place == "energy" else None
        self.phase = self._build_phase(model) if self.place == "phase" else None
        self.bars = EnergyBars(vp, model=model, reference=reference)
        self.bars.show(self.place == "bars")
        self.titles_text = vp.wtext(text="")
        self._publish_titles()

    @property
    def graphs(self) -> list:
        """The vpython graphs on the page, in the order they are shown."""
        return [graph for graph in (self.scene_graph, self.position_graph, self.error_graph, self.energy_graph,
                                    self.phase.graph if self.phase else None) if graph is not None]

    # ---- building ----

    def _build_phase(self, model) -> PhaseSpace:
        return PhaseSpace(self.vp, model=model, graphed=self.graphed, colours=self.colours, axis=self.axes[0],
                          span=self.span, size=self.size, canvas_height=GRAPH_CANVAS_HEIGHT,
                          exact=self.exact_curves)

    def _build_scene_graph(self, spec) -> None:
        """The scene's own graph (view_graph): lines and dots, and dots that follow the run."""
        vp = self.vp
        width, height = self.size
        self.scene_graph = vp.graph(title=spec["title"], xtitle=spec["xtitle"], ytitle=spec["ytitle"],
                                    width=width, height=height, align="left", fast=True)
        for label, _, _, j in spec.get("lines", []):
            self.scene_series.append(vp.gcurve(graph=self.scene_graph, label=label,
                                               color=vp.vector(*curve_colour(j)), width=2))
        for label, _, _, j in spec.get("dots", []):
            self.scene_series.append(vp.gdots(graph=self.scene_graph, label=label,
                                              color=vp.vector(*curve_colour(j)), radius=3))
        if "live" in spec:
            self.live_dots = vp.gdots(graph=self.scene_graph, label=spec.get("live_label", ""),
                                      color=vp.vector(*LIVE_COLOUR), radius=5)
        self._fill_scene_graph(spec)

    def _fill_scene_graph(self, spec) -> None:
        """Put a view_graph spec's points and labels into the scene graph's curves and dots."""
        graph = self.scene_graph
        for axis, pixels in (("x", self.size[0]), ("y", GRAPH_CANVAS_HEIGHT)):
            low, high = spec.get(f"{axis}min"), spec.get(f"{axis}max")
            if low is not None and high is not None:  # widened to round ticks
                low, high = nice_range(low, high, pixels=pixels)
            for key, value in ((f"{axis}min", low), (f"{axis}max", high)):
                if value is not None:
                    setattr(graph, key, value)
        for series, (label, xs, ys, _) in zip(self.scene_series, spec.get("lines", []) + spec.get("dots", [])):
            replace_points(series, [[float(x), float(y)] for x, y in zip(xs, ys)])
            if series.label != label:
                series.label = label
        self.live_points = spec.get("live")
        if self.live_dots is not None and self.live_dots.label != spec.get("live_label", ""):
            self.live_dots.label = spec.get("live_label", "")

    def _build_position_graph(self, model):
        vp = self.vp
        width, height = self.size
        names = ", ".join("xyz"[axis] for axis in self.axes)
        count = len(self.graphed)
        legend = count <= LEGEND_MASSES  # a long row's legend would hide the graph
        title = ("Position" if count == model.state.count else f"Position of {count} of the "
                 f"{model.state.count} masses") if legend else f"Position of each of the {count} masses"
        graph = vp.graph(title=title, xtitle="t (s)", ytitle=f"{names} (m)",
                         width=width, height=height, align="left", fast=True, xmin=0, xmax=self.span)
        many = model.state.count > 1
        for n, i in enumerate(self.graphed):
            label = model.labels[i]
            for axis in self.axes:
                name = "xyz"[axis] + (f" {label}" if many or len(self.axes) > 1 else " (simulation)")
                name = name if legend else ""
                colour = vp.vector(*shade(self.colours[i], self.axes.index(axis)))
                self._curve(graph, name, colour, Series("position", mass=i, axis=axis),
                            width=simulation_width(n, count, crowded=not legend))
        return graph

    def _add_exact_curves(self, model) -> None:
        """Made after the simulated curves, so drawn on top: thin and dark inside the thick ones."""
        legend = len(self.graphed) <= LEGEND_MASSES
        for n, i in enumerate(self.graphed):
            for axis in self.axes:
                # one legend entry for all the exact curves: they share a colour
                name = f"{'xyz'[axis]} exact" if n == 0 and legend else ""
                self._curve(self.position_graph, name, self.vp.vector(*EXACT_COLOUR), Series("exact", mass=i, axis=axis),
                            width=EXACT_WIDTH)

    def _build_error_graph(self, model):
        """Each mass's error against t, one curve per mass (per method, in integrators): log₁₀ of
        the largest |x − x_exact| over the last period (browser/error_envelope.py), without the
        dips where x crosses x_exact.

        On a logarithmic scale a first-order method's error sits (ωΔt)³ above a fourth-order one's,
        and an error that grows like e^(γt) is a straight line of slope γ / ln 10: euler climbs,
        euler-cromer and verlet grow slowly (their phase drifts), rk4 stays far below them all.
        """
        vp = self.vp
        width, height = self.size
        name = "xyz"[self.axes[0]]
        graph = vp.graph(title="Error of each method, on a log scale", xtitle="t (s)",
                         ytitle=f"log₁₀ of the largest |{name} − {name}_exact| over a period (m)", width=width, height=height, align="left",
                         fast=True, xmin=0, xmax=self.error_span)
        for n, i in enumerate(self.graphed):
            self._curve(graph, model.labels[i], vp.vector(*self.colours[i]), Series("error", mass=i, axis=self.axes[0]),
                        width=3, span=self.error_span)
        return graph

    def _energy_title(self, setup) -> str:
        """The energy graph's title, and after NOTE_MARK the scene's line under it (the page's
        script, browser/page_layout.py, puts that line under the graph)."""
        title = ("Energy of each mass, E = K + U" if self.per_mass_energy else
                 "Energy, measured from rest at equilibrium" if self.energy_offset else "Energy")
        return title + (NOTE_MARK + self.energy_note(setup) if self.energy_note else "")

    def _build_energy_graph(self, model, setup):
        vp = self.vp
        width, height = self.size
        title = self._energy_title(setup)
        graph = vp.graph(title=title, xtitle="t (s)", ytitle="energy (J)",
                         width=width, height=height, align="left", fast=True, xmin=0, xmax=self.span)
        if self.per_mass_energy:
            for i, label in enumerate(model.labels):
                # half the position curves' widths: an energy that wobbles fast would fill a band
                self._curve(graph, f"E {label}", vp.vector(*self.colours[i]), Series("mass_energy", mass=i),
                            width=simulation_width(i, model.state.count) / 2)
        else:
            for key, colour in ENERGY_COLOURS.items():
                # E − W_nc comes last and thinner, so it shows on top of E when no work is done
                label = energy_label(key, from_rest=bool(self.energy_offset))
                self._curve(graph, label, vp.vector(*colour), Series("energy", key=key), width=4 if key == "E" else 2)
        return graph

    def _curve(self, graph, label, colour, series: Series, *, width, span=None) -> None:
        line = self.vp.gcurve(graph=graph, label=label, color=colour, width=width)
        self.curves.append(Curve(line=line, trace=Trace(span=span or self.span), series=series))

    # ---- a new run ----

    def rebuilt(self, setup, model, *, changes: dict) -> None:
        """The model was built again (new constants or integrator): redraw the scene's own graph
        for the new constants, and show the exact curves if the new model has a closed form."""
        if self.scene_graph is not None and changes:
            self._fill_scene_graph(setup.hooks.view_graph(setup))
        self.setup = setup
        if self.energy_graph is not None and self.energy_note and changes and \
                self.energy_graph.title != self._energy_title(setup):
            self.energy_graph.title = self._energy_title(setup)
        self.show_exact = self.exact_curves and model.exact is not None
        for curve in self.curves:    # no legend entry for a closed form the run has not (a force added)
            if curve.series.kind == "exact":
                own = self.exact_labels.setdefault(id(curve), curve.line.label)   # kept before the first change
                shown = own if self.show_exact else ""
                if curve.line.label != shown:
                    curve.line.label = shown
        self.spacing = max(model.dt, SAMPLE_EVERY)   # s between graph points
        self.error_windows = [PeriodMax(period) for period in periods(model)]   # a new m or k: a new period

    def new_reference(self, model, reference) -> None:
        """The energy bars of a rebuilt model: its forces and its equilibrium."""
        shown = self.bars.shown
        self.bars.forces, self.bars.reference = model.forces, reference
        self.bars.show(shown)

    def choose(self, place: str, live) -> None:
        """Show `place` in the graph place ("energy", "phase" or "bars"), filled with the run
        so far (the samples kept for Download CSV)."""
        if place not in PLACES or place == self.place:
            return
        if self.energy_graph is not None:
            self.energy_graph.delete()
            self.energy_graph = None
            self.curves = [curve for curve in self.curves if curve.series.kind not in ENERGY_KINDS]
        if self.phase is not None:
            self.phase.take_down()
            self.phase = None
        self.place = place
        self.bars.show(place == "bars")
        samples = list(self.recorded)
        if place == "energy":
            self.energy_graph = self._build_energy_graph(live.model, self.setup)
            self.energy_fit.clear()
            fresh = [curve for curve in self.curves if curve.series.kind in ENERGY_KINDS]
            energies = self._energies(samples, live)
            self._plot_curves(fresh, samples, live, energies=energies, redraw=True)
            self._fit_energy(energies, live, samples)
        elif place == "phase":
            self.phase = self._build_phase(live.model)
            self.phase.plot(samples, live, redraw=True)
        else:
            self.bars.clear()
            self.bars.draw(live)
        self._publish_titles()

    def _publish_titles(self) -> None:
        """Each graph's axis titles, for reading a graph by clicking it (browser/graph_reading.py),
        keyed by its first curve's label: in a notebook the page's script cannot reach the graphs."""
        titles = {}
        for graph in self.graphs:
            labels = [curve.line.label for curve in self.curves if _on(curve.line, graph)]
            if self.phase is not None and graph is self.phase.graph:
                labels = [line.label for line, *_ in self.phase.curves]
            if graph is self.scene_graph:
                labels = [series.label for series in self.scene_series]
            if labels and labels[0]:
                titles[labels[0]] = [graph.xtitle, graph.ytitle]
        self.titles_text.text = graph_titles_script(titles)

    def clear(self) -> None:
        """Empty every curve and the recorded samples, and show t from 0 again."""
        self.position_fit.clear()
        self.energy_fit.clear()
        self.error_fit.clear()
        for envelope in self.error_windows:
            envelope.clear()
        if self.data_values or self.beside_values:
            _fit(self.position_graph, self.position_fit, self.data_values + self.beside_values)
        for curve in self.curves:
            curve.trace.clear()
        self.recorded.clear()
        if self.phase is not None:
            self.phase.clear()
        self.bars.clear()
        for graph in (self.position_graph, self.energy_graph):
            if graph is not None:
                graph.xmin, graph.xmax = time_axis(0.0, span=self.span, dt=self.spacing, pixels=self.size[0])
        if self.held:
            self.position_graph.xmin, self.position_graph.xmax = self.held
        if self.error_graph is not None:
            self.error_graph.xmin, self.error_graph.xmax = time_axis(0.0, span=self.error_span, dt=self.spacing,
                                                                     pixels=self.size[0])
        self.live_drawn = -math.inf

    def take_down(self) -> None:
        """Remove the graphs from the page."""
        for graph in self.graphs:
            graph.delete()
        self.scene_graph = self.position_graph = self.error_graph = self.energy_graph = self.phase = None
        self.bars.show(False)

    # ---- measured data ----

    def show_data(self, points, *, label: str) -> None:
        """The measured points [[t, position], ...] on the position graph (browser/data_panel.py),
        as dots in DATA_COLOUR; [] takes them off. The position axis widens to hold them."""
        if self.data_dots is None and points:
            self.data_dots = self.vp.gdots(graph=self.position_graph, label=label,
                                           color=self.vp.vector(*DATA_COLOUR), radius=2.5)
        if self.data_dots is not None:
            if self.data_dots.label != label:
                self.data_dots.label = label
            replace_points(self.data_dots, points)
        self.data_values = [y for _, y in points]
        self.held = data_window(points, dt=self.spacing, pixels=self.size[0])
        for curve in self.curves:   # a held curve keeps every point in the window
            if curve.series.kind in HELD:
                curve.trace.span = max(self.span, self.held[1] - self.held[0]) if self.held else self.span
        if points:
            _fit(self.position_graph, self.position_fit, self.data_values)

    def keep_on_axis(self, values) -> None:
        """The y values of a curve another part draws on the position graph (browser/force_box.py:
        the run before a force was added): the axis keeps them in view, through Reset; [] lets go."""
        self.beside_values = [float(v) for v in values if math.isfinite(v)]
        if self.beside_values:
            _fit(self.position_graph, self.position_fit, self.beside_values)

    # ---- plotting ----

    def plot(self, samples, live, *, matter, redraw: bool = False) -> None:
        """Add samples to every curve (a whole curve is resent only when its window scrolls).

        matter  the masses the position axis follows: not those that may run away
                (live.may_run_away), whose own energy does not widen the energy axis either
        """
        if self.hold:
            samples = [sample for sample in samples if sample.t <= self.span + 1e-9]
        if not samples and not redraw:
            return
        self._record(samples)
        t = np.array([s.t for s in samples])
        r = np.array([s.r for s in samples]) if samples else np.zeros((0,) + live.state.r.shape)
        # NaN where the closed form no longer describes a mass (past its anchor): no point there
        exact = live.model.exact_where_valid(t)[0] if (self.show_exact and len(t)) else None
        energies = self._energies(samples, live) if self.energy_graph is not None else {}
        errors_shown = self._plot_curves(self.curves, samples, live, energies=energies, exact=exact, redraw=redraw)
        if exact is not None and np.isfinite(exact[..., self.axes]).any():
            # the exact motion, and the simulated points near it (within the exact span again), so
            # a few Steps after Reset show on the axis while a run that strays far runs off it
            exact_values = exact[..., self.axes].ravel()
            low = min(self.position_fit.seen[0], float(np.nanmin(exact_values)))
            high = max(self.position_fit.seen[1], float(np.nanmax(exact_values)))
            simulated = r[:, matter][..., self.axes].ravel()
            near = simulated[(simulated >= low - (high - low)) & (simulated <= high + (high - low))]
            _fit(self.position_graph, self.position_fit, np.concatenate([exact_values, near]))
        elif len(t):
            _fit(self.position_graph, self.position_fit, r[:, matter][..., self.axes].ravel())
        self._fit_energy(energies, live, samples)
        if self.error_graph is not None:
            _fit(self.error_graph, self.error_fit, errors_shown)
        if len(t):
            start, end = time_axis(float(t[-1]), span=self.span, dt=self.spacing,
                                   pixels=self.size[0])
            graph, (low, high) = self.position_graph, self.held or (start, end)
            if (low, high) != (graph.xmin, graph.xmax):
                graph.xmin, graph.xmax = low, high
            if self.error_graph is not None:
                self.error_graph.xmin, self.error_graph.xmax = time_axis(
                    float(t[-1]), span=self.error_span, dt=self.spacing, pixels=self.size[0])
        if self.phase is not None:
            self.phase.plot(samples, live, redraw=redraw)
        self._plot_live(live, redraw=redraw)

    def _plot_curves(self, curves, samples, live, *, energies: dict, exact=None, redraw: bool = False) -> list:
        """Add the samples to these curves; returns the errors shown on the error graph."""
        t = np.array([s.t for s in samples])
        r = np.array([s.r for s in samples]) if samples else np.zeros((0,) + live.state.r.shape)
        errors_shown = []
        for curve in curves:
            series = curve.series
            if series.kind == "position":
                values = r[:, series.mass, series.axis]
            elif series.kind in ("exact", "error"):
                if exact is None:
                    values = np.zeros(0)
                elif series.kind == "exact":
                    values = exact[:, series.mass, series.axis]
                else:   # the error's envelope: its largest size over the last period (error_envelope.py)
                    values = [self.error_windows[series.mass].add(float(a), float(b)) for a, b in
                              zip(t, r[:, series.mass, series.axis] - exact[:, series.mass, series.axis])]
            elif series.kind == "mass_energy":
                values = energies[series.mass]
            else:
                values = energies[series.key]
            points = [[float(a), float(b)] for a, b in zip(t, values) if math.isfinite(b)
                      and not (self.held and series.kind in HELD and a > self.held[1])]
            if series.kind in ("position", "mass_energy", "error") and series.mass in live.runaways:
                frozen = live.runaways[series.mass][0]  # the curve ends where the mass ran away
                points = [point for point in points if point[0] <= frozen]
            if series.kind == "error":   # the axis: errors over a whole period (euler's too: its climb is the
                whole = self.error_windows[series.mass].period      # lesson); the first period's, from 0 m, ran
                errors_shown += [value for at, value in points if at >= whole]   # to 1e-7 m and squashed them
            if curve.trace.add(points) or redraw:
                replace_points(curve.line, list(curve.trace.points))
            elif points:
                curve.line.plot(points)
        return errors_shown

    def _fit_energy(self, energies: dict, live, samples) -> None:
        """The energy graph's axes: its values (not the masses that may run away), and time."""
        if self.energy_graph is None:
            return
        _fit(self.energy_graph, self.energy_fit,
             [value for key, values in energies.items() if key not in live.may_run_away for value in values])
        if samples:
            low, high = time_axis(float(samples[-1].t), span=self.span, dt=self.spacing, pixels=self.size[0])
            if (low, high) != (self.energy_graph.xmin, self.energy_graph.xmax):
                self.energy_graph.xmin, self.energy_graph.xmax = low, high

    def _energies(self, samples, live) -> dict:
        """What the energy graph plots, per curve key, one value per sample, J.

        K, U, E, E − W_nc of the system (U, E and E − W_nc less energy_offset), or, with one
        integrator per mass, each mass's own E = K + U (key: the mass's index).
        """
        if not self.per_mass_energy:
            return {key: [s.energy[key] - (0.0 if key == "K" else self.energy_offset) for s in samples]
                    for key in ENERGY_COLOURS}
        forces, m = live.model.forces, live.state.m
        per_mass = [kinetic(State(t=s.t, r=s.r, p=s.p, m=m)) + potential(State(t=s.t, r=s.r, p=s.p, m=m), forces)
                    for s in samples]
        return {i: [float(E[i]) for E in per_mass] for i in range(len(m))}

    def live_now(self, live) -> None:
        """The scene graph's live dots at the state now, whenever they were last moved (after a jump)."""
        self._plot_live(live, redraw=True)

    def _plot_live(self, live, *, redraw: bool) -> None:
        """Move the scene graph's live dots to the state now, at most every LIVE_EVERY seconds."""
        if self.live_dots is None:
            return
        now = time.perf_counter()
        if not redraw and now - self.live_drawn < LIVE_EVERY:
            return
        self.live_drawn = now
        xs, ys = self.live_points(live.model, live.state)
        replace_points(self.live_dots, [[float(x), float(y)] for x, y in zip(xs, ys) if math.isfinite(y)])

    def _record(self, samples) -> None:
        """Keep the samples the graphs show (the last `span` seconds), for Download CSV."""
        self.recorded.extend(samples)
        if self.recorded:
            start = window(self.recorded[-1].t, span=self.span)[0]
            while self.recorded and self.recorded[0].t < start - 1e-9:
                self.recorded.popleft()

    # ---- the caption's error readout ----

    def error_readout(self, live, *, matter) -> str:
        """How far the simulation is from the exact solution now, for the caption ('' without one)."""
        if not self.show_exact:
            return ""
        model, state = live.model, live.state
        until = model.exact_valid_until_each(state.t)
        known = [i for i in matter if state.t <= until[i]]
        if not known:
            first = float(np.min(until[matter])) if len(matter) else float(np.min(until))
            return (f"no exact value after t = {first:.3g} s: the closed form "
                    f"stops holding {model.exact_limit}")
        exact = model.exact_where_valid([state.t])[0][0]
        errors = state.r[known][:, self.axes] - exact[known][:, self.axes]
        known_errors = errors[np.isfinite(errors)]
        if not known_errors.size:
            return ""
        if errors.size == 1:
            name = "xyz"[self.axes[0]]
            return f"error {name} − {name}<sub>exact</sub> = {length_text(float(errors.flat[0]), signed=True)}"
        left_out = [model.labels[i] for i in live.may_run_away]
        past = [model.labels[i] for i in matter if i not in known]
        others = (f" ({', '.join(left_out)} left out)" if left_out else "") + \
                 (f" ({', '.join(past)}: past the anchor, no exact value)" if past else "")
        largest = length_text(float(np.max(np.abs(known_errors))))
        return f"largest |error| against the exact solutions = {largest}{others}"


def csv_text(samples, *, m, labels, dt) -> str:
    """The samples as CSV, with the command line's columns (export.numbers.CSV_HEADER).

    One row per sample and mass: t, r, v = p/m, p, then the system's K, U, E, W_nc in J; several
    masses add a `body` column with each mass's label. Numbers as in --csv: t rounded to Δt's
    decimals, the rest to 15 significant digits.
    """
    single = len(labels) == 1
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(CSV_HEADER + ([] if single else ["body"]))
    for sample in samples:
        v = velocity(sample.p, m)
        energy = [clean(sample.energy[key]) for key in ENERGY_KEYS]
        for i, label in enumerate(labels):
            row = [clean_time(sample.t, dt), *map(clean, sample.r[i]), *map(clean, v[i]), *map(clean, sample.p[i]),
                   *energy]
            writer.writerow(row + ([] if single else [label]))
    return out.getvalue()


def _on(line, graph) -> bool:
    """Whether a gcurve is drawn on this graph (vpython keeps the graph's index in line.graph)."""
    where = getattr(line, "graph", None)
    return where is graph or (where is not None and where == getattr(graph, "idx", None))


def graph_titles_script(titles: dict) -> str:
    """A script adding {first curve's label: [xtitle, ytitle]} to the page's window.smGraphTitles."""
    import json

    return ("<script>window.smGraphTitles = Object.assign(window.smGraphTitles || {}, "
            + json.dumps(titles, ensure_ascii=False).replace("</", "<\\/") + ");</script>")


def replace_points(series, points) -> None:
    """Replace all the points of a gcurve or gdots."""
    series.delete()
    series._data = []  # vpython 7.6.5's delete() keeps its Python copy of the points
    if points:
        series.plot(points)


def _fit(graph, fit: AxisFit, values) -> None:
    """Widen a graph's y axis, to round ticks, when the values leave it (browser/axes.py).

    The position axis follows the exact motion where there is one: a numerical curve that
    strays far from it runs off the graph, rather than squashing every other curve flat, as
    euler's growing swing would.
    """
    ends = fit.update(values)
    if ends is not None:
        graph.ymin, graph.ymax = ends

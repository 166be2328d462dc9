"""The browser view of any scene: support, springs and masses in 3-D, graphs, and classroom controls.

This is the one shared view. A scene file names what to draw in its VIEW dict:

    support   "ceiling" (a box above the anchors) or "wall" (a box beside them)
    plot      the coordinate that moves: "x", "y", "z", or "xyz" for all three
    trail     True draws each mass's path over the last 15 s (default False)
    exact     False hides the exact-solution curve even where a closed form exists (default True)
    sliders   names of the constants that get a slider (default: m and k, and b, F0 and omega
              where the scene switches them on)
    coils     turns drawn in each helix (default 12)
    window    seconds of simulation time the graphs show before they scroll (default 30)

A scene may also give the page one more graph with a function ``view_graph(setup)`` returning a
dict: title, xtitle, ytitle (with units), xmin/xmax/ymin/ymax, "lines" and "dots" as lists of
(label, xs, ys, colour), and optionally "live": a function (model, state) -> (xs, ys) drawn as
dots that follow the run (scenes/resonance.py draws its resonance curves this way).

The view only reads the state. The physics is physics.simulate.stepper (the chosen integrator);
energy is physics.energy; the real-time stepping and the graph windows are browser/clock.py.

How the page behaves, for the teacher:

* Run/Pause, Step (one Δt, pausing first) and Reset (back to the exact initial state, empty
  graphs, W_nc = 0).
* Moving a slider, or picking another integrator, rebuilds the model with that choice and starts
  again from t = 0, so the graphs and the exact curve always describe one run. The caption says so.
* Speed ¼× to 4× scales simulation time against wall-clock time and does not restart.
* The preset menu applies one of the scene's presets (scenes/_catalog.py: Moon, Earth or Jupiter
  gravity, critical damping, the driven scenarios, ...) and starts again from t = 0, with the page
  rebuilt so that every slider shows the new value (a slider's range cannot change in vpython).
* The scene menu switches to another scene in place, with its default constants: the 3-D objects
  of the old scene are hidden, its graphs and controls removed, and the new scene's built.
* The graphs: the simulation thick in each mass's colour, the exact solution thin and dark on
  top (export/palette.py, shared with --plot); every y axis ticks at round steps (browser/axes.py).
  The energy graph shows K, U, E and E − W_nc, measured from rest at equilibrium where the run
  starts there (resonance), or each mass's own E where masses use different integrators.
* A mass the scene expects may run away (euler in `integrators`, LiveRun.runaways) is shown
  frozen where it leaves the picture, labelled with its method and time; the others run on, and
  the camera stays on them. A new constant frames the new motion again.
* Download CSV saves the graphed samples (the last `window` seconds, one row per 0.05 s and mass)
  with the same columns as the command line's --csv: t, x, y, z, vx, vy, vz, px, py, pz, K, U, E,
  W_nc (and body for several masses). The file is made here and handed to the browser as a
  data: link that a one-line script clicks; the link stays on the page as a fallback.
* Download program saves the scene, with the constants, integrator and preset chosen now, as a
  standalone VPython program to hand out (export/, the same as main.py SCENE --vpython FILE.py).
* The graphs show one point per 0.05 s of simulation time (at most 20 per simulated second), in a
  window of the last `window` seconds that scrolls. A curve keeps at most 2 × window × 20 points
  (1,200 for 30 s), so a 30-minute run costs the page no more than a 1-minute run.
* If the page stops asking for updates for more than 5 s (a tab the browser has frozen, a laptop
  that slept), the clock stops and resumes without a jump; a page that is merely slow to draw
  keeps real time (browser/clock.py).

Closing the tab, or Ctrl-C, makes vpython raise SystemExit(0) in this (main) thread; nothing here
catches it, so the program ends with status 0.
"""
from __future__ import annotations

import csv
import io
import math
import queue
import sys
import time
from collections import deque
from dataclasses import dataclass
from urllib.parse import quote

import numpy as np

from export.numbers import CSV_HEADER, ENERGY_KEYS, clean, clean_time
from physics.energy import kinetic, potential, rest_potential
from physics.integrators import INTEGRATORS
from physics.state import State, velocity

from scenes import DECLARED, catalog
from .axes import AxisFit, nice_range
from .clock import LiveRun, RealTimeClock, Sample, StepBudget, Trace, expected_runaways, window
from scenes import format_value
from export.palette import (ENERGY_COLOURS, ENERGY_LABELS, EXACT_COLOUR, EXACT_WIDTH, mass_colour, shade,
                      simulation_width)

FRAME_RATE = 50           # frames per second the loop aims for
SAMPLE_EVERY = 0.05       # s of simulation time between graph points
LEGEND_MASSES = 6         # more masses than this: no legend entry per mass
SPEEDS = {"¼×": 0.25, "½×": 0.5, "1×": 1.0, "2×": 2.0, "4×": 4.0}
SLIDER_CHOICES = ("m", "k", "b", "F0", "omega")
DEFAULT_VIEW = {"support": "ceiling", "plot": "y", "trail": False, "exact": True, "coils": 12,
                "window": 30.0}

CANVAS_SIZE = (900, 440)  # px
GRAPH_SIZE = (580, 290)   # px
NARROW_GRAPH_WIDTH = 440  # px: three graphs side by side fit a 1400-px window (a projector's 1440 × 900)
GRAPH_CANVAS_HEIGHT = GRAPH_SIZE[1] + 26  # px: vpython adds room for the title; flot spaces ticks by this
# Larger text than vpython's default, for a projector at the back of a classroom.
# A row of graphs that wraps leaves room under the x-axis titles for the next row's titles.
PAGE_STYLE = ("<style>body { font-size: 17px; } button, select { font-size: 17px; }"
              " .glowscript-graph { margin-bottom: 36px; }</style>")
PRESET_PROMPT = "choose a preset"
LIVE_EVERY = 0.5          # s of wall time between redraws of a scene graph's live dots
TRAIL_POINTS = 300        # points kept in a trail: the last 15 s at one point per SAMPLE_EVERY
# vpython 7.6.5's page sends a slider's value only when it differs from the last value it sent, and
# before the first move there is none, so the first move of every slider was lost. This script tells
# the page each new slider's starting value, by calling the slider's own change handler once with a
# stand-in for a mouse event (its handlers ignore events without one), so the first move is sent.
# It runs in the page from a wtext (jQuery runs scripts in the HTML it inserts); each slider is primed once.
PRIME_SLIDERS = ("<script>$('.ui-slider').each(function () {"
                 " if (this.dataset.primed) return; this.dataset.primed = '1';"
                 " var change = $(this).slider('option', 'change');"
                 " if (change) change({originalEvent: {}}); });</script>")


def show(setup, *, integrator: str, port: int | None, open_browser: bool, preset: str | None = None) -> int:
    """Show a scene in the browser and run it in real time until the page is closed.

    preset  the label of the preset already applied to `setup` (--preset), shown in the menu.

    Returns 2 (after a one-line message) if the model or the server cannot start; otherwise the
    program ends through SystemExit(0) when the tab closes or on Ctrl-C.
    """
    try:
        model = setup.build()
    except ValueError as problem:
        print(f"error: {problem}", file=sys.stderr)
        return 2
    from .loopback_server import ServerError, start

    try:
        server = start(port=port, open_browser=open_browser)
    except ServerError as problem:
        print(f"error: {problem}", file=sys.stderr)
        return 2
    try:
        SceneView(setup=setup, model=model, integrator=integrator, server=server, preset=preset).run_forever()
    except KeyboardInterrupt:  # Ctrl-C before vpython's own handler turns it into SystemExit(0)
        return 0
    return 0


def scene_menu_choices() -> list[str]:
    """The scene menu: every scene found (scenes/_catalog.py), in menu order."""
    return list(catalog.SCENE_NAMES)


def slider_names(setup, view: dict) -> list[str]:
    """The constants that get a slider: VIEW["sliders"], else m and k and the forces switched on.

    Only plain numbers get one (a vector, or None meaning "derived", does not).
    """
    names = view.get("sliders") or [name for name in SLIDER_CHOICES
                                    if name in ("m", "k") or setup.values.get(name)]
    return [name for name in names if name in setup.constants
            and isinstance(setup.values[name], (int, float)) and not isinstance(setup.values[name], bool)]


def slider_range(name: str, value: float, default: float | None = None) -> tuple[float, float, float]:
    """(min, max, step) around a constant's default: from a tenth of it (or 0) to three times it.

    Constants that must stay positive (m, k, dt, ...) start at a tenth; those where 0 means "off"
    (b, F0, ω, C, g, x0: slider_from_zero in scenes/_constants.py) start at 0. A value outside that range (set by a preset or --set) widens
    it, to one and a half times the value.
    """
    default = value if default is None or not isinstance(default, (int, float)) else default
    declared = DECLARED.get(name)
    low = 0.0 if declared is not None and declared.slider_from_zero else 0.1 * abs(default)
    high = 3.0 * abs(default) if default else 1.0
    low = min(low, value)
    high = max(high, 1.5 * value)
    step = 10 ** math.floor(math.log10((high - low) / 200))
    return low, high, step


def symbol(name: str) -> str:
    """How the page writes a constant: ω for omega, ρ for rho (declared in scenes/_constants.py)."""
    declared = DECLARED.get(name)
    return declared.symbol if declared is not None and declared.symbol else name


def time_decimals(dt: float) -> int:
    """Enough decimals that one step of Δt shows: 2 for Δt = 0.01 s, 4 for Δt = 1e-4 s."""
    return max(2, math.ceil(-math.log10(dt) - 1e-9))


def constants_text(setup) -> str:
    """The scene's constants that are switched on, with units: `m = 10 kg, k = 40 N/m, ...`."""
    parts = []
    for name, constant in setup.constants.items():
        value = setup.values[name]
        if name == "until" or value is None or (not isinstance(value, tuple) and value == 0):
            continue
        if name == "drive_axis" and not setup.values.get("F0"):
            continue
        parts.append(f"{symbol(name)} = {format_value(value, constant.unit)}")
    lines, line = [], ""
    for part in parts:  # wrapped by hand: the caption keeps line breaks but does not wrap
        if line and len(line) + len(part) > 95:
            lines.append(line + ",")
            line = ""
        line = f"{line}, {part}" if line else part
    return "\n".join(lines + [line])


def motion_box(model) -> tuple[np.ndarray, np.ndarray]:
    """Corners (low, high) of the region the masses and anchors use over the first 20 s, m."""
    if model.exact is not None:
        r, _ = model.exact(np.linspace(0.0, 20.0, 801))
    else:
        from physics.simulate import BlowUpError, run
        until = min(10.0, 4000 * model.dt)
        try:
            r = run(model.state, model.forces, dt=model.dt, until=until).r
        except BlowUpError:
            r = model.state.r[None]
    points = np.concatenate([np.reshape(r, (-1, 3)), model.anchors, model.state.r])
    points = points[np.all(np.isfinite(points), axis=1)]
    return points.min(axis=0), points.max(axis=0)


@dataclass(frozen=True)
class StateSample(Sample):
    """A graph sample that also keeps the momenta p (N, 3) kg·m/s, for the CSV download."""

    p: np.ndarray = None


class RecordedRun(LiveRun):
    """LiveRun whose samples carry p as well as r, so the page can offer them as CSV."""

    def sample(self) -> StateSample:
        shown = super().sample()
        return StateSample(t=shown.t, r=shown.r, energy=shown.energy, p=self.state.p)


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


class SceneView:
    """The page: builds a scene's objects, then redraws from the LiveRun once per frame.

    Everything that belongs to one scene (3-D objects, controls, graphs) is made by
    :meth:`_build_page`; switching scene or applying a preset takes it down and builds it again.
    """

    def __init__(self, *, setup, model, integrator: str, server, preset: str | None = None):
        import vpython as vp  # already imported, loopback-only, by loopback_server.start

        self.vp, self.server = vp, server
        self.integrator = integrator
        self.speed = "1×"
        self.commands: queue.SimpleQueue = queue.SimpleQueue()
        self.running = True
        self.clock = RealTimeClock(dt=model.dt, now=time.perf_counter())
        self.budget = StepBudget()
        self.shapes, self.graphs = [], []
        self.page = 0  # which build of the page the controls' clicks come from
        self.downloads = 0
        self.loads_shown = self._page_loads()
        self._build_page(setup, model, preset=preset)

    # ---- building the page ----

    def _build_page(self, setup, model, *, preset: str | None = None) -> None:
        """Take down the old scene's objects, if any, and build this one's, at t = 0."""
        self._take_down()
        self.page += 1
        self.setup = setup
        self.defaults = {name: constant.value for name, constant in setup.constants.items()}
        self.view = {**DEFAULT_VIEW, **getattr(setup.module, "VIEW", {})}
        self.span = float(self.view["window"])
        self.axes = ["xyz".index(axis) for axis in self.view["plot"]]
        self.live = RecordedRun(model, integrator=self.integrator, sample_every=SAMPLE_EVERY)
        self.recorded: deque = deque()
        self.position_fit = AxisFit(pixels=GRAPH_CANVAS_HEIGHT)
        self.energy_fit = AxisFit(pixels=GRAPH_CANVAS_HEIGHT)
        self._build_scene(model)
        self._build_controls(preset)
        self._build_graphs(model)
        self._restart(model)
        self.clock.restart(now=time.perf_counter())

    # ---- a reloaded tab ----

    def _page_loads(self) -> int:
        """How often a page has connected (1 in a notebook, whose server does not count reloads)."""
        return self.server.page_loads() if hasattr(self.server, "page_loads") else 1

    def _page_reloaded(self) -> None:
        """The tab was reloaded (F5): the new page is empty, and vpython cannot send it the objects
        made for the old one, so the scene is built again, from t = 0, on a new canvas.

        vpython's queue of changes is dropped first: they are for the old page's objects, and the
        new page would stop at the first object it does not know.
        """
        from vpython.vpython import baseObj

        loads = self._page_loads()
        baseObj.initialize()
        baseObj.sent = True
        for kept in (baseObj.attach_arrows, baseObj.attach_trails, baseObj.follow_objects):
            kept.clear()
        self.shapes, self.graphs = [], []  # on the old page only: nothing to take down
        self.vp.scene = self.vp.canvas()
        self._build_page(self.setup, self.setup.build())
        self.loads_shown = loads
        self.server.page_built(loads)

    def _take_down(self) -> None:
        """Hide the 3-D objects and remove the graphs and controls of the scene shown so far.

        vpython 7.6.5 cannot delete a 3-D object from the page, so they are hidden; graphs and the
        caption's controls are removed from the page.
        """
        vp = self.vp
        for shape in self.shapes:
            if getattr(shape, "make_trail", False):
                shape.clear_trail()
                shape.make_trail = False
            shape.visible = False
        for graph in self.graphs:
            graph.delete()
        self.shapes, self.graphs = [], []
        vp.scene.caption = ""
        vp.scene.forward, vp.scene.up = vp.vector(0, 0, -1), vp.vector(0, 1, 0)

    def _build_scene(self, model) -> None:
        vp = self.vp
        scene = vp.scene
        scene.width, scene.height = CANVAS_SIZE
        scene.background = vp.vector(0.12, 0.13, 0.16)
        scene.fov = 0.2  # rad: a long lens, so the support and springs look flat, as in a drawing
        scene.title = (PAGE_STYLE + f"<b style='font-size:130%'>{self.setup.name}</b>: "
                       f"{_summary(self.setup.module)}\n")
        low, high = motion_box(model)
        anchors = model.anchors
        radius = _mass_radius(low, high, anchors)
        self.radius = radius
        thickness = 0.4 * radius
        pad = 2 * radius
        low, high = low - radius, high + radius  # the spheres' own size
        centre = 0.5 * (low + high)
        if self.view["support"] == "wall":
            wall_x = float(anchors[:, 0].min())
            span_y = float(high[1] - low[1]) + 2 * pad
            support = vp.box(pos=vp.vector(wall_x - thickness / 2, centre[1], centre[2]),
                             size=vp.vector(thickness, span_y, 2 * radius), color=vp.vector(0.6, 0.6, 0.65))
            low = np.minimum(low, [wall_x - thickness, centre[1] - span_y / 2, low[2]])
            high = np.maximum(high, [high[0], centre[1] + span_y / 2, high[2]])
        else:
            ceiling_y = float(anchors[:, 1].max())
            span_x = float(high[0] - low[0]) + 2 * pad
            support = vp.box(pos=vp.vector(centre[0], ceiling_y + thickness / 2, centre[2]),
                             size=vp.vector(span_x, thickness, 2 * radius), color=vp.vector(0.6, 0.6, 0.65))
            low = np.minimum(low, [centre[0] - span_x / 2, low[1], low[2]])
            high = np.maximum(high, [centre[0] + span_x / 2, ceiling_y + thickness, high[2]])
        self.support_box = (np.asarray(_array(support.pos) - 0.5 * _array(support.size)),
                            np.asarray(_array(support.pos) + 0.5 * _array(support.size)))
        low, high = low - 0.3 * radius, high + 0.3 * radius
        self._frame_camera(low, high)
        self.masses, self.springs = [], []
        # A long row gets fewer turns per spring: each turn is many triangles for the browser.
        coils = max(4, min(self.view["coils"], round(4 * self.view["coils"] / len(anchors))))
        for i, (anchor, r) in enumerate(zip(anchors, model.state.r)):
            colour = vp.vector(*mass_colour(i))
            self.springs.append(vp.helix(pos=_vec(vp, anchor), axis=_vec(vp, r - anchor),
                                         radius=0.45 * radius, thickness=0.12 * radius,
                                         coils=coils, color=vp.vector(0.85, 0.85, 0.9)))
            mass = vp.sphere(pos=_vec(vp, r), radius=radius, color=colour)
            self.masses.append(mass)
        # The trail is drawn from the graph samples (every 0.05 s of simulation time), not by
        # vpython's make_trail, which adds a point only when the page draws a frame: on a busy
        # computer that is a few times a second, and the trail came out as jagged straight segments.
        self.trails = [vp.curve(color=vp.vector(*mass_colour(i)), radius=0.06 * radius, retain=TRAIL_POINTS)
                       for i in range(len(anchors))] if self.view["trail"] else []
        self.shapes = [support, *self.springs, *self.masses, *self.trails]

    def _reframe(self, model) -> None:
        """Frame the new motion and the support once, after a new constant: in or out, as it needs.

        Without this the view would only zoom out after the mass (a heavier mass hangs lower), and
        the masses would shrink with every change.
        """
        low, high = motion_box(model)
        radius = _mass_radius(low, high, model.anchors)  # a mass swinging 20 m is drawn bigger
        if radius != self.radius:
            self.radius = radius
            for mass, spring in zip(self.masses, self.springs):
                mass.radius = radius
                spring.radius, spring.thickness = 0.45 * radius, 0.12 * radius
        low = np.minimum(low - 1.3 * radius, self.support_box[0])
        high = np.maximum(high + 1.3 * radius, self.support_box[1])
        self._frame_camera(low, high)

    def _frame_camera(self, low, high) -> None:
        scene = self.vp.scene
        width, height = CANVAS_SIZE
        box = high - low
        scene.autoscale = False
        scene.center = _vec(self.vp, 0.5 * (low + high))
        # range is the distance from the centre to the nearer (here: top and bottom) edge
        self.range = 0.55 * max(box[1], box[0] * height / width, 1e-3)
        self.max_range = 2 * self.range
        scene.range = self.range
        self.centre = 0.5 * (low + high)

    def _build_controls(self, preset: str | None) -> None:
        vp, scene, page = self.vp, self.vp.scene, self.page

        def put(command):  # a click on a control that is no longer on the page is ignored
            self.commands.put((page, command))
        scene.append_to_caption("\n")
        self.run_button = vp.button(text="Pause", bind=lambda _: put(("toggle",)))
        scene.append_to_caption("  ")
        vp.button(text="Step", bind=lambda _: put(("step",)))
        scene.append_to_caption("  ")
        vp.button(text="Reset", bind=lambda _: put(("reset",)))
        scene.append_to_caption("    integrator ")
        if self.live.model.integrators:
            vp.wtext(text="<i>" + ", ".join(self.live.model.integrators) + "</i> (one per mass)")
        else:
            vp.menu(choices=list(INTEGRATORS), selected=self.integrator,
                    bind=lambda menu: put(("integrator", menu.selected)))
        scene.append_to_caption("    speed ")
        vp.menu(choices=list(SPEEDS), selected=self.speed, bind=lambda menu: put(("speed", menu.selected)))
        scene.append_to_caption("\n\nscene ")
        vp.menu(choices=scene_menu_choices(), selected=self.setup.name,
                bind=lambda menu: put(("scene", menu.selected)))
        scene.append_to_caption("    preset ")
        labels = [label for label, _ in catalog.presets(self.setup)]
        self.preset_menu = None
        if labels:
            self.preset_menu = vp.menu(choices=[PRESET_PROMPT] + labels, selected=preset or PRESET_PROMPT,
                                       bind=lambda menu: put(("preset", menu.selected)))
        else:
            vp.wtext(text="<i>none for this scene</i>")
        scene.append_to_caption("    ")
        vp.button(text="Download CSV", bind=lambda _: put(("csv",)))
        scene.append_to_caption(" ")
        vp.button(text="Download program", bind=lambda _: put(("program",)))
        scene.append_to_caption(" ")
        self.download_text = vp.wtext(text="")
        scene.append_to_caption("\n\n")
        self.time_text = vp.wtext(text="t = 0.00 s")
        scene.append_to_caption("    ")
        self.error_text = vp.wtext(text="")
        scene.append_to_caption("\n")
        self.sliders, self.slider_texts = {}, {}
        for name in slider_names(self.setup, self.view):
            low, high, step = slider_range(name, float(self.setup.values[name]), self.defaults.get(name))
            scene.append_to_caption("\n")
            self.sliders[name] = vp.slider(min=low, max=high, step=step, value=self.setup.values[name],
                                           length=320, bind=lambda s, name=name: put(("set", name, s.value)))
            self.slider_texts[name] = vp.wtext(text="")
        if self.sliders:
            vp.wtext(text="").text = PRIME_SLIDERS  # set, not made with it: the setter runs scripts
        scene.append_to_caption("\n\n")
        self.constants_text = vp.wtext(text="")
        scene.append_to_caption("\n<i>Moving a slider, choosing another integrator or a preset restarts "
                                "the run from t = 0; Reset returns to the start; "
                                "Step advances one Δt.</i>\n")
        self.status_text = vp.wtext(text="")
        scene.append_to_caption("\n")

    def _build_graphs(self, model) -> None:
        vp = self.vp
        has_own = hasattr(self.setup.module, "view_graph")
        self.graph_size = (NARROW_GRAPH_WIDTH if has_own else GRAPH_SIZE[0], GRAPH_SIZE[1])
        self._build_scene_graph()
        width, height = self.graph_size
        names = ", ".join("xyz"[axis] for axis in self.axes)
        legend = model.state.count <= LEGEND_MASSES  # a long row's legend would hide the graph
        title = "Position" if legend else f"Position of each of the {model.state.count} masses"
        self.position_graph = vp.graph(title=title, xtitle="t (s)", ytitle=f"{names} (m)",
                                       width=width, height=height, align="left", fast=True,
                                       xmin=0, xmax=self.span)
        self.curves = []  # (gcurve, Trace, what it plots)
        many = model.state.count > 1
        for i, label in enumerate(model.labels):
            for axis in self.axes:
                name = "xyz"[axis] + (f" {label}" if many or len(self.axes) > 1 else " (simulation)")
                name = name if legend else ""
                colour = vp.vector(*shade(mass_colour(i), self.axes.index(axis)))
                self._curve(self.position_graph, name, colour, ("r", i, axis),
                            width=simulation_width(i, model.state.count, crowded=not legend))
        self.exact_curves = bool(self.view["exact"]) and model.exact is not None
        self.show_exact = self.exact_curves
        if self.show_exact:  # made last, so drawn on top: thin and dark inside the thick simulated curves
            for i, label in enumerate(model.labels):
                for axis in self.axes:
                    # one legend entry for all the exact curves: they share a colour
                    name = f"{'xyz'[axis]} exact" if i == 0 and legend else ""
                    self._curve(self.position_graph, name, vp.vector(*EXACT_COLOUR), ("exact", i, axis),
                                width=EXACT_WIDTH)
        # What the energy graph shows, so that it tells the story (what would fill it otherwise):
        # one method per mass: each mass's own E = K + U (summed, euler's runaway would swamp it);
        # a system that starts at rest at equilibrium: energies measured from there (else a large
        # constant m g h would flatten every curve).
        self.per_mass_energy = bool(model.integrators)
        self.energy_offset = 0.0 if self.per_mass_energy else (rest_potential(model.state, model.forces) or 0.0)
        title = ("Energy of each mass, E = K + U" if self.per_mass_energy else
                 "Energy, measured from rest at equilibrium" if self.energy_offset else "Energy")
        self.energy_graph = vp.graph(title=title, xtitle="t (s)", ytitle="energy (J)",
                                     width=width, height=height, align="left", fast=True,
                                     xmin=0, xmax=self.span)
        if self.per_mass_energy:
            for i, label in enumerate(model.labels):
                # half the position curves' widths: an energy that wobbles fast would fill a band
                self._curve(self.energy_graph, f"E {label}", vp.vector(*mass_colour(i)), ("mass_energy", i),
                            width=simulation_width(i, model.state.count) / 2)
        else:
            for key, colour in ENERGY_COLOURS.items():
                # E − W_nc comes last and thinner, so it shows on top of E when no work is done
                label = ENERGY_LABELS[key] + (" − U_rest" if self.energy_offset and key != "K" else "")
                self._curve(self.energy_graph, label, vp.vector(*colour), ("energy", key),
                            width=4 if key == "E" else 2)
        self.graphs.extend([self.position_graph, self.energy_graph])

    def _build_scene_graph(self) -> None:
        """The scene's own graph (view_graph), if it has one: lines and dots, and dots that follow the run.

        It is made before the position graph and filled at once, so it comes first on the page
        (vpython places a graph when its first points arrive).
        """
        vp, make = self.vp, getattr(self.setup.module, "view_graph", None)
        self.scene_graph, self.scene_series, self.live_dots = None, [], None
        self.live_drawn = -math.inf
        if make is None:
            return
        spec = make(self.setup)
        width, height = self.graph_size
        self.scene_graph = vp.graph(title=spec["title"], xtitle=spec["xtitle"], ytitle=spec["ytitle"],
                                    width=width, height=height, align="left", fast=True)
        self.graphs.append(self.scene_graph)
        for label, _, _, colour in spec.get("lines", []):
            self.scene_series.append(vp.gcurve(graph=self.scene_graph, label=label, color=vp.vector(*colour),
                                               width=2))
        for label, _, _, colour in spec.get("dots", []):
            self.scene_series.append(vp.gdots(graph=self.scene_graph, label=label, color=vp.vector(*colour),
                                              radius=3))
        if "live" in spec:
            self.live_dots = vp.gdots(graph=self.scene_graph, label=spec.get("live_label", ""),
                                      color=vp.vector(*spec.get("live_colour", (0, 0, 0))), radius=5)
        self._fill_scene_graph(spec)

    def _fill_scene_graph(self, spec) -> None:
        """Put a view_graph spec's points and labels into the scene graph's curves and dots."""
        graph = self.scene_graph
        for axis, pixels in (("x", self.graph_size[0]), ("y", GRAPH_CANVAS_HEIGHT)):
            low, high = spec.get(f"{axis}min"), spec.get(f"{axis}max")
            if low is not None and high is not None:  # widened to round ticks
                low, high = nice_range(low, high, pixels=pixels)
            for key, value in ((f"{axis}min", low), (f"{axis}max", high)):
                if value is not None:
                    setattr(graph, key, value)
        for series, (label, xs, ys, _) in zip(self.scene_series, spec.get("lines", []) + spec.get("dots", [])):
            _replace_points(series, [[float(x), float(y)] for x, y in zip(xs, ys)])
            if series.label != label:
                series.label = label
        self.live_points = spec.get("live")
        if self.live_dots is not None and self.live_dots.label != spec.get("live_label", ""):
            self.live_dots.label = spec.get("live_label", "")

    def _curve(self, graph, label, colour, what, *, width) -> None:
        curve = self.vp.gcurve(graph=graph, label=label, color=colour, width=width)
        self.curves.append((curve, Trace(span=self.span), what))

    # ---- the loop ----

    def run_forever(self) -> None:
        """Step in real time and redraw, about FRAME_RATE times a second, until the page closes."""
        while True:
            time.sleep(self.frame())

    def frame(self) -> float:
        """One frame: carry out the page's clicks, run the steps real time says are due, redraw.

        Returns the seconds to wait before the next frame. run_forever calls it in a loop; in a
        notebook, browser/notebook.py calls it from the kernel's event loop, so the cell returns.
        """
        start = time.perf_counter()
        if self._page_loads() > self.loads_shown:
            self._page_reloaded()
        changed = self._apply_commands(now=start)
        steps = self.clock.steps_due(now=start, running=self.running and not self.live.problem,
                                     quiet=self.server.seconds_since_contact(),
                                     max_steps=self.budget.max_steps)
        if steps:
            cpu = time.thread_time()  # the steps' own cost: time this thread waited does not count
            samples = self.live.advance(steps)
            self.budget.record(steps=steps, seconds=time.thread_time() - cpu)
            self._plot(samples)
        if steps or changed:
            self._draw()
        return max(0.002, 1.0 / FRAME_RATE - (time.perf_counter() - start))

    def _apply_commands(self, *, now: float) -> bool:
        """Carry out the clicks queued by the page (they arrive on vpython's server thread)."""
        pending = []
        while True:
            try:
                pending.append(self.commands.get_nowait())
            except queue.Empty:
                break
        changes, integrator = {}, None
        for page, command in pending:
            kind = command[0]
            if page != self.page:
                continue
            if kind == "toggle":
                self.running = not self.running
            elif kind == "step":
                self.running = False
                self._plot(self.live.advance(1))
            elif kind == "reset":
                self._plot(self._clear_graphs(self.live.restart()), redraw=True)
                self.clock.restart(now=now)
            elif kind == "speed":
                self.speed = command[1] if command[1] in SPEEDS else "1×"
                self.clock.speed = SPEEDS[self.speed]
            elif kind == "integrator":
                integrator = command[1]
            elif kind == "set" and command[2] != self.setup.values.get(command[1]):
                changes[command[1]] = float(command[2])
            elif kind == "csv":
                self._offer_csv()
            elif kind == "program":
                self._offer_program()
            elif kind == "preset" and command[1] != PRESET_PROMPT:
                self._switch(self.setup.with_preset(command[1]), preset=command[1])
                changes, integrator = {}, None
            elif kind == "scene" and command[1] != self.setup.name:
                self._switch(catalog.configure(command[1]))
                changes, integrator = {}, None
        if changes or integrator:
            self._rebuild(changes=changes, integrator=integrator or self.integrator)
        return bool(pending)

    def _switch(self, setup, *, preset: str | None = None) -> None:
        """Another scene, or new values from a preset: build the page again, from t = 0."""
        try:
            model = setup.build()
        except ValueError as problem:
            self.status_text.text = f"<b>Cannot use that:</b> {problem}"
            return
        self._build_page(setup, model, preset=preset)

    def _rebuild(self, *, changes: dict, integrator: str) -> None:
        """A new constant or integrator: rebuild the model and start again from t = 0."""
        setup = self.setup.with_values(**changes)
        try:
            model = setup.build()
        except ValueError as problem:
            self.status_text.text = f"<b>Cannot use that value:</b> {problem}"
            return
        if changes and self.preset_menu is not None:
            self.preset_menu.selected = PRESET_PROMPT  # the constants no longer match the preset
        self.setup, self.integrator = setup, integrator
        if self.scene_graph is not None and changes:
            self._fill_scene_graph(setup.module.view_graph(setup))
        self.live = RecordedRun(model, integrator=integrator, sample_every=SAMPLE_EVERY)
        self.show_exact = self.exact_curves and model.exact is not None
        self._reframe(model)
        self._restart(model)
        self.clock.restart(now=time.perf_counter())

    def _restart(self, model) -> None:
        self.may_run_away = expected_runaways(model)
        self.matter = [i for i in range(model.state.count) if i not in self.may_run_away]
        self._plot(self._clear_graphs(self.live.restart()), redraw=True)
        self.clock.dt = model.dt
        self.decimals = time_decimals(model.dt)
        self.constants_text.text = "Constants: " + constants_text(self.setup)
        for name, text in self.slider_texts.items():
            unit = self.setup.constants[name].unit
            text.text = f"  {symbol(name)} = {format_value(self.setup.values[name], unit)}"
        self.download_text.text = ""
        self._draw()

    def _clear_graphs(self, samples):
        self.position_fit.clear()
        self.energy_fit.clear()
        for label in getattr(self, "runaway_labels", {}).values():
            label.visible = False
        self.runaway_labels = {}
        for trail in self.trails:
            trail.clear()
        for curve, trace, _ in self.curves:
            trace.clear()
        self.recorded.clear()
        for graph in (self.position_graph, self.energy_graph):
            graph.xmin, graph.xmax = window(0.0, span=self.span)
        self.live_drawn = -math.inf
        return samples

    def _plot(self, samples, *, redraw: bool = False) -> None:
        """Add samples to every curve (a whole curve is resent only when its window scrolls)."""
        if not samples and not redraw:
            return
        self._record(samples)
        t = np.array([s.t for s in samples])
        r = np.array([s.r for s in samples]) if samples else np.zeros((0,) + self.live.state.r.shape)
        exact = self.live.model.exact(t)[0] if (self.show_exact and len(t)) else None
        if exact is not None:  # past the anchor the closed form no longer describes the mass
            keep = t <= self._exact_valid_until(float(t[-1]))
            exact = exact[keep] if not keep.all() else exact
        energies = self._energies(samples)
        for i, trail in enumerate(self.trails):
            points = [_vec(self.vp, where) for where in r[:, i] if np.all(np.isfinite(where))]
            if points and i not in self.live.runaways:
                trail.append(points)
        for curve, trace, what in self.curves:
            if what[0] == "r":
                values = r[:, what[1], what[2]]
            elif what[0] == "exact":
                if exact is None:
                    values = np.zeros(0)
                else:
                    values = exact[:, what[1], what[2]]
            else:
                values = energies[what[1]]
            points = [[float(a), float(b)] for a, b in zip(t, values)]  # zip stops where exact does
            if what[0] in ("r", "mass_energy") and what[1] in self.live.runaways:
                frozen = self.live.runaways[what[1]][0]  # the curve ends where the mass ran away
                points = [point for point in points if point[0] <= frozen]
            if trace.add(points) or redraw:
                _replace_points(curve, list(trace.points))
            elif points:
                curve.plot(points)
        if exact is not None and len(exact):
            self._fit(self.position_graph, self.position_fit, exact[..., self.axes].ravel())
        elif len(t):
            self._fit(self.position_graph, self.position_fit, r[:, self.matter][..., self.axes].ravel())
        self._fit(self.energy_graph, self.energy_fit,
                  [value for key, values in energies.items() if key not in self.may_run_away for value in values])
        if len(t):
            start, end = window(float(t[-1]), span=self.span)
            if start != self.position_graph.xmin:
                for graph in (self.position_graph, self.energy_graph):
                    graph.xmin, graph.xmax = start, end
        self._plot_live(redraw=redraw)

    def _energies(self, samples) -> dict:
        """What the energy graph plots, per curve key, one value per sample, J.

        K, U, E, E − W_nc of the system (U, E and E − W_nc less energy_offset), or, with one
        integrator per mass, each mass's own E = K + U (key: the mass's index).
        """
        if not self.per_mass_energy:
            return {key: [s.energy[key] - (0.0 if key == "K" else self.energy_offset) for s in samples]
                    for key in ENERGY_COLOURS}
        forces, m = self.live.model.forces, self.live.state.m
        per_mass = [kinetic(State(t=s.t, r=s.r, p=s.p, m=m)) + potential(State(t=s.t, r=s.r, p=s.p, m=m), forces)
                    for s in samples]
        return {i: [float(E[i]) for E in per_mass] for i in range(len(m))}

    def _plot_live(self, *, redraw: bool) -> None:
        """Move the scene graph's live dots to the state now, at most every LIVE_EVERY seconds."""
        if self.live_dots is None:
            return
        now = time.perf_counter()
        if not redraw and now - self.live_drawn < LIVE_EVERY:
            return
        self.live_drawn = now
        xs, ys = self.live_points(self.live.model, self.live.state)
        _replace_points(self.live_dots, [[float(x), float(y)] for x, y in zip(xs, ys) if math.isfinite(y)])

    def _record(self, samples) -> None:
        """Keep the samples the graphs show (the last `span` seconds), for Download CSV."""
        self.recorded.extend(samples)
        if self.recorded:
            start = window(self.recorded[-1].t, span=self.span)[0]
            while self.recorded and self.recorded[0].t < start - 1e-9:
                self.recorded.popleft()

    def _offer_csv(self) -> None:
        """Hand the graphed samples to the browser as a CSV file (a data: link the page clicks)."""
        samples = list(self.recorded)
        if not samples:
            self.download_text.text = "<i>nothing graphed yet</i>"
            return
        text = csv_text(samples, m=self.live.state.m, labels=self.live.model.labels, dt=self.live.model.dt)
        self.downloads += 1
        link = f"csv-download-{self.downloads}"
        name = f"{self.setup.name}.csv"
        rows = text.count("\n") - 1
        self.download_text.text = (
            f'<a id="{link}" download="{name}" href="data:text/csv;charset=utf-8,{quote(text, safe=",.-+")}">'
            f'{name}</a> ({rows} rows, t = {samples[0].t:.{self.decimals}f} to {samples[-1].t:.{self.decimals}f} s)'
            f'<script>document.getElementById("{link}").click()</script>')

    def _offer_program(self) -> None:
        """Hand the scene as chosen now (constants, integrator, preset) to the browser as a VPython
        program (export/), the way Download CSV hands over its file."""
        from export import program

        try:
            text = program(self.setup, integrator=self.integrator)
        except ValueError as problem:
            self.download_text.text = f"<i>no program: {problem}</i>"
            return
        self.downloads += 1
        link = f"program-download-{self.downloads}"
        name = f"{self.setup.name}.py"
        self.download_text.text = (
            f'<a id="{link}" download="{name}" href="data:text/x-python;charset=utf-8,{quote(text)}">'
            f'{name}</a> (a VPython program to hand out, {text.count(chr(10))} lines)'
            f'<script>document.getElementById("{link}").click()</script>')

    @staticmethod
    def _fit(graph, fit: AxisFit, values) -> None:
        """Widen a graph's y axis, to round ticks, when the values leave it (browser/axes.py).

        The position axis follows the exact motion where there is one: a numerical curve that
        strays far from it runs off the graph, rather than squashing every other curve flat, as
        euler's growing swing would.
        """
        ends = fit.update(values)
        if ends is not None:
            graph.ymin, graph.ymax = ends

    def _draw(self) -> None:
        """Move the masses and springs to the state now and update the caption: once per frame."""
        vp, state, anchors = self.vp, self.live.state, self.live.model.anchors
        for i, (mass, spring, anchor, r) in enumerate(zip(self.masses, self.springs, anchors, state.r)):
            if i in self.live.runaways:  # frozen: shown, and labelled, where it leaves the picture
                r = self._runaway_label(i, self._inside_frame(anchor, r))
            if np.all(np.isfinite(r)):
                mass.pos = _vec(vp, r)
                spring.axis = _vec(vp, r - anchor)  # the helix runs from the anchor to the mass
        self._keep_in_view(state.r[self.matter])
        self.time_text.text = f"<b style='font-size:150%'>t = {state.t:.{self.decimals}f} s</b>"
        self.run_button.text = "Pause" if self.running else "Run"
        self.error_text.text = self._error_readout()
        status = self.live.problem or "\n".join(_wrap(reason) for _, reason in self.live.runaways.values())
        if self.clock.dropped > 0.01 and not status:
            status = (f"Running slower than real time (Δt = {self.live.model.dt:g} s is small for "
                      f"this computer at this speed).")
        if status != self.status_text.text:
            self.status_text.text = status if not self.live.problem else f"<b>Stopped:</b> {status}"

    def _exact_valid_until(self, t_end: float) -> float:
        """The time, s, after which the model's closed form stops holding (math.inf if it holds to t_end)."""
        check = self.live.model.exact_valid_until
        return math.inf if check is None else check(t_end)

    def _error_readout(self) -> str:
        if not self.show_exact:
            return ""
        model, state = self.live.model, self.live.state
        valid_until = self._exact_valid_until(state.t)
        if state.t > valid_until:
            return (f"no exact value after t = {valid_until:.3g} s: the closed form "
                    f"stops holding {model.exact_limit}")
        exact = model.exact(np.array([state.t]))[0][0]
        errors = state.r[self.matter][:, self.axes] - exact[self.matter][:, self.axes]
        worst = float(np.max(np.abs(errors)))
        if errors.size == 1:
            name = "xyz"[self.axes[0]]
            return f"error {name} − {name}<sub>exact</sub> = {float(errors.flat[0]):+.3g} m"
        others = (f" ({', '.join(model.labels[i] for i in self.may_run_away)} left out)"
                  if self.may_run_away else "")
        return f"largest |error| against the exact solutions = {worst:.3g} m{others}"

    def _inside_frame(self, anchor, r):
        """The point where the line from the anchor to r leaves the picture (r itself if inside), m."""
        width, height = CANVAS_SIZE
        half = np.array([self.range * width / height, self.range, math.inf]) - 1.5 * self.radius
        d = r - anchor
        scale = 1.0
        for axis in (0, 1):
            if abs(d[axis]) > 1e-12:
                edge = self.centre[axis] + math.copysign(half[axis], d[axis])
                scale = min(scale, max(0.0, (edge - anchor[axis]) / d[axis]))
        return anchor + scale * d if np.all(np.isfinite(d)) else anchor

    def _runaway_label(self, i: int, where):
        """Label mass i, frozen after running away, with its method and time; returns where it is shown."""
        if i not in self.runaway_labels:
            t, _ = self.live.runaways[i]
            inward = 60 if where[0] < self.centre[0] else -60  # px: the text stays inside the picture
            label = self.vp.label(pos=_vec(self.vp, where), text=f"{self.live.model.labels[i]} ran away\nat t = {t:.2f} s",
                                  xoffset=inward, yoffset=30, height=15, color=self.vp.vector(1, 1, 1),
                                  box=False, line=False)
            self.runaway_labels[i] = label
            self.shapes.append(label)
        return where

    def _keep_in_view(self, r) -> None:
        """Zoom out (never in) if a mass that matters leaves the framed region, up to max_range.

        A mass the scene expects may run away (euler) is not followed: it leaves the picture, is
        frozen and labelled, instead of shrinking every other mass to a dot.
        """
        finite = r[np.all(np.isfinite(r), axis=1)]
        if not len(finite):
            return
        width, height = CANVAS_SIZE
        reach = np.abs(finite - self.centre).max(axis=0)
        needed = max(reach[1], reach[0] * height / width) + self.radius
        if self.range < needed and self.range < self.max_range:
            self.range = min(1.5 * needed, self.max_range)
            self.vp.scene.range = self.range


def _replace_points(series, points) -> None:
    """Replace all the points of a gcurve or gdots."""
    series.delete()
    series._data = []  # vpython 7.6.5's delete() keeps its Python copy of the points
    if points:
        series.plot(points)


def _mass_radius(low, high, anchors) -> float:
    """The spheres' radius, m: 8 % of the motion's size, and less than a third of the gap between anchors."""
    size = float(np.max(high - low)) or 1.0
    gaps = [np.linalg.norm(a - b) for i, a in enumerate(anchors) for b in anchors[i + 1:]]
    return min([0.08 * size] + [0.3 * gap for gap in gaps if gap > 0])


def _wrap(text: str, width: int = 110) -> str:
    """Line breaks in a long sentence: the caption keeps line breaks but does not wrap."""
    import textwrap

    return "\n".join(textwrap.wrap(text, width, break_on_hyphens=False))


def _array(v) -> np.ndarray:
    return np.array([v.x, v.y, v.z])


def _vec(vp, a):
    return vp.vector(float(a[0]), float(a[1]), float(a[2]))


def _summary(module) -> str:
    return (module.__doc__ or "").strip().splitlines()[0]

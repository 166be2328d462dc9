"""The page of any scene, and the frame loop that runs it.

The page has three parts, each built by its constructor from the scene's model at t = 0:

    browser/scene3d.py   the 3-D picture: support, springs, masses, trails, camera, runaway labels
    browser/graphs.py    position, energy and the scene's own graph; the CSV of what they show
    browser/controls.py  buttons, menus, sliders and captions, and the queue of their clicks

:class:`SceneView` here owns the run (browser/clock.py's LiveRun, RealTimeClock and StepBudget):
once per frame it carries out the clicks (browser/messages.py, one handler each), asks the engine
for the steps real time says are due, and tells the parts to draw. A scene's VIEW dict names what
to draw (the keys and their defaults: scenes/_view.py's DEFAULT_VIEW). What the page does for the teacher is in README.md.

Closing the tab, or Ctrl-C, makes vpython raise SystemExit(0) in this (main) thread. Closing the
tab ends the program with status 0; show() turns a Ctrl-C into KeyboardInterrupt, which the
command line reports with status 130.
"""
from __future__ import annotations

import functools
import sys
import threading
import time

import numpy as np

from export import files, offline_page
from export.description import describe
from export.offline_page import link_fragment
from export.step_update import step_lines, update_force
from physics.period import CrossingMeter, formula_period

from scenes import catalog
from scenes._view import DEFAULT_VIEW

from . import access
from .clock import LiveRun, RealTimeClock, StepBudget
from .controls import (PRESET_PROMPT, SPEEDS, Controls, constants_text, csv_href, page_href, program_href,
                       scene_menu_choices, slider_names, slider_range, symbol, time_decimals)
from .arrows3d import MomentumArrows
from .data_panel import MeasuredData, load_button_html
from .graphs import SAMPLE_EVERY, Graphs, csv_text
from .force_box import Comparison, ForceBox, change_forces
from .jump import batches, jump_steps, jump_time
from .measure_panel import period_text
from .messages import (AddForce, Batch, ChooseGraph, ChooseIntegrator, ChoosePreset, ChooseScene, ChooseSpeed,
                       ClearStopwatch, Describe, DownloadCsv, DownloadOfflinePage, DownloadProgram, FitData, JumpTo,
                       LapStopwatch, MoveMarker, RemoveForce, Reset, ResetForces, RunOrPause, SetConstant, ShowArrows,
                       ShowLine, ShowPeriod,
                       StartStopwatch, Step)
from .reference_lines import ReferenceLines
from .stopwatch import Stopwatch
from .page_layout import PROJECTOR_BUTTON, page_head
from .scene3d import Scene3D

# What other modules and the tests use; the helpers are defined in the part they belong to.
__all__ = ["show", "SceneView", "DEFAULT_VIEW", "csv_text", "constants_text", "scene_menu_choices",
           "slider_names", "slider_range", "symbol", "time_decimals"]

STEP_MASSES = 4           # masses whose Step is written out in the caption
PERIOD_MASSES = 4         # graphed masses whose period the Measure panel shows
FRAME_RATE = 50           # frames per second the loop aims for


def show(setup, model, *, integrator: str, port: int | None, open_browser: bool,
         preset: str | None = None, projector: bool = False, arrows=None, data=None) -> int:
    """Show a scene in the browser and run it in real time until the page is closed.

    model   the scene's model, built from `setup` (the command line has built and checked it)
    preset  the label of the preset already applied to `setup` (--preset), shown in the menu.
    projector  start in projector mode (--projector; browser/page_layout.py)
    arrows  the kinds of arrow to show (--arrows, export/arrows.py), None for each scene's VIEW
    data    the measured data to show from the start (--data --page): browser/data_panel.py's
            MeasuredData, or None (the page's Load data button loads one)

    Returns 2 (after a one-line message) if the server cannot start. Otherwise the program ends
    through SystemExit(0) when the tab closes, and Ctrl-C (while waiting for a browser or while
    running) raises KeyboardInterrupt, which the command line reports as one line and status 130.
    """
    from .loopback_server import ServerError, interrupted, start

    try:
        server = start(port=port, open_browser=open_browser)
        SceneView(setup=setup, model=model, integrator=integrator, server=server, preset=preset,
                  projector=projector, arrows=arrows, data=data).run_forever()
    except ServerError as problem:
        print(f"error: {problem}", file=sys.stderr)
        return 2
    except (KeyboardInterrupt, SystemExit):  # vpython ends both a closed page and Ctrl-C with SystemExit(0)
        if interrupted():
            raise KeyboardInterrupt from None
        raise
    return 0


class SceneView:
    """The page of one scene at a time, and its frame loop.

    It owns what lasts across scenes (the clock, the speed, Run or Pause) and, for the scene shown,
    the run and the three parts of the page. Switching scene, applying a preset or a reloaded tab
    takes the parts down and builds them again; a new constant or integrator keeps them and
    starts a new run.

    server  the loopback server (browser/loopback_server.py) or a notebook's link: how long
            since the page was last heard from, and how often it has been loaded
    """

    def __init__(self, *, setup, model, integrator: str, server, preset: str | None = None,
                 projector: bool = False, arrows=None, data=None):
        import vpython as vp  # already imported, loopback-only, by loopback_server.start

        self.vp, self.server = vp, server
        self.projector = projector
        self.arrows_asked, self.arrows_scene, self.arrows_shown = arrows, None, set()
        self.integrator = integrator
        self.speed = "1×"
        self.running = True
        self.clock = RealTimeClock(dt=model.dt, now=time.perf_counter())
        self.budget = StepBudget()
        self.loads_shown = self._page_loads()
        self.setup = setup
        self.preset = preset   # the preset whose constants run now (None once a slider moved one)
        self.data = data or MeasuredData()
        self.fresh_file = False     # a file from Load data, not yet compared
        self._page_writing = None   # the offline page being written on its thread (_offer_offline_page)
        self.live = LiveRun(model, integrator=integrator, sample_every=SAMPLE_EVERY)
        # the Measure panel's tools, kept across scenes as the arrows are (browser/measure_panel.py)
        self.stopwatch = Stopwatch()
        self.t_drawn = 0.0          # the t the page shows: a run restarting from 0 leaves the stopwatch that
        self.period_shown = False   # the period is hidden until its box is ticked
        self.lines_shown: set = set()
        self.graph_place = "energy"
        self.jumped = False         # a jump was made this frame: the page says so once it has drawn
        self.forces_start = setup.written   # the forces the scene opened with (--force): the box's way back
        self.comparison = Comparison(vp)    # the run before a force was added, dimmed (browser/force_box.py)
        self.scene, self.controls, self.graphs = self._build_parts(preset=preset)
        self._start_run()

    # ---- building the page ----

    def _build_parts(self, *, preset: str | None):
        """The 3-D picture, the controls and the graphs of self.setup, in the order the page shows them."""
        setup, model = self.setup, self.live.model
        view = {**DEFAULT_VIEW, **setup.hooks.view}
        title = (page_head(projector=self.projector) + access.head(setup) + access.scene_heading(setup.name) + ": "
                 f"{_summary(setup.module)}{PROJECTOR_BUTTON}\n")
        scene = Scene3D(self.vp, model=model, view=view, title=title)
        if self.arrows_scene != setup.name:  # a new scene starts with its own arrows, or --arrows
            self.arrows_scene = setup.name
            self.arrows_shown = set(view["arrows"] if self.arrows_asked is None else self.arrows_asked)
        self.arrows = MomentumArrows(self.vp, model=model, integrator=self.integrator, view=view,
                                     shown=self.arrows_shown, radius=scene.radius, masses=scene.masses,
                                     make_room=scene.make_room, camera=scene.camera)
        controls = Controls(self.vp, setup=setup, view=view, integrators=model.integrators,
                            integrator=self.integrator, speed=self.speed, preset=preset,
                            arrows=self.arrows_shown,
                            load_button=load_button_html() if hasattr(self.server, "uploaded") else "",
                            measure={"period": self.period_shown, "lines": self.lines_shown,
                                     "graph": self.graph_place},
                            force_box=functools.partial(ForceBox, setup=setup, model=model, start=self.forces_start))
        self.view = view
        self.lines = self._lines(scene, model)
        self.lines.bind_mouse(controls.commands.put)
        graphs = Graphs(self.vp, setup=setup, model=model, view=view, place=self.graph_place,
                        reference=self.lines.at["equilibrium"])
        self._measure(model, graphs)
        return scene, controls, graphs

    def _lines(self, scene, model) -> ReferenceLines:
        """The natural-length, equilibrium and marker lines of this model (browser/reference_lines.py)."""
        return ReferenceLines(self.vp, model=model, view=self.view, radius=scene.radius, centre=scene.centre,
                              reach=scene.range, shown=self.lines_shown)

    def _measure(self, model, graphs) -> None:
        """What the period is measured from, for this model: each graphed mass's crossings of its
        equilibrium along the graphed coordinate, and the formula's 2π/ω_d (physics/period.py)."""
        self.period_axis = graphs.axes[0]
        self.period_masses = graphs.graphed[:PERIOD_MASSES]
        centre = self.lines.at["equilibrium"]
        self.crossings = CrossingMeter(np.full(model.state.count, np.nan) if centre is None
                                       else centre[:, self.period_axis])
        covered = False if model.exact is None else np.isfinite(model.exact_where_valid([0.0])[0][0]).all(axis=-1)
        self.formula, self.formula_why = formula_period(model.forces, model.state, closed_form=covered)

    def _build_page(self, setup, model, *, preset: str | None = None, old_page_gone: bool = False) -> None:
        """Take down the parts shown so far (unless the page they were on is gone), build this
        scene's, and start its run at t = 0."""
        if setup.name != self.setup.name:     # another scene: its own forces, and the way back to them
            self.forces_start = setup.written
        self.comparison.forget()
        if not old_page_gone:
            self.lines.take_down()
            self.arrows.take_down()
            self.scene.take_down()
            self.graphs.take_down()
            self.controls.take_down()
        self.setup, self.preset = setup, preset
        self.live = LiveRun(model, integrator=self.integrator, sample_every=SAMPLE_EVERY)
        self.scene, self.controls, self.graphs = self._build_parts(preset=preset)
        self._start_run()

    def _start_run(self) -> None:
        """Show self.live from t = 0: empty graphs and trails, the constants, a restarted clock."""
        self.clock.dt = self.live.model.dt
        self._reset()
        self.controls.show_constants(self.setup)
        self.controls.show_link(link_fragment(self.setup, self.integrator))
        self.data.compare(self.setup, self.integrator)   # on a thread: the run starts at once
        self._show_data()
        self._draw()
        self.clock.restart(now=time.perf_counter())

    def _reset(self) -> None:
        """Back to the exact initial state, with empty graphs and trails (Reset)."""
        self.stopwatch.run_restarted(self.t_drawn)
        self.t_drawn = 0.0
        self.crossings.clear()
        samples = self.live.restart()
        self.arrows.legend_text = self.controls.arrow_legend
        self.arrows.reset()
        self.arrows.end_step()
        self.arrows.publish()
        self.controls.step_text.text = ""
        self.controls.description.text = ""
        self.scene.clear()
        self.graphs.clear()
        self._plot(samples, redraw=True)

    @property
    def matter(self) -> list[int]:
        """The masses the camera and the position axis follow: all but those that may run away."""
        return [i for i in range(self.live.state.count) if i not in self.live.may_run_away]

    @property
    def decimals(self) -> int:
        """Decimals of t on the page: enough that one step of Δt shows."""
        return time_decimals(self.live.model.dt)

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
        self.vp.scene = self.vp.canvas()
        # the menus show what runs: the preset whose constants these are, as the old page did
        self._build_page(self.setup, self.setup.build(), preset=self.preset, old_page_gone=True)
        self.loads_shown = loads
        self.server.page_built(loads)

    def close(self, reason: str) -> None:
        """Stop showing this scene (browser/notebook.py): the reason in the status line, the
        graphs and the 3-D canvas removed (a browser keeps only a few WebGL canvases alive)."""
        self.controls.say(reason)
        self.arrows.take_down()
        self.graphs.take_down()
        self.vp.scene.delete()

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
        changed = self._take_upload()
        changed = self._apply_commands(now=start) or changed
        changed = self._data_answered() or changed
        changed = self._offline_page_written() or changed
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
        if self.jumped:   # last, after everything it drew: the note a look from outside waits for
            self.jumped = False
            self.controls.show_jumped(self.live.state.t, decimals=self.decimals)
        return max(0.002, 1.0 / FRAME_RATE - (time.perf_counter() - start))

    def _apply_commands(self, *, now: float) -> bool:
        """Carry out the messages queued by the page's clicks (they arrive on vpython's server
        thread; browser/messages.py), each by its handler below.

        They take effect in the order they were made, as if each came in a frame of its own: an
        integrator or a slider value chosen just before a preset still holds after it (a preset
        changes only its own constants). A new scene or preset builds new controls; the messages
        after it in this batch were made on the old ones, so they are dropped.
        """
        pending = self.controls.clicks()
        batch = Batch(now=now)
        for message in pending:
            self.carry_out(message, batch)
            if batch.page_built:
                break
        if batch.changes or batch.integrator:
            self._rebuild(changes=batch.changes, integrator=batch.integrator or self.integrator)
        return bool(pending)

    # ---- one handler per message (browser/messages.py) ----

    @functools.singledispatchmethod
    def carry_out(self, message, batch: Batch) -> None:
        """Do what one message asks, now or (constants, the integrator) once the batch is done."""
        raise TypeError(f"the page has no handler for {message!r}")

    @carry_out.register
    def _run_or_pause(self, message: RunOrPause, batch: Batch) -> None:
        self.running = not self.running
        self.arrows.end_step()
        self.controls.step_text.text = ""

    @carry_out.register
    def _step_once(self, message: Step, batch: Batch) -> None:
        self.running = False
        self._step()

    @carry_out.register
    def _jump_to(self, message: JumpTo, batch: Batch) -> None:
        if batch.changes or batch.integrator:   # chosen before the jump: they restart the run first
            self._rebuild(changes=batch.changes, integrator=batch.integrator or self.integrator)
            batch.changes, batch.integrator = {}, None
        self._jump(message.text)

    @carry_out.register
    def _describe(self, message: Describe, batch: Batch) -> None:
        self._describe_motion()

    @carry_out.register
    def _change_forces(self, message: AddForce | RemoveForce | ResetForces, batch: Batch) -> None:
        change_forces(self, message, batch)     # browser/force_box.py

    @carry_out.register
    def _show_arrows(self, message: ShowArrows, batch: Batch) -> None:
        self.arrows.set_shown(message.kind, bool(message.shown))

    @carry_out.register
    def _reset_run(self, message: Reset, batch: Batch) -> None:
        self._reset()
        self.clock.restart(now=batch.now)

    @carry_out.register
    def _choose_speed(self, message: ChooseSpeed, batch: Batch) -> None:
        self.speed = message.label if message.label in SPEEDS else "1×"
        self.clock.speed = SPEEDS[self.speed]

    @carry_out.register
    def _choose_integrator(self, message: ChooseIntegrator, batch: Batch) -> None:
        batch.integrator = message.name

    @carry_out.register
    def _set_constant(self, message: SetConstant, batch: Batch) -> None:
        if message.value != self.setup.values.get(message.name):
            batch.changes[message.name] = float(message.value)

    @carry_out.register
    def _download_csv(self, message: DownloadCsv, batch: Batch) -> None:
        self._offer_csv()

    @carry_out.register
    def _download_program(self, message: DownloadProgram, batch: Batch) -> None:
        self._offer_program()

    @carry_out.register
    def _download_offline_page(self, message: DownloadOfflinePage, batch: Batch) -> None:
        self._offer_offline_page()

    @carry_out.register
    def _fit_data(self, message: FitData, batch: Batch) -> None:
        self._fit()

    @carry_out.register
    def _choose_preset(self, message: ChoosePreset, batch: Batch) -> None:
        if message.label == PRESET_PROMPT:
            return
        self._choose(lambda: self.setup.with_values(**batch.changes).with_preset(message.label),
                     preset=message.label, batch=batch,
                     refused=lambda: self.controls.show_preset(self.preset))

    @carry_out.register
    def _choose_scene(self, message: ChooseScene, batch: Batch) -> None:
        if message.name == self.setup.name:
            return
        self._choose(lambda: catalog.configure(message.name), preset=None, batch=batch,
                     refused=lambda: self.controls.show_scene(self.setup.name))

    @carry_out.register
    def _start_stopwatch(self, message: StartStopwatch, batch: Batch) -> None:
        self.stopwatch.start_stop(self.live.state.t)

    @carry_out.register
    def _lap_stopwatch(self, message: LapStopwatch, batch: Batch) -> None:
        self.stopwatch.lap(self.live.state.t)

    @carry_out.register
    def _clear_stopwatch(self, message: ClearStopwatch, batch: Batch) -> None:
        self.stopwatch.clear()

    @carry_out.register
    def _show_period(self, message: ShowPeriod, batch: Batch) -> None:
        self.period_shown = bool(message.shown)

    @carry_out.register
    def _show_line(self, message: ShowLine, batch: Batch) -> None:
        self.lines.set_shown(message.kind, bool(message.shown))

    @carry_out.register
    def _move_marker(self, message: MoveMarker, batch: Batch) -> None:
        self.lines.move_marker((message.x, message.y, message.z))

    @carry_out.register
    def _choose_graph(self, message: ChooseGraph, batch: Batch) -> None:
        self.graph_place = message.kind
        self.graphs.choose(message.kind, self.live)

    def _choose(self, configure, *, preset: str | None, batch: Batch, refused) -> None:
        """A scene or preset from a menu: configure() gives its setup, built anew from t = 0 with
        the integrator chosen in this batch; refused() puts the menu back where it cannot be."""
        try:
            setup = configure()
        except ValueError as problem:  # a scene file a teacher broke: say so, keep this one
            self.controls.say(f"<b>Cannot open that:</b> {problem}")
            refused()
            return
        self.integrator = batch.integrator or self.integrator
        batch.changes, batch.integrator = {}, None
        if self._switch(setup, preset=preset):
            batch.page_built = True
        else:
            refused()

    def _switch(self, setup, *, preset: str | None = None) -> bool:
        """Another scene, or new values from a preset: build the page again, from t = 0.
        Returns False, and says why, if the model cannot be built."""
        try:
            model = setup.build()
        except ValueError as problem:
            self.controls.say(f"<b>Cannot use that:</b> {problem}")
            return False
        self._build_page(setup, model, preset=preset)
        return True

    def _rebuild(self, *, changes: dict, integrator: str) -> None:
        """A new constant or integrator: rebuild the model and start again from t = 0."""
        setup = self.setup.with_values(**changes)
        try:
            model = setup.build()
        except ValueError as problem:
            self.controls.say(f"<b>Cannot use that value:</b> {problem}")
            return
        self.comparison.forget()     # the run before a force was added is another case now
        self.rebuild_with(setup, model, changes=changes, integrator=integrator)

    def rebuild_with(self, setup, model, *, changes: dict, integrator: str) -> None:
        """Run this setup's model from t = 0, keeping the page (new constants, integrator or forces)."""
        if changes:
            self.controls.preset_left()
            self.preset = None
        self.setup, self.integrator = setup, integrator
        self.graphs.rebuilt(setup, model, changes=changes)
        self.live = LiveRun(model, integrator=integrator, sample_every=SAMPLE_EVERY)
        self.arrows.rescale(model, integrator=integrator)
        self.scene.reframe(model)
        self.lines.take_down()       # the equilibrium and natural length move with the constants
        self.lines = self._lines(self.scene, model)
        self.lines.bind_mouse(self.controls.commands.put)
        self.graphs.new_reference(model, self.lines.at["equilibrium"])
        self._measure(model, self.graphs)
        self._start_run()

    def _jump(self, text: str) -> None:
        """Jump to t (browser/jump.py): the engine runs to the first step at or after t, from 0 if t
        is before now, each graph sample handed to the graphs as the frames of a run at 1× would
        have, and the page is drawn once, paused there. A t that cannot be reached is one sentence."""
        live = self.live
        try:
            t = jump_time(text, t0=live.model.state.t)
            target = jump_steps(live, t, sample_every=live.sample_every)
        except ValueError as problem:
            self.controls.say(str(problem))
            return
        self.running = False
        self.arrows.end_step()
        self.controls.step_text.text = ""
        if target < live.engine.steps:
            self._reset()
        for steps in batches(target - live.engine.steps, dt=live.model.dt, frame=1.0 / FRAME_RATE,
                             runaways_possible=bool(live.may_run_away)):
            for sample in live.advance(steps):
                self._plot([sample])
            if live.problem:
                break
        self.graphs.live_now(live)   # moved at most every LIVE_EVERY s of wall time: maybe not since the last
        self.clock.restart(now=time.perf_counter())
        self.jumped = True

    def _step(self) -> None:
        """Step: one Δt, drawn as p_f = p_i + F_net Δt at each mass and written out with its
        numbers in the caption (export/step_update.py: the digits `--steps` prints)."""
        live = self.live
        before = live.state
        t_i, r_i, p_i = before.t, np.array(before.r), np.array(before.p)
        self._plot(live.advance(1))
        after = live.state
        if after.t == t_i:   # the run had stopped
            return
        model, methods = live.model, live.engine.methods
        F_net = update_force(model.forces, methods, t_i=t_i, r_i=r_i, p_i=p_i, p_f=after.p, m=after.m,
                             dt=model.dt)
        self.arrows.show_step(r_f=after.r, p_i=p_i, impulse=F_net * model.dt, p_f=after.p)
        shown = range(min(after.count, STEP_MASSES))
        blocks = []
        for i in shown:
            lines = step_lines(method=methods[i], dt=model.dt, t_f=after.t, m=float(after.m[i]), F_net=F_net[i],
                               p_i=p_i[i], p_f=after.p[i], r_i=r_i[i], r_f=after.r[i])
            head = f"<b>{model.labels[i]}</b>\n" if after.count > 1 else ""
            blocks.append(head + "\n".join(lines))
        more = f"\n(and {after.count - len(shown)} more masses)" if after.count > len(shown) else ""
        self.controls.step_text.text = ("<span class='step-readout' style='font-family: monospace'>"
                                        + "\n".join(blocks) + more + "</span>")
        self._describe_motion()

    def _describe_motion(self) -> None:
        """The motion in words (export/description.py) in the live region under the clock: where
        each mass is, how it moves, and the last step's F_net and its parts, the engine's numbers."""
        live = self.live
        self.controls.description.text = describe(live.model, live.engine.methods, state=live.state,
                                                  before=live.before, equilibrium=self.lines.at["equilibrium"],
                                                  decimals=self.decimals)

    # ---- drawing ----

    def _plot(self, samples, *, redraw: bool = False) -> None:
        """Add the samples to the graphs and the trails."""
        if not samples and not redraw:
            return
        self.scene.extend_trails(samples, self.live.runaways)
        if samples:
            self.crossings.add([s.t for s in samples], [s.r[:, self.period_axis] for s in samples])
        self.graphs.plot(samples, self.live, matter=self.matter, redraw=redraw)

    def _draw(self) -> None:
        """Move the masses and springs to the state now and update the caption: once per frame."""
        live = self.live
        self.scene.draw(live, matter=self.matter)
        self.arrows.draw(live)
        self.controls.show_time(live.state.t, decimals=self.decimals, running=self.running,
                                error=self.graphs.error_readout(live, matter=self.matter))
        self.t_drawn = float(live.state.t)
        self.controls.measure.show_stopwatch(reading=self.stopwatch.reading(live.state.t),
                                             running=self.stopwatch.running, laps=self.stopwatch.lap_times(),
                                             decimals=self.decimals)
        self.controls.measure.show_period(self._period_text() if self.period_shown else "")
        self.graphs.bars.draw(live)
        self.controls.show_status(problem=live.problem, runaways=[reason for _, reason in live.runaways.values()],
                                  slow_dt=live.model.dt if self.clock.dropped > 0.01 else None,
                                  advice=live.advice)

    def _period_text(self) -> str:
        """The period of each graphed mass (a few), measured and from the formula, for the panel."""
        lines = []
        model, axis = self.live.model, "xyz"[self.period_axis]
        for i in self.period_masses:
            formula = None if self.formula is None else float(self.formula[i])
            said = period_text(self.crossings.period(i), crossings=len(self.crossings.times[i]),
                               formula=formula, why=self.formula_why, axis=axis,
                               centre=float(self.crossings.centres[i]))
            lines.append((f"<b>{model.labels[i]}</b>: " if len(self.period_masses) > 1 else "") + said)
        return "<span class='sm-period'>" + "\n".join(lines) + "</span>"

    # ---- measured data (browser/data_panel.py) ----

    def _take_upload(self) -> bool:
        """A file sent by the Load data button: read it and compare it with the run, on a thread
        (a bad file says why in one line and loads nothing)."""
        upload = self.server.uploaded() if hasattr(self.server, "uploaded") else None
        if upload is None:
            return False
        self.data.load(upload.raw, upload.name, self.setup, self.integrator)   # on a thread
        self.fresh_file = True      # once read, the run restarts (_data_answered)
        self._show_data()
        return True

    def _fit(self) -> None:
        if self.data.measured is None:
            self.data.problem = "load a file of measured positions first (Load data), then press Fit"
        else:
            self.data.compare(self.setup, self.integrator, fit=True)
        self._show_data()

    def _data_answered(self) -> bool:
        """A comparison or fit finished on its thread: show it; a fit moves the sliders to its
        values and restarts the run with them."""
        answer = self.data.finished()
        if answer is False:
            return False
        if self.fresh_file and answer is not None and not answer.fitted:
            self._reset()   # from t = 0, so the model's curve spans the data (early points scroll away)
        self.fresh_file = False
        if answer is not None and answer.fitted:
            fitted = {name: answer.setup.values[name] for name in answer.fitted}   # r0: its vector
            if self.controls.move_sliders(fitted):
                self._rebuild(changes=fitted, integrator=self.integrator)
            else:  # a slider's span does not reach its fitted value: new controls, spanning it
                self._switch(self.setup.with_values(**fitted))
        elif answer is not None:   # the constants may have moved while it worked (a file was read)
            self.data.compare(self.setup, self.integrator)
        self._show_data()
        return True

    def _show_data(self) -> None:
        self.controls.show_data(self.data.text(dt_slider="dt" in self.controls.sliders))
        self.graphs.show_data(self.data.points(), label="measured")

    # ---- downloads ----

    def _offer_csv(self) -> None:
        """Hand the graphed samples to the browser as a CSV file (a data: link the page clicks)."""
        samples = list(self.graphs.recorded)
        if not samples:
            self.controls.offer_nothing("nothing graphed yet")
            return
        text = csv_text(samples, m=self.live.state.m, labels=self.live.model.labels, dt=self.live.model.dt)
        rows = text.count("\n") - 1
        self.controls.offer(kind="csv", name=f"{self.setup.name}.csv", href=csv_href(text),
                            note=f"{rows} rows, t = {samples[0].t:.{self.decimals}f} to "
                                 f"{samples[-1].t:.{self.decimals}f} s")

    def _offer_program(self) -> None:
        """Hand the scene as chosen now (constants, integrator, preset) to the browser as a VPython
        program (export/), the way Download CSV hands over its file."""
        from export import program

        try:
            text = files.stamped(program(self.setup, integrator=self.integrator, arrows=self.arrows.shown))
        except ValueError as problem:
            self.controls.offer_nothing(f"no program: {problem}")
            return
        self.controls.offer(kind="program", name=f"{self.setup.name}.py", href=program_href(text),
                            note=f"a VPython program to hand out, {text.count(chr(10))} lines")


    def _offer_offline_page(self) -> None:
        """Hand the scene as chosen now (constants, integrator, preset, arrows) to the browser as the
        offline page `main.py SCENE --html` writes (export/offline_page.py). Writing it takes a
        second or more (it tries which constants the page may change), so it is written on a
        thread of its own while the run goes on; _offline_page_written offers it."""
        if self._page_writing is not None:
            return
        self.controls.offer_nothing("writing the offline page…")
        setup, integrator, shown = self.setup, self.integrator, tuple(self.arrows.shown)
        writing = self._page_writing = {"name": f"{setup.name}.html"}

        def write():
            try:
                writing["text"] = files.stamped(offline_page.page(setup, integrator=integrator, arrows=shown))
            except ValueError as problem:
                writing["problem"] = str(problem)
        writing["thread"] = threading.Thread(target=write, name="offline page", daemon=True)
        writing["thread"].start()

    def _offline_page_written(self) -> bool:
        """Offer the offline page once its thread has written it (or say why there is none)."""
        writing = self._page_writing
        if writing is None or writing["thread"].is_alive():
            return False
        self._page_writing = None
        if "text" not in writing:
            self.controls.offer_nothing(f"no offline page: {writing.get('problem', 'it could not be written')}")
            return True
        text = writing["text"]
        self.controls.offer(kind="page", name=writing["name"], href=page_href(text),
                            note=f"one file that runs offline in any browser, {len(text.encode()) / 1e6:.1f} MB")
        return True


def _summary(module) -> str:
    return (module.__doc__ or "").strip().splitlines()[0]

"""The momentum update on the page: p and F_net arrows on every mass, and a Step drawn as vector addition.

Arrows start at each mass's centre and are drawn at the run's scales (export/arrows.py: one for
momentum, one for forces, round numbers, fixed during a run; the legend states them). What can be
switched on, each with a check box under the picture (and `--arrows` on the command line):

    p        momentum, yellow
    F_net    net force, reddish purple
    forces   each force on its own arrow, tip to tail, ending at F_net's tip, labelled
    split    F∥ (along p, sky blue) and F⊥ (across p, white), labelled with their magnitudes

While any arrow that starts at the centre is switched on, the masses are drawn see-through
(SEE_THROUGH), so an arrow shorter than the ball's radius (a small force, the steady motion of
`driven --scenario 3`, F∥ near a pendulum's turning point) still shows inside it; its axis stays
exactly scale × the engine's value.

A Step while paused draws the update itself, at the momentum scale, just beside the mass: p_i (dark
yellow), F_net Δt from p_i's tip (reddish purple) and p_f from p_i's start to the sum (yellow, a
little further aside so that on a line the two do not cover each other), and the caption shows
the numbers (export/step_update.py, the digits of `--steps`).

For the tests, the legend holds a hidden element, #arrow-objects, whose data-objects attribute
names each arrow's GlowScript object (its index in the page's glowObjs) and the scales.
"""
from __future__ import annotations

import json

import numpy as np

from export.arrows import (ARROW_LABELS, ARROWS, LABEL_PX, PART_DIGITS, SEE_THROUGH, TIP_ROOM, choose_scales,
                           force_name, forces_each, split, unit_keeping_in)
from export.palette import ARROW_COLOURS
from physics.forces import net_force
from physics.state import velocity

from .messages import ShowArrows


def arrow_checkboxes(vp, put, shown) -> dict:
    """A check box per kind of arrow, each queueing ShowArrows(kind, checked); returns them by kind."""
    boxes = {}
    vp.scene.append_to_caption("arrows: ")
    for kind in ARROWS:
        boxes[kind] = vp.checkbox(text=ARROW_LABELS[kind] + " ", checked=kind in shown,
                                  bind=lambda box, kind=kind: put(ShowArrows(kind, box.checked)))
    return boxes


class MomentumArrows:
    """The arrows of one scene's masses, at the scales chosen for the run.

    vp          the vpython module
    model       the scene's Model (forces, masses, start)
    integrator  the method chosen, for the short run that chooses the scales
    shown       the kinds of arrow switched on (a subset of export.arrows.ARROWS)
    radius      the masses' radius, m: the arrows' shafts are a fraction of it
    masses      the masses' spheres, drawn see-through while an arrow is shown
    view        the scene's VIEW with the defaults: the picture the scales are chosen for
    make_room   called with the camera range, m, that holds the run's arrows once scales are chosen
    camera      gives the picture the page's camera shows now (export/framing.py's Camera), against
                which Reset rescales; None: never rescale
    """

    def __init__(self, vp, *, model, integrator: str, shown, radius: float, masses=(), view: dict,
                 make_room=lambda reach: None, camera=None):
        self.vp, self.radius, self.masses = vp, radius, list(masses)
        self.view, self.make_room, self.camera = view, make_room, camera
        self.shown = shown if isinstance(shown, set) else set(shown)   # the view's own set: kept across rebuilds
        self.model, self.integrator = model, integrator
        self._scales = None                 # chosen when an arrow is first shown (a short engine run)
        self.needed = {"p": 0.0, "F": 0.0}   # the scales that would have kept this run's tips in the camera's view
        # every arrow is made the first time it is shown: a row of 2,000 springs with none shown has none
        self.count = count = model.state.count
        self.p, self.F_net, self.step = [], [], []              # per mass (step: p_i, F_net Δt, p_f)
        self.forces: list[list] = [[] for _ in range(count)]
        self.force_labels: list[list] = [[] for _ in range(count)]
        self.parts: list[list] = [[] for _ in range(count)]    # F∥, F⊥ and their labels
        self.stepping = False
        self.shapes = []
        self.legend_text = None             # the caption's wtext that shows legend() (set by the view)

    def _made(self, arrows: list, make) -> list:
        """The list of one kind of arrow per mass, made now if it is still empty."""
        if not arrows:
            arrows.extend(make() for _ in range(self.count))
            self.shapes += [a for item in arrows for a in (item if isinstance(item, list) else [item])]
            self.publish()
        return arrows

    def publish(self) -> None:
        """Show the legend (the scales, and the objects for the tests) in the caption."""
        if self.legend_text is not None:
            self.legend_text.text = self.legend()

    def _arrow(self, colour: str, *, thin: bool = False):
        vp = self.vp
        width = (0.12 if thin else 0.2) * self.radius
        return vp.arrow(pos=vp.vector(0, 0, 0), axis=vp.vector(width, 0, 0), color=vp.vector(*ARROW_COLOURS[colour]),
                        shaftwidth=width, visible=False)

    def _label(self, colour: str, *, below: bool = False, left: bool = False):
        """A label in the arrow's colour, 18 px (read from the back row), above its point or below
        it, and right of it or (left) ending left of it."""
        vp = self.vp
        label = vp.label(pos=vp.vector(0, 0, 0), text="", height=LABEL_PX["height"],
                         color=vp.vector(*ARROW_COLOURS[colour]), box=False, line=False,
                         xoffset=-LABEL_PX["xoffset"] if left else LABEL_PX["xoffset"],
                         align="right" if left else "left",
                         yoffset=-LABEL_PX["yoffset"] if below else LABEL_PX["yoffset"], visible=False)
        self.shapes.append(label)
        return label

    # ---- what is shown ----

    def set_shown(self, kind: str, on: bool) -> None:
        (self.shown.add if on else self.shown.discard)(kind)
        self.publish()

    @property
    def scales(self):
        """The run's scales (export/arrows.py), chosen the first time they are needed."""
        if self._scales is None:
            self._scales = choose_scales(self.model, view=self.view, integrator=self.integrator,
                                         forces="forces" in self.shown)
            self.make_room(self._scales.view_range)
        return self._scales

    def rescale(self, model, *, integrator: str) -> None:
        """A new run (new constants or integrator): scales chosen again for it."""
        self.model, self.integrator, self._scales = model, integrator, None
        self.needed = {"p": 0.0, "F": 0.0}
        self.publish()

    def reset(self) -> None:
        """Reset: if an arrow tip of the run just ended left the picture the camera showed, the next
        round scale that keeps it in; no Step shown."""
        scales = self._scales
        if scales is not None and (self.needed["p"] > scales.p_unit or self.needed["F"] > scales.F_unit):
            self._scales = scales.refitted(p_needed=self.needed["p"], F_needed=self.needed["F"])
            self.publish()
        self.needed = {"p": 0.0, "F": 0.0}
        self.stepping = False

    def objects(self) -> dict:
        """Each arrow's index among the page's GlowScript objects, and the scales (for the tests)."""
        def ids(arrows):
            return [a.idx for a in arrows]
        return {"p": ids(self.p), "F_net": ids(self.F_net), "forces": [ids(f) for f in self.forces],
                "F_par": [p[0].idx if p else None for p in self.parts],
                "F_perp": [p[1].idx if p else None for p in self.parts],
                "step": [ids(trio) for trio in self.step],
                "p_unit": self._scales and self._scales.p_unit, "F_unit": self._scales and self._scales.F_unit}

    def legend(self) -> str:
        """The scales in words, with the hidden element the tests read."""
        data = json.dumps(self.objects()).replace("'", "&#39;")
        words = self.scales.legend() if self.shown or self._scales is not None else ""
        return f"{words}<span id='arrow-objects' hidden data-objects='{data}'></span>"

    # ---- drawing ----

    def draw(self, live) -> None:
        """Put every arrow shown on its mass, at the state now (once per frame)."""
        self._see_through(bool(self.shown))
        if not self.shown and not self.stepping:
            for arrow in self.p + self.F_net:
                if arrow.visible:
                    arrow.visible = False
            for i in range(len(self.forces)):
                self._draw_forces(i, live.state.r[i], [], False)
                self._draw_split(i, live.state.r[i], None, None, False)
            return
        state, model = live.state, live.model
        r, p, m = state.r, state.p, state.m
        v = velocity(p, m)
        F_net = net_force(model.forces, state.t, r, v, m)
        scales = self.scales
        if "p" in self.shown:
            self._made(self.p, lambda: self._arrow("p"))
        if "F_net" in self.shown:
            self._made(self.F_net, lambda: self._arrow("F_net"))
        finite = np.all(np.isfinite(r), axis=1) & np.all(np.isfinite(p), axis=1)
        moving = [i for i in range(len(r)) if finite[i] and i not in live.runaways]
        each = forces_each(model.forces, state.t, r, v, m) if "forces" in self.shown else []
        self._measure(r[moving], p[moving], [F_net[moving]] + [F[moving] for F in np.cumsum(each, axis=0)])
        along, across = split(F_net, p) if "split" in self.shown else (None, None)
        for i in range(len(r)):
            ok = i in moving
            if self.p:
                self._place(self.p[i], r[i], scales.momentum_axis(p[i]), ok and "p" in self.shown and not self.stepping)
            if self.F_net:
                self._place(self.F_net[i], r[i], scales.force_axis(F_net[i]), ok and "F_net" in self.shown)
            self._draw_forces(i, r[i], each, ok and "forces" in self.shown)
            self._draw_split(i, r[i], along, across, ok and "split" in self.shown)

    def _measure(self, r, p, forces) -> None:
        """Note the scales that would have kept the tips shown (p; F_net and, tip to tail, each
        force) in the picture the camera shows now (it may have zoomed out after a mass): Reset
        picks them up."""
        if self.camera is None:
            return
        camera, scales = self.camera(), self.scales
        margin = TIP_ROOM * self.radius
        shown = [("p", p, scales.p_unit)] if "p" in self.shown and not self.stepping else []
        shown += [("F", F, scales.F_unit) for F in forces[:1 if "F_net" in self.shown else 0] + forces[1:]]
        for key, q, unit in shown:
            if len(q):
                self.needed[key] = max(self.needed[key], unit_keeping_in(camera, r, q, unit=unit, margin=margin))

    def _see_through(self, on: bool) -> None:
        """The masses see-through while arrows start at their centres, solid otherwise."""
        opacity = SEE_THROUGH if on else 1.0
        for mass in self.masses:
            if mass.opacity != opacity:
                mass.opacity = opacity

    def _place(self, arrow, at, axis, visible: bool) -> None:
        """An arrow from `at` along `axis` (m); hidden when off or of no length."""
        vp = self.vp
        visible = bool(visible and np.linalg.norm(axis) > 0)
        if visible:
            arrow.pos = vp.vector(*map(float, at))
            arrow.axis = vp.vector(*map(float, axis))
        if arrow.visible != visible:
            arrow.visible = visible

    def _draw_forces(self, i: int, at, each, visible: bool) -> None:
        """Each force on mass i on its own arrow, tip to tail, labelled with its name (every other
        one on the left)."""
        arrows, labels = self.forces[i], self.force_labels[i]
        if visible:
            while len(arrows) < len(each):
                arrows.append(self._arrow("forces", thin=True))
                labels.append(self._label("forces", left=len(labels) % 2 == 1))   # tip to tail, two forces
                # along one line (a hanging mass's spring and gravity) have their names on either side
                self.shapes.append(arrows[-1])
                self.publish()
        tail = np.asarray(at, float)
        for n, (arrow, label) in enumerate(zip(arrows, labels)):
            on = visible and n < len(each)
            axis = self.scales.force_axis(each[n][i]) if on else np.zeros(3)
            self._place(arrow, tail, axis, on)
            if on and np.linalg.norm(axis) > 0:
                label.pos = self.vp.vector(*map(float, tail + 0.5 * axis))
                label.text = force_name(self.model.forces[n])
                tail = tail + axis
            if label.visible != bool(on and np.linalg.norm(axis) > 0):
                label.visible = bool(on and np.linalg.norm(axis) > 0)

    def _draw_split(self, i: int, at, along, across, visible: bool) -> None:
        """F∥ and F⊥ of mass i, each labelled with its magnitude in N."""
        if visible and not self.parts[i]:
            self.parts[i] = [self._arrow("F_par"), self._arrow("F_perp"), self._label("F_par"),
                             self._label("F_perp", below=True)]   # short F∥ and F⊥: their labels apart
            self.shapes += self.parts[i][:2]
            self.publish()
        if not self.parts[i]:
            return
        par, perp, par_label, perp_label = self.parts[i]
        for arrow, label, name, F in ((par, par_label, "F∥", along), (perp, perp_label, "F⊥", across)):
            axis = self.scales.force_axis(F[i]) if visible else np.zeros(3)
            self._place(arrow, at, axis, visible)
            if visible:
                label.pos = self.vp.vector(*map(float, np.asarray(at) + axis))
                label.text = f"{name} = {PART_DIGITS.format(np.linalg.norm(F[i]))} N"
            if label.visible != bool(visible and np.linalg.norm(axis) > 0):
                label.visible = bool(visible and np.linalg.norm(axis) > 0)

    def show_step(self, *, r_f, p_i, impulse, p_f) -> None:
        """Draw one Step as vector addition at each mass: p_i, F_net Δt from its tip, and p_f = p_i + F_net Δt."""
        self.stepping = True
        self._made(self.step, lambda: [self._arrow("p_i"), self._arrow("F_net"), self._arrow("p")])
        for i, (arrow_i, arrow_dp, arrow_f) in enumerate(self.step):
            a_i, a_dp = self.scales.momentum_axis(p_i[i]), self.scales.momentum_axis(impulse[i])
            a_f = self.scales.momentum_axis(p_f[i])
            # beside the mass, across the motion on the screen, so that on a line (vertical, driven)
            # the sum and p_f do not hide each other or F_net: p_i + F_net Δt, then p_f beside it
            across = np.array([0.0, 1.0, 0.0]) if abs(a_f[0]) > abs(a_f[1]) else np.array([1.0, 0.0, 0.0])
            at = np.asarray(r_f[i], float) + 1.4 * self.radius * across
            self._place(arrow_i, at, a_i, True)
            self._place(arrow_dp, at + a_i, a_dp, True)
            self._place(arrow_f, at + 0.45 * self.radius * across, a_f, True)

    def end_step(self) -> None:
        """Run or Reset: the Step's arrows go, the p arrow comes back."""
        self.stepping = False
        for trio in self.step:
            for arrow in trio:
                arrow.visible = False

    def take_down(self) -> None:
        for shape in self.shapes:
            shape.visible = False
        self.shapes = []

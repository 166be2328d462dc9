"""Lines a student measures against in the 3-D view: the natural length, the equilibrium, a marker.

    natural length  where each mass would be with its spring relaxed, L0 from the anchor
    equilibrium     where each mass would rest (L0 + m g / k below the anchor on a vertical spring)
    marker          a line the student drags (or clicks) to a turning point; it shows its height

Where each mass would be comes from the forces themselves (physics/equilibrium.py: F_net = 0 at
rest, and each tether's declared length), so a new force moves these lines with no change here.
The lines cross the direction the scene moves in (VIEW["plot"]: horizontal lines for a hanging
spring, vertical ones for a spring on a table): a short line through each mass's own place, with
one label. Each is switched by a check box in the Measure panel (browser/measure_panel.py) and
hidden at first.

Where the mouse is pressed on the canvas with the marker shown, the marker moves there, and follows
the mouse while the button is held: vpython reports the mouse's place in the plane the camera
looks at (scene.mouse.pos), on its server thread, so the press only queues a MoveMarker message.
"""
from __future__ import annotations

import numpy as np

from export.palette import BLUISH_GREEN, SKY_BLUE, VERMILION
from physics.equilibrium import equilibrium, natural_length

from .messages import MoveMarker
from .readout import NO_BREAK

LINES = ("natural", "equilibrium", "marker")
LINE_NAMES = {"natural": "natural length", "equilibrium": "equilibrium", "marker": "marker"}
LINE_COLOURS = {"natural": SKY_BLUE, "equilibrium": BLUISH_GREEN, "marker": VERMILION}
LABEL_HEIGHT = 18        # px, as the masses' labels (the page's script makes it larger in projector mode)
HALF_LENGTH = 2.6        # × the masses' radius: each line reaches this far either side of its mass
MARKER_LABEL = 0.5       # × the camera's range: the marker's label, left of the middle (the lines' are right)


def marker_axis(view: dict) -> int:
    """The coordinate the lines mark, 0 for x or 1 for y: the scene's plotted one (y for a
    pendulum that moves in all three: its height)."""
    return 0 if view["plot"] == "x" else 1


def places(model) -> dict:
    """Where the natural-length and equilibrium lines go, {kind: (N, 3) m or None}."""
    centre = equilibrium(model.forces, model.state)
    return {"equilibrium": centre, "natural": natural_length(model.forces, model.state, centre)}


class ReferenceLines:
    """The three lines of one scene's picture, each hidden until its check box is ticked.

    vp      the vpython module
    model   the scene's Model (forces, masses, start)
    view    the scene's VIEW with the defaults (plot)
    radius  the masses' radius, m: the lines' length and thickness follow it
    centre  where the camera looks, m: the marker starts there
    reach   the camera's range, m: the marker reaches across the picture
    shown   the lines switched on (a set of LINES), kept by the view across rebuilds
    """

    def __init__(self, vp, *, model, view: dict, radius: float, centre, reach: float, shown: set):
        self.vp, self.radius, self.reach = vp, radius, reach
        self.axis = marker_axis(view)
        self.across = 1 - self.axis                       # the lines run along the other axis
        self.shown = shown
        self.shapes, self.lines = [], {}
        self.at = places(model)
        self.count = model.state.count
        self.marker_at = float(np.asarray(centre, dtype=float)[self.axis])
        self.marker_middle = np.asarray(centre, dtype=float).copy()
        for kind in ("natural", "equilibrium"):
            self.lines[kind] = self._make(kind)
        self.lines["marker"] = self._make_marker()
        for kind in LINES:
            self._show(kind, kind in shown)

    # ---- building ----

    def _segment(self, point, half: float):
        ends = []
        for sign in (-1, 1):
            end = np.array(point, dtype=float)
            end[self.across] += sign * half
            ends.append(self.vp.vector(*end))
        return ends

    def _make(self, kind: str):
        """A short line through each mass's place of this kind, and one label: [] where it has none."""
        where = self.at[kind]
        if where is None:
            return []
        vp, colour = self.vp, vp_colour(self.vp, LINE_COLOURS[kind])
        shapes = []
        places_drawn = where[:LABELLED_LINES] if self.count > LABELLED_LINES else where
        for point in places_drawn:
            shapes.append(vp.curve(pos=self._segment(point, HALF_LENGTH * self.radius), color=colour,
                                   radius=0.04 * self.radius))
        # natural length's label at the line's lower or left end, equilibrium's at the other: on
        # a table (g = 0) the two lines are one, and their labels must not cover each other
        side = -1 if kind == "natural" else 1
        end = np.array(where[0], dtype=float)
        end[self.across] += side * HALF_LENGTH * self.radius
        value = float(where[0][self.axis])
        if self.across == 0:     # horizontal lines: the label beside the end, outward
            place = {"xoffset": 12 * side, "yoffset": 0, "align": "left" if side > 0 else "right"}
        else:                    # vertical lines: above the top end, below the bottom one
            place = {"xoffset": 0, "yoffset": 16 if side > 0 else -40, "align": "center"}
        shapes.append(vp.label(pos=vp.vector(*end), text=f"{LINE_NAMES[kind]}\n{self._value_text(value)}",
                               height=LABEL_HEIGHT, color=colour, box=False, line=False, opacity=0, **place))
        self.shapes += shapes
        return shapes

    def _make_marker(self):
        vp, colour = self.vp, vp_colour(self.vp, LINE_COLOURS["marker"])
        point = self.marker_middle.copy()
        point[self.axis] = self.marker_at
        line = vp.curve(pos=self._segment(point, 1.2 * self.reach), color=colour, radius=0.05 * self.radius)
        end = point.copy()
        end[self.across] -= MARKER_LABEL * self.reach
        self.marker_label = vp.label(pos=vp.vector(*end), text=self.marker_text(), yoffset=14, align="right",
                                     height=LABEL_HEIGHT, color=colour, box=False, line=False, opacity=0)
        self.marker_line = line
        self.shapes += [line, self.marker_label]
        return [line, self.marker_label]

    # ---- what the student does ----

    def set_shown(self, kind: str, shown: bool) -> None:
        if shown:
            self.shown.add(kind)
        else:
            self.shown.discard(kind)
        self._show(kind, shown)

    def _show(self, kind: str, shown: bool) -> None:
        for shape in self.lines[kind]:
            shape.visible = shown

    def move_marker(self, position) -> None:
        """Put the marker at a place in the picture, m (its coordinate along the motion counts)."""
        value = float(position[self.axis])
        if not np.isfinite(value) or value == self.marker_at:
            return
        self.marker_at = value
        point = self.marker_middle.copy()
        point[self.axis] = value
        for n, end in enumerate(self._segment(point, 1.2 * self.reach)):
            self.marker_line.modify(n, pos=end)
        label = point.copy()
        label[self.across] -= MARKER_LABEL * self.reach
        self.marker_label.pos = self.vp.vector(*label)
        self.marker_label.text = self.marker_text()

    def marker_text(self) -> str:
        return f"marker {self._value_text(self.marker_at)}"

    def _value_text(self, value: float) -> str:
        return f"{'xy'[self.axis]} = {value:.3f}{NO_BREAK}m".replace("-", "−")

    def bind_mouse(self, put) -> None:
        """A press on the canvas moves the marker there, and it follows while the button is held
        (only while it is shown)."""
        held = {"down": False}

        def pressed(event):
            if "marker" in self.shown:
                held["down"] = True
                put(MoveMarker(float(event.pos.x), float(event.pos.y), float(event.pos.z)))

        def moved(event):
            if held["down"] and "marker" in self.shown:
                put(MoveMarker(float(event.pos.x), float(event.pos.y), float(event.pos.z)))

        def released(event):
            held["down"] = False

        self.handlers = (pressed, moved, released)
        for name, handler in zip(("mousedown", "mousemove", "mouseup"), self.handlers):
            self.vp.scene.bind(name, handler)

    def take_down(self) -> None:
        for shape in self.shapes:
            shape.visible = False
        self.shapes = []
        if getattr(self, "handlers", None):
            for name, handler in zip(("mousedown", "mousemove", "mouseup"), self.handlers):
                self.vp.scene.unbind(name, handler)
            self.handlers = None


LABELLED_LINES = 13     # a long row of springs (resonance's 39) gets lines at its first row's masses only


def vp_colour(vp, rgb):
    return vp.vector(*rgb)

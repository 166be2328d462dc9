"""The page's 3-D picture: the support, a helix per spring, a sphere per mass, trails, the camera.

A scene's VIEW names the support ("ceiling" or "wall"), whether to draw trails and how many coils
each helix has. The picture is framed on the region the masses use over the first 20 s; it zooms
out (never in) after a mass that matters, and a mass the scene expects may run away is frozen
where it leaves the picture and labelled with its method and time.
"""
from __future__ import annotations

import math

import numpy as np

from export.framing import CANVAS_SIZE, Camera, camera_range, frame, mass_radius, motion_box
from export.palette import ORANGE, SKY_BLUE, mass_colours

from .mass_labels import mass_labels

TRAIL_POINTS = 300        # points kept in a trail: the last 15 s at one point per graph sample (0.05 s)
TRAIL_RADIUS = 0.03       # × the masses' radius: a trail's thickness
TRAIL_SHADE = 0.6         # a trail's colour: this much of its palette colour, the rest the background's
SUPPORT_COLOUR = (0.6, 0.6, 0.65)
SPRING_COLOUR = (0.85, 0.85, 0.9)
BACKGROUND = (0.12, 0.13, 0.16)
LABEL_HEIGHT = 18         # px: the masses' labels, as the page's smallest text
SMALLEST_MASS_PX = 4      # px: a motion framed whole would draw the spheres smaller than this (a fall
                          # with no spring, 150 m and more): the camera follows the masses instead


class Scene3D:
    """The 3-D objects of one scene on vpython's canvas, built from the model at t = 0.

    vp      the vpython module (already imported, loopback-only, by browser/loopback_server.py)
    model   the scene's Model: anchors, initial state, exact solution
    view    the scene's VIEW merged with the defaults (support, trail, coils)
    title   the heading above the picture
    """

    def __init__(self, vp, *, model, view: dict, title: str):
        self.vp = vp
        canvas = vp.scene
        canvas.width, canvas.height = CANVAS_SIZE
        canvas.background = vp.vector(*BACKGROUND)
        canvas.fov = 0.2  # rad: a long lens, so the support and springs look flat, as in a drawing
        canvas.title = title
        self.frame = framed = frame(model, view)   # export/framing.py: the arrows' scales use it too
        anchors = model.anchors
        self.radius = radius = framed.radius
        support = vp.box(pos=vec(vp, framed.support_pos), size=vec(vp, framed.support_size),
                         color=vp.vector(*SUPPORT_COLOUR))
        self.wall = framed.wall
        # Rows one behind another (resonance) hid each other from the front: look down on them a little.
        self.pitch = framed.camera.pitch
        canvas.forward = vp.vector(0, -self.pitch, -1)
        self.support_box = (framed.support_pos - 0.5 * framed.support_size,
                            framed.support_pos + 0.5 * framed.support_size)
        self.centre, self.range, self.max_range = self._frame_camera(framed.camera.centre, framed.camera.range)
        self.follows_from_start = self._follow_if_tiny(model.state.r)
        self.following = self.follows_from_start  # the camera follows the masses (they left the widest view)
        self.home, self.home_range = self.centre, self.range
        # A long row gets fewer turns per spring: each turn is many triangles for the browser.
        coils = max(4, min(view["coils"], round(4 * view["coils"] / len(anchors))))
        self.springs, self.masses = [], []
        colours = mass_colours(model, view)  # each mass's, as its curves on the graphs
        for anchor, r, colour in zip(anchors, model.state.r, colours):
            self.springs.append(vp.helix(pos=vec(vp, anchor), axis=vec(vp, r - anchor),
                                         radius=0.45 * radius, thickness=0.12 * radius,
                                         coils=coils, color=vp.vector(*SPRING_COLOUR)))
            self.masses.append(vp.sphere(pos=vec(vp, r), radius=radius, color=vp.vector(*colour)))
        # The trail is drawn from the graph samples (every 0.05 s of simulation time), not by
        # vpython's make_trail, which adds a point only when the page draws a frame: on a busy
        # computer that is a few times a second, and the trail came out as jagged straight segments.
        # Thin, in a hue that is not the ball's, dimmed towards the background: the ball stands out
        # on it, see-through or not (in the ball's own colour, the pendulum's ball was lost in its rosette).
        self.trails = [vp.curve(color=vp.vector(*trail_colour(colour)), radius=TRAIL_RADIUS * radius,
                                retain=TRAIL_POINTS)
                       for colour in colours] if view["trail"] else []
        self.runaway_labels: dict = {}  # mass index -> its label, once it has run away
        self.last_open: dict = {}       # mass index -> its last position inside the picture, m
        specs = mass_labels(model, view)
        # the outermost labelled masses of a hanging row: their labels go outward, beside them
        xs = [float(model.state.r[spec.index][0]) for spec in specs if spec.side == "above"]
        self.outer_x = (min(xs), max(xs)) if len(xs) > 1 and view["support"] == "ceiling" else ()
        self.labels = [(spec, self._make_label(spec, model.state.r[spec.index], view)) for spec in specs]
        self.shapes = [support, *self.springs, *self.masses, *self.trails, *(label for _, label in self.labels)]

    def _make_label(self, spec, r, view):
        """A mass's label (browser/mass_labels.py): white text beside it, out of its spring's way."""
        vp = self.vp
        pixels = 0.5 * CANVAS_SIZE[1] / self.range * self.radius  # the sphere's radius on the page, px
        xoffset, yoffset, align = 0, 0, "center"
        if spec.side == "left":        # ending just left of the row's first mass: centred 60 px out,
            xoffset, align = -(pixels + 8), "right"   # resonance's "b = 0.5 kg/s" ran off the canvas at 1024 px
        elif spec.side == "above" and float(r[0]) in self.outer_x:  # beside the ball, outward: under
            outward = -1 if float(r[0]) == self.outer_x[0] else 1      # them, the two labels of drag ran
            xoffset = outward * (pixels + 6)                           # into each other at 1024 px
            align = "right" if outward < 0 else "left"
        elif view["support"] == "wall" and spec.side == "above":
            xoffset = pixels + 70      # beyond a mass on a horizontal spring, in the open
        else:
            yoffset = -(pixels + 24)   # under a hanging mass: its spring is above it
        return vp.label(pos=vec(vp, r), text=spec.text, xoffset=xoffset, yoffset=yoffset, align=align,
                        height=LABEL_HEIGHT, color=vp.vector(1, 1, 1), box=False, line=False, opacity=0)

    def reframe(self, model) -> None:
        """Frame the new motion and the support once, after a new constant: in or out, as it needs.

        Without this the view would only zoom out after the mass (a heavier mass hangs lower), and
        the masses would shrink with every change.
        """
        low, high = motion_box(model)
        radius = mass_radius(low, high, model.anchors)  # a mass swinging 20 m is drawn bigger
        if radius != self.radius:
            self.radius = radius
            for mass, spring in zip(self.masses, self.springs):
                mass.radius = radius
                spring.radius, spring.thickness = 0.45 * radius, 0.12 * radius
        low = np.minimum(low - 1.3 * radius, self.support_box[0])
        high = np.maximum(high + 1.3 * radius, self.support_box[1])
        self.centre, self.range, self.max_range = self._frame_camera(0.5 * (low + high),
                                                                     camera_range(low, high, self.pitch))
        self.follows_from_start = self._follow_if_tiny(model.state.r)
        self.following = self.follows_from_start
        self.home, self.home_range = self.centre, self.range

    def _follow_if_tiny(self, r) -> bool:
        """Whether the framed motion is so large that the spheres would be dots (a fall with no
        spring: 150 m and more in 20 s, from balls 1 m apart); if so, frame the masses themselves,
        close up, and follow them from the start. Returns whether the camera follows."""
        pixels = 0.5 * CANVAS_SIZE[1] / self.range * self.radius  # the sphere's radius on the page, px
        if pixels >= SMALLEST_MASS_PX:
            return False
        self._follow(r[np.all(np.isfinite(r), axis=1)])
        return True

    def _frame_camera(self, centre, reach: float) -> tuple[np.ndarray, float, float]:
        """Point the camera at centre with this range (export/framing.py); returns the centre, the
        range and the range the view may zoom out to (twice that)."""
        canvas = self.vp.scene
        canvas.autoscale = False
        canvas.center = vec(self.vp, centre)
        canvas.range = reach
        return np.asarray(centre, float), reach, 2 * reach

    def camera(self) -> Camera:
        """What the camera shows now: where it looks, its range (after any zoom out), its pitch."""
        return Camera(centre=np.asarray(self.centre, float), range=float(self.range), pitch=self.pitch)

    def make_room(self, reach: float) -> None:
        """Widen the picture to this range, m (the arrows' tips at their scales), never narrow it;
        not a camera that follows the masses from the start (a fall with no spring), whose framed
        view would draw them as dots."""
        if reach > self.home_range and not self.follows_from_start:
            self.home_range = reach
            self.max_range = max(self.max_range, 2 * reach)
            if not self.following:
                self.range = max(self.range, reach)
                self.vp.scene.range = self.range

    def clear(self) -> None:
        """Back to t = 0: no trails, no runaway labels."""
        for label in self.runaway_labels.values():
            label.visible = False
        self.runaway_labels = {}
        self.last_open = {}
        for trail in self.trails:
            trail.clear()
        for _, label in self.labels:
            label.visible = True
        self.following = self.follows_from_start
        if not np.array_equal(self.centre, self.home):  # the camera followed a fall: back to the start
            self.centre, self.range = self.home, self.home_range
            self.vp.scene.center, self.vp.scene.range = vec(self.vp, self.home), self.range

    def extend_trails(self, samples, runaways) -> None:
        """Add the graph samples' positions to each mass's trail (not to a mass that ran away), and
        keep each mass's last position in the open, where a runaway is frozen."""
        if not samples:
            return
        r = np.array([s.r for s in samples])
        for i in range(r.shape[1]):
            if i not in runaways:
                for where in r[::-1, i]:
                    if self._in_the_open(where):
                        self.last_open[i] = where
                        break
        if not self.trails:
            return
        for i, trail in enumerate(self.trails):
            points = [vec(self.vp, where) for where in r[:, i] if np.all(np.isfinite(where))]
            if points and i not in runaways:
                trail.append(points)

    def draw(self, live, *, matter) -> None:
        """Move the masses and springs to the run's state now; follow the masses that matter."""
        vp, state, anchors = self.vp, live.state, live.model.anchors
        for i, (mass, spring, anchor, r) in enumerate(zip(self.masses, self.springs, anchors, state.r)):
            if i in live.runaways:  # frozen: shown, and labelled, where it was last in the open
                r = self.last_open[i] if i in self.last_open else self._inside_frame(anchor, r)
                self._label_runaway(i, r, live)
            if np.all(np.isfinite(r)):
                mass.pos = vec(vp, r)
                spring.axis = vec(vp, r - anchor)  # the helix runs from the anchor to the mass
        for spec, label in self.labels:
            if spec.index in live.runaways:
                label.visible = False  # its runaway label names it
            elif spec.follows and np.all(np.isfinite(state.r[spec.index])):
                label.pos = vec(vp, state.r[spec.index])
        self._keep_in_view(state.r[matter])

    def take_down(self) -> None:
        """Hide every object (vpython 7.6.5 cannot delete a 3-D object from the page) and turn the
        camera back to face the page, for the next scene."""
        vp = self.vp
        for shape in self.shapes:
            shape.visible = False
        self.shapes = []
        vp.scene.forward, vp.scene.up = vp.vector(0, 0, -1), vp.vector(0, 1, 0)

    def _in_the_open(self, r) -> bool:
        """Whether a mass at r is inside the picture and not in or behind the wall."""
        width, height = CANVAS_SIZE
        half = np.array([self.range * width / height, self.range]) - 1.5 * self.radius
        inside = np.all(np.isfinite(r)) and np.all(np.abs(r[:2] - self.centre[:2]) <= half)
        return bool(inside and not (self.wall and r[0] < self.support_box[1][0] + 1.5 * self.radius))

    def _inside_frame(self, anchor, r):
        """The point where the line from the anchor to r leaves the picture (r itself if inside), m."""
        width, height = CANVAS_SIZE
        half = np.array([self.range * width / height, self.range, math.inf]) - 1.5 * self.radius
        d = r - anchor
        scale = 1.0
        for axis in (0, 1):
            if abs(d[axis]) > 1e-12:
                edge = self.centre[axis] + math.copysign(half[axis], d[axis])
                if axis == 0 and d[0] < 0 and self.wall:  # frozen in the open, in front of the wall
                    edge = max(edge, self.support_box[1][0] + 1.5 * self.radius)
                scale = min(scale, max(0.0, (edge - anchor[axis]) / d[axis]))
        return anchor + scale * d if np.all(np.isfinite(d)) else anchor

    def _label_runaway(self, i: int, where, live) -> None:
        """Label mass i, frozen after running away, with its method and time (once)."""
        if i in self.runaway_labels:
            return
        t, _ = live.runaways[i]
        label = self.vp.label(pos=vec(self.vp, where), text=f"{live.model.labels[i]} ran away\nat t = {t:.2f} s",
                              **self._runaway_place(where), height=LABEL_HEIGHT, color=self.vp.vector(1, 1, 1),
                              box=False, line=False)
        self.runaway_labels[i] = label
        self.shapes.append(label)

    def _runaway_place(self, where) -> dict:
        """Where a runaway's label sits: beside its frozen ball, toward the middle of the picture so
        the text stays inside it; in front of a wall, on the open side (centred 60 px left of a ball
        just right of the middle, integrators' "euler ran away" covered the wall)."""
        pixels = 0.5 * CANVAS_SIZE[1] / self.range * self.radius  # the sphere's radius on the page, px
        from_middle = (where[0] - self.centre[0]) / self.range * 0.5 * CANVAS_SIZE[1]   # px
        if from_middle < 0 or (self.wall and from_middle < 0.25 * CANVAS_SIZE[0]):
            return {"xoffset": pixels + 8, "yoffset": 0, "align": "left"}
        return {"xoffset": -(pixels + 8), "yoffset": 0, "align": "right"}

    def _follow(self, r) -> None:
        """Centre the camera on the masses at r, close enough to see the balls and their labels."""
        width, height = CANVAS_SIZE
        low, high = r.min(axis=0), r.max(axis=0)
        self.centre = 0.5 * (low + high)
        span = high - low + 8 * self.radius
        self.range = 0.55 * max(span[1], span[0] * height / width)
        self.vp.scene.center = vec(self.vp, self.centre)
        self.vp.scene.range = self.range

    def _keep_in_view(self, r) -> None:
        """Zoom out (never in) if a mass that matters leaves the framed region, up to max_range;
        once the masses leave even that (a fall with no spring), follow them from close by.

        A mass the scene expects may run away (euler) is not followed: it leaves the picture, is
        frozen and labelled, instead of shrinking every other mass to a dot.
        """
        finite = r[np.all(np.isfinite(r), axis=1)]
        if not len(finite):
            return
        width, height = CANVAS_SIZE
        reach = np.abs(finite - self.centre).max(axis=0)
        needed = max(reach[1], reach[0] * height / width) + self.radius
        self.following = self.following or needed > self.max_range
        if self.following:  # out of even the widest view (falling, no spring): the camera follows them
            self._follow(finite)
        elif self.range < needed and self.range < self.max_range:
            self.range = min(1.5 * needed, self.max_range)
            self.vp.scene.range = self.range


def trail_colour(colour) -> tuple[float, float, float]:
    """A mass's trail: sky blue, or orange behind a sky-blue mass (export/palette.py), dimmed
    towards the picture's background."""
    hue = ORANGE if tuple(colour) == SKY_BLUE else SKY_BLUE
    return tuple(TRAIL_SHADE * c + (1 - TRAIL_SHADE) * b for c, b in zip(hue, BACKGROUND))


def vec(vp, a):
    """A numpy 3-vector as a vpython vector."""
    return vp.vector(float(a[0]), float(a[1]), float(a[2]))

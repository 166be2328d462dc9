"""Where the page's camera looks: the region a scene's motion and support take, and what the
picture shows of it. Pure arithmetic on the model (no vpython), so that the page
(browser/scene3d.py) frames its camera with it and the arrows' scales (export/arrows.py), which
the handed-out program shares, are chosen against the same picture.

The picture is CANVAS_SIZE pixels; the camera looks along `forward` (straight at the scene, or a
little down on rows one behind another) at `centre`, and `range` is the distance from the centre
to the picture's top and bottom edges, m (the sides are range × width / height away).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

CANVAS_SIZE = (900, 440)  # px
ROWS_PITCH = 0.45         # the camera looks down this much (forward's y to its z) on rows one behind another


@dataclass(frozen=True)
class Camera:
    """What the camera shows: it looks at centre, m, from range, m, away from the top edge (the
    sides are range × width / height away), along forward = (0, −pitch, −1)."""

    centre: np.ndarray
    range: float
    pitch: float = 0.0

    def on_screen(self, points) -> np.ndarray:
        """Points (…, 3), m, as (right, up) distances from the picture's centre, m."""
        forward = np.array([0.0, -self.pitch, -1.0]) / np.hypot(1.0, self.pitch)
        up = np.array([0.0, 1.0, 0.0]) - forward[1] * forward
        up /= np.linalg.norm(up)
        right = np.cross(forward, up)
        d = np.asarray(points, float) - self.centre
        return np.stack([d @ right, d @ up], axis=-1)

    def half(self) -> np.ndarray:
        """The distances from the centre to the picture's side and top edges, m."""
        width, height = CANVAS_SIZE
        return np.array([self.range * width / height, self.range])

    def range_holding(self, points) -> float:
        """The smallest range, m, at which this camera (same centre) shows every finite point."""
        screen = self.on_screen(points).reshape(-1, 2)
        screen = screen[np.all(np.isfinite(screen), axis=1)]
        if not len(screen):
            return 0.0
        width, height = CANVAS_SIZE
        return float(max(np.abs(screen[:, 1]).max(), np.abs(screen[:, 0]).max() * height / width))


@dataclass(frozen=True)
class Frame:
    """The page's framing at t = 0: the camera, the masses' radius, m, and the support's box (its
    centre and size, m), a wall or a ceiling."""

    camera: Camera
    radius: float
    support_pos: np.ndarray
    support_size: np.ndarray
    wall: bool
    box: tuple = (0.0, 0.0)    # m: the width and height the picture must show (camera_range's), for another canvas size

    def face(self) -> tuple[int, float, int]:
        """The support's face the masses hang or push from, as (axis, where, towards): the
        ceiling's underside, y = where, above the masses (towards +y), or the wall's face,
        x = where, left of them (towards −x). An arrow that crosses it reads as going through."""
        low, high = self.support_pos - self.support_size / 2, self.support_pos + self.support_size / 2
        return (0, float(high[0]), -1) if self.wall else (1, float(low[1]), 1)


def frame(model, view: dict) -> Frame:
    """The page's framing of a scene at t = 0: its motion over the first 20 s (motion_box), the
    spheres, the support (view["support"]: "wall" or "ceiling"), and room beside rows for their labels."""
    low, high = motion_box(model)
    anchors = model.anchors
    radius = mass_radius(low, high, anchors)
    thickness, pad = 0.4 * radius, 2 * radius
    low, high = low - radius, high + radius  # the spheres' own size
    rows = np.ptp(anchors[:, 2]) > 0
    if rows:                                 # room on the left for each row's label, and under the front row
        size = high - low
        low = low - [0.3 * float(size[0]), 0.35 * float(size[1]), 0]
    centre = 0.5 * (low + high)
    wall = view["support"] == "wall"
    if wall:
        wall_x = float(anchors[:, 0].min())
        span_y = float(high[1] - low[1]) + 2 * pad
        pos = np.array([wall_x - thickness / 2, centre[1], centre[2]])
        size = np.array([thickness, span_y, 2 * radius])
        low = np.minimum(low, [wall_x - thickness, centre[1] - span_y / 2, low[2]])
        high = np.maximum(high, [high[0], centre[1] + span_y / 2, high[2]])
    else:
        ceiling_y = float(anchors[:, 1].max())
        span_x = float(high[0] - low[0]) + 2 * pad
        depth = float(np.ptp(anchors[:, 2])) + 2 * radius  # rows one behind another hang from it too
        pos = np.array([centre[0], ceiling_y + thickness / 2, float(np.mean(anchors[:, 2]))])
        size = np.array([span_x, thickness, depth])
        low = np.minimum(low, [centre[0] - span_x / 2, low[1], low[2]])
        high = np.maximum(high, [centre[0] + span_x / 2, ceiling_y + thickness, high[2]])
    pitch = ROWS_PITCH if rows else 0.0
    low, high = low - 0.3 * radius, high + 0.3 * radius
    camera = Camera(centre=0.5 * (low + high), range=camera_range(low, high, pitch), pitch=pitch)
    extent = np.asarray(high) - np.asarray(low)
    return Frame(camera=camera, radius=radius, support_pos=pos, support_size=size, wall=wall,
                 box=(float(extent[0]), float(extent[1] + pitch * extent[2])))


def camera_range(low, high, pitch: float = 0.0) -> float:
    """The range, m, that shows the box from low to high with a margin of 10 %: the distance from
    the centre to the nearer (here: top and bottom) edge; looking down on rows adds their depth
    to the height the picture must show."""
    width, height = CANVAS_SIZE
    box = np.asarray(high) - np.asarray(low)
    return 0.55 * max(box[1] + pitch * box[2], box[0] * height / width, 1e-3)


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


def mass_radius(low, high, anchors) -> float:
    """The spheres' radius, m: 8 % of the motion's size, and less than a third of the gap between anchors."""
    size = float(np.max(high - low)) or 1.0
    gaps = [np.linalg.norm(a - b) for i, a in enumerate(anchors) for b in anchors[i + 1:]]
    return min([0.08 * size] + [0.3 * gap for gap in gaps if gap > 0])

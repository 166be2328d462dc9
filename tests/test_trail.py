"""The pendulum's trail is a smooth curve through the graph samples, not frame-by-frame segments.

vpython's own make_trail adds a point only when the page draws a frame (a few times a second on a
busy computer), which drew the swing as jagged straight lines. browser/scene3d.py appends the
samples the graphs get, one every 0.05 s of simulation time, whatever the frame rate. Checked here
with a stand-in for vpython that records what is drawn (no browser, no server).
"""
from types import SimpleNamespace

import numpy as np

from browser.clock import LiveRun
from browser.scene3d import Scene3D
from browser.view import DEFAULT_VIEW
from scenes import catalog


class Shape(SimpleNamespace):
    """A drawn object that only keeps its attributes; a curve keeps its points."""

    def __init__(self, **attributes):
        super().__init__(points=[], **attributes)

    def append(self, points):
        self.points.extend(points)

    def clear(self):
        self.points.clear()


class Vec(np.ndarray):
    """A 3-vector with vpython's .x, .y, .z."""

    x = property(lambda self: float(self[0]))
    y = property(lambda self: float(self[1]))
    z = property(lambda self: float(self[2]))


class Series(Shape):
    """A graph's curve or dots: plot() adds points, delete() empties it."""

    def delete(self):
        self.points.clear()

    def plot(self, points):
        self.points.extend(points)


def stand_in_vpython():
    """What the page's parts (browser/scene3d.py, browser/graphs.py) call, as objects that only keep
    what they are given: enough to draw a scene with no browser and no server."""
    vector = lambda x, y, z: np.array([x, y, z], dtype=float).view(Vec)     # noqa: E731
    return SimpleNamespace(scene=SimpleNamespace(), vector=vector, box=Shape, helix=Shape, sphere=Shape,
                           curve=Shape, label=Shape, color=SimpleNamespace(white=vector(1, 1, 1)),
                           graph=Shape, gcurve=Series, gdots=Series, wtext=Shape)


def test_the_trail_gets_every_graph_sample_however_few_frames_the_page_draws():
    setup = catalog.configure("pendulum")
    model = setup.build()
    view = {**DEFAULT_VIEW, **setup.module.VIEW}
    assert view["trail"]
    scene = Scene3D(stand_in_vpython(), model=model, view=view, title="pendulum")
    live = LiveRun(model, integrator="euler-cromer", sample_every=0.05)
    for frame in range(4):                       # four slow frames of 2 s each: 40 samples each
        scene.extend_trails(live.advance(round(2.0 / model.dt)), live.runaways)
    (trail,) = scene.trails
    assert len(trail.points) == 160              # one point per 0.05 s of simulation, not per frame
    points = np.array(trail.points)
    assert np.allclose(points[-1], live.state.r[0])
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    size = np.ptp(points, axis=0).max()
    assert steps.max() < 0.1 * size               # short chords: the curve follows the swing smoothly

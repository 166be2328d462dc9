"""Jump to t (browser/jump.py): the page's run taken to a time in one go equals a run played there.

The local page's frame loop (browser/view.py's SceneView) is driven here without a browser, on a
stand-in for vpython that records every point each graph curve and trail is given. One view
jumps; the other plays to the same step a frame at a time, as real time at 1× does (each frame a
step or two, the last one stopping on the step). The two must agree to the last digit: the state,
W_nc, every graph point of every curve in the order given, every trail point, the period's
crossings and the samples Download CSV writes. Jumping back restarts from 0 and lands on the
same numbers; a bad t is one sentence and changes nothing.
"""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from browser.jump import MAX_JUMP_SECONDS, batches, jump_steps, jump_time
from browser.messages import JumpTo, Step
from physics.recording import steps_to_reach
from scenes import catalog


# ---- a stand-in for vpython: every object records what it is given ----

class Vector:
    """vpython's vector, as far as the page uses it (numbers of float64, as vpython's are)."""

    def __init__(self, x=0.0, y=0.0, z=0.0):
        self.x, self.y, self.z = float(x), float(y), float(z)

    def _of(self, a):
        return np.array([a.x, a.y, a.z]) if isinstance(a, Vector) else a

    def __array__(self, dtype=None, copy=None):
        return np.array([self.x, self.y, self.z], dtype=dtype)

    def _make(self, values):
        return Vector(*values)

    def __add__(self, other):
        return self._make(np.array(self) + self._of(other))

    def __sub__(self, other):
        return self._make(np.array(self) - self._of(other))

    def __mul__(self, k):
        return self._make(np.array(self) * k)

    __rmul__ = __mul__

    def __truediv__(self, k):
        return self._make(np.array(self) / k)

    def __neg__(self):
        return self._make(-np.array(self))

    def __eq__(self, other):
        return isinstance(other, Vector) and (self.x, self.y, self.z) == (other.x, other.y, other.z)

    def mag(self):
        return float(np.linalg.norm(np.array(self)))

    def __repr__(self):
        return f"vector({self.x!r}, {self.y!r}, {self.z!r})"


class Thing:
    """Any vpython object (sphere, helix, curve, graph, gcurve, wtext, button, ...): keeps what it
    is set to, records every point plotted or appended (one by one, as the page then holds them)
    and every delete or clear, and does nothing else."""

    def __init__(self, *args, **options):
        self.__dict__.update(options)
        self.given = []     # every point plotted (a graph curve) or appended (a trail), deletes, in order

    def plot(self, *points):
        self.given.extend(("point", point) for point in _each(points))

    def append(self, *points, **options):
        self.given.extend(("point", point) for point in _each(points))

    def delete(self, *args):
        self.given.append(("delete",))

    def clear(self, *args):
        self.given.append(("clear",))

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return lambda *args, **options: None      # delete, clear, bind, unbind, ...


def _plain(value):
    """A point as a tuple of floats, exactly (a Vector as its three components)."""
    if isinstance(value, Vector):
        return (value.x, value.y, value.z)
    if isinstance(value, np.ndarray):
        return tuple(value.tolist())
    return tuple(float(x) for x in value) if isinstance(value, (list, tuple)) else value


def _each(points) -> list:
    """The points of plot(...) or append(...), one by one, however they were grouped in the call:
    a frame gives one or two, a redraw the whole curve."""
    each = []
    for arg in points:
        if isinstance(arg, (list, tuple)) and arg and isinstance(arg[0], (list, tuple, Vector, np.ndarray)):
            each.extend(_plain(point) for point in arg)
        else:
            each.append(_plain(arg))
    return each


class FakeVpython:
    """The vpython module as the page uses it: every object made is kept in `made`."""

    vector = Vector

    def __init__(self):
        self.made = []
        self.scene = self._thing(caption="")
        self.scene.append_to_caption = lambda text: None

    def _thing(self, **options):
        thing = Thing(idx=len(self.made), **options)
        self.made.append(thing)
        return thing

    def canvas(self, **options):
        return self._thing(**options)

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return lambda *args, **options: self._thing(**options)


def page(scene: str, **values):
    """The local page of a scene (browser/view.py's SceneView) built on the stand-in; returns the
    view and the stand-in, which holds every object the page made."""
    import sys

    from browser.view import SceneView

    setup = catalog.configure(scene)
    setup = setup.with_values(**values) if values else setup
    model = setup.build()
    vp = FakeVpython()
    saved = sys.modules.get("vpython")
    sys.modules["vpython"] = vp          # SceneView imports vpython itself
    try:
        view = SceneView(setup=setup, model=model, integrator=model.methods()[0],
                         server=SimpleNamespace(seconds_since_contact=lambda: 0.0))
    finally:
        if saved is None:
            del sys.modules["vpython"]
        else:
            sys.modules["vpython"] = saved
    return view, vp


def click(view, message) -> None:
    """The page's click: the message queued, then one frame carries it out and draws."""
    view.controls.commands.put(message)
    view.frame()


def play(view, steps: int, *, per_frame) -> None:
    """Run as real time at 1× does: a frame at a time, each taking the steps its clock says are
    due (per_frame(n) for the n-th frame), the last one stopping on step `steps`."""
    frame = 0
    while view.live.engine.steps < steps and not view.live.problem:
        due = min(per_frame(frame), steps - view.live.engine.steps)
        view.clock.steps_due = lambda *, due=due, **_: due
        view.frame()
        frame += 1
    view.clock.steps_due = lambda **_: 0


def given(view, vp) -> list:
    """Everything every object was given (graph and trail points, deletes), object by object, in
    order; but resonance's live dots, which move at most every LIVE_EVERY s of wall time, on any
    frame (their last place is checked on its own)."""
    return [thing.given for thing in vp.made if thing.given and thing is not view.graphs.live_dots]


def assert_same_run(a, b) -> None:
    """The two pages' runs agree to the last digit: state, W_nc, runaways, samples, crossings."""
    sa, sb = a.live.state, b.live.state
    assert sa.t == sb.t
    assert np.array_equal(sa.r, sb.r) and np.array_equal(sa.p, sb.p)
    assert np.array_equal(a.live.engine.work, b.live.engine.work)
    assert a.live.runaways == b.live.runaways
    recorded = [(s.t, s.r.tolist(), s.p.tolist(), s.energy) for s in a.graphs.recorded]
    assert recorded == [(s.t, s.r.tolist(), s.p.tolist(), s.energy) for s in b.graphs.recorded]
    assert [list(times) for times in a.crossings.times] == [list(times) for times in b.crossings.times]


# ---- the local page: a jump equals a run played there ----

@pytest.mark.parametrize("scene, t", [("vertical", 0.2), ("vertical", 75.0), ("damped", 4.7), ("driven", 3.0), ("regimes", 2.5),
                                      ("drag", 2.0), ("friction", 3.0), ("pendulum", 2.0),
                                      ("integrators", 8.0), ("resonance", 1.0)])
def test_a_jump_gives_the_state_and_every_graph_point_of_a_run_played_there(scene, t):
    """Every scene: Jump to t against a run played frame by frame to the same step (frames of
    one to three steps, as a 1× run takes them), compared to the last digit, every graph and
    trail point included; the page is paused there, t on its clock. vertical at 75 s is past
    twice the graphs' 30 s window, where they have dropped their oldest points."""
    jumped, jumped_vp = page(scene)
    played, played_vp = page(scene)
    dt = jumped.live.model.dt
    target = steps_to_reach(t, dt)
    click(jumped, JumpTo(f"{t:g}"))
    rhythm = max(1, round(0.02 / dt))       # steps a 50 Hz frame takes at 1×
    play(played, target, per_frame=lambda n: rhythm if n % 3 else rhythm + (n % 2))
    played.running = False
    played.frame()
    assert jumped.live.engine.steps == target and not jumped.running
    assert_same_run(jumped, played)
    assert given(jumped, jumped_vp) == given(played, played_vp)
    if jumped.graphs.live_dots is not None:       # the row's dots now, whenever they last moved
        xs, ys = jumped.graphs.live_points(jumped.live.model, jumped.live.state)
        assert jumped.graphs.live_dots.given[-len(xs):] == [("point", (float(x), float(y))) for x, y in zip(xs, ys)]
    assert jumped.controls.time_text.text == played.controls.time_text.text
    assert f"t = {target * dt:.2f}" in jumped.controls.time_text.text or dt < 0.01
    assert "data-jumps='1'" in jumped.controls.jumped_text.text


def test_a_jump_lands_on_the_headless_answer_and_step_goes_on_from_there():
    """Jump to the question time is `--headless`'s state (run_until: the first step at or after
    it); Step then takes exactly one Δt more, as the engine does."""
    view, _ = page("damped")
    model = view.live.model
    click(view, JumpTo(f"{model.until:g}"))
    engine = model.simulation(view.integrator)
    engine.run_until(model.until)
    assert view.live.state.t == engine.state.t
    assert np.array_equal(view.live.state.r, engine.state.r) and np.array_equal(view.live.state.p, engine.state.p)
    click(view, Step())
    engine.advance(1)
    assert np.array_equal(view.live.state.r, engine.state.r) and np.array_equal(view.live.state.p, engine.state.p)
    assert "F_net" in view.controls.step_text.text and not view.running


def test_jumping_back_restarts_from_0_and_lands_on_the_same_numbers():
    """A t before now starts the run again from t = 0: its graphs hold 0 to t only, and the
    numbers are those of a first jump there."""
    back, back_vp = page("driven")
    click(back, JumpTo("4"))
    click(back, JumpTo("1.5 s"))
    straight, straight_vp = page("driven")
    click(straight, JumpTo("1.5"))
    assert_same_run(back, straight)
    assert back.graphs.recorded[0].t == 0.0 and back.graphs.recorded[-1].t == pytest.approx(1.5)
    assert "data-jumps='2'" in back.controls.jumped_text.text


@pytest.mark.parametrize("text, says", [
    ("abc", "'abc' is not a time in seconds"),
    ("", "'' is not a time in seconds"),
    ("-1", "the run starts at t = 0 s, so it cannot show t = -1 s"),
    ("1e400", "is not a time the run can reach"),
    ("nan", "'nan' is not a time in seconds"),
    ("2,5", "'2,5' is not a time in seconds"),
])
def test_a_time_that_cannot_be_reached_is_one_sentence_and_changes_nothing(text, says):
    view, _ = page("vertical")
    before = (view.live.engine.steps, view.running)
    click(view, JumpTo(text))
    status = view.controls.status_text.text
    assert says in status and "\n" not in status and status.startswith("jump to t: ")
    assert (view.live.engine.steps, view.running) == before


def test_a_jump_too_long_for_this_computer_is_refused_with_the_longest_that_fits():
    """A jump the engine estimates at more than MAX_JUMP_SECONDS of computing is refused before a
    step, naming a t that fits (physics/run_cost.py's wording)."""
    view, _ = page("resonance")
    click(view, JumpTo("1e7"))
    status = view.controls.status_text.text
    assert status.startswith("jump to t: a run to t = 1e+07 s") and "smaller t (at most" in status
    assert view.live.engine.steps == 0
    longest = float(status.split("at most ")[1].split(" s")[0])
    assert jump_steps(view.live, longest, sample_every=view.live.sample_every) == steps_to_reach(longest, 0.02)


def test_the_jump_box_starts_at_the_question_time_and_its_button_sends_the_text_last_entered():
    view, _ = page("regimes")
    controls = view.controls
    assert controls.jump_text == "8"
    box = next(thing for thing in view.vp.made if getattr(thing, "type", None) == "string")
    button = next(thing for thing in view.vp.made if getattr(thing, "text", None) == "Jump")
    box.bind(SimpleNamespace(text="2.5"))
    button.bind(button)
    assert controls.clicks() == [JumpTo("2.5")]


def test_reading_the_box():
    assert jump_time("2.5") == 2.5 and jump_time(" 2.5 s ") == 2.5 and jump_time("1e2") == 100.0
    assert jump_time("0") == 0.0 and jump_time(".5") == 0.5
    with pytest.raises(ValueError, match="the run starts at t = 1 s"):
        jump_time("0.5", t0=1.0)
    assert batches(10, dt=0.01, runaways_possible=False, frame=0.02) == [10]
    assert batches(7, dt=0.01, runaways_possible=True, frame=0.02) == [2, 2, 2, 1]
    assert batches(0, dt=0.01, runaways_possible=True, frame=0.02) == []
    assert MAX_JUMP_SECONDS > 1 and math.isfinite(MAX_JUMP_SECONDS)

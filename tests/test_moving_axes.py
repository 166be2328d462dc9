"""Stepping only the axes a motion uses (physics/motion_axes.py) gives the very numbers of all three axes.

The engine leaves out an axis along which nothing can move (no velocity, every anchor level with
the mass, no direction of gravity or drive along it). The claim is strong: the same bits, not
round-off, because every component is worked out from the same component and the row sums add
exact zeros. So these tests compare the engine with cut_axes=True and cut_axes=False byte for byte
(signs of zero included), on every scene and integrator, in the traced loop and in numpy, through
blow-ups and runaways, and on random systems.
"""
import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from physics.motion_axes import moving_axes
from physics.forces import Driving, Force, Gravity, LinearDamping, QuadraticDrag, Spring
from physics.integrators import INTEGRATORS
from physics.simulate import BlowUpError, Simulation, every
from physics.state import make_state
from scenes._catalog import configure

SCENES = ("vertical", "damped", "driven", "regimes", "drag", "pendulum", "integrators", "resonance")


def bits(a) -> bytes:
    return np.ascontiguousarray(np.asarray(a, dtype=float)).tobytes()


def run_both(make_engine, steps, record=None):
    """The same run with and without cutting: (engine, samples or the BlowUpError's text) each."""
    out = []
    for cut in (True, False):
        engine = make_engine(cut)
        try:
            result = engine.advance(steps, record=record)
        except BlowUpError as problem:
            result = f"{problem} at t = {problem.t}"
        out.append((engine, result))
    return out


def assert_same(cut_run, whole_run):
    (cut, cut_result), (whole, whole_result) = cut_run, whole_run
    assert cut.steps == whole.steps
    for name in ("_r", "_p", "work"):
        assert bits(getattr(cut, name)) == bits(getattr(whole, name)), name
    assert cut.runaways == whole.runaways
    if isinstance(whole_result, str):
        assert cut_result == whole_result
    elif whole_result is not None:
        for name in ("t", "r", "p", "work"):
            assert bits(getattr(cut_result, name)) == bits(getattr(whole_result, name)), name


@pytest.mark.parametrize("compiled", (True, False), ids=("traced loop", "numpy"))
@pytest.mark.parametrize("integrator", INTEGRATORS)
@pytest.mark.parametrize("scene", SCENES)
def test_every_scene_steps_the_same_bits_on_fewer_axes(scene, integrator, compiled):
    model = configure(scene).build()
    runs = run_both(lambda cut: model.simulation(integrator, cut_axes=cut, compiled=compiled),
                    1500, record=every(7))
    assert_same(*runs)


@pytest.mark.parametrize("scene, axes", [("vertical", (1,)), ("damped", (1,)), ("regimes", (1,)),
                                         ("drag", (1,)), ("resonance", (1,)), ("driven", (0,)),
                                         ("integrators", (0,))])
def test_the_scenes_that_swing_along_one_line_are_stepped_on_that_line(scene, axes):
    assert configure(scene).build().simulation().axes == axes


def test_the_pendulum_swings_in_3_d_and_keeps_every_axis():
    assert configure("pendulum").build().simulation().axes is None


def test_the_traced_loop_of_the_hanging_spring_works_out_y_alone():
    """The page's spring (from rest at ⟨0, −1.5, 0⟩ m) as the traced loop writes it: no arithmetic on
    x (a0_0) or z (a0_2), where stepping all three axes squares both every step."""
    model = configure("vertical", assignments=["dt=0.0001"]).build()
    sources = []
    for cut in (True, False):
        engine = model.simulation(cut_axes=cut)
        engine.advance(200)
        sources.append(engine._loop.source)
    cut_source, whole_source = sources
    assert "a0_0 * a0_0" in whole_source and "a0_2 * a0_2" in whole_source
    assert "a0_0 *" not in cut_source and "a0_2 *" not in cut_source and "a0_1 * a0_1" in cut_source


def test_runaways_and_blow_ups_are_the_same_on_fewer_axes():
    integrators = configure("integrators").build()     # euler runs away beside the others
    runs = run_both(lambda cut: integrators.simulation(cut_axes=cut), 60000)
    assert runs[1][0].runaways, "euler should have run away in 60 s"
    assert_same(*runs)
    # Blown up to inf: the same error, at the same t, with the same y. Stepping every axis then
    # also turns x and z into NaN (inf × 0 in the spring's push); cut, they stay where they were.
    vertical = configure("vertical", assignments=["dt=0.9"]).build()
    (cut, cut_error), (whole, whole_error) = run_both(lambda cut: vertical.simulation("euler", cut_axes=cut), 5000)
    assert "non-finite state" in whole_error and cut_error == whole_error and cut.steps == whole.steps
    assert bits(cut._r[:, 1]) == bits(whole._r[:, 1]) and bits(cut._p[:, 1]) == bits(whole._p[:, 1])
    assert not np.isfinite(whole._r[:, 1]).all()
    assert bits(cut._r[:, [0, 2]]) == bits(vertical.state.r[:, [0, 2]])


@dataclasses.dataclass(frozen=True, eq=False)
class Wind(Force):
    """A steady push along x, declaring no VECTORS: the engine cannot know where it pushes."""

    F: float = 1.0
    conservative = False

    def __call__(self, t, r, v, m):
        F = np.zeros_like(r)
        F[:, 0] = self.F
        return F


def test_a_force_that_does_not_declare_its_vectors_keeps_every_axis():
    state = make_state(r=(0.0, -1.5, 0.0), m=10.0)
    assert moving_axes(state.r, state.p, (Spring(k=40.0, L0=1.0), Gravity(g=9.8))) == (1,)
    engine = Simulation(state, (Spring(k=40.0, L0=1.0), Gravity(g=9.8), Wind(F=3.0)), dt=0.01)
    assert engine.axes is None
    engine.advance(100)
    assert engine.state.r[0, 0] > 0, "the wind pushes the mass along x"


def test_what_keeps_an_axis():
    def axes(r, v=(0.0, 0.0, 0.0), forces=(Spring(k=40.0, L0=1.0),)):
        state = make_state(r=r, v=v, m=1.0)
        return moving_axes(state.r, state.p, forces)
    assert axes((0.0, -1.5, 0.0)) == (1,)
    assert axes((0.0, -1.5, 0.0), v=(0.0, 0.0, 0.1)) == (1, 2)       # moving along z
    assert axes((0.2, -1.5, 0.0)) == (0, 1)                          # off the anchor along x
    assert axes((-0.0, -1.5, 0.0)) == (0, 1)                         # −0 would become +0: kept
    assert axes((0.0, -1.5, 0.0), forces=(Spring(k=40.0, L0=1.0), Driving(F0=1.0, omega=2.0))) == (0, 1)
    assert axes((0.0, -1.5, 0.0), forces=(Gravity(g=9.8, direction=(0.0, -1.0, 1.0)),)) == (1, 2)
    assert axes((0.3, -1.5, 0.2), v=(0.1, 0.2, 0.3)) is None          # every axis: nothing to cut
    assert axes((0.0, 0.0, 0.0), forces=(LinearDamping(b=1.0),)) == (0,)   # nothing moves: one axis


def _component(draw, zero):
    return 0.0 if zero else draw(st.sampled_from([-1.0, 1.0])) * draw(st.floats(0.05, 2.0))


@st.composite
def systems(draw):
    """A few masses whose motion stays off some axes: anchors level with the masses there, no
    velocity, gravity and drive with no part along them; any mix of the page's forces."""
    count = draw(st.integers(1, 3))
    quiet = draw(st.lists(st.booleans(), min_size=3, max_size=3))
    anchors = np.array([[_component(draw, False) for _ in range(3)] for _ in range(count)])
    r = np.array([[anchors[i, j] if quiet[j] else _component(draw, False) for j in range(3)]
                  for i in range(count)])
    at_rest = draw(st.booleans())     # released from rest: only the springs' pull moves them off the line
    v = np.array([[_component(draw, quiet[j] or at_rest) for j in range(3)] for _ in range(count)])
    direction = [_component(draw, quiet[j]) for j in range(3)]
    if not any(direction):
        direction = [1.0 if not q else 0.0 for q in quiet] if not all(quiet) else [0.0, 1.0, 0.0]
    forces = [Spring(k=draw(st.floats(1.0, 50.0)), L0=draw(st.sampled_from([0.0, 0.5, 1.0])), anchor=anchors)]
    if draw(st.booleans()) and any(direction):
        forces.append(Gravity(g=9.8, direction=direction))
    if draw(st.booleans()):
        forces.append(LinearDamping(b=draw(st.floats(0.1, 3.0))))
    if draw(st.booleans()):
        forces.append(QuadraticDrag(C=0.5, A=0.1, rho=1.2))
    if draw(st.booleans()) and any(direction):
        forces.append(Driving(F0=draw(st.floats(-3.0, 3.0)), omega=draw(st.floats(0.5, 5.0)), axis=direction))
    masses = draw(st.lists(st.floats(0.5, 5.0), min_size=count, max_size=count))
    return make_state(r=r, v=v, m=masses), tuple(forces)


@settings(max_examples=60, deadline=None)
@given(systems(), st.sampled_from(sorted(INTEGRATORS)), st.booleans())
def test_random_systems_step_the_same_bits_on_fewer_axes(system, integrator, compiled):
    state, forces = system
    runs = run_both(lambda cut: Simulation(state, forces, dt=0.01, integrator=integrator, compiled=compiled,
                                           cut_axes=cut), 300, record=every(50))
    assert_same(*runs)

"""The momentum arrows' arithmetic (export/arrows.py) and the Step written out (export/step_update.py).

Scales are round (1, 2 or 5 × 10ⁿ) and make the largest magnitude of a run fit; the forces drawn
tip to tail add up to F_net; F∥ + F⊥ = F_net with F⊥ ⟂ p; and the page's Step read-out has the
digits of the command line's `--steps` table, for the page's method and the others.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import main
from export.arrows import (GROW, TIP_ROOM, choose_scales, forces_each, largest, parse_arrows, room_used, round_scale,
                           sampled, split)
from export.framing import frame
from export.step_update import step_lines, update_force, vector
from physics.forces import net_force
from physics.integrators import DEFAULT_INTEGRATOR, INTEGRATORS
from physics.state import velocity
from scenes import catalog
from scenes._view import DEFAULT_VIEW


def is_round(x: float) -> bool:
    mantissa = x / 10 ** math.floor(math.log10(x))
    return any(math.isclose(mantissa, step) for step in (1, 2, 5))


@settings(deadline=None)
@given(st.floats(min_value=1e-9, max_value=1e9))
def test_round_scale_is_the_next_1_2_5_step(x):
    scale = round_scale(x)
    assert is_round(scale) and x * (1 - 1e-12) <= scale < 2.5 * x


def test_round_scale_by_hand():
    assert [round_scale(x) for x in (13, 0.031, 50, 1, 7.2, 0)] == [20, 0.05, 50, 1, 10, 1]


def view_of(setup) -> dict:
    return {**DEFAULT_VIEW, **setup.hooks.view}


def next_smaller(unit: float) -> float:
    return round_scale(unit / 2.5 * (1 - 1e-9))


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
def test_the_scales_are_round_and_the_longest_arrows_that_fit(scene):
    """Each scale is round; at it every tip of the run is inside the picture the page frames,
    widened by at most GROW (the range the scales ask for); at the next smaller round scale (arrows
    2 or 2.5 times longer) some tip would need the picture widened by more."""
    setup = catalog.configure(scene)
    model = setup.build()
    scales = choose_scales(model, view=view_of(setup))
    framed = frame(model, view_of(setup))
    camera, margin = framed.camera, TIP_ROOM * framed.radius
    r, p, F = sampled(model)
    base = max(camera.range, camera.range_holding(r) + margin)
    axis, where, towards = framed.face()   # the ceiling's underside or the wall's face
    assert camera.range <= scales.view_range <= GROW * base * (1 + 1e-12)
    for q, unit in ((p, scales.p_unit), (F, scales.F_unit)):
        assert is_round(unit)
        if np.any(q):
            tips, longer = r + q / unit, r + q / next_smaller(unit)
            assert camera.range_holding(tips) + margin <= scales.view_range * (1 + 1e-12)   # fits ...
            assert np.all((tips[..., axis] - where) * towards <= -margin)   # not through the support
            # ... as long as can be
            assert (camera.range_holding(longer) + margin > GROW * base
                    or np.any((longer[..., axis] - where) * towards > -margin))


@pytest.mark.parametrize("method", sorted(INTEGRATORS))
@pytest.mark.parametrize("scene", ["vertical", "driven", "pendulum", "integrators"])
def test_every_method_gets_round_scales_even_when_its_run_blows_up(scene, method):
    """`vertical --integrator euler --vpython` never ended: its mass, blowing up, passes up through
    the ceiling, so no arrow could keep out of it and the search for longer arrows went on to
    0 kg·m/s per m. Each method gets round scales and a finite picture."""
    setup = catalog.configure(scene)
    scales = choose_scales(setup.build(), view=view_of(setup), integrator=method)
    assert is_round(scales.p_unit) and is_round(scales.F_unit) and math.isfinite(scales.view_range)


def test_vertical_scales_by_hand():
    # Simple Example: y_eq = −(L0 + mg/k) = −3.45 m, released at −1.5 m: A = 1.95 m, ω = 2 rad/s, so
    # |p| ≤ m A ω = 39 kg·m/s and |F_net| ≤ k A = 78 N. The page frames the ceiling (0 m) to the
    # lowest point (−5.4 m) and the ball: range 3.59 m about y = −2.7 m. At 20 kg·m/s and 20 N per m
    # the p arrow at y_eq and the F_net arrows at the turning points reach 1.95 m and 3.9 m, from
    # −1.5 to −5.4 m, the motion's own length; at 10 per m they would reach −7.35 m, 4.65 m below the
    # centre: more than GROW × 3.59 = 4.3 m.
    setup = catalog.configure("vertical")
    p_max, F_max = largest(setup.build())
    assert p_max == pytest.approx(39, rel=0.03) and F_max == pytest.approx(78, rel=0.03)
    scales = choose_scales(setup.build(), view=view_of(setup))
    assert (scales.p_unit, scales.F_unit) == (20, 20)
    assert scales.legend() == "an arrow of 1 m = 20 kg·m/s for p, 20 N for forces"
    # With each force drawn tip to tail, the spring's arrow starts at the mass: at the bottom it
    # pulls k (5.4 − L0) = 40 × 4.4 = 176 N up, 8.8 m at 20 N per m, through the ceiling; at 50 N
    # per m 3.52 m, to −1.88 m. The page (and the program) with "forces" on choose 50.
    with_forces = choose_scales(setup.build(), view=view_of(setup), forces=True)
    assert (with_forces.p_unit, with_forces.F_unit) == (20, 50)


def test_refitted_only_grows_to_the_next_round_scale_that_keeps_the_tips_in():
    setup = catalog.configure("vertical")
    scales = choose_scales(setup.build(), view=view_of(setup))
    bigger = scales.refitted(p_needed=31, F_needed=3)
    assert (bigger.p_unit, bigger.F_unit) == (50, scales.F_unit)
    assert scales.refitted(p_needed=20, F_needed=20) == scales


@pytest.mark.parametrize("scene", ["vertical", "damped", "driven", "pendulum", "drag"])
def test_the_forces_tip_to_tail_end_at_F_nets_tip(scene):
    model = catalog.configure(scene).build()
    s = model.state
    r, p = s.r + 0.1, s.p + 0.3     # somewhere the run goes, moving
    v = velocity(p, s.m)
    each = forces_each(model.forces, 1.3, r, v, s.m)
    assert len(each) == len(model.forces)
    assert np.allclose(np.sum(each, axis=0), net_force(model.forces, 1.3, r, v, s.m), rtol=1e-12, atol=1e-12)


@settings(deadline=None)
@given(st.lists(st.floats(-100, 100), min_size=6, max_size=6))
def test_split_is_along_and_across_p(numbers):
    F, p = np.array(numbers[:3]), np.array(numbers[3:])
    along, across = split(F, p)
    assert np.allclose(along[0] + across[0], F)
    if np.linalg.norm(p) > 1e-6:
        assert abs(np.dot(across[0], p)) <= 1e-9 * max(1.0, np.linalg.norm(F) * np.linalg.norm(p))
        assert np.allclose(np.cross(along[0], p), 0, atol=1e-9 * max(1.0, np.linalg.norm(F) * np.linalg.norm(p)))
    elif not p.any():   # from rest there is no direction to split along: F∥ is all of F_net
        assert np.allclose(along[0], F)


def test_parse_arrows():
    assert parse_arrows("p,F_net") == ("p", "F_net") and parse_arrows("") == ()
    with pytest.raises(ValueError, match="'Fnet'"):
        parse_arrows("p,Fnet")


def page_readout(args, steps):
    """The Step read-out the page would show after Reset and `steps` Steps: the engine stepped one
    Δt at a time, as the page's Step does, and step_lines for each."""
    setup = catalog.configure(args[0], scenario=int(args[2]) if len(args) > 2 else None)
    model = setup.build()
    engine = model.simulation()
    out = []
    for _ in range(steps):
        before = engine.state
        t_i, r_i, p_i = before.t, np.array(before.r), np.array(before.p)
        engine.advance(1)
        after = engine.state
        F = update_force(model.forces, engine.methods, t_i=t_i, r_i=r_i, p_i=p_i, p_f=after.p, m=after.m,
                         dt=model.dt)
        out.append(step_lines(method=engine.methods[0], dt=model.dt, t_f=after.t, m=float(after.m[0]),
                              F_net=F[0], p_i=p_i[0], p_f=after.p[0], r_i=r_i[0], r_f=after.r[0]))
    return out


def steps_rows(capsys, args, steps):
    """`main.py ARGS --steps N` as printed: each row's cells (step, t, F_net, p_f, v_f, r_f)."""
    assert main.run([*args, "--steps", str(steps)]) == 0
    lines = capsys.readouterr().out.splitlines()[-steps:]
    return [[cell.strip() for cell in line.split("  ") if cell.strip()] for line in lines]


@pytest.mark.parametrize("args", [("vertical",), ("damped",), ("driven", "--scenario", "3")])
def test_the_step_read_out_has_the_digits_of_steps(capsys, args):
    for lines, row in zip(page_readout(args, 3), steps_rows(capsys, args, 3), strict=True):
        text = "\n".join(lines)
        step, t, F_net, p_f, v_f, r_f = row
        assert lines[0].startswith(f"t = {t} s, euler-cromer")
        assert f"F_net = {F_net} N" in text
        assert f"    = {p_f} kg·m/s" in text
        assert f"v_f = p_f / m = {v_f} m/s" in text
        assert f"    = {r_f} m" in text


def test_the_step_by_hand():
    # step 2 of the Simple Example (tests/test_cli.py): p1 = −7.8, F = −74.88 N, so F Δt = −7.488
    lines = page_readout(("vertical",), 2)[1]
    assert lines[-5:] == ["p_f = p_i + F_net Δt = < 0, -7.8, 0 > + < 0, -7.488, 0 >",
                          "    = < 0, -15.288, 0 > kg·m/s",
                          "v_f = p_f / m = < 0, -1.5288, 0 > m/s",
                          "r_f = r_i + v_f Δt = < 0, -1.578, 0 > + < 0, -0.15288, 0 >",
                          "    = < 0, -1.73088, 0 > m"]


@pytest.mark.parametrize("method", ["euler", "verlet", "rk4"])
def test_other_methods_show_their_own_update(capsys, method):
    setup = catalog.configure("vertical")
    model = setup.build()
    engine = model.simulation(method)
    before = engine.state
    t_i, r_i, p_i = before.t, np.array(before.r), np.array(before.p)
    engine.advance(1)
    after = engine.state
    F = update_force(model.forces, engine.methods, t_i=t_i, r_i=r_i, p_i=p_i, p_f=after.p, m=after.m, dt=model.dt)
    lines = step_lines(method=method, dt=model.dt, t_f=after.t, m=10.0, F_net=F[0], p_i=p_i[0], p_f=after.p[0],
                       r_i=r_i[0], r_f=after.r[0])
    row = steps_rows(capsys, ("vertical", "--integrator", method), 1)[0]
    text = "\n".join(lines)
    assert lines[0] == f"t = 0.1 s, {method}:" and "F_net = " in text and row[2] + " N" in text
    assert f"= {row[3]} kg·m/s" in text and f"{row[5]} m" in text
    assert ("average force" in text) == (method != "euler")
    assert vector(after.r[0]) == row[5]


def stand_in_with_arrows():
    """tests/test_trail.py's stand-in vpython, with arrows (each gets an idx, as vpython's do)."""
    from itertools import count

    from test_trail import Shape, stand_in_vpython

    numbers = count()

    def arrow(**attributes):
        return Shape(idx=next(numbers), **attributes)
    vp = stand_in_vpython()
    vp.arrow = arrow
    return vp


def test_the_page_arrows_are_scale_times_the_engines_p_and_F_net_and_made_only_when_shown():
    from browser.arrows3d import MomentumArrows
    from browser.clock import LiveRun

    model = catalog.configure("pendulum").build()
    live = LiveRun(model, integrator="euler-cromer")
    arrows = MomentumArrows(stand_in_with_arrows(), model=model, integrator="euler-cromer", shown=(), radius=0.1,
                            view=view_of(catalog.configure("pendulum")))
    arrows.draw(live)
    assert arrows.shapes == [] and arrows._scales is None     # nothing shown: nothing made, no run
    for kind in ("p", "F_net", "split", "forces"):
        arrows.set_shown(kind, True)
    live.advance(137)
    arrows.draw(live)
    s, scales = live.state, arrows.scales
    F = net_force(model.forces, s.t, s.r, velocity(s.p, s.m), s.m)
    assert np.allclose(np.array(arrows.p[0].axis), s.p[0] / scales.p_unit)
    assert np.allclose(np.array(arrows.F_net[0].axis), F[0] / scales.F_unit)
    tips = np.array(arrows.forces[0][0].pos) + sum(np.array(a.axis) for a in arrows.forces[0])
    assert np.allclose(tips, s.r[0] + F[0] / scales.F_unit)              # tip to tail, ending at F_net's tip
    along, across = (np.array(a.axis) for a in arrows.parts[0][:2])
    assert np.allclose(along + across, F[0] / scales.F_unit) and abs(across @ s.p[0]) < 1e-9
    assert arrows.parts[0][2].text.startswith("F∥ = ") and arrows.parts[0][2].text.endswith(" N")
    assert [label.text for label in arrows.force_labels[0]] == ["spring", "gravity"]
    spring, gravity = arrows.force_labels[0]     # along one line under a ceiling: names on either side
    assert spring.xoffset > 0 > gravity.xoffset and (spring.align, gravity.align) == ("left", "right")


@pytest.mark.parametrize("args, message", [
    (("vertical", "--arrows", "p,Fnet"), "--arrows knows p, F_net, forces, split (got 'Fnet')"),
    (("vertical", "--headless", "--arrows", "p"), "--arrows (and --no-arrows) is for the page and the program"),
    (("vertical", "--steps", "2", "--no-arrows"), "--arrows (and --no-arrows) is for the page and the program"),
])
def test_bad_arrows_get_one_line_and_status_2(capsys, args, message):
    assert main.run(list(args)) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"error: {message}") and len(err.strip().splitlines()) == 1


def test_the_notebooks_show_checks_its_arrows_before_anything_is_drawn():
    from browser.notebook import show
    from scenes import ConstantError

    with pytest.raises(ConstantError, match="got 'q'"):
        show("vertical", arrows=("p", "q"))


def test_the_masses_are_see_through_while_an_arrow_starts_inside_them():
    """An arrow shorter than the ball's radius (driven --scenario 3's steady motion) would hide in
    it: while any arrow is shown the masses are drawn see-through, and solid again when none is;
    the arrows themselves keep their length, scale × the engine's value."""
    from browser.arrows3d import SEE_THROUGH, MomentumArrows
    from browser.clock import LiveRun
    from test_trail import Shape

    model = catalog.configure("driven", scenario=3).build()
    live = LiveRun(model, integrator="euler-cromer")
    ball = Shape(opacity=1.0)
    arrows = MomentumArrows(stand_in_with_arrows(), model=model, integrator="euler-cromer", shown={"p"},
                            radius=0.32, masses=[ball], view=view_of(catalog.configure("driven", scenario=3)))
    live.advance(round(20.0 / model.dt))   # the steady motion: p is far shorter than the ball
    arrows.draw(live)
    length = np.linalg.norm(np.array(arrows.p[0].axis))
    assert 0 < length < 0.32 and np.isclose(length * arrows.scales.p_unit, np.linalg.norm(live.state.p[0]))
    assert 0 < SEE_THROUGH < 1 and ball.opacity == SEE_THROUGH
    arrows.set_shown("p", False)
    arrows.draw(live)
    assert ball.opacity == 1.0
    arrows.set_shown("split", True)
    arrows.draw(live)
    assert ball.opacity == SEE_THROUGH


def page_picture(name, scenario, shown=("p", "F_net")):
    """The page's 3-D picture of a scene on the stand-in vpython, with its arrows drawn once (their
    scales chosen and the camera widened for them): the scene, the arrows and the camera."""
    from browser.arrows3d import MomentumArrows
    from browser.clock import LiveRun
    from browser.scene3d import Scene3D
    from export.framing import Camera

    setup = catalog.configure(name, scenario=scenario)
    model = setup.build()
    vp = stand_in_with_arrows()
    scene = Scene3D(vp, model=model, view=view_of(setup), title=name)
    arrows = MomentumArrows(vp, model=model, integrator=DEFAULT_INTEGRATOR, shown=set(shown), radius=scene.radius,
                            view=view_of(setup), make_room=scene.make_room,
                            camera=scene.camera)
    arrows.draw(LiveRun(model, integrator=DEFAULT_INTEGRATOR))
    forward = vp.scene.forward
    camera = Camera(centre=np.array(vp.scene.center, float), range=vp.scene.range, pitch=forward.y / forward.z)
    return scene, arrows, camera


def run_30_s(model):
    """t, r, p and F_net every 0.06 s or so of a 30 s run, the masses the scene expects to run away left out."""
    from physics.simulate import every, trajectory

    engine = model.simulation()
    steps = round(30.0 / model.dt)
    traj = trajectory(engine, engine.advance(steps, record=every(max(1, steps // 500))), with_energy=False)
    kept = [i for i in range(model.state.count) if i not in model.expected_runaways(engine.methods)]
    for n in range(len(traj.t)):
        F = net_force(model.forces, traj.t[n], traj.r[n], velocity(traj.p[n], traj.m), traj.m)
        yield traj.t[n], traj.r[n][kept], traj.p[n][kept], F[kept]


SIX = [("vertical", None), ("damped", None), ("driven", 3), ("pendulum", None), ("resonance", None), ("regimes", None)]


@pytest.mark.parametrize("name, scenario", SIX)
def test_the_arrows_stay_in_the_picture_the_page_frames(name, scenario):
    """Every p and F_net arrow, at the run's scales, ends inside the 3-D view the page frames
    (browser/scene3d.py, drawn on the stand-in vpython, its camera as the page leaves it after
    the arrows are first drawn, looking along `forward`) over the 30 s the scales are chosen for;
    no arrow goes up through the ceiling or back through the wall. `resonance --arrows p` had its
    scale chosen from the whole row's width (4.8 m) while each spring moves 1.8 m: its p arrows
    ran 2 m up, through the ceiling to the top of the view."""
    scene, arrows, camera = page_picture(name, scenario)
    scales = arrows.scales
    for t, r, p, F in run_30_s(scene_model(name, scenario)):
        for axes in (scales.momentum_axis(p), scales.force_axis(F)):
            used = room_used(camera, r, axes)
            assert np.all(used <= 1), f"{name}: an arrow ends {np.nanmax(used):.2f} of the way out, t = {t:.1f} s"
            through = (r + axes)[:, 1] - scene.support_box[0][1] if not scene.wall else \
                scene.support_box[1][0] - (r + axes)[:, 0]
            assert np.all(through <= 0), f"{name}: an arrow ends {through.max():.2f} m through the support"


def scene_model(name, scenario):
    return catalog.configure(name, scenario=scenario).build()


@pytest.mark.parametrize("name, scenario, least", [*((name, scenario, 0.5) for name, scenario in SIX[:3] + SIX[4:]),
                                                   ("integrators", None, 0.5), ("drag", None, 0.5),
                                                   ("pendulum", None, 0.75)])
def test_the_longest_arrow_of_a_run_uses_most_of_its_room(name, scenario, least):
    """Over 30 s the longest p arrow and the longest F_net arrow each reach most of the way from
    their mass to the picture's edge, or to the ceiling or wall (pendulum, the 0.12 m ball in a 2 m
    tall picture, over three quarters). The scales used to be rounded up from half the motion's size with no regard to
    where the edge was: pendulum's longest p and F_net arrows reached 0.56 and 0.50 of the way,
    integrators' 0.14 and 0.13."""
    scene, arrows, camera = page_picture(name, scenario)
    face = (0, scene.support_box[1][0], -1) if scene.wall else (1, scene.support_box[0][1], 1)
    longest = {"p": 0.0, "F_net": 0.0}
    for t, r, p, F in run_30_s(scene_model(name, scenario)):
        for kind, axes in (("p", arrows.scales.momentum_axis(p)), ("F_net", arrows.scales.force_axis(F))):
            longest[kind] = max(longest[kind], np.nanmax(room_used(camera, r, axes, face=face)))
    assert min(longest.values()) >= least, f"{name}: the longest arrows reach {longest} of the way to the edge"


def test_reset_rescales_against_the_picture_the_camera_shows():
    """An arrow tip that left the picture the page's camera showed makes the next Reset pick the
    next round scale that keeps every tip of that run in it, and only then. The camera here is
    moved closer, on the swing itself (pendulum: looking straight on, so the picture is x and y
    within range × 900/440 and range of its centre); the old rule compared the largest |p| with
    twice its own reach and kept the scale, though the tips were out of the picture."""
    from browser.arrows3d import MomentumArrows
    from browser.clock import LiveRun
    from browser.scene3d import CANVAS_SIZE, Scene3D

    setup = catalog.configure("pendulum")
    model = setup.build()
    vp = stand_in_with_arrows()
    scene = Scene3D(vp, model=model, view=view_of(setup), title="pendulum")
    arrows = MomentumArrows(vp, model=model, integrator=DEFAULT_INTEGRATOR, shown={"p"}, radius=scene.radius,
                            view=view_of(setup), make_room=scene.make_room, camera=scene.camera)
    live = LiveRun(model, integrator=DEFAULT_INTEGRATOR)

    def run(seconds: float):
        """Draw a frame every 0.05 s; the masses' r and p at each, and the p arrow's tip drawn."""
        r, p, tips = [], [], []
        for _ in range(round(seconds / 0.05)):
            live.advance(round(0.05 / model.dt))
            arrows.draw(live)
            r.append(live.state.r[0].copy())
            p.append(live.state.p[0].copy())
            tips.append(np.array(arrows.p[0].pos) + np.array(arrows.p[0].axis))
        return np.array(r), np.array(p), np.array(tips)

    def inside(tips) -> bool:
        width, height = CANVAS_SIZE
        half = np.array([scene.range * width / height, scene.range]) - TIP_ROOM * scene.radius
        return bool(np.all(np.abs(tips[:, :2] - scene.centre[:2]) <= half))

    r, p, tips = run(10.0)
    first = arrows.scales
    assert inside(tips) and np.allclose(tips, r + p / first.p_unit)   # framed for them: Reset keeps the scales
    live.restart()
    arrows.reset()
    assert arrows.scales == first

    scene.centre, scene.range = np.array([0.0, -1.3, 0.0]), 0.3   # the picture the camera shows: closer
    r, p, tips = run(10.0)
    assert inside(r) and not inside(tips)
    assert arrows.scales == first and np.allclose(tips, r + p / first.p_unit)   # fixed through the run
    live.restart()
    arrows.reset()
    unit = arrows.scales.p_unit
    assert is_round(unit) and unit > first.p_unit and arrows.scales.F_unit == first.F_unit
    assert inside(r + p / unit) and not inside(r + p / next_smaller(unit))   # the next round scale that keeps them in


def test_the_arrows_leave_a_camera_that_follows_the_masses_alone():
    """drag "falling, no spring": the camera follows the balls from the start (the whole fall
    framed would draw them as dots). Choosing the arrows' scales must not widen it, then or at
    Reset, to the fall's framed range."""
    from browser.arrows3d import MomentumArrows
    from browser.clock import LiveRun
    from browser.scene3d import Scene3D

    setup = catalog.configure("drag", preset="falling, no spring")
    model = setup.build()
    vp = stand_in_with_arrows()
    scene = Scene3D(vp, model=model, view=view_of(setup), title="drag")
    assert scene.follows_from_start
    close = scene.range
    arrows = MomentumArrows(vp, model=model, integrator=DEFAULT_INTEGRATOR, shown={"p", "F_net"}, radius=scene.radius,
                            view=view_of(setup), make_room=scene.make_room, camera=scene.camera)
    live = LiveRun(model, integrator=DEFAULT_INTEGRATOR)
    arrows.draw(live)
    assert arrows.scales.view_range > 10 * close and vp.scene.range == close
    live.advance(round(3.0 / model.dt))        # the balls fall; the camera follows them
    scene.draw(live, matter=list(range(model.state.count)))
    arrows.draw(live)
    live.restart()
    arrows.reset()
    scene.clear()                              # back to the start, as close as it began
    assert vp.scene.range == scene.range == pytest.approx(close)

"""The labels the 3-D view writes beside its masses (browser/mass_labels.py), for every scene.

A scene with several masses names each one (method, regime, drag) or, in rows, each row (b) and
the masses along the front row (ω); a single mass needs no label. Checked on the texts, and on the
page's 3-D objects with a stand-in for vpython (no browser).
"""
import pytest

from browser.mass_labels import mass_labels, two_lines
from scenes import catalog
from scenes._view import DEFAULT_VIEW


def labels_of(scene: str):
    setup = catalog.configure(scene)
    model = setup.build()
    return model, mass_labels(model, {**DEFAULT_VIEW, **getattr(setup.module, "VIEW", {})})


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
def test_every_scene_with_several_masses_labels_them(scene):
    model, labels = labels_of(scene)
    if model.state.count == 1:
        assert labels == []
    else:
        assert labels, f"{scene}: {model.state.count} masses and no label"
        assert all(label.text.strip() for label in labels)


def test_the_methods_regimes_and_drags_are_named_on_their_masses():
    for scene, expected in (("integrators", ["euler", "euler-cromer", "verlet", "rk4"]),
                            ("regimes", ["under-damped", "critically damped", "over-damped"]),
                            ("drag", ["linear", "quadratic"])):
        _, labels = labels_of(scene)
        assert [label.index for label in labels] == list(range(len(expected)))
        shown = [label.text.replace("\n", " ") for label in labels]
        assert all(text == name or text.startswith(name + " ") and "=" in text for text, name in zip(shown, expected)), shown
        assert all(label.follows for label in labels)
    assert two_lines("under-damped (b = 0.8 kg/s)") == "under-damped\nb = 0.8 kg/s"
    # two lines, not three: the outer labels sit outward, beside their balls (browser/scene3d.py), so the
    # middle one has room, and a third line ran off the canvas's bottom at 1024 x 768
    assert two_lines("critically damped (b = 8 kg/s)") == "critically damped\nb = 8 kg/s"


def test_resonance_names_each_row_by_its_b_and_the_front_row_by_omega():
    model, labels = labels_of("resonance")
    rows = [label.text for label in labels if label.side == "left"]
    assert rows == ["b = 0.5 kg/s", "b = 1 kg/s", "b = 2 kg/s"]
    below = [label.text.replace("\n", " ") for label in labels if label.side == "below"]
    assert below[0] == "ω = 2 rad/s" and below[-1] == "ω = 8 rad/s" and len(below) == 7
    assert all("ω" not in text for text in rows) and not any(label.follows for label in labels)


def test_the_page_draws_the_labels_and_looks_down_on_resonance_rows():
    from browser.scene3d import Scene3D
    from test_trail import stand_in_vpython

    vp = stand_in_vpython()
    for scene, count, pitched in (("integrators", 4, False), ("resonance", 3 + 7, True)):
        setup = catalog.configure(scene)
        model = setup.build()
        view = {**DEFAULT_VIEW, **setup.module.VIEW}
        shown = Scene3D(vp, model=model, view=view, title=scene)
        assert len(shown.labels) == count
        assert (shown.pitch > 0) == pitched
    # each row's label ends just left of the row's first mass (right-aligned, a few pixels out):
    # centred 60 px out, resonance's "b = 0.5 kg/s" ran off the canvas's left edge at 1024 px
    rows = [label for spec, label in shown.labels if spec.side == "left"]
    assert len(rows) == 3
    for label in rows:
        assert label.align == "right" and -40 < label.xoffset < 0, (label.text, label.align, label.xoffset)


def test_euler_ran_away_is_written_on_the_open_side_of_its_ball_not_over_the_wall():
    """integrators: euler's "ran away" label was centred 60 px left of its frozen ball, over the
    wall the springs hang from. It now starts just right of the ball (left-aligned), in the open."""
    from browser.clock import LiveRun
    from browser.scene3d import Scene3D
    from test_trail import stand_in_vpython

    setup = catalog.configure("integrators")
    model = setup.build()
    view = {**DEFAULT_VIEW, **setup.module.VIEW}
    shown = Scene3D(stand_in_vpython(), model=model, view=view, title="integrators")
    live = LiveRun(model, integrator="euler-cromer", sample_every=0.05)
    while not live.runaways and live.state.t < 30.0:
        shown.extend_trails(live.advance(round(1.0 / model.dt)), live.runaways)
    assert list(live.runaways) == [0]                          # euler, alone
    shown.draw(live, matter=[1, 2, 3])
    (label,) = shown.runaway_labels.values()
    assert label.text.startswith("euler ran away")
    wall = shown.support_box[1][0]                             # the wall's face, m
    assert float(label.pos[0]) > wall                          # the ball, in front of the wall
    placed = getattr(label, "align", "center"), label.xoffset   # vpython centres a label unless told
    assert placed[0] == "left" and placed[1] > 0, placed

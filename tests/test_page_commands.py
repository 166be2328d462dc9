"""The page's clicks take effect in the order they were made, even when several arrive in one frame.

A teacher (or a fast test) can pick an integrator and then a preset before the frame loop runs;
the preset must not undo the integrator, and a slider value set just before a preset stays
unless the preset sets that constant. The frame loop's command handling is driven here without
vpython: the view's rebuild and switch are replaced by recorders.
"""
from types import SimpleNamespace

from browser.messages import ChooseIntegrator, ChoosePreset, ChooseScene, SetConstant
from browser.view import SceneView
from scenes import catalog


def view_with_clicks(*clicks):
    """A SceneView of `vertical` on euler-cromer whose page has queued `clicks`, and what it did."""
    view = SceneView.__new__(SceneView)
    view.setup, view.integrator, view.preset = catalog.configure("vertical"), "euler-cromer", None
    view.controls = SimpleNamespace(clicks=lambda: list(clicks))
    done = []
    view._switch = lambda setup, preset=None: done.append(("switch", setup, preset)) or True
    view._rebuild = lambda changes, integrator: done.append(("rebuild", changes, integrator))
    return view, done


def test_an_integrator_chosen_just_before_a_preset_still_holds_after_it():
    view, done = view_with_clicks(ChooseIntegrator("verlet"), ChoosePreset("Moon gravity"))
    view._apply_commands(now=0.0)
    (kind, setup, preset), = done
    assert (kind, preset) == ("switch", "Moon gravity")
    assert setup.values["g"] == 1.62
    assert view.integrator == "verlet"


def test_a_slider_value_set_just_before_a_preset_stays_unless_the_preset_sets_it():
    view, done = view_with_clicks(SetConstant("k", 60.0), ChoosePreset("Moon gravity"))
    view._apply_commands(now=0.0)
    (kind, setup, preset), = done
    assert setup.values["k"] == 60.0 and setup.values["g"] == 1.62
    view, done = view_with_clicks(SetConstant("m", 20.0), ChoosePreset("critical damping"))
    view._apply_commands(now=0.0)
    (kind, setup, preset), = done
    m, k = setup.values["m"], setup.values["k"]
    assert m == 20.0 and abs(setup.values["b"] - 2 * (m * k) ** 0.5) < 1e-12  # b = 2√(mk), from the new m


def test_an_integrator_alone_rebuilds_the_run_with_it():
    view, done = view_with_clicks(ChooseIntegrator("rk4"))
    view._apply_commands(now=0.0)
    assert done == [("rebuild", {}, "rk4")]


def test_the_page_clock_shows_every_step_time_as_the_csv_writes_it():
    """The caption's t has Δt's decimals (at least 2): at Δt = 0.125 s it read 0.13 s, not 0.125 s."""
    from browser.controls import time_decimals
    from export.numbers import clean_time

    for dt in (0.125, 0.1, 0.005, 1e-4, 0.02):
        decimals = time_decimals(dt)
        for n in (1, 3, 7, 1001):
            shown = f"{n * dt:.{decimals}f}"
            assert float(shown) == clean_time(n * dt, dt), (dt, n, shown)


def test_a_broken_scene_chosen_in_the_scene_menu_is_a_sentence_on_the_page(monkeypatch):
    """A teacher's scene file with a typo is in the menu (found by its name); choosing it says why it
    cannot open, and the scene shown keeps running (it raised out of the frame loop)."""
    from scenes import ConstantError

    def broken(name, **options):
        raise ConstantError(f"scenes/{name}.py, line 13: invalid syntax")

    said, refused = [], []
    view, done = view_with_clicks(ChooseScene("damped"))
    view.controls.say = said.append
    view.controls.show_scene = lambda scene: refused.append(("scene", scene))
    monkeypatch.setattr(catalog, "configure", broken)
    view._apply_commands(now=0.0)
    assert done == [] and view.setup.name == "vertical"
    assert said == ["<b>Cannot open that:</b> scenes/damped.py, line 13: invalid syntax"]
    assert refused == [("scene", "vertical")]   # the menu goes back to the scene that runs (issue 20)


def test_a_scene_or_preset_that_cannot_be_built_puts_its_menu_back():
    """The menu showed the refused scene's name while the old scene ran on (issue 20, item 6)."""
    for click in (ChooseScene("damped"), ChoosePreset("Moon gravity")):
        refused = []
        view, done = view_with_clicks(click)
        view._switch = lambda setup, preset=None: False   # it said why, and built nothing
        view.controls.show_scene = lambda scene: refused.append(("scene", scene))
        view.controls.show_preset = lambda preset: refused.append(("preset", preset))
        view._apply_commands(now=0.0)
        assert refused == ([("scene", "vertical")] if isinstance(click, ChooseScene) else [("preset", None)])


def test_what_the_page_says_stays_on_it_until_the_next_run_starts():
    """The next frame's status line cleared the sentence at once, so a broken scene showed no message."""
    from browser.controls import Controls

    controls = Controls.__new__(Controls)
    controls.status_text, controls.notice = SimpleNamespace(text=""), ""
    controls.scene_menu, controls.preset_menu = SimpleNamespace(selected="damped"), None
    controls.say("<b>Cannot open that:</b> scenes/damped.py, line 13: invalid syntax")
    for _ in range(3):
        controls.show_status(problem=None, runaways=[], slow_dt=None)
    assert controls.status_text.text == "<b>Cannot open that:</b> scenes/damped.py, line 13: invalid syntax"
    controls.show_status(problem="it blew up", runaways=[], slow_dt=None)   # a stopped run says so first
    assert controls.status_text.text == "<b>Stopped:</b> it blew up"
    controls.show_scene("vertical")
    assert controls.scene_menu.selected == "vertical"


def test_a_refused_preset_puts_the_menu_back_on_the_preset_that_runs():
    """A preset that cannot be built leaves the constants of the one before: the menu names that
    one (it showed the prompt, though the Moon's g still ran), or the prompt if none runs."""
    from browser.controls import PRESET_PROMPT, Controls

    controls = Controls.__new__(Controls)
    controls.preset_menu = SimpleNamespace(selected="Jupiter gravity")
    controls.show_preset("Moon gravity")
    assert controls.preset_menu.selected == "Moon gravity"
    controls.show_preset(None)
    assert controls.preset_menu.selected == PRESET_PROMPT

"""The local page's Add a force box (browser/force_box.py) in headless Chromium, worked from the
keyboard as a student would:

* a force added runs from t = 0: the program's F_net line names it, its arrow is drawn, the run
  before stays grey on the position graph, and what the page holds at t (Download CSV: every
  graphed sample) is the engine's run with that force, digit for digit;
* a typo, a number where a vector is needed, a force with no value at t = 0, one that blows the run
  up, a name taken: one line by the box, and the run on the page is the one before;
* forces are removed, the file's program is one click away, Download my program is the program
  `--vpython --force` writes;
* every control of the box has a name a screen reader speaks; screenshots at three sizes and in
  projector mode.

Tests ask for time with the jump (tests/browser_support.py's jump_to).
"""
from __future__ import annotations

import pytest

from browser_support import jump_to, require_browser, screenshot_folder

pytestmark = pytest.mark.browser
require_browser()

from browser.clock import LiveRun  # noqa: E402
from browser.graphs import SAMPLE_EVERY, csv_text  # noqa: E402
from physics.recording import steps_to_reach  # noqa: E402
from scenes import catalog  # noqa: E402
from test_browser import Program  # noqa: E402
from test_export import main_py  # noqa: E402
from test_jump_browser import download_csv  # noqa: E402

# The page's gcurves on its position graph, as vpython's page holds them (label, points, colour).
CURVES = """() => glowObjs.filter(o => o && o.graph_series && !o.__deleted && (o.title || '').startsWith('Position'))
  .flatMap(g => g.graph_series.map(s => ({label: s.label, points: (s.__data || []).length,
                                          colour: [s.__color.x, s.__color.y, s.__color.z]})))"""


def engine_csv(scene: str, t: float, *forces: str) -> str:
    """What Download CSV gives after a run to t with these forces: the engine's samples through LiveRun."""
    model = catalog.configure(scene, forces=forces).build()
    live = LiveRun(model, integrator=model.methods()[0], sample_every=SAMPLE_EVERY)
    samples = live.restart() + live.advance(steps_to_reach(t - model.state.t, model.dt))
    return csv_text(samples, m=live.state.m, labels=model.labels, dt=model.dt)


class Page:
    """One scene's page open in the module's browser, with its program; closed by close()."""

    def __init__(self, browser, scene="vertical", *extra, size=(1280, 800)):
        self.program = Program(scene, *extra)
        self.page = browser.new_page(viewport={"width": size[0], "height": size[1]}, accept_downloads=True)
        self.page.set_default_timeout(180_000)
        self.errors = []
        self.page.on("pageerror", lambda error: self.errors.append(str(error)))
        self.page.goto(self.program.url())
        self.page.locator("#force-text").wait_for()

    def text(self, element_id: str) -> str:
        return self.page.locator(f"#{element_id}").text_content()

    def add(self, name: str, text: str, *, said: str) -> str:
        """Type the force in, Enter, and wait for the box's line to say `said`; returns the line."""
        page = self.page
        page.fill("#force-name", name)
        page.fill("#force-text", text)
        page.press("#force-text", "Enter")
        page.wait_for_function("s => document.getElementById('force-said').textContent.includes(s)", arg=said)
        return self.text("force-said")

    def close(self):
        self.page.close()
        self.program.stop()


def test_a_force_typed_in_runs_with_its_arrow_beside_the_run_before(browser):
    page = Page(browser)
    try:
        p = page.page
        assert jump_to(p, 1.0) == pytest.approx(1.0)
        p.focus("#force-example")                          # the keyboard alone: the menu, then Tab, Enter
        p.keyboard.press("ArrowDown")                      # a constant push, vector(2, 0, 0)
        assert p.input_value("#force-text") == "vector(2, 0, 0)" and p.input_value("#force-name") == "push"
        p.keyboard.press("Tab")
        p.keyboard.press("Tab")
        p.keyboard.press("Control+a")
        p.keyboard.type("vector(0, 50, 0)")
        p.keyboard.press("Enter")
        p.wait_for_function("() => document.getElementById('force-said').textContent.includes('push added')")
        assert page.text("force-line") == "Fnet = Fspring + Fgravity + F_push"
        assert page.text("force-list").startswith("push: F = vector(0, 50, 0) N")
        boxes = p.locator(":not(.sm-measure) > input[type=checkbox]")       # p, F_net, forces, F∥ and F⊥
        assert boxes.nth(2).is_checked()                                       # each force's arrow is shown
        assert jump_to(p, 0.2) == pytest.approx(0.2)
        assert download_csv(p) == engine_csv("vertical", 0.2, "push=vector(0, 50, 0)")
        curves = p.evaluate(CURVES)
        grey = [curve for curve in curves if curve["label"] == "without push"]
        assert grey and grey[0]["points"] >= 100 and max(grey[0]["colour"]) - min(grey[0]["colour"]) < 0.01
        assert not any(curve["label"].endswith("exact") for curve in curves)   # no closed form with a push
        p.screenshot(path=str(screenshot_folder() / "force-box-local-1280.png"), full_page=True)
        assert not page.errors and "Traceback" not in "".join(page.program.errors)
    finally:
        page.close()


@pytest.mark.parametrize("name, text, said", [
    ("push", "vector(2, 0", "cannot read the force: a ( is not closed"),
    ("push", "-0.5*mag(v)", "is a number, but a force is a vector"),
    ("spring", "vector(2, 0, 0)", "the name spring is taken"),
    ("pull", "-1/mag(r - vector(0, -1.5, 0))*r", "the force pull has no value at t = 0"),
    ("stiff", "-1e6*r", "the force stiff makes the run blow up by t = "),
    ("brake", "__import__('os')", "text in quotes is not allowed"),
])
def test_a_force_that_cannot_run_is_one_line_and_the_run_stays(name, text, said, browser):
    page = Page(browser)
    try:
        p = page.page
        jump_to(p, 0.5)
        held = download_csv(p)
        line = page.add(name, text, said=said)
        assert line.endswith("the run before is still on") and "\n" not in line
        assert download_csv(p) == held                      # the same run, still at 0.5 s
        assert page.text("force-line") == "Fnet = Fspring + Fgravity"
        assert "Traceback" not in "".join(page.program.errors)
    finally:
        page.close()


def test_forces_are_removed_and_the_files_forces_are_one_click_away(browser):
    """Opened with --force, the page starts with that force; Back to the file's program returns to it."""
    page = Page(browser, "vertical", "--force", "wind=-0.5*mag(v)*v")
    try:
        p = page.page
        assert page.text("force-line") == "Fnet = Fspring + Fgravity + F_wind"
        assert p.is_disabled("#force-reset")
        page.add("push", "vector(0, 50, 0)", said="push added")
        assert page.text("force-line") == "Fnet = Fspring + Fgravity + F_wind + F_push"
        p.get_by_role("button", name="Remove wind").click()
        p.wait_for_function("() => document.getElementById('force-said').textContent.includes('wind removed')")
        assert page.text("force-line") == "Fnet = Fspring + Fgravity + F_push"
        jump_to(p, 0.2)
        assert download_csv(p) == engine_csv("vertical", 0.2, "push=vector(0, 50, 0)")
        p.get_by_role("button", name="Back to the file's program").click()
        p.wait_for_function("() => document.getElementById('force-said').textContent.includes(\"back to the file's\")")
        assert page.text("force-line") == "Fnet = Fspring + Fgravity + F_wind"
        jump_to(p, 0.2)
        assert download_csv(p) == engine_csv("vertical", 0.2, "wind=-0.5*mag(v)*v")
    finally:
        page.close()


def test_download_my_program_is_the_program_with_the_force(browser):
    page = Page(browser)
    try:
        p = page.page
        page.add("wind", "-0.5*mag(v)*v", said="wind added")
        with p.expect_download() as caught:
            p.get_by_role("button", name="Download my program").click()
        with open(caught.value.path(), encoding="utf-8") as handle:
            written = handle.read()
        expected = main_py("vertical", "--vpython", "-", "--force", "wind=-0.5*mag(v)*v", "--arrows", "p,F_net,forces")
        assert written == expected.stdout
    finally:
        page.close()


def test_every_control_of_the_box_has_a_name_a_screen_reader_speaks(browser):
    page = Page(browser)
    try:
        p = page.page
        for label in ("start from", "name", "F ="):
            assert p.get_by_label(label, exact=True).count() == 1, label
        for name in ("Add and run", "Back to the file's program", "Download my program"):
            assert p.get_by_role("button", name=name).count() == 1, name
        assert p.get_by_role("status").filter(has=p.locator("#force-said")).count() <= 1
        assert p.locator("#force-said").get_attribute("aria-live") == "polite"
        assert p.get_by_role("list", name="forces added").count() == 1
        hidden = p.evaluate("""() => { const root = document.getElementById('force-box').parentNode;
            let box = root; while (box && box.tagName !== 'INPUT') box = box.previousElementSibling;
            return box && box.getAttribute('aria-hidden') === 'true' && box.tabIndex === -1; }""")
        assert hidden                                       # the channel is no control of the page
    finally:
        page.close()


@pytest.mark.parametrize("size, projector", [((1024, 768), False), ((1280, 800), False), ((1920, 1080), False),
                                             ((1280, 800), True)])
def test_screenshots_of_the_box_with_a_force_added(size, projector, browser):
    page = Page(browser, "vertical", *(("--projector",) if projector else ()), size=size)
    try:
        p = page.page
        jump_to(p, 1.5)
        page.add("wind", "-0.5*mag(v)*v", said="wind added")
        jump_to(p, 3.0)
        p.locator("#force-box").scroll_into_view_if_needed()
        name = f"force-box-local-{size[0]}x{size[1]}{'-projector' if projector else ''}.png"
        p.screenshot(path=str(screenshot_folder() / name))
        box = p.locator("#force-box").bounding_box()
        assert box["x"] >= 0 and box["x"] + box["width"] <= size[0] + 1      # the box fits the window's width
        font = p.evaluate("parseFloat(getComputedStyle(document.getElementById('force-text')).fontSize)")
        assert font >= (22 if projector else 18)                             # read from the back of the room
    finally:
        page.close()

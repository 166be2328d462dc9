"""Issue 39 in headless Chromium: no WCAG 2.1 A or AA violation that axe-core finds, any impact.

* the local page of every scene, paused, with the Measure panel open and each graph choice
  (energy graph, phase space, energy bars), a graph's table of points open, and in projector mode;
* the offline page (`main.py SCENE --html F`) of every scene, after a Step and a description, with
  a table open, and in projector mode;
* with prefers-reduced-motion, each page opens paused with its first frame drawn;
* the description in words on the offline page is, word for word, the local page's sentences for
  the same step (export/description.py's template, the program's numbers against the engine's).

The pages are opened with prefers-reduced-motion, so they start paused at t = 0, and reach the
times they need by Step: nothing here waits for the animation.
"""
from __future__ import annotations

import subprocess
import sys

import pytest

from axe_support import violations
from browser_support import launched, require_browser, screenshot_folder, wait_for
from export.description import describe
from physics.equilibrium import equilibrium
from scenes import catalog
from test_browser import ROOT, Program, shown_time

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()
SCREENSHOTS = screenshot_folder()
WAIT = 180.0          # s: a frame on a busy machine with software WebGL
GRAPH_CHOICES = ("phase space", "energy bars", "energy graph")


@pytest.fixture(scope="module")
def browser():
    with launched(sync_api, scrollbars=True) as chromium:
        yield chromium


class Local:
    """`main.py SCENE` in a browser context with prefers-reduced-motion: open, paused at t = 0."""

    def __init__(self, browser, scene: str, size=(1280, 800)):
        self.program = Program(scene)
        self.context = browser.new_context(viewport={"width": size[0], "height": size[1]}, reduced_motion="reduce")
        self.page = self.context.new_page()
        self.page.goto(self.program.url())
        self.page.get_by_role("button", name="Run", exact=True).wait_for(timeout=WAIT * 1000)
        wait_for(lambda: shown_time(self.page) == 0.0, timeout=WAIT, what="the page paused at t = 0")

    def step(self, times: int = 1) -> float:
        for _ in range(times):
            before = shown_time(self.page)
            self.page.get_by_role("button", name="Step", exact=True).click()
            wait_for(lambda: shown_time(self.page) > before, timeout=WAIT, what="a Step")
        return shown_time(self.page)

    def graphs_described(self) -> None:
        """Wait until every graph shown has its text alternative (export/page_access.js)."""
        self.page.wait_for_function("""() => { const gs = Array.from(document.querySelectorAll('.glowscript-graph'))
            .filter(g => g.offsetParent !== null); return gs.length > 0 && gs.every(g => g.getAttribute('aria-label')); }""",
                                    timeout=WAIT * 1000)

    def close(self):
        self.context.close()
        self.program.stop()


def no_violations(page, where: str) -> None:
    found = violations(page)
    assert not found, f"{where}:\n" + "\n".join(found)


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
def test_the_local_page_has_no_wcag_violation(scene, browser):
    local = Local(browser, scene)
    page = local.page
    try:
        local.step(2)
        page.get_by_role("button", name="Describe (D)", exact=True).click()
        page.locator(".sm-description").filter(has_text="t = ").wait_for(timeout=WAIT * 1000)
        page.locator(".sm-measure-toggle").click()
        page.locator(".sm-measure").wait_for(state="visible")
        local.graphs_described()
        page.locator("details.sm-alt summary").first.click()
        page.locator("table.sm-points").first.wait_for(timeout=WAIT * 1000)
        no_violations(page, f"{scene}, Measure open, energy graph, a table open")
        menu = page.get_by_role("combobox", name="graph")
        for choice in GRAPH_CHOICES:
            menu.select_option(choice)
            local.step()   # the menu's message is carried out before this step's
            if choice == "energy bars":
                page.locator(".sm-bars").first.wait_for(timeout=WAIT * 1000)
            local.graphs_described()
            no_violations(page, f"{scene}, graph place: {choice}")
        page.get_by_role("button", name="Projector: off (P)", exact=True).click()
        page.wait_for_function("() => document.body.classList.contains('sm-projector')")
        no_violations(page, f"{scene}, projector mode")
        page.screenshot(path=str(SCREENSHOTS / f"access-local-{scene}.png"))
    finally:
        local.close()


def written_page(tmp_path, scene: str) -> str:
    path = tmp_path / f"{scene}.html"
    done = subprocess.run([sys.executable, str(ROOT / "main.py"), scene, "--html", str(path)], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return path.as_uri()


def offline(browser, url: str):
    context = browser.new_context(viewport={"width": 1280, "height": 800}, reduced_motion="reduce")
    context.route("**/*", lambda route: route.continue_() if route.request.url.split("#")[0] == url else route.abort())
    page = context.new_page()
    page.goto(url)
    page.wait_for_function("() => window.offlineState && window.offlineState().paused && "
                           "document.querySelector('.glowscript-graph')", timeout=WAIT * 1000)
    return context, page


def offline_step(page, times: int = 1) -> int:
    for _ in range(times):
        n = page.evaluate("() => window.offlineState().n || 0")
        page.click("#step-button")
        page.wait_for_function("n => window.offlineState().n > n", arg=n, timeout=WAIT * 1000)
    return page.evaluate("() => window.offlineState().n")


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
def test_the_offline_page_has_no_wcag_violation(scene, browser, tmp_path):
    context, page = offline(browser, written_page(tmp_path, scene))
    try:
        offline_step(page, 2)
        page.wait_for_function("() => document.getElementById('description').textContent.startsWith('t = ')")
        page.wait_for_function("() => document.querySelector('.glowscript-graph').getAttribute('aria-label')",
                               timeout=WAIT * 1000)
        page.locator("details.sm-alt summary").first.click()
        page.locator("table.sm-points").first.wait_for()
        no_violations(page, f"offline {scene}")
        page.get_by_label("projector").check()
        no_violations(page, f"offline {scene}, projector")
        page.screenshot(path=str(SCREENSHOTS / f"access-offline-{scene}.png"))
    finally:
        context.close()


@pytest.mark.parametrize("scene", ["vertical", "regimes", "pendulum", "friction"])
def test_the_offline_description_is_the_local_pages_for_the_same_step(scene, browser, tmp_path):
    """Both pages fill export/description.py's template: the offline page with the program's numbers
    after 7 Steps, here the engine's, through the local page's own function."""
    context, page = offline(browser, written_page(tmp_path, scene))
    try:
        n = offline_step(page, 7)
        said = page.evaluate("() => document.getElementById('description').textContent")
    finally:
        context.close()
    setup = catalog.configure(scene)
    model = setup.build()
    from browser.clock import LiveRun
    live = LiveRun(model, integrator=model.methods()[0] if model.integrators is None else "euler-cromer")
    live.advance(n)
    from browser.controls import time_decimals
    expected = describe(model, live.engine.methods, state=live.state, before=live.before,
                        equilibrium=equilibrium(model.forces, model.state), decimals=time_decimals(model.dt))
    assert said == expected


def test_with_reduced_motion_each_page_opens_paused_on_its_first_frame(browser, tmp_path):
    local = Local(browser, "damped")       # waits for Run shown and t = 0.00
    try:
        assert local.step() == pytest.approx(catalog.configure("damped").build().dt)
    finally:
        local.close()
    context, page = offline(browser, written_page(tmp_path, "damped"))   # waits for paused, graph drawn
    try:
        assert page.evaluate("() => window.offlineState().n") in (None, 0)
        assert page.evaluate("() => document.getElementById('run').textContent") == "Run"
        assert offline_step(page) == 1
    finally:
        context.close()

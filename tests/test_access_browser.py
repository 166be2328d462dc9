"""Issue 39 in headless Chromium: no WCAG 2.1 A or AA violation that axe-core finds, any impact;
nothing lost or overlapping at 200 % zoom; the pages open paused with reduced motion.

* the local page of every scene, paused, with the Measure panel open and each graph choice
  (energy graph, phase space, energy bars), a graph's table of points open, the description said,
  and in projector mode: one page for the whole module, taken from scene to scene by its scene
  menu (tests/access_pages.py), at the time it needs by Jump;
* the offline page (`main.py SCENE --html F`) of every scene, after 7 Steps, with a table open, and
  in projector mode; its description in words is, word for word, the local page's sentences for
  the same step (export/description.py's template, the program's numbers against the engine's);
* at 200 % browser zoom of a 1280 × 800 window (on integrators' offline page, and on the local
  page of integrators and resonance) both pages show every control, graph and line of
  text, none cut off and none over another;
* with prefers-reduced-motion each page opens paused on its first frame.

Nothing here waits for the animation: the pages are paused from the start and move by Jump or Step.

What it costs, and which scenes: on this 2-core machine under load one axe run on a page takes
10–40 s and opening a page 1–3 min (GlowScript compiles the program), so all 9 scenes × 2 pages ×
5 page states would cost about an hour. The pages' DOM differs by scene only in what the scene
declares: how many masses (curves, legends, tables), which sliders, the lab's data box, and
resonance's own graph; every control, name, table and live region is made by the same code for
every scene. So axe runs on the scenes whose DOM differs (LOCAL_SCENES, OFFLINE_SCENES): each
kind of control and graph occurs in one of them. damped and driven are vertical's page with one
or two more sliders of the same kind; regimes and drag are friction's with three or two masses;
pendulum's graphs are a mass's x and y, as integrators' several curves. The graph choices and
projector mode (which change the graph place and the colours, not the scene's controls) are
checked once, on integrators: four masses, the most curves. Each page is opened once per module.
"""
from __future__ import annotations

import pytest

from access_pages import (GRAPH_CHOICES, LocalPage, graphs_described, layout_problems, offline, offline_step,
                          open_table, settled, zoomed)
from axe_support import violations
from browser_support import launched, require_browser, screenshot_folder, shaded_like
from export.description import describe
from export.palette import mass_colour
from physics.equilibrium import equilibrium
from scenes import catalog

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()
SCREENSHOTS = screenshot_folder()
SHOWN_T = 2.0         # s: the time the local page jumps to, so each graph has points and a table
# The scenes whose pages differ in DOM (see above): the lab's box and one mass, several masses and
# friction, four masses without the method menu, and resonance's own graph and 39 masses.
LOCAL_SCENES = ["vertical", "friction", "integrators", "resonance"]
OFFLINE_SCENES = ["vertical", "friction", "integrators"]
EVERY_STATE = "integrators"   # where the graph choices and projector mode are checked too


@pytest.fixture(scope="module")
def browser():
    with launched(sync_api, scrollbars=True) as chromium:   # scrollbars take room, as on a desktop
        yield chromium


@pytest.fixture(scope="module")
def local(browser):
    page = LocalPage(browser)
    try:
        yield page
    finally:
        page.close()


def no_violations(page, where: str, context=None) -> None:
    found = violations(page, context)
    assert not found, f"{where}:\n" + "\n".join(found)


@pytest.mark.parametrize("scene", LOCAL_SCENES)
def test_the_local_page_has_no_wcag_violation(scene, local):
    page = local.show(scene)
    local.measure()
    local.jump(SHOWN_T)
    local.describe()
    local.graphs_described()
    open_table(page)
    shown = page.get_by_role("combobox", name="graph").input_value()
    no_violations(page, f"{scene}, Measure open, {shown}, the description said, a table open, the force box")
    page.screenshot(path=str(SCREENSHOTS / f"access-local-{scene}.png"))
    if scene != EVERY_STATE:
        return
    for choice in [choice for choice in GRAPH_CHOICES if choice != shown]:
        local.choose_graph(choice)
        if GRAPH_CHOICES[choice]:
            local.graphs_described()
        no_violations(page, f"{scene}, graph place: {choice}", context="#sm-graphs")   # what the choice changed
    page.locator("#sm-projector").click()
    page.wait_for_function("() => document.body.classList.contains('sm-projector')")
    try:
        no_violations(page, f"{scene}, projector mode")
        page.screenshot(path=str(SCREENSHOTS / f"access-local-{scene}-projector.png"))
    finally:
        page.locator("#sm-projector").click()
        page.wait_for_function("() => !document.body.classList.contains('sm-projector')")


def test_with_reduced_motion_the_local_page_opens_paused_on_its_first_frame(local):
    page = local.show("damped")
    assert local.opened == {"t": 0.0, "button": "Run"}
    assert local.jump(0.0) == 0.0   # a jump to t = 0 draws what the page opened with
    canvas = page.locator(".glowscript-canvas-wrapper canvas").first
    path = SCREENSHOTS / "access-local-first-frame.png"
    canvas.screenshot(path=str(path))
    assert shaded_like(Image.open(path).convert("RGB"), mass_colour(0)) > 100, "no mass drawn in the first frame"


@pytest.mark.parametrize("scene", ["integrators", "resonance"])   # the most graphs, masses and sliders
def test_at_200_percent_zoom_nothing_on_the_local_page_is_lost_or_overlaps(scene, local):
    page = local.show(scene)
    local.measure()
    local.jump(SHOWN_T)
    local.describe()
    zoomed(page)
    try:
        graphs_described(page)
        problems = layout_problems(page)
        page.screenshot(path=str(SCREENSHOTS / f"access-local-{scene}-200.png"), full_page=True)
    finally:
        page.set_viewport_size({"width": local.size[0], "height": local.size[1]})   # Playwright's own emulation again
        settled(page)
    assert not problems, f"{scene} at 200 %:\n" + "\n".join(problems)


def engine_sentences(scene: str, steps: int) -> str:
    """The local page's sentences after `steps` Steps from t = 0 (browser/view.py's, from the engine)."""
    from browser.clock import LiveRun
    from browser.controls import time_decimals

    model = catalog.configure(scene).build()
    live = LiveRun(model, integrator=model.methods()[0] if model.integrators is None else "euler-cromer")
    live.advance(steps)
    return describe(model, live.engine.methods, state=live.state, before=live.before,
                    equilibrium=equilibrium(model.forces, model.state), decimals=time_decimals(model.dt))


@pytest.mark.parametrize("scene", OFFLINE_SCENES)
def test_the_offline_page_has_no_wcag_violation_and_says_the_local_pages_words(scene, browser, tmp_path):
    context, page = offline(browser, scene, tmp_path)
    try:
        assert page.evaluate("() => window.offlineState().n") in (None, 0)     # reduced motion: paused
        assert page.evaluate("() => document.getElementById('run').textContent") == "Run"
        n = offline_step(page, 7)
        said = page.evaluate("() => document.getElementById('description').textContent")
        assert said == engine_sentences(scene, n)
        graphs_described(page)
        open_table(page)
        no_violations(page, f"offline {scene}")
        page.screenshot(path=str(SCREENSHOTS / f"access-offline-{scene}.png"))
        if scene != EVERY_STATE:
            return
        page.get_by_label("projector").check()
        no_violations(page, f"offline {scene}, projector")
        page.get_by_label("projector").uncheck()
        # 200 % zoom on the same page (no second load): a 1280 × 800 window is 640 × 400 CSS px
        zoomed(page)
        problems = layout_problems(page)
        page.screenshot(path=str(SCREENSHOTS / f"access-offline-{scene}-200.png"), full_page=True)
        assert not problems, f"offline {scene} at 200 %:\n" + "\n".join(problems)
    finally:
        context.close()

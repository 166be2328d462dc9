"""Issue 39 in headless Chromium: no WCAG 2.1 A or AA violation that axe-core finds, any impact;
nothing lost or overlapping at 200 % zoom; the pages open paused with reduced motion.

* the local page of every scene, paused, with the Measure panel open and each graph choice
  (energy graph, phase space, energy bars), a graph's table of points open, the description said,
  and in projector mode: one page for the whole module, taken from scene to scene by its scene
  menu (tests/access_pages.py), at the time it needs by Jump;
* the offline page (`main.py SCENE --html F`) of every scene, after 7 Steps, with a table open, and
  in projector mode; its description in words is, word for word, the local page's sentences for
  the same step (export/description.py's template, the program's numbers against the engine's);
* at 200 % browser zoom of a 1280 × 800 window both pages show every control, graph and line of
  text, none cut off and none over another;
* with prefers-reduced-motion each page opens paused on its first frame.

Nothing here waits for the animation: the pages are paused from the start and move by Jump or Step.
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


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
def test_the_local_page_has_no_wcag_violation(scene, local):
    page = local.show(scene)
    local.measure()
    local.jump(SHOWN_T)
    local.describe()
    local.graphs_described()
    open_table(page)
    shown = page.get_by_role("combobox", name="graph").input_value()
    no_violations(page, f"{scene}, Measure open, {shown}, the description said, a table open")
    page.screenshot(path=str(SCREENSHOTS / f"access-local-{scene}.png"))
    for choice in [choice for choice in GRAPH_CHOICES if choice != shown]:
        local.choose_graph(choice)
        if GRAPH_CHOICES[choice]:
            local.graphs_described()
        no_violations(page, f"{scene}, graph place: {choice}", context="#sm-graphs")   # what the choice changed
    page.locator("#sm-projector").click()
    page.wait_for_function("() => document.body.classList.contains('sm-projector')")
    try:
        no_violations(page, f"{scene}, projector mode")
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


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
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
        page.get_by_label("projector").check()
        no_violations(page, f"offline {scene}, projector")
    finally:
        context.close()


def test_at_200_percent_zoom_nothing_on_the_offline_page_is_lost_or_overlaps(browser, tmp_path):
    """A 1280 × 800 window at 200 %: 640 × 400 CSS px, each drawn with 2 × 2 device px."""
    context, page = offline(browser, "regimes", tmp_path, size=(640, 400), device_scale_factor=2)
    try:
        offline_step(page, 7)
        graphs_described(page)
        problems = layout_problems(page)
        page.screenshot(path=str(SCREENSHOTS / "access-offline-regimes-200.png"), full_page=True)
    finally:
        context.close()
    assert not problems, "offline regimes at 200 %:\n" + "\n".join(problems)

"""Jump to t on both pages, in headless Chromium, with the controls a teacher uses.

The local page: the box starts at the question time; Jump, Enter in the box and the key J each
take the run there, paused, and what the page then holds (Download CSV: every graphed sample) is
the engine's run to that step, digit for digit; Step goes on from there; a bad t is one line.
tests/test_jump.py holds the same for every scene and every graph point, without a browser.

The offline page: a jump equals a run stepped there in the same page (Step pressed n times):
each mass's r and p as the program reported them, and every point of every graph curve, to the
last digit; the jump to the question time prints --headless's answer; Step, Run and a bad t.
"""
from __future__ import annotations


import pytest

from browser_support import jump_offline, jump_to, require_browser, screenshot_folder

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()

from browser.clock import LiveRun  # noqa: E402
from browser.graphs import SAMPLE_EVERY, csv_text  # noqa: E402
from physics.recording import steps_to_reach  # noqa: E402
from scenes import catalog  # noqa: E402
from test_browser import Program, shown_time  # noqa: E402
from test_export import main_py  # noqa: E402
from test_offline_page_browser import Offline, json_answers  # noqa: E402


def engine_csv(scene: str, t: float) -> str:
    """What Download CSV gives after a run to t: the engine's samples through the page's LiveRun."""
    model = catalog.configure(scene).build()
    live = LiveRun(model, integrator=model.methods()[0], sample_every=SAMPLE_EVERY)
    samples = live.restart() + live.advance(steps_to_reach(t - model.state.t, model.dt))
    return csv_text(samples, m=live.state.m, labels=model.labels, dt=model.dt)


def download_csv(page) -> str:
    with page.expect_download() as download:
        page.get_by_role("button", name="Download CSV", exact=True).click()
    with open(download.value.path(), newline="", encoding="utf-8") as handle:
        return handle.read()


def test_the_local_pages_jump_lands_where_the_engine_does_and_goes_on_from_there(browser):
    """driven: Jump (its box at the question time, 20 s), then 1.5 s by Enter in the box, then
    0.5 s by the key J: each time paused there, with the engine's every sample in the CSV; Step
    adds one Δt; a bad entry is one sentence and the run stays."""
    program = Program("driven")
    page = None
    try:
        page = browser.new_page(viewport={"width": 1024, "height": 768}, accept_downloads=True)
        page.goto(program.url())
        box = page.locator("#sm-jump-t")
        box.wait_for()
        assert box.input_value() == "20" and box.get_attribute("aria-label") == "jump to t, in seconds"

        page.get_by_role("button", name="Jump", exact=True).click()                       # the button, at 20 s
        page.locator(".sm-jumped[data-jumps='1']").wait_for(state="attached")
        page.get_by_role("button", name="Run", exact=True).wait_for()                     # paused there
        assert shown_time(page) == 20.0
        assert download_csv(page) == engine_csv("driven", 20.0)
        page.screenshot(path=str(screenshot_folder() / "jump-driven.png"))

        box.fill("1.5")                                                        # Enter: back, from 0
        box.press("Enter")
        page.locator(".sm-jumped[data-jumps='2']").wait_for(state="attached")
        assert shown_time(page) == 1.5
        assert download_csv(page) == engine_csv("driven", 1.5)

        box.fill("0.5 s")                                                      # the key J, from the page
        page.evaluate("() => document.activeElement.blur()")
        page.keyboard.press("j")
        page.locator(".sm-jumped[data-jumps='3']").wait_for(state="attached")
        assert shown_time(page) == 0.5

        page.get_by_role("button", name="Step", exact=True).click()                       # Step goes on from there
        page.wait_for_function("() => document.body.innerText.includes('t = 0.51 s')")
        assert download_csv(page) == engine_csv("driven", 0.51)
        assert jump_to(page, 0.25) == pytest.approx(0.25)                      # the tests' helper

        box.fill("soon")
        page.get_by_role("button", name="Jump", exact=True).click()
        page.get_by_text("jump to t: 'soon' is not a time in seconds").wait_for()
        assert shown_time(page) == 0.25
        assert "Traceback" not in "".join(program.errors)
    finally:
        if page is not None:
            page.close()
        program.stop()


GRAPH_POINTS = """() => { const out = [];
  jQuery('#view *, #graphs *').each(function () { const plot = jQuery(this).data('plot');
    if (plot) out.push(plot.getData().map(s => s.data.map(d => [d[0], d[1]]))); });
  return out; }"""


def test_the_offline_pages_jump_equals_a_run_stepped_there(browser, tmp_path):
    """driven.html: Reset, Step pressed 150 times, then Reset and Jump to 1.5 s (the same step):
    the program's r and p and every graph point are the same numbers; Jump to the question time
    prints --headless's answer; Enter and the key J jump; Step after a jump is one Δt; a bad t
    is one line."""
    path = tmp_path / "driven.html"
    assert main_py("driven", "--html", str(path)).returncode == 0
    page = Offline(browser, path, size=(800, 600))
    try:
        web = page.page
        web.click("#run")
        web.click("#reset")
        web.wait_for_function("() => window.offlineState().paused && window.offlineState().n === 0")
        web.evaluate("n => { for (let i = 0; i < n; i++) document.getElementById('step-button').click(); }", 150)
        web.wait_for_function("() => window.offlineState().n === 150")
        web.wait_for_function("() => document.getElementById('step').textContent.includes('t = 1.5 s')")
        stepped = web.evaluate("window.offlineState()")["last"], web.evaluate(GRAPH_POINTS)

        web.click("#reset")
        web.wait_for_function("() => window.offlineState().n === 0")
        web.fill("#jump-t", "1.5")
        web.click("#jump")
        web.wait_for_function("() => window.offlineState().jumpsDrawn === 1")
        state = web.evaluate("window.offlineState()")
        jumped = state["last"], web.evaluate(GRAPH_POINTS)
        assert state["n"] == 150 and state["paused"]
        assert web.evaluate("document.getElementById('time').textContent") == "t = 1.50 s"
        assert jumped == stepped
        assert sum(len(curve) for graph in jumped[1] for curve in graph) >= 2 * 150

        assert web.input_value("#jump-t") == "1.5"
        web.fill("#jump-t", "20")                                           # the question time, by Enter
        web.press("#jump-t", "Enter")
        web.wait_for_function("() => window.offlineState().jumpsDrawn === 2")
        assert page.answers(1) == json_answers("driven")
        web.click("#step-button")                                           # one Δt on
        web.wait_for_function("() => window.offlineState().n === 2001")

        web.fill("#jump-t", "0.3")                                          # the key J
        web.evaluate("() => document.activeElement.blur()")
        web.keyboard.press("j")
        web.wait_for_function("() => window.offlineState().jumpsDrawn === 3")
        assert web.evaluate("window.offlineState()")["n"] == 30
        assert jump_offline(web, 0.05)["n"] == 5                            # the tests' helper

        web.fill("#jump-t", "-2")
        web.click("#jump")
        assert page.text("status") == "jump to t: the run starts at t = 0 s, so it cannot show t = -2 s"
        assert web.evaluate("window.offlineState()")["n"] == 5
        assert not page.refused and not page.errors, (page.refused, page.errors)
    finally:
        page.close()

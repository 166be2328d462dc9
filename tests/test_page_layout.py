"""A page a class can read (issue 18), checked in headless Chromium: browser/page_layout.py.

Each scene's page is laid out, at a laptop's 1280 × 800 window and at 1024 × 768, in
tests/test_browser.py::test_scene_in_the_browser (one page load per scene does both jobs, issue 31).

One page goes through the keys with real key presses (Space, →, R, +, −), Tab's focus outline,
and projector mode (key P): text at least 22 px and graph lines LINE_FACTOR times thicker.

Skipped, with the reason, where Chromium or Playwright is missing.
"""
from __future__ import annotations

import subprocess
import sys

import pytest

from browser.page_layout import LINE_FACTOR, PROJECTOR_PX
from scenes import catalog
from test_browser import MEASURE, ROOT, Program, laid_out, shown_time, speed_shown
from browser_support import jump_to, wait_for

pytestmark = pytest.mark.browser


def line_widths(page) -> list[float]:
    return page.evaluate("() => glowObjs.filter(o => o && o.graph_series && !o.__deleted)"
                         ".flatMap(g => g.graph_series.map(s => s.width))")


def test_keys_tab_and_projector_mode(browser):
    """Space runs and pauses, → steps one Δt, R resets, + and − change the speed (real key presses,
    the focus on the page, not on a control); Tab reaches the buttons with a visible outline;
    P turns projector mode on: text at least 22 px and thicker graph lines. The page is jumped to
    t = 1 s first, paused there."""
    dt = catalog.configure("damped").build().dt
    program = Program("damped")
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    try:
        page.goto(program.url())
        jump_to(page, 1.0)                  # paused there
        laid_out(page, graphs=2)
        widths = line_widths(page)
        page.evaluate("() => document.activeElement && document.activeElement.blur()")      # the focus on the page itself

        page.keyboard.press("Space")        # runs: t goes on from 1 s
        page.get_by_role("button", name="Pause", exact=True).wait_for()
        wait_for(lambda: shown_time(page) > 1.0, what="Space to run")
        page.keyboard.press("Space")        # pauses
        page.get_by_role("button", name="Run", exact=True).wait_for()
        paused = shown_time(page)
        page.keyboard.press("ArrowRight")
        stepped = wait_for(lambda: (t := shown_time(page)) != paused and t, what="→ to step")
        assert stepped - paused == pytest.approx(dt, abs=1e-6)
        page.keyboard.press("r")
        wait_for(lambda: shown_time(page) == 0.0, what="R to reset")
        assert speed_shown(page) == "1×"
        page.keyboard.press("+")
        wait_for(lambda: speed_shown(page) == "2×", what="+ to speed up")
        page.keyboard.press("-")
        page.keyboard.press("-")
        wait_for(lambda: speed_shown(page) == "½×", what="− to slow down")
        page.keyboard.press("Space")
        page.get_by_role("button", name="Pause", exact=True).wait_for()

        page.keyboard.press("Tab")
        focused = page.evaluate("() => [document.activeElement.tagName, getComputedStyle(document.activeElement)"
                                ".outlineWidth, getComputedStyle(document.activeElement).outlineStyle]")
        assert focused[0] in ("BUTTON", "SELECT") and float(focused[1].rstrip("px")) >= 3 and focused[2] != "none"
        reached = set()
        for _ in range(20):
            reached.add(page.evaluate("() => document.activeElement.tagName + ':' + "
                                      "(document.activeElement.textContent || '').trim().slice(0, 12)"))
            page.keyboard.press("Tab")
        assert {"BUTTON:Step", "BUTTON:Reset", "BUTTON:Download CSV"} <= reached, reached
        assert any(name.startswith("SELECT") for name in reached) and any(name.startswith("SPAN") for name in reached)

        page.evaluate("() => document.activeElement && document.activeElement.blur()")
        page.keyboard.press("p")
        m = wait_for(lambda: (m := page.evaluate(MEASURE)) and m["fonts"]["buttons"] >= PROJECTOR_PX and m,
                     what="projector mode's larger text")
        for name, size in m["fonts"].items():
            assert size >= PROJECTOR_PX, f"{name} in {size} px text in projector mode"
        thick = line_widths(page)
        assert len(thick) == len(widths) and all(b == pytest.approx(LINE_FACTOR * a) for a, b in zip(widths, thick))
        page.keyboard.press("p")
        wait_for(lambda: page.evaluate(MEASURE)["fonts"]["buttons"] < PROJECTOR_PX, what="projector mode off")
        assert "Traceback" not in "".join(program.errors)
    finally:
        page.close()
        program.stop()


def test_projector_is_for_the_page_only():
    done = subprocess.run([sys.executable, "main.py", "vertical", "--headless", "--projector"],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and "--projector is for the browser page" in done.stderr

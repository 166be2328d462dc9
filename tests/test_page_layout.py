"""A page a class can read (issue 18), checked in headless Chromium: browser/page_layout.py.

One page load per scene, at a laptop's 1280 × 800 window: nothing scrolls sideways, the 3-D view
and the position graph are both wholly inside the window, every text (body, buttons, menus, axis
ticks, legends) is at least 18 px, each legend sits outside its graph's drawing area, and every
tick label is a plain decimal on one line. On the same page the keys work with real key presses
(Space, →, R, +, −), and in projector mode (key P) every text is at least 22 px and the ticks stay
on one line. Then at 1024 × 768 nothing scrolls sideways either.

One more page goes through the keys with real key presses (Space, →, R, +, −), Tab's focus outline,
and projector mode (key P): text at least 22 px and graph lines LINE_FACTOR times thicker.

Skipped, with the reason, where Chromium or Playwright is missing.
"""
from __future__ import annotations

import re
import subprocess
import sys

import pytest

from browser.page_layout import BODY_PX, LINE_FACTOR, PROJECTOR_PX
from scenes import catalog
from test_browser import ROOT, Program, browser, drawable_scenes, graph_count, shown_time  # noqa: F401 (a fixture)
from browser_support import wait_for

pytestmark = pytest.mark.browser
KEY_PATIENCE_MS = 120_000   # a key's effect waits for the next frame: resonance's 39 masses on a busy machine
PLAIN = re.compile(r"^[-−]?\d+(\.\d+)?$")   # a tick label: a plain decimal, never 4e-2

MEASURE = """() => {
  const box = e => { const b = e.getBoundingClientRect(); return {x: b.x, y: b.y, width: b.width, height: b.height}; };
  const sizes = sel => Array.from(document.querySelectorAll(sel)).filter(e => e.offsetParent !== null)
                          .map(e => parseFloat(getComputedStyle(e).fontSize));
  const texts = Array.from(document.querySelectorAll('#glowscript span, #glowscript div, #glowscript i'))
      .filter(e => e.offsetParent !== null && Array.from(e.childNodes).some(n => n.nodeType === 3 && n.textContent.trim()));
  return {
    scrollWidth: document.documentElement.scrollWidth, width: window.innerWidth, height: window.innerHeight,
    canvas: box(document.querySelector('.glowscript-canvas-wrapper canvas')),
    graphs: Array.from(document.querySelectorAll('.glowscript-graph canvas.base')).map(box),
    legends: Array.from(document.querySelectorAll('.sm-legend')).map(box),
    fonts: {text: Math.min(...texts.map(e => parseFloat(getComputedStyle(e).fontSize))),
            buttons: Math.min(...sizes('button')), menus: Math.min(...sizes('select')),
            ticks: Math.min(...sizes('.tickLabel')), legends: Math.min(...sizes('.legendLabel')),
            titles: Math.min(...sizes('.sm-title'))},
    ticks: Array.from(document.querySelectorAll('.glowscript-graph .tickLabel')).filter(e => e.offsetParent !== null)
      .map(e => ({text: e.textContent, height: e.getBoundingClientRect().height,
                  font: parseFloat(getComputedStyle(e).fontSize)})),
  };
}"""


def inside(box, width, height) -> bool:
    return box["x"] >= 0 and box["y"] >= 0 and box["x"] + box["width"] <= width and box["y"] + box["height"] <= height


def overlap(a, b) -> bool:
    return (a["x"] < b["x"] + b["width"] and b["x"] < a["x"] + a["width"]
            and a["y"] < b["y"] + b["height"] and b["y"] < a["y"] + a["height"])


def laid_out(page, *, graphs: int):
    """The page's measurements once vpython has made every graph and the layout has placed them."""
    return wait_for(lambda: (m := page.evaluate(MEASURE)) and len(m["graphs"]) == graphs
                    and len(m["legends"]) == graphs and m, timeout=30.0, what="the graphs to be laid out")


@pytest.mark.parametrize("scene", drawable_scenes())
def test_the_view_and_the_position_graph_fit_a_laptop_window_in_large_text(browser, scene):
    program = Program(scene)
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    try:
        page.goto(program.url(), timeout=30_000)
        wait_for(lambda: shown_time(page) >= 2.0, timeout=90.0, what="t to reach 2 s")
        own_graph = hasattr(catalog.load(scene), "view_graph")
        m = laid_out(page, graphs=graph_count(scene))
        assert m["scrollWidth"] <= m["width"], f"the page scrolls sideways ({m['scrollWidth']} px)"
        assert inside(m["canvas"], 1280, 800), f"3-D view at {m['canvas']}"
        assert m["canvas"]["width"] >= 600, f"3-D view only {m['canvas']['width']} px wide"
        position = m["graphs"][own_graph]
        assert inside(position, 1280, 800), f"position graph at {position}"
        assert not overlap(m["canvas"], position)
        for name, size in m["fonts"].items():
            assert size >= BODY_PX, f"{name} in {size} px text"
        for legend in m["legends"]:
            for graph in m["graphs"]:
                assert not overlap(legend, graph), f"legend {legend} over graph {graph}"
        single_line_ticks(page)
        keys_work(page, scene)
        projector_mode(page)

        page.set_viewport_size({"width": 1024, "height": 768})
        m = wait_for(lambda: (m := page.evaluate(MEASURE)) and m["canvas"]["width"] < 600 and m,
                     timeout=120.0, what="the page to follow the window")
        assert m["scrollWidth"] <= 1024, f"at 1024 px the page scrolls sideways ({m['scrollWidth']} px)"
        assert "Traceback" not in "".join(program.errors)
    finally:
        page.close()
        program.stop()


def single_line_ticks(page, *, font: float = BODY_PX) -> None:
    """Every tick label is a plain decimal on one line (its box under 1.5 lines of its text), read
    once flot has drawn them at `font` px or more (it writes them anew when a graph's axis changes)."""
    ticks = wait_for(lambda: (t := page.evaluate(MEASURE)["ticks"]) and min(tick["font"] for tick in t) >= font
                     and t, timeout=120.0, what=f"tick labels in {font} px text")
    for tick in ticks:
        assert PLAIN.match(tick["text"]), f"tick label {tick['text']!r}"
        assert tick["height"] < 1.5 * tick["font"], f"tick label {tick['text']!r} on more than one line"


def keys_work(page, scene: str) -> None:
    """Real key presses with the focus on the page: Space pauses, → steps one Δt, R resets to 0,
    + speeds up, − slows down again, Space runs again."""
    dt = catalog.configure(scene).build().dt
    page.evaluate("() => document.activeElement && document.activeElement.blur()")      # the focus on the page itself
    page.keyboard.press("Space")
    page.get_by_role("button", name="Run").wait_for(timeout=KEY_PATIENCE_MS)
    paused = shown_time(page)
    page.keyboard.press("ArrowRight")
    stepped = wait_for(lambda: (t := shown_time(page)) != paused and t, timeout=KEY_PATIENCE_MS / 1000,
                       what="→ to step")
    assert stepped - paused == pytest.approx(dt, abs=1e-6)
    page.keyboard.press("r")
    wait_for(lambda: shown_time(page) == 0.0, timeout=KEY_PATIENCE_MS / 1000, what="R to reset")
    page.keyboard.press("+")
    wait_for(lambda: speed_shown(page) == "2×", timeout=KEY_PATIENCE_MS / 1000, what="+ to speed up")
    page.keyboard.press("-")
    wait_for(lambda: speed_shown(page) == "1×", timeout=KEY_PATIENCE_MS / 1000, what="− to slow down")
    page.keyboard.press("Space")
    page.get_by_role("button", name="Pause").wait_for(timeout=KEY_PATIENCE_MS)


def projector_mode(page) -> None:
    """Key P: every text at least PROJECTOR_PX, the ticks still one line each; P again to leave it."""
    page.evaluate("() => document.activeElement && document.activeElement.blur()")
    page.keyboard.press("p")
    single_line_ticks(page, font=PROJECTOR_PX)
    m = wait_for(lambda: (m := page.evaluate(MEASURE)) and m["fonts"]["buttons"] >= PROJECTOR_PX and m,
                 timeout=120.0, what="projector mode's larger text")
    for name, size in m["fonts"].items():
        assert size >= PROJECTOR_PX, f"{name} in {size} px text in projector mode"
    page.keyboard.press("p")
    wait_for(lambda: page.evaluate(MEASURE)["fonts"]["buttons"] < PROJECTOR_PX, what="projector mode off")


def speed_shown(page) -> str:
    return page.locator("select").filter(has=page.locator("option", has_text="¼×")).input_value()


def line_widths(page) -> list[float]:
    return page.evaluate("() => glowObjs.filter(o => o && o.graph_series && !o.__deleted)"
                         ".flatMap(g => g.graph_series.map(s => s.width))")


def test_keys_tab_and_projector_mode(browser):
    """Space pauses and runs, → steps one Δt, R resets, + and − change the speed (real key presses,
    the focus on the page, not on a control); Tab reaches the buttons with a visible outline;
    P turns projector mode on: text at least 22 px and thicker graph lines."""
    dt = catalog.configure("damped").build().dt
    program = Program("damped")
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    try:
        page.goto(program.url(), timeout=30_000)
        wait_for(lambda: shown_time(page) >= 1.0, timeout=90.0, what="t to reach 1 s")
        laid_out(page, graphs=2)
        widths = line_widths(page)
        page.evaluate("() => document.activeElement && document.activeElement.blur()")      # the focus on the page itself

        page.keyboard.press("Space")
        page.get_by_role("button", name="Run").wait_for(timeout=30_000)
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
        page.get_by_role("button", name="Pause").wait_for(timeout=30_000)

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
                     timeout=120.0, what="projector mode's larger text")
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

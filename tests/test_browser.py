"""Every scene in a real browser: headless Chromium driven by Playwright.

For each scene whose VIEW the shared view can draw, `python main.py SCENE --no-browser --port P` is
started, its printed URL opened in a laptop's 1280 × 800 window, and the page checked: Jump to
t = 2 s shows it there, paused; the 3-D canvas is not blank, the position graph has a curve, Step
advances it by one Δt and it stays paused, Reset returns it to 0, Run makes t advance, and closing
the page ends the program with status 0 within ENDS_WITHIN s. The
same page load checks the layout (issue 18, browser/page_layout.py): nothing scrolls sideways, the
3-D view and the position graph are wholly inside the window, every text is at least 18 px, each
legend sits outside the graphs, every tick label is a plain decimal on one line; the keys work
with real key presses (Space pauses, →, R, +, −, Space runs); in projector mode (key P) every text is at least 22 px
and the ticks stay on one line; and at 1024 × 768 nothing scrolls sideways either. A screenshot of each scene is saved
to SCENE.png in a folder in /tmp, or in docs/screenshots/ with UPDATE_SCREENSHOTS=1. The resonance scene's own graph must show its three curves.

One more page goes through the menus: a preset (Moon gravity) changes the constant in the caption,
moves its slider and restarts at t = 0; the scene menu switches to another scene in place; and
Download CSV gives a file with the command line's columns whose rows obey v = p/m and E = K + U
(menus.png, beside the others).

Skipped, with the reason, where Chromium or Playwright is missing (.ci/run installs both).
"""
from __future__ import annotations

import csv
import queue
import re
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from browser_support import (ENDS_WITHIN, TIME, colours, curve_pixels, free_port, jump_to,
                             pixels_like, require_browser, screenshot_folder, wait_for)
from browser.page_layout import BODY_PX, PROJECTOR_PX
from scenes import catalog
from browser.view import slider_range, time_decimals

ROOT = Path(__file__).resolve().parent.parent
SCREENSHOTS = screenshot_folder()   # docs/screenshots/ only with UPDATE_SCREENSHOTS=1

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()


def drawable_scenes() -> list[str]:
    """The scenes whose VIEW names a support and a coordinate the shared view knows."""
    names = []
    for name in catalog.SCENE_NAMES:
        view = getattr(catalog.load(name), "VIEW", None)
        if (isinstance(view, dict) and view.get("support", "ceiling") in ("ceiling", "wall")
                and view.get("plot", "y") in ("x", "y", "z", "xyz")):
            names.append(name)
    return names


class Program:
    """`python main.py SCENE [EXTRA...] --no-browser --port P`, its output read on a thread, always killed."""

    def __init__(self, scene: str, *extra: str):
        self.port = free_port()
        self.process = subprocess.Popen(
            [sys.executable, str(ROOT / "main.py"), scene, *extra, "--no-browser", "--port", str(self.port)],
            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines: queue.Queue = queue.Queue()
        self.errors: list[str] = []
        threading.Thread(target=self._read, args=(self.process.stdout, self.lines.put), daemon=True).start()
        threading.Thread(target=self._read, args=(self.process.stderr, self.errors.append), daemon=True).start()

    @staticmethod
    def _read(stream, keep):
        for line in stream:
            keep(line)

    def url(self, timeout: float = 30.0) -> str:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                line = self.lines.get(timeout=0.2)
            except queue.Empty:
                if self.process.poll() is not None:
                    break
                continue
            found = re.search(r"http://127\.0\.0\.1:\d+/", line)
            if found:
                self._wait_until_listening(deadline)
                return found.group(0)
        pytest.fail(f"no URL printed; stderr: {''.join(self.errors)[-2000:]}")

    def _wait_until_listening(self, deadline: float):
        """The URL is printed just before vpython's server starts listening: wait for it."""
        while time.monotonic() < deadline and self.process.poll() is None:
            try:
                socket.create_connection(("127.0.0.1", self.port), timeout=1.0).close()
                return
            except OSError:
                time.sleep(0.05)
        pytest.fail(f"nothing listens on port {self.port}; stderr: {''.join(self.errors)[-2000:]}")

    def stop(self):
        if self.process.poll() is None:
            self.process.kill()
        self.process.wait(timeout=10)


def graph_count(scene: str) -> int:
    """The graphs a scene's page shows: its own (view_graph), position, its error graph (VIEW["error"],
    integrators), energy."""
    module = catalog.load(scene)
    return 2 + hasattr(module, "view_graph") + bool(getattr(module, "VIEW", {}).get("error"))


def shown_time(page) -> float:
    """The t the caption shows, read from the page's text (`t = 12.34 s`)."""
    text = page.locator("b").filter(has_text=TIME).first.inner_text()
    return float(TIME.match(text).group(1))


def crop(path: Path, box: dict):
    """The part of a full-page screenshot inside an element's bounding box."""
    left, top = round(box["x"]), round(box["y"])
    return Image.open(path).convert("RGB").crop((left, top, left + round(box["width"]),
                                                 top + round(box["height"])))


def assert_not_blank(image, what: str):
    """At least 0.3 % of the pixels stand out from the background (a blank canvas has none).

    0.3 %, not more: in `integrators` the euler mass has flown off the picture by the time the
    page pauses, leaving three small spheres and their helices (about 0.8 % of the canvas).
    """
    counts = colours(image)
    background = max(counts, key=counts.get)
    others = sum(n for rgb, n in counts.items() if sum(abs(a - b) for a, b in zip(rgb, background)) > 60)
    assert len(counts) > 50 and others > 0.003 * counts.total(), \
        f"{what} looks blank ({len(counts)} colours, {others} pixels unlike the background)"


def graph_boxes(page) -> list[dict]:
    """Bounding boxes of the page's graphs in page order (the scene's own graph, if any, comes first)."""
    graphs = page.locator(".glowscript-graph canvas.base")
    return [graphs.nth(i).bounding_box() for i in range(graphs.count())]


def menu(page, option: str):
    """The <select> that offers `option` (vpython's menus have no names)."""
    return page.locator("select").filter(has=page.locator("option", has_text=option))


def caption_lines(page) -> list[str]:
    return [line.strip() for line in page.locator("body").inner_text().splitlines()]


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
                    and len(m["legends"]) == graphs and m, what="the graphs to be laid out")


def single_line_ticks(page, *, font: float = BODY_PX) -> None:
    """Every tick label is a plain decimal on one line (its box under 1.5 lines of its text), read
    once flot has drawn them at `font` px or more (it writes them anew when a graph's axis changes)."""
    ticks = wait_for(lambda: (t := page.evaluate(MEASURE)["ticks"]) and min(tick["font"] for tick in t) >= font
                     and t, what=f"tick labels in {font} px text")
    for tick in ticks:
        assert PLAIN.match(tick["text"]), f"tick label {tick['text']!r}"
        assert tick["height"] < 1.5 * tick["font"], f"tick label {tick['text']!r} on more than one line"


def keys_work(page, scene: str) -> None:
    """Real key presses with the focus on the page: Space pauses, → steps one Δt, R resets to 0,
    + speeds up, − slows down again, Space runs again."""
    dt = catalog.configure(scene).build().dt
    page.evaluate("() => document.activeElement && document.activeElement.blur()")      # the focus on the page itself
    page.keyboard.press("Space")
    page.get_by_role("button", name="Run", exact=True).wait_for()
    paused = shown_time(page)
    page.keyboard.press("ArrowRight")
    stepped = wait_for(lambda: (t := shown_time(page)) != paused and t,
                       what="→ to step")
    assert stepped - paused == pytest.approx(dt, abs=1e-6)
    page.keyboard.press("r")
    wait_for(lambda: shown_time(page) == 0.0, what="R to reset")
    page.keyboard.press("+")
    wait_for(lambda: speed_shown(page) == "2×", what="+ to speed up")
    page.keyboard.press("-")
    wait_for(lambda: speed_shown(page) == "1×", what="− to slow down")
    page.keyboard.press("Space")
    page.get_by_role("button", name="Pause", exact=True).wait_for()


def projector_mode(page) -> None:
    """Key P: every text at least PROJECTOR_PX, the ticks still one line each; P again to leave it."""
    page.evaluate("() => document.activeElement && document.activeElement.blur()")
    page.keyboard.press("p")
    single_line_ticks(page, font=PROJECTOR_PX)
    m = wait_for(lambda: (m := page.evaluate(MEASURE)) and m["fonts"]["buttons"] >= PROJECTOR_PX and m,
                 what="projector mode's larger text")
    for name, size in m["fonts"].items():
        assert size >= PROJECTOR_PX, f"{name} in {size} px text in projector mode"
    page.keyboard.press("p")
    wait_for(lambda: page.evaluate(MEASURE)["fonts"]["buttons"] < PROJECTOR_PX, what="projector mode off")


def speed_shown(page) -> str:
    return page.locator("select").filter(has=page.locator("option", has_text="¼×")).input_value()


@pytest.mark.parametrize("scene", drawable_scenes())
def test_scene_in_the_browser(browser, scene):
    """One page load per scene checks both the page's controls and its layout in a laptop's
    1280 × 800 window (issue 31: the two were separate tests, each starting the program and waiting
    for the same run). It jumps to t = 2 s (issue 35: it used to watch the run get there)."""
    dt = catalog.configure(scene).build().dt
    decimals = time_decimals(dt)
    program = Program(scene)
    page = None
    try:
        url = program.url()
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        page.goto(url)

        # Jump to 2 s: the page shows it, paused (its clock's pace: tests/test_jump_browser.py)
        assert jump_to(page, 2.0) == pytest.approx(2.0)
        page.get_by_role("button", name="Run", exact=True).wait_for()
        assert shown_time(page) == pytest.approx(2.0)

        # the layout: nothing scrolls sideways, the view and the position graph inside the window,
        # every text large, legends outside the graphs, tick labels plain and on one line
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
        paused = shown_time(page)

        # the 3-D canvas and the position graph are drawn (one screenshot: they are slow)
        picture = SCREENSHOTS / f"{scene}.png"
        page.screenshot(path=str(picture), full_page=True)
        canvas = page.locator(".glowscript-canvas-wrapper canvas").first.bounding_box()
        boxes = graph_boxes(page)
        assert len(boxes) == graph_count(scene)
        assert_not_blank(crop(picture, canvas), "3-D canvas")
        assert curve_pixels(crop(picture, boxes[own_graph])) > 50, "the position graph shows no curve"
        if scene == "resonance":
            check_resonance_graph(crop(picture, boxes[0]))
        assert shown_time(page) == paused     # still paused, through a screenshot's frames

        # Step advances one Δt, and the page stays paused
        page.get_by_role("button", name="Step", exact=True).click()
        stepped = wait_for(lambda: (t := shown_time(page)) != paused and t, what="Step to show")
        assert stepped - paused == pytest.approx(dt, abs=0.6 * 10 ** -decimals)
        assert page.get_by_role("button", name="Run", exact=True).count() == 1 and shown_time(page) == stepped

        # Reset returns to 0
        page.get_by_role("button", name="Reset", exact=True).click()
        wait_for(lambda: shown_time(page) == 0.0, what="Reset to show t = 0")
        assert page.locator("b").filter(has_text=f"t = {0:.{decimals}f} s").count() == 1

        # Run: t advances (the next frame); then the keys do the same with real key presses;
        # projector mode (key P)
        page.get_by_role("button", name="Run", exact=True).click()
        page.get_by_role("button", name="Pause", exact=True).wait_for()
        wait_for(lambda: shown_time(page) > 0.0, what="t to advance after Run")
        keys_work(page, scene)
        projector_mode(page)

        # at 1024 × 768 nothing scrolls sideways either
        page.set_viewport_size({"width": 1024, "height": 768})
        m = wait_for(lambda: (m := page.evaluate(MEASURE)) and m["canvas"]["width"] < 600 and m,
                     what="the page to follow the window")
        assert m["scrollWidth"] <= 1024, f"at 1024 px the page scrolls sideways ({m['scrollWidth']} px)"

        # closing the page ends the program with status 0, on its own (ENDS_WITHIN)
        page.close()
        page = None
        closed = time.monotonic()
        try:
            status = program.process.wait(timeout=ENDS_WITHIN)
        except subprocess.TimeoutExpired:
            pytest.fail(f"the program was still running {ENDS_WITHIN:g} s after its page closed")
        assert status == 0, "".join(program.errors)[-2000:]
        assert time.monotonic() - closed <= ENDS_WITHIN
        assert "Traceback" not in "".join(program.errors)
    finally:
        if page is not None:
            page.close()
        program.stop()


def check_resonance_graph(image):
    """The resonance graph draws each b's exact curve and measured dots in that b's colour (three b),
    and the row's live dots in orange."""
    from export.palette import CURVE_COLOURS, LIVE_COLOUR

    values = catalog.configure("resonance").values
    assert values["curves"] == 3
    for colour in CURVE_COLOURS[:3] + [LIVE_COLOUR]:
        rgb = tuple(round(255 * c) for c in colour)
        assert pixels_like(image, rgb) > 150, f"the resonance graph has no curve in colour {rgb}"


def test_preset_menu_scene_menu_and_csv_download(browser):
    program = Program("pendulum")
    page = None
    try:
        url = program.url()
        page = browser.new_page(viewport={"width": 1024, "height": 768}, accept_downloads=True)
        page.goto(url)
        assert jump_to(page, 1.0) == pytest.approx(1.0)      # paused there
        page.get_by_role("button", name="Run", exact=True).wait_for()
        assert shown_time(page) >= 1.0
        assert "g = 9.8 m/s²" in caption_lines(page)

        # A preset: the caption and the g slider show 1.62 m/s², and the run is back at t = 0
        # (still paused, so it stays there).
        menu(page, "Moon gravity").select_option("Moon gravity")
        wait_for(lambda: "g = 1.62 m/s²" in caption_lines(page), what="the g slider to show 1.62 m/s²")
        constants = next(line for line in caption_lines(page) if line.startswith("Constants:"))
        assert "g = 1.62 m/s²" in constants and "g = 9.8" not in constants
        assert shown_time(page) == 0.0
        g_handle = page.locator(".ui-slider-handle").nth(2)       # sliders m, k, g, b
        low, high, _ = slider_range("g", 1.62, 9.8)
        left = float(g_handle.evaluate("handle => handle.style.left").rstrip("%"))
        assert left == pytest.approx(100 * (1.62 - low) / (high - low), abs=1.0)
        assert menu(page, "Moon gravity").input_value() == "Moon gravity"

        # The scene menu: the driven scene replaces the pendulum, in the same page and program.
        menu(page, "resonance").select_option("driven")
        page.locator("b", has_text=re.compile(r"^driven$")).wait_for()
        wait_for(lambda: menu(page, "scenario 3").count() == 1, what="the driven scene's presets")
        assert program.process.poll() is None
        assert len(graph_boxes(page)) == 2   # the pendulum's graphs are gone, the driven ones made
        menu(page, "scenario 3").select_option(label=next(
            label for label, _ in catalog.presets(catalog.load("driven")) if label.startswith("scenario 3")))
        wait_for(lambda: "b = 2 kg/s" in caption_lines(page), what="a b slider showing 2 kg/s")
        assert shown_time(page) == 0.0
        page.get_by_role("button", name="Run", exact=True).click()
        wait_for(lambda: shown_time(page) > 0.0, what="the driven run to go")
        paused = jump_to(page, 2.0)                              # and paused there
        page.get_by_role("button", name="Run", exact=True).wait_for()
        assert shown_time(page) == pytest.approx(paused)

        picture = SCREENSHOTS / "menus.png"
        page.screenshot(path=str(picture), full_page=True)
        canvas = page.locator(".glowscript-canvas-wrapper canvas").first.bounding_box()
        assert_not_blank(crop(picture, canvas), "3-D canvas after switching scene")
        assert curve_pixels(crop(picture, graph_boxes(page)[0])) > 50, "no curve after switching scene"

        # Download CSV: the graphed samples, with the command line's columns.
        with page.expect_download() as download:
            page.get_by_role("button", name="Download CSV", exact=True).click()
        assert download.value.suggested_filename == "driven.csv"
        with open(download.value.path(), newline="") as handle:
            rows = list(csv.reader(handle))
        assert rows[0] == ["t", "x", "y", "z", "vx", "vy", "vz", "px", "py", "pz", "K", "U", "E", "W_nc"]
        data = [[float(x) for x in row] for row in rows[1:]]
        assert len(data) >= 2.0 / 0.05
        t = [row[0] for row in data]
        assert t[0] == 0.0 and t[-1] == pytest.approx(paused, abs=1e-9)
        assert all(b - a == pytest.approx(0.05, abs=1e-9) for a, b in zip(t, t[1:]))
        driven = catalog.configure("driven", scenario=3).values
        m, L0, x0 = driven["m"], driven["L0"], driven["x0"]
        assert data[0][1:4] == [L0 + x0, 0.0, 0.0] and data[0][4:7] == [0.0, 0.0, 0.0]
        for row in data:
            vx, px, K, U, E = row[4], row[7], row[10], row[11], row[12]
            assert vx == pytest.approx(px / m, rel=1e-12, abs=1e-15)   # v = p/m
            assert K == pytest.approx(0.5 * m * vx**2, rel=1e-9, abs=1e-12)
            assert E == pytest.approx(K + U, rel=1e-9, abs=1e-12)
        assert "Traceback" not in "".join(program.errors)
    finally:
        if page is not None:
            page.close()
        program.stop()

"""Every scene in a real browser: headless Chromium driven by Playwright.

For each scene whose VIEW the shared view can draw, `python main.py SCENE --no-browser --port P` is
started, its printed URL opened, and the page checked: the 3-D canvas is not blank, the position
graph has a curve, t advances, Pause stops it, Step advances it by one Δt, Reset returns it to 0,
and closing the page ends the program with status 0 within 2 s. A screenshot of each scene is saved
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

from browser_support import (ENDS_WITHIN, TIME, colours, curve_pixels, free_port, launched, pixels_like,
                             require_browser, screenshot_folder, wait_for)
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


@pytest.fixture(scope="module")
def browser():
    with launched(sync_api) as chromium:
        yield chromium


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


@pytest.mark.parametrize("scene", drawable_scenes())
def test_scene_in_the_browser(browser, scene):
    dt = catalog.configure(scene).build().dt
    decimals = time_decimals(dt)
    program = Program(scene)
    page = None
    try:
        url = program.url()
        page = browser.new_page(viewport={"width": 1280, "height": 1100})
        page.goto(url)

        # t advances
        start = shown_time(page)
        wait_for(lambda: shown_time(page) > start + 0.5, timeout=60.0, what="t to advance")

        # Pause stops it
        wait_for(lambda: shown_time(page) >= 2.0, timeout=60.0, what="t to reach 2 s")
        page.get_by_role("button", name="Pause").click()
        page.get_by_role("button", name="Run").wait_for()
        paused = shown_time(page)

        # the 3-D canvas and the position graph are drawn (one screenshot: they are slow)
        picture = SCREENSHOTS / f"{scene}.png"
        page.screenshot(path=str(picture), full_page=True)
        canvas = page.locator(".glowscript-canvas-wrapper canvas").first.bounding_box()
        own_graph = hasattr(catalog.load(scene), "view_graph")
        boxes = graph_boxes(page)
        assert len(boxes) == graph_count(scene)
        assert_not_blank(crop(picture, canvas), "3-D canvas")
        assert curve_pixels(crop(picture, boxes[own_graph])) > 50, "the position graph shows no curve"
        if scene == "resonance":
            check_resonance_graph(crop(picture, boxes[0]))

        time.sleep(1.0)
        assert shown_time(page) == paused

        # Step advances one Δt
        page.get_by_role("button", name="Step").click()
        stepped = wait_for(lambda: (t := shown_time(page)) != paused and t, what="Step to show")
        assert stepped - paused == pytest.approx(dt, abs=0.6 * 10 ** -decimals)
        time.sleep(0.5)
        assert shown_time(page) == stepped  # still paused

        # Reset returns to 0
        page.get_by_role("button", name="Reset").click()
        wait_for(lambda: shown_time(page) == 0.0, what="Reset to show t = 0")
        assert page.locator("b").filter(has_text=f"t = {0:.{decimals}f} s").count() == 1

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
        page = browser.new_page(viewport={"width": 1280, "height": 1100}, accept_downloads=True)
        page.goto(url)
        wait_for(lambda: shown_time(page) >= 1.0, timeout=60.0, what="t to reach 1 s")
        page.get_by_role("button", name="Pause").click()
        page.get_by_role("button", name="Run").wait_for()
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
        page.get_by_role("button", name="Run").click()
        wait_for(lambda: shown_time(page) >= 2.0, timeout=60.0, what="t to reach 2 s")
        page.get_by_role("button", name="Pause").click()
        page.get_by_role("button", name="Run").wait_for()
        paused = shown_time(page)

        picture = SCREENSHOTS / "menus.png"
        page.screenshot(path=str(picture), full_page=True)
        canvas = page.locator(".glowscript-canvas-wrapper canvas").first.bounding_box()
        assert_not_blank(crop(picture, canvas), "3-D canvas after switching scene")
        assert curve_pixels(crop(picture, graph_boxes(page)[0])) > 50, "no curve after switching scene"

        # Download CSV: the graphed samples, with the command line's columns.
        with page.expect_download() as download:
            page.get_by_role("button", name="Download CSV").click()
        assert download.value.suggested_filename == "driven.csv"
        with open(download.value.path(), newline="") as handle:
            rows = list(csv.reader(handle))
        assert rows[0] == ["t", "x", "y", "z", "vx", "vy", "vz", "px", "py", "pz", "K", "U", "E", "W_nc"]
        data = [[float(x) for x in row] for row in rows[1:]]
        assert len(data) >= 2.0 / 0.05
        t = [row[0] for row in data]
        assert t[0] == 0.0 and t[-1] == pytest.approx(paused, abs=0.06)
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

"""Every scene in a real browser: headless Chromium driven by Playwright.

For each scene whose VIEW the shared view can draw, `python main.py SCENE --no-browser --port P` is
started, its printed URL opened, and the page checked: the 3-D canvas is not blank, the position
graph has a curve, t advances, Pause stops it, Step advances it by one Δt, Reset returns it to 0,
and closing the page ends the program with status 0 within 2 s. A screenshot of each scene is saved
to docs/screenshots/SCENE.png.

Skipped, with the reason, where Chromium or Playwright is missing (.ci/run installs both).
"""
from __future__ import annotations

import math
import os
import queue
import re
import socket
import subprocess
import sys
import threading
import time
from collections import Counter
from pathlib import Path

import pytest

from scenes import catalog
from scenes.view import time_decimals

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = "/usr/bin/chromium"
SCREENSHOTS = ROOT / "docs" / "screenshots"
CHROMIUM_ARGS = ["--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader",
                 "--enable-unsafe-swiftshader", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run"]
TIME = re.compile(r"^\s*t = (-?\d+\.\d+) s\s*$")

pytestmark = pytest.mark.browser
if not os.path.exists(CHROMIUM):
    pytest.skip(f"Chromium is not installed at {CHROMIUM} (apt-get install chromium)",
                allow_module_level=True)
sync_api = pytest.importorskip("playwright.sync_api",
                               reason="Playwright for Python is not installed (pip install playwright)")
Image = pytest.importorskip("PIL.Image", reason="Pillow is needed to inspect screenshots")


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
    with sync_api.sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        try:
            yield chromium
        finally:
            chromium.close()


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


class Program:
    """`python main.py SCENE --no-browser --port P`, its output read on a thread, always killed."""

    def __init__(self, scene: str):
        self.port = free_port()
        self.process = subprocess.Popen(
            [sys.executable, str(ROOT / "main.py"), scene, "--no-browser", "--port", str(self.port)],
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


def shown_time(page) -> float:
    """The t the caption shows, read from the page's text (`t = 12.34 s`)."""
    text = page.locator("b").filter(has_text=TIME).first.inner_text(timeout=30_000)
    return float(TIME.match(text).group(1))


def wait_for(predicate, *, timeout: float = 30.0, what: str):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.05)
    pytest.fail(f"timed out waiting for {what}")


def crop(path: Path, box: dict):
    """The part of a full-page screenshot inside an element's bounding box."""
    left, top = round(box["x"]), round(box["y"])
    return Image.open(path).convert("RGB").crop((left, top, left + round(box["width"]),
                                                 top + round(box["height"])))


def colours(image) -> Counter:
    """How many pixels of each (r, g, b) colour the image has."""
    return Counter(dict((rgb, n) for n, rgb in image.getcolors(maxcolors=1 << 24)))


def assert_not_blank(image, what: str):
    counts = colours(image)
    background = max(counts, key=counts.get)
    others = sum(n for rgb, n in counts.items() if sum(abs(a - b) for a, b in zip(rgb, background)) > 60)
    assert len(counts) > 50 and others > 0.01 * counts.total(), \
        f"{what} looks blank ({len(counts)} colours, {others} pixels unlike the background)"


def curve_pixels(image) -> int:
    """Strongly coloured pixels in the left 40 % of a graph, where the curves start.

    Grid lines and text are grey or black, and the legend sits at the top right, so these pixels
    can only be drawn curves.
    """
    image = image.crop((0, 0, int(0.4 * image.width), image.height))
    return sum(n for rgb, n in colours(image).items() if max(rgb) - min(rgb) > 80)


@pytest.mark.parametrize("scene", drawable_scenes())
def test_scene_in_the_browser(browser, scene):
    dt = catalog.configure(scene).build().dt
    decimals = time_decimals(dt)
    program = Program(scene)
    page = None
    try:
        url = program.url()
        page = browser.new_page(viewport={"width": 1280, "height": 1100})
        page.goto(url, timeout=30_000)

        # t advances
        start = shown_time(page)
        wait_for(lambda: shown_time(page) > start + 0.5, timeout=60.0, what="t to advance")

        # Pause stops it
        wait_for(lambda: shown_time(page) >= 2.0, timeout=60.0, what="t to reach 2 s")
        page.get_by_role("button", name="Pause").click()
        page.get_by_role("button", name="Run").wait_for(timeout=30_000)
        paused = shown_time(page)

        # the 3-D canvas and the position graph are drawn (one screenshot: they are slow)
        SCREENSHOTS.mkdir(parents=True, exist_ok=True)
        picture = SCREENSHOTS / f"{scene}.png"
        page.screenshot(path=str(picture), full_page=True)
        canvas = page.locator(".glowscript-canvas-wrapper canvas").first.bounding_box()
        graph = page.locator("#graph0 canvas.base").bounding_box()
        assert_not_blank(crop(picture, canvas), "3-D canvas")
        assert curve_pixels(crop(picture, graph)) > 50, "the position graph shows no curve"

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

        # closing the page ends the program with status 0 within 2 s
        page.close()
        page = None
        closed = time.monotonic()
        try:
            status = program.process.wait(timeout=2.0)
        except subprocess.TimeoutExpired:
            pytest.fail("the program was still running 2 s after its page closed")
        assert status == 0, "".join(program.errors)[-2000:]
        assert time.monotonic() - closed <= 2.0
        assert "Traceback" not in "".join(program.errors)
    finally:
        if page is not None:
            page.close()
        program.stop()

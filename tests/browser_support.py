"""What the real-browser tests share: how Chromium is launched, waiting, and reading screenshots.

tests/test_browser.py (each scene's page) and tests/test_notebook.py (the scenes in a Jupyter
notebook) both drive Debian's Chromium through Playwright and judge screenshots by their colours.
"""
from __future__ import annotations

import contextlib
import os
import re
import socket
import tempfile
import time
from collections import Counter
from pathlib import Path

import pytest

CHROMIUM = "/usr/bin/chromium"
# SwiftShader's software WebGL: with plain --disable-gpu the 3-D canvas renders blank.
CHROMIUM_ARGS = ["--no-sandbox", "--use-gl=angle", "--use-angle=swiftshader",
                 "--enable-unsafe-swiftshader", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run"]
TIME = re.compile(r"^\s*t = (-?\d+\.\d+) s\s*$")   # the caption's `t = 12.34 s`
# Playwright's own default, 30 s for a click, a screenshot or a page load, is exceeded on a busy
# 2-core machine running the whole suite (software WebGL makes each screenshot take seconds). Each
# of those waits for an event, so a generous limit costs nothing when the machine is quick.
PATIENCE_MS = 120_000
# After its page closes, the program ends on its own: CLOSE_GRACE (0.5 s), then its own exit, about
# 1 s on an idle machine but 2-4 s on a busy one (the README says "a second or two"). A wall-time
# bound of 2 s failed under load, so the tests bound it by what they guard against: that the
# program does not wait for a reload (RELOAD_WAIT, 20 s), nor forever.
ENDS_WITHIN = 10.0  # s


def require_browser():
    """Skip the calling test module, with the reason, unless Chromium, Playwright and Pillow are
    here; returns (playwright.sync_api, PIL.Image). Call it at module level."""
    if not os.path.exists(CHROMIUM):
        pytest.skip(f"Chromium is not installed at {CHROMIUM} (apt-get install chromium)",
                    allow_module_level=True)
    sync_api = pytest.importorskip("playwright.sync_api",
                                   reason="Playwright for Python is not installed (pip install playwright)")
    image = pytest.importorskip("PIL.Image", reason="Pillow is needed to inspect screenshots")
    return sync_api, image


_driver = None   # the run's one Playwright driver: Playwright's sync API cannot start a second beside it


def _playwright(sync_api):
    """The one Playwright driver of this run, started on first use and stopped by stop_all()."""
    global _driver
    if _driver is None:
        _driver = sync_api.sync_playwright().start()
    return _driver


def launch(sync_api, *extra_args, scrollbars: bool = False):
    """A new headless Chromium with the arguments that make its 3-D canvas draw; the caller closes it.

    scrollbars  draw scrollbars that take room, as a desktop browser does (Playwright hides them
                by default, and so hid that the page scrolled sideways at 1280 × 800)
    """
    hidden = ["--hide-scrollbars"] if scrollbars else []
    return patient(_playwright(sync_api).chromium.launch(executable_path=CHROMIUM,
                                                         args=CHROMIUM_ARGS + list(extra_args),
                                                         ignore_default_args=hidden))


def stop_all():
    """Stop the run's Playwright driver (conftest calls this as the run ends)."""
    global _driver
    if _driver is not None:
        driver, _driver = _driver, None
        driver.stop()


@contextlib.contextmanager
def launched(sync_api, *extra_args, scrollbars: bool = False):
    """A Chromium of its own (see launch), closed afterwards: conftest's `browser` for each module, or a module's own with other arguments."""
    chromium = launch(sync_api, *extra_args, scrollbars=scrollbars)
    try:
        yield chromium
    finally:
        chromium.close()


def patient(chromium):
    """The browser, whose new pages and contexts wait up to PATIENCE_MS for each event by default."""
    new_page, new_context = chromium.new_page, chromium.new_context

    def patient_page(*args, **kwargs):
        page = new_page(*args, **kwargs)
        page.set_default_timeout(PATIENCE_MS)
        page.set_default_navigation_timeout(PATIENCE_MS)
        return page

    def patient_context(*args, **kwargs):
        context = new_context(*args, **kwargs)
        context.set_default_timeout(PATIENCE_MS)
        context.set_default_navigation_timeout(PATIENCE_MS)
        return context

    chromium.new_page, chromium.new_context = patient_page, patient_context
    return chromium


def screenshot_folder() -> Path:
    """Where the browser tests save their screenshots: a folder in /tmp, or, with
    UPDATE_SCREENSHOTS=1, the tracked docs/screenshots/ (regenerated only on request, so a test run
    leaves `git status` clean)."""
    if os.environ.get("UPDATE_SCREENSHOTS") == "1":
        folder = Path(__file__).resolve().parent.parent / "docs" / "screenshots"
    else:
        folder = Path(tempfile.gettempdir()) / "spring-mass-screenshots"
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def wait_for(predicate, *, timeout: float = 30.0, what: str):
    """Poll predicate() until it returns something true, and return that; fail after `timeout` s."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.05)
    pytest.fail(f"timed out waiting for {what}")


# ---- Jump to t (browser/jump.py, export/offline_page.js): a test asks for the simulated time it needs ----

# The local page's Jump box is vpython's text box, which sends its text when the focus leaves it:
# the box is filled and left, then Jump pressed, in one go (in that order the page's events reach
# the program); what the page says after the jump carries its count, so the wait is for this jump.
_LOCAL_JUMP = """t => { const box = document.getElementById('sm-jump-t');
  const mark = document.querySelector('.sm-jumped');
  const before = Number(mark.dataset.jumps);
  box.value = t; box.dispatchEvent(new Event('blur'));
  for (const b of document.querySelectorAll('button')) if (b.textContent.trim() === 'Jump') { b.click(); break; }
  return before; }"""


def jump_to(page, t: float) -> float:
    """Jump the local page to t, s, and wait until it shows it, paused (the page says so last,
    after the state, graphs and caption it drew). Returns the t reached: the first step at or
    after t, as --headless reaches a time."""
    page.locator("#sm-jump-t").wait_for(state="attached")
    before = page.evaluate(_LOCAL_JUMP, repr(float(t)))
    mark = page.locator(f".sm-jumped[data-jumps='{before + 1}']")
    mark.wait_for(state="attached")
    return float(mark.get_attribute("data-t"))


def jump_offline(page, t: float) -> dict:
    """Jump the offline page to t, s, and wait until the program is there, paused, and the page
    has drawn it; returns window.offlineState() (n: the step reached, the first at or after t)."""
    page.wait_for_function("() => window.offlineState !== undefined")
    before = page.evaluate("""t => { const done = window.offlineState().jumps;
        document.getElementById('jump-t').value = t; document.getElementById('jump').click(); return done; }""",
                           repr(float(t)))
    page.wait_for_function("n => window.offlineState().jumpsDrawn > n", arg=before)
    return page.evaluate("window.offlineState()")


def colours(image) -> Counter:
    """How many pixels of each (r, g, b) colour the image has."""
    return Counter(dict((rgb, n) for n, rgb in image.getcolors(maxcolors=1 << 24)))


def pixels_like(image, rgb, *, within: int = 40) -> int:
    """How many pixels are within `within` (summed over r, g, b) of the colour rgb."""
    return sum(n for colour, n in colours(image).items()
               if sum(abs(a - b) for a, b in zip(colour, rgb)) <= within)


def curve_pixels(image) -> int:
    """Strongly coloured pixels in the left 40 % of a graph, where the curves start.

    Grid lines and text are grey or black, and the legend sits at the top right, so these pixels
    can only be drawn curves.
    """
    image = image.crop((0, 0, int(0.4 * image.width), image.height))
    return sum(n for rgb, n in colours(image).items() if max(rgb) - min(rgb) > 80)


def shaded_like(image, colour) -> int:
    """Pixels of `colour` (r, g, b from 0 to 1) lit or shaded, or seen through on black (a mass
    drawn see-through under its arrows): a multiple of it from a third to all of its brightness."""
    import numpy as np
    target = np.array(colour, dtype=float) * 255
    count = 0
    for n, rgb in image.getcolors(maxcolors=1 << 24):
        pixel = np.array(rgb[:3], dtype=float)
        scale = pixel @ target / (target @ target)
        if 0.3 <= scale <= 1.1 and np.abs(pixel - scale * target).sum() <= 40:
            count += n
    return count

"""Issue 28, item 7: the page in every window a class uses, in headless Chromium (Playwright).

Each check runs at 1024 × 768, 1280 × 800 and 1920 × 1080, and in projector mode at each, in a
Chromium whose scrollbars take room as a desktop browser's do (Playwright hides them by default,
which hid the first item):

* no scene scrolls sideways (it did by 14-28 px at 1280 × 800: the graphs' last time tick stuck
  out of the window), and every graph's tick labels are inside the window;
* the check boxes grow with the text: at least 18 px, and 22 px in projector mode (they stayed 16);
* nothing is drawn outside a graph's frame (resonance's position graph kept small blue marks above
  its frame from t ≈ 16 s: half the width of a thick curve that once touched the frame);
* the pendulum's ball stands out of its trail (the trail was in the ball's own colour);
* resizing the window keeps the curves of graphs that get no new points (a paused page's graphs
  went blank).

The fifth, a teacher's folder whose files are missing from the scene menu, is in
tests/test_teacher_folder_browser.py. Screenshots go to the screenshot folder
(tests/browser_support.py). Each page is jumped to the t it needs; every wait is for the page's
own layout, never a fixed time.
"""
from __future__ import annotations

import base64
import io

import numpy as np
import pytest

from browser.page_layout import BODY_PX, PROJECTOR_PX
from browser_support import jump_to, launched, require_browser, screenshot_folder, wait_for
from test_browser import Program, drawable_scenes, graph_count, shown_time

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()
SCREENSHOTS = screenshot_folder()
SIZES = ((1024, 768), (1280, 800), (1920, 1080))

# What a window shows: how far the page scrolls sideways when asked to scroll right, where the
# text of the graphs' tick labels ends, the check boxes' sizes, and the graphs' widths.
WINDOW = """() => {
  const y = window.scrollY;
  window.scrollTo(100000, y);
  const sideways = window.scrollX;
  window.scrollTo(0, y);
  const text = e => { const r = document.createRange(); r.selectNodeContents(e); return r.getBoundingClientRect(); };
  const ticks = Array.from(document.querySelectorAll('.glowscript-graph .tickLabel')).filter(e => e.offsetParent !== null);
  const boxes = Array.from(document.querySelectorAll('input[type=checkbox]')).filter(e => e.offsetParent !== null);
  return {sideways: sideways, client: document.documentElement.clientWidth, projector: !!window.smProjector,
          tickRight: Math.max(0, ...ticks.map(e => text(e).right)),
          boxes: boxes.map(e => Math.min(e.getBoundingClientRect().width, e.getBoundingClientRect().height)),
          graphWidths: Array.from(document.querySelectorAll('.glowscript-graph canvas.base')).map(c => c.getBoundingClientRect().width)};
}"""

# Each graph's drawing (its base canvas) and the frame flot plots in, in canvas pixels.
GRAPH_PICTURES = """() => glowObjs.filter(o => o && o.graph_options && o.__plot && !o.__deleted).map(g => {
  const p = g.__plot, o = p.getPlotOffset(), c = p.getCanvas(), ratio = c.width / p.getPlaceholder().width();
  return {title: g.title, png: c.toDataURL(), ratio: ratio,
          frame: [o.left, o.top, o.left + p.width(), o.top + p.height()]};
})"""


@pytest.fixture(scope="module")
def browser():
    with launched(sync_api, scrollbars=True) as chromium:
        yield chromium


def set_projector(page, on: bool, height: int) -> None:
    """Projector mode on or off with its key, P, the focus on the page."""
    if page.evaluate("() => !!window.smProjector") != on:
        page.evaluate("() => document.activeElement && document.activeElement.blur()")   # keys to the page
        page.keyboard.press("p")
        wait_for(lambda: page.evaluate("() => !!window.smProjector") == on, what="projector mode")


def each_window(page):
    """Every size and mode the page must work in: yields (width, height, projector) once the page
    is in it."""
    for width, height in SIZES:
        page.set_viewport_size({"width": width, "height": height})
        for projector in (False, True):
            set_projector(page, projector, height)
            yield width, height, projector


def laid_out(page, width: int) -> dict:
    """The window's measurements once the layout has followed a new size (the graphs' widths change
    with it) and flot has redrawn the ticks."""
    def settled():
        shown = page.evaluate(WINDOW)
        return shown if shown["graphWidths"] and all(w < shown["client"] for w in shown["graphWidths"]) else None
    return wait_for(settled, what=f"the page laid out at {width} px")


def picture(data_url: str):
    return Image.open(io.BytesIO(base64.b64decode(data_url.split(",", 1)[1]))).convert("RGB")


def opened(browser, scene: str, *, until: float, size=(1024, 768)):
    """The scene's page, jumped to `until` (paused there), with every graph made; each test then
    takes it through every window size (SIZES)."""
    program = Program(scene)
    page = browser.new_page(viewport={"width": size[0], "height": size[1]})
    page.goto(program.url())
    jump_to(page, until)
    wait_for(lambda: page.locator(".glowscript-graph canvas.base").count() == graph_count(scene),
             what="every graph on the page")
    return program, page


@pytest.mark.parametrize("scene", drawable_scenes())
def test_no_window_scrolls_sideways_and_the_check_boxes_grow_with_the_text(browser, scene):
    program, page = opened(browser, scene, until=1.0)
    try:
        for width, height, projector in each_window(page):
            def fits():
                shown = laid_out(page, width)
                return shown if shown["sideways"] == 0 and shown["tickRight"] <= shown["client"] else None
            shown = wait_for(fits, what=f"{scene} at {width} × {height}{' in projector mode' if projector else ''} "
                                  f"to fit the window: {page.evaluate(WINDOW)}")
            smallest = PROJECTOR_PX if projector else BODY_PX
            assert shown["boxes"] and min(shown["boxes"]) >= smallest, \
                f"check boxes of {min(shown['boxes'])} px at {width} × {height}, projector {projector}"
            if (width, projector) == (1280, True):
                page.screenshot(path=str(SCREENSHOTS / f"window-{scene}-{width}x{height}-projector.png"))
        assert "Traceback" not in "".join(program.errors)
    finally:
        page.close()
        program.stop()


def coloured_pixels(image) -> np.ndarray:
    """Which pixels are strongly coloured (curves; grid lines and text are grey or black), (h, w) bool."""
    rgb = np.asarray(image, dtype=int)
    return rgb.max(axis=-1) - rgb.min(axis=-1) > 80


def outside_the_frame(graph) -> int:
    """Strongly coloured pixels of a graph's drawing outside its frame (beyond the frame's line)."""
    image = picture(graph["png"])
    ratio = graph["ratio"]
    left, top, right, bottom = (round(ratio * edge) for edge in graph["frame"])
    edge = round(4 * ratio)
    outside = coloured_pixels(image)
    outside[max(0, top - edge):bottom + edge + 1, max(0, left - edge):right + edge + 1] = False
    return int(outside.sum())


def test_nothing_is_drawn_outside_a_graphs_frame(browser):
    """Resonance's thick curves, after their axis has widened to the growing swing (t ≥ 20 s)."""
    program, page = opened(browser, "resonance", until=20.0)
    try:
        for width, height, projector in each_window(page):
            laid_out(page, width)
            now = shown_time(page)
            page.get_by_role("button", name="Step", exact=True).click()      # a new point: the graphs redrawn since
            wait_for(lambda: shown_time(page) > now, what="a Step")
            for graph in page.evaluate(GRAPH_PICTURES):
                assert outside_the_frame(graph) == 0, \
                    f"{graph['title']!r} has marks outside its frame at {width} × {height}, projector {projector}"
        page.screenshot(path=str(SCREENSHOTS / "window-resonance-frames.png"))
    finally:
        page.close()
        program.stop()


# The ball's place on the canvas, from the page's own objects: its centre and radius in canvas
# pixels (the camera looks along −z with a long lens: fov 0.2 rad, so x and y scale alike).
BALL = """() => {
  const canvas = glowObjs.find(o => o && o.__canvas_element), ball = glowObjs.find(o => o && o.constructor && o.constructor.name === 'sphere' && o.visible);
  const box = canvas.__canvas_element.getBoundingClientRect(), scale = 0.5 * box.height / canvas.range;
  return {x: box.left + box.width / 2 + (ball.pos.x - canvas.center.x) * scale,
          y: box.top + box.height / 2 - (ball.pos.y - canvas.center.y) * scale,
          r: ball.radius * scale, canvas: [box.left, box.top, box.right, box.bottom]};
}"""


def test_the_pendulums_ball_stands_out_of_its_trail(browser):
    program, page = opened(browser, "pendulum", until=12.0)     # paused there
    try:
        for width, height, projector in each_window(page):
            laid_out(page, width)
            path = SCREENSHOTS / f"window-pendulum-{width}x{height}{'-projector' if projector else ''}.png"
            page.screenshot(path=str(path))
            ball = page.evaluate(BALL)
            left, top, right, bottom = (round(edge) for edge in ball["canvas"])
            rgb = np.asarray(Image.open(path).convert("RGB"), dtype=int)[max(top, 0):bottom, max(left, 0):right]
            r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
            like = (r >= 70) & (r - g >= 30) & (g - b >= 25)     # orange, lit or mixed with the dark background
            y, x = np.mgrid[max(top, 0):max(top, 0) + rgb.shape[0], max(left, 0):max(left, 0) + rgb.shape[1]]
            close = (x - ball["x"]) ** 2 + (y - ball["y"]) ** 2 <= (1.6 * ball["r"] + 3) ** 2
            near, elsewhere = int((like & close).sum()), int((like & ~close).sum())
            disc = 3.14159 * ball["r"] ** 2
            assert near > 0.1 * disc, f"the ball does not show ({near} px of about {disc:.0f})"   # arrows cross it
            assert elsewhere <= 0.1 * disc, \
                f"{elsewhere} px look like the ball away from it (its trail) at {width} × {height}, projector {projector}"
    finally:
        page.close()
        program.stop()


def curve_drawn(graph) -> bool:
    """Strongly coloured pixels inside the frame: a curve is drawn."""
    image = picture(graph["png"])
    ratio = graph["ratio"]
    left, top, right, bottom = (round(ratio * edge) for edge in graph["frame"])
    return int(coloured_pixels(image.crop((left + 3, top + 3, right - 3, bottom - 3))).sum()) > 100


def test_resizing_the_window_keeps_the_curves_of_a_paused_page(browser):
    program, page = opened(browser, "damped", until=3.0)        # paused there
    try:
        page.get_by_role("button", name="Run", exact=True).wait_for()
        paused = shown_time(page)
        for width, height, projector in each_window(page):
            laid_out(page, width)
            wait_for(lambda: all(curve_drawn(graph) for graph in page.evaluate(GRAPH_PICTURES)),
                     what=f"every graph's curves at {width} × {height}, projector {projector}")
        assert shown_time(page) == paused          # no new points came: the page stayed paused
        page.screenshot(path=str(SCREENSHOTS / "window-paused-resized.png"))
    finally:
        page.close()
        program.stop()

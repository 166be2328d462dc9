"""Every label of the 3-D view is wholly inside its canvas, at every window size a class uses.

The labels have a fixed text size (18 px) while the canvas follows the window (538 × 263 px at
1024 × 768): regimes' middle label was cut at the canvas's bottom there, and drag's quadratic label
ran off its right edge. Each label's box is read as vpython draws it: the rectangle its own
drawing code fills behind the text, through the 2-D context's transform, in canvas pixels.

Scenes with labels: integrators (methods, and euler's "ran away" label), regimes, drag (also its
"falling, no spring" preset, where the camera follows the balls) and resonance (rows and ω).
Skipped, with the reason, where Chromium or Playwright is missing.
"""
from __future__ import annotations

import pytest

from browser.mass_labels import mass_labels
from browser_support import jump_to, wait_for
from scenes import catalog
from scenes._view import DEFAULT_VIEW
from test_browser import Program

pytestmark = pytest.mark.browser

SIZES = [(1024, 768), (1280, 800), (1920, 1080)]
SUBPIXEL = 0.01   # px: a box computed in floating point may end a hair past an edge it touches

# Wraps vpython's label drawing once, so that each label keeps the box its drawing filled, where the
# context's transform put it, and the canvas size it was drawn for; asks for a redraw of the labels.
MEASURE_LABELS = """() => {
  const labels = glowObjs.filter(o => o && !o.__deleted && o.constructor && o.constructor.name === 'label');
  if (!labels.length) return [];
  const proto = Object.getPrototypeOf(labels[0]);
  if (!proto.__testMeasured) {
    proto.__testMeasured = true;
    const update = proto.__update;
    proto.__update = function (ctx, camera) {
      const me = this, fill = ctx.fillRect;
      ctx.fillRect = function (x, y, w, h) {
        const m = ctx.getTransform();
        me.__testBox = {x: m.a * x + m.e, y: m.d * y + m.f, width: m.a * w, height: m.d * h,
                        W: me.canvas.__width, H: me.canvas.__height, border: me.border};
        return fill.apply(this, arguments);
      };
      try { return update.call(this, ctx, camera); } finally { delete ctx.fillRect; }
    };
  }
  labels.forEach(l => { l.canvas.__overlay_objects.__changed = true; });
  return labels.filter(l => l.visible).map(l => ({text: l.text, box: l.__testBox || null}));
}"""

CANVAS = "() => { const c = document.querySelector('.glowscript-canvas-wrapper canvas'); return [c.width, c.height]; }"


def expected_labels(scene: str, *extra: str) -> int:
    setup = catalog.configure(scene)
    if extra:
        setup = setup.with_preset(extra[1])
    return len(mass_labels(setup.build(), {**DEFAULT_VIEW, **setup.module.VIEW}))


def drawn_labels(page, count: int):
    """The visible labels' boxes, each drawn for the canvas's size now (read from a redraw)."""
    def ready():
        width, height = page.evaluate(CANVAS)
        labels = page.evaluate(MEASURE_LABELS)
        fresh = [label for label in labels if label["box"] and label["box"]["W"] == width
                 and label["box"]["H"] == height]
        return len(labels) == count and len(fresh) == count and fresh
    return wait_for(ready, what=f"{count} labels drawn on the canvas at its size")


def overlap(a, b) -> bool:
    """Whether the texts of two label boxes overlap (each box has its border of empty space)."""
    a, b = text_box(a), text_box(b)
    return (a["x"] < b["x"] + b["width"] and b["x"] < a["x"] + a["width"]
            and a["y"] < b["y"] + b["height"] and b["y"] < a["y"] + a["height"])


def text_box(box):
    edge = box["border"]
    return {"x": box["x"] + edge, "y": box["y"] + edge, "width": box["width"] - 2 * edge,
            "height": box["height"] - 2 * edge}


@pytest.mark.parametrize("scene, extra", [("regimes", ()), ("drag", ()), ("integrators", ()), ("resonance", ()),
                                          ("drag", ("--preset", "falling, no spring"))],
                         ids=["regimes", "drag", "integrators", "resonance", "drag-falling"])
def test_every_mass_label_is_inside_the_canvas_at_every_window_size(browser, scene, extra):
    count = expected_labels(scene, *extra)
    assert count >= 2
    program = Program(scene, *extra)
    page = browser.new_page(viewport={"width": SIZES[0][0], "height": SIZES[0][1]})
    try:
        page.goto(program.url())
        jump_to(page, 8.0)
        for width, height in SIZES:
            page.set_viewport_size({"width": width, "height": height})
            labels = drawn_labels(page, count)
            for label in labels:
                box = label["box"]
                where = f"{scene} {' '.join(extra)} at {width}x{height}: {label['text']!r} at {box}"
                assert box["x"] >= -SUBPIXEL and box["y"] >= -SUBPIXEL, where
                assert box["x"] + box["width"] <= box["W"] + SUBPIXEL, where
                assert box["y"] + box["height"] <= box["H"] + SUBPIXEL, where
            for i, a in enumerate(labels):
                for b in labels[i + 1:]:
                    assert not overlap(a["box"], b["box"]), f"{a['text']!r} over {b['text']!r} at {width}x{height}"
        assert "Traceback" not in "".join(program.errors)
    finally:
        page.close()
        program.stop()

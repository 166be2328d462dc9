"""Graph tick labels are plain decimals, one line each, at any scale (issue 18, item 6).

vpython's own formatter wrote a small axis as `4e-2`, and the page broke it over two lines. Here
the page's real jQuery and flot (vpython's glow.min.js) draw axes from 10⁻⁶ to 10⁶ with
browser/axes.py's PLAIN_TICKS installed, and every label flot makes is read back.
"""
import math
import re
from pathlib import Path

import pytest

from browser.axes import PLAIN_TICKS, nice_range
from browser_support import require_browser

pytestmark = pytest.mark.browser
sync_api, _ = require_browser()

LIBRARIES = Path(pytest.importorskip("vpython").__file__).parent / "vpython_libraries"
PLAIN = re.compile(r"^-?\d+(\.\d+)?$")

DRAW = """([low, high, pixels]) => {
  const box = document.createElement("div");
  box.style.width = "400px"; box.style.height = pixels + "px";
  document.body.appendChild(box);
  // as vpython's graph does: its own formatter in the options, which the page's wrapper replaces
  const vpythonFormatter = (v) => (v * 100).toFixed(0) + "e-2";
  const plot = jQuery.plot(box, [[[0, low], [1, high]]],
                           {series: {shadowSize: 0}, crosshair: {mode: "xy", color: "rgba(0,0,0,1)"},
                            grid: {offsets: {left: 0, right: 0, top: 0, bottom: 0}},
                            xaxis: {min: 0, max: 1, tickFormatter: vpythonFormatter},
                            yaxis: {min: low, max: high, tickFormatter: vpythonFormatter}});
  const ticks = plot.getAxes().yaxis.ticks.map((t) => [t.v, t.label]);
  const size = plot.getAxes().yaxis.tickSize;
  box.remove();
  return [ticks, size];
}"""


@pytest.fixture(scope="module")
def page(browser):
    tab = browser.new_page(viewport={"width": 640, "height": 480})
    try:
        tab.set_content("<html><body></body></html>")
        for name in ("jquery.min.js", "glow.min.js"):
            tab.add_script_tag(path=str(LIBRARIES / name))
        tab.add_script_tag(content=PLAIN_TICKS.removeprefix("<script>").removesuffix("</script>"))
        assert tab.evaluate("typeof jQuery.plot.plainTicks") == "function"
        yield tab
    finally:
        tab.close()


def ranges():
    """Axis ends as the page's graphs choose them (round ticks), and raw ones, from 10⁻⁶ to 10⁶."""
    for exponent in range(-6, 7):
        scale = 10.0 ** exponent
        yield 0.0, 4.3 * scale                   # an amplitude: 0 to 4.3 × 10ⁿ
        yield -1.7 * scale, 2.9 * scale          # a swing about 0
        yield 1000 * scale, 1000 * scale + 3.1 * scale   # a small swing far from 0
        yield nice_range(-3.3 * scale, -1.2 * scale, pixels=316)


@pytest.mark.parametrize("low, high", list(ranges()))
def test_every_tick_label_is_a_plain_decimal_that_reads_back_as_its_tick(page, low, high):
    ticks, size = page.evaluate(DRAW, [low, high, 316])
    assert len(ticks) >= 2
    for value, label in ticks:
        assert PLAIN.match(label), (low, high, label)                    # no e, no 2-line label
        assert math.isclose(float(label), value, rel_tol=0, abs_tol=1e-6 * size), (value, label)
        assert label != "-0"

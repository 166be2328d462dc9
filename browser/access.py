"""The local page for keyboard and screen-reader users: its hooks into the page's parts.

The script and style both pages share are export/page_access.py's (keys, graph text alternatives
and tables, the 3-D view's text alternative, the live region, reduced motion); this module puts
them on the VPython page and adds what only this page needs:

    head(setup)          the page's title and language, the script, the keys and how the page
                         pauses for prefers-reduced-motion (Pause, then Reset: the first frame)
    scene_heading(name)  the scene's name as the page's one h1 (the script adds the h2s: the
                         controls, the Measure panel, each graph's title)
    describe_button      "Describe (D)", which queues Describe() (browser/messages.py)
    description_line     the live region the description (export/description.py) is written to,
                         under the clock, after each Step and on Describe
    slider_script        each slider's name and its value in words with its unit, for a screen
                         reader (vpython's jQuery UI sliders have no role or value text)

vpython's check boxes and menus cannot carry a label; the script names each from the words
beside it (nameWidgets).
"""
from __future__ import annotations

import html
import json

from export.page_access import STYLE, install_call, script
from export.page_keys import keys_html
from scenes import format_value
from scenes._sliders import round_slider_values, slider_range, symbol

from .messages import Describe

# With prefers-reduced-motion the page opens paused, its first frame drawn: Pause, then Reset
# (t = 0 again, paused), pressed by the page's own buttons as a click would.
PAUSE = """function () {
  var find = function (name) { return Array.prototype.filter.call(document.querySelectorAll('button'),
    function (b) { return b.textContent.trim() === name; })[0]; };
  var tries = 0;
  (function pause() {             // the buttons may come a moment after this script
    var button = find('Pause');
    if (button) button.click();
    else if (!find('Run') && ++tries < 300) return setTimeout(pause, 100);
    (function reset(n) {
      if (find('Run')) { var r = find('Reset'); if (r) r.click(); }
      else if (n < 300) setTimeout(function () { reset(n + 1); }, 100);
    })(0);
  })();
}"""


def head(setup) -> str:
    """The style and script the page's title carries (browser/view.py puts it beside page_layout's)."""
    summary = (setup.module.__doc__ or "").strip().splitlines()[0] if setup.module.__doc__ else ""
    view_label = (f"The 3-D view of the {setup.name} scene. {summary} "
                  "Press D, or the Describe button, to hear where each mass is and how it moves.")
    call = install_call(title=f"{setup.name}: spring-mass simulator", viewLabel=view_label, nameWidgets=True,
                        headings=True, pause=PAUSE)
    return f"<style>{STYLE}</style><script>{script()}\n{call}</script>"


def scene_heading(name: str) -> str:
    """The scene's name at the top of the page, as the page's heading (h1), in the bold it had before
    (still a <b>: a teacher's test may find the name there)."""
    return f"<h1 style='display:inline; font-size:130%; margin:0'><b>{html.escape(name)}</b></h1>"


def describe_button(vp, put):
    return vp.button(text="Describe (D)", bind=lambda _: put(Describe()))


class DescriptionLine:
    """The live region under the clock, empty until a Step or Describe: `.text` is the sentences.
    Its marker is there from the start, so the script makes its holder a live region before the
    first sentence arrives (a region made with its text is not read out)."""

    def __init__(self, vp):
        self.wtext, self._text = vp.wtext(text=""), None
        self.text = ""

    @property
    def text(self) -> str:
        return self._text

    @text.setter
    def text(self, value: str) -> None:
        if value == self._text:
            return
        self._text = value
        self.wtext.text = (("<br>" if value else "") + "<span class='sm-description'>"
                           + html.escape(value, quote=False) + "</span>")


def description_line(vp) -> DescriptionLine:
    return DescriptionLine(vp)


def keys_line() -> str:
    """The page's keys in words, with the box that turns the letter keys off (export/page_keys.py)."""
    return keys_html()


def slider_script(setup, names) -> str:
    """The script that gives each slider (in the order made) its name, range and value in words."""
    defaults = {name: constant.value for name, constant in setup.constants.items()}
    specs = []
    for name in names:
        constant, value = setup.constants[name], float(setup.values[name])
        unit, meaning = constant.unit, getattr(constant, "meaning", "") or ""
        spec = {"label": f"{symbol(name)}" + (f", {meaning}" if meaning else "") + (f" ({unit})" if unit and unit != "1" else ""),
                "symbol": symbol(name), "unit": unit}
        values = round_slider_values(name, value, defaults.get(name))
        if values:
            spec["texts"] = [f"{symbol(name)} = {format_value(v, unit)}" for v in values]
        else:
            step = slider_range(name, value, defaults.get(name))[2]
            spec["decimals"] = max(0, -int(f"{step:e}".split("e")[1]))
        specs.append(spec)
    return f"<script>window.smAccess && window.smAccess.sliders({json.dumps(specs, ensure_ascii=False)});</script>"

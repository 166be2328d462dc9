"""What both pages carry for keyboard and screen-reader users: one script and its style.

export/page_access.js (the keys of export/page_keys.py, the graphs' text alternatives and tables,
the 3-D view's text alternative, the live region of the description, reduced motion, each graph
line's dash pattern and its sample in the legend) is written
into the local page by browser/access.py and into the offline page by export/offline_page.py;
both hand it the same keys. The style gives every control that can take the focus a ring of
FOCUS_PX px in FOCUS_COLOUR (5.0:1 against white, the pages' background), and styles the tables.
"""
from __future__ import annotations

import json
import os

from .page_keys import KEYS, keys_json
from .palette import DASH_UNIT, line_styles

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "page_access.js")
FOCUS_PX = 3                 # px: the focus ring's width (WCAG 2.4.7; 2.4.11's 2 px at least)
FOCUS_COLOUR = "#0072b2"     # Okabe-Ito blue: 5.0:1 against white

STYLE = """
:focus-visible, .ui-slider-handle:focus { outline: %(px)dpx solid %(colour)s !important; outline-offset: 2px !important; }
input[type=checkbox]:focus-visible { outline-offset: 3px !important; }
details.sm-alt { margin: 0 0 8px 0; }
details.sm-alt summary { cursor: pointer; }
details.sm-alt .sm-points-box { max-height: 16em; overflow: auto; }
table.sm-points { border-collapse: collapse; margin: 4px 8px 8px 0; display: inline-table; vertical-align: top; }
table.sm-points caption { text-align: left; font-weight: 600; }
table.sm-points th, table.sm-points td { border: 1px solid #767676; padding: 1px 8px; text-align: right; }
.sm-description { display: inline-block; max-width: 44em; white-space: normal; }
.sm-unseen { position: absolute !important; width: 1px; height: 1px; margin: -1px; padding: 0; overflow: hidden;
             clip: rect(0 0 0 0); white-space: nowrap; border: 0; }
svg.sm-sample { vertical-align: middle; }
""" % {"px": FOCUS_PX, "colour": FOCUS_COLOUR}


def script() -> str:
    """export/page_access.js, as text to write into a <script> element."""
    with open(SCRIPT, encoding="utf-8") as file:
        return file.read()


def install_call(**config) -> str:
    """The call that sets the page's access up with the keys (export/page_keys.py), the graphs' line
    styles (export/palette.py) and `config`
    (title, viewLabel, nameWidgets, headings; `pause` is a JavaScript function written as text)."""
    pause = config.pop("pause", None)
    fields = json.dumps(config, ensure_ascii=False)[1:-1]
    keys = (f'"keys": {keys_json(KEYS)}, "lineStyles": {json.dumps(line_styles())}, '
            f'"dashUnit": {json.dumps(list(DASH_UNIT))}')
    body = ", ".join(part for part in (keys, fields, f'"pause": {pause}' if pause else "") if part)
    return "window.smAccess.install({" + body + "});"

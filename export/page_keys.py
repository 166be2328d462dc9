"""The pages' keys, declared once: what each key does, the control it presses, and its words.

Both pages (the local page, browser/, and the offline page, export/offline_page.py) hand this list
to one script, export/page_access.js, which listens for the keys and presses the control that
carries the action; the list of keys on each page and in docs/teaching.md is written from it.

A key works wherever the focus is, and never also activates the focused control:

* on a button, a check box, a menu or the 3-D view, every key below is the page's (Space runs or
  pauses; it does not press the focused button, and Enter presses or ticks the focused control);
* on a slider the arrow keys (and Home, End, Page Up, Page Down) move the slider, as a slider's
  keys must (WAI-ARIA's slider pattern), and the other keys are the page's;
* in a text box (a number to type) keys type; Escape leaves the box.

The letter and symbol keys (everything but Space and →) are single-character shortcuts, which
WCAG 2.1's success criterion 2.1.4 asks a page to let its user turn off: the "letter keys" check
box beside the list does that (a speech-input user's words would otherwise press them).

A key presses the visible control whose text begins with one of its `labels` (case aside: the
local page's button reads "Projector: off (P)", the offline page's check box "projector"), so a
control that another part of the page adds (a Jump box) is found by its label, with no list of
element ids. `menu` keys step the menu that offers `menu` (the speed menu's 1×) by `by`.
"""
from __future__ import annotations

import json
from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class Key:
    """One action on a key: the key names (KeyboardEvent.key values), what it does in words, and
    the control it presses (labels) or the menu it steps (menu, by)."""

    keys: tuple[str, ...]
    shown: str                      # how the page writes the key: "Space", "→", "R"
    words: str                      # what it does: "run or pause"
    labels: tuple[str, ...] = ()    # the text a control it presses begins with
    menu: str = ""                  # or: an option of the menu it steps
    by: int = 0                     # and by how many places
    letter: bool = True             # a single-character key (WCAG 2.1.4): the letter-keys box turns it off
    where: str = ""                 # when it works, if not always


KEYS = (
    Key((" ",), "Space", "run or pause", labels=("Run", "Pause"), letter=False),
    Key(("ArrowRight",), "→", "one step of Δt (paused)", labels=("Step",), letter=False),
    Key(("r", "R"), "R", "reset", labels=("Reset",)),
    Key(("j", "J"), "J", "jump to a time", labels=("Jump",)),
    Key(("d", "D"), "D", "describe the motion in words", labels=("Describe",)),
    Key(("p", "P"), "P", "projector mode on or off", labels=("Projector",)),
    Key(("+", "="), "+", "faster", menu="1×", by=1),
    Key(("-", "−", "_"), "−", "slower", menu="1×", by=-1),
    Key(("s", "S"), "S", "start or stop the stopwatch", labels=("Start (S)", "Stop (S)"),
        where="while the Measure panel is open"),
    Key(("l", "L"), "L", "lap", labels=("Lap (L)",), where="while the Measure panel is open"),
    Key(("c", "C"), "C", "clear the stopwatch", labels=("Clear (C)",), where="while the Measure panel is open"),
)

LETTER_KEYS_BOX = "letter keys"   # the check box that turns the single-character keys off


def keys_json(keys=KEYS) -> str:
    """The keys for export/page_access.js."""
    return json.dumps([asdict(key) for key in keys], ensure_ascii=False)


def keys_sentence(keys=KEYS) -> str:
    """The keys in one line of words, as each page lists them."""
    parts = [f"{key.shown} {key.words}" + (f" ({key.where})" if key.where else "") for key in keys]
    return ("Keys: " + ", ".join(parts) + ". Tab moves between controls; Enter presses or ticks the one "
            "with the focus; on a slider the arrow keys move it.")


def keys_html(keys=KEYS) -> str:
    """The list of keys with the box that turns the letter keys off (WCAG 2.1.4), for either page."""
    return (f"<span class='sm-keys'>{keys_sentence(keys)} <label><input type='checkbox' class='sm-letter-keys' "
            f"checked> {LETTER_KEYS_BOX}</label></span>")

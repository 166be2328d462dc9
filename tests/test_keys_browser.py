"""Issue 39, everything by keyboard, in headless Chromium: the local page and the offline page.

* Tab walks every control in reading order: each button, menu, check box, slider, text box and
  folded table the page shows (found on the page, not listed here) is reached once, in document
  order, and shows a focus ring at least 2 px wide with 3:1 contrast against the page;
* each of the page's keys (export/page_keys.py) is pressed with the focus on each kind of control
  (button, check box, menu, slider, folded table, none) and does its job there, without also
  pressing the focused control: Space on the Lap button runs or pauses and takes no lap;
* a slider moves with the arrow keys and says its new value with its unit (aria-valuetext);
* the letter-keys box turns the single-letter keys off.

The pages open with prefers-reduced-motion (paused at t = 0) and move by Step only.
"""
from __future__ import annotations

import pytest

from browser_support import launched, require_browser, wait_for
from export.page_keys import KEYS
from test_access_browser import WAIT, Local, offline, written_page
from test_browser import shown_time

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()

CONTROLS = ("button, select, input:not([type=hidden]):not([type=file]), textarea, summary, a[href], "
            "[tabindex]:not([tabindex='-1']), .ui-slider-handle")
# Every control the page shows, in document order, with what the Tab walk needs of it.
SHOWN = """sel => Array.from(document.querySelectorAll(sel)).filter(e => e.offsetParent !== null && !e.disabled
  && e.tabIndex >= 0 && getComputedStyle(e).visibility !== 'hidden')"""
FOCUS = """() => { const e = document.activeElement; if (!e || e === document.body) return null;
  const s = getComputedStyle(e);
  const all = (%s)(%r);
  return {index: all.indexOf(e), tag: e.tagName, text: (e.textContent || e.value || '').trim().slice(0, 40),
          width: parseFloat(s.outlineWidth), style: s.outlineStyle, colour: s.outlineColor}; }""" % (SHOWN, CONTROLS)


def luminance(css: str) -> float:
    parts = [float(x) for x in css[css.index("(") + 1:css.index(")")].split(",")[:3]]
    linear = [c / 255 / 12.92 if c / 255 <= 0.03928 else ((c / 255 + 0.055) / 1.055) ** 2.4 for c in parts]
    return 0.2126 * linear[0] + 0.7152 * linear[1] + 0.0722 * linear[2]


def contrast(a: str, b: str) -> float:
    la, lb = sorted((luminance(a), luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


def tab_walk(page) -> None:
    """Tab from the top through every control: each once, in document order, each with its ring."""
    count = page.evaluate("(%s)(%r).length" % (SHOWN, CONTROLS))
    # from the first control (the browser's Tab from the address bar lands there), Tab to the last
    page.evaluate("(%s)(%r)[0].focus({focusVisible: true})" % (SHOWN, CONTROLS))
    seen = [page.evaluate(FOCUS)]
    for _ in range(count - 1):
        page.keyboard.press("Tab")
        seen.append(page.evaluate(FOCUS))
        if seen[-1] is None:
            break
    assert None not in seen, f"Tab left the page's controls after {len(seen) - 1} of {count}"
    indices = [f["index"] for f in seen]
    assert -1 not in indices, f"Tab reached something that is not a control: {seen[indices.index(-1)]}"
    assert indices == list(range(count)), f"Tab order is not the page's order of its {count} controls: {indices}"
    for focus in seen:
        assert focus["style"] != "none" and focus["width"] >= 2, f"no focus ring of 2 px on {focus}"
        assert contrast(focus["colour"], "rgb(255, 255, 255)") >= 3, f"focus ring below 3:1 on {focus}"


def focus_kind(page, kind: str) -> None:
    """Put the focus on a control of this kind (or on none): a button is Lap where it is shown
    (the issue's case: Space pressed it again)."""
    if kind == "button" and page.get_by_role("button", name="Lap (L)", exact=True).count():
        page.get_by_role("button", name="Lap (L)", exact=True).focus()
        return
    selector = {"button": "button", "checkbox": "input[type=checkbox]", "menu": "select",
                "slider": ".ui-slider-handle, input[type=range]", "table": "details.sm-alt summary"}.get(kind)
    page.evaluate("""sel => { document.activeElement && document.activeElement.blur();
      if (!sel) return; const shown = Array.from(document.querySelectorAll(sel)).filter(e => e.offsetParent !== null);
      const e = shown.filter(e => !(e.textContent || '').match(/^(Run|Pause|Step|Reset|Describe|Projector)/))[0] || shown[0];
      e.focus(); }""", selector)


def state(page) -> dict:
    """What a key may change, and what pressing the focused control would change."""
    return page.evaluate("""() => { const e = document.activeElement;
      return {checked: e && e.type === 'checkbox' ? e.checked : null, value: e && e.tagName === 'SELECT' ? e.value : null,
              open: e && e.tagName === 'SUMMARY' ? e.parentNode.open : null,
              projector: document.body.classList.contains('sm-projector') || document.body.classList.contains('projector'),
              run: Array.from(document.querySelectorAll('button')).map(b => b.textContent.trim())
                     .filter(t => t === 'Run' || t === 'Pause')[0],
              said: (document.querySelector('.sm-description') || {}).textContent || '',
              laps: (document.querySelector('.sm-stopwatch') || {parentNode: {textContent: ''}}).parentNode.textContent}; }""")


KINDS = ("button", "checkbox", "menu", "slider", "table", None)


@pytest.fixture(scope="module")
def browser():
    with launched(sync_api, scrollbars=True) as chromium:
        yield chromium


def test_the_local_page_by_keyboard(browser):
    local = Local(browser, "vertical")
    page = local.page
    try:
        local.step()
        page.locator(".sm-measure-toggle").click()
        page.locator(".sm-measure").wait_for(state="visible")
        local.graphs_described()
        tab_walk(page)
        dt = 0.1
        for kind in KINDS:
            where = f"focus on {kind or 'nothing'}"
            # → steps (on a slider it moves the slider instead: below)
            if kind != "slider":
                focus_kind(page, kind)
                before, t = state(page), shown_time(page)
                page.keyboard.press("ArrowRight")
                wait_for(lambda: shown_time(page) >= round(t + dt, 6), timeout=WAIT, what=f"→ to step, {where}")
                after = state(page)
                assert (after["checked"], after["value"], after["open"]) == (before["checked"], before["value"],
                                                                             before["open"]), where
            # Space runs, Space again pauses; the focused control is not pressed
            focus_kind(page, kind)
            before = state(page)
            page.keyboard.press(" ")
            wait_for(lambda: state(page)["run"] == "Pause", timeout=WAIT, what=f"Space to run, {where}")
            page.keyboard.press(" ")
            wait_for(lambda: state(page)["run"] == "Run", timeout=WAIT, what=f"Space to pause, {where}")
            after = state(page)
            assert (after["checked"], after["value"], after["open"], after["laps"]) == \
                (before["checked"], before["value"], before["open"], before["laps"]), f"Space pressed the control, {where}"
            # D describes; S, L, C work the stopwatch; P projector on and off; R resets
            page.keyboard.press("d")
            wait_for(lambda: state(page)["said"].startswith("t = " + f"{shown_time(page):.2f}"), timeout=WAIT,
                     what=f"D to describe, {where}")
            page.keyboard.press("s")
            wait_for(lambda: page.get_by_role("button", name="Stop (S)", exact=True).count() == 1, timeout=WAIT, what=f"S, {where}")
            page.keyboard.press("l")
            wait_for(lambda: "laps:" in state(page)["laps"], timeout=WAIT, what=f"L, {where}")
            page.keyboard.press("s")
            wait_for(lambda: page.get_by_role("button", name="Start (S)", exact=True).count() == 1, timeout=WAIT, what=f"S again, {where}")
            page.keyboard.press("c")
            wait_for(lambda: "laps:" not in state(page)["laps"], timeout=WAIT, what=f"C, {where}")
            page.keyboard.press("p")
            assert state(page)["projector"], where
            page.keyboard.press("p")
            assert not state(page)["projector"], where
            speed = page.get_by_role("combobox", name="speed")
            page.keyboard.press("+")
            assert speed.input_value() == "2×", where
            page.keyboard.press("-")
            assert speed.input_value() == "1×", where
            page.keyboard.press("r")
            wait_for(lambda: shown_time(page) == 0.0, timeout=WAIT, what=f"R to reset, {where}")
            local.step()
        # a slider moves with the arrow keys and says its value with its unit
        focus_kind(page, "slider")
        said = page.evaluate("() => document.activeElement.getAttribute('aria-valuetext')")
        page.keyboard.press("ArrowRight")
        now = page.evaluate("() => document.activeElement.getAttribute('aria-valuetext')")
        assert said == "m = 10 kg" and now == "m = 10.1 kg"
        wait_for(lambda: "m = 10.1 kg" in page.locator("#glowscript").inner_text(), timeout=WAIT,
                 what="the new mass reaching the program")
        # Enter ticks a box; the letter keys can be turned off
        page.evaluate("() => document.activeElement.blur()")
        box = page.get_by_role("checkbox", name="letter keys")
        box.focus()
        page.keyboard.press("Enter")
        assert not box.is_checked()
        t = shown_time(page)
        page.keyboard.press("r")
        page.keyboard.press("ArrowRight")       # → is no letter: it still steps, after R was ignored
        wait_for(lambda: shown_time(page) > t, timeout=WAIT, what="→ with the letter keys off")
        assert shown_time(page) > 0
        jump = [label for key in KEYS if key.shown == "J" for label in key.labels]
        if any(page.get_by_role("button", name=label).count() for label in jump):   # issue 35's Jump, once it lands
            box.check()
            t = shown_time(page)
            page.keyboard.press("j")
            wait_for(lambda: shown_time(page) != t or page.evaluate(
                "() => ['INPUT', 'TEXTAREA'].includes(document.activeElement.tagName)"), timeout=WAIT, what="J to jump")
    finally:
        local.close()


def test_the_offline_page_by_keyboard(browser, tmp_path):
    context, page = offline(browser, written_page(tmp_path, "damped"))
    try:
        page.locator("details summary").first.wait_for()
        tab_walk(page)
        for kind in ("button", "checkbox", "menu", None):
            where = f"focus on {kind or 'nothing'}"
            focus_kind(page, kind)
            before = state(page)
            n = page.evaluate("() => window.offlineState().n || 0")
            page.keyboard.press("ArrowRight")
            page.wait_for_function("n => window.offlineState().n > n", arg=n, timeout=WAIT * 1000)
            page.keyboard.press(" ")
            page.wait_for_function("() => !window.offlineState().paused")
            page.keyboard.press(" ")
            page.wait_for_function("() => window.offlineState().paused")
            page.keyboard.press("d")
            page.wait_for_function("() => document.getElementById('description').textContent.startsWith('t = ')")
            page.keyboard.press("p")
            assert state(page)["projector"], where
            page.keyboard.press("p")
            after = state(page)
            assert not after["projector"], where
            assert (after["checked"], after["value"]) == (before["checked"], before["value"]), where
            page.keyboard.press("r")
            page.wait_for_function("() => !window.offlineState().n")
        slider = page.locator("input[type=range]").first
        slider.focus()
        value = slider.input_value()
        page.keyboard.press("ArrowRight")
        assert slider.input_value() != value
        assert " = " in page.evaluate("() => document.activeElement.getAttribute('aria-valuetext') || ''")
    finally:
        context.close()

"""Issue 39, everything by keyboard, in headless Chromium: the local page and the offline page.

* Tab walks every control in reading order: each button, menu, check box, slider, text box and
  folded table the page shows (found on the page, not listed here) is reached once, in document
  order, and shows a focus ring at least 2 px wide with 3:1 contrast against the page;
* each of the page's keys (export/page_keys.py) is pressed with the focus on each kind of control
  (button, check box, menu, slider, folded table, text box, none). What it presses is read in the
  page: every click, change and input it causes is caught before the page's own handlers, so no
  program is asked anything and the check costs a key press. A key presses the one control it
  names (the control shown whose label begins with the key's, as export/page_keys.py says), or
  the speed menu it steps, and never the focused control too (Space on the Lap button takes no
  lap); on a slider the arrows move the slider; in a text box keys type and Escape leaves it;
* then, for real, a few keys whose work is the program's: → steps, Space runs and pauses, D
  describes, S, L and C work the stopwatch, J jumps, R resets, and a slider's new value, spoken
  with its unit, reaches the program;
* the letter-keys box (Enter ticks it) turns the single-letter keys off and leaves → and Space.

Each page is opened once (tests/access_pages.py), with prefers-reduced-motion: paused at t = 0.
"""
from __future__ import annotations

import pytest

from access_pages import LocalPage, graphs_described, offline, offline_step, open_table
from browser_support import launched, require_browser, wait_for
from export.page_keys import KEYS, LETTER_KEYS_BOX
from test_browser import shown_time

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()

CONTROLS = ("button, select, input:not([type=hidden]):not([type=file]), textarea, summary, a[href], "
            "[tabindex]:not([tabindex='-1']), .ui-slider-handle")
# Every control the page shows, in document order, with what the Tab walk needs of it.
# (what a folded table holds is not shown: Chromium gives it an offsetParent all the same)
SHOWN = """sel => Array.from(document.querySelectorAll(sel)).filter(e => e.offsetParent !== null && !e.disabled
  && e.tabIndex >= 0 && getComputedStyle(e).visibility !== 'hidden' && !e.closest('details:not([open]) > :not(summary)'))"""
FOCUS = """() => { const e = document.activeElement; if (!e || e === document.body) return null;
  const s = getComputedStyle(e);
  const all = (%s)(%r);
  return {index: all.indexOf(e), tag: e.tagName, text: (e.textContent || e.value || '').trim().slice(0, 40),
          width: parseFloat(s.outlineWidth), style: s.outlineStyle, colour: s.outlineColor}; }""" % (SHOWN, CONTROLS)

# Catch what a key press causes: each click, change and input event, caught at the window before
# any handler of the page's, written down and stopped there (a click's default undone too).
CATCH = """() => {
  if (window.__smCaught) return;
  window.__smCaught = [];
  const text = e => e.tagName === 'SELECT' ? 'menu ' + Array.from(e.options).map(o => o.text).join('|') :
    e.tagName === 'INPUT' && e.type === 'checkbox' ? 'box ' + ((e.closest('label') || {}).textContent ||
      e.getAttribute('aria-label') || '').trim() : e.tagName + ' ' + (e.textContent || '').trim();
  for (const type of ['click', 'change', 'input']) window.addEventListener(type, ev => {
    if (!window.__smCatching) return;
    window.__smCaught.push(type + ': ' + text(ev.target));
    ev.stopImmediatePropagation();
    if (type === 'click') ev.preventDefault();
  }, true);
}"""
# What a key should press: the control shown whose label begins with one of the key's labels (the
# rule export/page_keys.py states), or the menu offering its option.
EXPECTED = """key => {
  const shown = e => e.offsetParent !== null && !e.disabled;
  if (key.menu) { const m = Array.from(document.querySelectorAll('select')).filter(shown)
      .find(m => Array.from(m.options).some(o => o.text === key.menu));
    return m ? 'change: menu ' + Array.from(m.options).map(o => o.text).join('|') : null; }
  for (const e of document.querySelectorAll('button, input[type=checkbox]')) {
    if (!shown(e)) continue;
    const label = e.tagName === 'BUTTON' ? e.textContent.trim() :
      ((e.closest('label') || {}).textContent || e.getAttribute('aria-label') || '').trim();
    if (key.labels.some(l => label.toLowerCase().startsWith(l.toLowerCase())))
      return e.tagName === 'BUTTON' ? 'click: BUTTON ' + label : 'click: box ' + label;
  }
  return null; }"""
# The kinds of control the focus is put on, found on the page: a button (Lap where the stopwatch
# shows: the case), a check box, a menu, a slider, a folded table, a text box, nothing.
KIND = {"button": "button", "checkbox": "input[type=checkbox]", "menu": "select",
        "slider": ".ui-slider-handle, input[type=range]", "table": "details.sm-alt summary",
        "text box": "input[type=text], input[type=number], input:not([type])"}
FOCUS_ON = """sel => { document.activeElement && document.activeElement.blur();
  document.querySelectorAll('[data-sm-focused]').forEach(e => e.removeAttribute('data-sm-focused'));
  if (!sel) return null;
  const shown = Array.from(document.querySelectorAll(sel)).filter(e => e.offsetParent !== null && !e.disabled &&
    !(e.textContent || '').match(/^(Run|Pause|Step|Reset|Describe|Projector|Jump|Start|Stop|Clear)/) &&
    !e.classList.contains('sm-letter-keys'));
  const e = shown.find(e => e.textContent.trim() === 'Lap (L)') || shown[0];
  if (!e) return null;
  e.focus();
  e.dataset.smFocused = '1';
  return e === document.activeElement ? (e.textContent || e.value || e.getAttribute('aria-label') || '').trim() : null; }"""
STATE = """() => { const e = document.activeElement;
  return {focused: !!(e && e.dataset && e.dataset.smFocused), value: e && 'value' in e ? e.value : null, now: e && e.getAttribute('aria-valuenow'),
          open: e && e.tagName === 'SUMMARY' ? e.parentNode.open : null, checked: e ? !!e.checked : null}; }"""


def luminance(css: str) -> float:
    parts = [float(x) for x in css[css.index("(") + 1:css.index(")")].split(",")[:3]]
    linear = [c / 255 / 12.92 if c / 255 <= 0.03928 else ((c / 255 + 0.055) / 1.055) ** 2.4 for c in parts]
    return 0.2126 * linear[0] + 0.7152 * linear[1] + 0.0722 * linear[2]


def contrast(a: str, b: str) -> float:
    la, lb = sorted((luminance(a), luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


def tab_walk(page) -> int:
    """Tab from the top through every control: each once, in document order, each with its ring."""
    count = page.evaluate("(%s)(%r).length" % (SHOWN, CONTROLS))
    # from the first control (the browser's Tab from the address bar lands there), Tab to the last
    # (blurred first: a control focused by a mouse click keeps no ring when focused again)
    page.evaluate("() => document.activeElement && document.activeElement.blur()")
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
    return count


def caught(page, press: str) -> list[str]:
    """What pressing `press` clicked or changed, caught before the page's handlers saw it."""
    page.evaluate("() => { window.__smCaught.length = 0; window.__smCatching = true; }")
    try:
        page.keyboard.press(press)
    finally:
        found = page.evaluate("() => { window.__smCatching = false; return window.__smCaught.slice(); }")
    return found


def each_key_on_each_kind(page) -> int:
    """Every key with the focus on every kind of control the page has: what it presses, and that
    the focused control is left as it was. Returns how many presses were checked."""
    page.evaluate(CATCH)
    checked = 0
    for kind, selector in [*KIND.items(), ("nothing", None)]:
        focused = page.evaluate(FOCUS_ON, selector)
        if selector and focused is None:
            continue                                   # this page has no control of this kind
        typed = page.evaluate(STATE)["value"]
        for key in KEYS:
            where = f"{key.shown} with the focus on {kind} {focused or ''}".strip()
            before = page.evaluate(STATE)
            expected = page.evaluate(EXPECTED, {"labels": list(key.labels), "menu": key.menu})
            got = caught(page, key.keys[0])
            after = page.evaluate(STATE)
            assert after["focused"] == bool(selector), f"{where}: the focus moved"
            if kind == "text box":                      # a text box's keys are its own: they type
                assert all(event.startswith("input: ") for event in got), f"{where}: pressed {got}"
                continue
            if kind == "slider" and key.keys[0] == "ArrowRight":   # the slider's own arrow moves it
                assert not got and after["now"] != before["now"], f"{where}: the slider did not move"
                page.keyboard.press("ArrowLeft")
                checked += 1
                continue
            want = [expected] if expected else []
            assert got == want, f"{where}: pressed {got}, not {want}"
            if key.menu and expected:                  # the menu really moved: step it back (it may be the focused one)
                page.evaluate("by => { const m = Array.from(document.querySelectorAll('select')).find(m => Array.from("
                              "m.options).some(o => o.text === '1×')); m.selectedIndex -= by; }", key.by)
                after = page.evaluate(STATE)
            assert (after["value"], after["now"], after["open"], after["checked"]) == \
                (before["value"], before["now"], before["open"], before["checked"]), f"{where}: the focused control changed"
            checked += 1
        if kind == "text box":                          # its text put back; Escape leaves it
            page.evaluate("v => { document.activeElement.value = v; }", typed)
            page.keyboard.press("Escape")
            assert page.evaluate("() => document.activeElement === document.body"), "Escape did not leave the text box"
    return checked


@pytest.fixture(scope="module")
def browser():
    with launched(sync_api, scrollbars=True) as chromium:
        yield chromium


def test_the_local_page_by_keyboard(browser):
    local = LocalPage(browser)
    try:
        page = local.show("vertical")
        local.measure()
        local.jump(1.0)
        graphs_described(page)
        assert tab_walk(page) > 30
        assert each_key_on_each_kind(page) >= 6 * len(KEYS)
        # the program's side, key by key, the focus on the Lap button
        page.get_by_role("button", name="Lap (L)", exact=True).focus()
        t = shown_time(page)
        page.keyboard.press("ArrowRight")
        wait_for(lambda: shown_time(page) > t, timeout=120, what="→ to step")
        page.keyboard.press(" ")
        wait_for(lambda: local.run_button() == "Pause", timeout=120, what="Space to run")
        page.keyboard.press(" ")
        wait_for(lambda: local.run_button() == "Run", timeout=120, what="Space to pause")
        said = local.describe()
        assert said.startswith(f"t = {shown_time(page):.2f} s. The mass is ")
        watch = page.locator(".sm-stopwatch")
        page.keyboard.press("s")
        page.get_by_role("button", name="Stop (S)", exact=True).wait_for()
        page.keyboard.press("l")
        wait_for(lambda: "laps:" in watch.locator("xpath=..").inner_text(), timeout=120, what="L to take a lap")
        page.keyboard.press("s")
        page.get_by_role("button", name="Start (S)", exact=True).wait_for()
        page.keyboard.press("c")
        wait_for(lambda: "laps:" not in watch.locator("xpath=..").inner_text(), timeout=120, what="C to clear")
        assert "Lap (L)" in page.evaluate("() => document.activeElement.textContent")   # the focus never moved
        page.keyboard.press("r")
        wait_for(lambda: shown_time(page) == 0.0, timeout=120, what="R to reset")
        page.keyboard.press("j")                       # Jump: to the box's t, the scene's question time
        wait_for(lambda: shown_time(page) == 0.2, timeout=120, what="J to jump to t = 0.2 s")
        # a slider moves with the arrow keys and says its value with its unit; the program gets it
        slider = page.locator(".ui-slider-handle").first
        slider.focus()
        said = slider.get_attribute("aria-valuetext")
        page.keyboard.press("ArrowRight")
        assert (said, slider.get_attribute("aria-valuetext")) == ("m = 10 kg", "m = 10.1 kg")
        wait_for(lambda: "m = 10.1 kg" in page.locator("#glowscript").inner_text(), timeout=120,
                 what="the new mass reaching the program")
        letter_keys_off(page, step="Step")
    finally:
        local.close()


def letter_keys_off(page, *, step: str) -> None:
    """Enter unticks the letter-keys box; then R presses nothing, and → and Space still work."""
    box = page.get_by_role("checkbox", name=LETTER_KEYS_BOX)
    box.focus()
    page.keyboard.press("Enter")
    assert not box.is_checked()
    try:
        page.evaluate("() => document.activeElement.blur()")
        for key in KEYS:
            got = caught(page, key.keys[0])
            if key.letter:
                assert got == [], f"{key.shown} with the letter keys off: pressed {got}"
            else:
                assert len(got) == 1 and got[0].startswith("click: "), f"{key.shown} with the letter keys off: {got}"
        assert caught(page, "ArrowRight") == [f"click: BUTTON {step}"]
    finally:
        box.check()


def test_the_offline_page_by_keyboard(browser, tmp_path):
    context, page = offline(browser, "damped", tmp_path)
    try:
        offline_step(page, 3)
        graphs_described(page)
        open_table(page)
        page.locator("details.sm-alt summary").first.click()     # folded again: a folded table is a kind
        assert tab_walk(page) > 10
        assert each_key_on_each_kind(page) >= 4 * len(KEYS)
        # the program's side: → steps, Space runs and pauses, D describes, R resets
        page.evaluate("() => document.activeElement && document.activeElement.blur()")
        n = page.evaluate("() => window.offlineState().n || 0")
        page.keyboard.press("ArrowRight")
        page.wait_for_function("n => window.offlineState().n > n", arg=n)
        page.keyboard.press(" ")
        page.wait_for_function("() => !window.offlineState().paused")
        page.keyboard.press(" ")
        page.wait_for_function("() => window.offlineState().paused")
        page.keyboard.press("d")
        page.wait_for_function("() => document.getElementById('description').textContent.startsWith('t = ')")
        page.keyboard.press("r")
        page.wait_for_function("() => !window.offlineState().n")
        slider = page.locator("input[type=range]").first
        slider.focus()
        value = slider.input_value()
        page.keyboard.press("ArrowRight")
        assert slider.input_value() != value
        assert " = " in page.evaluate("() => document.activeElement.getAttribute('aria-valuetext') || ''")
        letter_keys_off(page, step="Step")
    finally:
        context.close()

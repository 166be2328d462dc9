"""The page's controls and captions: buttons, menus, sliders, the time, the constants and the status.

A click arrives on vpython's server thread; the control only queues it as a message, a small named
type of browser/messages.py such as RunOrPause(), SetConstant("k", 45.0) or ChooseScene("pendulum"),
and the frame loop (browser/view.py) carries the messages out between frames. Each build of the
page has its own queue, so a click on a control of a page already taken down is never carried out.
"""
from __future__ import annotations

import base64
import html
import queue
from urllib.parse import quote

from physics.integrators import INTEGRATORS

from export.idle_render import idle_render_script
from export.numbers import time_decimals as file_time_decimals
from scenes import catalog, format_value
from scenes._constants import idle as idle_constants
from scenes._sliders import round_slider_values, slider_names, slider_range, symbol

from .axes import PLAIN_TICKS
from .graph_reading import GRAPH_READING
from .measure_panel import MeasurePanel
from .arrows3d import arrow_checkboxes
from . import access
from .messages import (ChooseIntegrator, ChoosePreset, ChooseScene, ChooseSpeed, DownloadCsv, DownloadOfflinePage,
                       DownloadProgram, FitData, JumpTo, Reset, RunOrPause, SetConstant, Step)
from .readout import units_kept

SPEEDS = {"¼×": 0.25, "½×": 0.5, "1×": 1.0, "2×": 2.0, "4×": 4.0}
PRESET_PROMPT = "choose a preset"
# vpython 7.6.5's page sends a slider's value only when it differs from the last value it sent, and
# before the first move there is none, so the first move of every slider was lost. This script tells
# the page each new slider's starting value, by calling the slider's own change handler once with a
# stand-in for a mouse event (its handlers ignore events without one), so the first move is sent.
# It runs in the page from a wtext (jQuery runs scripts in the HTML it inserts); each slider is primed once.
PRIME_SLIDERS = ("<script>$('.ui-slider').each(function () {"
                 " if (this.dataset.primed) return; this.dataset.primed = '1';"
                 " var change = $(this).slider('option', 'change');"
                 " if (change) change({originalEvent: {}}); });</script>")


UNSEEN = ("position:absolute; width:1px; height:1px; overflow:hidden; clip:rect(0 0 0 0); "
          "white-space:nowrap")   # read by a screen reader, not drawn
# The Jump box is vpython's winput, an <input> just before the Jump button: this names it (for the
# tests and a screen reader) and makes Enter in it press its Jump button, after the box has sent its
# text. A notebook keeps the captions of the scenes it ran before: each box is set up once.
JUMP_SCRIPT = ("<script>document.querySelectorAll('.sm-jumped').forEach(function (mark) {"
               " var box = mark.parentNode; while (box && box.tagName !== 'INPUT') box = box.previousElementSibling;"
               " if (!box || box.dataset.jump) return; box.dataset.jump = '1'; box.id = 'sm-jump-t';"
               " box.classList.add('sm-jump-t'); box.setAttribute('aria-label', 'jump to t, in seconds');"
               " box.style.fontSize = 'inherit'; box.style.height = 'auto'; box.style.width = '4.5em';"
               " var button = box.nextElementSibling; while (button && button.tagName !== 'BUTTON') button = button.nextElementSibling;"
               " box.addEventListener('keyup', function (e) { if (e.key === 'Enter' && button) button.click(); });"
               "});</script>")


class _OwnLine:
    """A wtext on a line of its own when it has something to say, and no room at all when empty:
    `.text` is the sentence, the page shows it after a line break, each number kept on the line of
    its unit (the browser wrapped `330` and `%` onto two lines at 1280×800)."""

    def __init__(self, wtext):
        self.wtext, self._text = wtext, None
        self.text = ""

    @property
    def text(self) -> str:
        return self._text

    @text.setter
    def text(self, value: str) -> None:
        # its marker is there while empty, so the page's script makes it a live region before its
        # first sentence (export/page_access.js): a screen reader hears why a run stopped
        self._text = value
        self.wtext.text = "<span class='sm-status'>" + ("<br>" + units_kept(value) if value else "") + "</span>"


class Controls:
    """The caption under the 3-D picture for one scene: its controls, their queued clicks, and
    the texts the frame loop updates.

    vp           the vpython module
    setup        the scene as configured (name, constants and their values)
    measure      the Measure panel's state to show (browser/measure_panel.py): period, lines, graph
    view         the scene's VIEW merged with the defaults (sliders)
    integrators  the model's one integrator per mass, if it has them (then no integrator menu)
    integrator   the integrator chosen now; speed: the speed chosen now (a key of SPEEDS)
    preset       the label of the preset applied, shown in the preset menu
    arrows       the kinds of arrow switched on now, ticked in their check boxes
    load_button  the Load data button's HTML (browser/data_panel.py), '' where files cannot be sent
    force_box    makes the Add a force box under the sliders, given vp and the queue's put
                 (browser/force_box.py's ForceBox), or None for none
    """

    def __init__(self, vp, *, setup, view: dict, integrators, integrator: str, speed: str,
                 preset: str | None = None, arrows=(), load_button: str = "", measure: dict | None = None,
                 force_box=None):
        self.vp = vp
        self.commands: queue.SimpleQueue = queue.SimpleQueue()
        self.downloads = 0  # links offered so far: each gets its own id
        caption = vp.scene.append_to_caption
        caption("\n")
        self._run_row(integrators=integrators, integrator=integrator, speed=speed,
                      until=setup.values.get("until"))
        self._time_row()
        caption("\n")
        access.describe_button(vp, self.commands.put)   # browser/access.py: the motion in words (key D)
        caption(" ")
        # browser/measure_panel.py: its button here, its block (closed at first) under it, by the clock
        self.measure = MeasurePanel(vp, self.commands.put,
                                    **(measure or {"period": False, "lines": (), "graph": "energy"}))
        caption("\n\n")
        self._menu_row(setup=setup, preset=preset)
        caption("\n\n")
        self._data_row(load_button)
        caption("\n")
        self.arrow_boxes = arrow_checkboxes(vp, self.commands.put, arrows)   # browser/arrows3d.py
        self.arrow_legend = vp.wtext(text="")
        caption("\n")
        self.step_text = vp.wtext(text="")
        self._slider_rows(setup=setup, view=view)
        self.force_box = force_box(vp, self.commands.put) if force_box else None
        vp.wtext(text="").text = PLAIN_TICKS  # every graph's tick labels in plain decimals (browser/axes.py)
        vp.wtext(text="").text = idle_render_script()  # the 3-D view drawn only when it changed (export/)
        vp.wtext(text="").text = GRAPH_READING  # a click reads a graph (browser/graph_reading.py)
        caption("\n\n")
        self.constants_text = vp.wtext(text="")
        caption("\n")
        self.link_text = vp.wtext(text="")   # the set-up's link, for its offline page on a web site (show_link)
        caption("\n<i>Moving a slider, choosing another integrator or a preset, or loading data restarts "
                "the run from t = 0; Reset returns to the start; "
                "Step advances one Δt.</i>\n")
        vp.wtext(text="").text = access.keys_line()   # the keys, and the box that turns the letter keys off

    # ---- building the caption, one row at a time ----

    def _run_row(self, *, integrators, integrator: str, speed: str, until) -> None:
        """Run/Pause, Step, Reset, Jump to t, the integrator (a menu, or the masses' own methods)
        and the speed."""
        vp, put, caption = self.vp, self.commands.put, self.vp.scene.append_to_caption
        self.run_button = vp.button(text="Pause", bind=lambda _: put(RunOrPause()))
        caption("  ")
        vp.button(text="Step", bind=lambda _: put(Step()))
        caption("  ")
        vp.button(text="Reset", bind=lambda _: put(Reset()))
        self._jump_box(until)
        caption("    integrator ")
        if integrators:
            vp.wtext(text="<i>" + ", ".join(integrators) + "</i> (one per mass)")
        else:
            vp.menu(choices=list(INTEGRATORS), selected=integrator,
                    bind=lambda menu: put(ChooseIntegrator(menu.selected)))
        caption("    speed ")
        vp.menu(choices=list(SPEEDS), selected=speed, bind=lambda menu: put(ChooseSpeed(menu.selected)))
        caption("\n")

    def _jump_box(self, until) -> None:
        """"Jump to t = [ ] s" and its button (browser/jump.py), the box starting at the question
        time. vpython's box sends its text when Enter is pressed or the focus leaves it (a click on
        Jump does that first), so the button reads the text last sent; Enter in the box presses
        Jump too (JUMP_SCRIPT), and the key J presses it from anywhere (browser/page_layout.py)."""
        vp, put, caption = self.vp, self.commands.put, self.vp.scene.append_to_caption
        self.jump_text = f"{until:g}" if isinstance(until, (int, float)) else "1"
        caption("    jump to t = ")
        vp.winput(type="string", text=self.jump_text, width=64,
                  bind=lambda box: setattr(self, "jump_text", box.text))
        caption(" s ")
        vp.button(text="Jump", bind=lambda _: put(JumpTo(self.jump_text)))
        self.jumped_text = vp.wtext(text="")
        self.jumps = 0
        self.show_jumped(None)

    def show_jumped(self, t: float | None, *, decimals: int = 2) -> None:
        """After a jump (the view calls this once it has drawn): a note of where it went, carrying
        the jump's count and t for a look from outside (tests/browser_support.py's jump_to waits
        for it); None writes the empty note and the box's script."""
        if t is not None:
            self.jumps += 1
        note = "" if t is None else f"jumped to t = {t:.{decimals}f} s, paused"
        # heard, not seen: the page's big t and its Run button already show it
        self.jumped_text.text = (f"<span class='sm-jumped' role='status' data-jumps='{self.jumps}' "
                                 f"data-t='{'' if t is None else repr(float(t))}' style='{UNSEEN}'>{note}</span>"
                                 f"{JUMP_SCRIPT}")

    def _time_row(self) -> None:
        """The time, the error read-out, and the status line under them."""
        vp, caption = self.vp, self.vp.scene.append_to_caption
        self.time_text = vp.wtext(text="t = 0.00 s")
        caption("    ")
        self.error_text = vp.wtext(text="")
        # the status (why the run stopped, a runaway, Δt stable but inaccurate, a file that cannot
        # open) under the time, where a class looks: at the page's foot it was below a 1280×800 screen
        self.status_text = _OwnLine(vp.wtext(text=""))
        self.description = access.description_line(vp)   # the live region (browser/access.py)
        self.notice = ""   # a sentence said (say()) that stays until the next run starts

    def _menu_row(self, *, setup, preset: str | None) -> None:
        """The scene and preset menus, and the three downloads with the line that offers them."""
        vp, put, caption = self.vp, self.commands.put, self.vp.scene.append_to_caption
        caption("scene ")
        self.scene_menu = vp.menu(choices=scene_menu_choices(), selected=setup.name,
                                  bind=lambda menu: put(ChooseScene(menu.selected)))
        if catalog.SKIPPED:   # files of a teacher's folder left out of the menu: say why, folded away
            vp.wtext(text=left_out_html(catalog.SKIPPED))
        caption("    preset ")
        labels = [label for label, _ in catalog.presets(setup)]
        self.preset_menu = None
        if labels:
            self.preset_menu = vp.menu(choices=[PRESET_PROMPT] + labels, selected=preset or PRESET_PROMPT,
                                       bind=lambda menu: put(ChoosePreset(menu.selected)))
        else:
            vp.wtext(text="<i>none for this scene</i>")
        caption("    ")
        vp.button(text="Download CSV", bind=lambda _: put(DownloadCsv()))
        caption(" ")
        vp.button(text="Download program", bind=lambda _: put(DownloadProgram()))
        caption(" ")
        vp.button(text="Download offline page", bind=lambda _: put(DownloadOfflinePage()))
        caption(" ")
        self.download_text = vp.wtext(text="")

    def _data_row(self, load_button: str) -> None:
        """Measured data: Load data (where files can be sent), Fit, and the lines on the data."""
        vp, put, caption = self.vp, self.commands.put, self.vp.scene.append_to_caption
        caption("measured data ")
        if load_button:
            vp.wtext(text="").text = load_button  # set, not made with it: the setter runs its script
            caption(" ")
        vp.button(text="Fit", bind=lambda _: put(FitData()))
        caption("\n")
        self.data_text = vp.wtext(text="")

    def _slider_rows(self, *, setup, view: dict) -> None:
        """A slider for each constant the scene's VIEW offers (scenes/_sliders.py), each on its own
        line with its value: a list of round values where the constant has one, else its span."""
        vp, put, caption = self.vp, self.commands.put, self.vp.scene.append_to_caption
        defaults = {name: constant.value for name, constant in setup.constants.items()}
        self.sliders, self.slider_texts = {}, {}
        for name in slider_names(setup, view):
            caption("\n")
            values = round_slider_values(name, float(setup.values[name]), defaults.get(name))
            if values:   # the slider picks a place in the list of round values
                self.sliders[name] = vp.slider(
                    min=0, max=len(values) - 1, step=1, value=values.index(float(setup.values[name])),
                    length=320, bind=lambda s, name=name, values=values: put(SetConstant(name, values[round(s.value)])))
            else:
                low, high, step = slider_range(name, float(setup.values[name]), defaults.get(name))
                self.sliders[name] = vp.slider(min=low, max=high, step=step, value=setup.values[name],
                                               length=320, bind=lambda s, name=name: put(SetConstant(name, s.value)))
            self.slider_texts[name] = vp.wtext(text="")
        if self.sliders:
            vp.wtext(text="").text = PRIME_SLIDERS  # set, not made with it: the setter runs scripts
            vp.wtext(text="").text = access.slider_script(setup, list(self.sliders))   # names and values in words

    def clicks(self) -> list:
        """The messages queued by clicks since the last call (browser/messages.py), oldest first."""
        pending = []
        while True:
            try:
                pending.append(self.commands.get_nowait())
            except queue.Empty:
                return pending

    # ---- the texts ----

    def show_constants(self, setup) -> None:
        """The constants line and each slider's value, for a run that starts now."""
        self.constants_text.text = "Constants: " + constants_text(setup)
        for name, text in self.slider_texts.items():
            unit = setup.constants[name].unit
            text.text = f"  {symbol(name)} = {format_value(setup.values[name], unit)}"
        self.download_text.text = ""
        self.notice = ""

    def show_link(self, fragment: str) -> None:
        """The Copy link line: the address fragment of the set-up running now (export/offline_page.py's
        link_fragment), which an offline page of this scene on a web site reads from its address."""
        shown = html.escape("#" + fragment if fragment else "(the scene as shipped: no fragment)")
        self.link_text.text = (
            f"link <input id='sm-link' readonly tabindex='-1' size='36' value='{shown}' style='font-family: monospace'> "
            "<button id='sm-copy-link' type='button' onclick=\"var f = document.getElementById('sm-link');"
            " f.select(); if (navigator.clipboard) navigator.clipboard.writeText(f.value);\">Copy link</button>"
            " <i>add it to the address of this scene's offline page on a web site</i>")

    def show_time(self, t: float, *, decimals: int, running: bool, error: str) -> None:
        """The time (to `decimals` places), Run or Pause on the button, and the error readout."""
        self.time_text.text = f"<b style='font-size:150%'>t = {t:.{decimals}f} s</b>"
        self.run_button.text = "Pause" if running else "Run"
        self.error_text.text = error

    def show_status(self, *, problem: str | None, runaways, slow_dt: float | None,
                    advice: str | None = None) -> None:
        """The status line: why the run stopped, or which masses ran away and that Δt is stable but
        inaccurate (advice, physics/accuracy.py), or that it runs slower than real time (slow_dt:
        the Δt that is small for this computer, None if keeping up)."""
        status = problem or "\n".join([*runaways] + ([advice] if advice else []))   # the page wraps them
        if slow_dt is not None and not status:
            status = (f"Running slower than real time (Δt = {slow_dt:g} s is small for "
                      f"this computer at this speed).")
        text = f"<b>Stopped:</b> {status}" if problem else status or self.notice
        if text != self.status_text.text:
            self.status_text.text = text

    def say(self, text: str) -> None:
        """Put a sentence in the status line (a value that could not be used, a scene file that
        cannot open): it stays there until the next run starts."""
        self.notice = text
        self.status_text.text = text

    def show_scene(self, scene: str) -> None:
        """A scene chosen in the menu could not be used: the menu goes back to the scene that runs."""
        self.scene_menu.selected = scene

    def show_preset(self, preset: str | None) -> None:
        """A preset chosen in the menu could not be used: the menu goes back to the preset whose
        constants run, or to its prompt if none does."""
        if self.preset_menu is not None:
            self.preset_menu.selected = preset or PRESET_PROMPT

    def preset_left(self) -> None:
        """The constants no longer match the preset chosen: the menu shows its prompt again."""
        if self.preset_menu is not None:
            self.preset_menu.selected = PRESET_PROMPT

    def show_data(self, text: str) -> None:
        """The lines on the measured data (browser/data_panel.py), if they changed."""
        if text != self.data_text.text:
            self.data_text.text = text

    def move_sliders(self, values: dict) -> bool:
        """Put the constants' sliders at `values` (a fit's); a constant without a slider is shown
        in the constants line only. False, moving none, if a slider's span does not reach its value
        (vpython cannot change a slider's span once it is made: the controls must be built again)."""
        moved = {name: value for name, value in values.items() if name in self.sliders}
        for name, value in moved.items():
            slider = self.sliders[name]
            if round_slider_values(name, value) or not slider.min <= value <= slider.max:
                return False
        for name, value in moved.items():
            self.sliders[name].value = value
        return True

    def offer(self, *, kind: str, name: str, href: str, note: str) -> None:
        """Hand a file to the browser: a data: link that a one-line script clicks; the link stays
        on the page as a fallback, with a note on what it holds."""
        self.downloads += 1
        link = f"{kind}-download-{self.downloads}"
        self.download_text.text = (f'<a id="{link}" download="{name}" href="{href}">{name}</a> ({note})'
                                   f'<script>document.getElementById("{link}").click()</script>')

    def offer_nothing(self, why: str) -> None:
        """Say in place of a link why there is no file to download."""
        self.download_text.text = f"<i>{why}</i>"

    def take_down(self) -> None:
        """Remove the controls from the page (the caption is emptied)."""
        self.vp.scene.caption = ""


def csv_href(text: str) -> str:
    return f"data:text/csv;charset=utf-8,{quote(text, safe=',.-+')}"


def program_href(text: str) -> str:
    return f"data:text/x-python;charset=utf-8,{quote(text)}"


def page_href(text: str) -> str:
    """An offline page (6 MB of mostly JavaScript) as a data: link, base64 (shorter than %-escapes)."""
    return "data:text/html;charset=utf-8;base64," + base64.b64encode(text.encode("utf-8")).decode("ascii")


def scene_menu_choices() -> list[str]:
    """The scene menu: every scene found (scenes/_catalog.py), in menu order."""
    return list(catalog.SCENE_NAMES)


def left_out_html(skipped: dict) -> str:
    """Why files of the scene folders are not in the scene menu (scenes/_catalog.py's SKIPPED:
    not a scene, a name the program's code has taken, not a regular file, too big), folded into
    one line the teacher opens: a file that silently did not appear looked like a bug."""
    count = len(skipped)
    reasons = "".join(f"<li>{html.escape(why, quote=False)}</li>" for why in skipped.values())
    return (f" <details class='sm-left-out' style='display:inline-block; vertical-align:top'><summary>"
            f"{count} file{'s' if count != 1 else ''} not in the menu: why</summary>"
            f"<ul style='margin:0; white-space:normal; max-width:40em'>{reasons}</ul></details>")


def time_decimals(dt: float) -> int:
    """Decimals of t on the page: Δt's own (export/numbers.py, as in the files), and at least 2,
    so the clock reads `t = 2.90 s` at Δt = 0.1 s and `t = 0.125 s` at Δt = 0.125 s."""
    return max(2, file_time_decimals(dt))


def constants_text(setup) -> str:
    """The scene's constants that are switched on, with units: `m = 10 kg, k = 40 N/m, ...`."""
    parts = []
    idle = idle_constants(setup.values)     # drive_axis where F0 = 0: its force is off
    for name, constant in setup.constants.items():
        value = setup.values[name]
        if name == "until" or value is None or (not isinstance(value, tuple) and value == 0) or name in idle:
            continue
        parts.append(f"{symbol(name)} = {format_value(value, constant.unit)}")
    lines, line = [], ""
    for part in parts:  # wrapped by hand: the caption keeps line breaks but does not wrap
        if line and len(line) + len(part) > 95:
            lines.append(line + ",")
            line = ""
        line = f"{line}, {part}" if line else part
    return "\n".join(lines + [line])

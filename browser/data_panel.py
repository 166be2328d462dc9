"""The page's measured data: Load data, the points on the position graph, and the Fit button.

A file arrives from the page's Load data button (its bytes are sent to the loopback server, POST
/data; browser/server/http_server.py) or from `--data FILE` on the command line. It is read by
lab/readers.py, as the command line reads it, and compared with the scene as it runs now by
lab/compare.py: the data's clock and zero are the file's own, so the comparison fits a time offset
t₀ and a position offset, and the graph shows each measured point at (t − t₀, position − offset),
on the model's own axes, with the RMS residual in metres. Fit fits the constants (those the scene
declares, LAB["fit"], or the names given with --fit) with the page's own integrator and Δt, and the
frame loop moves the sliders to the fitted values. A fit whose numbers cannot be trusted (lab/trust.py:
with the page's Euler-Cromer at Δt = 0.1 s, halving Δt moves them by many σ) shows its values
without ± figures, and in their place the sentence saying why.

Comparing and fitting run the engine many times, so they run on a thread of their own: the page's
frame loop keeps going, says "fitting…" meanwhile, and picks the answer up when it is there. Each
request has a number; an answer to a request overtaken by a newer one (a slider moved meanwhile) is
dropped.
"""
from __future__ import annotations

import html
import os
import queue
import threading

import numpy as np

from lab import LabError, compare, readers

from .controls import symbol
from .readout import length_text

MAX_DOTS = 1500              # measured points drawn at most (a long file is thinned evenly)
SENDING_SCRIPT = """<script>
window.smLoadData = function (input) {
  var file = input.files && input.files[0], note = document.getElementById('sm-data-note');
  input.value = '';  // choosing the same file again is a new choice
  if (!file) return;
  function say(text) { note.textContent = text; }
  if (file.size > %(limit)d) {
    say(file.name + ': the file is ' + Math.round(file.size / 1e6) + ' MB, more than the %(limit_mb)d MB ' +
        'this program reads; keep the part of the run you need');
    return;
  }
  say('sending ' + file.name + '\\u2026');
  file.arrayBuffer().then(function (bytes) {
    return fetch('/data', {method: 'POST', body: bytes, cache: 'no-store',
                           headers: {'X-File-Name': encodeURIComponent(file.name)}});
  }).then(function (reply) {
    if (reply.ok) { say(''); return; }
    return reply.text().then(function (text) { say(file.name + ': ' + (text || 'not accepted')); });
  }).catch(function () { say(file.name + ': could not be sent (has the program ended?)'); });
};
</script>"""


def load_button_html() -> str:
    """The Load data button: a hidden file input it opens, a note the page's script writes while
    it sends the file, and that script (vpython has no file input of its own)."""
    limit = readers.MAX_BYTES
    return ("<button type='button' id='sm-load-data' onclick=\"document.getElementById('sm-data-file').click()\">"
            "Load data</button>"
            "<input type='file' id='sm-data-file' style='display:none' "
            "accept='.csv,.txt,.tsv,.dat,.cmbl,text/csv,text/plain' onchange='smLoadData(this)'>"
            " <span id='sm-data-note'></span>"
            + SENDING_SCRIPT % {"limit": limit, "limit_mb": limit // 2 ** 20})


class MeasuredData:
    """The measured file shown on the page, its comparison with the scene, and the fits under way.

    measured    the file read (lab/readers.py's Measured), or None before one is loaded
    fit_names   the constants the Fit button fits (none: what the scene declares, LAB["fit"])
    coordinate  --coordinate, or None for the scene's plotted one
    sign        --data-sign (1 or −1), or None to try both (lab/compare.py)
    """

    def __init__(self, *, measured=None, fit_names=(), coordinate: str | None = None, sign: int | None = None):
        self.measured = measured
        self.fit_names = tuple(fit_names)
        self.fitting = ()         # the names of the fit under way
        self.coordinate, self.sign = coordinate, sign
        self.result = None        # the Comparison shown (lab/compare.py)
        self.shown_for = None     # the scene, values and integrator it was made for
        self.job = 0              # the newest request's number
        self.working = ""         # "reading", "comparing" or "fitting" while a thread works, else ""
        self.reading = ""         # the name of the file being read
        self.problem = ""         # the last one-line error (a bad file, a fit refused)
        self.answers: queue.SimpleQueue = queue.SimpleQueue()

    def load(self, raw: bytes, name: str, setup, integrator: str) -> None:
        """Read a file the page sent, then compare it with `setup`, on a thread of its own (a file
        of 200,000 rows takes seconds to read). A bad file keeps what was loaded before and says why."""
        self._start("reading", setup, integrator, (), None, upload=(raw, name))

    # ---- the work, on a thread ----

    def compare(self, setup, integrator: str, *, fit: bool = False) -> None:
        """Start comparing the data with `setup` (and fitting fit_names, if fit) on a thread of
        its own; a comparison already shown for the same constants is not made again, and none
        starts while a file is read (the frame loop asks again once it is in)."""
        if self.measured is None or self.working == "reading" or \
                (not fit and self.shown_for == _key(setup, integrator)):
            return
        names = (self.fit_names or tuple(setup.hooks.lab.get("fit", ()))) if fit else ()
        if fit and not names:
            self.problem = (f"scene {setup.name!r} declares nothing to fit; name the constants with --fit "
                            f"(e.g. --fit k,b)")
            return
        self.fitting = names
        self._start("fitting" if fit else "comparing", setup, integrator, names, self.measured)

    def _start(self, working: str, setup, integrator: str, names, measured, upload=None) -> None:
        self.job += 1
        self.working, self.problem = working, ""
        self.reading = upload[1] if upload else ""
        threading.Thread(target=self._work, args=(self.job, setup, integrator, names, measured, upload),
                         name="measured-data-fit", daemon=True).start()

    def coordinate_for(self, setup) -> str:
        """The coordinate compared with `setup`: --coordinate, else the one the scene plots."""
        return compare.coordinate_of(setup, self.coordinate)

    def _work(self, job: int, setup, integrator: str, names, measured, upload) -> None:
        loaded = None if upload is None else False      # False: a file sent but not read (yet)
        coordinate = self.coordinate_for(setup)
        try:
            if upload is not None:
                measured = loaded = readers.from_bytes(*upload, coordinate=coordinate)
            answer = compare.compare(setup, measured.t, measured.position, integrator=integrator,
                                     coordinate=coordinate, fit=names, sign=self.sign)
        except LabError as problem:
            answer = str(problem)
        except Exception as problem:  # a bug of ours: one line on the page, never a traceback
            answer = f"unexpected {type(problem).__name__}: {problem}"
        self.answers.put((job, integrator, bool(names), loaded, answer))

    def finished(self):
        """The newest request's answer if it has come: the Comparison (also kept as the one
        shown), or None after an error (kept in problem: a file that cannot be read leaves what was
        loaded before, a comparison that cannot be made takes the points off, a fit that cannot be
        made leaves the comparison shown); False while none has come."""
        newest = False
        while True:
            try:
                job, integrator, fit, loaded, answer = self.answers.get_nowait()
            except queue.Empty:
                return newest
            if job != self.job:
                continue          # overtaken by a newer request
            self.working = ""
            if loaded:
                self.measured, self.result, self.shown_for = loaded, None, None
            if isinstance(answer, str):
                self.problem, newest = answer, None
                if not fit and loaded is not False:   # a bad file leaves what was shown
                    self.result, self.shown_for = None, None
            else:
                self.result, self.shown_for, newest = answer, _key(answer.setup, integrator), answer

    # ---- what the page shows ----

    def points(self):
        """The measured points on the model's axes, (t − t₀, position − offset), at most MAX_DOTS."""
        result = self.result
        if result is None:
            return []
        keep = np.unique(np.linspace(0, result.points - 1, min(result.points, MAX_DOTS)).astype(int))
        t = result.t[keep] - result.t_offset.value
        y = result.sign * (result.data[keep] - result.position_offset.value)
        return [[float(a), float(b)] for a, b in zip(t, y) if np.isfinite(a) and np.isfinite(b)]

    def text(self, *, dt_slider: bool = False) -> str:
        """The caption's lines on the data (HTML): what was read, the offsets, the RMS residual,
        the fitted values, and what is under way or went wrong. dt_slider: the page has a Δt
        slider (else a Δt longer than the data's interval is a matter of the integrator menu)."""
        lines = []
        if self.problem:
            lines.append(f"<b>Data:</b> {html.escape(self.problem, quote=False)}")
        measured, result = self.measured, self.result
        if measured is not None:
            name = os.path.basename(measured.path)
            lines.append(f"<b>Data</b> {html.escape(name, quote=False)}: {measured.position.size} points, "
                         f"{html.escape(measured.choice, quote=False)}")
        if self.working:
            names = ", ".join(self.fitting)
            lines.append({"fitting": f"<i>fitting {names}…</i>", "comparing": "<i>comparing…</i>",
                          "reading": f"<i>reading {html.escape(self.reading, quote=False)}…</i>"}[self.working])
        elif result is not None:
            c = result.coordinate
            shown = f"{c} − {c}₀" if result.sign > 0 else f"−({c} − {c}₀)"
            t0, c0 = result.t_offset, result.position_offset
            if result.trust is not None and not result.trust.trusted:
                t0, c0 = t0.plain, c0.plain
            lines.append(f"<b>RMS residual = {length_text(result.rms)}</b>; blue dots: the data at t − t₀, {shown} "
                         f"with t₀ = {t0}, {c}₀ = {c0} (fitted offsets)")
            if result.sign < 0:
                lines.append(html.escape(result.sign_said, quote=False))
            untrusted = result.trust is not None and not result.trust.trusted
            if result.fitted and untrusted:      # the values without ± figures, and why in their place
                lines.append("<b>Fit:</b> <span class='sm-fit'>" + ", ".join(
                    f"{symbol(name)} = {estimate.plain}" for name, estimate in result.fitted.items()) + "</span>")
                lines.append("<b class='sm-untrusted'>" + html.escape(_untrusted_said(result.trust, dt_slider),
                                                                      quote=False) + "</b>")
            elif result.fitted:
                lines.append("<b>Fit:</b> <span class='sm-fit'>" + ", ".join(
                    f"{symbol(name)} = {estimate}" for name, estimate in result.fitted.items()) + "</span>")
            if result.slow_dt and not untrusted:
                lines.append(_slow_dt_note(*result.slow_dt, dt_slider=dt_slider))
            if result.misfit and not untrusted:
                lines.append(html.escape("Note: " + result.misfit, quote=False))
        elif measured is None and not self.problem:
            return ""
        return "\n".join(line.replace(" ± ", "\u00a0±\u00a0") for line in lines)


def _untrusted_said(trust, dt_slider: bool) -> str:
    """The fit's verdict as the page says it: the reasons, then what the page offers where its Δt
    moved the answer (the command line's advice names flags the page has none of)."""
    said = trust.said[0].upper() + trust.said[1:]
    if trust.smaller_dt == trust.smaller_dt:      # not NaN: the page's Δt moved the answer
        said += ("; move the Δt slider to " + f"{trust.smaller_dt:.3g} s or choose rk4 in the integrator menu"
                 if dt_slider else "; choose rk4 in the integrator menu")
    return said + "."


def _slow_dt_note(dt: float, interval: float, smaller: str, *, dt_slider: bool) -> str:
    """What a page user can do about a Δt longer than the data's sample interval (the command
    line's note says --set dt=...; the page may have no Δt slider)."""
    what = (f"move the Δt slider to {smaller} s" if dt_slider else
            "choose rk4 in the integrator menu (far closer to the real motion at the same Δt)")
    return (f"The model's Δt = {dt:g} s is longer than the data's sample interval {interval:.3g} s, so the "
            f"integrator's own error is in the comparison: {what}.")


def _key(setup, integrator: str):
    return setup.name, repr(sorted(setup.values.items())), integrator

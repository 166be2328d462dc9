"""The Web VPython program in GlowScript 3.2 itself: compiled by its RapydScript compiler and run in
headless Chromium, it prints the command line's answer digit for digit, and its arrow lines run.

GlowScript's files are the repository's own copy (export/glowscript/, pinned by sha256 in
export/offline_page.py): jQuery, jQuery UI, glow, RSrun and RScompiler, the five the offline page
holds. GlowScript's own editor page (GlowScript.html) would need its editor, split and font files
too; a page of a few lines loads the five and compiles the program as that page does
(`glowscript_compile(source, {lang: 'vpython', version: '3.2'})`, then `__main__()`), with
print() caught, and rate() answering at once (the program's arithmetic, not its real-time pace, is
what is checked: a run to t_end takes no wall time to speak of). tests/test_handout.py checks the answer's digits with GlowScript's str.format under
node as well.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from browser_support import launched, require_browser, wait_for
from test_export import main_py
from test_handout import headless_answer

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()
GLOWSCRIPT = Path(__file__).resolve().parent.parent / "export" / "glowscript"
LIBRARIES = ("jquery.min.js", "jquery-ui.custom.min.js", "glow.3.2.min.js", "RSrun.3.2.min.js",
             "RScompiler.3.2.min.js")

RUNNER = """<!DOCTYPE html><html><head><meta charset="utf-8"></head><body>
<div id="glowscript" class="glowscript"></div>
%(scripts)s
<script>
window.printed = []; window.failed = null; window.ended = false;
window.GSprint = function () { window.printed.push(Array.prototype.slice.call(arguments).join(" ")); };
var steps = 0;   // rate(): on at once, letting the page breathe every 1000 steps
window.rate = function () { steps += 1; return steps % 1000 ? Promise.resolve() : new Promise(function (go) { setTimeout(go, 0); }); };
var source = %(source)s;
try {
  var compiled = window.glowscript_compile(source, {lang: "vpython", version: "3.2"});
  window.__context = {glowscript_container: $("#glowscript")};
  eval(compiled);
  __main__().then(function () { window.ended = true; }, function (e) { window.failed = String(e); });
} catch (e) { window.failed = String(e); }
</script></body></html>
"""


def run_in_glowscript(page, program: str, answers: int, folder: Path) -> list[str]:
    """Run `program` in GlowScript 3.2; its printed lines once `answers` answers are in."""
    errors = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    scripts = "\n".join(f'<script src="{(GLOWSCRIPT / name).as_uri()}"></script>' for name in LIBRARIES)
    runner = folder / "runner.html"
    runner.write_text(RUNNER % {"scripts": scripts, "source": json.dumps(program).replace("</", "<\\/")},
                      encoding="utf-8")
    page.goto(runner.as_uri())

    def printed():
        failed = page.evaluate("window.failed")
        assert not failed and not errors, (failed, errors)
        lines = page.evaluate("window.printed")
        return lines if sum("kg·m/s" in line for line in lines) >= answers else None

    return wait_for(printed, what="the program's answer in GlowScript")


@pytest.fixture(scope="module")
def chromium(browser):
    return browser       # conftest's: the module's Chromium


@pytest.mark.parametrize("case, program", [
    (("damped",), ("--until", "1", "--arrows", "forces,split")),
    (("vertical",), ("--until", "1", "--arrows", "p,F_net,forces,split")),
    (("pendulum", "--until", "1"), ("--arrows", "forces,split")),
    (("driven", "--until", "1"), ()),
    # p = 1.632e-05 kg·m/s: Web VPython's own '{:.6g}' wrote 1.63200e-5
    (("vertical", "--set", "m=0.00001", "--set", "k=0.0004"), ("--until", "1")),
])
def test_the_web_vpython_program_answers_as_the_command_line_in_glowscript(case, program, chromium, tmp_path):
    """The question's command line (case) and what only the program is given (program)."""
    done = main_py(*case, *program, "--webvpython", "-")
    assert done.returncode == 0, done.stderr
    page = chromium.new_page(viewport={"width": 640, "height": 480})
    try:
        lines = run_in_glowscript(page, done.stdout, answers=1, folder=tmp_path)
        # the run goes on to t_end (--until 1: 1 s): its arrow lines run without error to its end
        page.wait_for_function("window.failed !== null || window.ended")
        assert page.evaluate("window.failed") is None
    finally:
        page.close()
    assert lines == [headless_answer(*case)]

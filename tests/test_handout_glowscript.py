"""The Web VPython program in GlowScript 3.2 itself: compiled by its RapydScript compiler and run in
headless Chromium, it prints the command line's answer digit for digit, and its arrow lines run.

GlowScript's offline package (GlowScriptOffline3.2.zip in github.com/vpython/glowscript, about
4 MB unzipped) is not kept in this repository: unzip it and set GLOWSCRIPT_OFFLINE to its
GlowScriptOffline folder (the one with GlowScript.html) to run these tests; they are skipped
without it. tests/test_handout.py checks the answer's digits with GlowScript's str.format under
node on every run.
"""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from browser_support import launched, require_browser, wait_for
from test_export import main_py
from test_handout import headless_answer

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()
OFFLINE = Path(os.environ.get("GLOWSCRIPT_OFFLINE", "")).expanduser()
if not os.environ.get("GLOWSCRIPT_OFFLINE") or not (OFFLINE / "GlowScript.html").is_file():
    pytest.skip("set GLOWSCRIPT_OFFLINE to an unzipped GlowScriptOffline3.2 folder (github.com/vpython/glowscript)",
                allow_module_level=True)


def run_in_glowscript(page, program: str, answers: int) -> str:
    """Run `program` in GlowScript's offline page; its printed text once `answers` answers are in."""
    errors = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    page.goto((OFFLINE / "GlowScript.html").as_uri())
    page.wait_for_function("typeof GSedit !== 'undefined' && GSedit.editarea !== null")
    page.evaluate("source => GSedit.setValue(source)", program)
    page.evaluate("runCode()")

    def printed():
        failed = page.evaluate("() => document.getElementById('gserrors').innerText").strip()
        assert not failed and not errors, (failed, errors)
        text = page.evaluate("() => { const p = document.getElementById('print'); return p ? p.value : '' }")
        return text if text.count("kg·m/s") >= answers else None

    return wait_for(printed, timeout=240, what="the program's answer in GlowScript")


@pytest.mark.parametrize("case, program", [
    (("damped",), ("--until", "1", "--arrows", "forces,split")),
    (("vertical",), ("--until", "1", "--arrows", "p,F_net,forces,split")),
    (("pendulum", "--until", "1"), ("--arrows", "forces,split")),
    (("driven", "--until", "1"), ()),
    # p = 1.632e-05 kg·m/s: Web VPython's own '{:.6g}' wrote 1.63200e-5
    (("vertical", "--set", "m=0.00001", "--set", "k=0.0004"), ("--until", "1")),
])
def test_the_web_vpython_program_answers_as_the_command_line_in_glowscript(case, program):
    """The question's command line (case) and what only the program is given (program)."""
    done = main_py(*case, *program, "--webvpython", "-")
    assert done.returncode == 0, done.stderr
    with launched(sync_api, "--allow-file-access-from-files") as chromium:
        page = chromium.new_page(viewport={"width": 1280, "height": 800})
        text = run_in_glowscript(page, done.stdout, answers=1)
        page.wait_for_timeout(3000)   # the run goes on to t_end: its arrow lines run without error
        assert not page.evaluate("() => document.getElementById('gserrors').innerText").strip()
    assert text.strip().splitlines() == [headless_answer(*case)]

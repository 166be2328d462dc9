"""Friction's lines in Web VPython, in GlowScript 3.2 itself: the law's three cases (sliding, held,
starting) and the stop rule compile in its RapydScript and run in headless Chromium, and the
program prints what the same program prints under Python, digit for digit.

GlowScript's runtime is the one kept in export/glowscript (tests/test_handout_glowscript.py).
"""
from __future__ import annotations

import re

from browser_support import wait_for
from test_export import main_py, run_program, stand_in  # noqa: F401  (stand_in is a fixture)
from test_handout_glowscript import pytestmark, run_in_glowscript  # noqa: F401

# μ_k = 0.3 stops the top block within 1.5 s: by 2 s it has slid, turned, stopped and been held.
CASE = ("friction", "--set", "mu_k=0.3", "--set", "mu_s=0.5", "--set", "until=2", "--until", "2.5")


def test_friction_in_web_vpython_answers_as_in_python(stand_in, tmp_path, browser):  # noqa: F811
    path = tmp_path / "friction.py"
    assert main_py(*CASE, "--vpython", str(path)).returncode == 0
    printed = []
    run_program(path, stand_in, printed=printed)
    web = main_py(*CASE, "--webvpython", "-")
    assert web.returncode == 0, web.stderr
    assert "if dot(ps, ps + Fs*dt) <=" in web.stdout
    page = browser.new_page(viewport={"width": 640, "height": 480})   # conftest's: the module's Chromium
    errors = []
    page.on("pageerror", lambda error: errors.append(str(error)))
    try:
        lines = run_in_glowscript(page, web.stdout, answers=len(printed), folder=tmp_path)
        # on to t_end: the held block's lines run on without error until the program ends
        wait_for(lambda: page.evaluate("window.ended || window.failed"), what="the program to end in GlowScript")
        assert page.evaluate("window.ended") and not page.evaluate("window.failed") and not errors, \
            (page.evaluate("window.failed"), errors)
    finally:
        page.close()
    answers = [line for line in lines if re.search(r"kg·m/s", line)]
    assert answers == printed

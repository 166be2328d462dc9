"""A written force in the Web VPython program, run by GlowScript 3.2 itself: it prints the command
line's answer digit for digit (GlowScript reads the force's line as Python does: the writer puts
brackets where the two would differ, 2**(3**2), −(x**2))."""
from __future__ import annotations

import pytest

from browser_support import require_browser
from test_export import main_py
from test_handout import headless_answer
from test_handout_glowscript import run_in_glowscript
from test_written_force import FORCES

pytestmark = pytest.mark.browser
require_browser()

# Each runs 0.3 s of Δt = 0.01 s in real time (GlowScript's rate()): the forms the writer brackets
# (−(x**2), 2**(3**2), a unary minus in a product), hat of 0, cross, exp, every integrator.
CASES = [
    (FORCES[0], "euler-cromer"),
    (FORCES[1], "rk4"),
    (FORCES[2], "verlet"),
    (FORCES[3], "euler-cromer"),
    (FORCES[4], "rk4"),
    ("2**3**2*vector(0, 0.01, 0) - (-v)*0.1 + -(2**2)*vector(0.01, 0, 0)", "verlet"),
    ("vector(0, 50, 0)", "euler"),
]


@pytest.mark.parametrize("text, method", CASES)
def test_the_force_answers_as_the_command_line_in_glowscript(text, method, browser, tmp_path):
    case = ("vertical", "--set", "dt=0.01", "--set", "until=0.3", "--integrator", method,
            "--force", f"added={text}")
    done = main_py(*case, "--webvpython", "-", "--until", "0.3", "--arrows", "p,F_net,forces,split")
    assert done.returncode == 0, done.stderr
    page = browser.new_page(viewport={"width": 1024, "height": 768})
    try:
        lines = run_in_glowscript(page, done.stdout, answers=1, folder=tmp_path)
        page.wait_for_function("window.failed !== null || window.ended")
        assert page.evaluate("window.failed") is None    # its arrow of the force moved to the end
    finally:
        page.close()
    assert lines == [headless_answer(*case)]

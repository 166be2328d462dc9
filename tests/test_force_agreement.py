"""The same numbers everywhere (issue 42): a force added on the local page, on the offline page,
in the programs each page's "Download my program" gives (run in CPython with vpython's own vector
class, and in GlowScript 3.2), and on the command line (`--force`) answers the question alike, to
the 6 significant digits the answers are printed to.

The case is the issue's: a constant 50 N push upward on vertical's 10 kg mass, which must give the
same answer as `--set g=4.8` (m g − 50 N = 10 kg × 4.8 m/s²). Each page reaches the question time
with the jump; the local page's answer is its Download CSV's row at that time.
"""
from __future__ import annotations

import csv
import io

import pytest

from browser_support import jump_offline, jump_to, require_browser

pytestmark = pytest.mark.browser
require_browser()

from export.step_update import number, vector  # noqa: E402
from test_export import main_py, run_program, stand_in  # noqa: E402,F401  (a fixture)
from test_force_box_browser import Page  # noqa: E402
from test_handout import headless_answer  # noqa: E402
from test_handout_glowscript import run_in_glowscript  # noqa: E402
from test_jump_browser import download_csv  # noqa: E402
from test_offline_page_browser import Offline  # noqa: E402

PUSH = "vector(0, 50, 0)"
T = 0.2       # s: vertical's question time


def answer(t, r, p) -> str:
    """The answer as every front end prints it: `at t = 0.2 s: r = < 0, -1.58288, 0 > m, p = ...`."""
    return f"at t = {number(t)} s: r = {vector(r, 'm')}, p = {vector(p, 'kg·m/s')}"


def test_the_push_answers_alike_everywhere(browser, stand_in, tmp_path):  # noqa: F811
    answers = {"--force": headless_answer("vertical", "--force", f"push={PUSH}"),
               "--set g=4.8": headless_answer("vertical", "--set", "g=4.8")}

    local = Page(browser)
    try:
        local.add("push", PUSH, said="push added")
        assert jump_to(local.page, T) == pytest.approx(T)
        rows = list(csv.DictReader(io.StringIO(download_csv(local.page))))
        row = next(row for row in rows if float(row["t"]) == T)
        answers["local page"] = answer(T, [float(row[c]) for c in "xyz"], [float(row[c]) for c in ("px", "py", "pz")])
        with local.page.expect_download() as caught:
            local.page.get_by_role("button", name="Download my program").click()
        python_program = tmp_path / "vertical.py"
        caught.value.save_as(python_program)
    finally:
        local.close()
    printed = []
    run_program(python_program, stand_in, printed=printed)
    answers["local page's program, CPython"] = printed[0].strip()

    page_file = tmp_path / "vertical.html"
    assert main_py("vertical", "--html", str(page_file)).returncode == 0
    offline = Offline(browser, page_file)
    try:
        p = offline.page
        p.fill("#force-name", "push")
        p.fill("#force-text", PUSH)
        p.press("#force-text", "Enter")
        jump_offline(p, T)
        answers["offline page"] = offline.text("answer").strip()
        with p.expect_download() as caught:
            p.click("#force-download")
        web_program = caught.value.path().read_text(encoding="utf-8")
    finally:
        offline.close()
    glowscript = browser.new_page()
    try:
        answers["offline page's program, GlowScript 3.2"] = run_in_glowscript(glowscript, web_program, answers=1,
                                                                              folder=tmp_path)[0].strip()
    finally:
        glowscript.close()

    expected = answers["--force"]
    assert expected.startswith("at t = 0.2 s: r = < 0, -1.58288, 0 > m")
    assert {source: said for source, said in answers.items() if said != expected} == {}, expected

"""The offline page's Add a force box (export/force_box.js, export/offline_forces.py) in headless
Chromium, from file://:

* its reader follows the grammar's rules as physics/expression.py does: the same forces taken, the
  same written back, the same refused with the same line (a slip of syntax: both say they cannot
  read it);
* the program it runs, and the one Download my program gives, is the writer's own for those
  forces (`--force`), line for line but for the file's framing of the picture;
* a force added runs from t = 0 with its arrow and the run before dimmed beside it, and answers as
  `--headless --force` does; a force that cannot be read, is no vector, has no value at t = 0 or
  blows the run up is one line, and the run before it stays;
* screenshots at three sizes and in projector mode.

Tests ask for time with the jump (tests/browser_support.py's jump_offline), never wait for it.
"""
from __future__ import annotations

import random

import pytest

from browser_support import jump_offline, require_browser, screenshot_folder
from test_force_grammar import ACCEPTED, REFUSED
from test_offline_page_browser import Offline, json_answers
from test_export import main_py

pytestmark = pytest.mark.browser
require_browser()

from export.offline_page import FRAMING  # noqa: E402
from export.vpython_program import program  # noqa: E402
from physics.expression import ExpressionError, parse, program_text  # noqa: E402
from scenes import catalog  # noqa: E402
from scenes._view import DEFAULT_VIEW  # noqa: E402

# Each text as the page's reader reads it: all at once (the page is busy drawing between calls).
READ = """texts => texts.map(text => { const box = window.offlineForces.forTests;
  try { const law = box.parse(text); const spelled = {};
        ['r', 'v', 'p', 't', 'm', 'k', 'b', 'g', 'dt', 'pi'].forEach(n => spelled[n] = n);
        return {text: law.text, written: box.programText(law.tree, spelled)}; }
  catch (problem) { if (problem instanceof box.Refused) return {refused: problem.message}; throw problem; } })"""


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """Each scene's offline page, written once for the module: {scene: path}."""
    folder = tmp_path_factory.mktemp("forces")
    made = {}

    def page_for(scene, *options):
        key = (scene, *options)
        if key not in made:
            path = folder / f"{scene}-{len(made)}.html"
            done = main_py(scene, *options, "--html", str(path))
            assert done.returncode == 0, done.stderr
            made[key] = path
        return made[key]
    return page_for


def python_reads(text: str) -> dict:
    try:
        law = parse(text)
    except ExpressionError as problem:
        return {"refused": str(problem)}
    return {"text": law.text, "written": program_text(law.tree, {name: name for name in
                                                                 ("r", "v", "p", "t", "m", "k", "b", "g", "dt", "pi")})}


def tricky() -> list[str]:
    """Texts near the grammar's edges: each accepted one cut, doubled or with a character changed."""
    chosen = random.Random(42)
    texts = []
    for text, _ in ACCEPTED:
        for _ in range(4):
            at = chosen.randrange(len(text) + 1)
            texts += [text[:at], text[:at] + chosen.choice("()*,.+-^[ x2e") + text[at:], text + text[at:]]
    return texts


def test_the_pages_reader_takes_refuses_and_writes_as_the_grammar(chromium, pages):
    page = Offline(chromium, pages("vertical"))
    try:
        page.page.wait_for_function("() => window.offlineForces !== undefined")
        texts = [text for text, _ in ACCEPTED] + [text for text, _ in REFUSED] + tricky()
        for text, read in zip(texts, page.page.evaluate(READ, texts)):
            expected = python_reads(text)
            if "cannot read the force" in expected.get("refused", ""):      # a slip of syntax: both say so
                assert read.get("refused", "").startswith("cannot read the force"), (text, read)
            else:
                assert read == expected, text
        assert not page.errors
    finally:
        page.close()


CASES = [
    ("vertical", "euler-cromer", [("push", "vector(0, 50, 0)")]),
    ("vertical", "rk4", [("wind", "-0.5*mag(v)*v"), ("magnet", "-3/mag(r - vector(0,-4,0))**3 * (r - vector(0,-4,0))")]),
    ("vertical", "verlet", [("brake", "-b*v - k*0.01*r + 2**-t*vector(0, 0, 1)")]),
    ("vertical", "euler", [("a", "vector(1, 0, 0)"), ("b2", "-(2**2)*vector(0, 0.1, 0)"), ("c", "-p*0.01")]),
    ("friction", "euler-cromer", [("push", "vector(0.5*cos(t), 0, 0)")]),
    ("friction", "rk4", [("wind", "-0.1*mag(v)*v")]),
    ("integrators", None, [("push", "vector(-0.5, 0, 0)*exp(-t)")]),
]


def _code(text: str) -> list[str]:
    """A program's lines but the framing of its picture (the page keeps the file's)."""
    return [line for line in text.splitlines() if not line.startswith(FRAMING)]


@pytest.mark.parametrize("scene, integrator, forces", CASES)
def test_the_program_with_the_forces_is_the_writers(scene, integrator, forces, chromium, pages):
    """The page's program and Download my program's, for these forces, are what the writer writes
    for `--force` (framing aside): every F_net worked out with them, their arrows, their constants."""
    page = Offline(chromium, pages(scene, *(("--integrator", integrator) if integrator else ())))
    try:
        page.page.wait_for_function("() => window.offlineForces !== undefined")
        setup = catalog.configure(scene).with_written(forces)
        key = integrator or page.page.evaluate("() => window.offlineState().integrator")
        shown = tuple({**DEFAULT_VIEW, **catalog.load(scene).VIEW}["arrows"])
        for handout in (False, True):
            got = page.page.evaluate("""([key, forces, handout]) => { const box = window.offlineForces.forTests;
                const read = forces.map(pair => box.read(pair[0], pair[1], []));
                return box.program(key, read, handout); }""", [key, forces, handout])
            arrows = shown if not handout else tuple(dict.fromkeys((*shown, "forces")))
            expected = program(setup, integrator=integrator, web=True, page=not handout, arrows=arrows)
            assert _code(got) == _code(expected), f"{scene} {integrator} handout={handout}"
    finally:
        page.close()


def test_a_force_added_runs_with_its_arrow_beside_the_run_before(chromium, pages):
    page = Offline(chromium, pages("vertical"))
    try:
        p = page.page
        jump_offline(p, 1.0)
        p.select_option("#force-example", "0")                  # a constant push, then its numbers changed
        assert p.input_value("#force-name") == "push"
        p.fill("#force-text", "vector(0, 50, 0)")
        p.press("#force-text", "Enter")                         # Enter adds it
        assert "push added" in page.text("force-said")
        assert page.text("force-line") == "Fnet = Fspring + Fgravity + F_push"
        state = jump_offline(p, 0.2)
        assert page.text("answer").splitlines() == json_answers("vertical", "--force", "push=vector(0, 50, 0)")
        assert state["arrows"]["forces"]                        # each force's arrow, the push's too
        series = p.evaluate("""() => window.offlineForces.forTests.lastGraph().graph_series.map(
            s => ({label: s.label, dimmed: !!s.__dimmed, points: s.data.length}))""")
        dimmed = [s for s in series if s["dimmed"]]
        assert dimmed and dimmed[0]["label"] == "without push" and dimmed[0]["points"] >= 10   # the 1 s run before
        assert "F_push = vector(0, 50, 0)" in page.text("program-text")
        assert "#" not in p.evaluate("location.hash") or "push" not in p.evaluate("location.hash")   # no force in a link
        p.screenshot(path=str(screenshot_folder() / "force-box-offline-1280.png"), full_page=True)
        assert not page.errors
    finally:
        page.close()


@pytest.mark.parametrize("name, text, said", [
    ("push", "vector(2, 0", "cannot read the force: a ( is not closed"),
    ("push", "-0.5*mag(v)", "is a number, but a force is a vector"),
    ("spring", "vector(2, 0, 0)", "the name spring is taken"),
    ("pull", "-1/mag(r - vector(0, -1.5, 0))*r", "the force pull has no value at t = 0"),
    ("brake", "-mu*v", "unknown name mu"),
])
def test_a_force_that_cannot_run_is_one_line_and_the_run_stays(name, text, said, chromium, pages):
    page = Offline(chromium, pages("vertical"))
    try:
        p = page.page
        jump_offline(p, 0.5)
        program_before = page.text("program-text")
        p.fill("#force-name", name)
        p.fill("#force-text", text)
        p.click("#force-add")
        message = page.text("force-said")
        assert said in message and message.endswith("the run before is still on") and "\n" not in message
        state = p.evaluate("window.offlineState()")
        assert state["n"] == 5 and state["paused"]               # not started again
        assert page.text("program-text") == program_before
        assert not page.errors
    finally:
        page.close()


def test_a_force_that_blows_the_run_up_goes_back_to_the_run_before(chromium, pages):
    page = Offline(chromium, pages("vertical"))
    try:
        p = page.page
        p.fill("#force-name", "stiff")
        p.fill("#force-text", "-1e6*r")
        p.click("#force-add")     # the run, at 1×, blows up within its first steps: the page says so
        p.wait_for_function("() => document.getElementById('force-said').textContent.includes('blow up')")
        assert page.text("force-said").startswith("the force stiff makes the run blow up at t = ")
        assert p.evaluate("window.offlineForces.forTests.forces().length") == 0
        p.wait_for_function("() => !document.getElementById('program-text').textContent.includes('F_stiff')")
        state = jump_offline(p, 0.2)
        assert page.text("answer").splitlines() == json_answers("vertical")
        assert state["n"] == 2
    finally:
        page.close()


def test_forces_are_removed_and_the_files_program_is_one_click_away(chromium, pages):
    page = Offline(chromium, pages("vertical"))
    try:
        p = page.page
        for name, text in (("push", "vector(0, 50, 0)"), ("wind", "-0.5*mag(v)*v")):
            p.fill("#force-name", name)
            p.fill("#force-text", text)
            p.press("#force-text", "Enter")
        assert page.text("force-line") == "Fnet = Fspring + Fgravity + F_push + F_wind"
        p.get_by_role("button", name="Remove push").click()
        assert page.text("force-line") == "Fnet = Fspring + Fgravity + F_wind"
        jump_offline(p, 0.2)
        assert page.text("answer").splitlines() == json_answers("vertical", "--force", "wind=-0.5*mag(v)*v")
        p.get_by_role("button", name="Back to the file's program").click()
        assert page.text("force-line") == "Fnet = Fspring + Fgravity"
        jump_offline(p, 0.2)
        assert page.text("answer").splitlines() == json_answers("vertical")
        assert p.is_disabled("#force-reset")
    finally:
        page.close()


def test_download_my_program_is_the_handout_with_the_force(chromium, pages, tmp_path):
    page = Offline(chromium, pages("vertical"))
    try:
        p = page.page
        p.fill("#force-name", "wind")
        p.fill("#force-text", "-0.5*mag(v)*v")
        p.press("#force-text", "Enter")
        with p.expect_download() as caught:
            p.click("#force-download")
        path = tmp_path / "vertical.py"
        caught.value.save_as(path)
        expected = main_py("vertical", "--webvpython", "-", "--force", "wind=-0.5*mag(v)*v",
                           "--arrows", "p,F_net,forces")
        assert _code(path.read_text(encoding="utf-8")) == _code(expected.stdout)
    finally:
        page.close()


@pytest.mark.parametrize("size, projector", [((1024, 768), False), ((1280, 800), False), ((1920, 1080), False),
                                             ((1280, 800), True)])
def test_screenshots_of_the_box_with_a_force_added(size, projector, chromium, pages):
    page = Offline(chromium, pages("vertical"), size=size)
    try:
        p = page.page
        if projector:
            p.check("#projector")
        jump_offline(p, 1.5)
        p.select_option("#force-example", "1")
        p.press("#force-text", "Enter")
        jump_offline(p, 3.0)
        p.locator("#force-box").scroll_into_view_if_needed()
        name = f"force-box-offline-{size[0]}x{size[1]}{'-projector' if projector else ''}.png"
        p.screenshot(path=str(screenshot_folder() / name))
        box = p.locator("#force-box").bounding_box()
        assert box["width"] <= size[0]                            # the box fits the window's width
        font = p.evaluate("parseFloat(getComputedStyle(document.getElementById('force-text')).fontSize)")
        assert font >= (22 if projector else 18)                  # read from the back of the room
    finally:
        page.close()


@pytest.fixture(scope="module")
def chromium(browser):
    return browser

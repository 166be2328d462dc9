"""The offline page (`main.py SCENE --html FILE.html`) in headless Chromium, opened from file:// with
every request other than the file itself refused and counted: each scene draws and prints
--headless's answer; Step writes out the update as the local page does; Reset, a slider, the speed
menu and the keys work; a set-up in the address gives `--headless --set`'s answer; and a bad one
is one line on the page while the file's own set-up runs.

One browser for the module (software WebGL is slow here); every wait is for an event on the page.
"""
from __future__ import annotations

import json
import re

import numpy as np
import pytest

from browser_support import require_browser, screenshot_folder, shaded_like
from test_export import main_py
from test_handout import edge_values, headless_answer

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()

from export.palette import MASS_COLOURS  # noqa: E402
from export.step_update import number, shown, step_lines, update_force, vector  # noqa: E402
from scenes import catalog  # noqa: E402
from scenes._view import DEFAULT_VIEW  # noqa: E402

SCENES = list(catalog.SCENE_NAMES)
SHORT = {"resonance": ("--set", "until=5", "--set", "settle=0.5", "--set", "periods=0.1")}   # 250 steps, not 2,500
ANSWER = re.compile(r"at t = (\S+) s: r = (< .* >) m, p = (< .* >) kg·m/s$")


@pytest.fixture(scope="module")
def chromium(browser):
    return browser       # conftest's: the module's Chromium


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """Each scene's offline page, written once for the module: {scene: path}."""
    folder = tmp_path_factory.mktemp("offline")
    paths = {}

    def page_for(scene, *options):
        key = (scene, *options)
        if key not in paths:
            path = folder / f"{scene}-{len(paths)}.html"
            done = main_py(scene, *options, "--html", str(path))
            assert done.returncode == 0, done.stderr
            paths[key] = path
        return paths[key]
    return page_for


class Offline:
    """One offline page open in its own browser context, with every request that is not the file
    itself refused and kept in `refused`."""

    def __init__(self, chromium, path, fragment: str = "", size=(1280, 800)):
        self.url = path.as_uri()
        self.refused = []
        self.errors = []
        self.context = chromium.new_context(viewport={"width": size[0], "height": size[1]})
        self.context.route("**/*", self._route)
        self.page = self.context.new_page()
        self.page.on("pageerror", lambda error: self.errors.append(str(error)))
        self.page.goto(self.url + fragment)

    def _route(self, route):
        if route.request.url.split("#")[0] == self.url:
            route.continue_()
        else:
            self.refused.append(route.request.url)
            route.abort()

    def answers(self, count: int, *, patience_s: float = 120) -> list[str]:
        """The printed answer's lines, once there are `count` of them (waiting up to patience_s)."""
        assert not self.refused, self.refused
        self.page.wait_for_function(
            "n => { const s = document.getElementById('status').textContent;"
            " return s.startsWith('The program stopped') || document.getElementById('answer').textContent"
            ".split('\\n').filter(x => x).length >= n; }", arg=count, timeout=patience_s * 1000)
        assert not self.text("status").startswith("The program stopped"), self.text("status")
        return self.text("answer").splitlines()

    def text(self, element: str) -> str:
        return self.page.evaluate("id => document.getElementById(id).textContent", element)

    def fastest(self):
        self.page.select_option("#speed", "4×")

    def close(self):
        self.context.close()


def json_answers(*args) -> list[str]:
    """Each mass's answer as the program prints it (the part after its label), from --headless --json."""
    done = main_py(*args, "--headless", "--json")
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    bodies = report.get("bodies") or [report]
    t = number(report["t"])
    return [f"at t = {t} s: r = {vector(body['r'])} m, p = {vector(body['p'])} kg·m/s" for body in bodies]


# Each scene runs to its question time in the page (up to 50 s of simulated time; resonance's 39
# springs with rk4): with software WebGL on a busy 2-core machine that is many minutes, so the
# wait is for the answer itself, for up to an hour.
@pytest.mark.timeout(3600)
@pytest.mark.parametrize("scene", SCENES)
def test_each_scene_runs_from_file_with_no_request_draws_and_prints_the_headless_answer(scene, chromium, written):
    """No request leaves the page; the 3-D view draws the scene's masses in their colours; the
    answer printed at the question time is --headless's (its text for one mass, its numbers for
    several)."""
    # resonance's question time (50 s of 39 springs with rk4) took GlowScript under software WebGL
    # over half an hour on a 2-core machine: its answer at 5 s checks the same program as well
    options = SHORT.get(scene, ())
    page = Offline(chromium, written(scene, *options))
    try:
        page.fastest()
        expected = json_answers(scene, *options)
        # software WebGL on a busy machine draws a frame in a second or more, and a scene's question
        # time is up to 50 s of simulated time: wait long, for the answer itself
        lines = page.answers(len(expected), patience_s=3300)
        canvas = page.page.locator("canvas").first
        canvas.screenshot(path=str(screenshot_folder() / f"offline-{scene}.png"))
        image = Image.open(screenshot_folder() / f"offline-{scene}.png").convert("RGB")
        assert not page.refused and not page.errors, (page.refused, page.errors)
    finally:
        page.close()
    assert len(lines) == len(expected)
    assert [line[line.index("at t = "):] for line in lines] == expected
    if len(expected) == 1:
        assert lines == [headless_answer(scene)]
    drawn = sum(shaded_like(image, colour) for colour in MASS_COLOURS[:len(expected)])   # euler's runs off
    assert drawn > 30, "no mass is drawn in its colour"



# ---- the lesson's controls ----

def wait_state(page: Offline, condition: str):
    """Wait until offlineState() meets `condition`, a JavaScript expression of `state`."""
    page.page.wait_for_function(f"() => {{ const state = window.offlineState(); return {condition}; }}")
    return page.page.evaluate("window.offlineState()")


def expected_step(scene: str, steps: int, *options) -> str:
    """The local page's Step read-out after Reset and `steps` Steps (the engine one Δt at a time,
    export/step_update.py's step_lines for each mass), as the offline page writes it."""
    setup = catalog.configure(scene)
    model = setup.build()
    engine = model.simulation()
    for _ in range(steps):
        before = engine.state
        t_i, r_i, p_i = before.t, np.array(before.r), np.array(before.p)
        engine.advance(1)
    after = engine.state
    F = update_force(model.forces, engine.methods, t_i=t_i, r_i=r_i, p_i=p_i, p_f=after.p, m=after.m, dt=model.dt)
    blocks = []
    for i in range(min(after.count, 4)):
        lines = step_lines(method=engine.methods[i], dt=model.dt, t_f=after.t, m=float(after.m[i]), F_net=F[i],
                           p_i=p_i[i], p_f=after.p[i], r_i=r_i[i], r_f=after.r[i])
        blocks.append((f"{model.labels[i]}\n" if after.count > 1 else "") + "\n".join(lines))
    more = f"\n(and {after.count - 4} more masses)" if after.count > 4 else ""
    return "\n".join(blocks) + more


@pytest.mark.parametrize("scene", ["vertical", "regimes"])
def test_pause_reset_and_step_write_out_the_update_as_the_local_page(scene, chromium, written):
    """Pause, Reset (back to t = 0, still paused, nothing printed), then two Steps: t = 2 Δt and
    the second update written out digit for digit as the local page writes it (F_net, p_f = p_i +
    F_net Δt, v_f, r_f), for each mass; Run carries on to the answer."""
    page = Offline(chromium, written(scene))
    try:
        page.page.click("#run")
        wait_state(page, "state.paused")
        assert page.text("run") == "Run"
        page.page.click("#reset")
        wait_state(page, "state.paused && state.n === 0")
        assert page.text("answer") == "" and page.text("step") == ""
        page.page.click("#step-button")
        wait_state(page, "state.n === 1")
        page.page.wait_for_function("document.getElementById('step').textContent.length > 0")
        page.page.click("#step-button")
        wait_state(page, "state.n === 2")
        page.page.wait_for_function("t => document.getElementById('step').textContent.includes('t = ' + t + ' s')",
                                    arg=number(2 * catalog.configure(scene).build().dt))
        step_text = page.text("step")
        dt = catalog.configure(scene).build().dt
        shown_time = f"t = {2 * dt:.{max(2, len(repr(dt).partition('.')[2]))}f} s"
        page.page.wait_for_function("t => document.getElementById('time').textContent === t", arg=shown_time)
        assert not page.refused and not page.errors
    finally:
        page.close()
    assert step_text == expected_step(scene, 2)


def test_the_keys_run_step_and_reset(chromium, written):
    """Space pauses, → steps one Δt, R starts again from t = 0, + and − change the speed."""
    page = Offline(chromium, written("vertical"))
    try:
        page.page.keyboard.press("Space")
        wait_state(page, "state.paused")
        page.page.keyboard.press("r")
        wait_state(page, "state.paused && state.n === 0")
        page.page.keyboard.press("ArrowRight")
        wait_state(page, "state.n === 1")
        page.page.keyboard.press("+")
        assert wait_state(page, "state.speed === 2")["n"] == 1
        page.page.keyboard.press("-")
        page.page.keyboard.press("-")
        wait_state(page, "state.speed === 0.5")
        page.page.keyboard.press("Space")
        wait_state(page, "!state.paused && state.n > 1")
    finally:
        page.close()


def test_a_slider_restarts_the_run_with_its_value(chromium, written):
    """Moving m's slider to 12.5 kg restarts from t = 0 and prints `--headless --set m=12.5`'s
    answer; the value and its unit stand beside the slider, and the address carries the set-up."""
    page = Offline(chromium, written("vertical"))
    try:
        page.answers(1)
        page.page.evaluate("""() => { const s = document.getElementById('slider-m'); s.value = '12.5';
                                      s.dispatchEvent(new Event('input')); s.dispatchEvent(new Event('change')); }""")
        wait_state(page, "state.values.m === 12.5")
        lines = page.answers(1)
        label = page.text("slider-m-value")
        link = page.page.evaluate("document.getElementById('link').value")
        address = page.page.evaluate("location.hash")
    finally:
        page.close()
    assert lines == [headless_answer("vertical", "--set", "m=12.5")]
    assert label == "m = 12.5 kg" and link == address == "#m=12.5"


def test_a_set_up_in_the_address_gives_the_command_lines_answer(chromium, written):
    """vertical.html#k=60&dt=0.05&integrator=rk4 prints `--headless --set k=60 --set dt=0.05
    --integrator rk4`'s answer, with k's slider at 60 N/m."""
    page = Offline(chromium, written("vertical"), "#k=60&dt=0.05&integrator=rk4")
    try:
        lines = page.answers(1)
        status, label = page.text("status"), page.text("slider-k-value")
        state = page.page.evaluate("window.offlineState()")
        assert not page.refused and not page.errors
    finally:
        page.close()
    assert lines == [headless_answer("vertical", "--set", "k=60", "--set", "dt=0.05", "--integrator", "rk4")]
    assert status == "" and label == "k = 60 N/m" and state["integrator"] == "rk4"


@pytest.mark.parametrize("fragment, says", [
    ("#k=abc", "k needs a number (got 'abc')"),
    ("#kk=5", "unknown constant 'kk' in the address"),
    ("#k=1e9", "k must be from 0 to 1e6 N/m (got 1e+09 N/m)"),
    ("#k=500", "k = 500 N/m is outside what this file can run (4 to 120 N/m)"),
    ("#m=1e-400", "m = 1e-400 is too small for the computer to tell from 0"),
    ("#integrator=leapfrog", "integrator must be one of"),
    ("#r0=0,-1.2,0", "r0 cannot be set from the address in this file"),
    ("#k=%3Cimg%20src%3Dx%20onerror%3D%22window.hacked%3D1%22%3E", "k needs a number (got '<img src=x"),
])
def test_a_bad_set_up_in_the_address_is_one_line_and_the_file_runs_its_own(fragment, says, chromium, written):
    """One line on the page says what is wrong (as --set would), the file's own set-up runs and
    prints its answer, and nothing in the address runs as code."""
    page = Offline(chromium, written("vertical"), fragment)
    try:
        lines = page.answers(1)
        status = page.text("status")
        hacked = page.page.evaluate("window.hacked")
        images = page.page.evaluate("document.querySelectorAll('#status *').length")
    finally:
        page.close()
    assert says in status and status.endswith("running the file's own set-up instead.") and "\n" not in status
    assert lines == [headless_answer("vertical")]
    assert hacked is None and images == 0


def test_the_arrows_check_boxes_show_and_hide_the_programs_arrows(chromium, written):
    """p and F_net are on at first (vertical's VIEW), forces and F∥/F⊥ off; a check box switches
    its kind; with no arrow on, the mass is solid again."""
    page = Offline(chromium, written("vertical"))
    try:
        state = wait_state(page, "state.arrows.p !== undefined")
        assert state["arrows"] == {"p": True, "F_net": True, "forces": False, "split": False}
        assert state["opacity"] == [0.5]
        page.page.check("#arrow-forces")
        assert wait_state(page, "state.arrows.forces")["arrows"]["p"]
        for kind in ("p", "F_net", "forces"):
            page.page.uncheck(f"#arrow-{kind}")
        state = wait_state(page, "!state.arrows.p && !state.arrows.F_net && !state.arrows.forces")
        assert state["opacity"] == [1]
    finally:
        page.close()


def test_the_pages_numbers_are_the_command_lines(chromium, written):
    """The page writes numbers as export/step_update.py does (6 significant digits, exact ties to
    even, no '-0', round-off beside a vector's size as 0) and t with Δt's decimals, on thousands of
    values."""
    from export.numbers import clean_time, time_decimals
    page = Offline(chromium, written("vertical"))
    try:
        values = edge_values()
        numbers = page.page.evaluate("xs => xs.map(x => window.offlineNumbers.number(x))", values)
        vectors = [[2.5, -2.5e-13, 1.7], [0.0, -1.7301000000000002, 0.0], [100000.5, -2 ** -10, 12345.75]]
        vectors += [values[n:n + 3] for n in range(0, 600, 3)]
        written_vectors = page.page.evaluate("vs => vs.map(v => window.offlineNumbers.shown(v, 'N'))", vectors)
        dts = [0.1, 0.005, 2.0, 0.125, 1e-6, 0.02, 0.3]
        times = [[n * dt, dt] for dt in dts for n in (1, 3, 7, 1234)]
        cleaned = page.page.evaluate("ts => ts.map(([t, dt]) => [window.offlineNumbers.timeDecimals(dt),"
                                     " window.offlineNumbers.cleanTime(t, dt)])", times)
    finally:
        page.close()
    assert numbers == [number(x) for x in values]
    assert written_vectors == [shown(v, "N") for v in vectors]
    assert cleaned == [[time_decimals(dt), clean_time(t, dt)] for t, dt in times]


@pytest.mark.parametrize("scene, changes", [
    ("vertical", {"k": 60.0, "dt": 0.05, "until": 0.3}),
    ("damped", {"b": 2.5, "m": 3.5}),
    ("integrators", {"dt": 0.02, "k": 7.5}),
])
def test_the_page_writes_a_new_set_up_into_the_program_as_the_writer_would(scene, changes, chromium, written):
    """The program the page runs for new constants is the one export/vpython_program.py writes for
    them, line by line, but for what only frames the picture and the changed constants' own lines,
    which hold the new values."""
    from export.offline_page import FRAMING
    from export.vpython_program import program
    page = Offline(chromium, written(scene))
    try:
        data = json.loads(page.page.evaluate("document.getElementById('offline-data').textContent"))
        values = {name: constant["written"] for name, constant in data["constants"].items()}
        text = page.page.evaluate("s => window.offlineProgramFor(s)",
                                  {"values": {**values, **changes}, "integrator": data["integrator"]})
    finally:
        page.close()
    setup = catalog.configure(scene)
    writer = program(setup.with_values(**changes), web=True, page=True,
                     arrows={**DEFAULT_VIEW, **setup.hooks.view}["arrows"])

    def code(program_text):   # each line without its comment, the header and the framing left out
        lines = [line.split(" # ")[0].rstrip() for line in program_text.splitlines()]
        return [line for line in lines if not line.lstrip().startswith("#") and not line.startswith(FRAMING)]
    mine, theirs = code(text), code(writer)
    for name, value in changes.items():
        line = next(line for line in mine if line.startswith(f"{name} = "))
        assert float(line.partition(" = ")[2]) == value, line
    assert [line for line in mine if line.split(" = ")[0] not in changes] == \
           [line for line in theirs if line.split(" = ")[0] not in changes]


def test_a_force_constant_set_to_0_keeps_its_line_and_gives_the_command_lines_answer(chromium, written):
    """damped.html#b=0: the damping line stays (it adds exactly nothing), and the answer is
    `--headless --set b=0`'s, whose run leaves the force out."""
    page = Offline(chromium, written("damped"), "#b=0")
    try:
        lines = page.answers(1)
        program_text = page.text("program-text")
    finally:
        page.close()
    assert lines == [headless_answer("damped", "--set", "b=0")]
    assert "\nb = 0 " in program_text and "Fdamping = -b*v" in program_text


# ---- the local page's two controls ----

def test_the_local_page_downloads_its_set_up_as_an_offline_page_and_shows_its_link(chromium, tmp_path):
    """The local page's Download offline page gives the file `--html` writes for the set-up on the
    page (a preset and a slider applied), byte for byte, and its Copy link line carries that
    set-up's fragment, which the offline file reads to the same answer."""
    from test_browser import Program
    program = Program("vertical", "--preset", "Moon gravity")
    page = None
    try:
        url = program.url()
        page = chromium.new_page(viewport={"width": 1280, "height": 800}, accept_downloads=True)
        page.goto(url)
        page.wait_for_selector("#sm-link")
        page.wait_for_function("document.getElementById('sm-link').value === '#g=1.62'")
        handle = page.locator(".ui-slider-handle").nth(1)        # k's slider: the keyboard moves it one step
        handle.focus()
        handle.press("ArrowRight")
        page.wait_for_function("document.getElementById('sm-link').value.startsWith('#k=')")
        link = page.input_value("#sm-link")
        with page.expect_download() as download:
            page.get_by_role("button", name="Download offline page").click()
        downloaded = tmp_path / "downloaded.html"
        download.value.save_as(downloaded)
    finally:
        if page is not None:
            page.close()
        program.stop()
    k = re.match(r"#k=([^&]+)&g=1\.62$", link)
    assert k, link
    written = tmp_path / "written.html"
    done = main_py("vertical", "--preset", "Moon gravity", "--set", f"k={k[1]}", "--html", str(written))
    assert done.returncode == 0, done.stderr
    # the download is stamped with its mark and fingerprint as the written file is (export/marks.py): the same bytes
    assert downloaded.read_bytes() == written.read_bytes()
    shipped = tmp_path / "shipped.html"
    assert main_py("vertical", "--html", str(shipped)).returncode == 0
    offline = Offline(chromium, shipped, link)
    try:
        lines = offline.answers(1)
        status = offline.text("status")
    finally:
        offline.close()
    assert status == "" and lines == [headless_answer("vertical", "--set", f"k={k[1]}", "--set", "g=1.62")]


def test_the_graphs_tick_labels_are_plain_decimals_evenly_spaced(chromium, written):
    """GlowScript's flot may space ticks 2.5 × 10ⁿ apart and print them rounded (0.3, 0.5, 0.8 for
    0.25, 0.5, 0.75): the page installs export/plain_ticks.py's formatter, as the local page does."""
    page = Offline(chromium, written("driven"), size=(1024, 768))
    try:
        page.page.wait_for_function("() => document.querySelectorAll('.xAxis .tickLabel').length >= 3")
        # a graph drawn by the page's own $.plot over an axis flot spaces 0.25 apart
        labels = page.page.evaluate("""() => { const box = jQuery('<div>').css({width: '600px', height: '316px'})
            .appendTo(document.body); const plot = jQuery.plot(box, [[[0, 0], [1.8, 1]]], {grid: {offsets: {left: 0, right: 0, top: 0, bottom: 0}},
            xaxis: {min: 0, max: 1.8}, yaxis: {min: 0, max: 1}});
            const ticks = plot.getAxes().xaxis.ticks.map(t => [t.v, t.label]); box.remove(); return ticks; }""")
        shown = page.page.evaluate("""() => ['x', 'y'].map(a => Array.from(document.querySelectorAll(
            '.' + a + 'Axis .tickLabel')).map(e => e.textContent))""")
        assert not page.refused and not page.errors
    finally:
        page.close()
    assert [label for _, label in labels][:4] == ["0", "0.25", "0.50", "0.75"], labels
    for value, label in labels:
        assert float(label) == pytest.approx(value, abs=1e-9)
    for axis in shown:
        values = [float(label) for label in axis]
        steps = np.diff(values)
        assert len(values) >= 3 and np.allclose(steps, steps[0], rtol=1e-9), axis

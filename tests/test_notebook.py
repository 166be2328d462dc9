"""The scenes in a real Jupyter notebook: a Jupyter Notebook 7 server and headless Chromium.

Without a browser: the example notebook has one cell per scene and no saved outputs; show() refuses
to run outside a notebook without importing vpython; bad arguments give one clear message.

In a browser (marked `browser`): one notebook server per module is started on 127.0.0.1 (fresh
config and runtime folders, a random token) with a copy of examples/scenes.ipynb, whose kernel finds
the project through PYTHONPATH. One headless Chromium opens it with Playwright and runs cells as a
student would, with Ctrl+Enter, in this order:

* `vertical` runs under its cell and t advances; Pause and Jump to t = 4 s, clicked in the page,
  reach the kernel, and there its 3-D canvas shows the orange mass and the position graph has a
  curve; Run goes on (the screenshot
  notebook.png is taken here, into docs/screenshots/ only with UPDATE_SCREENSHOTS=1);
* running the cell again starts the scene again from t = 0 in that cell;
* its p and F_net arrows show, with their legend and check boxes, and unchecking the boxes hides them;
* the cells of `pendulum` and then `resonance` (with its own resonance graph) each stop the scene
  running before and run under their own cell;
* the page's scene menu switches scene in place, inside the cell.

Not every scene gets a browser run here (tests/test_browser.py runs each scene's page); the
notebook path is the same for all of them. Skipped, with the reason, where Chromium is missing.
"""
from __future__ import annotations

import io
import json
import os
import re
import secrets
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

from browser_support import (CHROMIUM, TIME, colours, curve_pixels, free_port, jump_to,
                             pixels_like, screenshot_folder, wait_for)
from scenes import catalog

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "scenes.ipynb"
SCREENSHOT = screenshot_folder() / "notebook.png"   # docs/screenshots/ only with UPDATE_SCREENSHOTS=1
SERVER_CONFIG = ROOT / "examples" / "jupyter_server_config.py"   # the README's --config
SHOW = re.compile(r'^show\("(\w+)"')


def example_scene_cells() -> list[tuple[str, str]]:
    """(scene name, source) of each code cell of the example notebook that calls show()."""
    cells = json.loads(EXAMPLE.read_text(encoding="utf-8"))["cells"]
    sources = ["".join(cell["source"]) for cell in cells if cell["cell_type"] == "code"]
    return [(SHOW.match(source).group(1), source) for source in sources if SHOW.match(source)]


# ---- without a browser ----

def test_the_example_notebook_has_one_cell_per_scene_and_no_outputs():
    assert [name for name, _ in example_scene_cells()] == catalog.SCENE_NAMES
    cells = json.loads(EXAMPLE.read_text(encoding="utf-8"))["cells"]
    assert all(not cell.get("outputs") for cell in cells if cell["cell_type"] == "code")


def test_outside_a_notebook_show_refuses_and_never_imports_vpython():
    code = ("import sys\n"
            "from browser.notebook import show\n"
            "try:\n"
            "    show('vertical', k=60)\n"
            "except RuntimeError as problem:\n"
            "    print(problem)\n"
            "print('vpython' in sys.modules)\n")
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stderr
    message, imported = result.stdout.strip().splitlines()
    assert "python main.py NAME" in message
    assert imported == "False"


@pytest.mark.parametrize("call, expected", [
    (dict(name="vertcal"), "did you mean 'vertical'"),
    (dict(name="vertical", kk=60), "did you mean 'k'"),
    (dict(name="vertical", m=-1), "m must be from 1e-6 to 1e6 kg"),
    (dict(name="vertical", r0=(0, 1)), "r0 needs a 3-vector"),
    (dict(name="driven", scenario=9), "scenario 9 is out of range"),
    (dict(name="vertical", integrator="leapfrog"), "unknown integrator 'leapfrog'"),
    (dict(name="vertical", preset="Mars gravity"), "unknown preset 'Mars gravity'"),
])
def test_bad_arguments_are_one_clear_message_before_anything_is_drawn(call, expected):
    from scenes import ConstantError
    from browser.notebook import show

    call = dict(call)
    with pytest.raises(ConstantError, match=re.escape(expected)):
        show(call.pop("name"), **call)


# ---- in a real notebook ----

def _skip_reason() -> str | None:
    if not os.path.exists(CHROMIUM):
        return f"Chromium is not installed at {CHROMIUM} (apt-get install chromium)"
    for module, package in (("playwright", "playwright"), ("notebook", "notebook"), ("PIL", "pillow")):
        try:
            __import__(module)
        except ImportError:
            return f"{package} is not installed (pip install -r requirements-test.txt)"
    return None


browser = pytest.mark.browser
needs_browser = pytest.mark.skipif(_skip_reason() is not None, reason=str(_skip_reason()))


@pytest.fixture(scope="module")
def jupyter(tmp_path_factory):
    """A Jupyter Notebook server on 127.0.0.1 serving a copy of the example notebook: (base URL, token)."""
    work = tmp_path_factory.mktemp("notebook")
    (work / "scenes.ipynb").write_bytes(EXAMPLE.read_bytes())
    config = work / ".config"
    # Render every cell at once, so each cell's output is in the page for the test to find.
    settings = config / "lab" / "user-settings" / "@jupyterlab" / "notebook-extension"
    settings.mkdir(parents=True)
    (settings / "tracker.jupyterlab-settings").write_text('{"windowingMode": "none"}')
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])),
           "JUPYTER_CONFIG_DIR": str(config), "JUPYTER_DATA_DIR": str(work / ".data"),
           "JUPYTER_RUNTIME_DIR": str(work / ".runtime"), "IPYTHONDIR": str(work / ".ipython")}
    port, token = free_port(), secrets.token_hex(16)
    command = [sys.executable, "-m", "notebook", "--no-browser", "--ip=127.0.0.1", f"--port={port}",
               "--ServerApp.port_retries=0", f"--IdentityProvider.token={token}",
               f"--ServerApp.root_dir={work}", "--LabApp.news_url=None",
               "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate", f"--config={SERVER_CONFIG}"]
    log = open(work / "server.log", "w")
    server = subprocess.Popen(command, cwd=work, env=env, stdout=log, stderr=subprocess.STDOUT)
    base = f"http://127.0.0.1:{port}/"
    try:
        deadline = time.monotonic() + 90
        while True:
            try:
                request = urllib.request.Request(base + "api/status", headers={"Authorization": f"token {token}"})
                urllib.request.urlopen(request, timeout=2).close()
                break
            except OSError:
                if server.poll() is not None or time.monotonic() > deadline:
                    pytest.fail(f"the notebook server did not start: {(work / 'server.log').read_text()[-2000:]}")
                time.sleep(0.2)
        yield base, token
    finally:
        server.terminate()  # the server shuts its kernels down on SIGTERM
        try:
            server.wait(timeout=20)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait(timeout=10)
        log.close()


@pytest.fixture(scope="module")
def page(jupyter, browser):
    """The example notebook open in headless Chromium (conftest's, the module's), its first code
    cell (the import) run."""
    base, token = jupyter
    page = browser.new_page(viewport={"width": 1280, "height": 1500})
    try:
        page.goto(f"{base}notebooks/scenes.ipynb?token={token}")
        page.locator(".jp-Notebook-ExecutionIndicator[data-status='idle']").wait_for()
        run(code_cells(page).first)
        yield page
    finally:
        page.close()


def code_cells(page):
    return page.locator(".jp-Notebook .jp-CodeCell")


def scene_cell(page, name: str):
    """The example notebook's cell that shows scene `name`."""
    return code_cells(page).filter(has=page.locator(".jp-InputArea", has_text=f'show("{name}")'))


def execution_count(cell) -> int | None:
    found = re.search(r"\[(\d+)\]", cell.locator(".jp-InputPrompt").inner_text())
    return int(found.group(1)) if found else None


def run(cell) -> None:
    """Run the cell in place (Ctrl+Enter) and wait until it has finished.

    Just after the page loads, Notebook 7 can drop the keystroke: its keyboard shortcuts are
    registered when their settings have loaded, which races with the page (the same race logs
    "reading 'schema'" in the console; jupyter/notebook#7862). So a press that has not started the
    cell (its prompt shows neither [*] nor a new number) within a few seconds is made again.
    """
    before = execution_count(cell)
    started = lambda: "*" in cell.locator(".jp-InputPrompt").inner_text() or \
        execution_count(cell) not in (None, before)                                  # noqa: E731
    for attempt in range(4):
        cell.locator(".jp-InputArea-editor").click()
        cell.page.keyboard.press("Control+Enter")
        deadline = time.monotonic() + 5.0
        while time.monotonic() < deadline and not started():
            time.sleep(0.05)
        if started():
            break
    wait_for(lambda: execution_count(cell) not in (None, before), what="the cell to finish")


def shown_time(cell) -> float | None:
    """The t the scene's caption in this cell shows (`t = 1.23 s`), or None if it has none."""
    text = cell.locator("b").filter(has_text=TIME)
    if not text.count():
        return None
    found = TIME.match(text.first.inner_text())
    return float(found.group(1)) if found else None


def wait_until_running(cell, *, past: float = 0.0) -> float:
    """Wait for the scene in this cell to show t > past, then for t to advance further."""
    start = wait_for(lambda: (shown_time(cell) or 0) > past and shown_time(cell), what=f"t to pass {past} s")
    return wait_for(lambda: (shown_time(cell) or 0) > start and shown_time(cell), what="t to advance")


def look(where, **parts):
    """Pictures of parts of the cell `where` (name=locator), cut from ONE screenshot of the page.

    The notebook scrolls inside its own panel, so the cell's top is scrolled to the top of the
    panel first, and the cut is kept inside the viewport. One screenshot per look, because with
    software WebGL each one takes seconds. (An animated element is never "stable", so
    Playwright's element screenshot could wait for ever.)
    """
    from PIL import Image

    where.evaluate("element => element.scrollIntoView({block: 'start'})")
    # two frames drawn at its new place: the browser's own signal (at 2-3 frames a second in software
    # WebGL, the 0.3 s this once slept was less than one frame)
    where.page.evaluate("() => new Promise(done => requestAnimationFrame(() => requestAnimationFrame(done)))")
    boxes = {name: locator.bounding_box() for name, locator in parts.items()}
    viewport = where.page.viewport_size
    left = max(0, min(box["x"] for box in boxes.values()))
    top = max(0, min(box["y"] for box in boxes.values()))
    right = min(viewport["width"], max(box["x"] + box["width"] for box in boxes.values()))
    bottom = min(viewport["height"], max(box["y"] + box["height"] for box in boxes.values()))
    shot = Image.open(io.BytesIO(where.page.screenshot(
        clip={"x": left, "y": top, "width": right - left, "height": bottom - top}))).convert("RGB")
    return {name: shot.crop((round(box["x"] - left), round(box["y"] - top),
                             round(min(box["x"] + box["width"], right) - left),
                             round(min(box["y"] + box["height"], bottom) - top)))
            for name, box in boxes.items()}


def mass_pixels(image) -> int:
    """Strongly coloured pixels: the masses (the palette's colours, lit and shaded). The canvas's
    background, the support and the helices are grey."""
    return sum(n for rgb, n in colours(image).items() if max(rgb) > 120 and max(rgb) - min(rgb) > 80)


def canvas(cell):
    """The cell's 3-D canvas (vpython's WebGL canvas, the first in its wrapper)."""
    return cell.locator(".glowscript-canvas-wrapper canvas").first


def graph(cell, index: int):
    """The cell's graph number `index` (page order: a scene's own graph first)."""
    return cell.locator(".glowscript-graph canvas.base").nth(index)


def running_scene_cell(page, name: str):
    """The cell of scene `name`, with its scene running: run here if an earlier test did not leave
    it running, so each test can be run alone by its id."""
    cell = scene_cell(page, name)
    if shown_time(cell) is None or "Stopped:" in cell.inner_text() or f"{name}:" not in cell.inner_text():
        run(cell)
        wait_until_running(cell)
    return cell


def assert_mass_drawn(image, what: str) -> None:
    assert image.height > 400, f"{what}: only {image.height} px of the 3-D canvas could be seen"
    assert mass_pixels(image) > 100, f"{what}: the 3-D canvas shows no mass"


@browser
@needs_browser
def test_a_scene_runs_under_its_cell_and_pause_reaches_the_kernel(page):
    cell = scene_cell(page, "vertical")
    run(cell)
    wait_until_running(cell)
    assert "k = 40 N/m" in cell.inner_text()  # the scene's own constants, with units

    cell.get_by_role("button", name="Pause", exact=True).click()
    cell.get_by_role("button", name="Run", exact=True).wait_for()
    paused = jump_to(cell, 4.0)  # a little over one period, for the screenshot's graphs; still paused
    assert shown_time(cell) == paused == 4.0
    seen = look(cell, cell=cell, canvas=canvas(cell), position=graph(cell, 0))
    assert_mass_drawn(seen["canvas"], "vertical")
    assert curve_pixels(seen["position"]) > 50, "the position graph shows no curve"
    SCREENSHOT.parent.mkdir(parents=True, exist_ok=True)
    seen["cell"].save(SCREENSHOT)
    assert shown_time(cell) == paused, "t moved while paused"     # through a screenshot's frames

    cell.get_by_role("button", name="Run", exact=True).click()
    wait_for(lambda: shown_time(cell) > paused, what="t to advance after Run")


@browser
@needs_browser
def test_running_the_cell_again_starts_the_scene_again_from_0(page):
    cell = running_scene_cell(page, "vertical")
    before = jump_to(cell, 10.5)  # paused there: only a new run shows a smaller t
    run(cell)
    first = wait_for(lambda: shown_time(cell) is not None and (shown_time(cell),),
                     what="the scene to show t again")[0]
    assert first < before, f"t went from {before} s to {first} s, not back to 0"
    assert cell.locator("b").filter(has_text=TIME).count() == 1  # the old output is gone
    assert cell.locator(".glowscript-canvas-wrapper").count() == 1
    wait_until_running(cell)


def arrow_pixels(image, kind: str) -> int:
    """Pixels of the 3-D canvas in the colour of one kind of arrow (export/palette.py), lit and shaded."""
    from export.palette import ARROW_COLOURS

    return pixels_like(image, tuple(round(255 * c) for c in ARROW_COLOURS[kind]), within=60)


@browser
@needs_browser
def test_the_notebook_shows_the_arrows_and_its_check_boxes_reach_the_kernel(page):
    """As on the page: `vertical` opens with its p (yellow) and F_net (reddish purple) arrows on,
    its checked boxes and the legend of the scales, and the mass see-through around them.
    Unchecking both boxes in the cell hides both arrows (at every moment one of them is over
    1 m long: |p|/20 and |F_net|/20 are never small together) and makes the mass solid again."""
    from export.arrows import choose_scales
    from export.palette import mass_colour
    from scenes._view import DEFAULT_VIEW

    cell = running_scene_cell(page, "vertical")
    setup = catalog.configure("vertical")
    scales = choose_scales(setup.build(), view={**DEFAULT_VIEW, **setup.hooks.view})
    assert scales.legend() in cell.inner_text()   # an arrow of 1 m = 20 kg·m/s for p, 20 N for forces
    boxes = cell.locator(":not(.sm-measure) > input[type=checkbox]")   # not the Measure panel's
    assert boxes.count() == 4                      # p, F_net, forces, F∥ and F⊥
    assert [boxes.nth(n).is_checked() for n in range(4)] == [True, True, False, False]
    orange = tuple(round(255 * c) for c in mass_colour(0))

    def drawn():
        image = look(cell, canvas=canvas(cell))["canvas"]
        return arrow_pixels(image, "p"), arrow_pixels(image, "F_net"), pixels_like(image, orange, within=60)
    shown = wait_for(lambda: max((seen := drawn())[:2]) > 150 and seen, what="the p or F_net arrow on the canvas")
    boxes.nth(0).uncheck()
    boxes.nth(1).uncheck()
    # a solid ball's highlights give a few yellowish pixels: a shown p arrow under 40 of them is
    # under 0.3 of its longest, and then F_net is over 0.95 of its own and far over 10
    last = []

    def gone():
        last[:] = drawn()
        return last[0] < 40 and last[1] < 10
    try:
        wait_for(gone, what="both arrows to go after their boxes were unchecked")
    except pytest.fail.Exception:
        pytest.fail(f"the arrows stayed after their boxes were unchecked: (p, F_net, orange) pixels {last}")
    # see-through, the ball had few pixels of its own orange; solid, it has far more
    assert last[2] > max(100, 2 * shown[2]), f"the mass did not turn solid with no arrow shown: {shown} then {last}"
    boxes.nth(0).check()
    boxes.nth(1).check()
    wait_for(lambda: max(drawn()[:2]) > 150, what="the arrows back after checking their boxes")


@browser
@needs_browser
@pytest.mark.parametrize("name, before", [("pendulum", "vertical"), ("resonance", "pendulum")])
def test_another_scenes_cell_stops_the_one_before_and_runs(page, name, before):
    old = running_scene_cell(page, before)
    cell = scene_cell(page, name)
    run(cell)
    wait_until_running(cell)
    assert "Stopped:" in old.inner_text(), f"the scene before {name} still looks live"
    assert not old.locator(".glowscript-canvas-wrapper").count(), "its 3-D view is still there"
    assert not old.locator(".glowscript-graph").count(), "its graphs are still there"
    stopped = shown_time(old)
    own_graph = name == "resonance"  # its own graph comes first, then position and energy
    parts = {"canvas": canvas(cell), "position": graph(cell, 1 if own_graph else 0)}
    if own_graph:
        parts["resonance"] = graph(cell, 0)
    seen = look(cell, **parts)
    assert_mass_drawn(seen["canvas"], name)
    assert curve_pixels(seen["position"]) > 50, f"{name}: the position graph shows no curve"
    if own_graph:  # the exact curves for three values of b, and the row's live dots in orange
        from export.palette import CURVE_COLOURS, LIVE_COLOUR

        assert catalog.configure("resonance").values["curves"] == 3
        for colour in CURVE_COLOURS[:3] + [LIVE_COLOUR]:
            rgb = tuple(round(255 * c) for c in colour)
            assert pixels_like(seen["resonance"], rgb) > 150, f"the resonance graph has no curve in colour {rgb}"
    assert shown_time(old) == stopped, f"{before} went on after it stopped"


@browser
@needs_browser
def test_the_scene_menu_switches_scene_inside_the_cell(page):
    cell = running_scene_cell(page, "resonance")
    menu = cell.locator("select").filter(has=page.locator("option", has_text="integrators"))
    menu.select_option("damped")
    wait_for(lambda: "damped:" in cell.inner_text(), what="the damped scene's title")
    assert "b = 1 kg/s" in cell.inner_text()
    wait_until_running(cell)
    assert cell.locator(".glowscript-graph canvas.base").count() == 2  # resonance's own graph has gone
    seen = look(cell, canvas=canvas(cell), position=graph(cell, 0))
    assert_mass_drawn(seen["canvas"], "damped, from the scene menu")
    assert curve_pixels(seen["position"]) > 50, "damped: the position graph shows no curve"


def test_saving_the_example_notebook_after_a_lesson_keeps_it_as_committed():
    """The README's notebook command loads examples/jupyter_server_config.py: its pre-save hook
    drops what running the cells adds, so Jupyter's autosave leaves the tracked file unchanged."""
    import nbformat
    from traitlets.config import Config

    settings = Config()
    exec(SERVER_CONFIG.read_text(encoding="utf-8"), {"get_config": lambda: settings})
    assert settings.ServerApp.allow_root is True       # works as root too
    hook = settings.ContentsManager.pre_save_hook
    committed = nbformat.reads(EXAMPLE.read_text(encoding="utf-8"), as_version=4)
    used = nbformat.reads(EXAMPLE.read_text(encoding="utf-8"), as_version=4)
    used.metadata["language_info"] = {"name": "python", "version": "3.11.2", "mimetype": "text/x-python"}
    for number, cell in enumerate(c for c in used.cells if c.cell_type == "code"):
        cell.execution_count = number + 1
        cell.outputs = [nbformat.v4.new_output("stream", name="stdout", text="t = 1.00 s\n")]
        cell.metadata["execution"] = {"iopub.status.busy": "2026-01-01T00:00:00Z"}
    model = {"type": "notebook", "content": used}
    hook(model=model, path="examples/scenes.ipynb", contents_manager=None)
    # Jupyter writes nbformat.writes(...) and a newline: byte for byte the committed file
    assert nbformat.writes(model["content"]) + "\n" == EXAMPLE.read_text(encoding="utf-8")
    assert nbformat.writes(model["content"]) == nbformat.writes(committed)


def test_after_the_page_has_gone_show_says_so_in_one_line_not_a_traceback():
    """Reopening the notebook page ends vpython's websocket server for good; show() then says so,
    and IPython prints only that line (PageGone._render_traceback_)."""
    code = (
        "import sys, threading, types\n"
        "from IPython.core.interactiveshell import InteractiveShell\n"
        "gone = threading.Thread(target=lambda: None); gone.start(); gone.join()\n"
        "sys.modules['vpython.with_notebook'] = types.SimpleNamespace(t=gone)  # its server thread, ended\n"
        "shell = InteractiveShell.instance()\n"
        "shell.run_cell('from browser.notebook import _require_live_page\\n_require_live_page()')\n")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    shown = [line for line in (done.stdout + done.stderr).splitlines() if line.strip()]
    assert len(shown) == 1, shown
    assert shown[0].startswith("PageGone: the notebook page vpython was connected to has gone")
    assert "restart the kernel" in shown[0] and "Traceback" not in shown[0]


@browser
@needs_browser
def test_the_measure_panel_works_in_the_notebook(page):
    """Issue 30, item 8: the Measure panel in a cell: closed at first; opened, its stopwatch
    counts, the period shows when ticked, the energy bars take the energy graph's place and add up,
    and a click on the position graph reads a point of it."""
    cell = running_scene_cell(page, "vertical")
    panel = cell.locator(".sm-measure")
    assert panel.evaluate("e => getComputedStyle(e).display") == "none"
    cell.locator(".sm-measure-toggle").click()
    panel.wait_for(state="visible")
    cell.get_by_role("button", name="Start (S)", exact=True).click()
    cell.get_by_role("button", name="Stop (S)", exact=True).wait_for()
    panel.locator("span").filter(has_text=re.compile(r"^ ?period")).first.locator(
        "xpath=preceding-sibling::input[1]").check()
    wait_for(lambda: cell.locator(".sm-period").count() and "formula 2π/ω" in cell.locator(".sm-period").inner_text(),
             what="the period's line")
    panel.locator("select").select_option("energy bars")
    wait_for(lambda: cell.locator(".sm-bar-value").count() == 5, what="the energy bars")
    joules = [float(v) for v in cell.locator(".sm-bar-value").evaluate_all("cells => cells.map(c => c.dataset.joules)")]
    assert joules[-1] == pytest.approx(sum(joules[:-1]), rel=1e-12, abs=1e-12)
    watch = wait_for(lambda: (value := float(cell.locator(".sm-stopwatch").inner_text().replace("\u00a0", " ")
                                             .split()[0])) > 0 and value, what="the stopwatch to count")
    assert watch > 0
    overlay = cell.locator(".glowscript-graph canvas.overlay").first
    overlay.scroll_into_view_if_needed()
    place = overlay.bounding_box()
    overlay.click(position={"x": 0.4 * place["width"], "y": 0.5 * place["height"]})
    read = wait_for(lambda: cell.locator(".sm-read").count() and cell.locator(".sm-read").first.inner_text(),
                    what="the graph's reading").replace("\u00a0", " ")
    # the point nearest the click, of the simulated curve or of the exact one beside it
    assert re.fullmatch(r"Read: t = [\d.]+ s, y (\(simulation\)|exact) = [−-]?[\d.]+ m", read), read
    look(cell, cell=cell)["cell"].save(SCREENSHOT.parent / "notebook-measure.png")
    panel.locator("select").select_option("energy graph")
    cell.locator(".sm-measure-toggle").click()

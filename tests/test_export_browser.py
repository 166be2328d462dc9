"""Exported programs in a real browser: the real vpython draws them, and the page hands them out.

1. `main.py vertical --vpython FILE.py` is run as a student runs it, `python FILE.py`, with the real
   vpython (its own server, on a free port, no browser launched), and its page is opened in
   headless Chromium: the 3-D canvas shows the orange sphere, the helix and the support, and the
   graph shows the position curve in the sphere's orange (export/palette.py, as on the page) and
   the near-black exact curve. The screenshot goes to /tmp.
2. The page's Download program button, after choosing a preset, hands over exactly the program
   `main.py SCENE --preset ... --vpython` writes.

Skipped, with the reason, where Chromium or Playwright is missing.
"""
from __future__ import annotations

import os
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from browser_support import free_port, require_browser, screenshot_folder, wait_for
from test_browser import Program, shown_time
from test_handout import headless_answer

ROOT = Path(__file__).resolve().parent.parent
SCREENSHOTS = screenshot_folder()

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()


def count(image, test) -> int:
    """How many pixels of the image pass test((r, g, b))."""
    return sum(n for n, rgb in image.convert("RGB").getcolors(maxcolors=1 << 24) if test(rgb))


def orange(rgb):
    r, g, b = rgb
    return r > 150 and 60 < g < 0.8 * r and b < 0.4 * g


def dim_orange(rgb):
    """The orange sphere see-through (export/arrows.py's SEE_THROUGH, 0.5) over vpython's black
    background, as the program draws it while it shows arrows: half as bright, the same hue."""
    r, g, b = rgb
    return r > 60 and 0.4 * r < g < 0.8 * r and b < 0.4 * g


def light_grey(rgb):
    return min(rgb) > 110 and max(rgb) - min(rgb) < 30


def black(rgb):
    return max(rgb) < 60


def test_exported_program_draws_with_the_real_vpython(browser, tmp_path):
    program = tmp_path / "vertical.py"
    written = subprocess.run([sys.executable, str(ROOT / "main.py"), "vertical", "--set", "dt=0.01",
                              "--set", "until=2", "--vpython", str(program)],
                             capture_output=True, text=True, timeout=60)
    assert written.returncode == 0, written.stderr
    port = free_port()
    env = {**os.environ, "VPYTHON_NO_LAUNCH_BROWSER": "1", "VPYTHON_HTTP_PORT": str(port)}
    process = subprocess.Popen([sys.executable, str(program)], cwd=tmp_path, env=env, text=True,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    output: list[str] = []
    threading.Thread(target=lambda: output.extend(process.stdout), daemon=True).start()
    page = None
    try:
        page = browser.new_page(viewport={"width": 1100, "height": 1000})

        def opened():
            try:
                page.goto(f"http://localhost:{port}/", timeout=5_000)
                return True
            except sync_api.Error:
                return process.poll() is not None
        wait_for(opened, what="the program's vpython page")
        assert process.poll() is None, process.stderr.read()
        wait_for(lambda: any("r = <" in line for line in output), what="the program's final print")
        SCREENSHOTS.mkdir(exist_ok=True)

        def drawn():
            """The page as it is now, once the graph's points have reached it (a fixed wait of 1.5 s
            read it at a wall-clock time; on a busy computer the frames come later)."""
            page.screenshot(path=str(SCREENSHOTS / "vertical-program.png"), full_page=True)
            box = page.locator("canvas").first.bounding_box()
            whole = Image.open(SCREENSHOTS / "vertical-program.png")
            bottom = box["y"] + box["height"]
            scene = whole.crop((box["x"], box["y"], box["x"] + box["width"], bottom))
            plot = whole.crop((box["x"], bottom, box["x"] + box["width"], whole.height))   # the graph is below
            return (scene, plot) if count(plot, orange) > 200 and count(plot, black) > 200 else None
        scene, plot = wait_for(drawn, what="the program's graph on its page")
        assert count(scene, dim_orange) > 200, "the sphere (see-through: vertical shows its arrows)"
        assert count(scene, light_grey) > 300, "the helix and the support"
        assert count(plot, orange) > 200, "the position curve, in the sphere's colour"
        assert count(plot, black) > 200, "the exact curve (and the axes)"
        final = [line for line in output if "r = <" in line][-1]
        # the answer at the question time, as --headless writes it (the program runs on, to watch)
        assert final.strip() == headless_answer("vertical", "--set", "dt=0.01", "--set", "until=2")
    finally:
        if page is not None:
            page.close()
        if process.poll() is None:
            process.kill()
        process.wait(timeout=10)


def test_download_program_button_hands_over_the_chosen_case(browser, tmp_path):
    scene, preset = "vertical", "Moon gravity"
    expected = subprocess.run([sys.executable, str(ROOT / "main.py"), scene, "--preset", preset,
                               "--integrator", "verlet", "--vpython", "-"],
                              capture_output=True, text=True, timeout=60)
    assert expected.returncode == 0, expected.stderr
    program = Program(scene)
    try:
        page = browser.new_page(viewport={"width": 1024, "height": 768}, accept_downloads=True)
        page.goto(program.url())
        wait_for(lambda: shown_time(page) > 0, what="the scene to run")
        page.locator("select").filter(has_text="euler-cromer").select_option("verlet")
        page.locator("select").filter(has_text="choose a preset").select_option(preset)
        wait_for(lambda: page.get_by_text("1.62 m/s²").count() > 0, what="the preset's g in the caption")
        with page.expect_download() as download:
            page.get_by_role("button", name="Download program", exact=True).click()
        assert download.value.suggested_filename == f"{scene}.py"
        text = Path(download.value.path()).read_text(encoding="utf-8")
        assert text == expected.stdout
        assert "g = 1.62" in text and "half a kick" in text
        page.close()
    finally:
        program.stop()

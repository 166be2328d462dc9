"""Issue 20, item 6, in a real browser: a teacher's scene folder (SPRING_SCENES) in the page's scene menu.

The folder holds a good scene (heavy.py), a scene named catalog.py (that crashed the page:
AttributeError ... SCENE_NAMES), a .py file that is not a scene (notes.py, which sleeps: run in the
page's process it froze the clock) and a scene that fails as it loads (fails.py). The page starts,
lists neither catalog.py nor notes.py and says why beside the menu (issue 28, item 7), says why
fails.py cannot open and keeps that sentence while the scene shown runs on with its name back in
the menu, and opens heavy.py.
"""
from __future__ import annotations

import os
import queue
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from browser_support import TIME, free_port, require_browser, wait_for

ROOT = Path(__file__).resolve().parent.parent

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()


def teacher_folder(folder: Path) -> Path:
    scene = (ROOT / "scenes" / "vertical.py").read_text(encoding="utf-8").replace("from ._", "from scenes._")
    (folder / "heavy.py").write_text(scene.replace("\nm = 10.0 ", "\nm = 25.0 "), encoding="utf-8")
    (folder / "catalog.py").write_text(scene, encoding="utf-8")
    (folder / "notes.py").write_text("import time\nprint('notes: not a scene')\ntime.sleep(600)\n", encoding="utf-8")
    (folder / "fails.py").write_text(scene.replace("\ndef build(", "\nundefined_name_here\ndef build(", 1),
                                     encoding="utf-8")
    return folder


@pytest.fixture
def program(tmp_path):
    port = free_port()
    env = {**os.environ, "SPRING_SCENES": str(teacher_folder(tmp_path))}
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), "vertical", "--no-browser", "--port", str(port)],
                               cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lines: queue.Queue = queue.Queue()
    process.errors = []
    threading.Thread(target=lambda: [lines.put(line) for line in process.stdout], daemon=True).start()
    threading.Thread(target=lambda: [process.errors.append(line) for line in process.stderr], daemon=True).start()
    process.url = f"http://127.0.0.1:{port}/"
    try:
        wait_for(lambda: "http://127.0.0.1" in lines.get(timeout=60), timeout=60, what="the URL")
        yield process
    finally:
        if process.poll() is None:
            process.kill()
        process.wait(timeout=60)


def shown_time(page) -> float:
    return float(TIME.match(page.locator("b").filter(has_text=TIME).first.inner_text()).group(1))


def scene_menu(page):
    menus = page.locator("select")
    return next(menus.nth(i) for i in range(menus.count())
                if "damped" in menus.nth(i).locator("option").all_inner_texts())


def test_a_teachers_folder_in_the_scene_menu(program, browser):
    page = browser.new_page(viewport={"width": 1024, "height": 768})
    try:
        page.goto(program.url)
        wait_for(lambda: shown_time(page) > 0, what="the clock to start")
        menu = scene_menu(page)
        names = menu.locator("option").all_inner_texts()
        assert "heavy" in names and "fails" in names and "vertical" in names, names
        assert "catalog" not in names and "notes" not in names, names
        # issue 28, item 7: the page says why those two are not in the menu
        page.locator(".sm-left-out summary").click()
        left_out = page.locator(".sm-left-out").inner_text()
        assert "2 files not in the menu" in left_out, left_out
        assert "catalog.py" in left_out and "taken by the simulator's own code" in left_out, left_out
        assert "notes.py is not a scene" in left_out and "build function" in left_out, left_out

        menu.select_option("fails")
        said = wait_for(lambda: next((line for line in page.inner_text("body").splitlines()
                                      if line.startswith("Cannot open that:")), None),
                        what="the page to say why fails.py cannot open")
        assert "fails.py" in said and "undefined_name_here" in said, said
        wait_for(lambda: menu.evaluate("menu => menu.value") == "vertical", what="the menu back on vertical")
        now = shown_time(page)
        wait_for(lambda: shown_time(page) > now, what="vertical to run on")
        assert said in page.inner_text("body")                     # the next frames did not clear it

        menu.select_option("heavy")
        wait_for(lambda: "heavy" in page.locator("b").first.inner_text(), what="the heavy scene's title")
        wait_for(lambda: "m = 25 kg" in page.inner_text("body"), what="heavy's m = 25 kg")
    finally:
        page.close()
    program.wait(timeout=60)
    assert program.returncode == 0, "".join(program.errors)
    assert "Traceback" not in "".join(program.errors)

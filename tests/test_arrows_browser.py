"""The momentum arrows and the Step read-out in a real browser (headless Chromium, Playwright).

The arrows are read back from the page's own GlowScript objects (glowObjs, by the indices the
legend's hidden #arrow-objects element names) and compared with the engine: after Reset and N
Steps, p_i, F_net Δt and p_f at the momentum scale, and F_net at the force scale. The read-out
must equal `--steps` for steps 1 to 3, and the scales are round and stay fixed through a run.
Screenshots of every scene with its arrows (1280×800 and 1920×1080) and of pendulum with F∥ and
F⊥ go to the screenshot folder (tests/browser_support.py).
"""
from __future__ import annotations

import json

import numpy as np
import pytest

import main
from browser_support import jump_to, require_browser, screenshot_folder, wait_for
from export.arrows import choose_scales
from scenes._view import DEFAULT_VIEW
from export.step_update import update_force
from physics.forces import net_force
from physics.state import velocity
from scenes import catalog
from test_browser import Program, drawable_scenes, shown_time

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()
SCREENSHOTS = screenshot_folder()


class Page:
    """A scene's page, with its arrows read back from the GlowScript objects."""

    def __init__(self, browser, args, viewport=(1024, 768)):
        self.program = Program(args[0]) if len(args) == 1 else ProgramWith(args)
        self.page = browser.new_page(viewport={"width": viewport[0], "height": viewport[1]})
        self.page.goto(self.program.url())
        self.page.locator("#arrow-objects").wait_for(state="attached")

    def objects(self) -> dict:
        return json.loads(self.page.locator("#arrow-objects").get_attribute("data-objects"))

    def axis(self, index) -> np.ndarray:
        return np.array(self.page.evaluate("i => { const a = glowObjs[i].axis; return [a.x, a.y, a.z]; }", index))

    def click(self, name):
        self.page.get_by_role("button", name=name).click()

    def close(self):
        self.page.close()
        self.program.stop()


class ProgramWith(Program):
    """`python main.py SCENE OPTIONS --no-browser --port P`."""

    def __init__(self, args):
        import queue
        import subprocess
        import sys
        import threading

        from browser_support import free_port
        from test_browser import ROOT

        self.port = free_port()
        self.process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), *args, "--no-browser", "--port",
                                         str(self.port)], cwd=ROOT, stdout=subprocess.PIPE,
                                        stderr=subprocess.PIPE, text=True)
        self.lines, self.errors = queue.Queue(), []
        threading.Thread(target=self._read, args=(self.process.stdout, self.lines.put), daemon=True).start()
        threading.Thread(target=self._read, args=(self.process.stderr, self.errors.append), daemon=True).start()


def steps_table(capsys, args, steps=3):
    assert main.run([*args, "--steps", str(steps)]) == 0
    lines = capsys.readouterr().out.splitlines()[-steps:]
    return [[cell.strip() for cell in line.split("  ") if cell.strip()] for line in lines]


@pytest.mark.parametrize("args", [("vertical",), ("damped",), ("driven", "--scenario", "3")])
def test_step_read_out_and_arrows_are_the_engines(browser, capsys, args):
    setup = catalog.configure(args[0], scenario=int(args[2]) if len(args) > 2 else None)
    model = setup.build()
    rows = steps_table(capsys, args)
    engine = model.simulation()
    # vertical's page gives the README's picture of a Step (docs/screenshots/momentum-update.png), at its size
    page = Page(browser, args, viewport=(1280, 1000) if args == ("vertical",) else (1024, 768))
    try:
        first = page.objects()
        scales = choose_scales(model, view={**DEFAULT_VIEW, **setup.hooks.view})
        assert (first["p_unit"], first["F_unit"]) == (scales.p_unit, scales.F_unit)
        jump_to(page.page, 1.0)                     # paused there
        page.click("Reset")
        wait_for(lambda: shown_time(page.page) == 0.0, what="Reset")
        for n, row in enumerate(rows, start=1):
            before = engine.state
            t_i, r_i, p_i = before.t, np.array(before.r), np.array(before.p)
            engine.advance(1)
            after = engine.state
            page.click("Step")
            text = wait_for(lambda: (t := page.page.locator(".step-readout").inner_text())
                            .startswith(f"t = {row[1]} s") and t, what=f"step {n}'s read-out")
            assert f"F_net = {row[2]} N" in text and f"= {row[3]} kg·m/s" in text
            assert f"v_f = p_f / m = {row[4]} m/s" in text and f"= {row[5]} m" in text
            objects = page.objects()
            assert (objects["p_unit"], objects["F_unit"]) == (first["p_unit"], first["F_unit"])
            F = update_force(model.forces, engine.methods, t_i=t_i, r_i=r_i, p_i=p_i, p_f=after.p, m=after.m,
                             dt=model.dt)[0]
            arrow_i, arrow_dp, arrow_f = objects["step"][0]
            p_unit, F_unit = objects["p_unit"], objects["F_unit"]
            wait_for(lambda: np.allclose(page.axis(arrow_f), after.p[0] / p_unit, rtol=1e-9, atol=1e-12),
                     what="the p_f arrow")
            if np.any(p_i[0]):
                assert np.allclose(page.axis(arrow_i), p_i[0] / p_unit, rtol=1e-9, atol=1e-12)
            else:   # from rest, p_i is no arrow at all
                assert not page.page.evaluate("i => glowObjs[i].visible", arrow_i)
            assert np.allclose(page.axis(arrow_dp), F * model.dt / p_unit, rtol=1e-9, atol=1e-12)
            F_now = net_force(model.forces, after.t, after.r, velocity(after.p, after.m), after.m)[0]
            assert np.allclose(page.axis(objects["F_net"][0]), F_now / F_unit, rtol=1e-9, atol=1e-12)
            if n == 2 and args == ("vertical",):   # the README's picture of a Step
                page.page.screenshot(path=str(SCREENSHOTS / "momentum-update.png"))
        # Run on: the p arrow is back, at the same scale, equal to the engine's p at the t shown
        # (Run, then a jump to 2 s, paused there)
        page.click("Run")
        wait_for(lambda: shown_time(page.page) > 3 * model.dt, what="the run to go on")
        jump_to(page.page, 2.0)
        page.page.get_by_role("button", name="Run", exact=True).wait_for()
        objects = page.objects()
        assert (objects["p_unit"], objects["F_unit"]) == (first["p_unit"], first["F_unit"])
        t = shown_time(page.page)
        steps = round(t / model.dt)
        assert t == pytest.approx(2.0)
        engine = model.simulation()
        engine.advance(steps)
        wait_for(lambda: np.allclose(page.axis(objects["p"][0]), engine.state.p[0] / first["p_unit"],
                                     rtol=1e-9, atol=1e-12), what="the p arrow at the t shown")
    finally:
        page.close()


@pytest.mark.parametrize("scene", drawable_scenes())
def test_screenshots_with_arrows(browser, scene):
    shots = [(1280, 800), (1920, 1080)]
    args = (scene, "--arrows", "p,F_net")
    if scene == "pendulum":
        args = (scene, "--arrows", "p,F_net,split")
    # one program and one page for both window sizes (issue 31: a program and a run to t = 2 s each
    # before): jumped to t = 2 s (paused there, issue 35), then the window grows and the page follows it
    page = Page(browser, args, viewport=shots[0])
    try:
        jump_to(page.page, 2.0)
        for width, height in shots:
            page.page.set_viewport_size({"width": width, "height": height})
            wait_for(lambda: page.page.evaluate("() => window.innerWidth") == width,
                     what=f"the window at {width} px")
            page.page.evaluate("() => new Promise(done => requestAnimationFrame(() => requestAnimationFrame(done)))")
            page.page.screenshot(path=str(SCREENSHOTS / f"arrows-{scene}-{width}x{height}.png"))
            objects = page.objects()
            visible = page.page.evaluate("ids => ids.map(i => glowObjs[i].visible)", objects["p"] + objects["F_net"])
            assert any(visible), f"{scene} at {width}x{height}: no arrow shown"
    finally:
        page.close()

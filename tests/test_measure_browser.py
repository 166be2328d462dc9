"""Issue 30, "Measure it like a lab", in headless Chromium (Playwright): every tool of the Measure
panel, its numbers compared with the engine's (physics/simulate.py run here to the same step).

* the panel is closed at first, and opened, the 3-D view and the position graph stay on a
  1280 × 800 screen; nothing scrolls sideways at 1024 × 768, 1280 × 800 or 1920 × 1080, in
  projector mode too, and its text is at least 18 px (22 px in projector mode);
* the stopwatch runs on simulated time through Pause, Step and speed changes, with its keys;
* the period, hidden until its box is ticked, is the engine's samples' crossings to the digit,
  and within its stated spread of 2π/ω_d;
* the natural-length and equilibrium lines sit at L0 and L0 + m g / k below the anchor, and the
  marker dragged to the lowest turning point reads the engine's turning point to a pixel;
* a click on the position graph reads the engine's own sample there, a second the difference;
* phase space's last points are the engine's (x, v) and the closed form's, and the energy bars
  are the engine's K, U of each force (from the equilibrium) and −W_nc.

Each page is jumped to the t it needs (issue 35); every wait is for the page's own text, never a
fixed time.
"""
from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from browser.measure_panel import with_spread
from browser.page_layout import BODY_PX, PROJECTOR_PX
from browser_support import jump_to, launched, require_browser, screenshot_folder, wait_for
from physics.energy import energy_parts
from physics.equilibrium import equilibrium
from physics.period import CrossingMeter, formula_period
from physics.simulate import time_grid
from scenes import catalog
from test_browser import Program, shown_time

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()
SCREENSHOTS = screenshot_folder()
SIZES = ((1024, 768), (1280, 800), (1920, 1080))


@pytest.fixture(scope="module")
def browser():
    with launched(sync_api, scrollbars=True) as chromium:
        yield chromium


def opened(browser, *args, size=(1280, 800), t: float = 0.5):
    """The page, jumped to t (paused there)."""
    program = Program(*args)
    page = browser.new_page(viewport={"width": size[0], "height": size[1]})
    page.goto(program.url())
    jump_to(page, t)
    return program, page


def pause(page) -> float:
    """Paused (pressing Pause if it runs); the t it shows."""
    if page.get_by_role("button", name="Pause", exact=True).count():
        page.get_by_role("button", name="Pause", exact=True).click()
    page.get_by_role("button", name="Run", exact=True).wait_for()
    return shown_time(page)


def run_to(page, t: float) -> None:
    """Run (t goes on), then jump to t: paused there."""
    now = shown_time(page)
    page.get_by_role("button", name="Run", exact=True).click()
    wait_for(lambda: shown_time(page) > now, what="the run to go on")
    jump_to(page, t)


def box(page, label: str):
    """The Measure panel's check box with this label."""
    labels = page.locator(".sm-measure span").filter(has_text=re.compile("^ ?" + re.escape(label)))
    return labels.first.locator("xpath=preceding-sibling::input[1]")


def stopwatch(page) -> float:
    return float(page.locator(".sm-stopwatch").inner_text().replace("\u00a0", " ").split()[0])


def engine_at(setup, integrator: str, t: float):
    """The engine's run of `setup` to the page's t, with the page's graph samples (every 0.05 s)."""
    model = setup.build()
    engine = model.simulation(integrator)
    first = engine.state
    steps = round(t / model.dt)
    samples = engine.advance(steps, record=time_grid(max(model.dt, 0.05), t0=0.0, dt=model.dt), final=False)
    return model, engine, first, samples


def test_the_panel_is_closed_at_first_and_fits_every_window_open(browser):
    program, page = opened(browser, "vertical")
    try:
        assert page.locator(".sm-measure").evaluate("e => getComputedStyle(e).display") == "none"
        page.screenshot(path=str(SCREENSHOTS / "measure-closed.png"))
        page.locator(".sm-measure-toggle").click()
        page.locator(".sm-measure").wait_for(state="visible")
        for width, height in SIZES:
            page.set_viewport_size({"width": width, "height": height})
            for projector in (False, True):
                if page.evaluate("() => !!window.smProjector") != projector:
                    page.evaluate("() => document.activeElement && document.activeElement.blur()")   # keys to the page
                    page.keyboard.press("p")
                smallest = PROJECTOR_PX if projector else BODY_PX

                def fits():
                    shown = page.evaluate("""() => { window.scrollTo(100000, 0);   // the top, as a class sees it
                      const x = window.scrollX; window.scrollTo(0, 0);
                      const fonts = Array.from(document.querySelectorAll('.sm-measure, .sm-measure *'))
                        .filter(e => e.offsetParent !== null).map(e => parseFloat(getComputedStyle(e).fontSize));
                      const box = e => e.getBoundingClientRect();
                      return {sideways: x, font: Math.min(...fonts),
                              canvas: box(document.querySelector('.glowscript-canvas-wrapper canvas')),
                              graph: box(document.querySelector('.glowscript-graph canvas.base')),
                              client: document.documentElement.clientWidth}; }""")
                    return shown if shown["sideways"] == 0 and shown["font"] >= smallest else None
                shown = wait_for(fits, what=f"the open panel to fit {width} × {height}, projector {projector}")
                if (width, height) == (1280, 800):
                    for name in ("canvas", "graph"):
                        place = shown[name]
                        assert place["y"] >= 0 and place["y"] + place["height"] <= height, f"{name} off the screen"
                    page.screenshot(path=str(SCREENSHOTS / f"measure-open-{width}x{height}"
                                                           f"{'-projector' if projector else ''}.png"))
        assert "Traceback" not in "".join(program.errors)
    finally:
        page.close()
        program.stop()


def test_stopwatch_lines_marker_and_reading_the_graph(browser):
    setup = catalog.configure("vertical")
    dt = setup.build().dt
    program, page = opened(browser, "vertical")
    try:
        page.locator(".sm-measure-toggle").click()
        page.locator(".sm-measure").wait_for(state="visible")

        # the stopwatch: started while paused, three Steps, then 2× speed, then stopped
        t0 = pause(page)
        page.get_by_role("button", name="Start (S)", exact=True).click()
        page.get_by_role("button", name="Stop (S)", exact=True).wait_for()
        for n in range(1, 4):
            page.get_by_role("button", name="Step", exact=True).click()
            wait_for(lambda: shown_time(page) == pytest.approx(t0 + n * dt, abs=1e-9), what="a Step")
        wait_for(lambda: stopwatch(page) == pytest.approx(3 * dt, abs=0.006), what="the stopwatch")
        page.evaluate("() => document.activeElement && document.activeElement.blur()")   # keys to the page
        page.keyboard.press("+")                       # 2×
        run_to(page, t0 + 3 * dt + 2.0)
        t1 = pause(page)
        page.evaluate("() => document.activeElement && document.activeElement.blur()")   # keys to the page
        page.keyboard.press("l")                       # a lap, by its key
        page.keyboard.press("s")                       # stop, by its key
        page.get_by_role("button", name="Start (S)", exact=True).wait_for()
        wait_for(lambda: stopwatch(page) == pytest.approx(t1 - t0, abs=0.006), what="the reading")
        assert f"1: {t1 - t0:.2f}" in page.locator(".sm-measure").inner_text()
        page.keyboard.press("c")
        wait_for(lambda: stopwatch(page) == 0.0, what="C to clear it")

        # the lines, where the forces put them: L0 and L0 + m g / k below the anchor
        v = setup.values
        for label in ("natural length", "equilibrium"):
            box(page, label).check()
        labels = wait_for(lambda: (texts := page.evaluate(
            "() => glowObjs.filter(o => o && o.constructor && o.constructor.name === 'label' && o.visible)"
            ".map(o => o.text)")) and any("equilibrium" in t for t in texts) and texts, what="the lines")
        expected = {"natural length": -v["L0"], "equilibrium": -(v["L0"] + v["m"] * v["g"] / v["k"])}
        for name, y in expected.items():
            said = next(t for t in labels if t.startswith(name))
            assert float(said.split("=")[1].replace("−", "-").split()[0]) == pytest.approx(y, abs=5e-4)

        # the marker, dragged to the lowest turning point of the engine's run
        model, engine, first, samples = engine_at(setup, "euler-cromer", 4.0)
        lowest = float(np.min(samples.r[:, 0, 1]))
        box(page, "marker").check()
        wait_for(lambda: page.evaluate("() => glowObjs.some(o => o && o.text && o.text.startsWith('marker ') && "
                                       "o.text.indexOf('=') > 0 && o.visible)"),
                 what="the marker shown (the page has taken the box's click)")
        canvas = page.locator(".glowscript-canvas-wrapper canvas").first.bounding_box()
        x = canvas["x"] + 0.8 * canvas["width"]

        shown = "() => glowObjs.find(o => o && o.text && o.text.startsWith('marker ') && o.text.indexOf('=') > 0).text"

        def marker() -> float:
            return float(page.evaluate(shown).split("=")[1].replace("−", "-").split()[0])

        def clicked_at(pixel_y: float) -> float:
            """A click on the picture puts the marker there (one message): its reading."""
            before = marker()
            page.mouse.click(x, pixel_y)
            return wait_for(lambda: (value := marker()) != before and value, what="the marker to move")
        top, bottom = canvas["y"] + 0.3 * canvas["height"], canvas["y"] + 0.7 * canvas["height"]
        y_top, y_bottom = clicked_at(top), clicked_at(bottom)
        metres_per_pixel = (y_top - y_bottom) / (bottom - top)
        assert metres_per_pixel > 0
        # dragged from the top to where the engine's lowest turning point is on the screen
        aim = top + (y_top - lowest) / metres_per_pixel
        page.mouse.move(x, top)
        page.mouse.down()
        page.mouse.move(x, aim, steps=5)
        page.mouse.up()
        wait_for(lambda: abs(marker() - lowest) <= 1.5 * metres_per_pixel,
                 what=f"the dragged marker to read the lowest turning point, {lowest:.3f} m")
        page.screenshot(path=str(SCREENSHOTS / "measure-lines.png"))

        # reading the position graph: the engine's own samples, then their difference
        t_now = shown_time(page)
        model, engine, first, samples = engine_at(setup, "euler-cromer", t_now)
        graph = page.locator(".glowscript-graph canvas.overlay").first
        place = graph.bounding_box()
        picks = []
        for fraction in (0.3, 0.6):
            graph.click(position={"x": fraction * place["width"], "y": 0.5 * place["height"]})
            picks = wait_for(lambda: (read := page.locator(".sm-read").first).count() and
                             len(p := json.loads(read.get_attribute("data-picks") or "[]")) == len(picks) + 1 and p,
                             what="the graph's reading")
        for t, y, label in picks:
            if label == "y (simulation)":
                n = int(np.argmin(np.abs(samples.t - t)))
                assert samples.t[n] == pytest.approx(t, abs=1e-9)
                assert samples.r[n, 0, 1] == pytest.approx(y, rel=1e-14)     # the page gets 16 digits
            else:
                assert label == "y exact" and model.exact(np.array([t]))[0][0, 0, 1] == pytest.approx(y, rel=1e-12)
        read = page.locator(".sm-read").first.inner_text().replace("\u2212", "-")
        dt_read = float(re.search(r"Δt = (-?[\d.]+)", read).group(1))
        dy_read = float(re.search(r"Δy = (-?[\d.e-]+)", read).group(1))
        assert dt_read == pytest.approx(picks[1][0] - picks[0][0], rel=1e-3, abs=1e-9)
        assert dy_read == pytest.approx(picks[1][1] - picks[0][1], rel=1e-3, abs=1e-6)
        assert "Traceback" not in "".join(program.errors)
    finally:
        page.close()
        program.stop()


def test_period_phase_space_and_energy_bars_are_the_engines(browser):
    setup = catalog.configure("damped").with_values(dt=0.01)
    model = setup.build()
    period = formula_period(model.forces, model.state, closed_form=True)[0][0]
    program, page = opened(browser, "damped", "--integrator", "rk4", "--set", "dt=0.01")
    try:
        page.locator(".sm-measure-toggle").click()
        page.locator(".sm-measure").wait_for(state="visible")
        assert page.locator(".sm-period").count() == 0              # hidden until its box is ticked
        box(page, "period").check()
        # five cycles at least: each crossing is found between samples 0.05 s apart, and what that
        # costs a crossing shifts the mean by at most its range over the number of cycles
        jump_to(page, round(6.5 * period, 2))
        wait_for(lambda: (found := re.search(r"over (\d+) cycles", page.locator(".sm-period").inner_text()))
                 and int(found.group(1)) >= 5, what="five cycles measured")
        t = pause(page)
        text = page.locator(".sm-period").inner_text().replace("\u00a0", " ")
        model, engine, first, samples = engine_at(setup, "rk4", t)
        centre = equilibrium(model.forces, model.state)
        meter = CrossingMeter(centre[:, 1])
        meter.add([0.0], first.r[None, :, 1])
        meter.add(samples.t, samples.r[:, :, 1])
        period = meter.period(0)
        assert with_spread(period.measured, period.spread).replace("\u00a0", " ") in text
        formula = formula_period(model.forces, model.state, closed_form=True)[0][0]
        assert f"formula 2π/ωd = {formula:.5g} s" in text
        assert abs(period.measured - formula) <= period.spread

        # phase space: its last points are the engine's (y, v_y) and the closed form's
        page.locator("select").filter(has=page.locator("option", has_text="phase space")).select_option("phase space")
        series = wait_for(lambda: page.evaluate("""() => { const g = glowObjs.find(o => o && o.graph_options &&
              !o.__deleted && o.title === 'Phase space'); return g && g.graph_series.every(s => s.data.length) &&
              g.graph_series.map(s => [s.label, s.data[s.data.length - 1]]); }"""), what="phase space")
        last = samples.t[-1]
        y, vy = samples.r[-1, 0, 1], samples.p[-1, 0, 1] / samples.m[0]
        exact_r, exact_v = model.exact(np.array([last]))
        for label, (x_shown, v_shown) in series:
            if label == "exact":
                assert (x_shown, v_shown) == pytest.approx((exact_r[0, 0, 1], exact_v[0, 0, 1]), rel=1e-12)
            else:
                assert (x_shown, v_shown) == pytest.approx((y, vy), rel=1e-14)
        page.screenshot(path=str(SCREENSHOTS / "measure-phase-space.png"))

        # the energy bars: K, U spring, U gravity (from the equilibrium), −W_nc (damping), total
        page.locator("select").filter(has=page.locator("option", has_text="phase space")).select_option("energy bars")
        cells = page.locator(".sm-bar-value")
        wait_for(lambda: cells.count() == 5, what="the energy bars")
        labels = page.locator(".sm-bar-label").all_inner_texts()
        assert labels == ["K", "U spring", "U gravity", "−W_nc (damping)", "total"]
        shown = [float(value) for value in cells.evaluate_all("cells => cells.map(c => c.dataset.joules)")]
        parts = energy_parts(engine.state, model.forces, engine.work, reference=centre)
        expected = [part.value for part in parts]
        assert shown == pytest.approx(expected + [sum(expected)], rel=1e-9, abs=1e-9)
        assert math.isclose(shown[-1], sum(shown[:-1]), rel_tol=1e-12, abs_tol=1e-12)
        page.screenshot(path=str(SCREENSHOTS / "measure-energy-bars.png"))
        assert "Traceback" not in "".join(program.errors)
    finally:
        page.close()
        program.stop()

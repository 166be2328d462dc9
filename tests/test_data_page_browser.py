"""The page's measured data in a real browser: Load data, the dots on the position graph, Fit.

The fixture is the program's own: `main.py damped --mystery FILE --seed N` (a Vernier CSV of a
spring with hidden k and b). The page is driven as a student drives it: the file is chosen in the
Load data button's file input (Playwright's set_input_files), and Fit is clicked. What the page
shows is held against the command line on the same file: the RMS residual of `--data FILE`, and
the k and b of `--data FILE --fit k,b`, with the page's integrator and Δt (the scene's own).

1. A bad file (binary) shows its one line on the page and loads nothing; a file sent by anything
   but the page (a foreign Origin, or none) is refused; then the mystery file loads, its dots are
   drawn on the position graph in the data colour, and Fit moves the k and b sliders to the
   command line's fitted values with the page's own model (`--integrator euler-cromer --set
   dt=0.1`). Halving that Δt moves them by many σ, so the page shows them without ± figures and,
   in their place, the sentence saying they cannot be trusted and why.
2. `--data FILE --page` shows the same comparison from the start; at a small Δt, where the fit
   takes seconds, the page (jumped to t = 10 s, where the data's release falls, then Run) says
   "fitting k, b…" while its clock goes on, then shows the values `--fit k,b` prints.
3. While data is loaded the position graph's time axis stays over the whole data: long after the
   data's last point the dots are still on the graph (it used to scroll them off).

Skipped, with the reason, where Chromium or Playwright is missing.
"""
from __future__ import annotations

import http.client
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from browser.readout import length_text
from lab.compare import Estimate
from browser_support import jump_to, pixels_like, require_browser, screenshot_folder, wait_for
from test_browser import Program, crop, graph_boxes, shown_time

ROOT = Path(__file__).resolve().parent.parent
DATA_BLUE = (0, 114, 178)          # export/palette.py's BLUE, the measured points' colour
SEED = 5

pytestmark = pytest.mark.browser
sync_api, Image = require_browser()


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def mystery(tmp_path: Path) -> Path:
    path = tmp_path / "spring.csv"
    made = cli("damped", "--mystery", str(path), "--seed", str(SEED))
    assert made.returncode == 0, made.stderr
    return path


def headless(path: Path, *fit: str) -> dict:
    """`--data FILE ... --json` as a dict: exit status 0, or 3 for a fit whose numbers cannot be trusted."""
    done = cli("damped", "--data", str(path), *fit, "--json")
    assert done.returncode in (0, 3), done.stderr
    out = json.loads(done.stdout)
    assert done.returncode == (3 if out["trusted"] is False else 0)
    return out


def data_lines(page) -> str:
    """The page's text, its no-break spaces (kept around ±) read as spaces."""
    return page.locator("body").inner_text().replace("\u00a0", " ")


def rms_shown(page) -> str | None:
    """The RMS residual as the page writes it, number and unit (`2.13 mm`), or None."""
    found = re.search(r"RMS residual = (\S+ \S*m)\b", data_lines(page))
    return found.group(1) if found else None


def rms_written(metres: float) -> str:
    """An RMS residual in metres as the page writes it (browser/readout.py), read as data_lines does."""
    return length_text(metres).replace("\u00a0", " ")


def position_graph_blue(page, tmp_path: Path, name: str) -> int:
    """Pixels of the data colour inside the position graph's plot (the legend is outside it)."""
    shot = tmp_path / f"{name}.png"
    page.screenshot(path=str(shot), full_page=True)
    return pixels_like(crop(shot, graph_boxes(page)[0]), DATA_BLUE, within=60)


def slider_values(page) -> list[tuple[float, float]]:
    """Each slider's (value, step) as the page's jQuery UI sliders hold them, in page order (m, k, b)."""
    return page.evaluate("Array.from(document.querySelectorAll('.ui-slider')).map(function (e) {"
                         " return [$(e).slider('value'), $(e).slider('option', 'step')]; })")


def post(port: int, body: bytes, origin: str | None) -> int:
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    headers = {"Content-Type": "application/octet-stream", "X-File-Name": "evil.csv"}
    if origin:
        headers["Origin"] = origin
    connection.request("POST", "/data", body=body, headers=headers)
    status = connection.getresponse().status
    connection.close()
    return status


def test_load_data_overlay_and_fit_move_the_sliders(browser, tmp_path):
    path = mystery(tmp_path)
    compared = headless(path)
    fitted = headless(path, "--fit", "k,b", "--integrator", "euler-cromer", "--set", "dt=0.1")
    assert fitted["trusted"] is False and "halving Δt = 0.1 s moves k" in fitted["trust_reason"]
    bad = tmp_path / "scope.bin"
    bad.write_bytes(bytes(range(256)) * 8)
    program = Program("damped")
    try:
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        page.goto(program.url())
        wait_for(lambda: shown_time(page) > 0, what="the scene to run")
        assert rms_shown(page) is None and position_graph_blue(page, tmp_path, "before") < 20

        # Only the page itself may send a file.
        assert post(program.port, path.read_bytes(), origin="http://evil.example") == 403
        assert post(program.port, path.read_bytes(), origin=None) == 403

        page.locator("#sm-data-file").set_input_files(str(bad))
        wait_for(lambda: "scope.bin line" in data_lines(page), what="the bad file's one line")
        error = next(line for line in data_lines(page).splitlines() if "scope.bin line" in line)
        assert error.startswith("Data: scope.bin line 1:") and "binary" in error
        assert rms_shown(page) is None and not re.search(r"\d+ points", data_lines(page))
        assert position_graph_blue(page, tmp_path, "refused") < 20

        page.locator("#sm-data-file").set_input_files(str(path))
        wait_for(lambda: rms_shown(page), what="the comparison's RMS residual")
        assert rms_shown(page) == rms_written(compared['rms_residual'])
        assert "spring.csv: 312 points" in data_lines(page) and "scope.bin" not in data_lines(page)

        page.get_by_role("button", name="Fit", exact=True).click()
        shown = wait_for(lambda: page.locator(".sm-fit").count() and page.locator(".sm-fit").inner_text(),
                         what="the fitted values")
        assert "±" not in shown                   # no ± figures for numbers that cannot be trusted
        for name, unit in (("k", "N/m"), ("b", "kg/s")):
            value = float(re.search(rf"{name} = (\S+) {unit}", shown).group(1))
            expected = fitted["fit"][name]
            assert abs(value - expected["value"]) <= 0.1 * expected["uncertainty"], (name, value, expected)
        sentence = page.locator(".sm-untrusted").inner_text()
        assert sentence.startswith("These numbers cannot be trusted: ") and "halving Δt = 0.1 s moves k by" in sentence

        def sliders_at_the_fit():
            values = slider_values(page)
            return len(values) == 3 and all(
                abs(values[i][0] - fitted["fit"][name]["value"]) <= 0.51 * values[i][1]
                for i, name in ((1, "k"), (2, "b"))) and values
        wait_for(sliders_at_the_fit, what="the k and b sliders to move to the fitted values")
        k = fitted["fit"]["k"]["value"]
        wait_for(lambda: f"k = {k:.6g} N/m" in data_lines(page), what="the fitted k in the caption")
        jump_to(page, 1.0)                 # the run with the fitted values, taken to 1 s
        # The fitted release is at the data's start, so the dots are on the graph from t = 0.
        wait_for(lambda: position_graph_blue(page, tmp_path, "fitted") > 100,
                 what="the measured dots on the position graph")
        page.screenshot(path=str(screenshot_folder() / "data-fitted-1280x800.png"))
        page.close()
    finally:
        program.stop()
    assert not [line for line in program.errors if "Traceback" in line], program.errors


def test_data_on_the_command_line_shows_on_the_page_and_fitting_does_not_stop_the_run(browser, tmp_path):
    """--data FILE --page, at a Δt small enough that the fit takes seconds: the page shows the
    comparison from the start, says "fitting k, b…" while the run goes on, then the fit's values."""
    path = mystery(tmp_path)
    model = ("--integrator", "rk4", "--set", "dt=0.0001")      # a fit of 25 runs of 200,000 steps: seconds anywhere
    compared, fitted = headless(path, *model), headless(path, *model, "--fit", "k,b")
    program = Program("damped", "--data", str(path), "--page", *model)
    try:
        page = browser.new_page(viewport={"width": 1920, "height": 1080})
        page.goto(program.url())
        wait_for(lambda: rms_shown(page), what="the comparison's RMS residual")
        assert rms_shown(page) == rms_written(compared['rms_residual'])
        for symbol, key in (("t₀", "t_offset"), ("y₀", "position_offset")):
            assert f"{symbol} = {Estimate(**compared['fit'][key])}" in data_lines(page)
        # With the scene's own k and b the data's release lands at the model's t ≈ 9 s: the dots
        # show once the page's clock gets there (a jump: paused there).
        jump_to(page, 10.0)
        wait_for(lambda: position_graph_blue(page, tmp_path, "cli") > 100,
                 what="the measured dots on the position graph")
        page.screenshot(path=str(screenshot_folder() / "data-loaded-1920x1080.png"))

        page.get_by_role("button", name="Run", exact=True).click()
        page.get_by_role("button", name="Fit", exact=True).click()
        wait_for(lambda: "fitting k, b…" in data_lines(page), what="the page to say it is fitting")
        during = shown_time(page)
        wait_for(lambda: "fitting k, b…" in data_lines(page) and shown_time(page) > during,
                 what="the run to go on while the fit works")
        shown = wait_for(lambda: page.locator(".sm-fit").count() and page.locator(".sm-fit").inner_text(),
                         what="the fitted values")
        for name, unit in (("k", "N/m"), ("b", "kg/s")):
            assert f"{name} = {Estimate(**fitted['fit'][name])}" in shown.replace("\u00a0", " ")
        page.close()
    finally:
        program.stop()


def test_the_position_graph_holds_the_data_in_view_long_after_its_last_point(browser, tmp_path):
    """The position graph used to scroll its 30 s window on with the clock, so the data's dots left
    it 30 to 45 s into the run. While data is loaded, its time axis stays over the whole data."""
    from lab import readers

    path = mystery(tmp_path)
    compared = headless(path)
    measured = readers.read(str(path))
    t_offset = compared["fit"]["t_offset"]["value"]
    first, last = measured.t[0] - t_offset, measured.t[-1] - t_offset      # the dots' model times, s
    program = Program("damped", "--data", str(path), "--page")
    try:
        page = browser.new_page(viewport={"width": 1024, "height": 768})
        page.goto(program.url())
        wait_for(lambda: rms_shown(page), what="the comparison's RMS residual")
        jump_to(page, round(last + 41, 1))     # 40 s past the data's last point
        axis = page.locator(".glowscript-graph").nth(0).locator(".xAxis .tickLabel")

        def ticks():
            return [float(label.replace("−", "-")) for label in axis.all_inner_texts() if label.strip()]
        wait_for(lambda: len(ticks()) >= 3, what="the position graph's time labels")
        shown = ticks()
        assert min(shown) <= max(first, 0.0) and max(shown) >= last - (shown[1] - shown[0]), (shown, first, last)
        assert max(shown) < shown_time(page) - 20, (shown, shown_time(page))   # not following the clock
        assert position_graph_blue(page, tmp_path, "held") > 100
        page.close()
    finally:
        program.stop()
    assert not [line for line in program.errors if "Traceback" in line], program.errors


def test_a_file_loaded_late_in_the_run_restarts_it_so_the_model_spans_the_data(browser, tmp_path):
    """Loaded 10 s into a run, the file's dots showed, but the model's curve for the data's first
    seconds had already scrolled out of the graph's records, so it was missing until Reset or Fit.
    Loading data now restarts the run from t = 0, as a slider does, and says so on the page."""
    path = mystery(tmp_path)
    program = Program("damped")
    try:
        page = browser.new_page(viewport={"width": 1024, "height": 768})
        page.goto(program.url())
        jump_to(page, 10.5)                    # 10 s into the run, paused there
        assert "or loading data restarts the run from t = 0" in data_lines(page)
        page.locator("#sm-data-file").set_input_files(str(path))
        wait_for(lambda: rms_shown(page), what="the comparison's RMS residual")
        wait_for(lambda: shown_time(page) < 10, what="the run to start again from t = 0 after the file was read")
        assert shown_time(page) < 10
        axis = page.locator(".glowscript-graph").nth(0).locator(".xAxis .tickLabel")
        wait_for(lambda: [label for label in axis.all_inner_texts() if label.strip()],
                 what="the position graph's time labels")
        ticks = [float(label.replace("−", "-")) for label in axis.all_inner_texts() if label.strip()]
        assert min(ticks) <= 0.0, ticks          # the graph shows the model from its start
        page.close()
    finally:
        program.stop()
    assert not [line for line in program.errors if "Traceback" in line], program.errors

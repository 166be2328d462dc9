"""The page's measured data without a browser: browser/data_panel.py's MeasuredData, the upload's
name, and the command line's --data FILE --page.

The fixture is the program's own mystery spring (lab/mystery.py, as `--mystery` writes it). What the
page shows is held against lab/compare.py's answer for the same file and constants, and the
dots against the data moved by the offsets by hand.
"""
from __future__ import annotations

import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from browser.data_panel import MAX_DOTS, MeasuredData
from browser.readout import length_text
from browser.server.http_server import upload_name
from lab import compare, mystery
from scenes import catalog

ROOT = Path(__file__).resolve().parent.parent


@pytest.fixture(scope="module")
def spring():
    setup = catalog.configure("damped")
    run = mystery.make(setup, seed=5, given=set(), coordinate="y")
    return setup, mystery.text(run).encode("utf-8")


def answer(data: MeasuredData, timeout: float = 120.0):
    """Wait for the thread's answer, as the frame loop does between frames."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        got = data.finished()
        if got is not False:
            return got
        time.sleep(0.02)
    pytest.fail("no answer from the comparison's thread")


def test_a_loaded_file_is_compared_off_the_calling_thread_and_shown(spring):
    setup, raw = spring
    data = MeasuredData()
    assert data.text() == "" and data.points() == []
    data.load(raw, "spring.csv", setup, "euler-cromer")
    assert data.working == "reading" and "reading spring.csv…" in data.text()
    result = answer(data)
    expected = compare.compare(setup, data.measured.t, data.measured.position, integrator="euler-cromer",
                               coordinate="y")
    assert result.rms == pytest.approx(expected.rms, rel=1e-9)
    text = data.text()
    assert f"RMS residual = {length_text(expected.rms)}</b>" in text       # as the page writes every length
    assert f"t₀ = {expected.t_offset}".replace(" ± ", "\u00a0±\u00a0") in text
    assert "nan" not in text and "inf" not in text
    # The dots are the data on the model's axes: t − t₀, y − y₀.
    dots = np.array(data.points())
    assert len(dots) == len(expected.t) <= MAX_DOTS
    assert np.allclose(dots[:, 0], expected.t - expected.t_offset.value)
    assert np.allclose(dots[:, 1], expected.data - expected.position_offset.value)
    # The same constants again: nothing to work out.
    data.compare(setup, "euler-cromer")
    assert data.working == "" and data.finished() is False
    # Other constants: compared again, on the thread.
    data.compare(setup.with_values(k=45.0), "euler-cromer")
    assert data.working == "comparing" and "comparing…" in data.text()
    assert answer(data).setup.values["k"] == 45.0


def fitting(spring) -> MeasuredData:
    """The mystery file loaded and compared, and a fit of k and b started."""
    setup, raw = spring
    data = MeasuredData()
    data.load(raw, "spring.csv", setup, "euler-cromer")
    answer(data)
    data.compare(setup, "euler-cromer", fit=True)
    return data


def test_fit_gives_the_command_lines_values_and_says_fitting_meanwhile(spring):
    """The page fits with its own integrator and Δt (Euler-Cromer at 0.1 s), as `--data FILE --fit k,b
    --integrator euler-cromer --set dt=0.1` does: the same values. Halving that Δt moves them by
    many σ, so the page shows the values without ± figures and, in their place, the sentence saying
    the numbers cannot be trusted and why (the lesson: the model's own error)."""
    setup, _ = spring
    data = fitting(spring)
    assert "fitting k, b…" in data.text()
    result = answer(data)
    expected = compare.compare(setup, data.measured.t, data.measured.position, integrator="euler-cromer",
                               coordinate="y", fit=("k", "b"))
    assert not expected.trust.trusted and "halving Δt = 0.1 s moves k by" in expected.trust.sentence
    text = data.text()
    for name in ("k", "b"):
        assert result.fitted[name].value == pytest.approx(expected.fitted[name].value, rel=1e-9)
        assert f"{name} = {expected.fitted[name].plain}" in text
    assert "±" not in text.split("Fit:")[1].split("\n")[0]          # no ± figures for untrusted numbers
    assert "These numbers cannot be trusted: halving Δt = 0.1 s moves k by" in text
    # The fitted constants are what the page now runs (the fitted release too, as its vector):
    # comparing them again is not needed.
    assert set(result.fitted) == {"k", "b", "r0"}
    fitted = setup.with_values(**{name: result.setup.values[name] for name in result.fitted})
    data.compare(fitted, "euler-cromer")
    assert data.working == "" and data.finished() is False


def test_a_fit_with_a_fine_model_shows_its_figures_with_their_uncertainties(spring):
    """rk4 at Δt = 0.002 s: the fit can be trusted, and the page shows each value ± its σ."""
    setup, raw = spring
    fine = setup.with_values(dt=0.002)
    data = MeasuredData()
    data.load(raw, "spring.csv", fine, "rk4")
    answer(data)
    data.compare(fine, "rk4", fit=True)
    result = answer(data)
    assert result.trust.trusted
    for name in ("k", "b"):
        assert f"{name} = {result.fitted[name]}".replace(" ± ", "\u00a0±\u00a0") in data.text()
    assert "cannot be trusted" not in data.text()


def test_data_read_mirrored_shows_its_dots_on_the_model_and_says_the_axis_points_down():
    """A detector above the mass: the dots are −(y − y₀), on the model's own axes, and the page
    says which way the data's axis was taken (the command line's --data-sign, or both tried)."""
    setup = catalog.configure("damped")
    run = mystery.make(setup, seed=5, given=set(), coordinate="y")
    down = mystery.text(mystery.Mystery(t=run.t, position=-run.position, answer=run.answer, known=run.known,
                                        rate=run.rate, noise=run.noise)).encode("utf-8")
    truth = setup.with_values(**{name: value for name, (value, _) in run.answer.items()})
    data = MeasuredData()
    data.load(down, "down.csv", truth, "euler-cromer")
    result = answer(data)
    assert result.sign == -1
    assert "the data's axis points down: the model is compared with −y" in data.text()
    assert "−(y − y₀)" in data.text()
    dots = np.array(data.points())
    model_y = -(result.model - result.position_offset.value)      # the model's own y at the data's times
    assert len(dots) == result.points and np.allclose(np.abs(dots[:, 1] - model_y), np.abs(result.residual))
    assert result.rms < 0.1 * np.ptp(model_y)       # the dots lie along the model's swing, not mirrored
    forced = MeasuredData(sign=1)
    forced.load(down, "down.csv", truth, "euler-cromer")
    assert answer(forced).sign == 1 and "points down" not in forced.text()


def test_a_dt_longer_than_the_data_interval_says_what_the_page_offers_not_a_command_line(spring):
    """damped's page has no Δt slider: the note names the integrator menu, not --set dt=...; a page
    with a Δt slider is told to move it."""
    setup, raw = spring
    data = MeasuredData()
    data.load(raw, "spring.csv", setup, "euler-cromer")
    result = answer(data)
    assert result.slow_dt and result.slow_dt[0] == 0.1
    text = data.text()
    assert "--set" not in text and "choose rk4 in the integrator menu" in text
    assert "Δt = 0.1 s is longer than the data's sample interval" in text
    assert "move the Δt slider to 0.001 s" in data.text(dt_slider=True)


def test_an_answer_overtaken_by_a_newer_request_is_dropped(spring):
    setup, _ = spring
    data = fitting(spring)
    moved = setup.with_values(k=50.0)
    data.compare(moved, "euler-cromer")          # a slider moved while the fit ran
    result = answer(data)
    assert not result.fitted and result.setup.values["k"] == 50.0
    for thread in threading.enumerate():     # the overtaken fit has finished too, not just 0.5 s passed
        if thread.name == "measured-data-fit":
            thread.join(timeout=120)
    assert data.finished() is False and data.result is result


def test_a_slider_moved_while_a_file_is_read_does_not_drop_the_file(spring):
    setup, raw = spring
    data = MeasuredData()
    data.load(raw, "first.csv", setup, "euler-cromer")
    answer(data)
    data.load(raw, "spring.csv", setup, "euler-cromer")
    data.compare(setup.with_values(k=45.0), "euler-cromer")     # a slider moved meanwhile
    data.compare(setup.with_values(k=45.0), "euler-cromer", fit=True)
    assert data.working == "reading"
    result = answer(data)
    assert data.measured.path == "spring.csv" and result.setup.values["k"] == setup.values["k"]
    data.compare(setup.with_values(k=45.0), "euler-cromer")     # what the frame loop then asks
    assert answer(data).setup.values["k"] == 45.0


def test_a_bad_file_says_its_one_line_and_keeps_what_was_loaded(spring):
    setup, raw = spring
    data = MeasuredData()
    data.load(b"\x00\x01\x02\x03" * 64, "scope.bin", setup, "euler-cromer")
    assert answer(data) is None
    assert data.measured is None and data.text().startswith("<b>Data:</b> scope.bin line 1:")
    assert data.text().count("\n") == 0
    data.load(raw, "spring.csv", setup, "euler-cromer")
    shown = answer(data)
    data.load("t,y\n0,1\n0,2\n".encode(), "<b>x</b>.csv", setup, "euler-cromer")
    assert answer(data) is None
    assert data.measured.path == "spring.csv" and data.result is shown and data.points()
    assert "&lt;b&gt;x&lt;/b&gt;.csv" in data.text() and "<b>x</b>" not in data.text()


def test_a_fit_that_cannot_be_made_says_so_and_keeps_the_comparison(spring):
    setup, raw = spring
    data = MeasuredData(fit_names=("k", "m"))
    data.load(raw, "spring.csv", setup, "euler-cromer")
    shown = answer(data)
    data.compare(setup, "euler-cromer", fit=True)
    assert answer(data) is None
    assert "k and m cannot be told apart" in data.text() and data.result is shown


def test_a_scene_the_data_cannot_be_compared_with_takes_the_dots_off(spring):
    setup, raw = spring
    data = MeasuredData()
    data.load(raw, "spring.csv", setup, "euler-cromer")
    answer(data)
    data.compare(catalog.configure("integrators"), "euler-cromer")
    assert answer(data) is None
    assert data.points() == [] and "masses" in data.text()


@pytest.mark.parametrize("header, name", [
    ("spring%20data.csv", "spring data.csv"),
    ("..%2F..%2Fetc%2Fpasswd", "passwd"),
    ("C%3A%5CUsers%5Cme%5Crun.txt", "run.txt"),
    ("a%0Ab%1B.csv", "ab.csv"),
    ("", "the file"),
    ("x" * 200, "x" * 80),
])
def test_a_sent_files_name_is_its_base_name_in_printable_characters(header, name):
    assert upload_name(header) == name


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("args, words", [
    (["--page"], "--page needs --data"),
    (["--data", "x.csv", "--page", "--json"], "--json does nothing with --data --page"),
    (["--data", "x.csv", "--page", "--plot", "f.png"], "--plot does nothing with --data --page"),
    (["--data", "x.csv", "--port", "8000"], "add --page to show the data on the page"),
    (["--data", "no-such-file.csv", "--page"], "no-such-file.csv: cannot read it"),
])
def test_page_flags_that_do_not_fit_are_one_line_before_any_page_opens(args, words):
    done = cli("damped", *args)
    assert done.returncode == 2 and words in done.stderr and done.stderr.count("\n") == 1, done.stderr
    assert "http://" not in done.stdout


def test_page_with_fit_names_that_cannot_be_fitted_is_one_line(tmp_path, spring):
    path = tmp_path / "spring.csv"
    path.write_bytes(spring[1])
    done = cli("damped", "--data", str(path), "--page", "--fit", "k,m")
    assert done.returncode == 2 and "k and m cannot be told apart" in done.stderr
    assert done.stderr.count("\n") == 1 and "http://" not in done.stdout

"""Measured-data files that used to hang, crash or be misread, run as a user runs them (main.py as a
subprocess, each with a timeout so that a hang fails the test instead of stopping the suite), and
the lab's messages (issue 28 item 5): each one line, every number in it rounded to the digits that
matter.

Issue 27 item 7: a FIFO, a device or a link to one is refused at once; the read stops at the byte
cap whatever size the system reports; implausible time units are caught from the data's own
spacing before any run; a position column that does not move is one line naming it (exit 2);
thousands separators are read right or refused; a fit longer than a second shows its progress.
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from lab import readers  # noqa: E402


def cli(*args, timeout=120) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "main.py", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=timeout)


def one_line(done) -> str:
    """The error line of a refused command: exit status 2, nothing on stdout, one line, no traceback,
    no numpy warning, and no number longer than 12 characters."""
    assert done.returncode == 2, (done.returncode, done.stdout, done.stderr)
    assert done.stdout == "" and done.stderr.count("\n") == 1 and "Traceback" not in done.stderr, done.stderr
    assert "Warning" not in done.stderr and "warning" not in done.stderr
    longest = max((len(number) for number in re.findall(r"[\d.,e+-]*\d", done.stderr)), default=0)
    assert longest <= 12, done.stderr
    return done.stderr


def spring_rows(t) -> str:
    return "".join(f"{a:.4f},{0.5 + 0.05 * np.cos(6 * a):.5f}\n" for a in t)


# ---- files that are no files ----

@pytest.mark.parametrize("page", [False, True])
def test_a_fifo_is_refused_at_once(tmp_path, page):
    fifo = tmp_path / "data.csv"
    os.mkfifo(fifo)
    done = cli("damped", "--data", str(fifo), *(["--page", "--no-browser"] if page else []), timeout=60)
    said = one_line(done)
    assert "a FIFO" in said and str(fifo) in said


@pytest.mark.parametrize("target", ["/dev/zero", "/dev/urandom"])
def test_a_device_or_a_link_to_one_is_refused_without_reading_it(tmp_path, target):
    if not os.path.exists(target):
        pytest.skip(f"{target} is not on this system")
    link = tmp_path / "run.csv"
    link.symlink_to(target)
    for path in (target, str(link)):
        said = one_line(cli("damped", "--data", path, timeout=60))
        assert "a device" in said


def test_the_read_stops_at_the_byte_cap_whatever_the_size_reports(tmp_path, monkeypatch):
    """A file whose size reads 0 (as /proc's files and some devices' do) is still read no further
    than the cap."""
    path = tmp_path / "big.csv"
    path.write_text("t,y\n" + spring_rows(np.arange(0, 2000) * 0.02))
    monkeypatch.setattr(readers, "MAX_BYTES", 1000)
    monkeypatch.setattr(readers.os.path, "getsize", lambda _: 0)
    with pytest.raises(readers.DataError, match="holds more than"):
        readers.read(str(path))


# ---- what the numbers say ----

def test_timestamps_in_nanoseconds_with_no_unit_are_refused_before_any_run(tmp_path):
    """Spacing around 2e7 with no unit: not seconds. Refused from the file's own spacing, before any
    run of the model (it took 40 s, and with --set dt=0.001 over a minute)."""
    path = tmp_path / "ns.csv"
    t = np.arange(0, 500) * 20_000_000
    path.write_text("t,y\n" + "".join(f"{a},{0.5 + 0.05 * np.cos(6e-9 * a):.5f}\n" for a in t))
    for extra in ([], ["--set", "dt=0.001", "--fit", "k,b"]):
        said = one_line(cli("damped", "--data", str(path), *extra, timeout=60))
        assert "the rows are 2e+07 s apart" in said and "Time (ms)" in said


@pytest.mark.parametrize("args, name, hint", [
    (["damped", "--data-column", "x"], "x", "'y' moves: --data-column y"),
    (["driven"], "x", "'y' moves: --data-column y"),
])
def test_a_position_column_that_does_not_move_is_one_line_naming_it(tmp_path, args, name, hint):
    """A Tracker file whose x never moves, read for x (by --data-column, or as the driven scene's
    coordinate): one line naming the column (it was exit 1, ZeroDivisionError)."""
    path = tmp_path / "tracker.txt"
    t = np.arange(0, 300) / 30
    path.write_text("mass A\nt\tx\ty\n" + "".join(f"{a:.4f}\t0.4200\t{0.3 + 0.05 * np.cos(6 * a):.4f}\n" for a in t))
    said = one_line(cli(args[0], "--data", str(path), *args[1:]))
    assert f"column {name!r} does not move (every row reads 0.42 m)" in said and hint in said


def test_a_file_of_equal_positions_is_one_line(tmp_path):
    path = tmp_path / "still.csv"
    path.write_text("t,y\n" + "".join(f"{a / 20:.3f},1.5\n" for a in range(100)))
    assert "column 'y' does not move (every row reads 1.5 m)" in one_line(cli("damped", "--data", str(path)))


def test_thousands_separators_are_read_right_or_refused(tmp_path):
    """A quoted "1,600.7" (mm) in a comma-separated file is 1600.7 mm, not 1; a tab-separated
    "1,601" in a file that never shows its decimal mark could be 1.601 or 1601: refused."""
    quoted = tmp_path / "quoted.csv"
    t = np.arange(0, 200) * 0.02
    quoted.write_text("t (s),y (mm)\n" + "".join(f'{a:.2f},"1,{600 + 50 * np.cos(6 * a):06.2f}"\n' for a in t))
    read = readers.read(str(quoted))
    assert read.position == pytest.approx(1.6 + 0.05 * np.cos(6 * t), abs=1e-5)
    done = cli("damped", "--data", str(quoted), "--json")
    assert done.returncode == 0 and json.loads(done.stdout)["data_points"] == 200
    tabbed = tmp_path / "tabbed.txt"
    tabbed.write_text("t (s)\ty (mm)\n" + "".join(f"{n}\t1,{600 + n % 7:03d}\n" for n in range(50)))
    said = one_line(cli("damped", "--data", str(tabbed)))
    assert "'1,600' could be 1.600 or 1600" in said and "thousands" in said


def test_a_fit_longer_than_a_second_shows_its_progress(monkeypatch):
    """The fit says how far it got once a second after its first second (the clock is made to run
    two seconds a run here, so the test does not depend on how fast the machine is)."""
    from lab import model_run
    from lab.compare import compare
    from scenes import catalog

    clock = iter(np.arange(0.0, 10_000.0, 2.0))
    monkeypatch.setattr(model_run.time, "monotonic", lambda: float(next(clock)))
    lines = []
    measured = readers.read(str(ROOT / "examples" / "data" / "vernier.csv"))
    compare(catalog.configure("damped", assignments=["m=0.5"]), measured.t, measured.position, fit=("k", "b"),
            choose=True, given={"m"}, progress=lines.append)
    assert lines and all(re.fullmatch(r"fitting: \d+ runs of the model so far \(\d+ s\)", line) for line in lines)


def test_the_command_line_passes_the_fits_progress_to_stderr(tmp_path):
    """A fit that takes more than a second by construction, on any machine: the model is
    tests/held_run.py's `held` scene with its force that waits once per run (slow_scene), SLOW s
    where a run first passes SLOW_FROM while the gate is shut, so the fit's first run over this
    2.5 s record ends over a second after the fit began, with a progress line on standard error.
    Once it is read the gate opens, the fit goes on at full speed, and the result follows. (It
    was a fit made slow by its size, 240,000 rk4 steps a run: a minute under load, and on a fast
    enough machine no progress line at all.)"""
    from held_run import SLOW_FROM, open_gate, slow_scene

    until = 2.5
    assert SLOW_FROM < until
    env, gate = slow_scene(tmp_path / "scenes")
    record = tmp_path / "held.csv"                     # the same motion (Held pushes with 0 N), at full speed
    made = cli("vertical", "--headless", "--set", "dt=0.001", "--until", str(until), "--csv", str(record))
    assert made.returncode == 0, made.stderr
    fit = subprocess.Popen([sys.executable, "main.py", "held", "--data", str(record), "--fit", "k",
                            "--set", "dt=0.001"], cwd=ROOT, env=env, text=True,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        said = []
        while not said or not (said[-1].startswith("fitting:") or said[-1] == ""):
            said.append(fit.stderr.readline())
        open_gate(gate)
        out, rest = fit.communicate(timeout=240)
    finally:
        if fit.poll() is None:
            fit.kill()
            fit.wait()
    assert re.fullmatch(r"fitting: \d+ runs of the model so far \(\d+ s\)\n", said[-1]), said
    assert fit.returncode in (0, 3), rest
    found = re.search(r"^k = (\S+) ", out, re.MULTILINE)
    assert found and float(found.group(1)) == pytest.approx(40.0, rel=1e-3), out


# ---- the lab's messages (issue 28 item 5) ----

def test_a_dt_equal_to_the_sample_interval_draws_no_note_and_a_longer_one_says_both_numbers(tmp_path):
    """"dt = 0.1 s is longer than the data's sample interval 0.1 s" came from round-off. A file sampled
    every 0.1 s draws no note at dt = 0.1 s; one sampled every 0.05 s says 0.1 and 0.05."""
    for step, note in ((0.1, False), (0.05, True)):
        path = tmp_path / f"every-{step}.csv"
        path.write_text("t,y\n" + spring_rows(np.arange(0, 400) * step))
        done = cli("damped", "--data", str(path))
        assert done.returncode == 0, done.stderr
        said = [line for line in done.stderr.splitlines() if "sample interval" in line]
        assert bool(said) == note, done.stderr
        if note:
            assert "dt = 0.1 s is longer than the data's sample interval 0.05 s" in said[0]


def test_a_record_too_long_for_dt_names_its_span_and_a_dt_that_is_then_accepted(tmp_path):
    """A 4000 s file with --set dt=0.001: the message gave "the data span 6003 s" and suggested
    --set dt=0.001 itself. Now it names the 4000 s and a Δt the same check accepts."""
    path = tmp_path / "long.csv"
    path.write_text("t,y\n" + spring_rows(np.arange(0, 4000, 0.5)))
    said = one_line(cli("damped", "--data", str(path), "--set", "dt=0.001"))
    assert "the data span 4000 s" in said
    suggested = re.search(r"use dt = (\S+) s or more", said).group(1)
    done = cli("damped", "--data", str(path), "--set", f"dt={suggested}", "--json", timeout=600)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout)["data_points"] == 8000


def test_decimal_commas_between_commas_are_one_line_saying_so(tmp_path):
    """"time 4 does not increase from the row above (4)": the cells were split at the decimal commas."""
    path = tmp_path / "commas.csv"
    path.write_text("t,y\n" + "".join(f"{n / 10:.1f},{0.5 + 0.05 * np.cos(n / 3):.4f}\n".replace(".", ",")
                                      for n in range(60)))
    said = one_line(cli("damped", "--data", str(path)))
    assert "4 cells, but the header names 2" in said and "decimal comma" in said


@pytest.mark.parametrize("size, words", [("1e200", "reads 2e+200 m, far beyond any spring"),
                                         ("1e-300", "moves by 1e-300 m at most")])
def test_absurd_positions_are_one_short_line(tmp_path, size, words):
    """Positions of 1e200 m printed five numpy warnings and a 200-digit number; of 1e-300 m a
    300-digit percentage."""
    path = tmp_path / "absurd.csv"
    path.write_text("t,y\n" + "".join(f"{n / 20:.2f},{(1 + n % 2) * float(size):g}\n" for n in range(100)))
    for extra in ([], ["--fit", "k,b"]):
        assert words in one_line(cli("damped", "--data", str(path), *extra))


def test_too_few_points_says_how_many_are_needed(tmp_path):
    """"3 points cannot fix 2 values" was wrong (they can) and named no constants."""
    path = tmp_path / "three.csv"
    path.write_text("t,y\n0,1\n0.1,2\n0.2,1\n")
    said = one_line(cli("damped", "--data", str(path)))
    assert "the data have 3 points, too few to fix the two offsets: at least 8 are needed" in said
    said = one_line(cli("damped", "--data", str(path), "--fit", "k,b"))
    assert "too few to fix k, b, r0 and the two offsets: at least 11 are needed" in said


def test_a_line_break_in_the_data_files_name_keeps_the_report_one_line(tmp_path):
    """The report's first line names the file; a name with a line break in it split that line in
    two (`data: we` / `ird.csv: read ...`), so a script reading `data:` lines lost the rest. It is
    written as \\n, as every error naming a path is."""
    path = tmp_path / "we\nird.csv"
    path.write_bytes((ROOT / "examples" / "data" / "vernier.csv").read_bytes())
    done = cli("damped", "--data", str(path), "--set", "m=0.5", "--set", "k=20", "--set", "b=0.1")
    assert done.returncode == 0, done.stderr
    first = done.stdout.splitlines()[0]
    assert first.startswith("data: ") and first.endswith("' against 'Latest: Time (s)'") and "we\\nird.csv" in first
    assert all(line.startswith("note: ") for line in done.stderr.splitlines())

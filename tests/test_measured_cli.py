"""--data, --fit, --mystery and --show-answer as a user runs them (subprocesses): every bad file is
one line naming the file and the line at fault, exit status 2, and no file written; the mystery
spring's answer round-trips, and fitting its file recovers it.
"""
from __future__ import annotations

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def cli(*args, timeout=120) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "main.py", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=timeout)


def _rows(count):
    return "".join(f"{n * 0.02:.2f},{math.cos(n * 0.04):.4f}\n" for n in range(count))


BAD_FILES = {
    "no numbers": (b"hello\nworld\n", 2, "no rows of numbers"),
    "one column": (b"Time (s)\n0\n0.1\n0.2\n", 2, "only one column"),
    "time not increasing": (b"t,y\n0,1\n0.1,2\n0.1,3\n0.3,4\n", 4, "does not increase"),
    "time going back": (b"t,y\n0,1\n0.1,2\n0.05,3\n0.3,4\n", 4, "does not increase"),
    "unknown time unit": (b"Time (min),Position (m)\n0,1\n1,2\n2,3\n", 1, "unknown unit 'min'"),
    "unknown length unit": (b"Time (s),Position (ft)\n0,1\n1,2\n2,3\n", 1, "unknown unit 'ft'"),
    "mixed separators": (b"t,y\n0,1\n0.1,2\n0.2;3\n0.3,4\n", 4, "mixed separators"),
    "NaN in the middle": (b"t,y\n0,1\n0.1,NaN\n0.2,3\n0.3,4\n", 3, "'NaN' in column 2"),
    "text in the middle": (b"t,y\n0,1\n0.1,2\n0.2,oops\n0.3,4\n", 4, "'oops' in column 2"),
    "no header, three columns": (b"0,1,5\n0.1,2,5\n0.2,3,5\n", 1, "no header line"),
    "binary": (bytes(range(256)) * 8, 1, "not a text file"),
    "too many rows": (("t,y\n" + _rows(200_001)).encode(), 200_002, "more than 200,000 rows"),
    "no time column": (b"a,y\n0,1\n1,2\n2,3\n", 1, "no time column"),
}


@pytest.mark.parametrize("case", BAD_FILES)
def test_a_bad_file_is_one_line_naming_the_file_and_line_and_writes_nothing(tmp_path, case):
    content, line, words = BAD_FILES[case]
    path = tmp_path / "measured.csv"
    path.write_bytes(content)
    before = sorted(p.name for p in tmp_path.iterdir())
    done = cli("damped", "--data", str(path), "--fit", "k,b", "--plot", str(tmp_path / "fit.png"))
    assert done.returncode == 2, done.stderr
    assert done.stdout == ""
    assert done.stderr.count("\n") == 1 and "Traceback" not in done.stderr
    assert done.stderr.startswith(f"error: {path} line {line}: "), done.stderr
    assert words in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == before
    assert path.read_bytes() == content


def test_a_million_rows_are_refused_quickly(tmp_path):
    path = tmp_path / "huge.csv"
    path.write_text("t,y\n" + _rows(1_000_000))
    done = cli("damped", "--data", str(path))
    assert done.returncode == 2 and "more than 200,000 rows" in done.stderr


def test_a_utf16_file_saved_by_excel_with_decimal_commas_is_read(tmp_path):
    path = tmp_path / "excel.txt"
    rows = "".join(f"{n * 0.04:.2f}\t{1.5 + 0.3 * math.cos(2 * n * 0.04):.4f}\r\n".replace(".", ",")
                   for n in range(100))
    path.write_bytes(("Latest: Time (s)\tLatest: Position (m)\r\n" + rows).encode("utf-16"))
    done = cli("damped", "--data", str(path), "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["data_points"] == 100 and math.isfinite(out["rms_residual"])


def test_the_mystery_spring_round_trips_and_its_fit_recovers_the_answer(tmp_path):
    path = tmp_path / "mystery.csv"
    made = cli("damped", "--mystery", str(path), "--seed", "11")
    assert made.returncode == 0, made.stderr
    assert made.stdout == ""                       # the answer is not printed
    assert "--show-answer --seed 11" in made.stderr
    assert path.read_text().startswith("Latest: Time (s),Latest: Position (m)\n")
    answer = cli("damped", "--show-answer", "--seed", "11")
    assert answer.returncode == 0, answer.stderr
    found = dict(re.findall(r"\b(k|b) = ([-\d.e]+)", answer.stdout))
    assert set(found) == {"k", "b"}
    assert found["k"] not in made.stderr.split("seed")[0]

    fitted = cli("damped", "--data", str(path), "--fit", "k,b", "--integrator", "rk4",
                 "--set", "dt=0.001", "--json")
    assert fitted.returncode == 0, fitted.stderr
    out = json.loads(fitted.stdout)
    for name in ("k", "b"):
        entry = out["fit"][name]
        assert abs(entry["value"] - float(found[name])) <= 3 * entry["uncertainty"], (name, entry, found)
    assert out["fit"]["k"]["unit"] == "N/m" and out["fit"]["b"]["unit"] == "kg/s"
    assert set(out["fit"]) == {"k", "b", "r0", "t_offset", "position_offset"}    # the release is fitted too
    assert out["trusted"] is True and out["trust_reason"] is None and out["release_fitted"] is True
    assert out["data_points"] == len(path.read_text().splitlines()) - 1
    assert 0.0005 < out["rms_residual"] < 0.004    # the file's noise: 1 to 3 mm

    again = tmp_path / "again.csv"
    assert cli("damped", "--mystery", str(again), "--seed", "11").returncode == 0
    assert again.read_bytes() == path.read_bytes()


def test_the_mystery_never_overwrites_a_file(tmp_path):
    path = tmp_path / "notes.csv"
    path.write_text("my own notes\n")
    done = cli("damped", "--mystery", str(path), "--seed", "3")
    assert done.returncode == 2 and "exists" in done.stderr and done.stderr.count("\n") == 1
    assert path.read_text() == "my own notes\n"


def test_the_teachers_set_values_are_the_mystery(tmp_path):
    answer = cli("damped", "--show-answer", "--seed", "4", "--set", "k=72", "--set", "b=3.5")
    assert "k = 72 N/m" in answer.stdout and "b = 3.5 kg/s" in answer.stdout


def test_text_report_has_one_line_each_with_units(tmp_path):
    path = tmp_path / "m.csv"
    assert cli("vertical", "--mystery", str(path), "--seed", "2").returncode == 0
    done = cli("vertical", "--data", str(path), "--fit", "k,b")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith(f"data: {path}: read 'Latest: Position (m)'")
    assert re.match(r"k = [\d.]+ ± [\d.]+ N/m$", lines[1]) and re.match(r"b = [\d.]+ ± [\d.]+ kg/s$", lines[2])
    assert re.match(r"r0 = -[\d.]+ ± [\d.]+ m  \(where the mass was let go, along y; --set r0 gives it", lines[3])
    assert lines[4].startswith("t_offset = ") and " s  (" in lines[4]
    assert lines[5].startswith("position_offset = ") and " m  (" in lines[5]
    assert re.match(r"RMS residual = [\d.e-]+ m \([\d.e-]+ mm\) over \d+ points$", lines[6])
    assert lines[7].startswith("data_sign = +1")
    assert re.search(r"note: the fit chose rk4 at dt = [\d.e-]+ s: its own error, about [\d.]+ .m, is under a "
                     r"tenth of the data's noise", done.stderr), done.stderr


def test_plot_draws_the_data_and_the_model(tmp_path):
    pytest.importorskip("matplotlib")
    path, figure = tmp_path / "m.csv", tmp_path / "fit.png"
    assert cli("damped", "--mystery", str(path), "--seed", "5").returncode == 0
    done = cli("damped", "--data", str(path), "--plot", str(figure), "--set", "dt=0.01")
    assert done.returncode == 0, done.stderr
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "RMS residual" in done.stdout


@pytest.mark.parametrize("args, words", [
    (["--fit", "k,b"], "--fit needs --data"),
    (["--show-answer"], "--show-answer needs --seed"),
    (["--seed", "3", "--headless"], "--seed needs --mystery or --show-answer"),
    (["--data", "x.csv", "--csv", "out.csv"], "--csv does nothing with --data"),
    (["--mystery", "x.csv", "--data", "y.csv"], "separate jobs"),
    (["--data", "no-such-file.csv"], "no-such-file.csv: cannot read it"),
    (["--data", "x.csv", "--run", "0"], "--run needs a whole number"),
])
def test_flags_that_do_not_fit_together_are_one_line(args, words):
    done = cli("damped", *args)
    assert done.returncode == 2 and words in done.stderr and done.stderr.count("\n") == 1, done.stderr


def test_fitting_k_with_m_is_refused_in_one_line(tmp_path):
    path = tmp_path / "m.csv"
    assert cli("damped", "--mystery", str(path), "--seed", "6").returncode == 0
    done = cli("damped", "--data", str(path), "--fit", "k,m")
    assert done.returncode == 2 and "k and m cannot be told apart" in done.stderr
    assert done.stderr.count("\n") == 1 and done.stdout == ""


def test_the_example_files_are_the_programs_own_and_each_reads(tmp_path):
    """examples/data/ is what examples/make_measured.py and --mystery write today, byte for byte."""
    made = subprocess.run([sys.executable, "examples/make_measured.py", str(tmp_path)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert made.returncode == 0, made.stderr
    assert cli("damped", "--mystery", str(tmp_path / "mystery.csv"), "--seed", "2026").returncode == 0
    committed = sorted(p.name for p in (ROOT / "examples" / "data").iterdir())
    assert committed == sorted(p.name for p in tmp_path.iterdir())
    for name in committed:
        assert (tmp_path / name).read_bytes() == (ROOT / "examples" / "data" / name).read_bytes(), name
    done = cli("damped", "--data", "examples/data/pasco.csv", "--fit", "k,b", "--set", "m=0.5", "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)                  # the spring the files record: k = 20 N/m, b = 0.1 kg/s
    for name, truth in (("k", 20.0), ("b", 0.1)):
        assert abs(out["fit"][name]["value"] - truth) <= 3 * out["fit"][name]["uncertainty"], out["fit"]


WITHOUT_SCIPY = ("import runpy, sys\n"
                 "sys.modules['scipy'] = None\nsys.modules['scipy.optimize'] = None\n"
                 "sys.argv = ['main.py', *sys.argv[1:]]\n"
                 "runpy.run_path('main.py', run_name='__main__')\n")


def test_without_scipy_the_comparison_runs_and_fit_says_what_to_install():
    """scipy is optional: the comparison is numpy only, and --fit names what to install in one line."""
    def run(*args):
        return subprocess.run([sys.executable, "-c", WITHOUT_SCIPY, *args], cwd=ROOT, capture_output=True,
                              text=True, timeout=120)
    compared = run("damped", "--data", "examples/data/vernier.csv", "--set", "m=0.5", "--set", "k=20", "--set",
                   "b=0.1", "--set", "r0=0,-1.325,0", "--set", "dt=0.005")
    assert compared.returncode == 0, compared.stderr
    assert "RMS residual = 0.00" in compared.stdout
    fitted = run("damped", "--data", "examples/data/vernier.csv", "--fit", "k,b", "--set", "dt=0.005")
    assert fitted.returncode == 2 and fitted.stdout == ""
    assert fitted.stderr == ("error: --fit needs scipy, which is not installed; install it with "
                             "python -m pip install scipy (everything else runs without it)\n")


def test_a_file_whose_swing_needs_a_spring_stiffer_than_the_range_is_one_line(tmp_path):
    """A Vernier file whose times are seconds but whose header says ms: its swing is 1000 times too
    fast, so it asks for k = 2e7 N/m on its 0.5 kg mass. One line names k, the value with its unit,
    k's range and what to check; exit status 2, no traceback, nothing written."""
    path = tmp_path / "ms.csv"
    path.write_text((ROOT / "examples" / "data" / "vernier.csv").read_text().replace("Time (s)", "Time (ms)", 1))
    done = cli("damped", "--data", str(path), "--fit", "k", "--set", "m=0.5", "--set", "dt=0.00001")
    assert done.returncode == 2 and done.stdout == "", done.stderr
    assert done.stderr.count("\n") == 1 and "Traceback" not in done.stderr
    found = re.match(r"error: --fit k: the data's swing \(ω = \S+ rad/s, dying away at \S+ per s\) asks for "
                     r"k = (\S+) N/m, outside its range \(from 0 to 1e6 N/m\); check the data's units", done.stderr)
    assert found, done.stderr
    assert float(found.group(1)) == pytest.approx(20.0 * 1e6, rel=0.02)      # 20 N/m, ω a thousand times
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ms.csv"]


def test_the_command_line_flags_a_fit_whose_model_misses_the_data(tmp_path):
    """The release given (--set r0) where the data swing 1 m and the model 1.95 m: the fit of k
    misses. Its first line says the numbers cannot be trusted and why, the figures follow, and the
    exit status is 3; JSON says "trusted": false with the reason."""
    import numpy as np
    t = np.arange(0.0, 5.0, 0.02)
    data = tmp_path / "swing.csv"
    data.write_text("t (s),y (m)\n" + "".join(f"{a:.3f},{0.7 + np.cos(2 * a):.6f}\n" for a in t))
    done = cli("vertical", "--data", str(data), "--fit", "k", "--set", "r0=0,-1.5,0", timeout=300)
    assert done.returncode == 3, done.stderr
    lines = done.stdout.splitlines()
    assert re.match(r"these numbers cannot be trusted: the model misses by \d+% of the data's half swing", lines[0])
    assert lines[1].startswith(f"data: {data}") and re.match(r"k = \S+ ± \S+ N/m$", lines[2])
    assert "r0" not in done.stdout.split("RMS")[0]          # the release was given, not fitted
    as_json = cli("vertical", "--data", str(data), "--fit", "k", "--set", "r0=0,-1.5,0", "--json", timeout=300)
    assert as_json.returncode == 3
    out = json.loads(as_json.stdout)
    assert out["trusted"] is False and out["trust_reason"] == lines[0]

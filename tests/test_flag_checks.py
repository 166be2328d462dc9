"""Issue 28, items 3, 4 and 5 (its messages outside lab/): every flag does what it says or says why
not, bad input is exit status 2 with one line naming it, and every message is one line.

Run as a user runs main.py (a subprocess), except the table of hostile values, which calls
main.run in this process: the same code, hundreds of times, without starting Python each time.
"""
from __future__ import annotations

import contextlib
import io
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

VERNIER = str(ROOT / "examples" / "data" / "vernier.csv")


def main_py(*args, cwd=ROOT):
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=300)


def one_error(done) -> str:
    lines = done.stderr.splitlines()
    assert done.returncode == 2 and len(lines) == 1 and lines[0].startswith("error: "), (done.returncode, done.stderr)
    return lines[0]


# ---- item 3: flags that were garbled or did nothing ----

PAGE_STUB = """
import sys
import browser.view
import main

def show(setup, model, **options):
    print("arrows:", repr(options["arrows"]))
    return 0

browser.view.show = show
sys.exit(main.run(sys.argv[1:]))
"""


def test_arrows_reach_the_data_page_as_names_not_characters():
    """`--arrows p,F_net --data FILE --page` reached the page as the string 'p,F_net', read there as
    the characters p, ',', F, ...: p showed and F_net was dropped, on the page and in its Download
    program. The page itself is stood in for; what it is handed is the tuple of names."""
    done = subprocess.run([sys.executable, "-c", PAGE_STUB, "damped", "--data", VERNIER, "--page", "--arrows",
                           "p,F_net", "--no-browser"], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["arrows: ('p', 'F_net')"]


@pytest.mark.parametrize("argv", [
    ["damped", "--data", VERNIER, "--arrows", "bogus"],
    ["damped", "--data", VERNIER, "--arrows", "p"],        # no page: nothing draws them
    ["damped", "--data", VERNIER, "--no-arrows"],
    ["damped", "--data", VERNIER, "--page", "--arrows", "bogus"],
    ["damped", "--mystery", "never.csv", "--arrows", "bogus"],
    ["damped", "--show-answer", "--seed", "3", "--arrows", "bogus"],
    ["damped", "--constants", "--arrows", "p"],           # bogus names were refused, good ones ignored
    ["--list", "--arrows", "bogus"],
    ["damped", "--data", VERNIER, "--fit", ""],
    ["damped", "--data", VERNIER, "--fit", " "],
    ["damped", "--data", VERNIER, "--overwrite"],
    ["damped", "--show-answer", "--seed", "3", "--overwrite"],
    ["damped", "--constants", "--overwrite"],
])
def test_a_flag_that_would_do_nothing_is_one_line_and_status_2(argv, tmp_path):
    line = one_error(main_py(*argv, cwd=tmp_path))
    flag = next(a for a in argv if a in ("--arrows", "--no-arrows", "--fit", "--overwrite"))
    assert flag in line, line
    assert os.listdir(tmp_path) == []


def test_overwrite_lets_the_mystery_replace_a_file_and_is_needed_for_it(tmp_path):
    """--overwrite was ignored with --mystery: an existing file was refused whatever it said."""
    path = tmp_path / "spring.csv"
    path.write_text("last year's mystery\n")
    assert "add --overwrite to replace it" in one_error(main_py("damped", "--mystery", path, "--seed", "5"))
    assert path.read_text() == "last year's mystery\n"
    done = main_py("damped", "--mystery", path, "--seed", "5", "--overwrite")
    assert done.returncode == 0, done.stderr
    assert path.read_text().startswith("Latest: Time (s)")


def test_overwrite_lets_data_plot_replace_a_file(tmp_path):
    figure = tmp_path / "fit.png"
    figure.write_bytes(b"someone else's picture")
    assert "did not write" in one_error(main_py("damped", "--data", VERNIER, "--plot", figure))
    assert main_py("damped", "--data", VERNIER, "--plot", figure, "--overwrite").returncode == 0
    assert figure.read_bytes()[:4] == b"\x89PNG"


# ---- item 4: bad input is status 2 with one line, never "a bug in main.py" ----

@pytest.mark.parametrize("argv, said", [
    (["damped", "--mystery", "m.csv", "--seed", "-1"], "--seed needs a whole number of 0 or more (got -1)"),
    (["damped", "--show-answer", "--seed", "-1"], "--seed needs a whole number of 0 or more (got -1)"),
    (["damped", "--data", VERNIER, "--data-column", "²"], "--data-column '²' matches 0 position columns"),
    (["damped", "--data", VERNIER, "--data-column", ""], "--data-column needs a column"),       # issue 37: once
    (["damped", "--data", VERNIER, "--data-column", "  "], "--data-column needs a column"),     # ignored in silence
    (["damped", "--data", VERNIER, "--data-column", "", "--page"], "--data-column needs a column"),
])
def test_the_issues_bad_input_is_status_2(argv, said, tmp_path):
    assert said in one_error(main_py(*argv, cwd=tmp_path))
    assert os.listdir(tmp_path) == []


HOSTILE = ["", " ", "-1", "0", "-0", "1e308", "1e400", "9" * 400, "1e-320", "nan", "inf", "-inf", "²", "١", "１",
           "0x10", "1,5", "a\nb", "\u2028", "é"]
FLAGS = [("--until", ["vertical", "--headless"]), ("--steps", ["vertical"]), ("--scenario", ["driven", "--headless"]),
         ("--preset", ["vertical", "--headless"]), ("--seed", ["damped", "--show-answer"]),
         ("--data-column", ["damped", "--data", VERNIER]), ("--run", ["damped", "--data", VERNIER]),
         ("--fit", ["damped", "--data", VERNIER, "--set", "dt=0.01"]), ("--arrows", ["vertical", "--vpython", "-"]),
         ("--port", ["vertical", "--vpython", "x.py"]), ("--coordinate", ["damped", "--data", VERNIER]),
         ("--data-sign", ["damped", "--data", VERNIER]), ("--integrator", ["vertical", "--headless"]),
         ("--data", ["damped"]), ("--csv", ["vertical", "--headless"]), ("--vpython", ["vertical"])]
CONSTANTS = [("vertical", name) for name in ("m", "k", "L0", "g", "b", "dt", "until", "r0", "v0")] + \
            [("driven", name) for name in ("omega", "F0", "drive_axis")] + \
            [("resonance", name) for name in ("count", "omega_min", "settle")]


def hostile_cases():
    for value in HOSTILE:
        for flag, before in FLAGS:
            yield before + [flag, value]
        for scene, name in CONSTANTS:
            yield [scene, "--headless", "--set", f"{name}={value}"]
        yield ["vertical", "--headless", "--set", value]


def test_hostile_values_for_every_flag_are_answered_in_one_line(tmp_path, monkeypatch):
    """Huge, tiny, negative, non-finite, unicode digits, empty, a line break: for every flag that
    takes a value and for a constant of each kind. The answer is a run (0), or one line naming the
    problem (2), or a run that blows up saying why (1): never "a bug in main.py", never a traceback,
    never a second line."""
    import main

    monkeypatch.chdir(tmp_path)
    problems = []
    for argv in hostile_cases():
        for leftover in os.listdir(tmp_path):
            path = tmp_path / leftover
            shutil.rmtree(path) if path.is_dir() else path.unlink()
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                status = main.run(argv)
            except SystemExit as stop:     # argparse's own errors
                status = stop.code
        lines = [line for line in err.getvalue().splitlines() if not line.startswith(("running:", "warning:",
                                                                                       "note:", "wrote "))]
        blown_up = status == 1 and len(lines) == 1 and ("blow up" in lines[0] or "blew up" in lines[0])
        if not (status == 0 and lines == [] or status == 2 and len(lines) == 1 or blown_up) \
                or "a bug in main.py" in err.getvalue() or "Traceback" in err.getvalue():
            problems.append((argv, status, err.getvalue()))
    assert problems == []


# ---- item 5: every message is one line ----

@pytest.mark.parametrize("argv", [
    ["vertical", "--headless", "--csv", "no\nsuch/run.csv"],
    ["vertical", "--vpython", "no\nsuch/handout.py"],
    ["vertical", "--plot", "no\rsuch/run.png"],
    ["damped", "--data", "no\nsuch.csv"],
    ["damped", "--data", VERNIER, "--fit", "k\nb"],
    ["damped", "--mystery", "no\u2028such/m.csv"],
    ["vertical", "--headless", "--set", "k=4\n0"],
    ["vertical", "--headless", "--bogus\nflag"],
    ["no\nscene", "--headless"],
])
def test_a_line_break_in_a_value_keeps_the_message_on_one_line(argv, tmp_path):
    """'a newline in a path splits the error across two lines': the value is written with \\n, as
    Python writes it in a string, so the line still names it exactly."""
    line = one_error(main_py(*argv, cwd=tmp_path))
    assert "\\n" in line or "\\r" in line or "\\u2028" in line, line


def test_a_line_break_in_the_name_of_a_written_file_is_one_line_too(tmp_path):
    folder = tmp_path / "a\nb"
    folder.mkdir()
    done = main_py("vertical", "--vpython", folder / "handout.py", cwd=tmp_path)
    assert done.returncode == 0 and done.stderr.splitlines() == [f"wrote {tmp_path}/a\\nb/handout.py"], done.stderr


@pytest.mark.parametrize("argv, said", [
    (["vertical", "--headless", "--until", "1e-320"], "(got 1e-320 s)"),
    (["vertical", "--headless", "--set", "A=-4e-323"], "(got -4e-323 m²)"),
])
def test_a_number_too_small_for_a_normal_double_is_echoed_as_typed(argv, said):
    """'got 9.99989e-321 s' for --until 1e-320: six digits of a subnormal double show its error."""
    assert one_error(main_py(*argv)).endswith(said)

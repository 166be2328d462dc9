"""Issue 37, item 1: each file the hostile-user pass lost, tried again, and checked byte for byte.

A file is this program's own only where its mark stands where we put it (a program's or page's
first line, after "Web VPython 3.2" or "<!DOCTYPE html>"; a figure's metadata field) and its
fingerprint matches (export/marks.py). Every case below was replaced with exit status 0 before;
each must now be refused in one line, exit status 2, and left exactly as it was.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from export import files  # noqa: E402


@pytest.fixture(autouse=True)
def own_record(tmp_path, monkeypatch):
    """Each test keeps its own record of the files written (export/written.py), in its folder."""
    monkeypatch.setenv("SPRING_MASS_CACHE", str(tmp_path / "record"))


def main_py(*args, cwd=ROOT):
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *map(str, args)], capture_output=True,
                          cwd=cwd, env=dict(os.environ), timeout=300)


def refused(done, *, says: str) -> None:
    lines = done.stderr.decode().splitlines()
    assert done.returncode == 2 and len(lines) == 1 and lines[0].startswith("error: cannot write"), done.stderr
    assert says in lines[0], lines[0]


# ---- 1. a printed program, saved and edited ----

@pytest.mark.parametrize("flag", ["--vpython", "--webvpython"])
def test_a_printed_program_saved_and_edited_is_not_replaced(flag, tmp_path):
    """`--vpython - > mine.py` (the guides show it), then edited: the printed program carries its
    mark and fingerprint as a written one does, so the edit shows."""
    printed = main_py("vertical", flag, "-")
    assert printed.returncode == 0
    mine = tmp_path / "mine.py"
    mine.write_bytes(printed.stdout)
    assert main_py("vertical", flag, mine).returncode == 0       # unedited: its own, replaced
    assert mine.read_bytes() == printed.stdout                   # the very same program
    edited = mine.read_bytes().replace(b"\nk = 40 ", b"\nk = 45 ")
    assert edited != mine.read_bytes()
    mine.write_bytes(edited)
    refused(main_py("vertical", flag, mine), says="has been changed since")
    assert mine.read_bytes() == edited


def test_a_printed_page_carries_its_fingerprint_too(tmp_path):
    """`--html -`: the page, printed, is the page written to a file, byte for byte."""
    printed = main_py("vertical", "--html", "-")
    written = tmp_path / "page.html"
    assert printed.returncode == 0 and main_py("vertical", "--html", written).returncode == 0
    assert printed.stdout == written.read_bytes()
    assert printed.stdout.split(b"\n")[1].startswith(b"<!-- " + files.MARK.encode() + b"; its fingerprint is sha256:")


# ---- 2. a page or program whose fingerprint was deleted or blanked ----

def _fingerprint_deleted(data: bytes) -> bytes:
    start = data.index(b"sha256:")
    return data[:start] + data[start + len("sha256:") + 16:]


def _digits_dashed(data: bytes) -> bytes:
    start = data.index(b"sha256:") + len("sha256:")
    return data[:start] + b"-" * 16 + data[start + 16:]


def _mark_line_deleted(data: bytes) -> bytes:
    lines = data.split(b"\n")
    at = next(i for i, line in enumerate(lines) if files.MARK.encode() in line)
    return b"\n".join(lines[:at] + lines[at + 1:])


@pytest.mark.parametrize("flag, name", [("--vpython", "spring.py"), ("--html", "spring.html")])
@pytest.mark.parametrize("change", [_fingerprint_deleted, _digits_dashed, _mark_line_deleted])
def test_a_handout_whose_fingerprint_was_deleted_or_blanked_is_not_replaced(flag, name, change, tmp_path):
    """The issue's four cases (a page or program, its sha256 deleted or its digits dashes), and the
    whole mark line deleted: marked with no fingerprint is edited; unmarked is not ours."""
    path = tmp_path / name
    assert main_py("vertical", flag, path).returncode == 0
    data = change(path.read_bytes())
    path.write_bytes(data)
    says = "did not write" if change is _mark_line_deleted else "no fingerprint"
    refused(main_py("vertical", flag, path), says=says)
    assert path.read_bytes() == data


# ---- 3. a user's file that merely holds the mark's sentence ----

MARK_LINE = ("# " + files.MARK + " with the euler-cromer integrator.\n").encode()


@pytest.mark.parametrize("flag, name, data", [
    ("--html", "notes.html", b"<!DOCTYPE html>\n<html><body><p>My notes on the simulator:</p>\n<pre>\n" + MARK_LINE
     + b"</pre>\n</body></html>\n"),
    ("--vpython", "homework.py", b"# my homework\n" + b"x = 1  # working\n" * 7000 + MARK_LINE + b"print(x)\n"),
    ("--vpython", "copied.py", b"# my homework, the handout's header pasted in:\n" + MARK_LINE + b"k = 2\n"),
    ("--plot", "fake.png", b"This is not a PNG. " + MARK_LINE + b" Software " + files.MARK.encode() + b"\n"),
    ("--plot", "notes.svg", b"<?xml version='1.0'?>\n<svg><text>" + files.MARK.encode() + b"</text></svg>\n"),
    ("--plot", "notes.pdf", b"%PDF-1.4\n% my notes: /Creator (" + files.MARK.encode() + b")\n"),
])
def test_a_file_that_merely_holds_the_marks_sentence_is_not_ours(flag, name, data, tmp_path):
    """A notes page, a 120 KB homework file with the sentence in its last 64 KB, a program with the
    header pasted in below its first line, a "PNG" holding the text: the mark counts only where
    we put it."""
    path = tmp_path / name
    path.write_bytes(data)
    assert files.ownership(str(path)) == files.THEIRS
    refused(main_py("vertical", flag, path), says="did not write")
    assert path.read_bytes() == data


# ---- 4. tool files: nowhere in the program's folder ----

@pytest.mark.parametrize("argv", [
    ["vertical", "--headless", "--csv", "pytest.ini"], ["vertical", "--headless", "--csv", "conftest.py"],
    ["vertical", "--vpython", "conftest.py"], ["vertical", "--vpython", "__init__.py"],
    ["vertical", "--webvpython", "sitecustomize.py"], ["vertical", "--headless", "--csv", "setup.cfg"],
])
def test_no_tool_file_is_written_beside_main_py_or_in_out(argv):
    """The issue's four (written beside main.py, after which the project's own tests failed), and
    the same names in out/, the user's folder of outputs: refused, nothing made."""
    for path in (argv[-1], f"out/{argv[-1]}"):
        target = ROOT / path
        assert not target.exists()
        done = main_py(*argv[:-1], path)
        refused(done, says="beside main.py" if "/" not in path else "Python's tools run")
        assert not target.exists()
    dot_pth = ROOT / "out" / "spring.pth"
    refused(main_py("vertical", "--headless", "--csv", "out/spring.pth"), says="Python's tools run")
    assert not dot_pth.exists()


# ---- 5. kept, as documented: a CSV file of ours that a student edited ----

def test_an_edited_csv_of_ours_is_replaced_as_docs_homework_says(tmp_path):
    """A CSV file has no room for a fingerprint (export/marks.py ownership says why): it is known by
    its header line, and replaced even after its rows were changed. docs/homework.md says so."""
    path = tmp_path / "run.csv"
    assert main_py("vertical", "--headless", "--csv", path).returncode == 0
    first = path.read_bytes()
    path.write_bytes(first.replace(b"\r\n0.1,", b"\r\n0.1000,", 1))
    assert main_py("vertical", "--headless", "--csv", path).returncode == 0
    assert path.read_bytes() == first
    assert "edited" in (ROOT / "docs" / "homework.md").read_text(encoding="utf-8")

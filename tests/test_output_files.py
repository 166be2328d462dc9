"""Issues 28 and 37: where an output file may go, run as a user runs main.py.

1. No file of the program's own tree is ever written, with or without --overwrite. The tree is
   found from the folder main.py is in (export/files.py own_tree), not from a list, so a copy of
   it without .git is protected the same way; nothing new goes beside main.py (issue 37: no
   pytest.ini or conftest.py there); ./out/, which the tree's .gitignore gives to the user, takes
   the user's outputs but no tool's file; a teacher's scene folder takes no Python file.
2. A file the program did not write is replaced only with --overwrite; its own outputs are known
   by their mark where we put it and a fingerprint that still matches (export/marks.py), a CSV
   file by its header. The --data file is never written, by name, through a symbolic link or a
   hard link. tests/test_lost_files.py tries each file issue 37 found lost.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from export import files, marks  # noqa: E402
from export.numbers import CSV_HEADER  # noqa: E402

VERNIER = ROOT / "examples" / "data" / "vernier.csv"


@pytest.fixture(autouse=True)
def own_record(tmp_path, monkeypatch):
    """Each test keeps its own record of the files written (export/written.py), in its folder."""
    monkeypatch.setenv("SPRING_MASS_CACHE", str(tmp_path / "record"))


def main_py(*args, cwd=ROOT, env=None, main=ROOT / "main.py"):
    return subprocess.run([sys.executable, str(main), *map(str, args)], capture_output=True, text=True, cwd=cwd,
                          env={**os.environ, **(env or {})}, timeout=300)


def one_error(done) -> str:
    """The one line of a refused command (exit status 2)."""
    lines = done.stderr.splitlines()
    assert done.returncode == 2 and len(lines) == 1 and lines[0].startswith("error: "), done.stderr
    return lines[0]


def tracked_files() -> list[str]:
    """The tree's files as git knows them (the checkout CI runs in has .git)."""
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, timeout=60)
    if listed.returncode != 0:
        pytest.skip("no git checkout here")
    return [name for name in listed.stdout.decode().split("\0") if name and (ROOT / name).is_file()]


# ---- 1. the program's own tree ----

@pytest.mark.parametrize("argv", [
    ["damped", "--vpython", "lab/mystery.py", "--overwrite"],                 # the first case
    ["vertical", "--headless", "--csv", "cli/options.py", "--overwrite"],     # and its second
    ["vertical", "--headless", "--csv", "examples/data/vernier.csv", "--overwrite"],
    ["vertical", "--plot", "docs/architecture.md", "--overwrite"],
    ["vertical", "--webvpython", ".gitignore", "--overwrite"],
    ["vertical", "--headless", "--csv", "pyproject.toml", "--overwrite"],
])
def test_no_file_of_the_tree_is_written_even_with_overwrite(argv):
    path = ROOT / argv[-2]
    before = path.read_bytes()
    try:
        line = one_error(main_py(*argv))
    finally:   # today's code writes some of them: put them back before anything else runs
        if path.read_bytes() != before:
            path.write_bytes(before)
            pytest.fail(f"{argv[-2]} was written")
    assert f"{argv[-2]!r}: it is " in line and ("own folder" in line or "own files" in line), line


def test_every_file_the_tree_holds_is_refused_and_no_new_file_is_made_in_its_folders():
    """Derived from the tree, not a list: every tracked file (and so every folder that holds one)
    is refused, with --overwrite, and a new file in each of its folders too."""
    names = tracked_files()
    for name in names:
        with pytest.raises(files.OutputError, match="own f"):
            files.check_writable(str(ROOT / name), what="CSV file", overwrite=True)
    for folder in sorted({str(Path(name).parent) for name in names} - {"."}):
        with pytest.raises(files.OutputError, match="inside the program's own folder"):
            files.check_writable(str(ROOT / folder / "new-output.csv"), what="CSV file")
    # beside main.py nothing is written, new or old: no file the tree keeps there may look like an output
    assert [name for name in names if "/" not in name and files.written_here(str(ROOT / name))] == []
    for name in ("new-output.csv", "pytest.ini", "conftest.py", "__init__.py", "damped.py"):
        with pytest.raises(files.OutputError, match="beside main.py"):
            files.check_writable(str(ROOT / name), what="CSV file")


def copy_of_the_tree(tmp_path: Path) -> Path:
    """The tree as a user who copied or unzipped it has it: no .git."""
    copy = tmp_path / "simulator"
    shutil.copytree(ROOT, copy, ignore=shutil.ignore_patterns(".git", "__pycache__", ".venv", ".pytest_cache",
                                                              ".hypothesis", "out"))
    return copy


def test_a_copy_without_git_is_protected_the_same_and_its_out_folder_is_the_users(tmp_path):
    copy = copy_of_the_tree(tmp_path)
    assert not (copy / ".git").exists()
    options = copy / "cli" / "options.py"
    before = options.read_bytes()
    line = one_error(main_py("vertical", "--headless", "--csv", "cli/options.py", "--overwrite", cwd=copy,
                             main=copy / "main.py"))
    assert line == ("error: cannot write CSV file 'cli/options.py': it is inside the program's own folder cli/, "
                    "which it never writes into; write it in out/ (kept for your files: out/options.py) or outside "
                    "the program's folder")
    assert options.read_bytes() == before
    # ./out/, gitignored, is a student's outputs: a fresh checkout has none, and the first output
    # into it makes it (the guides write `--vpython out/damped.py`); any other missing folder is
    # a mistyped path, refused
    assert not (copy / "out").exists()
    assert "folder" in one_error(main_py("vertical", "--headless", "--csv", "outs/run.csv", cwd=copy,
                                         main=copy / "main.py"))
    assert not (copy / "outs").exists()
    for argv in (["vertical", "--headless", "--csv", "out/run.csv"], ["vertical", "--plot", "out/run.png"],
                 ["damped", "--vpython", "out/handout.py"]):
        done = main_py(*argv, cwd=copy, main=copy / "main.py")
        assert done.returncode == 0, (argv, done.stderr)
        done = main_py(*argv, cwd=copy, main=copy / "main.py")   # again: its own output, replaced
        assert done.returncode == 0, (argv, done.stderr)
    assert sorted(os.listdir(copy / "out")) == ["handout.py", "run.csv", "run.png"]


def test_a_copy_without_git_takes_nothing_beside_main_py(tmp_path):
    """Beside main.py nothing at all: a module (json.py would be imported instead of json), a tool's
    file (pytest.ini broke the project's own tests), or any output, which belongs in out/."""
    copy = copy_of_the_tree(tmp_path)
    listing = sorted(os.listdir(copy))
    for argv in (["damped", "--vpython", "json.py"], ["vertical", "--headless", "--csv", "__main__.py"],
                 ["damped", "--headless", "--csv", "run.csv"], ["vertical", "--headless", "--csv", "pytest.ini"]):
        line = one_error(main_py(*argv, cwd=copy, main=copy / "main.py"))
        assert line == (f"error: cannot write {'the program' if '--vpython' in argv else 'CSV file'} {argv[-1]!r}: it "
                        f"would go beside main.py, in the program's own folder, which holds only the program's "
                        f"files; write it in out/ (kept for your files: out/{argv[-1]}) or outside the program's "
                        f"folder"), line
    assert sorted(os.listdir(copy)) == listing
    # and a file there that is not ours is not replaced, even with --overwrite
    (copy / "notes.txt").write_text("mine\n")
    assert "beside main.py" in one_error(main_py("vertical", "--headless", "--csv", "notes.txt", "--overwrite",
                                                 cwd=copy, main=copy / "main.py"))
    assert (copy / "notes.txt").read_text() == "mine\n"


def test_a_teachers_scene_folder_takes_no_python_file(tmp_path):
    """Every .py file in SPRING_SCENES is read as a scene: a handout written there would be one more
    broken scene in every --list; the teacher's other files are theirs, under the usual rules."""
    folder = tmp_path / "scenes"
    folder.mkdir()
    scene = folder / "mine.py"
    scene.write_text((ROOT / "scenes" / "vertical.py").read_text(encoding="utf-8").replace("from ._", "from scenes._"),
                     encoding="utf-8")
    env = {"SPRING_SCENES": str(folder)}
    line = one_error(main_py("vertical", "--vpython", folder / "handout.py", env=env))
    assert f"it is in the teacher's scene folder {str(folder)!r} (SPRING_SCENES)" in line
    before = scene.read_bytes()
    one_error(main_py("vertical", "--vpython", scene, "--overwrite", env=env))
    assert scene.read_bytes() == before
    assert main_py("vertical", "--headless", "--csv", folder / "run.csv", env=env).returncode == 0
    assert sorted(os.listdir(folder)) == ["mine.py", "run.csv"]
    assert main_py("vertical", "--vpython", tmp_path / "handout.py", env=env).returncode == 0   # elsewhere: fine


# ---- 2. a file the program did not write ----

def test_a_measurement_is_not_replaced_by_a_csv_without_overwrite(tmp_path):
    """`vertical --headless --csv mydata.csv` replaced a measurement silently."""
    data = tmp_path / "mydata.csv"
    shutil.copy(VERNIER, data)
    line = one_error(main_py("vertical", "--headless", "--csv", data))
    assert line == (f"error: cannot write CSV file {str(data)!r}: it is a file this program did not write; "
                    f"give another name, or add --overwrite to replace it")
    assert data.read_bytes() == VERNIER.read_bytes()
    assert main_py("vertical", "--headless", "--csv", data, "--overwrite").returncode == 0
    assert data.read_text().startswith(",".join(CSV_HEADER) + "\n")


@pytest.mark.parametrize("name", ["run.csv", "run.png", "run.svg", "run.svgz", "run.pdf", "run.eps", "handout.py"])
def test_its_own_outputs_are_known_by_their_mark_and_replaced(name, tmp_path):
    """A second run onto its own output needs no --overwrite: the CSV by its header line, the
    program by its header, each figure type by the metadata savefig writes."""
    path = tmp_path / name
    argv = (["damped", "--vpython", path] if name.endswith(".py") else
            ["damped", "--headless", "--csv", path] if name.endswith(".csv") else ["damped", "--plot", path])
    for _ in range(2):
        done = main_py(*argv)
        assert done.returncode == 0, done.stderr
    assert files.written_here(str(path))
    if name.endswith(".csv"):   # the contract: line 1 is the header, nothing before it
        assert path.read_bytes().startswith(files.CSV_HEADER_LINES[0])


def test_a_figure_that_is_not_ours_is_replaced_only_with_overwrite(tmp_path):
    """A PNG with no mark (drawn by another program) is kept; a type that carries no mark says so."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    theirs = tmp_path / "theirs.png"
    figure = plt.figure()
    figure.savefig(theirs)      # matplotlib's own metadata only
    plt.close(figure)
    before = theirs.read_bytes()
    assert "a file this program did not write" in one_error(main_py("vertical", "--plot", theirs))
    assert theirs.read_bytes() == before
    jpg = tmp_path / "run.jpg"      # no place for a mark: known only by the record of what it wrote
    assert main_py("vertical", "--plot", jpg, env={"SPRING_MASS_CACHE": ""}).returncode == 0
    assert one_error(main_py("vertical", "--plot", jpg, env={"SPRING_MASS_CACHE": ""})).endswith(
        "it is a .jpg file, a type that cannot carry this program's mark, so it cannot tell whether it wrote it; "
        "give another name, or add --overwrite to replace it")
    assert main_py("vertical", "--plot", jpg, "--overwrite").returncode == 0
    assert main_py("vertical", "--plot", jpg).returncode == 0     # recorded as written: its own, unchanged


@pytest.mark.parametrize("how", ["same name", "symbolic link", "hard link"])
@pytest.mark.parametrize("overwrite", [False, True])
def test_the_data_file_is_never_written(how, overwrite, tmp_path):
    """`--data run.svg --plot run.svg` drew the figure over the data, and so did a --plot path
    that is a link to it."""
    data = tmp_path / "run.svg"        # a measurement that happens to be called .svg
    shutil.copy(VERNIER, data)
    plot = data if how == "same name" else tmp_path / "link.svg"
    if how == "symbolic link":
        plot.symlink_to(data.name)
    elif how == "hard link":
        os.link(data, plot)
    line = one_error(main_py("damped", "--data", data, "--plot", plot, *(["--overwrite"] if overwrite else [])))
    assert line.startswith(f"error: --plot {str(plot)!r} is the --data file") and \
        line.endswith("and the data is never written over; give the figure another name")
    assert data.read_bytes() == VERNIER.read_bytes()
    if how == "symbolic link":
        assert plot.is_symlink()


def test_a_data_plot_onto_another_file_follows_the_rules(tmp_path):
    """--data with --plot writes a new figure, refuses a file not ours, and --overwrite lets it."""
    other = tmp_path / "notes.png"
    other.write_bytes(b"not a figure of ours")
    assert "did not write" in one_error(main_py("damped", "--data", VERNIER, "--plot", other))
    assert main_py("damped", "--data", VERNIER, "--plot", other, "--overwrite").returncode == 0
    assert files.written_here(str(other))


# ---- 2b. its own output, edited since: the fingerprint ----

def edit_one_line(path: Path) -> bytes:
    """Change one line of a text file as a student would (a constant's value); returns the new bytes."""
    text = path.read_bytes()
    lines = text.split(b"\n")
    number = next(i for i, line in enumerate(lines) if line.startswith((b"k = ", b"<title>")))
    lines[number] = lines[number].replace(b"k = ", b"k = 1") if lines[number].startswith(b"k = ") else \
        lines[number].replace(b"<title>", b"<title>My ")
    path.write_bytes(b"\n".join(lines))
    assert path.read_bytes() != text
    return path.read_bytes()


@pytest.mark.parametrize("flag, name", [("--vpython", "spring.py"), ("--webvpython", "spring.py"),
                                        ("--html", "spring.html")])
def test_a_handout_a_student_edited_is_replaced_only_with_overwrite(flag, name, tmp_path):
    """A handout of ours that a student has since edited is not ours any more: its fingerprint (the
    SHA-256 beside the mark) no longer matches, and rerunning the command refuses it, byte for byte."""
    path = tmp_path / name
    for _ in range(2):    # its own output, unedited: replaced with no --overwrite
        done = main_py("vertical", flag, path)
        assert done.returncode == 0, done.stderr
        assert files.ownership(str(path)) == files.OURS
    edited = edit_one_line(path)
    assert files.ownership(str(path)) == files.EDITED
    line = one_error(main_py("vertical", flag, path))
    assert line.endswith(f"{str(path)!r}: this program wrote it, but it has been changed since (its sha256 fingerprint "
                         f"no longer matches); give another name, or add --overwrite to replace it"), line
    assert path.read_bytes() == edited
    assert main_py("vertical", flag, path, "--overwrite").returncode == 0
    fresh = path.read_bytes()      # the student's edit (edit_one_line) is gone: a constant's line, or the title
    assert files.ownership(str(path)) == files.OURS and fresh != edited
    assert b"<title>My " not in fresh and not re.search(rb"^k = 1", fresh, re.M)


@pytest.mark.parametrize("kind", files.FINGERPRINTED_FIGURES)
def test_a_figure_changed_since_is_replaced_only_with_overwrite(kind, tmp_path):
    """A figure keeps its fingerprint in its metadata (PNG "Software", the others' "Creator"); one
    byte changed in the middle (the image itself) makes it not ours. The PNG stays a valid PNG:
    the CRC of the chunk holding the fingerprint is written again."""
    path = tmp_path / f"run.{kind}"
    for _ in range(2):
        assert main_py("vertical", "--plot", path).returncode == 0
    if kind == "png":
        from PIL import Image

        with Image.open(path) as image:
            image.verify()    # checks every chunk's CRC
    data = bytearray(path.read_bytes())
    assert re_digits(data)
    data[len(data) // 2] ^= 0x01
    path.write_bytes(bytes(data))
    assert "has been changed since" in one_error(main_py("vertical", "--plot", path))
    assert path.read_bytes() == bytes(data)
    assert main_py("vertical", "--plot", path, "--overwrite").returncode == 0
    assert files.ownership(str(path)) == files.OURS


def re_digits(data) -> bool:
    """Whether a file's bytes hold a filled-in fingerprint after the mark."""
    import re

    return re.search(re.escape(files.MARK.encode()) + rb".{0,600}?sha256:[0-9a-f]{16}", bytes(data), re.S) is not None


def earlier_handout(path: Path, *, digits: str | None) -> bytes:
    """A handout as the version before this one wrote it: its mark on the fifth line, its
    fingerprint's line under it (`digits`: None fills in the true fingerprint, the SHA-256 of the
    bytes without those 16 digits, worked out here on its own)."""
    import hashlib

    lines = ["from vpython import *", "import socket", "socket.socket.bind = bind",
             "# vertical: The page's Simple Example.",
             "# Written by the spring-mass simulator with the euler-cromer integrator. Edit the constants and run it again.",
             "# sha256:" + "-" * 16 + ": this file's fingerprint; once the file is edited, the simulator replaces it "
             "only with --overwrite", "", "k = 40                   # N/m: spring constant", ""]
    data = "\n".join(lines).encode()
    at = data.index(b"sha256:") + 7
    if digits is None:
        digits = hashlib.sha256(data[:at] + data[at + 16:]).hexdigest()[:16]
    data = data[:at] + digits.encode() + data[at + 16:]
    path.write_bytes(data)
    return data


def test_files_of_the_version_before_are_its_own_where_their_fingerprint_still_matches(tmp_path):
    """The version before this one put its mark and fingerprint a few lines down: such a file is
    replaced where its fingerprint matches, and refused, byte for byte, once edited or where it has
    none (its digits blank, or a file from before fingerprints): docs/homework.md says so."""
    old = tmp_path / "spring.py"
    earlier_handout(old, digits=None)
    assert files.ownership(str(old)) == files.OURS
    assert main_py("vertical", "--vpython", old).returncode == 0
    assert old.read_bytes().startswith(b"# " + files.MARK.encode())        # now in this version's form
    for digits in ("-" * 16, "0123456789abcdef"):
        data = earlier_handout(old, digits=digits)
        assert files.ownership(str(old)) == files.EDITED
        line = one_error(main_py("vertical", "--vpython", old))
        assert ("no fingerprint" if digits.startswith("-") else "no longer matches") in line
        assert old.read_bytes() == data
    before_fingerprints = (b"from vpython import *\n# vertical: The page's Simple Example.\n# " + files.MARK.encode()
                           + b" with the euler-cromer integrator.\nk = 40\n")
    old.write_bytes(before_fingerprints)
    assert "no fingerprint" in one_error(main_py("vertical", "--vpython", old))
    assert old.read_bytes() == before_fingerprints
    assert main_py("vertical", "--vpython", old, "--overwrite").returncode == 0


def test_a_compressed_svg_is_its_own_by_the_record_of_what_it_wrote(tmp_path):
    """An .svgz figure is compressed whole: its mark has no fingerprint, so it is ours only where
    the record of what this program wrote (export/written.py) has it, unchanged."""
    path = tmp_path / "run.svgz"
    assert main_py("vertical", "--plot", path).returncode == 0
    assert files.ownership(str(path)) == files.OURS
    (tmp_path / "record" / "written-sha256.txt").unlink()      # forgotten: marked, but not known unchanged
    assert files.ownership(str(path)) == files.EDITED
    assert "no fingerprint" in one_error(main_py("vertical", "--plot", path))


def test_a_csv_file_with_changed_rows_is_still_its_own(tmp_path):
    """The CSV format has no place for a fingerprint that every reader skips (see files.ownership):
    a CSV file is known by its header alone, and one whose rows were changed is replaced as before."""
    path = tmp_path / "run.csv"
    assert main_py("vertical", "--headless", "--csv", path).returncode == 0
    rows = path.read_bytes().split(b"\r\n")
    rows[3] = b"0.3,1,2,3,4,5,6,7,8,9,10,11,12,13"
    path.write_bytes(b"\r\n".join(rows))
    assert files.ownership(str(path)) == files.OURS
    assert main_py("vertical", "--headless", "--csv", path).returncode == 0


@pytest.mark.parametrize("at", [0, 100, (1 << 20) - 7, (1 << 20), 3 * (1 << 20) - 1])
def test_the_fingerprint_is_streamed_and_leaves_out_its_own_digits(at):
    """A figure's fingerprint reads the file in 1 MiB blocks; its own 16 digits (here across a
    block's end too) are left out, so filling them in does not change it."""
    import hashlib
    import io
    import random

    data = bytearray(random.Random(at).randbytes(3 * (1 << 20) + 5))
    expected = hashlib.sha256(bytes(data[:at] + data[at + 16:])).hexdigest()[:16].encode()
    assert marks._binary_digest(io.BytesIO(bytes(data)), at) == expected
    data[at:at + 16] = expected
    assert marks._binary_digest(io.BytesIO(bytes(data)), at) == expected


@pytest.mark.parametrize("block_end", [False, True])
def test_a_programs_fingerprint_reads_windows_line_ends_as_newlines(block_end, tmp_path):
    """A program printed and saved on Windows (`--vpython - > mine.py`: the shell writes "\\r\\n") is
    still the very text stamped; a line end changed, or a "\\r\\n" split across two 1 MiB blocks,
    is read the same way; a real edit is not."""
    padding = "x" * ((1 << 20) - 200) if block_end else ""
    text = marks.stamped("from vpython import *\nk = 1\n# " + padding + "\nm = 2\n")
    path = tmp_path / "spring.py"
    path.write_bytes(text.replace("\n", "\r\n").encode())
    if block_end:    # a "\r" as the last byte of the first block
        data = path.read_bytes()
        assert b"\r\n" in data[(1 << 20) - 1:(1 << 20) + 1] or data[(1 << 20) - 1:(1 << 20)] != b"\r"
    assert files.ownership(str(path)) == files.OURS
    path.write_bytes(path.read_bytes().replace(b"k = 1\r\n", b"k = 1\n"))
    assert files.ownership(str(path)) == files.OURS
    path.write_bytes(path.read_bytes().replace(b"k = 1", b"k = 2"))
    assert files.ownership(str(path)) == files.EDITED

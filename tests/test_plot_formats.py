"""--plot onto a file type, or a place, it cannot write: one line and exit 2, never matplotlib's own
message or a traceback (issue 28's rule: bad input is exit 2 with one line naming it)."""
from __future__ import annotations

import os
import shutil
import stat
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from test_output_files import main_py, one_error  # noqa: E402

from export import files  # noqa: E402

pytest.importorskip("matplotlib")


@pytest.mark.parametrize("name", ["run.eps", "run.ps", "run.EPS"])
def test_postscript_is_written_with_no_stray_line(name, tmp_path):
    """matplotlib's note that PostScript draws see-through lines opaque is not printed."""
    path = tmp_path / name
    done = main_py("vertical", "--plot", path)
    assert done.returncode == 0 and done.stderr == "", done.stderr
    assert files.ownership(str(path)) == files.OURS


def test_a_pgf_figure_without_tex_is_one_line(tmp_path):
    """.pgf is in matplotlib's list, but writing one needs a TeX system: without one it was exit 1,
    "unexpected RuntimeError: 'xelatex' not found ... (a bug in main.py)", after the whole run."""
    import matplotlib

    path = tmp_path / "run.pgf"
    tex = matplotlib.rcParams["pgf.texsystem"]
    if shutil.which(tex) is not None:
        assert main_py("vertical", "--plot", path).returncode == 0
        return
    for argv in (["vertical", "--plot", path], ["damped", "--data", ROOT / "examples" / "data" / "vernier.csv",
                                                "--plot", path]):
        assert one_error(main_py(*argv)) == (f"error: --plot cannot write {str(path)!r}: a .pgf figure needs {tex} "
                                             f"(a TeX system), which is not installed here; use .pdf, .svg or .png "
                                             f"instead, or install TeX")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("name", ["run.txt", "run.bmp", "run", "run.svg.gz"])
def test_a_type_it_cannot_write_is_one_line(name, tmp_path):
    line = one_error(main_py("vertical", "--plot", tmp_path / name))
    assert line.startswith(f"error: --plot cannot write {str(tmp_path / name)!r}: use one of the file types .")
    assert ".png" in line and ".svg" in line
    assert os.listdir(tmp_path) == []


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_a_named_pipe_is_refused_without_opening_it(tmp_path):
    """Opening a FIFO for writing waits for a reader: it is refused from os.stat alone (timeout: no hang)."""
    fifo = tmp_path / "run.png"
    os.mkfifo(fifo)
    assert one_error(main_py("vertical", "--plot", fifo)) == \
        f"error: cannot write figure {str(fifo)!r}: it is a named pipe, not a regular file"
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


def test_a_directory_and_a_missing_folder_are_one_line(tmp_path):
    folder = tmp_path / "run.png"
    folder.mkdir()
    assert one_error(main_py("vertical", "--plot", folder)) == \
        f"error: cannot write figure {str(folder)!r}: it is a directory"
    missing = tmp_path / "no such folder" / "run.png"
    assert one_error(main_py("vertical", "--plot", missing)) == \
        f"error: cannot write figure {str(missing)!r}: folder {str(missing.parent)!r} does not exist"
    assert os.listdir(tmp_path) == ["run.png"] and os.listdir(folder) == []


def test_a_failure_inside_matplotlib_is_one_line_and_keeps_the_old_figure(tmp_path, monkeypatch):
    """Whatever else savefig raises (a writer missing a library) becomes one OutputError line, and the
    old figure stays as it was, with no temporary file left."""
    from reports import plotting

    plt = plotting._pyplot()
    path = tmp_path / "run.png"
    path.write_bytes(b"old figure")
    figure = plt.figure()
    monkeypatch.setattr(type(figure), "savefig", lambda *args, **kwargs: (_ for _ in ()).throw(RuntimeError("no\nway")))
    with pytest.raises(files.OutputError) as raised:
        plotting.save_figure(figure, str(path))
    assert str(raised.value) == (f"--plot cannot write {str(path)!r}: matplotlib could not write a .png file "
                                 f"(RuntimeError: no way); use .png, .svg or .pdf instead")
    assert path.read_bytes() == b"old figure" and os.listdir(tmp_path) == ["run.png"]

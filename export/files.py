"""Writing an output file whole: checked before any work starts, then written to a temporary file in
the same folder and renamed over the target, so a failure part-way (a full disk, a file-size limit,
Ctrl-C) leaves the old file as it was and no half-written one. The CSV file and the figure of the
command line, and the VPython program of both front ends, are written this way.
"""
from __future__ import annotations

import contextlib
import os
import tempfile

STDOUT = "-"                   # the file name that means standard output


class OutputError(ValueError):
    """An output file that cannot be written: a one-line message, found before the run starts."""



def check_writable(path: str, *, what: str) -> None:
    """Raise OutputError if `path` cannot be written as a file (checked before a run starts).

    The check opens the file for writing, without changing one that exists and removing one it
    had to create, so it also catches what permission bits do not show (a read-only file system,
    /proc, a file standing where a folder should be, or running as root). "-" (standard output)
    is refused: the callers that can print to it handle it before asking.
    """
    if path == STDOUT:
        raise OutputError(f"cannot write {what} to '-' (standard output) here: give a file name, "
                          f"like run.csv")
    if not path:
        raise OutputError(f"cannot write {what} '': give a file name, like run.csv")
    if os.path.isdir(path):
        raise OutputError(f"cannot write {what} {path!r}: it is a directory")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise OutputError(f"cannot write {what} {path!r}: folder {folder!r} does not exist")
    existed = os.path.exists(path)
    try:
        with open(path, "ab"):
            pass
    except OSError as problem:
        raise OutputError(f"cannot write {what} {path!r}: {problem.strerror or problem}") from None
    if not existed:
        os.remove(path)
    os.remove(_temporary_beside(path, what=what))  # the folder must take the temporary file too


def _temporary_beside(path: str, *, what: str) -> str:
    """A new empty file in path's folder, with the permissions `path` has or a new file would get."""
    folder, name = os.path.split(os.path.abspath(path))
    try:
        handle, temporary = tempfile.mkstemp(prefix=f".{name}.", suffix=".part", dir=folder)
        os.close(handle)
        if os.path.exists(path):  # keep the old file's permissions, not mkstemp's private 0600
            os.chmod(temporary, os.stat(path).st_mode & 0o7777)
        else:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(temporary, 0o666 & ~umask)
    except OSError as problem:
        raise OutputError(f"cannot write {what} {path!r}: {problem.strerror or problem}") from None
    return temporary


@contextlib.contextmanager
def atomic_file(path: str, *, what: str):
    """Yield a temporary file name in path's folder; on success it is renamed onto `path`.

    A rename within one folder is atomic, so `path` is always either the old file, untouched, or
    the complete new one: a full disk, a file-size limit, Ctrl-C or SIGTERM part-way leave no
    half-written file (the temporary one is removed). An OSError becomes OutputError.
    """
    temporary = _temporary_beside(path, what=what)
    try:
        yield temporary
        os.replace(temporary, path)
    except OSError as problem:
        raise OutputError(f"cannot write {what} {path!r}: {problem.strerror or problem}") from None
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.remove(temporary)


def same_file(first: str, second: str) -> bool:
    """Whether two output paths name the same file (after ., .., symbolic links and case on disk)."""
    if first == STDOUT or second == STDOUT:
        return first == second
    if os.path.exists(first) and os.path.exists(second):
        return os.path.samefile(first, second)
    return os.path.realpath(first) == os.path.realpath(second)


def write_text(path: str, text: str, *, what: str) -> None:
    """Write text to path whole (atomic_file); raises OutputError with one line if it cannot."""
    check_writable(path, what=what)
    with atomic_file(path, what=what) as temporary:
        with open(temporary, "w", encoding="utf-8") as out:
            out.write(text)


def check_path(path: str) -> None:
    """Raise OutputError (one line) if a program cannot be written to path."""
    check_writable(path, what="the program")


def write_program(path: str, text: str) -> None:
    """Write a program to path whole: a temporary file in the same folder, then renamed over it."""
    write_text(path, text, what="the program")

"""Writing an output file whole: checked before any work starts, then written to a temporary file in
the same folder and renamed over the target, so a failure part-way (a full disk, a file-size limit,
Ctrl-C) leaves the old file as it was and no half-written one. The CSV file and the figure of the
command line, and the VPython program of both front ends, are written this way.

A symbolic link is followed: the file it points to is replaced, and the link stays a link. Only a
regular file is replaced: an existing device (/dev/null, /dev/stdout), named pipe or socket is
refused before anything opens it, since renaming over it would put a regular file in its place
and opening a pipe waits for a reader.
"""
from __future__ import annotations

import contextlib
import os
import stat
import tempfile

STDOUT = "-"                   # the file name that means standard output
HANDOUT_MARK = "Written by the spring-mass simulator"   # in the header of every program it writes
PROJECT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
OWN_FILES = ("main.py", "README.md", "pyproject.toml", ".gitignore", "physics", "scenes", "reports", "export",
             "browser", "tests", "benchmarks", "docs", "examples", ".ci", ".git")   # in PROJECT; also requirements*


class OutputError(ValueError):
    """An output file that cannot be written: a one-line message, found before the run starts."""


def _real(path: str, *, what: str) -> str:
    """os.path.realpath, but a relative path from a folder that was deleted is an OutputError."""
    try:
        return os.path.realpath(path)
    except FileNotFoundError:   # os.getcwd(): the folder the command runs in is gone
        raise OutputError(f"cannot write {what} {path!r}: the folder this command runs in no longer exists; "
                          f"cd to a folder that exists, or give the full path") from None


def _target(path: str, *, what: str) -> str:
    """The file to replace for `path`: itself, or the file a symbolic link points to.

    Raises OutputError if `path` exists and is not a regular file: a directory, a device
    (/dev/null, /dev/stdout), a named pipe or a socket. Only os.stat looks at it, so nothing is
    opened (opening a named pipe would wait for a reader).
    """
    try:
        mode = os.stat(path).st_mode       # follows links as the system does, /dev/stdout too
    except (FileNotFoundError, NotADirectoryError):   # a new file (a link to one), or no such folder
        return _real(path, what=what)
    except OSError as problem:
        raise OutputError(f"cannot write {what} {path!r}: {problem.strerror or problem}") from None
    if stat.S_ISREG(mode) and not _is_a_standard_stream(path):
        return _real(path, what=what)
    if stat.S_ISREG(mode):                 # /dev/stdout where the shell sends the output to a file
        raise OutputError(f"cannot write {what} {path!r}: it is this program's own standard input, "
                          f"output or error (to print the output, give - instead, where - is allowed)")
    if stat.S_ISDIR(mode):
        raise OutputError(f"cannot write {what} {path!r}: it is a directory")
    kind = "a named pipe" if stat.S_ISFIFO(mode) else "a socket" if stat.S_ISSOCK(mode) else "a device"
    raise OutputError(f"cannot write {what} {path!r}: it is {kind}, not a regular file")


def _is_a_standard_stream(path: str) -> bool:
    """Whether path is the very file this process reads or prints to (fd 0, 1 or 2)."""
    for fd in (0, 1, 2):
        try:
            if os.path.samestat(os.stat(path), os.fstat(fd)):
                return True
        except OSError:
            continue
    return False


def _refuse_foreign(path: str, target: str, *, what: str, overwrite: bool) -> None:
    """Raise OutputError if target is one of this program's own files, or (unless `overwrite`) an
    existing Python file it did not write: `--vpython main.py` or `--csv scenes/damped.py` would
    break the program, and a student's own program is not ours to replace."""
    inside = os.path.relpath(target, PROJECT).split(os.sep)
    if inside[0] in OWN_FILES or (len(inside) == 1 and inside[0].startswith("requirements")):
        raise OutputError(f"cannot write {what} {path!r}: it is one of this program's own files; "
                          f"give another name")
    if overwrite or not target.lower().endswith((".py", ".pyw")) or not os.path.isfile(target):
        return
    try:
        with open(target, "rb") as file:
            ours = HANDOUT_MARK.encode() in file.read(2000)
    except OSError:
        ours = False   # unreadable: not known to be ours
    if not ours:
        raise OutputError(f"cannot write {what} {path!r}: it is a Python file this program did not write; "
                          f"give another name, or add --overwrite to replace it")


def check_writable(path: str, *, what: str, overwrite: bool = False) -> None:
    """Raise OutputError if `path` cannot be written as a file (checked before a run starts).

    The check opens the file for writing, without changing one that exists and removing one it
    had to create, so it also catches what permission bits do not show (a read-only file system,
    /proc, a file standing where a folder should be, or running as root). A symbolic link is
    checked as the file it points to; a device, named pipe or socket is refused before it is
    opened (see _target), and so are the program's own files and, unless `overwrite`, a Python file
    it did not write (see _refuse_foreign). "-" (standard output) is refused: the callers that can print to it
    handle it before asking.
    """
    if path == STDOUT:
        raise OutputError(f"cannot write {what} to '-' (standard output) here: give a file name, "
                          f"like run.csv")
    if not path:
        raise OutputError(f"cannot write {what} '': give a file name, like run.csv")
    target = _target(path, what=what)
    folder = os.path.dirname(target)
    if not os.path.isdir(folder):
        raise OutputError(f"cannot write {what} {path!r}: folder {folder!r} does not exist")
    _refuse_foreign(path, target, what=what, overwrite=overwrite)
    existed = os.path.exists(target)
    try:
        with open(target, "ab"):
            pass
    except OSError as problem:
        raise OutputError(f"cannot write {what} {path!r}: {problem.strerror or problem}") from None
    if not existed:
        os.remove(target)
    os.remove(_temporary_beside(target, what=what, shown=path))  # the folder must take it too


def _temporary_beside(target: str, *, what: str, shown: str) -> str:
    """A new empty file in target's folder, with the permissions `target` has or a new file would
    get (`shown`: the path as the user gave it, for the message)."""
    folder, name = os.path.split(target)
    try:
        # a short name of its own: a legal name of 255 bytes would be too long with a suffix added
        handle, temporary = tempfile.mkstemp(prefix=".spring-", suffix=".part", dir=folder)
        os.close(handle)
        if os.path.exists(target):  # keep the old file's permissions, not mkstemp's private 0600
            os.chmod(temporary, os.stat(target).st_mode & 0o7777)
        else:
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(temporary, 0o666 & ~umask)
    except OSError as problem:
        raise OutputError(f"cannot write {what} {shown!r}: {problem.strerror or problem}") from None
    return temporary


# Windows refuses to replace a file another program holds open (a CSV open in Excel): say so.
IN_USE = " (is the file open in another program, such as Excel? close it there and run again)"


@contextlib.contextmanager
def atomic_file(path: str, *, what: str):
    """Yield a temporary file name in path's folder; on success it is renamed onto `path`.

    A rename within one folder is atomic, so `path` is always either the old file, untouched, or
    the complete new one: a full disk, a file-size limit, Ctrl-C or SIGTERM part-way leave no
    half-written file (the temporary one is removed). An OSError becomes OutputError. A symbolic
    link is followed (the temporary file goes beside the file it points to, and replaces that);
    a target that is not a regular file is refused (_target).
    """
    target = _target(path, what=what)
    temporary = _temporary_beside(target, what=what, shown=path)
    try:
        yield temporary
        os.replace(temporary, target)
    except OSError as problem:
        raise OutputError(f"cannot write {what} {path!r}: {problem.strerror or problem}"
                          f"{IN_USE if isinstance(problem, PermissionError) and os.path.exists(target) else ''}"
                          ) from None
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.remove(temporary)


def same_file(first: str, second: str) -> bool:
    """Whether two output paths name the same file (after ., .., symbolic links and case on disk)."""
    if first == STDOUT or second == STDOUT:
        return first == second
    if os.path.exists(first) and os.path.exists(second):
        return os.path.samefile(first, second)
    try:
        return os.path.realpath(first) == os.path.realpath(second)
    except FileNotFoundError:   # the working folder was deleted: check_writable says so
        return first == second


def write_text(path: str, text: str, *, what: str, overwrite: bool = False) -> None:
    """Write text to path whole (atomic_file); raises OutputError with one line if it cannot."""
    check_writable(path, what=what, overwrite=overwrite)
    with atomic_file(path, what=what) as temporary:
        with open(temporary, "w", encoding="utf-8") as out:
            out.write(text)


def check_path(path: str, *, overwrite: bool = False) -> None:
    """Raise OutputError (one line) if a program cannot be written to path."""
    check_writable(path, what="the program", overwrite=overwrite)


def write_program(path: str, text: str, *, overwrite: bool = False) -> None:
    """Write a program to path whole: a temporary file in the same folder, then renamed over it."""
    write_text(path, text, what="the program", overwrite=overwrite)

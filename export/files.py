"""Writing an output file whole, and never where it must not go.

Checked before any work starts, then written to a temporary file in the same folder and renamed
over the target, so a failure part-way (a full disk, a file-size limit, Ctrl-C) leaves the old file
as it was and no half-written one. The CSV file and the figure of the command line, the mystery
file, and the programs and pages of both front ends, are written this way.

Where a file may go (check_writable):

- Never into the program's own tree, with or without --overwrite (see own_tree): not beside
  main.py, not in any folder of the tree. The tree is worked out from the folder this program
  runs from, not from a list of its parts, so a module, folder, data file or document added later
  is covered without anyone remembering to list it. Outputs go in a folder of outputs the tree's
  .gitignore gives to the user (out/), where no tool's file (conftest.py, setup.py, *.pth, ...)
  may be written either.
- Never over a file the program did not write, or wrote and someone changed since, unless
  --overwrite is given: a file is ours only where its mark stands where we put it and its
  fingerprint still matches (export/marks.py ownership; the rules are in docs/homework.md).
- A symbolic link is followed: the file it points to is the one judged, and replaced, and the
  link stays a link. Only a regular file is replaced: an existing device (/dev/null,
  /dev/stdout), named pipe or socket is refused before anything opens it, since renaming over it
  would put a regular file in its place and opening a pipe waits for a reader.

Each file written is added to the record of what this program wrote (export/written.py).
"""
from __future__ import annotations

import contextlib
import importlib.machinery
import os
import stat
import sys
import tempfile

from . import marks, written
from .marks import (CSV_HEADER_LINES, DIGEST_SLOT, EDITED, FIGURE_MARK_KEYS, FINGERPRINTED_FIGURES,  # noqa: F401
                    MARK, OURS, THEIRS, figure_mark, fill_fingerprint, ownership, stamped)

STDOUT = "-"                   # the file name that means standard output
HANDOUT_MARK = MARK            # the name the program writers use
PROJECT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))   # the folder main.py is in
# Files that Python's tools read or run from the folder they lie in: pytest's conftest.py and
# settings, packaging's setup files, a package's __init__.py, the site module's customize files
# and path files. Written into the program's folder, even its out/, they would run with the tools.
TOOL_FILES = {"conftest.py", "pytest.ini", ".pytest.ini", "tox.ini", "setup.py", "setup.cfg", "pyproject.toml",
              "noxfile.py", "__init__.py", "__main__.py", "sitecustomize.py", "usercustomize.py", "manifest.in"}
TOOL_SUFFIXES = (".pth",)


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


# ---- the program's own tree ----

def _module_name(name: str) -> str | None:
    """The module Python would import from a file called `name` (json.py: json), or None."""
    for suffix in sorted(set(importlib.machinery.all_suffixes()) | {".pyw"}, key=len, reverse=True):
        if name.lower().endswith(suffix) and len(name) > len(suffix):
            return name[:-len(suffix)]
    return None


def _tool_file(name: str) -> bool:
    """Whether a file of this name is one Python's tools read or run where it lies (TOOL_FILES)."""
    folded = name.lower()
    return folded in TOOL_FILES or folded.endswith(TOOL_SUFFIXES)


def _user_folders() -> set[str]:
    """The folders at PROJECT's top that its own .gitignore gives to the user: the lines that name
    one folder at the root, such as `/out/` (none if there is no .gitignore)."""
    try:
        with open(os.path.join(PROJECT, ".gitignore"), encoding="utf-8") as file:
            lines = file.read().splitlines()
    except (OSError, UnicodeDecodeError):
        return set()
    names = set()
    for line in lines:
        name = line.strip().strip("/")
        if line.strip().startswith("/") and name and not any(c in name for c in "/*?[]!\\"):
            names.add(name)
    return names


def _made_user_folder(folder: str) -> bool:
    """Make the project's own out/ (a folder its .gitignore gives to the user, _user_folders) if
    `folder` is it and it is missing: the guides write `--vpython out/damped.py` from a fresh
    checkout, which has no out/ yet. Any other missing folder stays an error (a mistyped path)."""
    if os.path.dirname(folder) != os.path.realpath(PROJECT) or os.path.basename(folder) not in _user_folders():
        return False
    try:
        os.mkdir(folder)
    except FileExistsError:
        pass
    except OSError:
        return False
    return os.path.isdir(folder)


def _scene_folders() -> list[str]:
    """A teacher's scene folders (SPRING_SCENES), where Python imports scenes from."""
    from scenes import catalog

    return [str(folder) for folder in catalog.FOLDERS[1:]]


def _inside(target: str, folder: str) -> list[str] | None:
    """The parts of `target` below `folder` (both real paths; compared as files, so a folder
    reached by another spelling or mount is still found), or None if it is not below it."""
    try:
        top = os.stat(folder)
    except OSError:
        return None
    parts, here = [], target
    while True:
        parent = os.path.dirname(here)
        parts.insert(0, os.path.basename(here))
        try:
            if os.path.samestat(os.stat(parent), top):
                return parts
        except OSError:
            pass
        if parent == here or not parent:
            return None
        here = parent


def own_tree(target: str) -> str | None:
    """Why writing the real path `target` would write into the program's own tree (a phrase for
    the one-line message), or None where it would not.

    The tree is PROJECT, the folder main.py is in, and everything under it: the packages, the
    data, documents, tests and .git, found as folders and files, not from a list (one added later
    is covered) and not from git (a copy made without .git, or unzipped from an archive, is the
    same tree, and is just as broken by a CSV written over one of its modules). So:

    - Nothing is written directly in PROJECT, new or old, whatever --overwrite says: beside main.py
      a file may be a module (json.py would be imported in place of json), a tool's settings
      (pytest.ini, conftest.py: the project's own tests would fail) or a user's file that cannot
      be told from one, and every new file there is one more that `git status` shows.
    - Nothing is made in any folder below PROJECT: a new file in scenes/ would be a scene, in
      docs/ or tests/ a part of the project. The exception is the folders the tree's own
      .gitignore gives to the user by naming them at its root (`/out/`): a student who keeps
      outputs in ./out/ of a checkout writes there as anywhere else. Git ignores it, the program
      never reads it; it is the place this message suggests. Even there, no tool's file
      (TOOL_FILES: conftest.py, setup.py, __init__.py, sitecustomize.py, *.pth, ...) is written.
      The .gitignore's other lines (`__pycache__/`, `.venv/`, `*.pyc`) name what tools make
      wherever they run, which stays protected. A copy without the .gitignore has no such folder,
      and everything under PROJECT is refused.
    - A teacher's scene folder (SPRING_SCENES) is the teacher's, but Python imports scenes from
      it: no file named as a module is written there, new or old. Other files there are the
      teacher's, and the usual rules apply to them.
    """
    name = os.path.basename(target)
    parts = _inside(target, PROJECT)
    if parts is not None:
        if parts[0] in _user_folders() and len(parts) > 1:
            if _tool_file(name):
                return (f"{name} is a file Python's tools run where it lies (pytest, pip, site), and inside the "
                        f"program's folder they would run it")
            return None
        if len(parts) > 1:
            return f"it is inside the program's own folder {parts[0]}/, which it never writes into"
        where = "is" if os.path.lexists(target) else "would go"
        return f"it {where} beside main.py, in the program's own folder, which holds only the program's files"
    for folder in _scene_folders():
        if _inside(target, folder) == [name] and _module_name(name) is not None:
            return (f"it is in the teacher's scene folder {folder!r} (SPRING_SCENES), where every Python "
                    f"file is read as a scene")
    return None


# ---- the program's own outputs (export/marks.py) ----

def written_here(target: str) -> bool:
    """Whether the existing file at `target` is one this program wrote, unchanged since (marks.ownership)."""
    return ownership(target) == OURS


def _edited_how(target: str) -> str:
    """Why a file with our mark is not ours any more: its fingerprint no longer matches, or is gone."""
    try:
        with open(target, "rb") as file:
            mark = marks.find_mark(file, os.fstat(file.fileno()).st_size)
    except OSError:
        mark = None
    if mark is not None and mark.digits is None:
        return ("it carries this program's mark but no fingerprint (deleted, blanked, or written by a version "
                "before fingerprints), so it cannot tell whether it was edited")
    return "this program wrote it, but it has been changed since (its sha256 fingerprint no longer matches)"


def _refuse(path: str, target: str, *, what: str, overwrite: bool) -> None:
    """Raise OutputError if target is in the program's own tree (own_tree), or, unless
    `overwrite`, an existing file this program did not write or that was changed since (ownership)."""
    reason = own_tree(target)
    if reason is not None:
        where = sorted(_user_folders())
        name = os.path.basename(target)
        advice = ("give another name" if not reason.startswith(("it is inside", "it would go beside", "it is beside")) else
                  f"write it in {where[0]}/ (kept for your files: {where[0]}/{name}) or outside the program's folder"
                  if where else "write it outside the program's folder")
        raise OutputError(f"cannot write {what} {path!r}: {reason}; {advice}")
    if overwrite or not os.path.isfile(target):
        return
    owner = ownership(target)
    if owner == OURS:
        return
    kind = target.rsplit(".", 1)[-1].lower() if "." in os.path.basename(target) else ""
    if owner == EDITED:
        said = _edited_how(target)
    elif what == "figure" and kind not in FIGURE_MARK_KEYS:
        said = f"it is a .{kind} file, a type that cannot carry this program's mark, so it cannot tell whether it wrote it"
    else:
        said = f"it is {'a Python file' if kind in ('py', 'pyw') else 'a file'} this program did not write"
    raise OutputError(f"cannot write {what} {path!r}: {said}; give another name, or add --overwrite to replace it")


def check_writable(path: str, *, what: str, overwrite: bool = False) -> None:
    """Raise OutputError if `path` cannot be written as a file (checked before a run starts).

    The check opens the file for writing, without changing one that exists and removing one it
    had to create, so it also catches what permission bits do not show (a read-only file system,
    /proc, a file standing where a folder should be, or running as root). A symbolic link is
    checked as the file it points to; a device, named pipe or socket is refused before it is
    opened (see _target), and so is a path in the program's own tree (own_tree) and, unless
    `overwrite`, an existing file it did not write (written_here). "-" (standard output) is
    refused: the callers that can print to it handle it before asking.
    """
    if path == STDOUT:
        raise OutputError(f"cannot write {what} to '-' (standard output) here: give a file name, "
                          f"like run.csv")
    if not path:
        raise OutputError(f"cannot write {what} '': give a file name, like run.csv")
    target = _target(path, what=what)
    folder = os.path.dirname(target)
    if not os.path.isdir(folder) and not _made_user_folder(folder):
        raise OutputError(f"cannot write {what} {path!r}: folder {folder!r} does not exist")
    _refuse(path, target, what=what, overwrite=overwrite)
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
def atomic_file(path: str, *, what: str, record: bool = True):
    """Yield a temporary file name in path's folder; on success it is renamed onto `path`.

    A rename within one folder is atomic, so `path` is always either the old file, untouched, or
    the complete new one: a full disk, a file-size limit, Ctrl-C or SIGTERM part-way leave no
    half-written file (the temporary one is removed). An OSError becomes OutputError. A symbolic
    link is followed (the temporary file goes beside the file it points to, and replaces that);
    a target that is not a regular file is refused (_target). A figure's fingerprint is filled in
    (marks.fill_fingerprint), and the file, once in place, is added to the record of what this
    program wrote (export/written.py; `record=False` for a file known by its header, the CSV).
    """
    target = _target(path, what=what)
    temporary = _temporary_beside(target, what=what, shown=path)
    try:
        yield temporary
        fill_fingerprint(temporary)
        os.replace(temporary, target)
        if record:
            written.remember(target, inside=lambda folder: _inside(folder, PROJECT) is not None)
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
    """Write a program to path whole: a temporary file in the same folder, then renamed over it,
    stamped with its mark line and fingerprint (marks.stamped)."""
    write_text(path, stamped(text), what="the program", overwrite=overwrite)

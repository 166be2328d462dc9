"""The record of the files this program wrote: each one's SHA-256, kept in the user's cache folder.

A file that carries no fingerprint of its own (an .svgz or .jpg figure, the mystery file) is known
as ours where its whole SHA-256 is here: it was written by this program and not changed since. So
is any file written from now on, whatever a later version does to the marks (export/marks.py).
A copy of an output, byte for byte, is recognised too: replacing it loses nothing.

The record is a small text file, one digest per line, the newest last, cut back to its last
KEEP lines when it grows past twice that. It lives where each system keeps such files:

    Linux, ChromeOS  $XDG_CACHE_HOME/spring-mass-simulator, or ~/.cache/spring-mass-simulator
    macOS            ~/Library/Caches/spring-mass-simulator
    Windows          %LOCALAPPDATA%\\spring-mass-simulator

or in the folder SPRING_MASS_CACHE names (an empty value: no record). It is a convenience: a
record that cannot be read or written (a read-only home, a full disk) is passed over in silence,
and the file is judged by its mark alone. Deleting the folder forgets the record and nothing else.
"""
from __future__ import annotations

import hashlib
import os
import sys
import tempfile

FOLDER_VARIABLE = "SPRING_MASS_CACHE"
NAME = "written-sha256.txt"
KEEP = 5000                    # digests kept: 330 KB at most
LARGEST = 256 << 20            # a file bigger than this is not looked up (our outputs are far smaller)


def folder() -> str | None:
    """Where the record is kept (see the module's docstring); None where there is no place for it."""
    chosen = os.environ.get(FOLDER_VARIABLE)
    if chosen is not None:
        return chosen or None
    home = os.path.expanduser("~")
    if sys.platform == "win32":
        base = os.environ.get("LOCALAPPDATA") or os.path.join(home, "AppData", "Local")
    elif sys.platform == "darwin":
        base = os.path.join(home, "Library", "Caches")
    else:
        base = os.environ.get("XDG_CACHE_HOME") or os.path.join(home, ".cache")
    return os.path.join(base, "spring-mass-simulator") if os.path.isabs(base) else None


def _digest(file) -> str:
    digest = hashlib.sha256()
    file.seek(0)
    while block := file.read(1 << 20):
        digest.update(block)
    return digest.hexdigest()


def _digests() -> set[str]:
    where = folder()
    if where is None:
        return set()
    try:
        with open(os.path.join(where, NAME), encoding="ascii") as record:
            return {line.strip() for line in record.read(140 * KEEP).splitlines()}
    except (OSError, UnicodeDecodeError):
        return set()


def recorded(file, size: int) -> bool:
    """Whether an open file's bytes are those of a file this program wrote (in the record)."""
    if size > LARGEST:
        return False
    known = _digests()
    return bool(known) and _digest(file) in known


def remember(path: str, *, inside) -> None:
    """Add the file at `path`, just written, to the record. `inside(folder)` says whether a folder is
    one the program must never write into (its own tree): a record there is not kept."""
    where = folder()
    if where is None:
        return
    try:
        with open(path, "rb") as file:
            line = _digest(file) + "\n"
        if inside(os.path.realpath(where)):
            return
        os.makedirs(where, exist_ok=True)
        record = os.path.join(where, NAME)
        with open(record, "a", encoding="ascii") as out:
            out.write(line)            # one short write in append mode: whole, even beside another run
        if os.path.getsize(record) > 2 * 65 * KEEP:
            _cut(record)
    except OSError:
        pass


def _cut(record: str) -> None:
    """Keep the record's last KEEP digests (written whole, then renamed over it)."""
    with open(record, encoding="ascii") as file:
        lines = file.read().splitlines()[-KEEP:]
    handle, temporary = tempfile.mkstemp(prefix=".record-", dir=os.path.dirname(record))
    try:
        with os.fdopen(handle, "w", encoding="ascii") as out:
            out.write("".join(line + "\n" for line in lines))
        os.replace(temporary, record)
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)

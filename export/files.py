"""Writing an output file whole, and never where it must not go.

Checked before any work starts, then written to a temporary file in the same folder and renamed
over the target, so a failure part-way (a full disk, a file-size limit, Ctrl-C) leaves the old file
as it was and no half-written one. The CSV file and the figure of the command line, the mystery
file, and the programs and pages of both front ends, are written this way.

Where a file may go (check_writable):

- Never into the program's own tree, with or without --overwrite (see own_tree). The tree is
  worked out from the folder this program runs from, not from a list of its parts, so a module,
  folder, data file or document added later is covered without anyone remembering to list it.
- Never over a file the program did not write, unless --overwrite is given. Its own outputs
  carry a mark (see written_here): the programs and the offline page have MARK in their header,
  the figures have it in their metadata (matplotlib's savefig metadata: PNG "Software", SVG, PDF
  and PostScript "Creator"), and a CSV file is known by its header line, which is the program's
  contract with the scripts that read it (see ownership for why nothing is added to it).
  A file of a type that carries no metadata (.jpg, .tif, .webp, ...) is never known to be ours.
- Beside the mark is a fingerprint, the file's SHA-256 (fingerprint): a marked file that has been
  changed since, such as a handout a student edited, is not replaced without --overwrite either.
  A mark without one (an earlier version's file, an .svgz figure) and a CSV file are known as
  before, by the mark or the header alone (see ownership).
- A symbolic link is followed: the file it points to is the one judged, and replaced, and the
  link stays a link. Only a regular file is replaced: an existing device (/dev/null,
  /dev/stdout), named pipe or socket is refused before anything opens it, since renaming over it
  would put a regular file in its place and opening a pipe waits for a reader.
"""
from __future__ import annotations

import contextlib
import hashlib
import importlib.machinery
import importlib.util
import os
import re
import stat
import sys
import tempfile
import zlib

from .numbers import CSV_HEADER

STDOUT = "-"                   # the file name that means standard output
MARK = "Written by the spring-mass simulator"    # in every program, page and figure it writes
HANDOUT_MARK = MARK            # the name the program writers use
PROJECT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))   # the folder main.py is in
# The header lines of the CSV files it writes (reports/csv_file.py; several masses add "body"),
# with the line end csv.writer gives them: byte for byte, they are how a CSV file of ours is known.
CSV_HEADER_LINES = tuple((",".join(CSV_HEADER + extra) + "\r\n").encode() for extra in ([], ["body"]))
MARK_SPAN = 65536              # bytes read at each end of an existing file to look for the mark
# Where a figure of each file type keeps the note of who wrote it (matplotlib's savefig metadata;
# reports/plotting.py writes MARK there). The other types matplotlib writes (.jpg, .tif, .webp, raw
# pixels) have no such note in matplotlib, so an existing file of theirs is never known to be ours.
FIGURE_MARK_KEYS = {"png": "Software", "svg": "Creator", "svgz": "Creator", "pdf": "Creator", "eps": "Creator",
                    "ps": "Creator"}
# The fingerprint beside the mark (see fingerprint below): "sha256:" and the first 16 hex digits of
# the SHA-256 of the file's bytes without those 16 digits (and, in a PNG, without the CRC of the
# chunk holding them, which depends on them). A writer puts DIGEST_SLOT after MARK (with_fingerprint,
# figure_mark); the file is fingerprinted as written (atomic_file), so the digits match the bytes on
# the disk, line ends and all.
DIGEST_TAG = b"sha256:"
DIGEST_DIGITS = 16
DIGEST_SLOT = DIGEST_TAG.decode() + "-" * DIGEST_DIGITS
DIGEST_SPAN = 1000             # bytes after MARK in which its fingerprint is looked for
_DIGEST = re.compile(re.escape(DIGEST_TAG) + rb"([0-9a-f]{%d}|-{%d})" % (DIGEST_DIGITS, DIGEST_DIGITS))
# The figure types whose mark keeps a fingerprint: the note is stored as plain bytes in the file.
# An .svgz figure is compressed whole, so its digits cannot be found or changed in place: its mark
# has none, and it is known by the mark alone, as before.
FINGERPRINTED_FIGURES = ("png", "svg", "pdf", "eps", "ps")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def figure_mark(kind: str, writer: str) -> dict | None:
    """savefig's metadata for a figure of file type `kind` written by `writer` (its name and
    version): MARK, with DIGEST_SLOT where the type keeps it as plain bytes; None for a type with
    no place for a mark (FIGURE_MARK_KEYS)."""
    key = FIGURE_MARK_KEYS.get(kind)
    if key is None:
        return None
    slot = f" {DIGEST_SLOT}" if kind in FINGERPRINTED_FIGURES else ""
    return {key: f"{MARK} (with {writer}){slot}"}


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


def _importable(module: str) -> bool:
    """Whether Python already has a top-level module of this name (json, numpy, physics, __main__)."""
    if module in sys.stdlib_module_names or module in sys.builtin_module_names or module in sys.modules:
        return True
    try:
        return importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):   # a module whose spec cannot be told: one that exists
        return True


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

    - No existing file under PROJECT is replaced, whatever --overwrite says, except this
      program's own outputs (ownership: marked, edited since or not) lying directly in PROJECT:
      the README's examples run from this folder (`--csv damped.csv`), and running one twice
      replaces its own file (an edited one only with --overwrite, as anywhere). An unmarked file
      there may be main.py or a requirements file, or a user's file that cannot be told from one.
    - A new file may be made directly in PROJECT, the folder users run the program from, unless
      Python would import it in place of a module it already has: main.py's folder comes first
      on Python's path, so a json.py or numpy.py there would replace that module on the next run.
    - Nothing is made in any folder below PROJECT: a new file in scenes/ would be a scene, in
      docs/ or tests/ a part of the project. The exception is the folders the tree's own
      .gitignore gives to the user by naming them at its root (`/out/`): a student who keeps
      outputs in ./out/ of a checkout writes there as anywhere else. Git ignores it, the program
      never reads it, and refusing it would only push the same files somewhere less tidy; it is
      the place this message suggests. The .gitignore's other lines (`__pycache__/`, `.venv/`,
      `*.pyc`) name what tools make wherever they run, the compiled modules and installed
      packages the program runs on, which stay protected. A copy without the .gitignore has no
      such folder, and everything below PROJECT is refused.
    - A teacher's scene folder (SPRING_SCENES) is the teacher's, but Python imports scenes from
      it: no file named as a module is written there, new or old. Other files there are the
      teacher's, and the usual rules apply to them.
    """
    name = os.path.basename(target)
    parts = _inside(target, PROJECT)
    if parts is not None:
        if parts[0] in _user_folders() and len(parts) > 1:
            return None
        if len(parts) > 1:
            return f"it is inside the program's own folder {parts[0]}/, which it never writes into"
        if os.path.lexists(target):
            return None if ownership(target) != THEIRS else "it is one of this program's own files"
        module = _module_name(name)
        if module is not None and module.isidentifier() and _importable(module):
            return (f"in the program's own folder it would be imported in place of the {module} module "
                    f"and break the program")
        return None
    for folder in _scene_folders():
        if _inside(target, folder) == [name] and _module_name(name) is not None:
            return (f"it is in the teacher's scene folder {folder!r} (SPRING_SCENES), where every Python "
                    f"file is read as a scene")
    return None


# ---- the program's own outputs ----

def written_here(target: str) -> bool:
    """Whether the existing file at `target` is one this program wrote, unchanged since: see ownership."""
    return ownership(target) == OURS


OURS, EDITED, THEIRS = "ours", "edited", "theirs"


def ownership(target: str) -> str:
    """OURS if the existing file at `target` is one this program wrote and nobody has changed since,
    EDITED if it carries the mark but its fingerprint no longer matches, THEIRS otherwise.

    The programs, the offline page and the figures have MARK near one end (a header comment, the
    PNG's "Software" text, the SVG's, PDF's or PostScript's "Creator"); a compressed SVG (.svgz)
    is looked at unpacked. Beside the mark is the fingerprint (DIGEST_TAG and 16 hex digits, see
    fingerprint): the file's SHA-256 without those digits. A marked file whose bytes no longer
    give it, such as a handout a student has edited, is EDITED: not replaced without --overwrite.
    A mark with no fingerprint (written by a version before fingerprints, or an .svgz figure) is
    OURS by the mark alone, as it was: a teacher's script that reruns its commands onto files an
    earlier version wrote keeps working. Reading the fingerprint costs one pass over the file in
    blocks (hashlib), so a big figure costs its reading time and no more memory.

    A CSV file is ours if its first line is our header, byte for byte (CSV_HEADER_LINES, with
    csv.writer's line end), and it carries no fingerprint: a CSV file whose rows a student changed
    is still replaced as ours. Nothing is added to the CSV file for a mark or a fingerprint,
    because every addition breaks a reader the header is promised to: measured on our own
    vertical run with csv.DictReader, csv.reader, numpy.loadtxt, numpy.genfromtxt(names=True) and
    pandas.read_csv, and a grader reading line 1 as the header, a comment line before the header
    breaks all six, one after the rows breaks DictReader, csv.reader and pandas (the t column
    turns to text), an extra column breaks the line-1 grader and one or more of the others, and a
    UTF-8 byte-order mark breaks DictReader and genfromtxt. The header is as distinctive: a
    measurement file from Tracker, Vernier, PASCO or Logger Pro has its own. What it cannot tell
    is a file another program wrote in our exact format; the one such file a command reads, its
    --data file, is never written at all (cli/options.py).
    """
    try:
        with open(target, "rb") as file:
            head = file.read(MARK_SPAN)
            size = os.fstat(file.fileno()).st_size
            tail, tail_at = b"", 0
            if size > MARK_SPAN:
                tail_at = max(MARK_SPAN, size - MARK_SPAN)
                file.seek(tail_at)
                tail = file.read(MARK_SPAN)
            if head.startswith(CSV_HEADER_LINES):
                return OURS
            if head.startswith(b"\x1f\x8b"):   # gzip: an .svgz figure, unpacked as far as it was read
                try:
                    unpacked = zlib.decompressobj(wbits=31).decompress(head, MARK_SPAN)
                except zlib.error:
                    unpacked = head
                return OURS if MARK.encode() in unpacked else THEIRS
            found = _find_digest(head, 0) or _find_digest(tail, tail_at)
            if found is None:
                return OURS if MARK.encode() in head or MARK.encode() in tail else THEIRS
            at, digits = found
            if digits == b"-" * DIGEST_DIGITS:     # a slot never filled in: known by its mark alone
                return OURS
            return OURS if fingerprint(file, at) == digits else EDITED
    except OSError:
        return THEIRS   # unreadable: not known to be ours


def _find_digest(block: bytes, offset: int) -> tuple[int, bytes] | None:
    """Where the fingerprint's digits after MARK in `block` start in the file (block starts at
    `offset`), and the digits; None if `block` has no MARK or MARK has no fingerprint after it."""
    mark = block.find(MARK.encode())
    if mark < 0:
        return None
    found = _DIGEST.search(block, mark, mark + len(MARK) + DIGEST_SPAN)
    if found is None:
        return None
    return offset + found.start(1), found.group(1)


def _png_chunk(file, at: int) -> tuple[int, int] | None:
    """In a PNG file, the chunk holding byte `at`: where its type starts (its CRC covers the type
    and the data) and where its CRC starts; None if the file is not a PNG."""
    file.seek(0)
    if file.read(8) != PNG_SIGNATURE:
        return None
    place = 8
    while True:
        file.seek(place)
        head = file.read(8)
        if len(head) < 8:
            return None
        end = place + 8 + int.from_bytes(head[:4], "big")
        if place + 8 <= at < end:
            return place + 4, end
        place = end + 4


def fingerprint(file, at: int) -> bytes:
    """The 16 hex digits (as bytes) of the SHA-256 of an open binary file's bytes, leaving out the
    DIGEST_DIGITS bytes at `at` (the fingerprint's own place) and, in a PNG, the CRC of their
    chunk. Read in blocks of 1 MiB: a big file is never held whole."""
    skips = [(at, at + DIGEST_DIGITS)]
    chunk = _png_chunk(file, at)
    if chunk is not None:
        skips.append((chunk[1], chunk[1] + 4))
    digest = hashlib.sha256()
    file.seek(0)
    place = 0
    while block := file.read(1 << 20):
        end = place + len(block)
        kept, cursor = [], place
        for start, stop in sorted(skips):
            if start < end and stop > cursor:
                kept.append(block[cursor - place:max(start, cursor) - place])
                cursor = min(stop, end)
        kept.append(block[cursor - place:])
        digest.update(b"".join(kept))
        place = end
    return digest.hexdigest()[:DIGEST_DIGITS].encode()


def fill_fingerprint(path: str) -> None:
    """Write the fingerprint of the file at `path` into its place after MARK (DIGEST_SLOT, or the
    digits of an earlier one), and in a PNG the CRC of that chunk again; nothing if it has none.
    The file is changed in place, as many bytes as before: a PDF's table of offsets stays right."""
    with open(path, "r+b") as file:
        head = file.read(MARK_SPAN)
        size = os.fstat(file.fileno()).st_size
        tail_at = max(MARK_SPAN, size - MARK_SPAN) if size > MARK_SPAN else 0
        file.seek(tail_at)
        found = _find_digest(head, 0) or (_find_digest(file.read(MARK_SPAN), tail_at) if tail_at else None)
        if found is None:
            return
        at = found[0]
        digits = fingerprint(file, at)
        file.seek(at)
        file.write(digits)
        chunk = _png_chunk(file, at)
        if chunk is not None:
            file.seek(chunk[0])
            covered = file.read(chunk[1] - chunk[0])
            file.seek(chunk[1])
            file.write(zlib.crc32(covered).to_bytes(4, "big"))


def with_fingerprint(text: str, line: str) -> str:
    """`text` with `line` (a comment holding DIGEST_SLOT, in the file's language) after the line
    holding MARK; `text` as it is if it has no MARK near its top. Only files get it: the same
    program printed (`-`) or downloaded from the page is as before, known by its mark alone."""
    at = text.find(MARK, 0, MARK_SPAN)
    if at < 0:
        return text
    end = text.find("\n", at) + 1 or len(text)
    return text[:end] + line + "\n" + text[end:]


def _refuse(path: str, target: str, *, what: str, overwrite: bool) -> None:
    """Raise OutputError if target is in the program's own tree (own_tree), or, unless
    `overwrite`, an existing file this program did not write or that was changed since (ownership)."""
    reason = own_tree(target)
    if reason is not None:
        where = sorted(_user_folders())
        advice = ("give another name" if not reason.startswith("it is inside") else
                  f"write it outside the program's folder, or in {where[0]}/ (kept for your files)" if where else
                  "write it outside the program's folder")
        raise OutputError(f"cannot write {what} {path!r}: {reason}; {advice}")
    if overwrite or not os.path.isfile(target):
        return
    owner = ownership(target)
    if owner == OURS:
        return
    kind = target.rsplit(".", 1)[-1].lower() if "." in os.path.basename(target) else ""
    if owner == EDITED:
        said = "this program wrote it, but it has been changed since (its sha256 fingerprint no longer matches)"
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
        fill_fingerprint(temporary)
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


PROGRAM_FINGERPRINT = (f"# {DIGEST_SLOT}: this file's fingerprint; once the file is edited, the simulator replaces "
                       f"it only with --overwrite")


def write_program(path: str, text: str, *, overwrite: bool = False) -> None:
    """Write a program to path whole: a temporary file in the same folder, then renamed over it.
    Its header gets the fingerprint's line (PROGRAM_FINGERPRINT, filled in as written)."""
    write_text(path, with_fingerprint(text, PROGRAM_FINGERPRINT), what="the program", overwrite=overwrite)

"""How an output of ours is known: a mark where we wrote it, and a fingerprint that still matches.

A file is this program's own, to be replaced without --overwrite, only where both hold:

- the mark stands where we put it, never anywhere else in the file: the first line of a program or
  page (the second where the format's own first line must come first: "Web VPython 3.2",
  "<!DOCTYPE html>"), or a figure's own metadata field (a PNG's "Software" text chunk, the SVG's
  <metadata> creator, the PDF's /Info /Creator, a PostScript file's %%Creator header line). A
  homework file, a notes page or a "PNG" that merely holds the mark's sentence is not marked;
- the fingerprint beside the mark, `sha256:` and 16 hex digits, is that of the file as it is
  now. A marked file whose digits are deleted, blanked (dashes) or no longer match, such as a
  handout a student edited, is EDITED: refused without --overwrite, like a file not ours.

Every output that can carry a fingerprint carries one: the programs and pages written to a file,
printed (`--vpython -`) or downloaded from the page (stamped), and every figure but an .svgz,
which is compressed whole. A program's or page's fingerprint is of its text with Windows line
ends read as "\\n", so a program printed and saved by the shell on Windows stays ours; a figure's
is of its bytes (with, in a PNG, the CRC of the chunk holding the digits left out).

A CSV file is ours by its header line alone (see ownership). A file that carries no fingerprint of
its own (an .svgz, a .jpg figure, an earlier version's file) is ours where its SHA-256 is in the
record of the files this program wrote (export/written.py, in the user's cache folder). A handout,
page or figure written by the version before this one (its mark a few lines down, its fingerprint
on the line below: docs/homework.md) is ours where that fingerprint still matches.
"""
from __future__ import annotations

import hashlib
import re
import zlib
from dataclasses import dataclass

from . import written
from .numbers import CSV_HEADER

MARK = "Written by the spring-mass simulator"    # in every program, page and figure it writes
DIGEST_TAG = b"sha256:"
DIGEST_DIGITS = 16
DIGEST_SLOT = DIGEST_TAG.decode() + "-" * DIGEST_DIGITS
# The mark line of a program or page, fixed but for the fingerprint's digits (a comment in the
# file's own language; an HTML comment may not hold "--", so it says "told to overwrite").
MARK_LINE = (f"{MARK}; its fingerprint is {DIGEST_SLOT}: once this file is edited, the simulator replaces "
             f"it only when told to overwrite")
LEADS = ("Web VPython 3.2", "<!DOCTYPE html>")     # a format's own first line, before the mark
HEAD = 4096                    # bytes read for the first two lines
SPAN = 65536                   # bytes read at each end of a figure for its metadata
# The header lines of the CSV files it writes (reports/csv_file.py; several masses add "body"),
# with the line end csv.writer gives them: byte for byte, they are how a CSV file of ours is known.
CSV_HEADER_LINES = tuple((",".join(CSV_HEADER + extra) + "\r\n").encode() for extra in ([], ["body"]))
# Where a figure of each file type keeps the note of who wrote it (matplotlib's savefig metadata).
# The other types matplotlib writes (.jpg, .tif, .webp, raw pixels) have no such note.
FIGURE_MARK_KEYS = {"png": "Software", "svg": "Creator", "svgz": "Creator", "pdf": "Creator", "eps": "Creator",
                    "ps": "Creator"}
FINGERPRINTED_FIGURES = ("png", "svg", "pdf", "eps", "ps")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_DIGITS = re.compile(re.escape(DIGEST_TAG) + rb"([0-9a-f]{%d})(?![0-9a-f])" % DIGEST_DIGITS)
# Earlier versions put the mark on the line after the program's description (a page: the line after
# <!DOCTYPE html>), `# Written by the spring-mass simulator with ...` or `<!-- Written by the
# spring-mass simulator (python main.py ...`, and, from the version before this one, on the next line
# `# sha256:<digits>: this file's fingerprint; ...` (a page: in an HTML comment).
_EARLIER_MARKS = (b"# " + MARK.encode() + b" with ", b"<!-- " + MARK.encode() + b" (python main.py ")
_EARLIER_DIGITS = re.compile(rb"(?:# |<!-- )" + re.escape(DIGEST_TAG) + rb"([0-9a-f]{16}|-{16}): this file's fingerprint")

OURS, EDITED, THEIRS = "ours", "edited", "theirs"


@dataclass(frozen=True)
class Mark:
    """Where a file's mark was found: its fingerprint's digits (None where the mark has none, or
    they are blank), where they stand in the file, and whether it is text (line ends read as
    "\\n") or binary (a figure: every byte counts)."""

    digits: bytes | None
    at: int = -1
    text: bool = True


def figure_mark(kind: str, writer: str) -> dict | None:
    """savefig's metadata for a figure of file type `kind` written by `writer` (its name and
    version): MARK, with DIGEST_SLOT where the type keeps it as plain bytes; None for a type with
    no place for a mark (FIGURE_MARK_KEYS)."""
    key = FIGURE_MARK_KEYS.get(kind)
    if key is None:
        return None
    slot = f" {DIGEST_SLOT}" if kind in FINGERPRINTED_FIGURES else ""
    return {key: f"{MARK} (with {writer}){slot}"}


# ---- programs and pages: the mark line, stamped as they are written, printed or downloaded ----

def stamped(text: str) -> str:
    """The program or page `text` with its mark line at its place, the fingerprint filled in: what
    is written to a file, printed, or downloaded from the page. Its line ends are "\\n"."""
    lines = text.split("\n")
    place = 1 if lines and lines[0] in LEADS else 0
    comment = "<!-- {} -->" if lines and lines[0] == "<!DOCTYPE html>" else "# {}"
    lines.insert(place, comment.format(MARK_LINE))
    slotted = "\n".join(lines)
    at = slotted.encode("utf-8").index(DIGEST_SLOT.encode()) + len(DIGEST_TAG)
    digits = _text_digest(slotted.encode("utf-8"), at)
    return slotted.replace(DIGEST_SLOT, DIGEST_TAG.decode() + digits.decode(), 1)


def _text_digest(data: bytes, at: int) -> bytes:
    """The fingerprint of text: SHA-256 of its bytes with "\\r\\n" read as "\\n" and its own 16 digits
    (at `at`, in the bytes as given) read as dashes."""
    data = data[:at] + b"-" * DIGEST_DIGITS + data[at + DIGEST_DIGITS:]
    return hashlib.sha256(data.replace(b"\r\n", b"\n")).hexdigest()[:DIGEST_DIGITS].encode()


def _text_mark(head: bytes) -> Mark | None:
    """The mark of a program or page: its first line (or second, after a LEAD) is the mark line."""
    first, _, rest = head.partition(b"\n")
    at = 0
    if first.rstrip(b"\r").decode("utf-8", "replace") in LEADS:
        at = len(first) + 1
        first = rest.partition(b"\n")[0]
    line = first.rstrip(b"\r")
    prefix = MARK_LINE.partition(DIGEST_SLOT)[0].encode()      # "Written by ...; its fingerprint is "
    if not (line.startswith(b"# " + prefix) or line.startswith(b"<!-- " + prefix)):
        return None
    found = _DIGITS.search(line)
    if found is None:
        return Mark(None)          # marked, its fingerprint deleted or blanked: edited
    return Mark(found.group(1), at + found.start(1), text=True)


def _earlier_mark(head: bytes) -> Mark | None:
    """The mark of a handout or page an earlier version wrote, where it put it: the line after the
    description (a VPython program: its first comment line, after the import lines; Web VPython:
    after its first line), or a page's second line; and, from the version before this one, the
    fingerprint's line under it (a fingerprint of its bytes, every one)."""
    lines = head.split(b"\n")
    first = lines[0].rstrip(b"\r")
    if first == b"from vpython import *":
        place = next((i + 1 for i, line in enumerate(lines) if line.startswith(b"#")), len(lines))
    else:
        place = {b"Web VPython 3.2": 2, b"<!DOCTYPE html>": 1}.get(first)
    if place is None or place + 1 >= len(lines) or not lines[place].startswith(_EARLIER_MARKS):
        return None
    found = _EARLIER_DIGITS.match(lines[place + 1])
    if found is None or found.group(1) == b"-" * DIGEST_DIGITS:
        return Mark(None, text=False)      # written before fingerprints, or never filled in: cannot tell
    at = sum(len(line) + 1 for line in lines[:place + 1]) + found.start(1)
    return Mark(found.group(1), at, text=False)


# ---- figures: a metadata field of their own ----

def _png_text(file) -> Mark | None:
    """A PNG's "Software" text chunk, where it holds the mark: the fingerprint in it."""
    file.seek(0)
    if file.read(8) != PNG_SIGNATURE:
        return None
    place = 8
    while True:
        file.seek(place)
        head = file.read(8)
        if len(head) < 8 or head[4:] == b"IEND":
            return None
        length = int.from_bytes(head[:4], "big")
        if head[4:] == b"tEXt" and length < SPAN:
            data = file.read(length)
            if data.startswith(b"Software\0" + MARK.encode()):
                return _within(data, place + 8)
        place += 12 + length


def _within(field: bytes, offset: int) -> Mark:
    """The fingerprint inside a figure's mark field (`field`, starting at `offset` in the file)."""
    found = _DIGITS.search(field)
    return Mark(None, text=False) if found is None else Mark(found.group(1), offset + found.start(1), text=False)


_SVG = re.compile(rb"\A<\?xml[^>]*>\s*(?:<!DOCTYPE[^>]*>\s*)?<svg\b[^>]*>\s*<metadata>(.*?)</metadata>", re.S)
_SVG_CREATOR = re.compile(rb"<dc:creator>\s*<cc:Agent>\s*<dc:title>(" + re.escape(MARK.encode()) + rb"[^<]*)</dc:title>")


def _svg_metadata(head: bytes) -> Mark | None:
    """An SVG's <metadata>, the first thing in it, naming its creator: the mark."""
    block = _SVG.search(head)
    creator = _SVG_CREATOR.search(block.group(1)) if block else None
    if creator is None:
        return None
    return _within(creator.group(1), block.start(1) + creator.start(1))


def _postscript_creator(head: bytes) -> Mark | None:
    """A PostScript or EPS file's %%Creator line, among its header comments."""
    if not head.startswith(b"%!PS-Adobe"):
        return None
    place = 0
    for line in head.split(b"\n"):
        if line.startswith(b"%%EndComments") or not line.startswith(b"%"):
            return None
        if line.startswith(b"%%Creator: " + MARK.encode()):
            return _within(line, place)
        place += len(line) + 1
    return None


def _pdf_info(file, size: int) -> Mark | None:
    """A PDF's document information (the trailer's /Info), whose /Creator is the mark."""
    file.seek(0)
    if not file.read(5) == b"%PDF-":
        return None
    start = max(0, size - SPAN)
    file.seek(start)
    tail = file.read(SPAN)
    trailers = re.findall(rb"trailer\s*<<(.*?)>>", tail, re.S)
    reference = re.search(rb"/Info\s+(\d+)\s+0\s+R", trailers[-1]) if trailers else None
    if reference is None:
        return None
    info = re.search(rb"(?:^|\s)" + reference.group(1) + rb"\s+0\s+obj\s*<<(.*?)>>\s*endobj", tail, re.S)
    creator = re.search(rb"/Creator\s*\((" + re.escape(MARK.encode()) + rb".*?)\)\s*(?:/|$)", info.group(1), re.S) \
        if info else None
    if creator is None:
        return None
    return _within(creator.group(1), start + info.start(1) + creator.start(1))


def _svgz_metadata(head: bytes) -> Mark | None:
    """A compressed SVG's mark, unpacked as far as it was read: never a fingerprint (the digits
    cannot be found or changed in place), so it is ours only where written.py has it."""
    try:
        unpacked = zlib.decompressobj(wbits=31).decompress(head, SPAN)
    except zlib.error:
        return None
    return Mark(None, text=False) if _svg_metadata(unpacked) is not None else None


# ---- the fingerprint ----

def _binary_digest(file, at: int) -> bytes:
    """The 16 hex digits of the SHA-256 of an open binary file's bytes, leaving out the 16 at `at`
    (the fingerprint's own place) and, in a PNG, the CRC of their chunk. Read in blocks of 1 MiB."""
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
        for begin, stop in sorted(skips):
            if begin < end and stop > cursor:
                kept.append(block[cursor - place:max(begin, cursor) - place])
                cursor = min(stop, end)
        kept.append(block[cursor - place:])
        digest.update(b"".join(kept))
        place = end
    return digest.hexdigest()[:DIGEST_DIGITS].encode()


def _streamed_text_digest(file, at: int) -> bytes:
    """_text_digest of an open file, read in blocks of 1 MiB (a "\\r" at a block's end waits for the
    next block, so a "\\r\\n" split between two is still read as "\\n")."""
    digest = hashlib.sha256()
    file.seek(0)
    place, carried = 0, b""
    while block := file.read(1 << 20):
        if place <= at + DIGEST_DIGITS and place + len(block) > at:
            block = bytearray(block)
            for i in range(max(at, place), min(at + DIGEST_DIGITS, place + len(block))):
                block[i - place] = ord("-")
            block = bytes(block)
        place += len(block)
        block = carried + block
        carried = b"\r" if block.endswith(b"\r") else b""
        digest.update((block[:-1] if carried else block).replace(b"\r\n", b"\n"))
    digest.update(carried)
    return digest.hexdigest()[:DIGEST_DIGITS].encode()


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


def find_mark(file, size: int) -> Mark | None:
    """Where an open file's mark is (see the module's docstring), or None where it has none."""
    file.seek(0)
    head = file.read(SPAN)
    return (_text_mark(head[:HEAD]) or _earlier_mark(head[:HEAD]) or _png_text(file) or _svg_metadata(head)
            or _postscript_creator(head) or _pdf_info(file, size) or _svgz_metadata(head))


def fill_fingerprint(path: str) -> None:
    """Write the fingerprint of a figure at `path` into its mark (DIGEST_SLOT), and in a PNG the CRC
    of that chunk again; nothing for a file with no slot (a program or page is stamped whole). The
    file is changed in place, as many bytes as before: a PDF's table of offsets stays right."""
    with open(path, "r+b") as file:
        size = file.seek(0, 2)
        file.seek(0)
        head = file.read(SPAN)
        slot = head.find(DIGEST_SLOT.encode())
        if slot < 0 and size > SPAN:
            file.seek(size - SPAN)
            found = file.read(SPAN).find(DIGEST_SLOT.encode())
            slot = -1 if found < 0 else size - SPAN + found
        if slot < 0:
            return
        at = slot + len(DIGEST_TAG)
        digits = _binary_digest(file, at)
        file.seek(at)
        file.write(digits)
        mark = find_mark(file, size)
        if mark is None or mark.at != at:      # the slot was not in the figure's mark field
            file.seek(at)
            file.write(b"-" * DIGEST_DIGITS)
            return
        chunk = _png_chunk(file, at)
        if chunk is not None:
            file.seek(chunk[0])
            covered = file.read(chunk[1] - chunk[0])
            file.seek(chunk[1])
            file.write(zlib.crc32(covered).to_bytes(4, "big"))


def ownership(target: str) -> str:
    """OURS if the existing file at `target` is one this program wrote and nobody has changed since,
    EDITED if it carries the mark where we put it but not a fingerprint that matches, THEIRS otherwise.

    A CSV file is ours if its first line is our header, byte for byte (CSV_HEADER_LINES, with
    csv.writer's line end): a CSV file whose rows a student changed is still replaced as ours.
    Nothing is added to the CSV file for a mark or a fingerprint, because every addition breaks a
    reader the header is promised to: measured on our own vertical run with csv.DictReader,
    csv.reader, numpy.loadtxt, numpy.genfromtxt(names=True) and pandas.read_csv, and a grader
    reading line 1 as the header, a comment line before the header breaks all six, one after the
    rows breaks DictReader, csv.reader and pandas (the t column turns to text), an extra column
    breaks the line-1 grader and one or more of the others, and a UTF-8 byte-order mark breaks
    DictReader and genfromtxt. The one such file a command reads, its --data file, is never
    written at all (cli/options.py).

    Any other file is judged by its mark and fingerprint (find_mark), read in blocks, so a big
    figure costs its reading time and no more memory; a file whose whole SHA-256 is in the record
    of what this program wrote (export/written.py) is ours whatever its format.
    """
    try:
        with open(target, "rb") as file:
            head = file.read(HEAD)
            if head.startswith(CSV_HEADER_LINES):
                return OURS
            size = file.seek(0, 2)
            mark = find_mark(file, size)
            if mark is not None and mark.digits is not None:
                digest = _streamed_text_digest(file, mark.at) if mark.text else _binary_digest(file, mark.at)
                if digest == mark.digits:
                    return OURS
            if written.recorded(file, size):
                return OURS
            return THEIRS if mark is None else EDITED
    except OSError:
        return THEIRS   # unreadable: not known to be ours


__all__ = ["CSV_HEADER_LINES", "DIGEST_SLOT", "EDITED", "FIGURE_MARK_KEYS", "FINGERPRINTED_FIGURES", "MARK",
           "MARK_LINE", "OURS", "THEIRS", "figure_mark", "fill_fingerprint", "find_mark", "ownership",
           "stamped"]

"""Reading a measured position against time, from whatever program recorded it.

A motion detector or a video (Tracker, Vernier Graphical Analysis, PASCO Capstone, Logger Pro) and
this program's own --csv all write the same thing: a few lines naming the columns, then rows of
numbers. The reader finds

    the text      UTF-8 (with or without a byte-order mark), UTF-16 (as Excel saves "Unicode
                  text"), or Windows-1252; CRLF or LF line ends
    the rows      the first run of lines that are all numbers (or empty cells), separated by tabs,
                  semicolons, commas or spaces; a decimal comma (0,25) where the separator is ; or tab
    the header    up to three lines above the rows: names, symbols, units (Logger Pro writes all three)
    the series    each position column (x, y, z, Position, Distance, ...) with the time column to its
                  left; several runs side by side (PASCO: `Position (m) Run #2`) are several series
    the units     from the header: s or ms, and m, cm or mm; a header with no unit is read as s and m
    no header     two columns of numbers and nothing above them: t in s and position in m, and said so
    numbers       a decimal point or a decimal comma, and thousands separators (1,600.7 or 1.600,7)
                  read right where the file shows which is which; a cell such as 1,601 that could be
                  either, in a file that never says, is refused
    checks        before anything runs: the file is a regular file (a FIFO or a device is refused
                  at once, and no read goes past MAX_BYTES whatever size the system reports), the
                  samples are a plausible time apart for a spring (a spacing of 10⁷ is not seconds),
                  the position column moves, and its values are lengths a spring can have

Anything it cannot read is a :class:`DataError` whose message is one line naming the file and the
line at fault. Nothing is loaded from a bad file.
"""
from __future__ import annotations

import os
import re
import stat
from dataclasses import dataclass, field

import numpy as np

from . import LabError, cells
from export.numbers import CSV_HEADER

MAX_BYTES = 64 * 1024 * 1024     # larger files are refused before they are read
MAX_ROWS = 200_000               # rows of numbers a file may have (about an hour at 50 samples/s)
TIME_UNITS = {"s": 1.0, "sec": 1.0, "ms": 1e-3}
LENGTH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3}
POSITION_WORDS = ("position", "distance", "displacement", "height", "pos")
SPACING = (1e-5, 10.0)           # s between samples a motion detector or a video of a spring can have
FARTHEST = 1e4                   # m: positions beyond this are no spring's (the constants' own range)
LEAST_SWING = 1e-9               # m: a column that moves less than this does not move
THOUSANDS = {",": re.compile(r"^[+-]?[1-9]\d{0,2}(,\d{3})+$"), ".": re.compile(r"^[+-]?[1-9]\d{0,2}(\.\d{3})+$")}


class DataError(LabError):
    """A measured-data file that cannot be read: one line naming the file and the line at fault."""


@dataclass(frozen=True)
class Series:
    """One position column and the time column it goes with (column numbers from 0)."""

    time: int
    position: int
    name: str          # the position column's header, as written
    coordinate: str    # "x", "y", "z", or "" when the header does not say


@dataclass(frozen=True)
class Measured:
    """The chosen series of a measured file: t in s and position in m, in the file's own clock and zero.

    points is the number of rows used; skipped the rows left out because a cell of the series was
    empty; choice says in words which column was read and how to pick another; lines is each
    point's line in the file; own_step is the Δt of this program's own --csv run (one row a step,
    every column written), else None.
    """

    path: str
    t: np.ndarray
    position: np.ndarray
    choice: str
    skipped: int = 0
    lines: np.ndarray = field(default=None, compare=False)
    own_step: float | None = None


def _fail(path: str, line: int | None, what: str):
    where = f"{path} line {line}" if line else path
    raise DataError(f"{where}: {what}")


# ---- text ----

def decode(raw: bytes, path: str) -> str:
    """The file's text: UTF-16 (with its byte-order mark, or without one when every other byte is 0),
    UTF-8 (a BOM is dropped), else Windows-1252. A binary file is refused, naming its line."""
    if raw.startswith((b"\xff\xfe", b"\xfe\xff")):
        encoding = "utf-16"
    elif len(raw) >= 4 and raw[1::2].count(0) > 0.4 * len(raw) / 2 and raw[0::2].count(0) == 0:
        encoding = "utf-16-le"
    elif len(raw) >= 4 and raw[0::2].count(0) > 0.4 * len(raw) / 2 and raw[1::2].count(0) == 0:
        encoding = "utf-16-be"
    else:
        encoding = None
    if encoding:
        try:
            text = raw.decode(encoding)
        except UnicodeDecodeError as problem:
            _fail(path, raw[:problem.start].count(b"\n\x00") + 1, "not readable as UTF-16 text")
    else:
        try:
            text = raw.decode("utf-8-sig")
        except UnicodeDecodeError:
            text = raw.decode("cp1252", errors="replace")
    text = text.lstrip("\ufeff")
    for number, line in enumerate(text.splitlines(), start=1):
        if any(ord(c) < 32 and c not in "\t\r\n\f\v" for c in line) or "\ufffd" in line:
            _fail(path, number, "not a text file of numbers (it holds binary data); "
                                "export the data as text (CSV or tab-separated) and try again")
    return text


# ---- the header ----

UNIT = re.compile(r"[(\[]\s*([^()\[\]]*?)\s*[)\]]")


def _unit_of(name: str) -> str | None:
    found = UNIT.search(name)
    return found.group(1) if found else None


def _bare(name: str) -> str:
    """`Latest: Position (m)` → `position`; `x (cm)` → `x`; `Time (s) Run #1` → `time run #1`."""
    name = UNIT.sub("", name).lower()
    name = re.sub(r"^[^:]*:\s*", "", name)          # `Latest: ` / `Run 1: ` before the name
    return " ".join(name.split())


def _is_time(name: str) -> bool:
    bare = _bare(name)
    return bare == "t" or bare.startswith("time")


def _coordinate(name: str) -> str | None:
    """"x", "y" or "z" for a position column, "" for one that does not say which, None for others."""
    bare = _bare(name)
    first = bare.split()[0] if bare else ""
    if first in ("x", "y", "z"):
        return first
    if any(bare.startswith(word) for word in POSITION_WORDS):
        return ""
    return None


def _runs(name: str) -> str:
    found = re.search(r"run\s*#?\s*(\d+)", name, re.IGNORECASE)
    return found.group(1) if found else ""


# ---- the file ----

def read(path: str, *, column: str | None = None, run: int | None = None,
         coordinate: str = "y") -> Measured:
    """The measured position against time in `path` (see the module's docstring).

    column   a header to read (a unique part of it, any case) or a column number from 1
    run      the run to read, 1 for the first (the default is the first run)
    coordinate  "x", "y" or "z": preferred where the file has several (Tracker writes x and y)
    Raises DataError with one line naming the file and the line at fault.
    """
    try:
        mode = os.stat(path).st_mode            # follows links: a link to /dev/urandom is a device
        if not stat.S_ISREG(mode):
            kind = ("a folder" if stat.S_ISDIR(mode) else "a FIFO (a named pipe)" if stat.S_ISFIFO(mode) else
                    "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else "a socket" if stat.S_ISSOCK(mode)
                    else "not a regular file")
            _fail(path, None, f"this is {kind}, not a file of measured data; give a file saved from the "
                              f"data program (CSV or text)")
        size = os.path.getsize(path)
        if size > MAX_BYTES:
            _fail(path, None, f"the file is {size / 1e6:.0f} MB, more than the {MAX_BYTES // 2**20} MB "
                              f"this program reads; keep the part of the run you need")
        with open(path, "rb") as handle:
            raw = handle.read(MAX_BYTES + 1)     # whatever size the system reported
    except OSError as problem:
        _fail(path, None, f"cannot read it: {problem.strerror or problem}")
    if len(raw) > MAX_BYTES:
        _fail(path, None, f"the file holds more than the {MAX_BYTES // 2**20} MB this program reads; keep "
                          f"the part of the run you need")
    return from_bytes(raw, path, column=column, run=run, coordinate=coordinate)


def from_bytes(raw: bytes, name: str, *, column: str | None = None, run: int | None = None,
               coordinate: str = "y") -> Measured:
    """The same as read(), for a file's bytes already in hand (a page's upload); `name` names it
    in messages."""
    if len(raw) > MAX_BYTES:
        _fail(name, None, f"the file is {len(raw) / 1e6:.0f} MB, more than the {MAX_BYTES // 2**20} MB "
                          f"this program reads; keep the part of the run you need")
    lines = decode(raw, name).splitlines()
    return _parse(lines, name, column=column, run=run, coordinate=coordinate)


def _parse(lines, path, *, column, run, coordinate) -> Measured:
    # The rows: from the first line of two or more numbers to the end of the file.
    start = None
    for number, line in enumerate(lines):
        if line.strip() and cells.is_numbers(cells.cells(line, cells.separator(line))):
            start = number
            break
    if start is None:
        _fail(path, max(1, len(lines)), "no rows of numbers found; the file needs a header "
                                        "(time and position) and then one row of numbers per sample")
    separator = cells.separator(lines[start])
    width = len(cells.cells(lines[start], separator))
    if width < 2:
        _fail(path, start + 1, "only one column of numbers; the file needs time and position columns")

    header_lines = []
    for number in range(start - 1, -1, -1):
        line = lines[number]
        if not line.strip():
            if header_lines:
                break
            continue
        found = cells.cells(line, separator)
        if len(found) < 2 and header_lines:
            break
        header_lines.insert(0, (number, found))
        if len(header_lines) == 3:
            break
    if separator == "," and header_lines and 2 <= len(header_lines[-1][1]) < width:
        _fail(path, start + 1, f"{width} cells, but the header names {len(header_lines[-1][1])}: with commas "
                               f"between the cells, a decimal comma (0,25) splits each number in two; export "
                               f"with semicolons or tabs between the cells, or with a decimal point")
    headerless = not header_lines and width == 2
    if headerless:
        names, units = ["t", "position"], ["", ""]
    else:
        names, units = _header(header_lines, width, path, start)

    rows_end = len(lines)
    while rows_end > start and not lines[rows_end - 1].strip():
        rows_end -= 1
    if rows_end - start > MAX_ROWS:
        _fail(path, start + MAX_ROWS + 1, f"more than {MAX_ROWS:,} rows of numbers, the most this program "
                                          f"reads; keep the part of the run you need (or sample less often)")
    rows = []
    for number in range(start, rows_end):
        line = lines[number]
        if not line.strip():
            _fail(path, number + 1, "an empty line among the rows of numbers")
        found = cells.cells(line, separator)
        if cells.separator(line) != separator and not (separator == "," and '"' in line):
            if len(line.split()) == 1 and cells.separator(line) is None:
                _fail(path, number + 1, f"only one cell, but the header and the first row have {width}")
            _fail(path, number + 1, f"separated by {_said(cells.separator(line))}, but the lines above by "
                                    f"{_said(separator)} (mixed separators)")
        if len(found) > width:
            _fail(path, number + 1, f"{len(found)} cells, but the header and the first row have {width}")
        rows.append(found)
    try:
        style = cells.style_of(rows)
    except cells.Ambiguous as problem:
        row = next(n for n, found in enumerate(rows) if problem.cell in found)
        _fail(path, start + row + 1, f"{problem.cell!r} could be {problem.cell.replace(',', '.')} or "
                                     f"{problem.cell.replace(',', '')} (a decimal comma or a thousands "
                                     f"separator), and the file never shows which; export the numbers without "
                                     f"thousands separators")
    table = np.full((len(rows), width), np.nan)
    for row, found in enumerate(rows):
        for place, cell in enumerate(found):
            try:
                value = cells.number(cell, style)
            except ValueError:
                _fail(path, start + row + 1, f"{cell[:20]!r} in column {place + 1} ({names[place]!r}) is not a number")
            if value is not None:
                table[row, place] = value

    where = header_lines[-1][0] + 1 if header_lines else start + 1
    series = _series(names, path, where)
    chosen, said = _choose(series, names, column=column, run=run, coordinate=coordinate, path=path, line=where)
    t_unit, x_unit = units[chosen.time], units[chosen.position]
    t = table[:, chosen.time] * TIME_UNITS[t_unit or "s"]
    x = table[:, chosen.position] * LENGTH_UNITS[x_unit or "m"]
    present = ~np.isnan(t) & ~np.isnan(x)
    last = np.flatnonzero(present)
    if last.size < 3:
        _fail(path, start + 1, f"fewer than 3 rows with both {names[chosen.time]!r} and "
                               f"{names[chosen.position]!r}; nothing to compare with")
    t, x, line_numbers = t[present], x[present], np.arange(start + 1, rows_end + 1)[present]
    step = np.diff(t)
    if np.any(step <= 0):
        bad = int(np.flatnonzero(step <= 0)[0]) + 1
        shown = [cells_said(table[present][i, chosen.time]) for i in (bad, bad - 1)]
        _fail(path, int(line_numbers[bad]), f"time {shown[0]} does not increase from the row above "
                                            f"({shown[1]}); the rows must be in order of time")
    _check_values(path, t, x, names, chosen, table[present], t_unit, x_unit, start, line_numbers)
    skipped = int(last[-1] + 1 - last.size)
    if headerless:
        said = "no header: read column 1 as t in s and column 2 as position in m"
    elif not t_unit or not x_unit:
        said += "; no unit in the header, read as s and m"
    if skipped:
        said += f"; {skipped} row{'s' if skipped > 1 else ''} with an empty cell left out"
    return Measured(path=path, t=t, position=x, choice=said, skipped=skipped, lines=line_numbers,
                    own_step=_own_step(names, table[present], t))


def cells_said(value: float) -> str:
    """A number from the file as a message shows it: its own digits, up to 12 significant."""
    return f"{value:.12g}"


def _check_values(path, t, x, names, chosen, table, t_unit, x_unit, start, line_numbers) -> None:
    """The checks on the numbers themselves, before anything runs (see the module's docstring)."""
    spacing = float(np.median(np.diff(t)))
    if not SPACING[0] <= spacing <= SPACING[1]:
        unit = t_unit or "s"
        hint = ("if the times are not in seconds, name their unit in the header, like Time (ms)" if not t_unit
                else f"check the time column's unit (the header says {unit})")
        _fail(path, start + 1, f"the rows are {spacing / TIME_UNITS[unit]:.3g} {unit} apart (the median), and "
                               f"no motion detector or video records a spring "
                               f"{'that seldom' if spacing > SPACING[1] else 'that often'}; {hint}")
    name = names[chosen.position]
    farthest = float(np.max(np.abs(x)))
    if farthest > FARTHEST:
        row = int(line_numbers[int(np.argmax(np.abs(x)))])
        _fail(path, row, f"column {name!r} reads {farthest:.3g} m, far beyond any spring (this program's "
                         f"positions stay within {FARTHEST:g} m); check the column and its unit")
    swing = float(np.ptp(x))
    if swing < LEAST_SWING:
        moving = [other for other, column in enumerate(table.T)
                  if other not in (chosen.position, chosen.time) and _coordinate(names[other]) is not None
                  and np.nanmax(column) - np.nanmin(column) >= LEAST_SWING]
        other = f"; the file's {names[moving[0]]!r} moves: --data-column {names[moving[0]]}" if moving else ""
        amount = (f"every row reads {x[0]:.6g} m" if swing == 0 else f"it moves by {swing:.2g} m at most, far less "
                  f"than any measurement")
        _fail(path, start + 1, f"column {name!r} does not move ({amount}), so there is nothing to "
                               f"compare{other}")


def _own_step(names, table, t) -> float | None:
    """The Δt of this program's own --csv run (its header, every column written, one row a step)."""
    if tuple(names) != tuple(CSV_HEADER) or np.isnan(table).any() or len(t) < 3:
        return None
    steps = np.diff(t)
    middle = float(np.median(steps))
    if np.max(np.abs(steps - middle)) > 1e-6 * middle:
        return None
    return float(f"{middle:.6g}")


def _said(separator) -> str:
    return {"\t": "tabs", ";": "semicolons", ",": "commas", None: "spaces"}[separator]


def _header(header_lines, width, path, start):
    """Each column's name and unit ("" where the header gives none) from the lines above the rows."""
    if not header_lines:
        _fail(path, start + 1, "no header line above the numbers; the file needs one naming the "
                               "columns (time and position, e.g. t,x or Time (s),Position (m))")
    names = [""] * width
    units = [""] * width
    for number, found in reversed(header_lines):     # the line nearest the numbers names best
        found = (found + [""] * width)[:width]
        if all(cell in TIME_UNITS or cell in LENGTH_UNITS or cell == "" or "/" in cell for cell in found) \
                and any(found) and number == header_lines[-1][0] and len(header_lines) > 1:
            units = [cell if cell in TIME_UNITS or cell in LENGTH_UNITS else "?" + cell if cell else ""
                     for cell in found]
            continue
        for place, cell in enumerate(found):
            if cell and not names[place]:
                names[place] = cell
    for place, name in enumerate(names):
        unit = units[place] or _unit_of(name) or ""
        kind = "time" if _is_time(name) else "position" if _coordinate(name) is not None else None
        known = TIME_UNITS if kind == "time" else LENGTH_UNITS
        if kind and unit and unit.lstrip("?") not in known:
            _fail(path, header_lines[-1][0] + 1,
                  f"unknown unit {unit.lstrip('?')!r} for column {name!r}; this program reads "
                  f"{'s or ms' if kind == 'time' else 'm, cm or mm'}")
        units[place] = unit if kind else ""
        names[place] = name or f"column {place + 1}"
    return names, units


def _series(names, path, line) -> list[Series]:
    found = []
    time = None
    for place, name in enumerate(names):
        if _is_time(name):
            time = place
            continue
        coordinate = _coordinate(name)
        if coordinate is not None and time is not None:
            found.append(Series(time=time, position=place, name=name, coordinate=coordinate))
    if time is None:
        _fail(path, line, f"no time column in the header ({', '.join(repr(n) for n in names[:6])}); "
                          f"name it t or Time (s)")
    if not found:
        _fail(path, line, f"no position column after the time column ({', '.join(repr(n) for n in names[:6])}); "
                          f"name it x, y or Position (m), or pick one with --data-column")
    return found


def _choose(series, names, *, column, run, coordinate, path, line):
    """The series asked for (or the first, preferring the scene's coordinate), and a sentence saying so."""
    if column is not None:
        if column.strip().isdecimal():   # not isdigit: "²" is a digit int() cannot read
            place = int(column) - 1
            if not 0 <= place < len(names):
                _fail(path, line, f"--data-column {column}: the file has columns 1 to {len(names)}")
            matches = [s for s in series if s.position == place]
        else:
            matches = [s for s in series if column.lower() in s.name.lower()]
        if len(matches) != 1:
            _fail(path, line, f"--data-column {column!r} matches {len(matches)} position columns of "
                              f"{', '.join(repr(s.name) for s in series)}; give a unique part of one")
        pool = matches
    else:
        pool = series
    runs = sorted({_runs(s.name) for s in pool}, key=lambda r: int(r) if r else 0)
    if run is not None:
        if len(runs) == 1 and run == 1:
            pass
        elif runs == [""] or not 1 <= run <= len(runs):
            _fail(path, line, f"--run {run}: the file has {len(runs) if runs != [''] else 1} run"
                              f"{'s' if len(runs) > 1 else ''}")
        else:
            pool = [s for s in pool if _runs(s.name) == runs[run - 1]]
    else:
        pool = [s for s in pool if _runs(s.name) == runs[0]]
    preferred = [s for s in pool if s.coordinate == coordinate] or pool
    chosen = preferred[0]
    said = f"read {names[chosen.position]!r} against {names[chosen.time]!r}"
    if len(runs) > 1:
        number = runs.index(_runs(chosen.name)) + 1
        said += f" (run {number} of {len(runs)}; --run N reads another)"
    elif len(series) > 1 and column is None:
        said += f" ({len(series)} position columns; --data-column NAME reads another)"
    return chosen, said

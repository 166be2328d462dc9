"""CSV rows a block at a time: the text csv.writer gives for clean()ed numbers, without a call per number.

A file number is clean(x) = float(f"{x:.15g}"), and csv.writer writes a float as repr. Each column
of a block is written in numpy by export/number_text.py (the 15 digits of x worked out exactly, and
laid out as repr lays them out), the rows' endings (",,,,\r\n", or a body label) are added, and the
block's text is its characters with the padding deleted. tests/test_csv_rows.py compares the bytes
with the row-by-row writer, csv.writer on clean()ed numbers.
"""
from __future__ import annotations

import csv
import io

import numpy as np

from .number_text import DROPPED, column_text

ROWS_PER_BLOCK = 16384


def csv_field(text: str) -> str:
    """One field as csv.writer writes it (quoted if it holds a comma, a quote or a line break)."""
    buffer = io.StringIO()
    csv.writer(buffer).writerow(["", text])
    return buffer.getvalue()[1:-2]


def format_numbers(values: np.ndarray, *, after: list[str]) -> str:
    """Rows of cleaned numbers, comma-separated: values (rows, columns), after[i] the text that ends
    row i's line (",,,,\r\n", or a body label and "\r\n"); len(after) divides the rows and repeats.

    The same text as csv.writer.writerow([*map(clean, row)] + ...) for each row.
    """
    return number_rows(values, after=after).decode("utf-8")


def number_rows(values: np.ndarray, *, after: list[str]) -> bytes:
    """format_numbers' text as UTF-8 bytes, for a file opened in binary (no decoding and encoding again)."""
    rows, columns = values.shape
    ending = _endings(after, rows)
    line = np.concatenate([column_text(values[:, j]) for j in range(columns)] + [ending], axis=1)
    line[:, line.shape[1] - ending.shape[1] - 1] = DROPPED       # no comma after a row's last number
    return line.tobytes().translate(None, bytes([DROPPED]))


def _endings(after: list[str], rows: int) -> np.ndarray:
    """Each row's ending, after[i % len(after)] for row i, as UTF-8 padded with DROPPED."""
    endings = [ending.encode("utf-8") for ending in after]
    chars = np.full((len(endings), max(map(len, endings))), DROPPED, dtype=np.uint8)
    for i, ending in enumerate(endings):
        chars[i, :len(ending)] = np.frombuffer(ending, dtype=np.uint8)
    return chars[np.arange(rows) % len(endings)]

"""CSV rows a block at a time: the text csv.writer gives for clean()ed numbers, without a call per number.

A file number is clean(x) = float(f"{x:.15g}"), and csv.writer writes a float as repr. Each column
of a block is written in numpy by export/number_text.py (the 15 digits of x worked out exactly, and
laid out as repr lays them out), the rows' endings (",,,,\r\n", or a body label) are added, and the
block's text is one selection of the characters kept. tests/test_csv_rows.py compares the bytes
with the row-by-row writer, csv.writer on clean()ed numbers.
"""
from __future__ import annotations

import csv
import io

import numpy as np

from .number_text import column_text

ROWS_PER_BLOCK = 4096


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
    rows, columns = values.shape
    chars, keep = zip(*(column_text(values[:, j]) for j in range(columns)), _endings(after, rows))
    line_keep = np.concatenate(keep, axis=1)
    line_keep[:, line_keep.shape[1] - chars[-1].shape[1] - 1] = False     # no comma after the last number
    return np.concatenate(chars, axis=1)[line_keep].tobytes().decode("utf-8")


def _endings(after: list[str], rows: int):
    """(chars, keep) of each row's ending: after[i % len(after)] for row i, as UTF-8."""
    endings = [ending.encode("utf-8") for ending in after]
    width = max(map(len, endings))
    chars = np.zeros((len(endings), width), dtype=np.uint8)
    keep = np.zeros((len(endings), width), dtype=bool)
    for i, ending in enumerate(endings):
        chars[i, :len(ending)] = np.frombuffer(ending, dtype=np.uint8)
        keep[i, :len(ending)] = True
    label = np.arange(rows) % len(endings)
    return chars[label], keep[label]

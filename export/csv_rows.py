"""CSV rows a block at a time: the text csv.writer gives for clean()ed numbers, without a call per number.

A file number is clean(x) = float(f"{x:.15g}"), and csv.writer writes a float as repr, the shortest
text that reads back as the same double. A decimal of at most 15 significant digits reads back
exactly (a double holds 15 to 17), so repr(clean(x)) has the same digits as "%.15g" % x; the two
texts differ only where

* the value is a whole number below 10¹⁵: "%.15g" writes 3, repr 3.0 (0 and −0 are 0.0 and −0.0);
* its exponent is 15: "%.15g" writes 1.5e+15, repr 1500000000000000.0;
* the 15 digits overflow: "%.15g" writes 1.79769313486232e+308, which reads back as inf;
* the value is subnormal (below 2.2e-308) and holds fewer digits: 5e-324, not 4.94065645841247e-324.

So each block is formatted with one "%.15g" format string; zeros are written into the format as
text, and the few values that could be any of the other cases (picked by a generous test in numpy)
are written the old way, repr(clean(x)). tests/test_csv_rows.py compares the two writers byte for
byte.
"""
from __future__ import annotations

import csv
import io

import numpy as np

from .numbers import FILE_DIGITS

ROWS_PER_BLOCK = 4096
NUMBER = f"%.{FILE_DIGITS}g"


def csv_field(text: str) -> str:
    """One field as csv.writer writes it (quoted if it holds a comma, a quote or a line break)."""
    buffer = io.StringIO()
    csv.writer(buffer).writerow(["", text])
    return buffer.getvalue()[1:-2]


def _exact(x: float) -> str:
    """repr(clean(x)): what csv.writer writes for a cleaned number."""
    return repr(float(NUMBER % x))


def format_numbers(values: np.ndarray, *, after: list[str]) -> str:
    """Rows of cleaned numbers, comma-separated: values (rows, columns), after[i] the text that ends
    row i's line (",,,,\\r\\n", or a body label and "\\r\\n"); len(after) divides the rows and repeats.

    The same text as csv.writer.writerow([*map(clean, row)] + ...) for each row.
    """
    rows, columns = values.shape
    zero = values == 0
    negative_zero = zero & np.signbit(values)
    with np.errstate(invalid="ignore"):
        size = np.abs(values)
        # A superset of the values whose 15 digits make a whole number or an exponent ≥ 15:
        # clean(x) is within 5e-15 |x| of x, so a whole clean(x) has x within 1e-14 |x| of one.
        # Subnormal numbers (below 2.2e-308) hold fewer than 15 digits: they go the old way too.
        odd = ~zero & ((size >= 1e15) | (size < 1e-307) | (np.abs(values - np.rint(values)) <= size * 1e-14))
    # Each column of a row is a number (0), the text 0.0 (1), −0.0 (2) or a value written the old way (3).
    kind = np.where(odd, 3, np.where(negative_zero, 2, np.where(zero, 1, 0)))
    codes = (kind * (4 ** np.arange(columns))).sum(axis=1)
    labels = len(after)
    patterns = {}

    def pattern(code: int, ending: str) -> str:
        key = (code, ending)
        if key not in patterns:
            cells = [(NUMBER, "0.0", "-0.0", "%s")[(code >> (2 * j)) & 3] for j in range(columns)]
            patterns[key] = ",".join(cells) + ending.replace("%", "%%")
        return patterns[key]

    template = "".join(pattern(code, after[i % labels]) for i, code in enumerate(codes.tolist()))
    kept = ~zero
    arguments = values[kept].tolist()
    if odd.any():
        spots = np.flatnonzero(odd[kept])
        for spot in spots.tolist():
            arguments[spot] = _exact(arguments[spot])
    return template % tuple(arguments)

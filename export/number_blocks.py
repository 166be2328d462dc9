"""export/numbers.py's clean() for a whole block of numbers at once, bit for bit the same.

JSON output cleans every number to FILE_DIGITS significant digits; a run of 10⁴ masses has
hundreds of thousands of them, too many to format one by one. :func:`clean_array` finds the
digits by arithmetic instead of through text: for x with FILE_DIGITS digits before the point
after shifting by 10^s, the integer n = round(x·10^s) is the number's digits, and n / 10^s is
the double nearest to them, as float() of the text is (IEEE division rounds correctly, and
10^s is exact up to 10^22). The product x·10^s is rounded, but its error is recovered exactly
(Dekker's product), so a tie is decided as the exact value decides it, half to even as text
formatting does. Any element outside that range, or found too close to a power of ten, goes
through clean() itself.
"""
from __future__ import annotations

from itertools import chain
from typing import Optional

import numpy as np

from .numbers import FILE_DIGITS, clean

_POWERS = 10.0 ** np.arange(23)     # 1 … 1e22, each exact as a double
_SPLIT = 2.0 ** 27 + 1              # Veltkamp's splitter for doubles
_LOW, _HIGH = 10.0 ** (FILE_DIGITS - 1), 10.0 ** FILE_DIGITS   # n has FILE_DIGITS digits
SHORTEST_BLOCK = 32     # numbers: a shorter list is quicker one number at a time


def float_block(value) -> Optional[np.ndarray]:
    """A list of floats, or a list of equally long lists of floats, as one array; else None.

    Anything else (ints, None, strings, mixed or ragged lists), and a list of fewer than
    SHORTEST_BLOCK numbers, is left to be walked one item at a time.
    """
    if not isinstance(value, (list, tuple)) or not value:
        return None
    kinds = set(map(type, value))
    if kinds == {float}:
        return np.array(value, dtype=float) if len(value) >= SHORTEST_BLOCK else None
    if kinds <= {list, tuple} and len(set(map(len, value))) == 1 and len(value) * len(value[0]) >= SHORTEST_BLOCK \
            and set(map(type, chain.from_iterable(value))) == {float}:
        return np.array(value, dtype=float)
    return None


def clean_array(x) -> np.ndarray:
    """clean() of every element of x, as a new float array; inf, nan and zeros are kept as they are."""
    x = np.asarray(x, dtype=float)
    out = x.copy().reshape(-1)
    flat = x.reshape(-1)
    size = np.abs(flat)
    shift = np.zeros(flat.shape, dtype=int)
    inside = (size >= 1e-7) & (size < _HIGH)        # False for 0, inf and nan
    shift[inside] = FILE_DIGITS - 1 - np.floor(np.log10(size[inside])).astype(int)
    by_arithmetic = inside & (shift >= 0) & (shift < len(_POWERS))
    index = np.flatnonzero(by_arithmetic)
    digits, power = _digits(flat[index], _POWERS[shift[index]])
    found = (np.abs(digits) >= _LOW) & (np.abs(digits) <= _HIGH)
    out[index[found]] = digits[found] / power[found]
    rest = np.concatenate([np.flatnonzero(np.isfinite(flat) & (flat != 0) & ~by_arithmetic), index[~found]])
    out[rest] = [clean(value) for value in flat[rest].tolist()]
    return out.reshape(x.shape)


def _digits(x: np.ndarray, power: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """n = x·power rounded to the nearest integer, half to even, from the exact product; and power.

    y = fl(x·power) and the exact product is y + error (Dekker). y is rounded from the exact
    value, so it lies on the same side of any half-integer; only where y is one exactly does
    the error decide. Elements whose y falls outside [10^14, 10^15) give an n out of that range.
    """
    y = x * power
    error = product_error(x, power)
    n = np.rint(y)
    below = np.floor(y)
    half = (y - below) == 0.5
    n = np.where(half & (error > 0), below + 1, np.where(half & (error < 0), below, n))
    n = np.where((np.abs(y) >= _LOW) & (np.abs(y) < _HIGH), n, 0.0)   # 0: left to clean()
    return n, power


def product_error(a, b):
    """error, such that a·b = fl(a·b) + error exactly (Dekker's two-product, no FMA; also used
    by export/number_text.py)."""
    a_high, a_low = _split(a)
    b_high, b_low = _split(b)
    return ((a_high * b_high - a * b) + a_high * b_low + a_low * b_high) + a_low * b_low


def _split(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """a = high + low exactly, each with at most 26 significant bits (Veltkamp)."""
    c = _SPLIT * a
    high = c - (c - a)
    return high, a - high

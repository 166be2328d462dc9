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
_HALVES_EXACT = 2.0 ** 52           # below it, every half-integer is a double
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

    Elements whose x·power falls outside [10^14, 10^15) give an n out of that range.
    """
    y, n, _, _ = rounded_product(x, power)
    n = np.where((np.abs(y) >= _LOW) & (np.abs(y) < _HIGH), n, 0.0)   # 0: left to clean()
    return n, power


def rounded_product(x: np.ndarray, power, *, edges: tuple[float, ...] = ()):
    """(y, n, close, error): n = x·power rounded to the nearest whole number, ties to even, as
    the exact product decides (the one copy of this rounding: clean_array, rounded_times and
    export/number_text.py's digits use it). Needs |x·power| < 2^52, where halves are doubles.

    y = fl(x·power), and the exact product is y + error (Dekker). y is rounded from the exact
    value, so it lies on the same side of any half-integer; only where y is one exactly does the
    error decide. `close` indexes those elements, and those where y equals one of `edges`
    (numbers whose exact product may lie just beside y); `error` is the product's error there.
    """
    y = x * power
    n = np.rint(y)
    near = np.abs(y - n) == 0.5
    for edge in edges:
        near |= y == edge
    close = np.flatnonzero(near)
    error = product_error(x[close], power[close] if np.ndim(power) else power)
    if close.size:
        y_close, n_close = y[close], n[close]
        tie = np.abs(y_close - n_close) == 0.5
        n[close] = np.where(tie & (error > 0), np.ceil(y_close),
                            np.where(tie & (error < 0), np.floor(y_close), n_close))
    return y, n, close, error


def rounded_times(t: np.ndarray, decimals: int) -> np.ndarray:
    """round(t, decimals) of every element, bit for bit as Python's round (export/numbers.py's
    clean_time rounds a step time so): the whole number n nearest to t·10^decimals, ties to even
    on t's exact value, then n / 10^decimals, the double nearest to that decimal (IEEE division
    rounds correctly; n and 10^decimals are exact). Elements this cannot do exactly (|n| ≥ 2^52,
    more than 22 decimals, inf, nan) go through round() itself.
    """
    t = np.asarray(t, dtype=float)
    if not 0 <= decimals < len(_POWERS):
        return np.array([round(value, decimals) for value in t.tolist()], dtype=float)
    power = _POWERS[decimals]
    with np.errstate(invalid="ignore", over="ignore"):
        _, n, _, _ = rounded_product(t, power)
        out = n / power
        rest = np.flatnonzero(~(np.abs(t * power) < _HALVES_EXACT))
    out[rest] = [round(value, decimals) for value in t[rest].tolist()]
    return out


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

"""The text of many numbers at once, in numpy: repr(clean(x)), as csv.writer writes a file's number.

clean(x) = float("%.15g" % x) keeps FILE_DIGITS = 15 significant digits, and repr writes a double
with the fewest digits that read back as it. A decimal of at most 15 digits reads back exactly (a
double holds 15 to 17), so repr(clean(x)) is the 15 digits D of x, correctly rounded, written out
with its trailing zeros dropped: for 1e-4 ≤ |x| < 1e15 in fixed notation, with at least one digit
after the point (3.0, 0.5, 0.0001, 123.456).

In numpy, for x in that range:

    e  = the decimal exponent of x, so that y = |x|·10^(14−e) lies in [1e14, 1e15)
    y  = |x|·10^(14−e) exactly, as a rounded product plus its error (Dekker's two-product; 10^k
         is an exact double for k ≤ 22)
    D  = y rounded to the nearest whole number, ties to even (as C's printf rounds)
    text = the 15 digits of D placed around the point by e, leading and trailing zeros dropped

A zero is 0.0 or -0.0; every other number (below 1e-4, 1e15 and above, inf, NaN) is written by
Python, repr(clean(x)). The texts of a column of numbers are laid out side by side in a table of
characters as wide as that column needs, padded with a byte that UTF-8 never holds, so that a whole
block of a CSV file is one bytes.translate that deletes the padding. tests/test_csv_rows.py compares the text with
repr(clean(x)) on awkward and random numbers, and the files with csv.writer's.
"""
from __future__ import annotations

import functools

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from .number_blocks import rounded_product
from .numbers import clean

_FOUR_DIGITS = np.frombuffer("".join(f"{i:04d}" for i in range(10_000)).encode(), dtype=np.uint32)
_TRAILING_ZEROS = np.array([len(f"{i:04d}") - len(f"{i:04d}".rstrip("0")) for i in range(10_000)])
DROPPED = 0xFF               # marks a character that is not part of a text (never in UTF-8)
_E_LOW = 4                   # the smallest exponent written in fixed notation is -4
_POWERS = 10.0 ** np.arange(20)     # 10^0 … 10^19, each an exact double
_ZERO, _POINT, _MINUS, _COMMA = ord("0"), ord("."), ord("-"), ord(",")


def _rounded_digits(a):
    """(D, e, ok): |x| = a rounded to 15 significant digits, D·10^(e−14) with 1e14 ≤ D < 1e15."""
    with np.errstate(invalid="ignore"):
        ok = (a >= 1e-4) & (a < 1e15)
    a = np.where(ok, a, 1.0)                         # the others get a dummy, finite text
    e = np.clip(np.floor(np.log10(a)), -5, 14).astype(np.int64)
    scale = _POWERS[14 - e]                          # exact: 14 − e is 0 … 19
    # D: a·10^(14−e) rounded, ties to even; where y = fl(a·10^(14−e)) is on the edge of
    # [1e14, 1e15) the exact product's error says on which side a·10^(14−e) lies.
    y, D, close, error = rounded_product(a, scale, edges=(1e14, 1e15))
    inside = (y > 1e14) & (y < 1e15)                 # then a·scale is inside too: e is right
    y_close = y[close]
    inside[close] = (((y_close > 1e14) | ((y_close == 1e14) & (error >= 0))) &
                     ((y_close < 1e15) | ((y_close == 1e15) & (error < 0))))
    ok &= inside
    carried = D == 1e15                              # 9.999…95 rounds up to 10.0000…
    D = np.where(carried, 1e14, D)
    e = e + carried
    ok &= e <= 14
    return np.where(ok, D, 1e14).astype(np.int64), np.where(ok, e, 0), ok


def _groups(D):
    """Each D (15 digits) as four groups of four digits, the highest first (it starts with a 0)."""
    return np.stack([D // 10**12, D // 10**8 % 10**4, D // 10**4 % 10**4, D % 10**4], axis=1)


def _last_digit(groups):
    """Index (0 … 14) of the last non-zero digit of each D."""
    zeros = _TRAILING_ZEROS[groups[:, 0]] + 12
    for k in (1, 2, 3):
        zeros = np.where(groups[:, k] != 0, _TRAILING_ZEROS[groups[:, k]] + 4 * (3 - k), zeros)
    return 14 - zeros


@functools.lru_cache(maxsize=64)
def _dropped(top: int, decimals: int) -> np.ndarray:
    """DROPPED where a row's character is not part of its text, 0 where it is, for each exponent e
    and last non-zero digit `last` (row (e + 4)·15 + last): a text is the digits from the first (or
    from 10^0) to the last (or to 10^-1), the point and the comma; the sign is set for each number."""
    e, last = np.divmod(np.arange((15 + _E_LOW) * 15), 15)
    e = e[:, None] - _E_LOW
    integer = np.arange(top, -1, -1) <= np.maximum(e, 0)
    decimal = np.arange(decimals) <= np.maximum(last[:, None] - e - 1, 0)
    ends = np.ones((len(e), 1), dtype=bool)
    return np.where(np.concatenate([ends, integer, ends, decimal, ends], axis=1), 0, DROPPED).astype(np.uint8)


def _placed(groups, e, *, top: int, decimals: int) -> np.ndarray:
    """Each number's row: "-", its digits at the places 10^top … 10^0, ".", its digits at 10^-1 …
    10^-decimals, ","; '0' at every place it has no digit."""
    n = len(e)
    # The 15 digits with '0's either side; digit j (place e − j) goes to column top − e + j.
    left, right = top - int(e.min()), max(0, int((e + decimals).max()) - 14)
    padded = np.full((n, left + 15 + right), _ZERO, dtype=np.uint8)
    padded[:, left:left + 15] = _FOUR_DIGITS[groups].view(np.uint8).reshape(n, 16)[:, 1:]
    places = sliding_window_view(padded.reshape(-1), top + 1 + decimals)[
        np.arange(n) * padded.shape[1] + left - top + e]
    chars = np.empty((n, top + decimals + 4), dtype=np.uint8)
    chars[:, 0] = _MINUS
    chars[:, 1:top + 2] = places[:, :top + 1]
    chars[:, top + 2] = _POINT
    chars[:, top + 3:-1] = places[:, top + 1:]
    chars[:, -1] = _COMMA
    return chars


def column_text(x: np.ndarray):
    """The texts repr(clean(x)) + "," of a 1-D array of numbers, as UTF-8 in chars (n, W) uint8,
    each row padded with DROPPED, a byte that UTF-8 never holds.

    Each row is: the sign, the places 10^top … 10^0, the point, the places 10^-1 … 10^-decimals,
    the comma; top and decimals are the most this column's numbers need.
    """
    n = len(x)
    zero = x == 0
    if zero.all() and not np.signbit(x).any():
        return np.broadcast_to(np.frombuffer(b"0.0,", dtype=np.uint8), (n, 4))
    D, e, fast = _rounded_digits(np.abs(x))
    groups = _groups(D)
    last = _last_digit(groups)
    top = max(int(e.max()), 0)
    decimals = max(int((last - e).max()), 1)
    slow = np.flatnonzero(~(fast | zero))
    texts = [repr(clean(value)).encode("ascii") for value in x[slow].tolist()]
    top = max(top, max(map(len, texts), default=0) - 3)
    chars = _placed(groups, e, top=top, decimals=decimals)
    chars[zero, top + 1] = _ZERO                 # a zero got the dummy D = 1e14, e = 0: "1.0"
    chars |= _dropped(top, decimals)[(e + _E_LOW) * 15 + last]
    chars[:, 0] = np.where(np.signbit(x), _MINUS, DROPPED)
    for i, text in zip(slow.tolist(), texts):
        chars[i, :-1] = DROPPED
        chars[i, :len(text)] = np.frombuffer(text, dtype=np.uint8)
    return chars

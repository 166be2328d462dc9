"""--csv writes its rows a block at a time (export/csv_rows.py): the file must be byte for byte what
the row-by-row writer gave, csv.writer on clean()ed numbers, which is kept here as the reference."""
from __future__ import annotations

import csv
import dataclasses
import io
import math

import numpy as np
import pytest

from export.csv_rows import csv_field, format_numbers
from export.number_blocks import rounded_times
from export.numbers import CSV_HEADER, ENERGY_KEYS, clean, clean_time
from reports import csv_file, headless
from scenes import configure


def reference_rows(result) -> str:
    """The row writer --csv used before the block writer: one csv.writer row, one clean() per number."""
    handle = io.StringIO(newline="")
    traj = result.trajectory
    v = traj.v
    single = len(traj.m) == 1
    writer = csv.writer(handle)
    writer.writerow(CSV_HEADER + ([] if single else ["body"]))
    dt = result.model.dt
    for n, t in enumerate(traj.t):
        energy = [clean(traj.energy[key][n]) for key in ENERGY_KEYS] if traj.energy else [""] * 4
        for i, label in enumerate(result.labels):
            row = [clean_time(t, dt), *map(clean, traj.r[n, i]), *map(clean, v[n, i]), *map(clean, traj.p[n, i]),
                   *energy]
            writer.writerow(row + ([] if single else [label]))
    return handle.getvalue()


def block_rows(result) -> tuple[str, int]:
    handle = io.BytesIO()
    rows = csv_file._write_rows(result, handle.write)
    return handle.getvalue().decode("utf-8"), rows


RUNS = [
    ("vertical", ["until=3"]),                                  # one mass, energies, many exact zeros
    ("damped", ["until=2", "dt=0.005"]),
    ("driven", ["until=2"]),
    ("regimes", ["until=1"]),                                   # several masses: the body column
    ("integrators", ["until=1"]),
    ("resonance", ["count=7", "curves=2", "settle=0.5", "periods=1", "until=4"]),  # labels with commas
]


@pytest.mark.parametrize("scene, assignments", RUNS, ids=[name for name, _ in RUNS])
@pytest.mark.parametrize("energies", [True, False], ids=["energies", "no-energies"])
def test_block_writer_gives_the_row_writers_bytes(scene, assignments, energies):
    result = headless.simulate(configure(scene, assignments=assignments), progress=None)
    if not energies:
        result = dataclasses.replace(result, trajectory=dataclasses.replace(result.trajectory, forces=None))
    text, rows = block_rows(result)
    assert text == reference_rows(result)
    assert rows == len(result.trajectory.t) * len(result.trajectory.m) == text.count("\r\n") - 1


AWKWARD = [0.0, -0.0, 1.0, -3.0, 10.0, 1e14, 99999999999999.9, 1e15, 1.5e15, -1234567890123456.0, 9.999999999999999e14,
           1e16, 1.5e16, 1e-5, 1e-4, 0.0001234, 1.5e-7, -2.5e-300, 5e-324, 2.9999999999999996, 0.1 + 0.2,
           -7.800000000000001, 1.7976931348623157e308, -1.7976931348623157e308, 1.79769313486231e308,
           math.inf, -math.inf, math.nan, 123456.00000000001, 0.5, 1 / 3, 2 ** 53, 2.0 ** 60, -0.49999999999999994]


def test_awkward_numbers_are_written_as_csv_writes_their_clean_values():
    rng = np.random.default_rng(16)
    values = np.concatenate([AWKWARD,
                             rng.normal(size=2000) * 10.0 ** rng.integers(-20, 20, 2000),
                             rng.integers(-10**6, 10**6, 500).astype(float),
                             rng.integers(-10**6, 10**6, 500) + rng.choice([1e-15, -1e-14, 1e-12, 0.5], 500)])
    values = np.resize(values, (len(values) + 7) // 7 * 7).reshape(-1, 7)
    expected = io.StringIO(newline="")
    writer = csv.writer(expected)
    for i, row in enumerate(values):
        writer.writerow([clean(x) for x in row] + [["a,b", 'say "hi"', "%s %d"][i % 3]])
    after = ["," + csv_field(label) + "\r\n" for label in ["a,b", 'say "hi"', "%s %d"]]
    assert format_numbers(values, after=after) == expected.getvalue()


def _edges(rng) -> np.ndarray:
    """Numbers where the numpy digits could go wrong: exact ties at the 16th digit (k + ½ units of
    the 15th), neighbours of the powers of ten from 1e-5 to 1e16 (the exponent misjudged, 9.99…95
    carried to 10.0…), short decimals (trailing zeros dropped) and the values the brief names."""
    ties = (rng.integers(10**14, 10**15, 3000) * 10 + 5) / 2.0 ** rng.integers(1, 9, 3000)   # x.5 exactly
    ties = np.concatenate([ties, rng.integers(10**14, 10**15, 1000) + 0.5, rng.integers(10**13, 10**14, 1000) + 0.25])
    powers = 10.0 ** np.arange(-5, 17)
    near = np.concatenate([np.nextafter(powers, 0), powers, np.nextafter(powers, np.inf),
                           powers * (1 - 5e-16), powers * (1 + 5e-16), powers * 0.99999999999999995,
                           powers * 9.999999999999995, powers * 9.99999999999995])
    short = np.array([round(x, int(d)) for x, d in zip(rng.normal(size=3000) * 10.0 ** rng.integers(-3, 6, 3000),
                                                        rng.integers(0, 9, 3000))])
    named = [0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300, 0.1 + 0.2, 1e-4, -1e-4, 0.00010000000000000002,
             99999999999999.95, 999999999999999.4, 999999999999999.5, 999999999999999.6, 12345678901234.5]
    values = np.concatenate([ties, -ties, near, -near, short, named])
    return np.concatenate([values, rng.normal(size=20000) * 10.0 ** rng.integers(-8, 18, 20000)])


def test_numpy_digits_are_the_row_writers_at_the_edges():
    """format_numbers works out the digits in numpy (export/number_text.py): on numbers chosen to
    catch a wrong rounding or a wrong exponent, each text is csv.writer's text of clean(x)."""
    values = _edges(np.random.default_rng(7))
    values = np.resize(values, (len(values) + 4) // 5 * 5).reshape(-1, 5)
    values[:, 4] = np.where(np.arange(len(values)) % 2, -0.0, 0.0)      # a column of zeros of both signs
    expected = io.StringIO(newline="")
    writer = csv.writer(expected)
    for row in values:
        writer.writerow([clean(x) for x in row] + ["ω = 2 rad/s"])
    assert format_numbers(values, after=[",ω = 2 rad/s\r\n"]) == expected.getvalue()


def _same_bits(a, b) -> bool:
    return np.array_equal(np.asarray(a, dtype=float).view(np.int64), np.asarray(b, dtype=float).view(np.int64))


def _awkward_times(rng, decimals: int) -> np.ndarray:
    """Times where round(t, decimals) is easy to get wrong: halfway decimals (k + ½)·10^-decimals,
    which as doubles lie a hair above or below the half (or on it, for k/2^j), their neighbours,
    exact binary ties, n·Δt for Δt that is not a short decimal, negatives, ±0 and numbers too big
    for the arithmetic (left to round())."""
    k = np.concatenate([np.arange(-3000, 3000), rng.integers(-10**9, 10**9, 3000)]).astype(float)
    halves = (k + 0.5) / 10.0 ** decimals
    binary = rng.integers(-10**6, 10**6, 3000) / 2.0 ** rng.integers(1, 12, 3000)
    steps = np.arange(0, 30000) * np.array([0.1, 0.003, 1e-4, 0.0123456789, 0.333333333, 1 / 3])[:, None]
    named = [0.0, -0.0, 0.285, 2.675, 1.005, -0.125, 0.375, 1e15, 2.0 ** 52 / 10 ** decimals, 2.0 ** 60, -1e300, 5e-324]
    return np.concatenate([halves, np.nextafter(halves, np.inf), np.nextafter(halves, -np.inf), binary,
                           steps.ravel(), named, rng.normal(size=5000) * 10.0 ** rng.integers(-6, 16, 5000)])


@pytest.mark.parametrize("decimals", [0, 1, 2, 3, 4, 9, 10, 15, 22, 23])
def test_rounded_times_are_pythons_round_bit_for_bit(decimals):
    """The CSV's t column is round(t, Δt's decimals) worked out in numpy (export/number_blocks.py):
    each value has the bits of Python's round, ties and near-ties included."""
    times = _awkward_times(np.random.default_rng(decimals), decimals)
    expected = [round(t, decimals) for t in times.tolist()]
    assert _same_bits(rounded_times(times, decimals), expected)
    assert _same_bits(rounded_times(np.array([np.inf, -np.inf]), decimals), [np.inf, -np.inf])
    assert np.isnan(rounded_times(np.array([np.nan]), decimals)).all()


def test_rounded_times_need_the_exact_product_at_halfway_decimals():
    """The case the exact product is there for: t·10^d, rounded to a double, is exactly a half
    while t itself lies below or above it (0.285 is 0.28499999999999998…, 0.285·100 gives 28.5),
    so rounding the product alone (np.rint) is wrong for some of these, and rounded_times is not."""
    times = (np.arange(0, 10000) + 0.5) / 100
    naive = np.rint(times * 100) / 100
    expected = np.array([round(t, 2) for t in times.tolist()])
    assert (naive != expected).sum() > 1000
    assert _same_bits(rounded_times(times, 2), expected)
    assert rounded_times(np.array([0.285, 2.675, 0.125, 0.375, -0.125]), 2).tolist() == [0.28, 2.67, 0.12, 0.38, -0.12]

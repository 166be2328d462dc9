"""One palette for the page and for `--plot` (export/palette.py), and curves that stay apart.

The page's graphs are checked in a browser (tests/test_classroom_page.py); here the figure that
`--plot` writes is checked by its pixels: each mass in the page's colour, never matplotlib's own.
"""
import subprocess
import sys
from pathlib import Path

import pytest

from export.palette import MASS_COLOURS, simulation_width

ROOT = Path(__file__).resolve().parent.parent
MATPLOTLIB_DEFAULTS = [(31, 119, 180), (255, 127, 14)]   # its first two colours, blue then orange


def rgb(colour) -> tuple[int, int, int]:
    return tuple(round(255 * c) for c in colour)


def test_the_palette_imports_neither_vpython_nor_matplotlib():
    code = ("import sys, export.palette\n"
            "print(sorted(m for m in ('vpython', 'matplotlib') if m in sys.modules))")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.stdout.strip() == "[]", done.stderr


def test_curves_of_two_or_three_masses_have_different_widths_the_first_widest():
    for count in (2, 3):
        widths = [simulation_width(i, count) for i in range(count)]
        assert all(a >= b + 4 for a, b in zip(widths, widths[1:])), widths  # 2 px of border each side


def test_the_plot_draws_each_mass_in_the_page_colour(tmp_path):
    pytest.importorskip("matplotlib")
    Image = pytest.importorskip("PIL.Image")
    from browser_support import pixels_like

    path = tmp_path / "drag.png"
    done = subprocess.run([sys.executable, "main.py", "drag", "--headless", "--plot", str(path), "--until", "8"],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    image = Image.open(path).convert("RGB")
    first, second = rgb(MASS_COLOURS[0]), rgb(MASS_COLOURS[1])   # orange, blue: as on the page
    assert pixels_like(image, first, within=30) > 500
    assert pixels_like(image, second, within=30) > 500
    for colour in MATPLOTLIB_DEFAULTS:
        assert pixels_like(image, colour, within=12) < 50, f"a curve in matplotlib's own colour {colour}"

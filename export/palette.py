"""One palette for everything the class sees: the page (browser/) and `--plot` (reports/plotting.py).

Colours are (r, g, b) from 0 to 1, as both vpython and matplotlib take them. This module imports
neither, so the command line can use it without a browser and the page without matplotlib.

How curves stay apart on a projector:

* mass i has colour MASS_COLOURS[i] in the 3-D view and in every graph;
* the simulation is a thick line in the mass's colour, and the exact solution a thin dark line drawn
  on top of it: where the two agree the thin line runs inside the thick one and both show;
* several masses whose curves may coincide (the two balls of `drag` at first) get lines of
  different widths, the first widest, so one shows as a border round the other.
"""
from __future__ import annotations

MASS_COLOURS = [(1.0, 0.55, 0.1), (0.25, 0.65, 1.0), (0.3, 0.85, 0.35), (0.95, 0.35, 0.6),
                (0.8, 0.75, 0.2), (0.65, 0.45, 0.95)]      # orange, blue, green, pink, yellow, purple
EXACT_COLOUR = (0.1, 0.1, 0.1)                              # near black
ENERGY_COLOURS = {"K": (0.85, 0.1, 0.1), "U": (0.1, 0.3, 0.9), "E": (0.0, 0.0, 0.0),
                  "E_minus_W_nc": (0.1, 0.6, 0.1)}          # red, blue, black, green
ENERGY_LABELS = {"K": "K", "U": "U", "E": "E = K + U", "E_minus_W_nc": "E − W_nc"}

EXACT_WIDTH = 1            # px: the exact solution, thin, on top
SIMULATION_WIDTH = 6       # px: the last (or only) mass's simulated curve
WIDTH_STEP = 4             # px: each earlier mass's curve is this much wider (2 px of border each side)
MAX_WIDTH = 14             # px: the widest curve
CROWDED_WIDTH = 2          # px: every curve of a long row of masses (they do not overlap)


def mass_colour(i: int) -> tuple[float, float, float]:
    """The colour of mass i (the palette repeats after six masses)."""
    return MASS_COLOURS[i % len(MASS_COLOURS)]


def shade(colour, rank: int) -> tuple[float, float, float]:
    """The colour, darker for the second and third coordinate of one mass (x, y, z in `pendulum`)."""
    factor = 1.0 - 0.3 * rank
    return tuple(c * factor for c in colour)


def simulation_width(i: int, count: int, *, crowded: bool = False) -> float:
    """Width, px, of mass i's simulated curve among `count`: wider for earlier masses."""
    if crowded:
        return CROWDED_WIDTH
    return min(SIMULATION_WIDTH + WIDTH_STEP * (count - 1 - i), MAX_WIDTH)

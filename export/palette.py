"""One palette for everything the class sees: the page (browser/) and `--plot` (reports/plotting.py).

Colours are (r, g, b) from 0 to 1, as both vpython and matplotlib take them. This module imports
neither, so the command line can use it without a browser and the page without matplotlib.

How curves stay apart on a projector:

* mass i has colour MASS_COLOURS[i] in the 3-D view and in every graph; where a scene groups its
  masses in rows, one row per curve of its own graph (resonance: a row of springs per b), each
  mass has its row's curve colour instead (mass_colours), so "the blue row" is the blue line;
* the simulation is a thick line in the mass's colour, and the exact solution a thin dark line drawn
  on top of it: where the two agree the thin line runs inside the thick one and both show;
* several masses whose curves may coincide (the two balls of `drag` at first, the four methods of
  `integrators`) get lines of different widths, the first widest, so each shows as a border round
  the next;
* no curve is told from another by its colour alone (WCAG 2.1's 1.4.1): each colour a graph line
  can have draws its own dash pattern (LINE_DASHES), the same on both pages, in `--plot` and in the
  legends, so any two curves of one graph differ by dash or width as well as by colour;
* every line is at least 3:1 against the white graphs and the dark 3-D view (WCAG 1.4.11).
"""
from __future__ import annotations

# The Okabe–Ito palette (Okabe and Ito, "Color Universal Design", 2008): eight colours chosen so that
# people with any of the common colour-vision deficiencies tell them apart. tests/test_palette.py
# checks it under simulated deuteranopia and protanopia, and each line's contrast.
# Its orange (0.902, 0.624, 0) and sky blue (0.337, 0.706, 0.914) are 2.25:1 and 2.31:1 on a white
# graph, below WCAG's 3:1 for a line; here they are deepened, hue kept, to 3.3:1 on white and 4.9:1
# on the dark 3-D view (browser/scene3d.py BACKGROUND), so one colour per mass serves both.
ORANGE, SKY_BLUE, BLUISH_GREEN = (0.76, 0.5, 0.0), (0.0, 0.58, 0.9), (0.0, 0.620, 0.451)
YELLOW, BLUE, VERMILION = (0.941, 0.894, 0.259), (0.0, 0.447, 0.698), (0.835, 0.369, 0.0)
REDDISH_PURPLE, BLACK = (0.800, 0.475, 0.655), (0.0, 0.0, 0.0)
OKABE_ITO = [ORANGE, SKY_BLUE, BLUISH_GREEN, YELLOW, BLUE, VERMILION, REDDISH_PURPLE, BLACK]
ROYAL_BLUE = (0.36, 0.38, 1.0)   # not Okabe–Ito's: a sixth mass colour 29 ΔE from the others for any vision
GREY = (0.5, 0.5, 0.5)

# Yellow is left out of the masses and curves: on a white graph it barely shows from the back row.
# Vermilion is left out of the masses: the deepened orange and it look alike to a deuteranope.
MASS_COLOURS = [ORANGE, SKY_BLUE, BLUISH_GREEN, REDDISH_PURPLE, BLUE, ROYAL_BLUE]
CURVE_COLOURS = [BLUE, VERMILION, BLUISH_GREEN, REDDISH_PURPLE, GREY]
                                                            # blue, vermilion, green, purple, grey: a family of
                                                            # curves, such as resonance's A(ω) per b
LIVE_COLOUR = MASS_COLOURS[0]                               # a scene graph's dots that follow the run
                                                            # (resonance's springs now): orange, no curve's
EXACT_COLOUR = (0.1, 0.1, 0.1)                              # near black
ENERGY_COLOURS = {"K": VERMILION, "U": BLUE, "E": BLACK,
                  "E_minus_W_nc": BLUISH_GREEN}             # vermilion, blue, black, green
ENERGY_LABELS = {"K": "K", "U": "U", "E": "E = K + U", "E_minus_W_nc": "E − W_nc"}
# x, y and z of one mass (pendulum): the mass's own colour, then these, so the three never look alike
AXIS_COLOURS = [BLUE, REDDISH_PURPLE, BLUISH_GREEN, VERMILION]

EXACT_WIDTH = 1            # px: the exact solution, thin, on top
SIMULATION_WIDTH = 6       # px: the last (or only) mass's simulated curve
WIDTH_STEP = 4             # px: each earlier mass's curve is this much wider (2 px of border each side)
MAX_WIDTH = 14             # px: the widest curve (more than three masses share it in smaller steps)
CROWDED_WIDTH = 2          # px: every curve of a long row of masses (they do not overlap)


# Dash patterns, in units of the line's width (at least DASH_UNIT[0], at most DASH_UNIT[1] px, so a
# thin line's dots show and a thick curve's dashes stay short enough to follow a swing): on, off, ...
SOLID, DASHED, DOTTED, DASH_DOT = (), (4, 2), (1, 2), (6, 2, 1, 2)
DASH_DOT_DOT, LONG_SHORT, DASH_DASH, LONG_DASH = (6, 2, 1, 2, 1, 2), (8, 2, 3, 2), (3, 1.5, 3, 4), (10, 3)
DASH_UNIT = (2.0, 4.0)     # px
# Each colour a graph line can have, and its dash: the first mass, E and the exact solution solid
# (they never share a graph but by width: the exact curve is thin); colours that share a graph (the
# masses, the energies, a family of curves, a mass's x, y and z) all draw differently, and the two
# blues of the masses most differently (dashes; long and short).
LINE_DASHES = {ORANGE: SOLID, BLACK: SOLID, EXACT_COLOUR: SOLID, SKY_BLUE: DASHED, BLUISH_GREEN: DOTTED,
               REDDISH_PURPLE: DASH_DOT, BLUE: LONG_SHORT, VERMILION: DASH_DOT_DOT, ROYAL_BLUE: DASH_DASH,
               GREY: LONG_DASH}


def line_dashes(colour, width: float) -> tuple[float, ...]:
    """The dash pattern, px (on, off, ...; () for a solid line), of a graph line of this colour and
    width, px: LINE_DASHES's pattern in units of the width, kept within DASH_UNIT."""
    unit = min(max(float(width), DASH_UNIT[0]), DASH_UNIT[1])
    return tuple(unit * length for length in LINE_DASHES.get(tuple(colour), SOLID))


def line_styles() -> list[dict]:
    """LINE_DASHES for the pages' script (export/page_access.js): each colour as 0–255 and its
    pattern in units, with DASH_UNIT, as it draws every graph line and legend sample."""
    return [{"rgb": [int(255 * c) for c in colour], "dashes": list(dashes)} for colour, dashes in LINE_DASHES.items()]


def mass_colour(i: int) -> tuple[float, float, float]:
    """The colour of mass i (the palette repeats after six masses)."""
    return MASS_COLOURS[i % len(MASS_COLOURS)]


def curve_colour(j: int) -> tuple[float, float, float]:
    """The colour of curve j of a family (the palette repeats after five curves)."""
    return CURVE_COLOURS[j % len(CURVE_COLOURS)]


def mass_colours(model, view: dict) -> list[tuple[float, float, float]]:
    """The colour of each mass of a model: its sphere, its trail and its curves, on the page and in --plot.

    Mass i has mass_colour(i), unless the scene's VIEW names "rows": a function of the model giving
    each mass's row, one row per curve of the scene's own graph. Then every mass of row j has that
    curve's colour, curve_colour(j): in `resonance` the springs of the row with b = 0.5 kg/s are
    blue, as is the line of b = 0.5 kg/s on the amplitude graph.
    """
    rows = view.get("rows")
    if rows is None:
        return [mass_colour(i) for i in range(model.state.count)]
    return [curve_colour(int(j)) for j in rows(model)]


def shade(colour, rank: int) -> tuple[float, float, float]:
    """The colour of coordinate `rank` of a mass whose colour is `colour` (x, y, z in `pendulum`):
    the mass's own for the first, then the first AXIS_COLOURS that is not the mass's own, so the
    curves of x, y and z have three different Okabe–Ito hues, not three shades of one."""
    if rank == 0:
        return tuple(colour)
    others = [c for c in AXIS_COLOURS if c != tuple(colour)]
    return others[(rank - 1) % len(others)]


def energy_label(key: str, *, from_rest: bool = False) -> str:
    """The legend of energy curve `key` (K, U, E, E_minus_W_nc); from_rest: measured from rest at
    equilibrium, so every energy but K has U_rest taken off."""
    return ENERGY_LABELS[key] + (" − U_rest" if from_rest and key != "K" else "")


def simulation_width(i: int, count: int, *, crowded: bool = False) -> float:
    """Width, px, of mass i's simulated curve among `count`: wider for earlier masses, never wider
    than MAX_WIDTH, so with four or more masses the step between neighbours is less than WIDTH_STEP
    (four masses: 14, 11.3, 8.7 and 6 px)."""
    if crowded:
        return CROWDED_WIDTH
    step = min(WIDTH_STEP, (MAX_WIDTH - SIMULATION_WIDTH) / max(count - 1, 1))
    return SIMULATION_WIDTH + step * (count - 1 - i)


# The momentum update's arrows (export/arrows.py), on the page and in the handed-out program: yellow
# and reddish purple, told apart with any colour vision and from every mass colour on the dark page.
ARROW_COLOURS = {"p": (0.95, 0.88, 0.2),           # yellow: momentum p (p_f in a Step)
                 "p_i": (0.6, 0.55, 0.12),         # dark yellow: p_i, before the Step
                 "F_net": (0.9, 0.4, 0.75),        # reddish purple: F_net, and F_net Δt in a Step
                 "forces": (0.75, 0.75, 0.78),     # light grey: each force on its own arrow, labelled
                 "F_par": (0.35, 0.75, 1.0),       # sky blue: F∥, along p, changes the speed
                 "F_perp": (1.0, 1.0, 1.0)}        # white: F⊥, across p, changes the direction

"""One palette for the page and for `--plot` (export/palette.py), and curves that stay apart.

The page's graphs are checked in a browser (tests/test_classroom_page.py); here the figure that
`--plot` writes is checked by its pixels: each mass in the page's colour, never matplotlib's own.
"""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from export.palette import (CURVE_COLOURS, LIVE_COLOUR, MASS_COLOURS, MAX_WIDTH, SIMULATION_WIDTH, mass_colours,
                            simulation_width)

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


# ---- issue 12, "What the class sees": what --plot draws, as the page draws it ----

def figure_of(scene: str, tmp_path, monkeypatch):
    """The figure `--plot` draws for a scene's default run, its matplotlib objects kept for looking at."""
    pytest.importorskip("matplotlib")
    import matplotlib.figure

    from reports import headless, plotting
    from scenes import catalog

    figures = []
    save = matplotlib.figure.Figure.savefig
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig",
                        lambda self, *a, **k: figures.append(self) or save(self, *a, **k))
    plotting.plot(headless.simulate(catalog.configure(scene), progress=None), str(tmp_path / f"{scene}.png"))
    (figure,) = figures
    return figure


def energy_axes(figure):
    (ax,) = [ax for ax in figure.axes if ax.get_ylabel() == "energy (J)"]
    return ax


def test_the_plot_measures_resonance_energy_from_rest_at_equilibrium_as_the_page_does(tmp_path, monkeypatch):
    """Not −450 J of m g h with the swing's few joules lost in it: U − U_rest starts at 0."""
    ax = energy_axes(figure_of("resonance", tmp_path, monkeypatch))
    lines = {line.get_label(): np.asarray(line.get_ydata()) for line in ax.lines}
    assert set(lines) == {"K", "U − U_rest", "E = K + U − U_rest", "E − W_nc − U_rest"}
    assert lines["U − U_rest"][0] == pytest.approx(0.0, abs=1e-9)
    assert lines["E − W_nc − U_rest"] == pytest.approx(0.0, abs=0.01)    # the energy principle
    low, high = ax.get_ylim()
    assert -1.0 < low < 0.0 and 1.0 < high < 20.0                         # a few joules, not hundreds
    assert 1.0 < lines["E = K + U − U_rest"].max() < high


def test_the_plot_fits_the_energy_axis_to_the_methods_that_do_not_run_away(tmp_path, monkeypatch):
    """integrators: euler's energy grows to 21 J; the axis shows the others' 0.3 J and euler leaves it."""
    from physics.stability import growing
    from scenes import catalog

    model = catalog.configure("integrators").build()
    runs_away = growing(model.forces, model.state.m, model.methods(), model.dt)
    assert [name for name, grows in zip(model.labels, runs_away) if grows] == ["euler"]
    ax = energy_axes(figure_of("integrators", tmp_path, monkeypatch))
    low, high = ax.get_ylim()
    assert high < 1.0
    for line in ax.lines:
        E = np.asarray(line.get_ydata())
        if line.get_label().startswith("euler:"):
            assert E.max() > 10 * high and "runs off the graph" in line.get_label()
        else:
            assert low < E.min() and E.max() < high, line.get_label()
            if line.get_label().startswith("euler-cromer:"):                 # its wobble fills the graph
                assert E.max() - E.min() > 0.5 * (high - low)


def test_the_plot_draws_the_exact_resonance_curve_smooth(tmp_path, monkeypatch):
    """A(ω) on hundreds of ω, not a polyline through the 13 springs' frequencies."""
    from physics.exact import steady_state_amplitude
    from scenes import catalog

    v = catalog.configure("resonance").values
    (ax,) = [ax for ax in energy_axes(figure_of("resonance", tmp_path, monkeypatch)).figure.axes
             if ax.get_ylabel() == "amplitude (m)"]
    exact = [line for line in ax.lines if line.get_label().startswith("exact")]
    assert len(exact) == v["curves"]
    for line in exact:
        omega, A = (np.asarray(a) for a in line.get_data())
        assert len(omega) >= 20 * v["count"]
        assert omega[0] == v["omega_min"] and omega[-1] == v["omega_max"]
        b = float(line.get_label().split("b = ")[1].split()[0])
        assert A == pytest.approx(steady_state_amplitude(m=v["m"], k=v["k"], b=b, F0=v["F0"], omega=omega))


def test_the_plot_draws_each_resonance_b_in_the_page_colour(tmp_path):
    """b = 1 kg/s was matplotlib's orange in --plot and red on the page: now each b has CURVE_COLOURS[j]
    in the amplitude panel and its row of springs in the position panel, and no curve is matplotlib's."""
    pytest.importorskip("matplotlib")
    Image = pytest.importorskip("PIL.Image")
    from browser_support import pixels_like

    path = tmp_path / "resonance.png"
    done = subprocess.run([sys.executable, "main.py", "resonance", "--plot", str(path)],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    image = Image.open(path).convert("RGB")
    for colour in CURVE_COLOURS[:3]:                     # blue, red, green: b = 0.5, 1 and 2 kg/s
        assert pixels_like(image, rgb(colour), within=30) > 2000, colour
    for colour in MATPLOTLIB_DEFAULTS + [rgb(c) for c in MASS_COLOURS[:2]]:
        # a curve drawn in one of these would have thousands of pixels, as the b curves have; a few
        # hundred come from the blended edges of the Okabe–Ito blue, 38 away from matplotlib's
        assert pixels_like(image, colour, within=12) < 400, f"a curve in colour {colour}"


def resonance_page():
    """The resonance page's 3-D view and graphs, drawn with a stand-in for vpython (no browser)."""
    from browser.graphs import Graphs
    from browser.scene3d import Scene3D
    from browser.view import DEFAULT_VIEW
    from scenes import catalog
    from test_trail import stand_in_vpython

    vp = stand_in_vpython()
    setup = catalog.configure("resonance")
    model = setup.build()
    view = {**DEFAULT_VIEW, **setup.module.VIEW}
    return setup, model, Scene3D(vp, model=model, view=view, title="resonance"), Graphs(vp, setup=setup,
                                                                                        model=model, view=view)


def test_each_row_of_resonance_springs_has_the_colour_of_its_b_line():
    """On the page, the springs with b = 0.5 kg/s are blue, as the b = 0.5 kg/s line of the
    amplitude graph and their curves on the position graph: a teacher can point at the blue row."""
    setup, model, scene, graphs = resonance_page()
    line_colour = {series.label: tuple(series.color) for series in graphs.scene_series}
    assert sorted(line_colour.values()) == sorted(CURVE_COLOURS[:3])
    positions = {curve.series.mass: curve.line.color for curve in graphs.curves if curve.series.kind == "position"}
    b = model.forces[1].b.ravel()
    assert len(scene.masses) == len(b) == 39
    assert len(positions) == 3                                # one chosen spring per row (issue 18)
    for i, (sphere, b_i) in enumerate(zip(scene.masses, b)):
        colour = line_colour[f"b = {b_i:.3g} kg/s"]
        assert tuple(sphere.color) == colour and tuple(positions.get(i, colour)) == colour
    assert tuple(graphs.live_dots.color) == LIVE_COLOUR      # the springs now: orange, no b's colour
    assert LIVE_COLOUR not in CURVE_COLOURS


def test_masses_not_in_rows_keep_their_own_colours():
    from browser.view import DEFAULT_VIEW
    from scenes import catalog

    setup = catalog.configure("integrators")
    colours = mass_colours(setup.build(), {**DEFAULT_VIEW, **setup.module.VIEW})
    assert colours == MASS_COLOURS[:4]


def test_four_masses_have_four_widths_that_a_projector_shows_apart():
    """integrators' euler and euler-cromer were both 14 px: where they coincide only one showed."""
    for count in (2, 3, 4):
        widths = [simulation_width(i, count) for i in range(count)]
        assert all(a >= b + 2 for a, b in zip(widths, widths[1:])), widths   # ≥ 1 px of border each side
        assert widths[0] <= MAX_WIDTH and widths[-1] == SIMULATION_WIDTH
    for count in (5, 6):
        widths = [simulation_width(i, count) for i in range(count)]
        assert all(a > b for a, b in zip(widths, widths[1:])) and widths[0] <= MAX_WIDTH, widths


# ---- issue 18, "A page a class can read": colours a colour-blind student tells apart ----

# Machado, Oliveira and Fernandes (2009), "A physiologically-based model for simulation of color vision
# deficiency", severity 1.0: the matrices act on linear RGB.
PROTANOPIA = np.array([[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216],
                       [-0.003882, -0.048116, 1.051998]])
DEUTERANOPIA = np.array([[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413],
                         [-0.011820, 0.042940, 0.968881]])
DISTINCT = 15.0   # ΔE*ab (CIE76): 2.3 is just noticeable side by side; 15 is two colours named apart


def lab(rgb) -> np.ndarray:
    """CIE L*a*b* (D65 white) of a linear-RGB colour (sRGB primaries), each channel clipped to [0, 1]."""
    to_xyz = np.array([[0.4124564, 0.3575761, 0.1804375], [0.2126729, 0.7151522, 0.0721750],
                       [0.0193339, 0.1191920, 0.9503041]])
    xyz = to_xyz @ np.clip(rgb, 0.0, 1.0) / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > (6 / 29) ** 3, np.cbrt(xyz), xyz / (3 * (6 / 29) ** 2) + 4 / 29)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def linear(colour) -> np.ndarray:
    """sRGB (0 to 1) to linear RGB."""
    c = np.asarray(colour, dtype=float)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def closest_pair(colours, vision) -> tuple[float, tuple, tuple]:
    """The smallest CIE76 ΔE*ab between two of the colours as seen with `vision` (a Machado matrix)."""
    seen = [lab(vision @ linear(c)) for c in colours]
    return min((float(np.linalg.norm(seen[i] - seen[j])), colours[i], colours[j])
               for i in range(len(colours)) for j in range(i + 1, len(colours)))


@pytest.mark.parametrize("vision", [PROTANOPIA, DEUTERANOPIA, np.eye(3)], ids=["protanopia", "deuteranopia", "normal"])
def test_any_two_colours_stay_apart_for_a_colour_blind_student(vision):
    """Any two mass colours, any two curves of a family (resonance's b), the energy curves and a
    mass's x, y, z curves (pendulum) differ by at least DISTINCT = 15 in CIE76 ΔE*ab after
    simulating protanopia or deuteranopia with Machado et al.'s (2009) matrices at full severity
    (and with normal vision). The palette before issue 18 had its sky blue and purple 4.8 apart
    under deuteranopia."""
    from export.palette import AXIS_COLOURS, ENERGY_COLOURS, shade

    families = {"masses": MASS_COLOURS, "curves": CURVE_COLOURS[:4], "energy": list(ENERGY_COLOURS.values()),
                "x, y, z": [shade(MASS_COLOURS[0], rank) for rank in range(3)]}
    for name, colours in families.items():
        distance, a, b = closest_pair(colours, vision)
        assert distance >= DISTINCT, f"{name}: {a} and {b} only ΔE = {distance:.1f} apart"
    assert all(len(set(family)) == len(family) for family in families.values())
    assert len(AXIS_COLOURS) >= 2


def test_the_simulation_of_colour_blindness_merges_red_and_green():
    """The check above can fail: a pure red and a green of the same lightness, far apart to normal
    eyes, come within DISTINCT of each other under deuteranopia."""
    red, green = (0.8, 0.3, 0.1), (0.45, 0.45, 0.1)
    assert closest_pair([red, green], np.eye(3))[0] > 2 * DISTINCT
    assert closest_pair([red, green], DEUTERANOPIA)[0] < DISTINCT


def contrast(a, b) -> float:
    """WCAG 2.1's contrast ratio of two colours (0–1 RGB)."""
    def luminance(colour):
        lin = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in colour]
        return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]
    high, low = sorted((luminance(a), luminance(b)), reverse=True)
    return (high + 0.05) / (low + 0.05)


def test_every_line_colour_is_3_to_1_on_the_white_graphs_and_masses_on_the_dark_view():
    """WCAG 1.4.11: a graph line is at least 3:1 against the white graph; a mass's colour (its ball,
    trail and arrows) against the 3-D view's dark background too."""
    from browser.scene3d import BACKGROUND
    from export.palette import ENERGY_COLOURS, EXACT_COLOUR

    white = (1.0, 1.0, 1.0)
    for colour in [*MASS_COLOURS, *CURVE_COLOURS, *ENERGY_COLOURS.values(), EXACT_COLOUR]:
        assert contrast(colour, white) >= 3.0, (colour, contrast(colour, white))
    for colour in MASS_COLOURS:
        assert contrast(colour, BACKGROUND) >= 3.0, (colour, contrast(colour, BACKGROUND))
    assert contrast((0.902, 0.624, 0.0), white) < 3.0   # Okabe–Ito's own orange: why it is deepened


def test_curves_that_share_a_graph_differ_by_dash_not_only_by_colour():
    """WCAG 1.4.1: the masses' colours, the energies' and a family of curves each draw a dash
    pattern of their own (export/palette.py LINE_DASHES), the same at every width."""
    from export.palette import ENERGY_COLOURS, LINE_DASHES, line_dashes

    for family in (MASS_COLOURS, list(ENERGY_COLOURS.values()), CURVE_COLOURS):
        patterns = [LINE_DASHES[tuple(c)] for c in family]
        assert len(set(patterns)) == len(patterns), family
    assert line_dashes(MASS_COLOURS[1], 1.0) == tuple(2.0 * n for n in LINE_DASHES[MASS_COLOURS[1]])   # floor 2 px
    assert line_dashes(MASS_COLOURS[1], 14.0) == tuple(4.0 * n for n in LINE_DASHES[MASS_COLOURS[1]])  # cap 4 px

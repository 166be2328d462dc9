"""A static figure of a headless run (`python main.py SCENE --headless --plot FILE.png`).

Two graphs, like the page's: position against time for each mass (the iteration thick, the exact
solution thin and dark on top where a closed form exists), and energy against time, K, U, E and
E − W_nc. Each line has its colour's dash pattern, as on the page (export/palette.py's LINE_DASHES).
E − W_nc staying flat is the energy principle; how flat it stays shows the integrator's accuracy.
As on the page, the energies of a system that starts at rest at equilibrium are measured from
there, and the energy axis is fitted to the masses not expected to run away. A scene with its own
graph (resonance) gets a third panel. Every colour is the page's (export/palette.py).

matplotlib is an optional extra: it is imported only here, only when a figure is asked for, and
with the Agg backend so no window is needed.
"""
from __future__ import annotations

import logging
import os
import shutil
import sys

import numpy as np

from export.files import OutputError, atomic_file, figure_mark
from export.palette import (ENERGY_COLOURS, EXACT_COLOUR, curve_colour, energy_label, line_dashes, mass_colours,
                            shade, simulation_width)
from physics.energy import kinetic, potential, rest_potential
from physics.state import State

POINTS_PER_PX = 0.75 # matplotlib widths are in points: the page's px widths, scaled to this figure


class MissingMatplotlib(OutputError):
    """matplotlib is not installed."""

    def __init__(self):
        super().__init__(f"--plot needs matplotlib: {sys.executable} -m pip install matplotlib")


def styled(colour, lw: float) -> dict:
    """A line's colour, width (points) and dashes as the page draws it (export/palette.py's
    LINE_DASHES, told apart by more than colour): matplotlib scales a dash pattern by the width."""
    dashes = line_dashes(colour, lw / POINTS_PER_PX)
    return {"color": colour, "lw": lw,
            "linestyle": (0, tuple(d * POINTS_PER_PX / lw for d in dashes)) if dashes else "-"}


def _pyplot():
    """matplotlib's pyplot drawing to files (Agg), whatever MPLBACKEND says: the figure needs no window."""
    backend = os.environ.pop("MPLBACKEND", None)   # matplotlib refuses to load with a misspelt one
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise MissingMatplotlib() from None
    except Exception as problem:   # a broken installation: say so in one line, not as our bug
        text = " ".join(str(problem).split())
        raise OutputError(f"--plot cannot load matplotlib ({type(problem).__name__}: {text}); "
                          f"reinstall it: {sys.executable} -m pip install --force-reinstall matplotlib") from None
    finally:
        if backend is not None:
            os.environ["MPLBACKEND"] = backend
    return plt


def check_format(path: str) -> None:
    """Raise MissingMatplotlib if matplotlib is absent, OutputError if it cannot write this file type."""
    plt = _pyplot()
    kinds = plt.figure().canvas.get_supported_filetypes()
    plt.close("all")
    extension = path.rsplit(".", 1)[-1].lower() if "." in path else ""
    if extension not in kinds:
        raise OutputError(f"--plot cannot write {path!r}: use one of the file types "
                         f"{', '.join('.' + kind for kind in sorted(kinds))}")
    if extension == "pgf":   # LaTeX drawing commands, which matplotlib lays out with a TeX system
        import matplotlib

        tex = matplotlib.rcParams["pgf.texsystem"]
        if shutil.which(tex) is None:
            raise OutputError(f"--plot cannot write {path!r}: a .pgf figure needs {tex} (a TeX system), which is not "
                              f"installed here; use .pdf, .svg or .png instead, or install TeX")


MAX_LEGEND = 8  # more curves than this (a row of 25 springs) get no legend


def moving_axes(r: np.ndarray, preferred: str | None = None) -> list[int]:
    """The coordinates worth plotting: the scene's choice ('y', or 'xyz'), else those that move."""
    if preferred and set(preferred) <= set("xyz"):
        return ["xyz".index(c) for c in dict.fromkeys(preferred)]
    span = np.ptp(r.reshape(-1, 3), axis=0)
    moving = [axis for axis in range(3) if span[axis] > 1e-12 * max(1.0, float(np.max(np.abs(r))))]
    return moving or [1]


def energy_per_body(traj, forces):
    """E = K + U and E − W_nc of each mass at every sample, (n, N) arrays in J."""
    states = State(t=traj.t, r=traj.r, p=traj.p, m=traj.m)     # every sample at once
    E = kinetic(states) + potential(states, forces)
    return E, E - traj.work     # W_nc of each mass, as the engine metered it


def resonance_panel(ax, curve: dict) -> None:
    """Measured steady-state amplitudes (dots) on the exact F0/√((k − mω²)² + (bω)²) (smooth lines),
    per b, each b in the colour of its line on the page and of its row of springs."""
    omega = np.asarray(curve["omega_rad_per_s"])
    measured_all = curve["amplitude_m"] or [None] * len(curve["b_kg_per_s"])   # None: run too short
    for j, (b, measured, exact) in enumerate(zip(curve["b_kg_per_s"], measured_all,
                                                 curve["smooth_exact_amplitude_m"])):
        ax.plot(curve["smooth_omega_rad_per_s"], exact, label=f"exact, b = {b:.3g} kg/s", **styled(curve_colour(j), 1.5))
        if measured is not None:
            ax.plot(omega, measured, "o", ms=5, color=curve_colour(j), markeredgecolor="white",
                    label=f"measured, b = {b:.3g} kg/s")
    ax.set_xlabel("driving angular frequency ω (rad/s)")
    ax.set_ylabel("amplitude (m)")
    ax.legend(loc="best", fontsize="small")
    ax.grid(alpha=0.3)


def fit_y(ax, values, *, margin: float = 0.05) -> tuple[float, float]:
    """Fix the y axis on `values`, with matplotlib's usual 5 % margin: other curves may leave it."""
    low, high = float(np.nanmin(values)), float(np.nanmax(values))
    pad = margin * (high - low) or margin * max(abs(high), 1e-9)
    ax.set_ylim(low - pad, high + pad)
    return low - pad, high + pad


def energy_panel(ax, result, *, colours) -> None:
    """Energy against time, as the page's energy graph shows it (browser/graphs.py); colours: each
    mass's (export/palette.py mass_colours), as on the position panel.

    Where the masses start at rest at equilibrium, every energy but K is measured from there
    (U − U_rest, …): the oscillation's energy, not a constant m g h of hundreds of joules that
    would flatten every curve. Two to four masses get each mass's own E (and E − W_nc where a force
    does work), and the axis fits the masses not expected to run away: euler's growing energy leaves
    the graph, as on the page.
    """
    traj, model = result.trajectory, result.model
    rest = rest_potential(model.state, model.forces)    # Σ U at rest at equilibrium, or None
    from_rest = rest is not None
    if 1 < len(model.labels) <= MAX_LEGEND // 2:
        E, E_minus_W = energy_per_body(traj, model.forces)
        if from_rest:   # each mass's own U at rest
            U_rest = potential(model.state, model.forces)
            E, E_minus_W = E - U_rest, E_minus_W - U_rest
        runaways = model.expected_runaways(result.methods)
        steady = [i for i in range(len(model.labels)) if i not in runaways]
        low, high = fit_y(ax, [E[:, steady], E_minus_W[:, steady]]) if runaways and steady else (-np.inf, np.inf)
        for i, label in enumerate(model.labels):
            name = f"{label}: {energy_label('E', from_rest=from_rest)}"
            if np.nanmax(E[:, i]) > high or np.nanmin(E[:, i]) < low:
                name += ", runs off the graph"
            ax.plot(traj.t, E[:, i], label=name, **styled(colours[i], 1.5))
            if np.any(traj.work):   # else E − W_nc is E: a second line on it would only crowd the legend
                ax.plot(traj.t, E_minus_W[:, i], ":", color=colours[i], lw=0.9,
                        label=f"{label}: {energy_label('E_minus_W_nc', from_rest=from_rest)}")
        ax.set_title("Energy of each mass" + (", measured from rest at equilibrium" if from_rest else ""))
        ax.legend(loc="best", fontsize="small")
    elif traj.energy is not None:
        for key, colour in ENERGY_COLOURS.items():
            ax.plot(traj.t, traj.energy[key] - (rest if from_rest and key != "K" else 0.0),
                    label=energy_label(key, from_rest=from_rest), **styled(colour, 2.4 if key == "E" else 1.5))
        if from_rest:
            ax.set_title("Energy, measured from rest at equilibrium")
        ax.legend(loc="best", fontsize="small")
    ax.set_ylabel("energy (J)")
    ax.set_xlabel("t (s)")
    ax.grid(alpha=0.3)


def save_figure(fig, path: str) -> None:
    """Write a matplotlib figure to path whole, in the format its extension names, marked as ours
    (export/files.py figure_mark), and close it.

    A temporary file renamed into place: a failure part-way leaves the old figure as it was.
    """
    import matplotlib
    import matplotlib.pyplot as plt

    kind = path.rsplit(".", 1)[-1].lower()
    metadata = figure_mark(kind, f"Matplotlib {matplotlib.__version__}")
    # The PostScript writer notes on stderr that the grid's see-through lines are drawn opaque:
    # true of every figure here and nothing to act on, so not printed beside our one-line messages.
    postscript = logging.getLogger("matplotlib.backends.backend_ps")
    level = postscript.level
    postscript.setLevel(logging.ERROR)
    try:
        with atomic_file(path, what="figure") as temporary:
            try:
                fig.savefig(temporary, dpi=110, format=kind, metadata=metadata)
            except OSError:
                raise           # atomic_file says why in one line (a full disk)
            except Exception as problem:   # matplotlib cannot write this type here
                text = " ".join(str(problem).split())
                raise OutputError(f"--plot cannot write {path!r}: matplotlib could not write a .{kind} file "
                                  f"({type(problem).__name__}: {text}); use .png, .svg or .pdf instead") from None
    finally:
        postscript.setLevel(level)
        plt.close(fig)


def plot(result, path: str) -> None:
    """Write the run's position and energy graphs to `path` (a reports.headless.Result)."""
    plt = _pyplot()
    traj, model = result.trajectory, result.model
    view = result.setup.hooks.view
    preferred = view.get("plot")
    axes_shown = moving_axes(traj.r, preferred if isinstance(preferred, str) else None)
    # closed forms drawn smooth, whatever Δt is: at least 50 points a second, 2,000 in all
    smooth_t = np.linspace(traj.t[0], traj.t[-1], max(2000, int(50 * (traj.t[-1] - traj.t[0]))))
    exact = model.exact_where_valid(smooth_t)   # NaN, a gap in the curve, where it does not hold
    extra_json = result.setup.hooks.extra_json
    curve = extra_json(result).get("resonance") if extra_json is not None else None
    fig, axes = plt.subplots(3 if curve else 2, 1, figsize=(8, 10 if curve else 7))
    ax_r, ax_e = axes[0], axes[1]
    ax_e.sharex(ax_r)
    if curve:
        resonance_panel(axes[2], curve)
    colours = mass_colours(model, view)
    for i, label in enumerate(model.labels):
        for axis in axes_shown:
            name = "xyz"[axis]
            tag = f"{label}: {name}" if len(model.labels) > 1 or len(axes_shown) > 1 else name
            crowded = len(model.labels) * len(axes_shown) > MAX_LEGEND
            width = POINTS_PER_PX * simulation_width(i, len(model.labels), crowded=crowded)
            ax_r.plot(traj.t, traj.r[:, i, axis], label=tag, **styled(shade(colours[i], axes_shown.index(axis)), width))
            if exact is not None and not crowded and np.any(np.isfinite(exact[0][:, i, axis])):
                first = not any(line.get_label() == "exact" for line in ax_r.lines)
                ax_r.plot(smooth_t, exact[0][:, i, axis], zorder=3, **styled(EXACT_COLOUR, 1.2),
                          label="exact" if first else "_nolegend_")
    ax_r.set_ylabel("position (m)")
    ax_r.set_title(f"{result.setup.name}: dt = {model.dt:g} s, {result.integrator}")
    if len(ax_r.lines) <= MAX_LEGEND:
        ax_r.legend(loc="best", fontsize="small")
    ax_r.grid(alpha=0.3)
    energy_panel(ax_e, result, colours=colours)
    fig.tight_layout()
    save_figure(fig, path)

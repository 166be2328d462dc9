"""A static figure of a headless run (`python main.py SCENE --headless --plot FILE.png`).

Two graphs, like the page's: position against time for each mass (the iteration solid, the exact
solution dashed where a closed form exists), and energy against time, K, U, E and E − W_nc.
E − W_nc staying flat is the energy principle; how flat it stays shows the integrator's accuracy.

matplotlib is an optional extra: it is imported only here, only when a figure is asked for, and
with the Agg backend so no window is needed.
"""
from __future__ import annotations

import sys

import numpy as np

from export.files import OutputError, atomic_file
from export.palette import (ENERGY_COLOURS, ENERGY_LABELS, EXACT_COLOUR, mass_colour, shade,
                            simulation_width)

POINTS_PER_PX = 0.75 # matplotlib widths are in points: the page's px widths, scaled to this figure


class MissingMatplotlib(OutputError):
    """matplotlib is not installed."""

    def __init__(self):
        super().__init__(f"--plot needs matplotlib: {sys.executable} -m pip install matplotlib")


def _pyplot():
    try:
        import matplotlib
    except ImportError:
        raise MissingMatplotlib() from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
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
    from physics.energy import kinetic, potential
    from physics.state import State

    states = State(t=traj.t, r=traj.r, p=traj.p, m=traj.m)     # every sample at once
    E = kinetic(states) + potential(states, forces)
    return E, E - traj.work     # W_nc of each mass, as the engine metered it


def resonance_panel(ax, curve: dict) -> None:
    """Measured steady-state amplitudes (dots) on the exact F0/√((k − mω²)² + (bω)²) (lines), per b."""
    omega = np.asarray(curve["omega_rad_per_s"])
    measured_all = curve["amplitude_m"] or [None] * len(curve["b_kg_per_s"])   # None: run too short
    for b, measured, exact in zip(curve["b_kg_per_s"], measured_all, curve["exact_amplitude_m"]):
        line, = ax.plot(omega, exact, label=f"exact, b = {b:.3g} kg/s")
        if measured is not None:
            ax.plot(omega, measured, "o", ms=4, color=line.get_color(), label=f"measured, b = {b:.3g} kg/s")
    ax.set_xlabel("driving angular frequency ω (rad/s)")
    ax.set_ylabel("amplitude (m)")
    ax.legend(loc="best", fontsize="small")
    ax.grid(alpha=0.3)


def exact_curve(model, t):
    """The closed form's (r, v) at times t, NaN (a gap in the curve) where it does not hold; or None."""
    if model.exact is None:
        return None
    r, v = (np.array(a, dtype=float) for a in model.exact(t))
    if model.exact_valid_until is not None:
        after = t > model.exact_valid_until(float(t[-1]))
        r[after], v[after] = np.nan, np.nan
    return r, v


def plot(result, path: str) -> None:
    """Write the run's position and energy graphs to `path` (a headless.Result)."""
    plt = _pyplot()
    traj, model = result.trajectory, result.model
    preferred = getattr(result.setup.module, "VIEW", {}).get("plot")
    axes_shown = moving_axes(traj.r, preferred if isinstance(preferred, str) else None)
    # closed forms drawn smooth, whatever Δt is: at least 50 points a second, 2,000 in all
    smooth_t = np.linspace(traj.t[0], traj.t[-1], max(2000, int(50 * (traj.t[-1] - traj.t[0]))))
    exact = exact_curve(model, smooth_t)
    extra = getattr(result.setup.module, "extra_json", None)
    curve = extra(result).get("resonance") if extra is not None else None
    fig, axes = plt.subplots(3 if curve else 2, 1, figsize=(8, 10 if curve else 7))
    ax_r, ax_e = axes[0], axes[1]
    ax_e.sharex(ax_r)
    if curve:
        resonance_panel(axes[2], curve)
    for i, label in enumerate(model.labels):
        for axis in axes_shown:
            name = "xyz"[axis]
            tag = f"{label}: {name}" if len(model.labels) > 1 or len(axes_shown) > 1 else name
            crowded = len(model.labels) * len(axes_shown) > MAX_LEGEND
            width = POINTS_PER_PX * simulation_width(i, len(model.labels), crowded=crowded)
            ax_r.plot(traj.t, traj.r[:, i, axis], lw=width, label=tag,
                      color=shade(mass_colour(i), axes_shown.index(axis)))
            if exact is not None and not crowded and np.any(np.isfinite(exact[0][:, i, axis])):
                first = not any(line.get_label() == "exact" for line in ax_r.lines)
                ax_r.plot(smooth_t, exact[0][:, i, axis], "--", lw=1.2, color=EXACT_COLOUR, zorder=3,
                          label="exact" if first else "_nolegend_")
    ax_r.set_ylabel("position (m)")
    ax_r.set_title(f"{result.setup.name}: dt = {model.dt:g} s, "
                   f"{result.integrator if isinstance(result.integrator, str) else ', '.join(result.integrator)}")
    if len(ax_r.lines) <= MAX_LEGEND:
        ax_r.legend(loc="best", fontsize="small")
    ax_r.grid(alpha=0.3)
    if 1 < len(model.labels) <= MAX_LEGEND // 2:
        E, E_minus_W = energy_per_body(traj, model.forces)
        for i, label in enumerate(model.labels):
            ax_e.plot(traj.t, E[:, i], color=mass_colour(i), label=f"{label}: E")
            ax_e.plot(traj.t, E_minus_W[:, i], ":", color=mass_colour(i), label=f"{label}: E − W_nc")
        ax_e.legend(loc="best", fontsize="small")
    elif traj.energy is not None:
        for key, label in ENERGY_LABELS.items():
            ax_e.plot(traj.t, traj.energy[key], color=ENERGY_COLOURS[key], label=label,
                      lw=2.4 if key == "E" else 1.5)
        ax_e.legend(loc="best", fontsize="small")
    ax_e.set_ylabel("energy (J)")
    ax_e.set_xlabel("t (s)")
    ax_e.grid(alpha=0.3)
    fig.tight_layout()
    try:
        # A temporary file renamed into place: a failure part-way leaves the old figure as it was.
        with atomic_file(path, what="figure") as temporary:
            fig.savefig(temporary, dpi=110, format=path.rsplit(".", 1)[-1].lower())
    finally:
        plt.close(fig)

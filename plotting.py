"""A static figure of a headless run (`python main.py SCENE --headless --plot FILE.png`).

Two graphs, like the page's: position against time for each mass (the iteration solid, the exact
solution dashed where a closed form exists), and energy against time, K, U, E and E − W_nc.
E − W_nc staying flat is the energy principle; how flat it stays shows the integrator's accuracy.

matplotlib is an optional extra: it is imported only here, only when a figure is asked for, and
with the Agg backend so no window is needed.
"""
from __future__ import annotations

import numpy as np

from headless import OutputError


class MissingMatplotlib(OutputError):
    """matplotlib is not installed."""

    def __init__(self):
        super().__init__("--plot needs matplotlib: pip install matplotlib")


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


def moving_axes(r: np.ndarray, preferred: str | None = None) -> list[int]:
    """The coordinates worth plotting: the scene's chosen one ('x', 'y' or 'z'), else those that move."""
    if preferred and preferred in "xyz" and len(preferred) == 1:
        return ["xyz".index(preferred)]
    span = np.ptp(r.reshape(-1, 3), axis=0)
    moving = [axis for axis in range(3) if span[axis] > 1e-12 * max(1.0, float(np.max(np.abs(r))))]
    return moving or [1]


def plot(result, path: str) -> None:
    """Write the run's position and energy graphs to `path` (a headless.Result)."""
    plt = _pyplot()
    traj, model = result.trajectory, result.model
    preferred = getattr(result.setup.module, "VIEW", {}).get("plot")
    axes_shown = moving_axes(traj.r, preferred if isinstance(preferred, str) else None)
    exact = model.exact(traj.t) if model.exact is not None else None
    fig, (ax_r, ax_e) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    for i, label in enumerate(model.labels):
        for axis in axes_shown:
            name = "xyz"[axis]
            tag = f"{label}: {name}" if len(model.labels) > 1 or len(axes_shown) > 1 else name
            line, = ax_r.plot(traj.t, traj.r[:, i, axis], lw=2.5, alpha=0.7, label=tag)
            if exact is not None and np.all(np.isfinite(exact[0][:, i, axis])):
                ax_r.plot(traj.t, exact[0][:, i, axis], "--", lw=1.2, color="black", label=f"{tag} exact")
    ax_r.set_ylabel("position (m)")
    ax_r.set_title(f"{result.setup.name}: dt = {model.dt:g} s, "
                   f"{result.integrator if isinstance(result.integrator, str) else ', '.join(result.integrator)}")
    ax_r.legend(loc="best", fontsize="small")
    ax_r.grid(alpha=0.3)
    if traj.energy is not None:
        for key, label in (("K", "K"), ("U", "U"), ("E", "E = K + U"), ("E_minus_W_nc", "E − W_nc")):
            ax_e.plot(traj.t, traj.energy[key], label=label)
        ax_e.legend(loc="best", fontsize="small")
    ax_e.set_ylabel("energy (J)")
    ax_e.set_xlabel("t (s)")
    ax_e.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)

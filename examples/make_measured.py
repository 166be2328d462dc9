"""Write the measured-looking example files in examples/data/, one per data program's format.

    .venv/bin/python examples/make_measured.py [FOLDER]       (default: examples/data)

Each file records the same classroom spring, as a class would measure it: a 0.5 kg mass on a spring
of k = 20 N/m, with b = 0.1 kg/s of damping (1.6 % of critical; a period of 1.0 s), hanging from the
ceiling as the `damped` scene's mass does. The run is the engine's (rk4, Δt = 1 ms); each file samples
it as its program would, on its own clock and zero, with its own noise (a fixed seed: the same files
every time), and none knows where the mass was let go:

    vernier.csv    a motion detector on the floor (20 samples/s, 1 mm steps), started 1.2 s before
                   the mass was let go 8 cm below its rest position: Graphical Analysis CSV
    pasco.csv      a motion sensor above the mass, looking down (50 samples/s; the axis points down),
                   started mid-swing, two runs, saved on a computer set to decimal commas: Capstone
    tracker.txt    a video at 30 frames/s, y up, its origin on the table (2 mm of noise, and the
                   mass wobbles 3 mm sideways in x), started mid-swing: Tracker's Export Data
    loggerpro.txt  a motion detector read by Logger Pro (25 samples/s): its text export
    plain.txt      two columns of numbers, t and y, and no header (25 samples/s)
    simulated.csv  this program's own --csv header, with t and y filled in (25 samples/s)

Fit any of them with the README's first recipe, the mass weighed on a balance:

    .venv/bin/python main.py damped --data examples/data/vernier.csv --fit k,b --set m=0.5

The mystery file is made by the command line itself:
`python main.py damped --mystery examples/data/mystery.csv --seed 2026`.
"""
from __future__ import annotations

import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))

from export.files import atomic_file  # noqa: E402
from lab import formats  # noqa: E402
from lab.model_run import ModelRun  # noqa: E402
from scenes import catalog  # noqa: E402

M, K, B = 0.5, 20.0, 0.1            # kg, N/m, kg/s: the spring every file records
REST = -1.0 - M * 9.8 / K           # m: where the damped scene's mass hangs at rest with these constants


def spring(pulled: float):
    """The engine's run of the spring let go from rest `pulled` m above its rest position (below: < 0)."""
    truth = catalog.configure("damped", assignments=[f"m={M}", f"k={K}", f"b={B}", "dt=0.001",
                                                     f"r0=0,{REST + pulled},0"])
    return ModelRun(truth, integrator="rk4", axis=1, until=40.0)


def sampled(run, *, rate, seconds, first, clock, zero, sign=1, noise, step, seed):
    """(t, y): the run sampled `rate` times a second for `seconds` s from model time `first` (the
    data's clock reads `clock` there), on the data's axis (sign) and zero, with Gaussian `noise` m,
    rounded to the program's `step` (m)."""
    tau = first + np.arange(0.0, seconds, 1.0 / rate)
    rng = np.random.default_rng(seed)
    y = zero + sign * (run.at(tau)[0] - REST) + rng.normal(0.0, noise, tau.size)
    return np.round(clock + tau - first, 4), np.round(np.round(y / step) * step, 6)


def main(folder: str) -> None:
    os.makedirs(folder, exist_ok=True)
    files = {}
    below = spring(-0.08)                              # pulled 8 cm down, let go at model time 0
    t, y = sampled(below, rate=20, seconds=15.0, first=-1.2, clock=0.0, zero=0.62, noise=0.001, step=0.001,
                   seed=1)
    files["vernier.csv"] = formats.vernier(t, y)
    above = spring(0.06)
    runs = [sampled(above, rate=50, seconds=seconds, first=first, clock=0.0, zero=0.45, sign=-1, noise=0.0008,
                    step=0.0001, seed=2 + n) for n, (seconds, first) in enumerate(((12.0, 2.37), (6.0, 0.81)))]
    files["pasco.csv"] = formats.pasco(runs, separator=";", decimal_comma=True)
    t, y = sampled(below, rate=30, seconds=10.0, first=3.1, clock=0.0, zero=0.31, noise=0.002, step=0.0001,
                   seed=4)
    wobble = 0.003 * np.sin(2 * np.pi * 0.7 * t) + np.random.default_rng(5).normal(0.0, 0.002, t.size)
    files["tracker.txt"] = formats.tracker(t, y, x=np.round(0.42 + wobble, 4))
    t, y = sampled(above, rate=25, seconds=12.0, first=-0.6, clock=3.3, zero=0.55, noise=0.0012, step=0.0001,
                   seed=6)
    files["loggerpro.txt"] = formats.loggerpro(t, y)
    t, y = sampled(below, rate=25, seconds=12.0, first=1.45, clock=12.8, zero=0.5, noise=0.0015, step=0.00001,
                   seed=7)
    files["plain.txt"] = formats.plain(t, y)
    t, y = sampled(below, rate=25, seconds=12.0, first=0.0, clock=0.0, zero=REST, noise=0.002, step=0.0001,
                   seed=8)
    files["simulated.csv"] = formats.own_csv(t, y)
    for name, text in files.items():      # the project's own fixtures: written here, not by the program
        path = os.path.join(folder, name)
        # atomic_file, not write_text: these files are the tree's own examples, which the program
        # itself never writes (export/files.py own_tree), but this script is there to make
        with atomic_file(path, what="example file") as temporary:
            with open(temporary, "w", encoding="utf-8") as out:
                out.write(text)
        print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "data"))

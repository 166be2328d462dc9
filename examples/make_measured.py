"""Write the measured-looking example files in examples/data/, one per data program's format.

    .venv/bin/python examples/make_measured.py [FOLDER]       (default: examples/data)

Each file is the same spring as the `damped` scene with k = 55 N/m and b = 2.5 kg/s (m = 10 kg,
released from rest at y = −1.5 m), run by the engine (rk4, Δt = 1 ms), sampled as each program
would, on its own clock and zero, with 2 mm of noise from a fixed seed: the same files every time.
Fit any of them with, for example,

    .venv/bin/python main.py damped --data examples/data/tracker.txt --fit k,b --integrator rk4 --set dt=0.001

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
from lab.compare import ModelRun  # noqa: E402
from scenes import catalog  # noqa: E402

TRUTH = ["k=55", "b=2.5", "dt=0.001"]
# file name, samples per second, seconds recorded, clock at the release (s), the file's zero (m)
FILES = [
    ("tracker.txt", 30, 12.0, 0.0, 1.5),       # a video: Tracker's frame times, its own origin
    ("vernier.csv", 20, 15.0, 4.35, 2.1),      # a motion detector on the floor
    ("pasco.csv", 50, 10.0, 1.12, 2.0),        # two runs side by side
    ("loggerpro.txt", 25, 12.0, 2.6, 2.2),
    ("simulated.csv", 25, 12.0, 0.0, 0.0),     # this program's own --csv header
]


def sampled(rate: float, seconds: float, *, seed: int, clock: float, zero: float):
    run = ModelRun(catalog.configure("damped", assignments=TRUTH), integrator="rk4", axis=1,
                   until=seconds + 1.0)
    t = np.arange(0.0, seconds, 1.0 / rate)
    y = run.at(t)[0] + zero + np.random.default_rng(seed).normal(0.0, 0.002, t.size)
    return np.round(t + clock, 4), np.round(y, 4)


def main(folder: str) -> None:
    os.makedirs(folder, exist_ok=True)
    for seed, (name, rate, seconds, clock, zero) in enumerate(FILES):
        t, y = sampled(rate, seconds, seed=seed, clock=clock, zero=zero)
        if name == "pasco.csv":
            t2, y2 = sampled(rate, seconds / 2, seed=seed + 100, clock=clock, zero=zero)
            text = formats.pasco([(t, y), (t2, y2)])
        else:
            text = formats.write_format({"tracker.txt": "tracker", "vernier.csv": "vernier",
                                         "loggerpro.txt": "loggerpro", "simulated.csv": "csv"}[name], t, y)
        path = os.path.join(folder, name)
        # atomic_file, not write_text: these files are the tree's own examples, which the program
        # itself never writes (export/files.py own_tree), but this script is there to make
        with atomic_file(path, what="example file") as temporary:
            with open(temporary, "w", encoding="utf-8") as out:
                out.write(text)
        print(f"wrote {path}: {len(t)} samples", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "data"))

"""A mystery spring for class: a measured-looking run of a spring whose k and b the students find.

The program picks k and b (unless the teacher sets them with --set), runs the engine with rk4 and
a small Δt (far closer to the exact motion than the noise), and writes what a motion detector
would: a Vernier Graphical Analysis CSV, 20 to 50 samples a second, a few millimetres of noise,
a clock that started before the release at an arbitrary reading, and a zero of its own (the
detector's distance). Everything is drawn from one seed, so the same seed gives the same file and
the same answer (--show-answer --seed N), and the answer is printed only when asked for.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .compare import AXES, FitError, ModelRun
from .formats import vernier

HIDDEN = ("k", "b")                   # what the students find
RATES = (20, 25, 30, 40, 50)          # samples per second a motion detector records
DURATION = 15.0                       # s of recording after the release
FINE_DT = 1e-3                        # s: the engine's Δt for the "real" spring (rk4)


@dataclass(frozen=True)
class Mystery:
    """The run and what made it: t (s, the detector's clock), position (m, its zero), the constants."""

    t: np.ndarray
    position: np.ndarray
    answer: dict          # name → (value, unit), the hidden constants
    known: dict           # name → (value, unit), what the students are told (m, r0)
    rate: int             # samples per second
    noise: float          # m, standard deviation of the noise


def _round(x: float, digits: int = 3) -> float:
    return float(f"{x:.{digits}g}")


def choose(setup, *, seed: int, given=()) -> dict:
    """The hidden constants from the seed: k from half to twice the scene's, and b for a damping
    ratio from 0.02 to 0.12 of critical (a swing that visibly dies away), at most one that leaves a
    twentieth of the swing at the end of the record; `given` names the ones the teacher set, which
    are kept."""
    missing = [name for name in ("m", *HIDDEN) if name not in setup.constants]
    if missing:
        raise FitError(f"scene {setup.name!r} has no {' or '.join(missing)}; a mystery spring needs a scene "
                       f"of one mass on a spring with m, k and b (vertical, damped, driven)")
    if not float(setup.values["k"]) > 0:
        raise FitError("a mystery spring needs a spring: k must be greater than 0 N/m")
    rng = np.random.default_rng(seed)
    m, k_scene = float(setup.values["m"]), float(setup.values["k"])
    k = _round(k_scene * 2.0 ** rng.uniform(-1.0, 1.0))
    zeta = rng.uniform(0.02, 0.12)
    k = float(setup.values["k"]) if "k" in given else k
    # The swing must last most of the record to be measured: a decay rate ζω of at most 3/DURATION.
    zeta = min(zeta, 3.0 / (DURATION * math.sqrt(k / m)))
    b = float(setup.values["b"]) if "b" in given else _round(zeta * 2.0 * math.sqrt(m * k))
    return {"k": k, "b": b}


def make(setup, *, seed: int, given=(), coordinate: str = "y") -> Mystery:
    """The mystery run for this scene and seed (see the module's docstring)."""
    hidden = choose(setup, seed=seed, given=given)
    rng = np.random.default_rng([seed, 1])
    rate = int(rng.choice(RATES))
    before = rng.uniform(0.2, 1.0)                # s the detector records before the release
    clock = _round(rng.uniform(0.5, 8.0), 3)      # its clock's reading at the first sample, s
    noise = _round(rng.uniform(0.001, 0.003), 2)  # m
    real = setup.with_values(dt=min(FINE_DT, float(setup.values["dt"])), **hidden)
    run = ModelRun(real, integrator="rk4", axis=AXES[coordinate], until=DURATION + 1.0)
    samples = np.arange(0.0, before + DURATION, 1.0 / rate)
    tau = samples - before                        # model time: negative while the mass is held
    y, _ = run.at(tau)
    zero = -float(np.min(y)) + rng.uniform(0.2, 0.8)  # the detector below the lowest point
    reading = np.round(y + zero + rng.normal(0.0, noise, y.size), 4)
    t = np.round(clock + samples, 4)
    units = {name: setup.constants[name].unit for name in ("k", "b", "m", "r0") if name in setup.constants}
    return Mystery(t=t, position=reading, answer={name: (value, units[name]) for name, value in hidden.items()},
                   known={name: (setup.values[name], units[name]) for name in ("m", "r0") if name in units},
                   rate=rate, noise=noise)


def text(mystery: Mystery) -> str:
    """The file as Vernier Graphical Analysis exports it."""
    return vernier(mystery.t, mystery.position)


def answer_line(mystery: Mystery, seed: int) -> str:
    """`mystery spring, seed 7: k = 63.2 N/m, b = 1.85 kg/s (m = 10 kg)`."""
    hidden = ", ".join(f"{name} = {value:g} {unit}" for name, (value, unit) in mystery.answer.items())
    return f"mystery spring, seed {seed}: {hidden} (m = {mystery.known['m'][0]:g} kg)"

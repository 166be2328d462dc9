"""A mystery spring for class: a measured-looking run of a spring whose hidden constants the students find.

The scene declares what is hidden (LAB["hidden"] in its file, scenes/_hooks.py: k and b for vertical,
damped and driven). The program picks their values from the seed (unless the teacher sets them with
--set) over the whole stated range: a natural frequency ω₀ from 1/√2 to √2 times the scene's (k from
half to twice the scene's) and a damping ratio ζ from 2 % to 12 % of critical, both uniform, turned
into the hidden constants through the rates the forces declare (lab/start.py's `matched`, as the
fit's start does), rounded to three digits. It runs the engine with rk4 and a small Δt (far closer
to the exact motion than the noise), and writes what a motion detector would: a Vernier Graphical
Analysis CSV, 20 to 50 samples a second, a few millimetres of noise, a clock that started before the
release at an arbitrary reading, and a zero of its own (the detector's distance). Everything is
drawn from one seed, so the same seed gives the same file and the same answer (--show-answer --seed
N), and the answer is printed only when asked for.

A mystery no class could solve is refused with one line, and no file is written: a compared
coordinate that does not move, or a swing so fast that the detector takes fewer than 8 samples a
period.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from physics.stability import rates

from .formats import vernier
from .model_run import AXES, FitError, ModelRun
from .start import matched

RATES = (20, 25, 30, 40, 50)          # samples per second a motion detector records
DURATION = 15.0                       # s of recording after the release
FINE_DT = 1e-3                        # s: the engine's Δt for the "real" spring (rk4)
ZETA = (0.02, 0.12)                   # damping ratios drawn from
LEAST_SAMPLES = 8                     # samples a period a class needs to see the swing


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


def hidden_names(setup) -> tuple:
    """The constants the scene hides in a mystery (its LAB["hidden"]); FitError for a scene of more
    than one mass, or one that hides none."""
    count = setup.build().state.count
    if count != 1:
        raise FitError(f"scene {setup.name!r} has {count} masses; a mystery spring is a scene of one mass "
                       f"(vertical, damped, driven)")
    names = tuple(setup.hooks.lab.get("hidden", ()))
    if not names or any(name not in setup.constants for name in names):
        raise FitError(f"scene {setup.name!r} declares no constants to hide (LAB = {{\"hidden\": ...}} in its "
                       f"file); a mystery spring needs a scene of one mass on a spring (vertical, damped, driven)")
    return names


def _natural(setup, values=None):
    """(ω₀ rad/s, damping rate b/m 1/s) of the scene's mass, from its forces' declared rates."""
    model = (setup if values is None else setup.with_values(**values)).build()
    found = rates(model.forces, model.state.m)
    return float(found.omega[0]), float(found.damping[0])


def choose(setup, *, seed: int, given=()) -> dict:
    """The hidden constants from the seed (see the module's docstring); `given` names the ones the
    teacher set, which are kept."""
    names = hidden_names(setup)
    omega_scene, _ = _natural(setup)
    if not omega_scene > 0:
        raise FitError("a mystery spring needs a spring: the scene's spring has no stiffness")
    rng = np.random.default_rng(seed)
    omega0 = omega_scene * 2.0 ** (rng.uniform(-1.0, 1.0) / 2)
    zeta = rng.uniform(*ZETA)
    free = [name for name in names if name not in given]
    if not free:
        return {name: float(setup.values[name]) for name in names}
    start = tuple(float(setup.values[name]) for name in free)
    if not any(_natural(setup, {name: value * 1.01 + 1e-6})[0] != _natural(setup)[0]
               for name, value in zip(free, start)):
        omega0 = _natural(setup)[0]      # the teacher set what makes the swing's pace: only ζ is drawn
    decay = zeta * omega0
    try:
        found = matched(setup, free, start, omega=omega0 * math.sqrt(1 - zeta ** 2), decay=decay, axis=0)
    except FitError:
        found = None
    if found is None:
        raise FitError(f"scene {setup.name!r}: no values of {', '.join(free)} give this spring a swing of "
                       f"ω₀ = {omega0:.3g} rad/s damped at {zeta:.0%} of critical; set them with --set")
    chosen = {name: _round(value) for name, value in zip(free, found)}
    return {name: chosen.get(name, float(setup.values[name])) for name in names}


def make(setup, *, seed: int, given=(), coordinate: str = "y") -> Mystery:
    """The mystery run for this scene and seed (see the module's docstring)."""
    hidden = choose(setup, seed=seed, given=given)
    rng = np.random.default_rng([seed, 1])
    rate = int(rng.choice(RATES))
    before = rng.uniform(0.2, 1.0)                # s the detector records before the release
    clock = _round(rng.uniform(0.5, 8.0), 3)      # its clock's reading at the first sample, s
    noise = _round(rng.uniform(0.001, 0.003), 2)  # m
    real = setup.with_values(dt=min(FINE_DT, float(setup.values["dt"])), **hidden)
    omega0, damping = _natural(real)
    omega_d = math.sqrt(max(omega0 ** 2 - (damping / 2) ** 2, 0.0))
    if omega_d > 0 and 2 * math.pi * rate / omega_d < LEAST_SAMPLES:
        raise FitError(f"this spring swings {omega_d / (2 * math.pi):.3g} times a second, so a detector's {rate} "
                       f"samples a second are fewer than {LEAST_SAMPLES} a period, too few to see its swing; "
                       f"set a softer spring or a heavier mass")
    run = ModelRun(real, integrator="rk4", axis=AXES[coordinate], until=DURATION + 1.0)
    samples = np.arange(0.0, before + DURATION, 1.0 / rate)
    tau = samples - before                        # model time: negative while the mass is held
    y, _ = run.at(tau)
    if np.ptp(y) < 5 * noise:
        raise FitError(f"in scene {setup.name!r} the mass hardly moves along {coordinate} (by {np.ptp(y):.2g} m, "
                       f"less than 5 times the detector's noise); choose the coordinate that moves with "
                       f"--coordinate, or a start position away from equilibrium")
    zero = -float(np.min(y)) + rng.uniform(0.2, 0.8)  # the detector below the lowest point
    reading = np.round(y + zero + rng.normal(0.0, noise, y.size), 4)
    t = np.round(clock + samples, 4)
    units = {name: setup.constants[name].unit for name in (*hidden, "m", "r0") if name in setup.constants}
    known = {name: (setup.values[name], units[name]) for name in ("m", "r0")
             if name in units and setup.values[name] is not None}
    return Mystery(t=t, position=reading, answer={name: (value, units[name]) for name, value in hidden.items()},
                   known=known, rate=rate, noise=noise)


def text(mystery: Mystery) -> str:
    """The file as Vernier Graphical Analysis exports it."""
    return vernier(mystery.t, mystery.position)


def answer_line(mystery: Mystery, seed: int) -> str:
    """`mystery spring, seed 7: k = 63.2 N/m, b = 1.85 kg/s (m = 10 kg)`."""
    hidden = ", ".join(f"{name} = {value:g} {unit}" for name, (value, unit) in mystery.answer.items())
    return f"mystery spring, seed {seed}: {hidden} (m = {mystery.known['m'][0]:g} kg)"

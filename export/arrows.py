"""The momentum update drawn as arrows: what each arrow is, and the scale it is drawn at.

The page (browser/arrows3d.py) and the handed-out program (export/program_arrows.py) draw, at
each mass's centre,

    p       the momentum, kg·m/s
    F_net   the net force, N
    forces  each force on its own arrow, tip to tail, so together they end at F_net's tip
    split   F_net split along p and across it: F∥ = (F_net·p̂) p̂ changes the speed,
            F⊥ = F_net − F∥ changes the direction

An arrow's length is its quantity divided by a scale, "arrow of 1 m = 20 kg·m/s": one scale for
momentum and one for every force, chosen once per run from the largest magnitudes a short headless
run of the engine meets, rounded up to 1, 2 or 5 × 10ⁿ so the legend can be read and two arrows
compared. The force scale is chosen from F_net, the arrow the lesson is about; a single force
(gravity on a hanging mass) may be drawn longer than F_net ever is. Nothing here imports vpython.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from physics.forces import net_force
from physics.rounding import round_up as round_scale  # 13 → 20 per metre of arrow
from physics.simulate import BlowUpError, every, trajectory
from physics.state import velocity

ARROWS = ("p", "F_net", "forces", "split")   # what --arrows and the page's check boxes may name
ARROW_LABELS = {"p": "p", "F_net": "F_net", "forces": "forces", "split": "F∥ and F⊥"}
REACH = 0.5           # the longest arrow, as a fraction of the size of the motion and its support
SCALE_RUN = 30.0      # s: how far the short run that chooses the scales looks ahead (the graphs show 30 s)
SCALE_STEPS = 6000    # at most this many steps of it
TOO_LONG = 2.0        # an arrow this many times REACH is out of the picture: the next Reset rescales


def parse_arrows(text: str) -> tuple[str, ...]:
    """`--arrows p,F_net,split` as a tuple of names; ValueError naming an unknown one."""
    names = tuple(name.strip() for name in text.split(",") if name.strip())
    unknown = [name for name in names if name not in ARROWS]
    if unknown:
        raise ValueError(f"--arrows knows {', '.join(ARROWS)} (got {unknown[0]!r})")
    return names


@dataclass(frozen=True)
class ArrowScales:
    """How long an arrow is drawn: p_unit kg·m/s and F_unit N per metre of arrow (round numbers),
    and reach, m, the length the longest arrow of the run was expected to have."""

    p_unit: float
    F_unit: float
    reach: float

    def momentum_axis(self, p) -> np.ndarray:
        """The arrow of momentum p, m: p / p_unit."""
        return np.asarray(p, dtype=float) / self.p_unit

    def force_axis(self, F) -> np.ndarray:
        """The arrow of force F (F_net, one force, F∥ or F⊥), m: F / F_unit."""
        return np.asarray(F, dtype=float) / self.F_unit

    def legend(self) -> str:
        """`an arrow of 1 m = 20 kg·m/s for p, 50 N for forces` (it follows the check boxes' `arrows:`)."""
        return (f"an arrow of 1 m = {self.p_unit:g} kg·m/s for p, "
                f"{self.F_unit:g} N for forces")

    def fits(self, *, p_max: float, F_max: float) -> bool:
        """Whether arrows of these magnitudes (kg·m/s, N) stay in the picture at these scales."""
        return max(p_max / self.p_unit, F_max / self.F_unit) <= TOO_LONG * self.reach

    def refitted(self, *, p_max: float, F_max: float) -> "ArrowScales":
        """Scales chosen again so magnitudes up to these fit (at Reset, never during a run)."""
        return ArrowScales(p_unit=max(self.p_unit, round_scale(p_max / self.reach)),
                           F_unit=max(self.F_unit, round_scale(F_max / self.reach)), reach=self.reach)


def forces_each(forces, t: float, r, v, m) -> list[np.ndarray]:
    """Each force on every mass, in the scene's order, (N, 3) N each: they add up to F_net."""
    return [np.asarray(force(t, r, v, m), dtype=float) for force in forces]


FORCE_NAMES = {"Spring": "spring", "SpringBetween": "spring", "Gravity": "gravity",
               "LinearDamping": "damping", "QuadraticDrag": "drag", "Driving": "driving"}


def force_name(force) -> str:
    """A force's name for its arrow label: `spring`, `gravity`, ... (a force of a new kind: its
    own `name`, else its class name)."""
    kind = type(force).__name__
    return getattr(force, "name", FORCE_NAMES.get(kind, kind))


def split(F_net, p) -> tuple[np.ndarray, np.ndarray]:
    """F_net along p and across it, (N, 3) each: F∥ = (F_net·p̂) p̂ and F⊥ = F_net − F∥.

    Where p = 0 there is no direction to split along: F∥ is all of F_net and F⊥ is 0 (from rest,
    the force only starts the motion, along itself).
    """
    F_net, p = np.atleast_2d(np.asarray(F_net, float)), np.atleast_2d(np.asarray(p, float))
    size = np.linalg.norm(p, axis=-1, keepdims=True)
    p_hat = np.divide(p, size, out=np.zeros_like(p), where=size > 0)
    along = np.sum(F_net * p_hat, axis=-1, keepdims=True) * p_hat
    along = np.where(size > 0, along, F_net)
    return along, F_net - along


def largest(model, *, integrator: str | None = None) -> tuple[float, float, float]:
    """The largest |p| (kg·m/s), |F_net| (N) and size of one mass's motion (m, motion_size)
    over a short run of the engine from the model's start (SCALE_RUN s, at most SCALE_STEPS steps).

    Masses the scene expects to run away are left out, and a run that blows up is judged on the
    steps before it did.
    """
    engine = model.simulation(integrator)
    steps = max(1, min(SCALE_STEPS, int(SCALE_RUN / model.dt)))
    try:
        samples = engine.advance(steps, record=every(max(1, steps // 200)))
        traj = trajectory(engine, samples, with_energy=False)
        t, r, p = traj.t, traj.r, traj.p
    except BlowUpError:
        start = model.state
        t, r, p = np.array([start.t]), start.r[None], start.p[None]
    kept = [i for i in range(model.state.count) if i not in model.expected_runaways(engine.methods)]
    kept = kept or list(range(model.state.count))
    m = model.state.m
    p_max = F_max = 0.0
    for n in range(len(t)):
        if not np.all(np.isfinite(r[n][kept])):
            break
        F_net = net_force(model.forces, t[n], r[n], velocity(p[n], m), m)
        F_max = max(F_max, float(np.max(np.linalg.norm(F_net[kept], axis=-1))))
        p_max = max(p_max, float(np.max(np.linalg.norm(p[n][kept], axis=-1))))
    return p_max, F_max, motion_size(r, model.anchors, kept) or 1.0


def motion_size(r, anchors, kept) -> float:
    """The size of one mass's motion with its support, m: the largest extent of the box around a
    mass's positions r[:, i] and its anchor, over the masses kept. Each arrow starts on its own
    mass, so it is this, not the whole row's width (`resonance`: 13 springs 4.8 m wide, each
    moving 1.8 m), that an arrow must stay within to stay in the picture."""
    sizes = [0.0]
    for i in kept:
        points = np.concatenate([r[:, i], anchors[i][None]])
        points = points[np.all(np.isfinite(points), axis=1)]
        if len(points):
            sizes.append(float(np.max(points.max(axis=0) - points.min(axis=0))))
    return max(sizes)


def choose_scales(model, *, integrator: str | None = None) -> ArrowScales:
    """One scale for momentum and one for forces, for a run of this model: the largest magnitude
    of each (largest) fits in an arrow REACH × the size of one mass's motion with its support
    long, rounded up to 1, 2 or 5 × 10ⁿ, so the longest arrow is between 0.4 and 1 times that length."""
    p_max, F_max, size = largest(model, integrator=integrator)
    reach = REACH * size
    return ArrowScales(p_unit=round_scale(p_max / reach), F_unit=round_scale(F_max / reach), reach=reach)

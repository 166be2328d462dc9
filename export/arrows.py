"""The momentum update drawn as arrows: what each arrow is, and the scale it is drawn at.

The page (browser/arrows3d.py) and the handed-out program (export/program_arrows.py) draw, at
each mass's centre,

    p       the momentum, kg·m/s
    F_net   the net force, N
    forces  each force on its own arrow, tip to tail, so together they end at F_net's tip
    split   F_net split along p and across it: F∥ = (F_net·p̂) p̂ changes the speed,
            F⊥ = F_net − F∥ changes the direction

An arrow's length is its quantity divided by a scale, "arrow of 1 m = 20 kg·m/s": one scale for
momentum and one for every force, a round 1, 2 or 5 × 10ⁿ so the legend can be read and two
arrows compared, chosen once per run against the picture the page frames (export/framing.py):
over a short headless run of the engine, the longest arrows it allows (the smallest round scale)
whose tips all stay in the picture when it widens by at most GROW. The picture then widens to
hold them, so the longest arrow of the run reaches (nearly) the picture's edge: the rounding
costs room only when the next round step would need the picture to widen more than that. The
force scale is chosen from F_net, the arrow the lesson is about; a single force (gravity on a
hanging mass) may be drawn longer than F_net ever is, unless the run shows each force. Nothing
here imports vpython.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from physics.forces import forces_each as each_force, net_force
from physics.rounding import round_up as round_scale  # 13 → 20 per metre of arrow

from .framing import Camera, frame
from physics.simulate import BlowUpError, every, trajectory
from physics.state import velocity

ARROWS = ("p", "F_net", "forces", "split")   # what --arrows and the page's check boxes may name
ARROW_LABELS = {"p": "p", "F_net": "F_net", "forces": "forces", "split": "F∥ and F⊥"}
LABEL_PX = {"height": 18, "xoffset": 20, "yoffset": 16}   # px: an arrow's label (the back row reads 18 px),
                                                         # beside its point; F⊥'s below it (−yoffset)
SEE_THROUGH = 0.5    # the masses' opacity while an arrow is shown (page and program): the arrow inside the ball shows
PART_DIGITS = "{:.2f}"  # N: how F∥'s and F⊥'s labels write their sizes, on the page and in the program
                       # (Web VPython's own '{:.3g}' writes 0.3135 as 0.314: 7 of a pendulum run's 401)
STEP_ASIDE = 1.4      # × the masses' radius: a Step's p_i and F_net Δt start this far beside the mass, across its motion
STEP_APART = 0.45     # × the radius: and p_f this much further, so on a line the two do not cover each other
GROW = 1.2            # the picture may widen this much (its range) to hold the arrows at a round scale
TIP_ROOM = 0.3        # × the masses' radius: how far inside the picture's edge an arrow's tip stays
SCALE_RUN = 30.0      # s: how far the short run that chooses the scales looks ahead (the graphs show 30 s)
SCALE_STEPS = 6000    # at most this many steps of it


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
    and view_range, m, the camera's range that holds every arrow of the run at these scales."""

    p_unit: float
    F_unit: float
    view_range: float

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

    def refitted(self, *, p_needed: float, F_needed: float) -> "ArrowScales":
        """Scales chosen again (at Reset, never during a run) so that arrows that needed p_needed
        kg·m/s and F_needed N per metre to stay in the picture do: the next round scale up."""
        return ArrowScales(p_unit=max(self.p_unit, round_scale(p_needed)),
                           F_unit=max(self.F_unit, round_scale(F_needed)), view_range=self.view_range)


def room_used(camera: Camera, r, axes, *, margin: float = 0.0, face=None) -> np.ndarray:
    """Each arrow (axes, m, from r, both (N, 3)) as a fraction of the distance from its mass to the
    edge of the camera's picture (margin m inside it) in the arrow's direction on the screen, or
    to the support's face (face: (axis, where, towards), Frame.face) if it points at it and that
    is nearer: 1 is a tip on that edge, over 1 a tip out of the picture or through the support.
    0 for an arrow of no length on the screen, nan for a mass that is itself out of the picture."""
    r, axes = np.asarray(r, float), np.asarray(axes, float)
    at = camera.on_screen(r)
    along = camera.on_screen(r + axes) - at
    half = camera.half() - margin
    with np.errstate(divide="ignore", invalid="ignore"):
        used = np.where(along != 0, along / (np.copysign(half, along) - at), 0.0).max(axis=-1)
        if face is not None:
            axis, where, towards = face
            ahead = axes[..., axis] * towards
            used = np.maximum(used, np.where(ahead > 0, ahead / ((where - r[..., axis]) * towards), 0.0))
    inside = np.all(np.abs(at) < half, axis=-1)
    return np.where(inside, used, np.nan)


def unit_keeping_in(camera: Camera, r, q, *, unit: float, margin: float) -> float:
    """The smallest scale (q's units per metre) at which every arrow q / scale from r (both (N, 3))
    ends inside the camera's picture, margin m inside its edge: `unit` if they all do at it.
    An arrow whose mass is itself out of the picture is not counted."""
    used = room_used(camera, r, np.asarray(q, float) / unit, margin=margin)
    worst = float(np.nanmax(used)) if np.any(np.isfinite(used)) else 0.0
    return unit * max(1.0, worst)


def forces_each(forces, t: float, r, v, m) -> list[np.ndarray]:
    """Each force on every mass, in the scene's order, (N, 3) N each: they add up to F_net
    (physics.forces.forces_each: static friction given the others' sum, as the engine does)."""
    return [np.asarray(force, dtype=float) for force in each_force(forces, t, r, v, m)]


def force_name(force) -> str:
    """A force's name for its arrow label and its energy bar: the LABEL it declares (`spring`,
    `gravity`, `friction`; physics/forces/), else its class name (a plain function: its name)."""
    return getattr(force, "LABEL", "") or getattr(force, "name", "") or type(force).__name__


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


def sampled(model, *, integrator: str | None = None, chain: bool = False) -> tuple[np.ndarray, ...]:
    """r (m), p (kg·m/s) and F_net (N), each (samples, masses, 3), over a short run of the engine
    from the model's start (SCALE_RUN s, at most SCALE_STEPS steps, about 200 samples). With
    chain, the third is (forces + 1, samples, masses, 3): F_net, then where each force drawn tip
    to tail ends (the first force, the first two added, ...), N.

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
    rs, ps, Fs = [], [], []
    for n in range(len(t)):
        if not (np.all(np.isfinite(r[n][kept])) and np.all(np.isfinite(p[n][kept]))):
            break
        rs.append(r[n][kept])
        ps.append(p[n][kept])
        v = velocity(p[n], m)
        ends = np.cumsum(forces_each(model.forces, t[n], r[n], v, m), axis=0)[:, kept] if chain else []
        Fs.append([net_force(model.forces, t[n], r[n], v, m)[kept], *ends])
    Fs = np.moveaxis(np.array(Fs), 1, 0)
    return np.array(rs), np.array(ps), Fs if chain else Fs[0]


def largest(model, *, integrator: str | None = None) -> tuple[float, float]:
    """The largest |p| (kg·m/s) and |F_net| (N) over the short run of `sampled`."""
    _, p, F = sampled(model, integrator=integrator)
    return (float(np.linalg.norm(p, axis=-1).max(initial=0.0)), float(np.linalg.norm(F, axis=-1).max(initial=0.0)))


def _longest_that_fit(camera: Camera, r, q, *, margin: float, face) -> tuple[float, float]:
    """The smallest round scale for q (the longest arrows) at which the picture, widened by at most
    GROW, holds every tip r + q / scale (margin m inside its edge) and no tip goes through the
    support's face (Frame.face: up through the ceiling, back through the wall); and the range
    that needs, m."""
    axis, where, towards = face
    size = float(np.linalg.norm(q, axis=-1).max(initial=0.0))
    if size == 0:
        return 1.0, camera.range
    open_side = (r[..., axis] - where) * towards < 0   # a mass that ran away through the support is not judged

    def needed(unit: float) -> float:
        tips = r + q / unit
        through = np.any(((tips[..., axis] - where) * towards > -margin) & open_side)
        return math.inf if through else camera.range_holding(tips) + margin

    limit = GROW * max(camera.range, camera.range_holding(r) + margin)
    unit = round_scale(size / (0.01 * camera.range))   # arrows a hundredth of the picture: they fit
    if needed(unit) == math.inf:   # even these cross the support: masses that blow up (euler) pass it
        open_side[...] = False     # at speed; such a run is judged on the picture alone
    # no longer than the picture is wide: a run that blows up (euler) holds its huge arrows in
    # the huge picture its masses need, for every scale
    while size / (smaller := round_scale(unit / 2.5 * (1 - 1e-9))) <= 5 * limit and needed(smaller) <= limit:
        unit = smaller
    return unit, max(camera.range, needed(unit))


def choose_scales(model, *, view: dict, integrator: str | None = None, forces: bool = False) -> ArrowScales:
    """One scale for momentum and one for forces, for a run of this model shown in the page's
    picture of it (view: the scene's VIEW with the defaults): the longest arrows at a round scale
    that the picture, widened by at most GROW, holds over the run (_longest_that_fit). The force
    scale fits F_net; with forces (each force drawn, tip to tail) every force's tip too, so a
    hanging mass's spring (176 N at the bottom of `vertical`, where F_net is 78 N) stays in."""
    framed = frame(model, view)
    r, p, F = sampled(model, integrator=integrator, chain=forces)
    if forces:
        r_each, F = np.concatenate([r] * len(F)), np.concatenate(F)
    else:
        r_each = r
    margin = TIP_ROOM * framed.radius
    p_unit, p_range = _longest_that_fit(framed.camera, r, p, margin=margin, face=framed.face())
    F_unit, F_range = _longest_that_fit(framed.camera, r_each, F, margin=margin, face=framed.face())
    return ArrowScales(p_unit=p_unit, F_unit=F_unit, view_range=float(max(p_range, F_range)))

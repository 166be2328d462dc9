"""The resonance curve: steady-state amplitude against driving frequency, for a row of driven springs.

A row of identical damped springs hangs from the ceiling; each is driven by F = F0 cos(ω t) (up and
down) at its own ω, from omega_min on the left to omega_max on the right. After the start-up
transient has died away (it decays like e^(−bt/2m)), each mass swings at its driving frequency
with the steady-state amplitude

    A(ω) = F0 / √((k − m ω²)² + (b ω)²)

largest near ω0 = √(k/m), and the smaller b, the taller and narrower the peak. With b² ≥ 2mk there
is no peak at all (the preset "critical damping", b = 2√(mk), shows this).

The scene IS the sweep: one batch with a spring per (b, ω) pair, a row of `count` springs for each b,
stepped together by the engine (the forces take per-mass b and ω). The page shows every row and
their amplitudes now; a headless run records the measuring window (`settle` to `settle` + a few
periods of the slowest drive) and :func:`extra_json` gives the measured and exact curves, from the
same single run that gives the final state.
"""
from typing import NamedTuple

import numpy as np

from physics.exact import critical_damping, steady_state_amplitude
from physics.forces import Driving, Gravity, LinearDamping, Spring
from physics.simulate import time_grid, trajectory
from physics.state import make_state, velocity

from ._constants import DECLARED, SMALLEST, ConstantError
from ._model import Model
from ._row import MassList, anchors_in_a_row, exact_row, row_anchors, row_loop, row_starts, start_positions

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
m = 1.0                    # kg: mass of each block
k = 25.0                   # N/m: spring constant of each spring
L0 = 1.0                   # m: relaxed length of each spring
g = 9.8                    # m/s²: strength of gravity, acting along −y (it only moves the equilibrium)
F0 = 1.0                   # N: driving force amplitude in F = F0 cos(ω t), up and down
b = 0.5                    # kg/s: damping constant of the row shown (None: critical, b = 2√(mk))
b_ratio = 2.0              # 1: each further resonance curve has b times this
curves = 3                 # 1: number of resonance curves (damping constants b, b·ratio, b·ratio², …)
omega_min = 2.0            # rad/s: driving angular frequency of the leftmost spring
omega_max = 8.0            # rad/s: driving angular frequency of the rightmost spring
count = 13                 # 1: number of springs in each row (driving frequencies per curve, omega_min to omega_max)
spacing = 0.4              # m: distance between neighbouring anchors along x
settle = 40.0              # s: time for the transient to die away before measuring
periods = 3.0              # 1: periods of the slowest driving frequency over which to measure
dt = 0.02                  # s: time step Δt
until = 50.0               # s: how long the row runs in the view and headless
# ---- end of constants ----

MENU_ORDER = 8               # where it stands in --list and the page's scene menu

DRIVE_AXIS = (0.0, 1.0, 0.0)   # F0 cos(ω t) acts up and down, along the springs
SMOOTH_POINTS = 401            # ω values on which extra_json gives the exact curves as lines
# rk4 by default: fourth order, so the measured amplitudes stay far below 1 % from the closed form
# at the default Δt (Euler-Cromer's shadow orbit is tilted by about ωΔt/2, which A = √(x² + (v/ω)²)
# would read as several per cent). --integrator still chooses another method.
DEFAULT_INTEGRATOR = "rk4"
ROW_DEPTH = 1.0                # m: distance between the rows of different b, front to back
BLOCK_VALUES = 2**17           # numbers per array when measuring the amplitudes: 1 MB, kept in the cache


class Sweep(NamedTuple):
    """A measured resonance curve per damping constant.

    omega      driving angular frequencies, (count,) rad/s
    b          damping constants, (curves,) kg/s
    amplitude  measured steady-state amplitudes, (curves, count) m
    exact      F0 / √((k − mω²)² + (bω)²), (curves, count) m
    """

    omega: np.ndarray
    b: np.ndarray
    amplitude: np.ndarray
    exact: np.ndarray


def _whole(name, value, least):
    if value != int(value) or value < least:
        raise ConstantError(f"{name} must be a whole number, {least} or more (got {value:g})")
    return int(value)


def frequency_grid(*, omega_min, omega_max, count) -> np.ndarray:
    """count driving angular frequencies evenly spaced from omega_min to omega_max, rad/s."""
    count = _whole("count", count, 2)
    if not 0 < omega_min < omega_max:
        raise ConstantError(f"need 0 < omega_min < omega_max (got {omega_min:g} and {omega_max:g} rad/s)")
    # ω_min + i·(ω_max − ω_min)/(count − 1): the arithmetic of the program's list (sweep_lists)
    return omega_min + np.arange(count) * ((omega_max - omega_min) / (count - 1))


def damping_values(*, m, k, b, b_ratio, curves) -> np.ndarray:
    """b, b·ratio, b·ratio², … (curves of them), kg/s; b = None means critical, 2√(mk)."""
    if b_ratio <= 0:
        raise ConstantError(f"b_ratio must be greater than 0 (got {b_ratio:g})")
    b = critical_damping(m=m, k=k) if b is None else b
    values = b * b_ratio ** np.arange(_whole("curves", curves, 1), dtype=float)
    largest = DECLARED["b"].high
    if not values[-1] <= largest:  # b·ratio^(curves − 1) must stay a damping constant b may be
        raise ConstantError(f"b_ratio = {b_ratio:g} over {curves:g} curves makes the last b = "
                            f"{values[-1]:.3g} kg/s, more than the {largest:g} kg/s b may be; "
                            f"use a smaller b_ratio or fewer curves")
    if b != 0 and not values[-1] >= SMALLEST:  # nor shrink below what any nonzero b may be
        # b·ratio^(curves − 1) ≥ SMALLEST: ratio ≥ (SMALLEST/b)^(1/(curves − 1)), or fewer curves
        least_ratio = _rounded_up((SMALLEST / b) ** (1.0 / (len(values) - 1)))
        most_curves = 1 + int(np.floor(np.log(SMALLEST / b) / np.log(b_ratio)))
        raise ConstantError(f"b = {b:.3g} kg/s with b_ratio = {b_ratio:g} over {curves:g} curves makes "
                            f"the last b = {values[-1]:.3g} kg/s, less than the {SMALLEST:g} kg/s a "
                            f"nonzero b may be; use b_ratio = {least_ratio:g} or more, or at most "
                            f"{most_curves} curves")
    return values


def sweep_lists(*, b) -> tuple:
    """damping_values and frequency_grid as lists of the program, row by row and along each row:
    b·b_ratio^row (b_c = 2√(mk) where b is None) and ω from omega_min to omega_max in count steps."""
    first = "b" if b is not None else "b_c"
    critical = () if b is not None else (("b_c = 2*sqrt(m*k)", "kg/s: critical damping, 2√(mk)"),)
    return (MassList("b", f"row by row: {first}, {first}·b_ratio, {first}·b_ratio², …",
                     each=f"{first}*b_ratio**row", before=critical),
            MassList("omega", "from omega_min to omega_max along each row", each="omega_min + col*omega_step",
                     before=(("omega_step = (omega_max - omega_min)/(count - 1)",
                              "rad/s: from one spring's drive to the next"),)))


def _rounded_up(x: float) -> float:
    """x rounded up to 3 significant figures, so that the value printed still works."""
    scale = 10.0 ** (np.floor(np.log10(x)) - 2)
    return float(np.ceil(x / scale * (1 - 1e-12)) * scale)


def _grid(*, m, k, b, b_ratio, curves, omega_min, omega_max, count):
    """Every (b, ω) pair of the sweep, curve by curve: b_all and ω_all, (curves × count,) each."""
    omega = frequency_grid(omega_min=omega_min, omega_max=omega_max, count=count)
    b_each = damping_values(m=m, k=k, b=b, b_ratio=b_ratio, curves=curves)
    return omega, b_each, np.tile(omega, len(b_each)), np.repeat(b_each, len(omega))


def _grid_of(values):
    """_grid for a scene's constants."""
    return _grid(**{key: values[key] for key in (
        "m", "k", "b", "b_ratio", "curves", "omega_min", "omega_max", "count")})


def curve_amplitude(values, *, b, omega):
    """The steady-state amplitude |A| = |F0| / √((k − mω²)² + (bω)²) of the scene's springs, m: a
    size, like the measured A = √(x² + (v/ω)²), whatever the sign of F0 (inf at undamped resonance)."""
    return np.abs(steady_state_amplitude(m=values["m"], k=values["k"], b=b, F0=values["F0"], omega=omega))


def build(*, m, k, L0, g, F0, b, b_ratio, curves, omega_min, omega_max, count, spacing, settle,
          periods, dt, until):
    """One driven, damped spring per (b, ω) pair: a row of `count` springs for each b, one row
    behind the other. This one batch is the whole sweep: the browser shows it, and a headless run
    measures the amplitudes from the same steps (:func:`amplitudes`)."""
    omega, b_each, omega_all, b_all = _grid(m=m, k=k, b=b, b_ratio=b_ratio, curves=curves,
                                            omega_min=omega_min, omega_max=omega_max, count=count)
    row = anchors_in_a_row(count=count, spacing=spacing)
    loop = row_loop(count=count, count_name="count", rows_name="curves")
    depth = np.repeat(np.arange(len(b_each)) * ROW_DEPTH, count)
    anchors = np.tile(row, (len(b_each), 1)) - depth[:, None] * np.array([0.0, 0.0, 1.0])
    r0 = start_positions(anchors=anchors, L0=L0, m=m, k=k, g=g, x0=0.0)
    forces = [Spring(k=k, L0=L0, anchor=anchors), LinearDamping(b=b_all),
              Driving(F0=F0, omega=omega_all, axis=DRIVE_AXIS)]
    if g:
        forces.append(Gravity(g=g))
    return Model(
        state=make_state(r=r0, m=m),
        forces=tuple(forces),
        dt=float(dt),
        until=float(until),
        **exact_row(forces=forces, r0=r0, m=m),
        anchors=anchors,
        labels=tuple(f"b = {b_j:.3g} kg/s, ω = {w:.3g} rad/s" for b_j, w in zip(b_all, omega_all)),
        default_integrator=DEFAULT_INTEGRATOR,
        per_mass=loop.then(row_anchors(loop, count=count, count_name="count", row_depth=ROW_DEPTH),
                           row_starts(k=k, x0_name=""), *sweep_lists(b=b)),
    )


def measure_window(values) -> tuple[float, float]:
    """When the amplitudes are measured, s: from `settle` for `periods` periods of the slowest drive."""
    return values["settle"], values["settle"] + values["periods"] * 2 * np.pi / values["omega_min"]


def amplitude_now(model, state) -> np.ndarray:
    """A = √(x² + (v/ω)²) of every mass at this instant, m (x from the equilibrium it started at).

    For a steady swing x = A cos(ωt − δ) this equals A at every instant (cos² + sin² = 1), so the
    measurement does not depend on catching the sampled peak; a transient left makes it wobble.
    """
    omega = declared_per_mass(model, "omega")
    x = state.r[..., 1] - model.state.r[:, 1]
    v = velocity(state.p[..., 1:2], model.state.m)[..., 0]     # only v_y: the swing is along y
    return np.sqrt(x**2 + (v / omega) ** 2)


def amplitudes(setup, model, trajectory) -> Sweep | None:
    """The sweep measured from a run's recorded steps: the largest A over the measuring window.

    None if the run did not reach the end of the window (until < settle + the periods).
    """
    v = setup.values
    start, end = measure_window(v)
    inside = np.flatnonzero((trajectory.t >= start - 1e-9 * v["dt"]) & (trajectory.t <= end + v["dt"]))
    if trajectory.t[-1] < end or not inside.size:
        return None
    measured = _largest_amplitude(model, trajectory, first=inside[0], last=inside[-1])
    omega, b_each, omega_all, b_all = _grid_of(v)
    shape = (len(b_each), len(omega))
    exact = curve_amplitude(v, b=b_all, omega=omega_all)
    return Sweep(omega=omega, b=b_each, amplitude=measured.reshape(shape), exact=exact.reshape(shape))


def _largest_amplitude(model, trajectory, *, first: int, last: int) -> np.ndarray:
    """The largest amplitude_now of each mass over the recorded samples first to last, (N,) m.

    Worked out a block of samples at a time, each about BLOCK_VALUES numbers per array, so that no
    array as large as the whole window ((samples, N): 38 MB at 10⁴ masses) is ever made.
    """
    State = type(model.state)
    per_block = max(1, BLOCK_VALUES // model.state.count)
    largest = None
    for start in range(first, last + 1, per_block):
        block = slice(start, min(start + per_block, last + 1))     # the times are in order: no copy
        A = amplitude_now(model, State(t=trajectory.t[block], r=trajectory.r[block], p=trajectory.p[block],
                                       m=trajectory.m)).max(axis=0)
        largest = A if largest is None else np.maximum(largest, A, out=largest)
    return largest


def sweep(setup, *, integrator=None) -> Sweep:
    """Run the scene's batch to the end of the measuring window and measure every amplitude."""
    model = setup.build()
    engine = model.simulation(integrator)
    start, end = measure_window(setup.values)
    samples = engine.run_until(end, record=time_grid(model.dt, t0=0.0, dt=model.dt, start=start, end=end))
    return amplitudes(setup, model, trajectory(engine, samples, with_energy=False))


def extra_json(result) -> dict:
    """The resonance curves for headless --json, measured from the run itself: the ω grid, and
    measured and exact amplitudes per b. The exact curves are also given on a fine grid
    ("smooth_..."), for drawing them as lines. Where the run stopped before the measuring window
    ended, the measured amplitudes are null and "amplitude_note" says why. Where b = 0 and ω = ω0
    there is no steady state (the swing grows without bound): the exact amplitude is null there,
    and "exact_amplitude_note" says so.
    """
    v = result.setup.values
    measured = amplitudes(result.setup, result.model, result.trajectory)
    omega, b_each, omega_all, b_all = _grid_of(v)
    exact = curve_amplitude(v, b=b_all, omega=omega_all)
    smooth = np.linspace(v["omega_min"], v["omega_max"], SMOOTH_POINTS)
    out = {
        "omega_rad_per_s": omega.tolist(),
        "b_kg_per_s": b_each.tolist(),
        "amplitude_m": None if measured is None else measured.amplitude.tolist(),
        "exact_amplitude_m": _null_if_unbounded(exact.reshape(len(b_each), len(omega))),
        "smooth_omega_rad_per_s": smooth.tolist(),
        "smooth_exact_amplitude_m": [_null_if_unbounded(curve_amplitude(v, b=b_j, omega=smooth))
                                     for b_j in b_each],
    }
    if any(None in line for line in out["exact_amplitude_m"] + out["smooth_exact_amplitude_m"]):
        out["exact_amplitude_note"] = f"null where {_unbounded_words(v)}"
    if measured is None:
        start, end = measure_window(v)
        out["amplitude_note"] = (f"the amplitudes are measured from t = {start:g} s to {end:.4g} s; "
                                 f"run until at least {end:.4g} s (--until or --set until=...)")
    return {"resonance": out}


def extra_text(result) -> str:
    """The resonance curves for the headless report: a table of A against ω, measured from the run
    and exact, one pair of columns per b (the numbers --json gives, as a teacher reads them)."""
    v = result.setup.values
    measured = amplitudes(result.setup, result.model, result.trajectory)
    omega, b_each, omega_all, b_all = _grid_of(v)
    exact = curve_amplitude(v, b=b_all, omega=omega_all).reshape(len(b_each), len(omega))
    start, end = measure_window(v)
    if measured is None:
        return (f"amplitudes: none, the run ended before the measuring window (t = {start:g} s to "
                f"{end:.4g} s) did; run until at least {end:.4g} s (--until or --set until=...)")

    def shown(A):
        return f"{A:.4g}" if np.isfinite(A) else "unbounded"
    heads = [f"b = {b_j:.4g} kg/s" for b_j in b_each]
    width = max(9, *(len(head) for head in heads))
    lines = [f"steady-state amplitude A (m) against the driving frequency ω, measured from t = {start:g} s "
             f"to {end:.4g} s; exact A = F0 / √((k − m ω²)² + (b ω)²)",
             f"{'ω (rad/s)':<10}" + "".join(f"  {head:<{2 * width + 1}}" for head in heads),
             f"{'':<10}" + "".join(f"  {'measured':<{width}} {'exact':<{width}}" for _ in heads)]
    for n, omega_n in enumerate(omega):
        lines.append(f"{omega_n:<10.4g}" + "".join(
            f"  {shown(measured.amplitude[j, n]):<{width}} {shown(exact[j, n]):<{width}}"
            for j in range(len(b_each))))
    if not np.all(np.isfinite(exact)):
        lines.append(f"unbounded where {_unbounded_words(v)}")
    return "\n".join(line.rstrip() for line in lines)


def _unbounded_words(v) -> str:
    """Why A(ω) has no value at undamped resonance, in words, for the constants v."""
    omega0 = np.sqrt(v["k"] / v["m"])
    return (f"b = 0 and ω = ω0 = √(k/m) = {omega0:.4g} rad/s: undamped resonance has no steady state, "
            f"the swing grows by F0/(2 m ω0) = {abs(v['F0']) / (2 * v['m'] * omega0):.3g} m every second "
            f"without bound")


def _null_if_unbounded(A) -> list:
    """A as (nested) lists, with None (JSON null) where it is unbounded (undamped resonance)."""
    return np.where(np.isfinite(A), A, None).tolist()


def rows(model) -> np.ndarray:
    """Which row each spring is in, 0 for the front one: row j has the j-th b (b·ratio^j), j·ROW_DEPTH
    behind the front. The view draws row j's springs in the colour of curve j on the resonance
    graph, the line of their b (export/palette.py's mass_colours)."""
    return np.rint(-model.anchors[:, 2] / ROW_DEPTH).astype(int)


def graphed(model) -> list[int]:
    """The springs the position graph shows: in each row, the one driven nearest ω0 = √(k/m), at
    resonance, so the graph compares how far each b lets it swing (39 curves made a solid band)."""
    m = model.state.m.ravel()
    k, omega = declared_per_mass(model, "k"), declared_per_mass(model, "omega")
    row = rows(model)
    return [int(min(np.flatnonzero(row == j), key=lambda i: abs(omega[i] - np.sqrt(k[i] / m[i]))))
            for j in sorted(set(row.tolist()))]


def declared_per_mass(model, name: str) -> np.ndarray:
    """The constant `name` (k, ω) of the model's force that declares it in its CONSTANTS, one value
    per mass, (N,): read from the force's declaration (Force.program_values), whatever its kind."""
    value = next(force.program_values()[name] for force in model.forces if name in force.CONSTANTS)
    return np.broadcast_to(np.asarray(value, dtype=float).ravel(), (model.state.count,))


def view_graph(setup) -> dict:
    """The page's resonance graph (browser/graphs.py): amplitude against driving frequency.

    For each b, the exact A(ω) = F0/√((k − mω²)² + (bω)²) as a line, curve j in the palette's
    colour j (the colour of the row of springs with that b). On top, every spring of the
    batch shown in 3-D: its A = √(x² + (v/ω)²) at this instant, as dots that wobble while the
    start-up transient lasts and settle onto their b's line as it dies away (like e^(−bt/2m)).
    Nothing is run twice: the dots are the very springs the page steps.

    With b = 0 there is no steady state at ω0 (the swing grows without bound): that b's line runs
    up to the top of the graph there, and its label says why.
    """
    v = setup.values
    omega, b_each, *_ = _grid_of(v)
    smooth = np.linspace(v["omega_min"], v["omega_max"], SMOOTH_POINTS)
    exacts = [curve_amplitude(v, b=b_j, omega=smooth) for b_j in b_each]
    top = 1.15 * float(max(np.max(A, initial=0.0, where=np.isfinite(A)) for A in exacts))
    lines = []
    for j, (b_j, exact) in enumerate(zip(b_each, exacts)):
        label = f"b = {b_j:.3g} kg/s"
        if not np.all(np.isfinite(exact)):
            label += f" (unbounded at ω0 = {np.sqrt(v['k'] / v['m']):.3g} rad/s: no steady state)"
            exact = np.where(np.isfinite(exact), exact, top)
        lines.append((label, smooth, exact, j))
    omega_all = np.tile(omega, len(b_each))

    def live(model, state):
        return omega_all, amplitude_now(model, state)

    return {"title": "Amplitude: lines exact, dots the springs now",
            "xtitle": "driving angular frequency ω (rad/s)", "ytitle": "amplitude A (m)",
            "xmin": float(v["omega_min"]), "xmax": float(v["omega_max"]), "ymin": 0.0, "ymax": top,
            "lines": lines, "dots": [],
            "live": live, "live_label": "springs now"}



def beat_period(values) -> float:
    """π/Δω, s: how often the total energy of the batch repeats once the transient has gone.

    In the steady state each spring swings as x = A cos(ωt − δ), so its energy
    E = ½ A² (k cos²(ωt − δ) + m ω² sin²(ωt − δ)) rises and falls twice a swing, at 2ω (unless
    k = mω²). The drives are Δω = (ω_max − ω_min)/(count − 1) apart, so two springs' rises and
    falls differ in phase by 2(ω_i − ω_j)t, a whole multiple of 2π every π/Δω: then they all come
    back in step, and the sum spikes. The spikes of the energy graph are this beat, not energy
    gained. (With ω_min a whole multiple of Δω, as by default, 2 = 4 × 0.5 rad/s, the steady
    total energy repeats exactly with this period.)
    """
    step = (values["omega_max"] - values["omega_min"]) / (values["count"] - 1)
    return float(np.pi / step)


def energy_note(setup) -> str:
    """The line under the page's energy graph: what its spikes are (beat_period)."""
    v = setup.values
    step = (v["omega_max"] - v["omega_min"]) / (v["count"] - 1)
    return (f"Spikes every π/Δω = {beat_period(v):.3g} s: each spring's energy rises and falls twice a "
            f"swing, and the springs, driven Δω = {step:.3g} rad/s apart, do so in step again then.")


# The resonance graph shows the amplitudes; each spring's exact curve would only crowd the position graph.
# Each row of springs in the colour of its b's line (rows).
VIEW = {"support": "ceiling", "plot": "y", "trail": False, "exact": False, "sliders": ["m"],
        "rows": rows, "graphed": graphed, "energy_note": energy_note}

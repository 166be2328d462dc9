"""The closed form on a whole row at once (physics.exact on arrays) is the one-mass closed form,
mass by mass, bit for bit, and it is right: it matches a fine rk4 run of the same row.

The row mixes every case the closed form tells apart: under-, critically and over-damped masses,
undamped resonance (b = 0, ω = ω0, where x_p = F0 t sin(ω0 t) / (2 m ω0) grows), b = 0 off
resonance, F0 = 0, and per-mass m and k.
"""
import numpy as np
import pytest

from physics import exact
from physics.simulate import run
from scenes import catalog

# (m kg, k N/m, b kg/s, x0 m, v0 m/s, F0 N, ω rad/s): one mass per row
MIX = np.array([
    (1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0),           # under-damped, free
    (1.0, 1.0, 2.0, 1.0, -0.5, 0.0, 0.0),          # critically damped: b² = 4mk
    (1.0, 1.0, 2.0 * (1 + 1e-12), 0.3, 0.2, 0.0, 0.0),   # critical to round-off (damping_regime's rtol)
    (1.0, 1.0, 5.0, -0.7, 1.0, 0.0, 0.0),          # over-damped
    (1.0, 25.0, 0.0, 0.0, 0.0, 1.0, 5.0),          # undamped resonance: ω = ω0 = 5 rad/s
    (4.0, 100.0, 0.0, 1.0, 0.0, 1.0, 5.0),         # undamped resonance from x0 = 1 m (the page's scenario 2)
    (1.0, 25.0, 0.0, 0.0, 0.0, 0.0, 5.0),          # b = 0, ω = ω0 but no drive: stays at rest
    (1.0, 25.0, 0.0, 0.2, 0.0, 1.0, 3.0),          # b = 0 off resonance
    (2.0, 8.0, 4.0, 0.0, 0.3, 3.0, 6.0),           # driven, far above resonance
    (1.0, 25.0, 0.5, 0.0, 0.0, 1.0, 5.0),          # driven at resonance, damped
    (0.5, 50.0, 30.0, 0.1, 0.0, -0.5, 9.5),        # over-damped and driven
    (1.0, 16.0, 8.0, 0.4, -1.0, 2.0, 1.5),         # critically damped and driven
])
NAMES = ("m", "k", "b", "x0", "v0", "F0", "omega")


def each_mass():
    return [dict(zip(NAMES, row)) for row in MIX]


def test_the_mix_has_every_case():
    regimes = {exact.damping_regime(m=p["m"], k=p["k"], b=p["b"]) for p in each_mass()}
    assert regimes == {"under-damped", "critically damped", "over-damped"}
    resonant = exact.undamped_resonance(m=MIX[:, 0], k=MIX[:, 1], b=MIX[:, 2], omega=MIX[:, 6])
    assert resonant.sum() == 3 and np.any(resonant & (MIX[:, 5] == 0))


def test_oscillator_on_a_row_is_the_one_mass_oscillator_mass_by_mass():
    t = np.linspace(0.0, 12.0, 241)
    x, v = exact.oscillator(t[:, None], **dict(zip(NAMES, MIX.T)))
    assert x.shape == v.shape == (len(t), len(MIX))
    for i, p in enumerate(each_mass()):
        x_i, v_i = exact.oscillator(t, **p)
        np.testing.assert_array_equal(x[:, i], x_i, err_msg=str(p))
        np.testing.assert_array_equal(v[:, i], v_i, err_msg=str(p))
    assert np.all(x[:, 6] == 0) and np.all(v[:, 6] == 0)        # F0 = 0 at ω0: never moves


def test_oscillator_on_a_row_matches_a_fine_rk4_run_of_the_row(line_oscillators):
    state, forces = line_oscillators(**dict(zip(NAMES, MIX.T)))
    trajectory = run(state, forces, dt=0.001, until=4.0, integrator="rk4")
    x, v = exact.oscillator(trajectory.t[:, None], **dict(zip(NAMES, MIX.T)))
    np.testing.assert_allclose(trajectory.r[:, :, 0], x, atol=1e-9)
    np.testing.assert_allclose(trajectory.v[:, :, 0], v, atol=1e-8)


def test_oscillator_warns_of_nothing_on_a_mixed_row():
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")        # no sqrt of a negative, no 0/0 in a regime not taken
        x, v = exact.oscillator(np.linspace(0, 5, 11)[:, None], **dict(zip(NAMES, MIX.T)))
    assert np.all(np.isfinite(x)) and np.all(np.isfinite(v))


# A row of springs, each from its own anchor: hanging and on lines in 3-D, with masses that have no
# closed form (quadratic drag; a sideways push; started at the anchor itself).
ROW = dict(m=2.0, k=8.0, g=9.8, drive_axis=(0.0, 1.0, 0.0),
           anchors=[(0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0), (4, 0, 0), (5, 0, 0), (6, 1, 0), (7, 0, 0)],
           r0=[(0, -1.5, 0), (1, -2.5, 0), (2, -1.2, 0), (3, -1.5, 0), (4, -1.5, 0), (5, -1.0, 0), (6, 1, 0),
               (7, 0.5, 0)],
           v0=[(0, 0, 0), (0, 0.5, 0), (0, -1, 0), (0, 0, 0), (0.3, 0, 0), (0, 0, 0), (0, 0, 0), (0, 1, 0)],
           b=[0.5, 8.0, 20.0, 0.0, 0.5, 0.0, 0.5, 1.0],      # under, critical (b² = 4mk), over, undamped
           C=[0, 0, 0, 0, 0, 0.4, 0, 0],
           F0=[0.0, 1.0, 2.0, 1.0, 0.0, 1.0, 1.0, 0.5],
           omega=[0.0, 1.0, 3.0, 2.0, 0.0, 2.0, 2.0, 2.5])   # ω0 = 2 rad/s: mass 3 at undamped resonance


def single(row, i):
    """The one-mass arguments of mass i of a row."""
    per_mass = ("b", "C", "F0", "omega")
    return {**{key: row[key] for key in ("m", "k", "L0", "g", "drive_axis")},
            **{key: row[key][i] for key in per_mass}, "anchor": row["anchors"][i], "r0": row["r0"][i],
            "v0": row["v0"][i]}


@pytest.mark.parametrize("L0", [0.0, 1.0])
def test_row_motion_is_single_mass_motion_mass_by_mass(L0):
    row = {**ROW, "L0": L0}
    known, motion = exact.row_motion(**row)
    t = np.linspace(0.0, 6.0, 61)
    r, v = motion(t)
    assert r.shape == v.shape == (len(t), len(row["r0"]), 3)
    for i in range(len(row["r0"])):
        alone = exact.single_mass_motion(**single(row, i))
        assert known[i] == (alone is not None), i
        if alone is None:
            assert np.all(np.isnan(r[:, i])) and np.all(np.isnan(v[:, i]))
            continue
        r_i, v_i = alone(t)
        np.testing.assert_array_equal(r[:, i], r_i, err_msg=str(i))
        np.testing.assert_array_equal(v[:, i], v_i, err_msg=str(i))
    # C ≠ 0 has none; on a line (L0 > 0) neither has the sideways push nor the mass at its anchor
    assert known.tolist() == ([True] * 5 + [False] + [True] * 2 if L0 == 0 else
                              [True] * 4 + [False, False, False, True])


def test_the_resonance_row_is_worked_out_without_a_closed_form_per_mass(monkeypatch):
    """The 10⁴-mass sweep's exact answers (headless --json) and their validity come from the row's
    closed form at once: no mass's own closed form is made (none of them swings far enough to reach
    its anchor: |x| ≤ 0.8 m < s_eq = 1.39 m, physics.exact.displacement_bound)."""
    import scenes._row as row_module
    made = []
    one_mass = row_module.single_mass_motion
    monkeypatch.setattr(row_module, "single_mass_motion", lambda **p: made.append(p) or one_mass(**p))
    model = catalog.configure("resonance", assignments=["count=10000", "curves=1"]).build()
    r, v = model.exact_where_valid([50.0])
    assert r.shape == (1, 10000, 3) and np.all(np.isfinite(r))
    assert np.all(model.exact_valid_until_each(50.0) == np.inf)
    assert made == []
    # undamped (b = 0): only the masses driven near ω0 may reach their anchors, and only they are searched
    model = catalog.configure("resonance", assignments=["count=1000", "curves=1", "b=0"]).build()
    until = model.exact_valid_until_each(50.0)
    assert 0 < np.sum(until < 50.0) <= len(made) < 100


def test_lengths_are_numpys_norm_of_each_row_bit_for_bit():
    rng = np.random.default_rng(7)
    vectors = rng.normal(size=(5000, 3)) * rng.uniform(1e-3, 1e3, size=(5000, 1))
    np.testing.assert_array_equal(exact.lengths(vectors), [np.linalg.norm(a) for a in vectors])


"""The batch speed-ups of issue 16 (row_dot, Driving's kept cosines, rk4's in-place sums) change no bit:
each is compared with the plain numpy expression it replaced."""
from __future__ import annotations

import numpy as np
import pytest

from physics.forces import Driving, LinearDamping, Spring, net_force
from physics.rows import magnitude, row_dot
from physics.integrators import rk4
from physics.state import State, make_state, velocity


def _batch(N=500, seed=7):
    rng = np.random.default_rng(seed)
    anchors = rng.normal(size=(N, 3))
    forces = (Spring(k=25.0, L0=1.0, anchor=anchors), LinearDamping(b=rng.uniform(0, 1, N)),
              Driving(F0=1.0, omega=rng.uniform(2, 8, N), axis=(1.0, 0.0, 0.0)))
    state = make_state(r=anchors + rng.normal(size=(N, 3)), v=rng.normal(size=(N, 3)), m=rng.uniform(0.5, 2, N))
    return state, forces


def test_row_dot_and_magnitude_equal_the_sum_along_the_last_axis():
    rng = np.random.default_rng(1)
    for a in (rng.normal(size=(1000, 3)), np.asfortranarray(rng.normal(size=(1000, 3))), rng.normal(size=(5, 7, 3)),
              rng.normal(size=(10, 1))):
        b = rng.normal(size=a.shape)
        assert np.array_equal(row_dot(a, b), (a * b).sum(axis=-1))
        assert np.array_equal(magnitude(a), np.sqrt((a * a).sum(axis=-1, keepdims=True)))


def test_driving_gives_the_same_force_when_asked_again_and_fresh():
    _, forces = _batch()
    drive = forces[2]
    r = np.zeros((500, 3))
    for t in (0.0, 0.25, 0.5, 0.25, 1e-3, 0.0, 7.75, 0.5, 0.25):
        expected = np.multiply(drive.F0 * np.cos(drive.omega * t), drive.axis)
        assert np.array_equal(drive(t, r, None, None), expected)


def test_rk4_equals_the_textbook_expression_bit_for_bit():
    state, forces = _batch()
    t, r, p, m, dt = state.t, state.r, state.p, state.m, 0.02
    for _ in range(20):
        def slopes(t_, r_, p_):
            v_ = velocity(p_, m)
            return v_, net_force(forces, t_, r_, v_, m)
        half = 0.5 * dt
        dr1, dp1 = slopes(t, r, p)
        dr2, dp2 = slopes(t + half, r + dr1 * half, p + dp1 * half)
        dr3, dp3 = slopes(t + half, r + dr2 * half, p + dp2 * half)
        dr4, dp4 = slopes(t + dt, r + dr3 * dt, p + dp3 * dt)
        expected_r = r + (dr1 + 2 * dr2 + 2 * dr3 + dr4) * (dt / 6.0)
        expected_p = p + (dp1 + 2 * dp2 + 2 * dp3 + dp4) * (dt / 6.0)
        new = rk4(State(t=t, r=r, p=p, m=m), forces, dt)
        assert np.array_equal(new.r, expected_r) and np.array_equal(new.p, expected_p)
        t, r, p = new.t, new.r, new.p


def _window_run(count=600, steps=60):
    """A resonance batch of `count` springs, every step recorded: more numbers than one energy block."""
    from physics.recording import every
    from scenes import configure
    model = configure("resonance", assignments=[f"count={count}", "curves=1"]).build()
    engine = model.simulation(None)
    return engine, engine.advance(steps, record=every(1))


def test_energy_series_in_blocks_is_the_whole_arrays_bit_for_bit():
    """physics.energy.series works out many samples a block at a time: the same bits as all at once."""
    from physics import energy
    from physics.recording import trajectory
    engine, samples = _window_run()
    traj = trajectory(engine, samples, with_energy=False)
    assert traj.r.size > energy.SERIES_BLOCK
    state = State(t=traj.t, r=np.ascontiguousarray(traj.r), p=np.ascontiguousarray(traj.p), m=traj.m)
    blocked = energy.series(state, engine.forces, traj.work)
    whole = energy._series(state, engine.forces, traj.work)
    assert blocked.keys() == whole.keys()
    for key in whole:
        assert blocked[key].shape == (len(traj.t),)
        assert np.array_equal(blocked[key].view(np.int64), whole[key].view(np.int64)), key


def test_trajectory_puts_the_start_in_the_recorded_rows_with_the_same_numbers():
    """trajectory() writes the start into the samples' free first row instead of copying every
    sample: r, p, W_nc and the energies equal those of the copying path, and the samples are unchanged."""
    import dataclasses
    from physics.recording import trajectory
    engine, samples = _window_run()
    kept = {name: np.array(getattr(samples, name)) for name in ("t", "r", "p", "work")}
    copied = trajectory(engine, dataclasses.replace(samples, rows=None))
    in_place = trajectory(engine, samples)
    assert np.shares_memory(in_place.r, samples.rows) and not np.shares_memory(copied.r, samples.rows)
    for name in ("t", "r", "p", "work"):
        assert np.array_equal(getattr(in_place, name), getattr(copied, name)), name
        assert np.array_equal(getattr(samples, name), kept[name]), name
    assert np.array_equal(in_place.r[0], engine.start.r) and np.array_equal(in_place.p[0], engine.start.p)
    assert not in_place.work[0].any()
    for key in copied.energy:
        assert np.array_equal(in_place.energy[key], copied.energy[key]), key


@pytest.mark.parametrize("stride, steps", [(1, 3000), (7, 3000), (1000, 2500)])
def test_every_n_is_kept_in_one_array_made_beforehand_with_the_same_rows(monkeypatch, stride, steps):
    """every(n) knows how many rows it keeps: the recorder writes them into one array made before
    the run (no block arrays copied at the end); the rows are those of the block-by-block path."""
    from physics import recording
    from scenes import configure

    def record(prepared):
        monkeypatch.setattr(recording, "PREPARED_NUMBERS", prepared)
        engine = configure("damped", assignments=["dt=0.001"]).build().simulation(None)
        return engine.advance(steps, record=recording.every(stride))
    kept, blocks = record(1 << 25), record(0)
    assert len(kept) == len(blocks) == len(range(stride, steps + 1, stride)) + (steps % stride != 0)
    assert kept.rows.base is not None and blocks.rows.base is None     # a view of the prepared array
    for name in ("t", "r", "p", "work"):
        assert np.array_equal(getattr(kept, name), getattr(blocks, name)), name


def test_the_energy_of_a_few_samples_is_those_samples_of_the_whole_series():
    """A report of the start and the end asks energy_at; a CSV file reads every sample's energy.
    Both are the same numbers, bit for bit, and the whole series is worked out only when asked."""
    from physics.forces import Gravity, QuadraticDrag
    from physics.recording import every, trajectory
    from physics.simulate import Simulation
    from physics.state import make_state
    state = make_state(r=[(0.0, -1.5, 0.0), (1.0, -1.2, 0.3)], v=[(0.1, 0.0, 0.0), (0.0, 0.2, 0.1)], m=[10.0, 2.0])
    forces = (Spring(k=40.0, L0=1.0, anchor=[(0, 0, 0), (1, 0, 0)]), Gravity(g=9.8), LinearDamping(b=1.0),
              QuadraticDrag(C=0.5, A=0.1, rho=1.2), Driving(F0=2.0, omega=3.0))
    engine = Simulation(state, forces, dt=0.01)
    traj = trajectory(engine, engine.advance(500, record=every(7)))
    few = traj.energy_at([0, -1])
    assert "energy" not in traj.__dict__, "energy_at alone must not work out the whole series"
    whole = traj.energy
    assert set(few) == set(whole) == {"K", "U", "E", "W_nc", "E_minus_W_nc"}
    for key in whole:
        assert few[key].tobytes() == whole[key][[0, -1]].tobytes(), key
        assert traj.energy_at([-1])[key].tobytes() == whole[key][-1:].tobytes(), key
    assert trajectory(engine, engine.advance(5), with_energy=False).energy is None

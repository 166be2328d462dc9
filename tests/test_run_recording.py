"""physics.simulate.run can record every n-th step, or only the final state (record_every).

The steps are the same whatever is recorded, so the recorded rows must equal the matching rows
of a run that records every step, bit for bit, energy included (W_nc is still summed every step).
"""
import numpy as np
import pytest

from physics.forces import Driving, Gravity, LinearDamping, Spring
from physics.simulate import BlowUpError, run
from physics.state import make_state


def _system():
    rng = np.random.default_rng(3)
    forces = (Spring(k=40.0, L0=1.0), Gravity(g=9.8), LinearDamping(b=rng.uniform(0, 2, 5)),
              Driving(F0=1.0, omega=2.0))
    return make_state(r=rng.uniform(-2, 2, (5, 3)), m=rng.uniform(1, 10, 5)), forces


@pytest.mark.parametrize("every", [1, 3, 7, 1000])
@pytest.mark.parametrize("with_energy", [False, True])
def test_recording_every_nth_step_keeps_exactly_those_rows(every, with_energy):
    state, forces = _system()
    full = run(state, forces, dt=0.01, until=1.0, with_energy=with_energy)          # 100 steps
    some = run(state, forces, dt=0.01, until=1.0, with_energy=with_energy, record_every=every)
    rows = sorted(set(range(0, 101, every)) | {100})
    np.testing.assert_array_equal(some.t, full.t[rows])
    np.testing.assert_array_equal(some.r, full.r[rows])
    np.testing.assert_array_equal(some.p, full.p[rows])
    if with_energy:
        for key in full.energy:
            np.testing.assert_array_equal(some.energy[key], full.energy[key][rows])


def test_recording_only_the_final_state():
    state, forces = _system()
    full = run(state, forces, dt=0.01, until=1.0, with_energy=True)
    final = run(state, forces, dt=0.01, until=1.0, with_energy=True, record_every=None)
    assert final.r.shape == (2,) + state.r.shape
    np.testing.assert_array_equal(final.t, full.t[[0, -1]])
    np.testing.assert_array_equal(final.r, full.r[[0, -1]])
    np.testing.assert_array_equal(final.final.p, full.final.p)
    np.testing.assert_array_equal(final.energy["E_minus_W_nc"], full.energy["E_minus_W_nc"][[0, -1]])
    still = run(state, forces, dt=0.01, until=0.0, record_every=None)
    np.testing.assert_array_equal(still.r, state.r[None])


@pytest.mark.parametrize("bad", [0, -2, 1.5, "3", True])
def test_record_every_must_be_a_whole_number_at_least_one(bad):
    state, forces = _system()
    with pytest.raises(ValueError, match="record_every"):
        run(state, forces, dt=0.01, until=0.1, record_every=bad)


def test_a_run_that_records_little_still_catches_a_blow_up():
    state = make_state(r=(1.0, 0.0, 0.0), m=1.0)
    with pytest.raises(BlowUpError, match="ω·dt < 2"):
        run(state, (Spring(k=4.0, L0=0.0),), dt=1.05, until=300.0, record_every=None)


def test_the_final_state_continues_the_run_exactly():
    """Running 0 → 0.5 s, then on from .final to 1 s, is the same run as 0 → 1 s in one go."""
    state, forces = _system()
    whole = run(state, forces, dt=0.01, until=1.0, record_every=None)
    half = run(state, forces, dt=0.01, until=0.5, record_every=None).final
    assert half.r.flags.f_contiguous                       # the layout make_state uses
    np.testing.assert_array_equal(run(half, forces, dt=0.01, until=1.0).final.r, whole.final.r)

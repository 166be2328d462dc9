"""Properties that hold for every physical choice of m, k, b and start: checked by hypothesis.

Energy bound. Undamped, Euler-Cromer keeps Q = ω²x² + v² − ω²Δt x v exactly constant (its
"shadow" energy; the true energy ½kx² + ½mv² wobbles around it). On the ellipse Q = Q0 the largest
|x| is √(Q0 / (ω²(1 − (ωΔt/2)²))), and Q0 ≤ (ω²x0² + v0²)(1 + ωΔt/2), so the motion never leaves

    |x| ≤ A0 / √(1 − ωΔt/2),    A0 = √(2 E0 / k) = √(x0² + (v0/ω)²),

the amplitude its starting energy allows, give or take that small factor. Damping only takes energy
away, as long as its own explicit step is stable too: b Δt / m < 1.

Equilibrium. A mass at rest where the spring balances gravity, L0 + m g / k below the anchor,
feels F_net = 0 and stays there, whatever the method (with Δt inside its stability limits, or the
round-off in F_net = 0 grows).
"""
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from physics.forces import Gravity, LinearDamping, QuadraticDrag, Spring
from physics.integrators import INTEGRATORS
from physics.simulate import run
from physics.state import make_state

FAST = settings(max_examples=30, deadline=None)
masses = st.floats(0.1, 100.0)
stiffnesses = st.floats(0.1, 1000.0)


@FAST
@given(m=masses, k=stiffnesses, zeta=st.one_of(st.just(0.0), st.floats(0.0, 3.0)),
       omega_dt=st.floats(0.05, 1.0), x0=st.floats(-2.0, 2.0), v0_over_omega=st.floats(-2.0, 2.0))
def test_euler_cromer_motion_stays_within_its_energy_bound(m, k, zeta, omega_dt, x0, v0_over_omega,
                                                          line_oscillators):
    omega = np.sqrt(k / m)
    b = zeta * 2 * np.sqrt(m * k)           # ζ = b / b_critical
    dt = omega_dt / omega
    assume(b * dt / m < 1)
    assume(abs(x0) + abs(v0_over_omega) > 1e-3)
    state, forces = line_oscillators(m=m, k=k, b=b, x0=x0, v0=v0_over_omega * omega)
    trajectory = run(state, forces, dt=dt, until=3 * 2 * np.pi / omega, integrator="euler-cromer")
    A0 = np.hypot(x0, v0_over_omega)
    bound = A0 / np.sqrt(1 - omega_dt / 2)
    assert np.max(np.abs(trajectory.r[:, 0, 0])) <= bound * (1 + 1e-9)
    assert np.all(trajectory.r[:, 0, 1:] == 0)           # and never leaves its line


@pytest.mark.parametrize("integrator", INTEGRATORS)
@settings(max_examples=15, deadline=None)
@given(m=masses, k=stiffnesses, L0=st.floats(0.0, 5.0), g=st.floats(0.0, 25.0), b=st.floats(0.0, 10.0),
       C=st.floats(0.0, 2.0), anchor=st.tuples(*[st.floats(-10.0, 10.0)] * 3))
def test_a_mass_at_rest_at_equilibrium_stays_put(integrator, m, k, L0, g, b, C, anchor):
    hang = L0 + m * g / k
    r_eq = np.array(anchor) + np.array([0.0, -hang, 0.0])
    forces = (Spring(k=k, L0=L0, anchor=anchor), Gravity(g=g), LinearDamping(b=b),
              QuadraticDrag(C=C, A=0.1, rho=1.2))
    dt = 0.1 / np.sqrt(k / m)
    assume(b * dt / m < 1)  # else the explicit damping step is itself unstable and amplifies round-off
    trajectory = run(make_state(r=r_eq, m=m), forces, dt=dt, until=100 * dt, integrator=integrator)
    scale = 1.0 + np.linalg.norm(r_eq)
    assert np.max(np.abs(trajectory.r[:, 0] - r_eq)) <= 1e-9 * scale
    assert np.max(np.abs(trajectory.v[:, 0])) <= 1e-9 * scale * np.sqrt(k / m)

"""The physics of masses on springs, with numpy only (never vpython).

Modules: state (t, r, p, m), forces (pure force functions), integrators (the registry of step
methods), exact (closed forms), energy (K, U, W_nc), simulate (a run of fixed steps).
"""
from . import energy, exact, forces, integrators, simulate
from .forces import Driving, Gravity, LinearDamping, QuadraticDrag, Spring, SpringBetween, net_force
from .integrators import DEFAULT_INTEGRATOR, INTEGRATORS
from .state import State, make_state, velocity

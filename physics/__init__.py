"""The physics of masses on springs, with numpy only (never vpython).

Modules: state (t, r, p, m), forces (pure force functions), integrators (the registry of step
methods), exact (closed forms), energy (K, U, W_nc), simulate (the engine: the one loop that
steps the physics), stability (is Δt small enough?), compiled (the engine's fast loop).
"""
from . import energy, exact, forces, integrators, simulate, stability
from .forces import Driving, Gravity, LinearDamping, QuadraticDrag, Spring, SpringBetween, net_force
from .integrators import DEFAULT_INTEGRATOR, INTEGRATORS
from .simulate import Simulation
from .state import State, make_state, velocity

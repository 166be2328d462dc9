"""What a scene's build function returns: a model ready to run, and what the view needs to draw it."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from physics.state import State


@dataclass(frozen=True)
class Model:
    """A system of masses ready to step.

    state    the initial state (t, r, p, m)
    forces   the list of forces summed into F_net
    dt       the time step, s
    until    the question time, s (how long a headless run goes by default)
    exact    t -> (r, v) of shape (len(t), N, 3), or None where no closed form exists
    anchors  where each mass's spring is fixed, (N, 3) m: the view draws a helix from there
    labels   a name per mass, for graphs and tables
    integrators  None (use the chosen integrator), or one integrator name per mass, for scenes that
             compare methods side by side (physics.simulate.stepper)
    exact_valid_until  None if the closed form holds at all times, else T -> the first time up to T
             at which it stops holding, s (math.inf if it holds all the way to T)
    exact_limit  why the closed form can stop holding, one sentence
    """

    state: State
    forces: tuple
    dt: float
    until: float
    exact: Optional[Callable] = None
    anchors: np.ndarray = field(default_factory=lambda: np.zeros((1, 3)))
    labels: tuple = ("mass",)
    integrators: Optional[tuple] = None
    exact_valid_until: Optional[Callable[[float], float]] = None
    exact_limit: str = ""

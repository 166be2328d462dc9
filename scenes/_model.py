"""What a scene's build function returns: a model ready to run, and what the view needs to draw it."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from physics.integrators import DEFAULT_INTEGRATOR, methods_for
from physics.simulate import Simulation
from physics.stability import growing
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
             compare methods side by side
    default_integrator  the method used when none is chosen (None: the page's euler-cromer)
    may_run_away  masses the scene expects to run away (euler beside the other methods): the engine
             freezes them where they blow up and runs the others on
    exact_valid_until  None if the closed form holds at all times, else T -> the first time up to T
             at which it stops holding, s (math.inf if it holds all the way to T)
    exact_limit  why the closed form can stop holding, one sentence
    no_closed_form  where exact is None because a force present has no closed form, why, naming
             it: "no closed form with friction" ("" otherwise)
    no_closed_form_each  () where every mass's closed form covers its forces, else for each mass
             why it has none ("no closed form with drag"; "" for a mass that has one)
    per_mass  None, or how the scene's build makes its lists of one value per mass, as data the
             handed-out program writes out (scenes/_row.py's MassLoop)
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
    default_integrator: Optional[str] = None
    may_run_away: tuple = ()
    per_mass: Optional[object] = None
    no_closed_form: str = ""
    no_closed_form_each: tuple = ()

    def __post_init__(self):
        for force in self.forces:   # a plain callable, not a physics.forces.Force, declares nothing
            if hasattr(force, "undefined_at") and np.any(force.undefined_at(self.state.r)):
                raise ValueError("a mass starts at its spring's anchor, where the spring's direction "
                                     "L̂ is undefined: move r0 (or x0) off the anchor")

    def methods(self, integrator: Optional[str] = None) -> tuple:
        """The method of each mass: the scene's own list, else the chosen one, else its default."""
        if self.integrators is not None:
            return tuple(self.integrators)
        return methods_for(integrator or self.default_integrator or DEFAULT_INTEGRATOR, self.state.count)

    def exact_valid_until_each(self, T: float) -> np.ndarray:
        """When each mass's closed form stops holding, up to the horizon T, (N,) s: math.inf where
        it holds to T. A row of independent masses (scenes/_row.py) judges each mass on its own,
        through its exact_valid_until's each(T); otherwise one time holds for every mass."""
        check, count = self.exact_valid_until, self.state.count
        if check is None:
            return np.full(count, math.inf)
        each = getattr(check, "each", None)
        return np.asarray(each(T), dtype=float) if each is not None else np.full(count, float(check(T)))

    def exact_where_valid(self, t) -> Optional[tuple]:
        """The closed form's (r, v) at the times t, each (len(t), N, 3), NaN ("not known") for a mass
        at the times its closed form no longer describes it (past its anchor) or where it has none;
        None where the scene has no closed form. The one rule the report, --plot and the page use."""
        if self.exact is None:
            return None
        t = np.asarray(t, dtype=float)
        r, v = (np.array(a, dtype=float) for a in self.exact(t))
        if len(t):
            after = t[:, None] > self.exact_valid_until_each(float(t[-1]))[None, :]
            r[after], v[after] = np.nan, np.nan
        return r, v

    def expected_runaways(self, methods: Optional[tuple] = None) -> list[int]:
        """The masses expected to run away: those the scene names (may_run_away), and, where each
        mass has its own integrator, those whose method makes the motion grow at this Δt (euler at
        every Δt, the others beyond their limit), as physics.stability judges it. The page freezes
        them where they leave the picture; --plot leaves them off its axis limits."""
        expected = set(self.may_run_away)
        if self.integrators:
            methods = self.methods() if methods is None else methods
            expected |= {int(i) for i in np.flatnonzero(growing(self.forces, self.state.m, methods, self.dt))}
        return sorted(expected)

    def simulation(self, integrator: Optional[str] = None, **options) -> Simulation:
        """The engine for this model, ready at its initial state (physics/simulate.py)."""
        may_run_away = set(self.may_run_away) | set(options.pop("may_run_away", ()))
        return Simulation(self.state, self.forces, dt=self.dt, integrator=self.methods(integrator),
                          may_run_away=sorted(may_run_away), **options)


@dataclass(frozen=True)
class MassList:
    """One list of the program with a value per mass, as the scene's build works it out.

    name     the model's quantity it holds: "anchor", "r0", or a force's constant ("b", "omega")
    comment  the program's comment on the line that makes each value
    each     one mass's value, inside the loop over the masses (MassLoop.index names it), or
    whole    the whole list at once, before the loop
    before   (code, comment) lines it needs before the loop: `s_eq = L0 + m*g/k`
    keep     a name the value is kept in first, for the lists after it (`a`, the anchor)
    All text names the scene's constants, as its constants block does.
    """

    name: str
    comment: str = ""
    each: str = ""
    whole: str = ""
    before: tuple = ()
    keep: str = ""


@dataclass(frozen=True)
class MassLoop:
    """The scene's lists of one value per mass: the loop over the masses and the lists it fills.

    loop     the for line(s), `for i in range(3):` or a row per b and a column per ω
    index    the loop's index inside, for a mass's place in its row (`i`, `col`)
    lists    the MassList of each quantity, in the order they are made
    per_row  where there are rows: the constant that gives a row's length (`count`)
    """

    loop: tuple
    index: str
    lists: tuple
    per_row: str = ""

    def then(self, *lists: MassList) -> "MassLoop":
        """The same loop with more lists (a scene's own, after the row's)."""
        return MassLoop(self.loop, self.index, self.lists + tuple(lists), self.per_row)

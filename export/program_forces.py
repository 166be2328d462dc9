"""The forces and the integrator's update, as lines of the handed-out program.

Nothing here knows a force or a method by name: each force gives its constants' values and its
line(s) of program (physics/forces/base.py: Force.program_values, Force.program), and each integrator
its template (physics/integrators.py: the registry entry's program). This module fills them in
with the program's names, `b` or `b_each[i]` for a value per mass, in the order
physics.forces.net_force adds the forces.
"""
from __future__ import annotations

from physics.integrators import INTEGRATORS
from scenes import DECLARED

from .lines import ProgramError, commented

POSITION, VELOCITY, MASS, TIME = "r", "v", "m", "t"      # the names a force's PROGRAM fills in
START_R, START_P, REST = "r_i", "p_i", "Frest"          # a stop rule's: the step's start, the other forces


class ProgramForces:
    """The model's forces as lines of the program; their constants are added to `constants`
    (program_constants.ProgramConstants) as each force declares them."""

    def __init__(self, model, constants):
        self.constants = constants
        self.forces = list(model.forces)
        for force in self.forces:
            if not force.program():
                raise ProgramError(f"the program cannot write the force {type(force).__name__}: "
                                   f"it declares no PROGRAM line (physics/forces/base.py)")
            try:
                values = force.program_values()
            except ValueError as problem:
                raise ProgramError(str(problem)) from None
            for name, value in values.items():
                constants.add(name, value, is_vector=DECLARED[name].vector)
        self.uses_velocity = any(force.uses_velocity for force in self.forces)

    def lines(self, t: str, r: str, v: str, laws: bool) -> list[tuple[str, str]]:
        """Fnet at time t, position r and velocity v: each force's lines, then their sum, as (code,
        comment). A force that responds to the others (static friction) comes after them, with
        their sum Frest, as physics.forces.net_force adds them."""
        out, terms = [], []
        responding = [force for force in self.forces if force.responds]
        for force in [force for force in self.forces if not force.responds]:
            out += self._law(force, t=t, r=r, v=v, laws=laws)
            terms.append(force.TERM)
        for force in responding:
            out.append((f"{REST} = " + (" + ".join(terms) or "vector(0, 0, 0)"),
                        "the other forces, which it answers" if laws else ""))
            out += self._law(force, t=t, r=r, v=v, laws=laws)
            terms = [REST, force.TERM]
        out.append(("Fnet = " + (" + ".join(terms) or "vector(0, 0, 0)"),
                    "net force: the sum of the forces" if laws else ""))
        return out

    def _law(self, force, *, t: str, r: str, v: str, laws: bool) -> list[tuple[str, str]]:
        """A force's own lines (Force.program), filled in with the program's names."""
        names = {name: self.constants.name(name) for name in force.program_values()}
        names.update({TIME: t, POSITION: r, VELOCITY: v, MASS: self.mass, "F_rest": REST})
        return [(code.format(**names), comment if laws else "") for code, comment in force.program()]

    @property
    def mass(self) -> str:
        return self.constants.name("m")

    @property
    def stopping(self) -> list:
        """The forces with a stop rule (Force.STOP: static friction)."""
        return [force for force in self.forces if force.STOP]

    def stop_lines(self, *, r: str, p: str) -> list[tuple[str, str]]:
        """After the update, each stop rule (Force.STOP) as lines: the other forces at the step's
        start (r_i, p_i) summed into Frest, then the rule, which may set r and p. The engine does
        the same after every step (physics.forces.settle)."""
        out = []
        for force in self.stopping:
            others = [other for other in self.forces if other is not force]
            out.append((f"v = {START_P}/{self.mass}", "the other forces at the step's start, for the stop rule"))
            terms = []
            for other in others:
                out += self._law(other, t="t", r=START_R, v="v", laws=False)
                terms.append(other.TERM)
            out.append((f"{REST} = " + (" + ".join(terms) or "vector(0, 0, 0)"), "every force but this one"))
            names = {name: self.constants.name(name) for name in force.program_values()}
            names.update({TIME: "t", POSITION: r, "p": p, MASS: self.mass, "r_i": START_R, "p_i": START_P,
                          "F_rest": REST})
            out += [(code.format(**names), comment) for code, comment in force.STOP]
        return out


def update(method: str, forces: ProgramForces, *, r: str, p: str, m: str) -> list[str]:
    """The lines of one step of `method` for one mass (position r, momentum p, mass m), before t
    moves on: the integrator's own template (physics/integrators.py), filled in with the forces."""
    entry = INTEGRATORS.get(method)
    if entry is None or entry.program is None:
        raise ProgramError(f"the program cannot write the integrator {method!r} (known: "
                           f"{', '.join(name for name, known in INTEGRATORS.items() if known.program)})")
    lines = entry.program(forces.lines, r=r, p=p, m=m, uses_velocity=forces.uses_velocity)
    if forces.stopping:     # a stop rule reads the step's start: keep it
        lines = [(f"{START_R} = {r}", "the step's start, for the stop rule"), (f"{START_P} = {p}", "")] + \
            lines + forces.stop_lines(r=r, p=p)
    return [commented(code, comment) for code, comment in lines]

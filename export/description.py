"""The motion in words: one or two plain sentences that say what the 3-D view shows.

    t = 1.20 s. The mass is 0.3108 m below its equilibrium and moving up at 0.8213 m/s. In the
    step to 1.20 s F_net was 3.104 N up: spring 12.4 N up, gravity 98 N down.

PhET's "interactive description" is the model: a student who cannot see the canvas asks for it
(key D, or the Describe button) and hears it after each Step, in a live region. Both pages fill
the one template below: the local page (browser/) with the engine's numbers, through
:func:`describe`; the offline page (export/offline_page.js) with the numbers the program reports
after each step (export/program_page.py's `page.stepped`), in the same words, from
:func:`template_data`.

The numbers are rounded as the page's read-outs are: t as the clock shows it (Δt's decimals),
the rest to READ_DIGITS significant digits, as a click on a graph reads them
(browser/graph_reading.py). The forces are named by their declarations (each force's LABEL), in
the order the engine adds them; F_net and the parts are those of the last step, as the Step
read-out writes them (export/step_update.py's update_force): for a method that kicks once
(Euler-Cromer, Euler) each force at the step's start, which add up to F_net; for the others F_net
is the step's average force, and no parts are given (their stages have no one value per force).
"""
from __future__ import annotations

import numpy as np

from physics.forces import forces_each
from physics.integrators import INTEGRATORS
from physics.state import velocity

from .step_update import update_force, vector

READ_DIGITS = 4           # significant digits, as the graph reading's
MASSES = 4                # masses described one by one; the rest are counted
STILL = 1e-9              # a vector smaller than this (in its unit) is zero: at rest, at equilibrium
MINOR = 0.05              # a component below this share of its vector's size is left out of the words

# The template both pages fill. Each {slot} is a number (already rounded) or words.
TEMPLATE = {
    "time": "t = {t} s.",
    "one": "The mass",                       # the subject when the scene has one mass
    "many": "{label}: the mass",             # each mass's, when it has several
    "where": "{who} is {offset} its equilibrium",
    "at_equilibrium": "{who} is at its equilibrium",
    "where_no_equilibrium": "{who} is at {position} m",
    "moving": "and moving {direction} at {speed} m/s.",
    "still": "and at rest.",
    "step": "In the step to {t} s F_net was {size} N{direction}",
    "average": "In the step to {t} s F_net (its average over the step) was {size} N{direction}",
    "part": "{label} {size} N{direction}",
    "more": "(and {count} more masses)",
}
# Each axis's words: (positive, negative) for where a mass is from its equilibrium, and for
# which way a velocity or a force points. The page looks along −z with +y up.
OFFSET_WORDS = (("right of", "left of"), ("above", "below"), ("in front of", "behind"))
DIRECTION_WORDS = (("right", "left"), ("up", "down"), ("toward you", "away from you"))


def rounded(x: float) -> str:
    """A size to READ_DIGITS significant digits (Python's 'g', as the offline page's pyG writes it)."""
    return f"{abs(float(x)):.{READ_DIGITS}g}"


def _parts(v) -> list[tuple[int, float]]:
    """The components worth saying: (axis, value), largest first, none if the vector is ~0."""
    v = np.asarray(v, dtype=float)
    size = float(np.linalg.norm(v))
    if not size > STILL:
        return []
    kept = [(axis, float(v[axis])) for axis in range(len(v)) if abs(v[axis]) >= MINOR * size]
    return sorted(kept, key=lambda part: -abs(part[1]))


def listed(words: list[str]) -> str:
    """`a`, `a and b`, `a, b and c`."""
    return ", ".join(words[:-1]) + " and " + words[-1] if len(words) > 1 else "".join(words)


def offset_words(d) -> str:
    """`0.3108 m below` or `0.2 m left of and 0.05 m below`; '' at equilibrium."""
    return listed([f"{rounded(value)} m {OFFSET_WORDS[axis][value < 0]}" for axis, value in _parts(d)])


def direction_words(v) -> str:
    """`up`, `down and left`; '' for ~0."""
    return listed([DIRECTION_WORDS[axis][value < 0] for axis, value in _parts(v)])


def _force(slot: str, F, **fill) -> str:
    direction = direction_words(F)
    return TEMPLATE[slot].format(size=rounded(np.linalg.norm(F)), direction=" " + direction if direction else "",
                                 **fill)


def mass_sentences(*, who: str, t_text: str, r, v, centre, step: dict | None) -> str:
    """One mass: where it is and how it moves, then the last step's F_net and its parts.

    centre  its equilibrium (m), or None where it has none
    step    None before any step, else {"F_net": (3,), "average": bool, "parts": [(label, (3,)), ...]}
    """
    r = np.asarray(r, dtype=float)
    if centre is None or not np.all(np.isfinite(centre)):
        where = TEMPLATE["where_no_equilibrium"].format(who=who, position=vector(r, digits=READ_DIGITS))
    else:
        offset = offset_words(r - np.asarray(centre, dtype=float))
        where = (TEMPLATE["where"].format(who=who, offset=offset) if offset
                 else TEMPLATE["at_equilibrium"].format(who=who))
    speed = float(np.linalg.norm(v))
    motion = (TEMPLATE["moving"].format(direction=direction_words(v), speed=rounded(speed))
              if direction_words(v) else TEMPLATE["still"])
    text = f"{where} {motion}"
    if step is not None:
        said = _force("average" if step["average"] else "step", step["F_net"], t=t_text)
        parts = [_force("part", F, label=label) for label, F in step["parts"]]
        text += " " + said + (": " + ", ".join(parts) if parts else "") + "."
    return text


def describe(model, methods, *, state, before, equilibrium, decimals: int) -> str:
    """The sentences for the local page: the engine's `state` now, `before` it the state at the start
    of the last step (None before any step), each mass's `equilibrium` ((N, 3) m, or None)."""
    t_text = f"{state.t:.{decimals}f}"
    v = velocity(state.p, state.m)
    step = _last_step(model, methods, state=state, before=before) if before is not None else None
    count = min(state.count, MASSES)
    sentences = []
    for i in range(count):
        who = TEMPLATE["one"] if state.count == 1 else TEMPLATE["many"].format(label=model.labels[i])
        centre = None if equilibrium is None else equilibrium[i]
        sentences.append(mass_sentences(who=who, t_text=t_text, r=state.r[i], v=v[i], centre=centre,
                                        step=None if step is None else step[i]))
    more = " " + TEMPLATE["more"].format(count=state.count - count) if state.count > count else ""
    return TEMPLATE["time"].format(t=t_text) + " " + " ".join(sentences) + more


def _last_step(model, methods, *, state, before) -> list[dict]:
    """Each mass's F_net of the step from `before` to `state` (export/step_update.py's update_force)
    and, for a method that kicks once, each force at the step's start (they add up to F_net)."""
    F_net = update_force(model.forces, methods, t_i=before.t, r_i=before.r, p_i=before.p, p_f=state.p,
                         m=state.m, dt=model.dt)
    v_i = velocity(before.p, before.m)
    each = list(zip([force.LABEL for force in model.forces],
                    forces_each(model.forces, before.t, before.r, v_i, before.m)))
    steps = []
    for i in range(state.count):
        once = INTEGRATORS[methods[i]].kicks_once
        parts = [(label, F[i]) for label, F in each if np.linalg.norm(F[i]) > STILL] if once else []
        steps.append({"F_net": F_net[i], "average": not once, "parts": parts})
    return steps


def template_data(model) -> dict:
    """What the offline page needs to fill the same template in the browser (export/offline_page.js)."""
    return {"template": TEMPLATE, "offset_words": OFFSET_WORDS, "direction_words": DIRECTION_WORDS,
            "digits": READ_DIGITS, "masses": MASSES, "still": STILL, "minor": MINOR,
            "labels": [force.LABEL for force in model.forces]}

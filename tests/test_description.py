"""The motion in words (export/description.py) against the engine, and the keys' one declaration
(export/page_keys.py) against what the pages and docs/teaching.md list. No browser."""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from browser.clock import LiveRun
from export.description import READ_DIGITS, _last_step, describe, direction_words, offset_words
from export.page_keys import KEYS, keys_html
from physics.equilibrium import equilibrium
from physics.integrators import INTEGRATORS
from scenes import catalog

ROOT = Path(__file__).resolve().parent.parent


def run(scene: str, steps: int, integrator: str = "euler-cromer"):
    model = catalog.configure(scene).build()
    live = LiveRun(model, integrator=integrator)
    live.advance(steps)
    return model, live


def test_a_hanging_mass_is_said_where_the_engine_has_it():
    model, live = run("vertical", 12)
    centre = equilibrium(model.forces, model.state)
    said = describe(model, live.engine.methods, state=live.state, before=live.before, equilibrium=centre, decimals=2)
    below = centre[0, 1] - live.state.r[0, 1]
    v = live.state.p[0, 1] / live.state.m[0]
    assert said.startswith("t = 1.20 s. The mass is ")
    assert f"{abs(below):.{READ_DIGITS}g} m {'below' if below > 0 else 'above'} its equilibrium" in said
    assert f"moving {'up' if v > 0 else 'down'} at {abs(v):.{READ_DIGITS}g} m/s" in said
    assert re.search(r"F_net was [\d.]+ N (up|down): spring [\d.]+ N up, gravity 98 N down\.$", said)


@pytest.mark.parametrize("integrator", list(INTEGRATORS))
def test_the_last_steps_forces_are_the_step_read_outs(integrator):
    """The parts add up to F_net where the method kicks once; F_net is (p_f − p_i)/Δt where it does not."""
    model, live = run("damped", 9, integrator)
    step = _last_step(model, live.engine.methods, state=live.state, before=live.before)[0]
    average = (live.state.p[0] - live.before.p[0]) / model.dt
    if INTEGRATORS[integrator].kicks_once:
        assert [label for label, _ in step["parts"]] == ["spring", "gravity", "damping"] or step["parts"]
        assert np.allclose(sum(F for _, F in step["parts"]), step["F_net"], rtol=1e-12, atol=1e-12)
        if integrator == "euler-cromer":
            assert np.allclose(step["F_net"], average, rtol=1e-9)
    else:
        assert step["average"] and not step["parts"]
        assert np.allclose(step["F_net"], average, rtol=1e-12)


def test_before_any_step_there_is_no_force_sentence_and_several_masses_are_each_named():
    model = catalog.configure("regimes").build()
    live = LiveRun(model, integrator="euler-cromer")
    said = describe(model, live.engine.methods, state=live.state, before=live.before,
                    equilibrium=equilibrium(model.forces, model.state), decimals=2)
    assert "F_net" not in said
    for label in model.labels:
        assert f"{label}: the mass is" in said


def test_directions_read_as_words():
    assert offset_words([0.2, -0.05, 0]) == "0.2 m right of and 0.05 m below"
    assert direction_words([0, 0, 0]) == ""
    assert direction_words([-1, 2, 0.5]) == "up, left and toward you"


def test_every_key_is_listed_on_the_pages_and_in_teaching_md():
    teaching = (ROOT / "docs" / "teaching.md").read_text(encoding="utf-8")
    listed = keys_html()
    for key in KEYS:
        assert f"{key.shown} {key.words}" in listed
        assert key.words in teaching, f"docs/teaching.md does not say what {key.shown} does"
    assert "letter keys" in listed and "letter keys" in teaching

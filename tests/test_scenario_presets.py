"""A driven scenario preset reproduces the book's case, whatever was changed before it (issue 18,
item 9): "scenario 5" ran with m = 6.97 kg after the m slider had been moved."""
import json
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest

from browser.messages import ChoosePreset, SetConstant
from browser.view import SceneView
from scenes import catalog
from scenes._constants import DECLARED

ROOT = Path(__file__).resolve().parents[1]
SCENARIO_5 = "scenario 5: as 4, with ω = 4 rad/s"


def case(values: dict) -> dict:
    """The constants that make up the physical case (all but Δt and the question time)."""
    return {name: value for name, value in values.items() if not (name in DECLARED and DECLARED[name].numerical)}


def page_after(setup, *clicks):
    """What the page's frame loop makes of these clicks on `setup` (its switch recorded, no vpython)."""
    view = SceneView.__new__(SceneView)
    view.setup, view.integrator = setup, "euler-cromer"
    view.controls = SimpleNamespace(clicks=lambda: list(clicks))
    done = []
    view._switch = lambda setup, preset=None: done.append((setup, preset)) or True
    view._rebuild = lambda changes, integrator: done.append(("rebuild", changes))
    view._apply_commands(now=0.0)
    return done


def test_on_the_page_a_scenario_sets_m_and_k_back_to_the_books_case():
    book = catalog.configure("driven", scenario=5)
    moved = catalog.configure("driven").with_values(m=6.97, k=50.0, L0=2.0, dt=0.02)
    for clicks in ([ChoosePreset(SCENARIO_5)], [SetConstant("m", 3.3), ChoosePreset(SCENARIO_5)]):
        (setup, preset), = page_after(moved, *clicks)
        assert preset == SCENARIO_5
        assert setup.values["m"] == 4.0 and setup.values["k"] == 100.0
        assert case(setup.values) == case(book.values)
        assert setup.values["dt"] == 0.02             # how the run is computed stays as chosen


def test_a_scenario_chosen_after_another_is_that_scenario_alone():
    first = catalog.configure("driven").with_preset("scenario 3")
    assert case(first.with_preset("scenario 1").values) == case(catalog.configure("driven", scenario=1).values)


def test_the_other_presets_still_change_only_their_own_constants():
    moved = catalog.configure("vertical").with_values(m=2.0, k=18.0)
    moon = moved.with_preset("Moon gravity")
    assert moon.values["m"] == 2.0 and moon.values["k"] == 18.0 and moon.values["g"] == 1.62


def cli_json(*args):
    done = subprocess.run([sys.executable, str(ROOT / "main.py"), *args, "--headless", "--json"],
                          capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.mark.parametrize("number", [1, 5])
def test_headless_preset_is_the_books_scenario_in_every_constant(number):
    preset = cli_json("driven", "--preset", f"scenario {number}", "--until", "2")
    scenario = cli_json("driven", "--scenario", str(number), "--until", "2")
    assert preset["constants"] == scenario["constants"] and preset["r"] == scenario["r"]
    assert preset["constants"]["m"]["value"] == 4.0 and preset["constants"]["k"]["value"] == 100.0
    assert cli_json("driven", "--preset", f"scenario {number}", "--set", "m=5", "--until", "2")[
        "constants"]["m"]["value"] == 5.0                  # --set, given explicitly, still wins

"""--json keeps the promise of its "units" entry: every key it gives a unit is in the output.

F_net is the net force at the final time, for the one mass at the top level and for each mass in
"bodies"; exact_valid_until is a time where the closed form stopped holding, else null with a
line in "notes" saying why.
"""
from __future__ import annotations

import json

import pytest

import main
from scenes import catalog


def run_json(capsys, *args) -> dict:
    assert main.run([*args, "--headless", "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
def test_every_key_with_a_unit_is_in_the_output(capsys, scene):
    out = run_json(capsys, scene)
    missing = [key for key in out["units"] if key not in out]
    assert not missing, f"{scene}: units promised for {missing}"
    if "bodies" in out:
        assert all(len(body["F_net"]) == 3 for body in out["bodies"])
        assert [body["F_net"] for body in out["bodies"]] == out["F_net"]
    if out["exact_valid_until"] is None:
        assert any(note.startswith("exact_valid_until: null") for note in out["notes"])


def test_F_net_is_the_hand_worked_force_at_the_final_time(capsys):
    # The Simple Example at t = 0.2 s: y = −1.73088 m, so F_net = 40(1.73088 − 1) − 10·9.8 = −68.7648 N
    out = run_json(capsys, "vertical", "--until", "0.2")
    assert out["F_net"] == pytest.approx([0.0, 40 * (1.73088 - 1) - 98, 0.0], abs=1e-9)
    assert out["exact_valid_until"] is None and "holds up to the final time" in out["notes"][0]

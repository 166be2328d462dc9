"""Issue 41 item 1: the program's exact curve holds for any values of its constants, because each
case of the closed form (the three damping regimes, undamped resonance) is a branch of the program,
chosen as physics/exact.py chooses it, and the masses' labels are expressions of the constants.

A program is written once, for the scene as shipped; then its constants block is edited as a
student (or the offline page's sliders) would edit it, and the edited program, run under the
stand-in vpython of tests/test_export.py, must draw the closed form of the edited case, and print
the labels and answer `--headless --set` prints for it.
"""
from __future__ import annotations

import json
import re

import numpy as np
import pytest

from export.palette import EXACT_COLOUR
from test_export import main_py, run_program, stand_in  # noqa: F401  (stand_in: the fixture)

EDITS = [
    # driven is written at exact resonance (b = 0, ω = ω0 = 5 rad/s): off resonance, and back on it
    ("driven", {"omega": 4.0}),
    ("driven", {"m": 6.25, "k": 100.0}),          # ω0 = 4 rad/s against ω = 5
    ("driven", {"m": 1.0, "k": 25.0}),            # ω0 = 5 rad/s again: resonance, with other m and k
    # damped (under-damped as shipped): critical and over-damped by b alone
    ("damped", {"b": 40.0}),                      # 2√(mk) = 40 kg/s
    ("damped", {"b": 55.0}),
    ("damped", {"b": 0.0}),
]


def edited(program: str, changes: dict) -> str:
    """The program with each constant's line in its constants block holding the new value."""
    lines = program.splitlines()
    for name, value in changes.items():
        at = next(n for n, line in enumerate(lines) if line.startswith(f"{name} = "))
        lines[at] = f"{name} = {value!r}"
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("scene, changes", EDITS, ids=[f"{s}-{'-'.join(f'{k}={v}' for k, v in c.items())}"
                                                       for s, c in EDITS])
def test_an_edited_constant_keeps_the_exact_curve_right(scene, changes, stand_in, tmp_path):  # noqa: F811
    """The edited program's exact curve ends at `--headless --set`'s exact position, and its answer
    is that command's: the curve's formula follows the case the new values make."""
    written = tmp_path / "shipped.py"
    done = main_py(scene, "--set", "until=3", "--vpython", str(written))
    assert done.returncode == 0, done.stderr
    path = tmp_path / "edited.py"
    path.write_text(edited(written.read_text(encoding="utf-8"), changes), encoding="utf-8")
    settings = [part for name, value in changes.items() for part in ("--set", f"{name}={value!r}")]
    drawn, printed = [], []
    run_program(path, stand_in, drawn, printed)
    t_end = next(shown for shown in drawn if shown["kind"] == "state")["t"]
    ended = main_py(scene, "--set", "until=3", *settings, "--headless", "--json", "--until", repr(t_end))
    assert ended.returncode == 0, ended.stderr
    expected = json.loads(ended.stdout)
    curve = next(shown for shown in drawn if shown["kind"] == "gcurve" and shown["color"] == list(EXACT_COLOUR))
    axis = 0 if scene == "driven" else 1
    assert curve["points"][-1][1] == pytest.approx(expected["exact"]["r"][axis], rel=1e-9, abs=1e-9)
    asked = json.loads(main_py(scene, "--set", "until=3", *settings, "--headless", "--json").stdout)
    from export.step_update import number, vector
    assert printed == [f"at t = {number(asked['t'])} s: r = {vector(asked['r'], 'm')}, "
                       f"p = {vector(asked['p'], 'kg·m/s')}"]


ROW_EDITS = [
    ("friction", {"b": 0.07, "mu_k": 0.035}),
    ("drag", {"b": 0.031, "C": 0.6}),
    ("regimes", {"m": 2.0, "k": 12.5}),        # the middle b = 8 kg/s is no longer 2√(mk) = 10: under-damped
    ("regimes", {"b": 12.0}),                  # over-damped
]


@pytest.mark.parametrize("scene, changes", ROW_EDITS, ids=[f"{s}-{'-'.join(f'{k}={v}' for k, v in c.items())}"
                                                           for s, c in ROW_EDITS])
def test_an_edited_constant_relabels_the_masses(scene, changes, stand_in, tmp_path):  # noqa: F811
    """A row's labels name its constants (damping, b = ...; its damping regime): the edited program
    prints each mass's answer under the label `--headless --set` gives it, digit for digit."""
    written = tmp_path / "shipped.py"
    done = main_py(scene, "--set", "until=2", "--vpython", str(written))
    assert done.returncode == 0, done.stderr
    path = tmp_path / "edited.py"
    path.write_text(edited(written.read_text(encoding="utf-8"), changes), encoding="utf-8")
    settings = [part for name, value in changes.items() for part in ("--set", f"{name}={value!r}")]
    printed = []
    run_program(path, stand_in, printed=printed)
    asked = json.loads(main_py(scene, "--set", "until=2", *settings, "--headless", "--json").stdout)
    labels = [body["label"] for body in asked["bodies"]]
    assert [re.sub(r":\s*at t = .*$", "", line) for line in printed] == labels
    assert any(str(value).rstrip("0").rstrip(".") in " ".join(labels) or scene == "regimes"
               for value in changes.values())
    if scene == "regimes":
        assert labels != [body["label"] for body in json.loads(main_py(scene, "--set", "until=2", "--headless",
                                                                       "--json").stdout)["bodies"]]
    assert np.all(np.isfinite([float(x) for line in printed for x in re.findall(r"-?\d+\.?\d*(?:e[-+]\d+)?", line)]))

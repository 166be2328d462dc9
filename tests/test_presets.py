"""Presets: the same named changes for the command line (--preset NAME) and the page's menu.

Checked through the real command line against closed forms and hand arithmetic:

- "critical damping" sets b = 2√(mk), and the motion is then the critical closed form
  y = y_eq + x0 (1 + γt) e^(−γt), γ = b/2m = √(k/m), which never crosses equilibrium;
- "Moon gravity" sets g = 1.62 m/s², so the mass settles a distance L0 + m g/k below its anchor;
- the step table under Moon gravity is the page's arithmetic with 1.62 in place of 9.8.
"""
from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from scenes import catalog
from scenes import ConstantError

ROOT = Path(__file__).resolve().parents[1]

# The page's Simple Example (scenes/vertical.py): m = 10 kg, k = 40 N/m, L0 = 1 m, released from
# rest 1.5 m below the anchor.
m, k, L0, y0 = 10.0, 40.0, 1.0, -1.5
G_MOON = 1.62  # m/s²


def cli(*args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "main.py", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=60)


def cli_json(*args) -> dict:
    done = cli(*args, "--headless", "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


# ---- the list of presets ----

@pytest.mark.parametrize("name", catalog.SCENE_NAMES)
def test_every_preset_names_real_constants_and_builds(name):
    setup = catalog.configure(name)
    labels = [label for label, _ in catalog.presets(setup)]
    assert len(labels) == len(set(labels))
    for label, overrides in catalog.presets(setup):
        assert set(overrides) <= set(setup.constants), label
        changed = setup.with_preset(label)
        assert all(changed.values[key] is not None for key in overrides   # critical b worked out
                   if setup.values[key] is not None)        # (a scenario's r0: derived, as in the file)
        changed.build()


def test_gravity_presets_only_where_gravity_is_on():
    for name in catalog.SCENE_NAMES:
        setup = catalog.configure(name)
        options = dict(catalog.presets(setup))
        if setup.values.get("g"):
            assert [options[label]["g"] for label in ("Moon gravity", "Earth gravity", "Jupiter gravity")] \
                == [1.62, 9.8, 24.79]
        else:  # driven lies on a table (g = 0); integrators has no gravity at all
            assert "Moon gravity" not in options, name


def test_critical_damping_where_the_scene_has_b_and_k():
    for name in catalog.SCENE_NAMES:
        setup = catalog.configure(name)
        has = "critical damping" in dict(catalog.presets(setup))
        assert has == ("b" in setup.constants and "k" in setup.constants), name


def test_driven_offers_the_pages_five_scenarios_as_presets():
    module = catalog.load("driven")
    options = catalog.presets(module)
    named = [(label, overrides) for label, overrides in catalog.presets(module, whole=False)
             if label.startswith("scenario")]
    assert [overrides for _, overrides in named] == [overrides for _, overrides in module.SCENARIOS]
    whole = dict(options)
    for label, overrides in named:              # each sets its whole case: the file's m, k, ... too
        assert whole[label]["m"] == 4.0 and whole[label]["k"] == 100.0 and "dt" not in whole[label]
        assert whole[label] == {**whole[label], **overrides}
    assert catalog.find_preset(module, "scenario 5")[1]["omega"] == 4.0


def test_critical_preset_uses_the_m_and_k_set_at_that_moment():
    setup = catalog.configure("vertical").with_values(m=2.0, k=18.0).with_preset("critical damping")
    assert setup.values["b"] == pytest.approx(2 * math.sqrt(2.0 * 18.0))  # 12 kg/s


def test_names_match_ignoring_case_and_by_a_unique_beginning():
    module = catalog.load("vertical")
    assert catalog.find_preset(module, "moon")[0] == "Moon gravity"
    assert catalog.find_preset(module, "CRITICAL DAMPING")[0] == "critical damping"
    with pytest.raises(ConstantError, match="could be any of"):
        catalog.find_preset(catalog.load("driven"), "scenario")


# ---- through the command line ----

def test_critical_damping_gives_b_two_root_mk_and_the_critical_closed_form(tmp_path):
    path = tmp_path / "critical.csv"
    out = cli_json("vertical", "--preset", "critical damping", "--integrator", "rk4", "--set", "dt=0.01",
                   "--until", "6", "--csv", str(path))
    b = 2 * math.sqrt(m * k)                       # 40 kg/s
    assert out["constants"]["b"]["value"] == pytest.approx(b)
    gamma = b / (2 * m)                            # = √(k/m) = 2 /s at critical damping
    y_eq = -(L0 + m * 9.8 / k)                     # −3.45 m
    x0 = y0 - y_eq                                 # 1.95 m above equilibrium, at rest
    with path.open() as handle:
        rows = list(csv.DictReader(handle))
    t = [float(row["t"]) for row in rows]
    y = [float(row["y"]) for row in rows]
    exact = [y_eq + x0 * (1 + gamma * s) * math.exp(-gamma * s) for s in t]
    assert max(abs(a - e) for a, e in zip(y, exact)) < 1e-6
    assert min(y) > y_eq                           # it never overshoots equilibrium


def test_critical_damping_is_worked_out_after_set():
    out = cli_json("vertical", "--preset", "critical", "--set", "m=2.5", "--set", "k=10", "--until", "0")
    assert out["constants"]["b"]["value"] == pytest.approx(10.0)   # 2√(2.5 · 10)


def test_moon_gravity_moves_the_equilibrium_to_L0_plus_mg_over_k():
    # with critical damping added by hand, the mass has settled by t = 20 s (e^(−40) is nothing)
    out = cli_json("vertical", "--preset", "Moon gravity", "--set", "b=40", "--set", "dt=0.001",
                   "--until", "20")
    assert out["constants"]["g"]["value"] == G_MOON
    assert out["r"][1] == pytest.approx(-(L0 + m * G_MOON / k), abs=1e-6)   # −1.405 m
    assert abs(out["v"][1]) < 1e-6


def test_moon_gravity_step_table_is_the_pages_arithmetic_with_1_62():
    done = cli("vertical", "--steps", "1", "--json", "--headless", "--preset", "moon")
    assert done.returncode == 0, done.stderr
    (row,) = json.loads(done.stdout)["step_table"]
    F_net = k * (1.5 - L0) - m * G_MOON            # 20 − 16.2 = 3.8 N, upward
    p1 = F_net * 0.1                               # 0.38 kg·m/s
    assert row["F_net"][1] == pytest.approx(F_net)
    assert row["p_f"][1] == pytest.approx(p1)
    assert row["r_f"][1] == pytest.approx(y0 + p1 / m * 0.1)   # −1.4962 m


def test_a_scenario_preset_is_the_same_run_as_that_scenario():
    assert cli_json("driven", "--preset", "scenario 3", "--until", "5")["r"] == \
        cli_json("driven", "--scenario", "3", "--until", "5")["r"]


def test_preset_works_with_plot(tmp_path):
    pytest.importorskip("matplotlib")
    path = tmp_path / "moon.png"
    done = cli("vertical", "--plot", str(path), "--preset", "Moon gravity", "--until", "2")
    assert done.returncode == 0, done.stderr
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_constants_lists_the_presets_with_their_values():
    done = cli("vertical", "--constants")
    assert done.returncode == 0, done.stderr
    text = done.stdout
    assert "presets (--preset NAME):" in text
    assert "Moon gravity" in text and "g = 1.62 m/s²" in text
    assert "b = 2√(mk) = 40 kg/s" in text


@pytest.mark.parametrize("args, expected", [
    (("vertical", "--headless", "--preset", "jupyter"), "did you mean 'Jupiter gravity'?"),
    (("vertical", "--preset", "mars"), "'Moon gravity', 'Earth gravity', 'Jupiter gravity', 'critical damping'"),
    (("integrators", "--headless", "--preset", "moon"), "scene 'integrators' has no presets"),
    (("driven", "--headless", "--json", "--preset", "scenario"), "could be any of"),
])
def test_a_bad_preset_is_one_line_and_status_2(args, expected):
    done = cli(*args)
    assert done.returncode == 2
    assert done.stdout == ""
    assert done.stderr.count("\n") == 1 and expected in done.stderr
    assert "Traceback" not in done.stderr

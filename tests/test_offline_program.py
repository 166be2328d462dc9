"""The offline page's program reports what the page shows, and what it reports is the engine's.

The page's program (export/vpython_program.py with page=True) tells the page, through its object
`page = offline_page()`, each mass's rates before anything is drawn (for the stability judgement),
each force's rule it breaks (friction's μ_s ≥ μ_k), and after every step each mass's K, each
conservative force's U and W_nc (export/program_page.py, from each force's PROGRAM_RATES,
RULES and PROGRAM_ENERGY). Here the program runs in plain Python under tests/test_export.py's
stand-in vpython, with a stand-in page that keeps every report, and each report is compared with
the physics: physics/stability.py's rates, the scene build's own refusal, and physics/energy.py's
K, U and the engine's W_nc meter after the same number of steps.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

import numpy as np
import pytest

from export.vpython_program import program
from physics.energy import kinetic
from physics.stability import rates
from scenes import catalog
from test_export import STAND_IN, _cyvector

PAGE = '''

class _Page:
    """A stand-in for the offline page: it keeps what the program reports."""

    def __init__(self):
        self.reports = {"constants": None, "rates": {}, "refused": [], "energy": [], "checked": False}

    def constants(self, values):
        self.reports["constants"] = dict(values)

    def rates(self, i, m, stiffness, damping, drag, speed):
        self.reports["rates"][i] = [m, stiffness, damping, drag, speed]

    def refuse(self, text):
        self.reports["refused"].append(text)

    def check(self):
        self.reports["checked"] = True
        if self.reports["refused"]:
            raise SystemExit(0)            # the page ends a refused run here, before anything is drawn

    def drawn(self, *args):
        pass

    def stepped(self, *args):
        pass

    def exact(self, *args):
        pass

    def energy(self, i, n, K, U, W):
        if n in (0, 1, 2, 10, 57):
            self.reports["energy"].append([i, n, K, dict(U), W])
        if n == 57 and i == len(DRAWN_MASSES) - 1 or n > 60:
            raise SystemExit(0)


DRAWN_MASSES = []
_PAGE = _Page()


def offline_page():
    return _PAGE


@atexit.register
def _page_report():
    with open(os.environ["PAGE_REPORT"], "w") as out:
        json.dump(_PAGE.reports, out)
'''


@pytest.fixture(scope="module")
def page_stand_in(tmp_path_factory):
    folder = tmp_path_factory.mktemp("page_stand_in")
    source = STAND_IN.replace("{cyvector!r}", repr(_cyvector())) + PAGE
    # the masses the program draws: the stand-in counts spheres, so its energy stops after the last one's report
    source = source.replace("class sphere(_Shown): pass", "class sphere(_Shown):\n"
                            "    def __init__(self, **attributes):\n        super().__init__(**attributes)\n"
                            "        DRAWN_MASSES.append(self)")
    (folder / "vpython.py").write_text(source, encoding="utf-8")
    return folder


def run_page_program(text: str, folder, stand_in) -> dict:
    """Run a page's program under the stand-ins; what it reported to the page."""
    path = folder / "page_program.py"
    path.write_text(text, encoding="utf-8")
    report = folder / "page.json"
    env = {**os.environ, "PYTHONPATH": str(stand_in), "STAND_IN_REPORT": str(folder / "drawn.json"),
           "PAGE_REPORT": str(report)}
    done = subprocess.run([sys.executable, str(path)], capture_output=True, text=True, env=env, cwd=folder,
                          timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(report.read_text())


def edited(text: str, changes: dict) -> str:
    lines = text.splitlines()
    for name, value in changes.items():
        at = next(n for n, line in enumerate(lines) if line.startswith(f"{name} = "))
        lines[at] = f"{name} = {value!r}"
    return "\n".join(lines) + "\n"


CASES = [("damped", None, {}), ("driven", 5, {}), ("friction", None, {}), ("drag", None, {}),
         ("regimes", None, {"m": 2.0}), ("vertical", None, {"g": 1.62})]


@pytest.mark.parametrize("scene, scenario, changes", CASES, ids=[case[0] for case in CASES])
def test_the_page_programs_energy_is_the_engines(scene, scenario, changes, page_stand_in, tmp_path):
    """K, each force's U and W_nc the program reports at steps 0, 1, 2, 10 and 57 are physics/energy.py's
    and the engine's W_nc meter after as many steps, mass by mass, to 1e-9 of the energy's size."""
    setup = catalog.configure(scene, scenario=scenario).with_values(**changes)
    reports = run_page_program(program(setup, page=True), tmp_path, page_stand_in)
    model = setup.build()
    engine = model.simulation()
    by_step = {}
    for i, n, K, U, W in reports["energy"]:
        by_step.setdefault(n, {})[i] = (K, U, W)
    assert sorted(by_step) == [0, 1, 2, 10, 57]
    done = 0
    for n in sorted(by_step):
        engine.advance(n - done)
        done = n
        state = engine.state
        K = kinetic(state)
        scale = max(1.0, float(np.max(np.abs(K))))
        for i, (K_i, U_i, W_i) in by_step[n].items():
            assert K_i == pytest.approx(K[i], rel=1e-9, abs=1e-9 * scale)
            for force in model.forces:
                if force.conservative:
                    expected = float(force.potential_energy(state.r, state.m)[i])
                    assert U_i[force.LABEL] == pytest.approx(expected, rel=1e-9, abs=1e-9 * scale), force.LABEL
            assert W_i == pytest.approx(engine.work[i], rel=1e-9, abs=1e-9 * scale)


@pytest.mark.parametrize("scene", ["vertical", "damped", "driven", "drag", "regimes", "friction", "integrators"])
def test_the_page_programs_rates_are_the_stability_judgements(scene, page_stand_in, tmp_path):
    """Each mass's stiffness, b/m and drag rate the program reports before anything is drawn are
    physics/stability.py's rates for the model (ω² m, b/m, ρCA|v|/m at the start's speed)."""
    setup = catalog.configure(scene)
    reports = run_page_program(program(setup, page=True), tmp_path, page_stand_in)
    model = setup.build()
    expected = rates(model.forces, model.state.m, model.state.v)
    assert reports["checked"] and not reports["refused"]
    assert sorted(int(i) for i in reports["rates"]) == list(range(model.state.count))
    for i, (m, stiffness, damping, drag, speed) in reports["rates"].items():
        i = int(i)
        assert m == model.state.m[i]
        assert np.sqrt(stiffness / m) == pytest.approx(expected.omega[i], rel=1e-12)
        assert damping == pytest.approx(expected.damping[i], rel=1e-12, abs=1e-300)
        assert drag == pytest.approx(expected.drag[i], rel=1e-12, abs=1e-300)
        assert speed == pytest.approx(expected.speed[i], rel=1e-12, abs=1e-300)


@pytest.mark.parametrize("changes", [{"mu_s": 0.01}, {"g": 0}, {"mu_k": 0.3, "mu_s": 0.25}])
def test_a_broken_force_rule_is_refused_by_the_program_in_the_command_lines_words(changes, page_stand_in,
                                                                                tmp_path):
    """The friction page's program, its constants edited as the page writes them, refuses a rule
    its force's check refuses (Friction.RULES), before anything is drawn, in that check's sentence."""
    text = edited(program(catalog.configure("friction"), page=True), changes)
    reports = run_page_program(text, tmp_path, page_stand_in)
    with pytest.raises(ValueError) as refused:
        catalog.configure("friction").with_values(**changes).build()
    assert reports["refused"] and reports["refused"][0] == str(refused.value)
    assert not reports["energy"]          # nothing ran

"""docs/architecture.md's "Adding a force", followed literally: new modules in physics/forces/.

The project's code is copied to a temporary folder (the tree itself is never written), and two
files are added there, nothing else edited:

- physics/forces/wind.py: a steady push of the wind, F = w x̂, declared as the recipe says (law,
  LABEL, CONSTANTS with a default that switches it off, TERM and PROGRAM; no closed form).
  `vertical --set w=3` switches it on (a single-mass scene takes every force's constants), and the
  first momentum update has F_net along x of exactly w; `--json` has "exact": null with the note
  "no closed form with wind"; the handed-out program writes its line, its constant with its unit
  and meaning, and names it on its arrows; `--constants` lists it, and `--set w=-5000` is refused.
- physics/forces/brake.py (issue 37): the issue's eddy-current brake, F = −c v, WITH its closed-form
  role (it is mathematically damping: CLOSED_FORM = {Role.DAMPING: "c"}) and a slider declared on
  its constant. Every command still runs (--list too); the brake gets its slider, is listed by
  --constants and --forces on and off, has the closed form of damping with its own c (and the
  program's exact curve names c), and the stability message names it and its own constant:
  "the eddy brake (c/m = 40 s⁻¹)", not the page's b.

A third copy holds a force with a bad declaration, one mistake at a time: each is one line, exit
status 2, naming the force and the fix, at the command that uses the forces; --list still runs.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("physics", "scenes", "export", "reports", "cli", "lab", "browser")

WIND = '''
"""A steady wind: a force in a module of its own."""
from dataclasses import dataclass

import numpy as np

from ..declared import Declared
from .base import Force


@dataclass(frozen=True, eq=False)
class Wind(Force):
    """A steady push of the wind along x.

    F = w x̂,  w in N (negative: it blows towards −x).
    """

    w: float = 0.0
    conservative = False
    uses_velocity = False
    LABEL = "wind"
    CONSTANTS = {"w": Declared("N", -1e3, 1e3, default=0.0, switch=True, slider_from_zero=True,
                               meaning="steady push of the wind along x")}
    TERM = "Fwind"
    PROGRAM = (("Fwind = vector({w}, 0, 0)", "wind: a steady push along x"),)

    def __call__(self, t, r, v, m):
        F = np.zeros_like(r, dtype=float)
        F[:, 0] = self.w
        return F
'''


BRAKE = '''
"""An eddy-current brake: a magnet slows a conductor moving past it. A force in a module of its own."""
from dataclasses import dataclass

import numpy as np

from ..declared import Declared
from ..exact import Role
from .base import Force


@dataclass(frozen=True, eq=False)
class EddyBrake(Force):
    """Eddy-current braking.

    F = −c v,  c in kg/s (N per m/s): the same law as linear damping, with a constant of its own.
    """

    c: float = 0.0
    conservative = False
    uses_velocity = True
    LABEL = "eddy brake"
    CONSTANTS = {"c": Declared("kg/s", 0, 1e6, slider=True, slider_from_zero=True, default=0.0, switch=True,
                               meaning="eddy-current braking constant in F = −c v")}
    TIED = ((("m", "c"), "the motion depends on c/m, not on c and m apart"),)
    TERM = "Fbrake"
    VECTORS = {}
    CLOSED_FORM = {Role.DAMPING: "c"}
    PROGRAM = (("Fbrake = -{c}*{v}", "eddy brake: F = −c v"),)

    def __call__(self, t, r, v, m):
        return -self.c * v

    def rates(self, m, speed):
        return {"damping": np.full(len(m), self.c) / m}      # F = −c v = −(c/m) m v

    def closed_form(self):
        return {Role.DAMPING: self.c}
'''


def copy_of_the_project(folder: Path, **modules: str) -> Path:
    """The project's packages and main.py in `folder`, with each of `modules` (name: text) added
    to physics/forces/."""
    for package in PACKAGES:
        shutil.copytree(ROOT / package, folder / package, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "main.py", folder / "main.py")
    for name, text in modules.items():
        (folder / "physics" / "forces" / f"{name}.py").write_text(textwrap.dedent(text), encoding="utf-8")
    return folder


@pytest.fixture(scope="module")
def project(tmp_path_factory) -> Path:
    return copy_of_the_project(tmp_path_factory.mktemp("project"), wind=WIND, brake=BRAKE)


def main_py(project: Path, *args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(project / "main.py"), *args], capture_output=True, text=True,
                          cwd=project, timeout=300, env={**os.environ, "SPRING_SCENES": "",
                                                         "PYTHONDONTWRITEBYTECODE": "1"})


def python_in(project: Path, code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                          cwd=project, timeout=120, env={**os.environ, "SPRING_SCENES": "",
                                                         "PYTHONDONTWRITEBYTECODE": "1"})


def test_set_switches_the_new_force_on_in_a_single_mass_scene(project):
    done = main_py(project, "vertical", "--set", "w=3", "--steps", "1", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    (first,) = json.loads(done.stdout)["step_table"]
    assert first["F_net"] == [3.0, -78.0, 0.0]          # the wind along x; −k(|L| − L0) + m g along y
    off = main_py(project, "vertical", "--headless", "--json")
    assert json.loads(off.stdout)["r"][0] == 0.0       # w = 0 by default: no wind, as before


def test_its_model_has_no_exact_answer_and_says_why(project):
    done = main_py(project, "vertical", "--set", "w=3", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["exact"] is None
    assert "exact_valid_until: null, no closed form with wind" in out["notes"]
    assert out["constants"]["w"] == {"value": 3.0, "unit": "N", "meaning": "steady push of the wind along x"}
    text = main_py(project, "vertical", "--set", "w=3", "--headless").stdout
    assert "exact: none (no closed form with wind)" in text


def test_the_program_writes_its_line_and_names_its_arrow(project):
    done = main_py(project, "vertical", "--set", "w=3", "--arrows", "forces", "--vpython", "-")
    assert done.returncode == 0, done.stderr
    program = done.stdout
    assert "Fwind = vector(w, 0, 0)" in program and "wind: a steady push along x" in program
    assert "Fnet = Fspring + Fgravity + Fwind" in program
    assert any(line.startswith("w = 3") and "N: steady push of the wind along x" in line
               for line in program.splitlines())
    assert '"wind"' in program                          # the label on its arrow
    label = subprocess.run([sys.executable, "-c", textwrap.dedent("""
        from export.arrows import force_name
        from scenes import catalog
        model = catalog.configure("vertical", assignments=["w=3"]).build()
        print([force_name(force) for force in model.forces])
    """)], capture_output=True, text=True, cwd=project, timeout=120)
    assert label.returncode == 0, label.stderr
    assert label.stdout.strip() == "['spring', 'gravity', 'wind']"


def test_its_range_and_unit_come_from_its_declaration(project):
    bad = main_py(project, "vertical", "--set", "w=-5000", "--headless")
    assert bad.returncode == 2
    (line,) = bad.stderr.strip().splitlines()
    assert "w must be from -1000 to 1000 N" in line
    listed = main_py(project, "vertical", "--set", "w=3", "--constants")
    assert listed.returncode == 0, listed.stderr
    assert any(line.split()[:1] == ["w"] and "N" in line for line in listed.stdout.splitlines())


# ---- the eddy brake, with its closed-form role (issue 37, item 3) ----

def test_every_command_runs_with_the_brakes_role_declared(project):
    """Declaring the brake's role once made every command, --list included, end in a traceback."""
    listed = main_py(project, "--list")
    assert listed.returncode == 0 and listed.stderr == "" and "vertical" in listed.stdout
    done = main_py(project, "vertical", "--headless")
    assert done.returncode == 0 and done.stderr == ""


def test_the_brake_alone_has_dampings_closed_form_with_its_own_constant(project):
    """F = −c v is damping's law: the engine's run and the closed form (found by the brake's role)
    are those of `--set b=40`, bit for bit; with both on, a role two forces hold gives no closed
    form, and the note says why."""
    brake = json.loads(main_py(project, "vertical", "--set", "c=40", "--set", "until=3", "--headless", "--json").stdout)
    damped = json.loads(main_py(project, "vertical", "--set", "b=40", "--set", "until=3", "--headless", "--json").stdout)
    assert brake["r"] == damped["r"] and brake["p"] == damped["p"]
    assert brake["exact"] is not None and brake["exact"] == damped["exact"]
    both = main_py(project, "vertical", "--set", "c=20", "--set", "b=20", "--headless", "--json")
    assert both.returncode == 0, both.stderr
    out = json.loads(both.stdout)
    assert out["exact"] is None
    assert any("no closed form with both damping and eddy brake" in note for note in out["notes"])


def test_the_program_writes_the_brake_and_its_exact_curve_by_its_role(project):
    done = main_py(project, "vertical", "--set", "c=8", "--vpython", "-")
    assert done.returncode == 0, done.stderr
    program = done.stdout
    assert "Fbrake = -c*v" in program and "Fnet = Fspring + Fgravity + Fbrake" in program
    assert any(line.startswith("c = 8 ") and "kg/s: eddy-current braking constant" in line
               for line in program.splitlines())
    exact = [line for line in program.splitlines() if "gamma" in line and "=" in line]
    assert exact and any("c/(2*m)" in line.replace(" ", "") for line in exact), exact


def test_the_brake_gets_its_slider_from_its_declaration(project):
    """No scene names it: the force's `slider=True` gives it one wherever it is on."""
    done = python_in(project, """
        import json
        from scenes import catalog
        from scenes._sliders import slider_names
        off, on = catalog.configure("vertical"), catalog.configure("vertical", assignments=["c=3"])
        pendulum = catalog.configure("pendulum", assignments=["c=3"])
        print(json.dumps([slider_names(s, s.hooks.view) for s in (off, on, pendulum)]))
    """)
    assert done.returncode == 0, done.stderr
    off, on, pendulum = json.loads(done.stdout)
    assert "c" not in off and on == ["m", "k", "c"] and "c" in pendulum


def test_constants_and_forces_list_the_brake_off_and_on(project):
    listed = main_py(project, "vertical", "--constants")
    assert listed.returncode == 0, listed.stderr
    lines = listed.stdout.splitlines()
    assert any(line.split()[:4] == ["c", "=", "0", "kg/s"] and "eddy-current braking constant" in line for line in lines)
    assert any(line.startswith("forces: spring, gravity on;") and "eddy brake" in line.split(" on;")[1]
               for line in lines)
    on = main_py(project, "vertical", "--set", "c=3", "--constants").stdout
    assert "forces: spring, gravity, eddy brake on;" in on
    forces = main_py(project, "vertical", "--forces")
    assert forces.returncode == 0, forces.stderr
    (row,) = [line for line in forces.stdout.splitlines() if line.strip().startswith("eddy brake")]
    assert row.split()[2] == "off" and "F = −c v" in row and "c = 0 kg/s (slider when on)" in row
    (row,) = [line for line in main_py(project, "vertical", "--set", "c=3", "--forces").stdout.splitlines()
              if line.strip().startswith("eddy brake")]
    assert row.split()[2] == "on" and "c = 3 kg/s (slider)" in row


def test_the_stability_message_names_the_brake_and_its_own_constant(project):
    """The issue's case: c = 400 with b = 0 said "the damping (b/m = 40 s⁻¹)"."""
    done = main_py(project, "vertical", "--set", "c=400", "--headless")
    assert done.returncode == 1
    (line,) = done.stderr.strip().splitlines()
    assert "the eddy brake (c/m = 40 s⁻¹) makes dt < 0.04988 s necessary" in line, line
    assert "b/m" not in line and "the damping" not in line and "2·(c/m)·dt" in line


# ---- a force with a bad declaration: one line naming it and the fix ----

BAD = '''
"""A contributor's brake, with one mistake."""
from dataclasses import dataclass

from ..declared import Declared
from ..exact import Role
from .base import Force


@dataclass(frozen=True, eq=False)
class MagnetBrake(Force):
    """A magnet's brake.

    F = −q v,  q in kg/s.
    """

    q: float = 0.0
    uses_velocity = True
    LABEL = "magnet brake"
    CONSTANTS = {"q": DECLARATION}
    CLOSED_FORM = ROLES
    TERM = "Fmagnet"
    PROGRAM = (("Fmagnet = -{q}*{v}", "magnet brake: F = −q v"),)

    def __call__(self, t, r, v, m):
        return -self.q * v

    def closed_form(self):
        return {Role.DAMPING: self.q}
'''
GOOD = 'Declared("kg/s", 0, 1e3, default=0.0, switch=True, meaning="magnet braking constant")'


@pytest.mark.parametrize("declaration, roles, said", [
    ('Declared("", 0, 1e3, default=0.0, switch=True, meaning="magnet braking constant")', "{Role.DAMPING: 'q'}",
     "its constant q has no unit; give its SI unit first"),
    ('Declared("kg/s", 0, 1e3, switch=True, meaning="magnet braking constant")', "{Role.DAMPING: 'q'}",
     "its constant q declares a range but no default; give it one, like default=0.0"),
    ('Declared("kg/s", 0, 1e3, default=-5.0, switch=True, meaning="magnet braking constant")', "{Role.DAMPING: 'q'}",
     "the default of its constant q, -5.0, is not from 0 to 1000 kg/s"),
    ('Declared("kg/s", 0, 1e3, default=0.0, switch=True)', "{Role.DAMPING: 'q'}",
     "its constant q has no meaning; add meaning="),
    (GOOD, "{'friction': 'q'}", "CLOSED_FORM gives 'friction', which is not a role of the closed form"),
    (GOOD, "{Role.DAMPING: 'p'}", "CLOSED_FORM gives the closed form's b to 'p', which is not one of its CONSTANTS (q)"),
    (GOOD, "{Role.DAMPING: 'q', Role.STIFFNESS: 'q'}", "CLOSED_FORM gives its constant q two roles"),
    (GOOD, "{}", "its closed_form() is written, but CLOSED_FORM names no constant for its roles"),
    ('Declared("N", 0, 1e3, default=0.0, switch=True, meaning="a b of its own")', "{Role.DAMPING: 'q'}",
     "declares a constant b, as the damping force (physics/forces/page.py, LinearDamping) does, but differently"),
    ("Declred(1)", "{}", "the force module physics/forces/bad.py cannot be imported (line 20: NameError: name 'Declred'"),
])
def test_a_bad_declaration_is_one_line_naming_the_force_and_the_fix(declaration, roles, said, tmp_path):
    """Never a traceback at import: --list still runs; the command that needs the forces (here a
    single-mass scene, which takes every force's constants, and --forces) says what to fix."""
    text = BAD.replace("DECLARATION", declaration).replace("ROLES", roles)
    if "a b of its own" in declaration:
        text = text.replace('{"q": ' + declaration + "}", '{"q": ' + GOOD + ', "b": ' + declaration + "}")
    project = copy_of_the_project(tmp_path / "project", bad=text)
    listed = main_py(project, "--list")
    assert listed.returncode == 0 and listed.stderr == "", listed.stderr
    for argv in (["vertical", "--headless", "--set", "q=1"], ["vertical", "--forces"]):
        done = main_py(project, *argv)
        assert done.returncode == 2 and done.stdout == "", (argv, done.stdout)
        (line,) = done.stderr.strip().splitlines()
        assert line.startswith("error: ") and "Traceback" not in done.stderr
        assert said in line, line
        if "cannot be imported" not in said:
            assert "the magnet brake force (physics/forces/bad.py, MagnetBrake)" in line, line

"""The layers point down, and a new scene is one file that every front end finds by itself.

    main.py  →  browser/, reports/, cli/  →  lab/  →  export/  →  scenes/  →  physics/

physics/ imports nothing of ours; scenes/ only physics; export/ scenes and physics; lab/ (measured
data and the fit) export, scenes and physics; browser/, reports/ and cli/ (the command line's
options) everything below them and never each other (docs/architecture.md). The imports are read
from the source with ast, so a test fails the moment an arrow points the wrong way.
"""
import ast
import json
import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("physics", "scenes", "export", "lab", "browser", "reports", "cli")
MAY_IMPORT = {
    "physics": set(),
    "scenes": {"physics"},
    "export": {"physics", "scenes"},
    "lab": {"physics", "scenes", "export"},
    "browser": {"physics", "scenes", "export", "lab"},
    "reports": {"physics", "scenes", "export", "lab"},
    "cli": {"physics", "scenes", "export", "lab"},
}


def ours_imported_by(path: Path) -> set[str]:
    """The project's top-level packages (and main) that a file imports, anywhere in it."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names = [node.module]
        else:
            continue
        found |= {name.split(".")[0] for name in names if name.split(".")[0] in PACKAGES + ("main",)}
    return found


@pytest.mark.parametrize("package", PACKAGES)
def test_imports_point_only_down(package):
    wrong = {}
    for path in sorted((ROOT / package).rglob("*.py")):
        bad = ours_imported_by(path) - MAY_IMPORT[package] - {package}
        if bad:
            wrong[str(path.relative_to(ROOT))] = sorted(bad)
    assert not wrong, f"imports that point up or sideways: {wrong}"


def test_the_check_would_see_an_arrow_pointing_up(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("from browser.view import show\nimport reports.headless\n")
    assert ours_imported_by(bad) == {"browser", "reports"}


def test_the_scenes_folder_holds_only_scenes_and_private_builders():
    for path in (ROOT / "scenes").glob("*.py"):
        if path.name.startswith("_"):
            continue
        source = path.read_text()
        assert "def build(" in source and "# ---- end of constants ----" in source, path.name


A_NEW_SCENE = '''
    """A test scene: one mass on a soft spring, found in a folder of the teacher's own."""
    from scenes._single_mass import build_single_mass

    # ---- constants: edit these (unit: meaning); 0 switches a force off ----
    m = 2.0                    # kg: mass of the block
    k = 8.0                    # N/m: spring constant (stiffness)
    L0 = 1.0                   # m: relaxed length of the spring
    g = 0.0                    # m/s²: strength of gravity, acting along −y (y is up)
    b = 0.0                    # kg/s: linear damping constant in F = −b v
    C = 0.0                    # 1: drag coefficient in F = −½ C A ρ |v| v
    A = 0.0                    # m²: cross-section area of the mass, for drag
    rho = 0.0                  # kg/m³: air density, for drag
    F0 = 0.0                   # N: driving force amplitude in F = F0 cos(ω t)
    omega = 0.0                # rad/s: driving angular frequency ω
    drive_axis = (1, 0, 0)     # 1: direction of the driving force
    anchor = (0, 0, 0)         # m: fixed end of the spring
    r0 = (1.5, 0, 0)           # m: start position (stretched 0.5 m)
    v0 = (0, 0, 0)             # m/s: start velocity
    dt = 0.01                  # s: time step Δt
    until = 3.14159            # s: about one and a half periods (ω = 2 rad/s)
    # ---- end of constants ----


    def build(**constants):
        """The soft spring."""
        return build_single_mass(**constants)


    VIEW = {"support": "wall", "plot": "x"}
'''


def test_a_scene_added_in_its_own_folder_is_found_everywhere(tmp_path):
    """One new file: --list, a headless run and the page's scene menu all find it (the tree stays as it is)."""
    (tmp_path / "softspring.py").write_text(textwrap.dedent(A_NEW_SCENE))
    env = {**os.environ, "SPRING_SCENES": str(tmp_path)}

    def main(*args):
        return subprocess.run([sys.executable, "main.py", *args], cwd=ROOT, env=env,
                              capture_output=True, text=True, timeout=120)

    listed = main("--list")
    assert listed.returncode == 0 and "softspring" in listed.stdout
    assert "A test scene: one mass on a soft spring" in listed.stdout
    done = main("softspring", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    # ω = √(k/m) = 2 rad/s about the relaxed length: x = L0 + 0.5 cos(2t) m, and the run is close
    assert out["exact"]["r"][0] == pytest.approx(1.0 + 0.5 * math.cos(2 * out["t"]), abs=1e-9)
    assert out["r"][0] == pytest.approx(out["exact"]["r"][0], abs=0.01)
    menu = subprocess.run([sys.executable, "-c", "from browser.view import scene_menu_choices\n"
                           "print(scene_menu_choices())"], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=60)
    assert menu.returncode == 0, menu.stderr
    assert "softspring" in menu.stdout and "vertical" in menu.stdout
    assert not (ROOT / "scenes" / "softspring.py").exists()

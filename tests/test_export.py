"""The exported VPython programs (main.py SCENE --vpython FILE.py) reach the engine's state.

Each scene's program is run as a teacher's student would run it, `python FILE.py`, but with a
stand-in `vpython` module of our own in front of the real one: its display objects only keep the
attributes they are given and `rate` returns at once, so no browser is needed. Its `vector` is
vpython's own compiled vector class (vpython/cyvector), loaded on its own, so the arithmetic is
exactly what the real vpython does. The program's printed final position and momentum must equal
`main.py SCENE --headless --json` after the same number of steps, to 1e-12 relative.
"""
from __future__ import annotations

import importlib.util
import json
import os
import re
import stat
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from scenes import catalog

ROOT = Path(__file__).resolve().parent.parent
NUMBER = r"(-?[0-9.]+(?:e[-+]?\d+)?|-?inf|nan)"
VECTOR = rf"<\s*{NUMBER}\s*,\s*{NUMBER}\s*,\s*{NUMBER}\s*>"
ANSWER = re.compile(rf"t = {NUMBER} s:\s+r = {VECTOR} m,\s+p = {VECTOR} kg·m/s")

STAND_IN = '''"""A stand-in for vpython: display objects keep their attributes, rate() returns at once."""
import atexit
import importlib.util
import json
import os
from math import *

_spec = importlib.util.spec_from_file_location("cyvector", {cyvector!r})
_vectors = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_vectors)
vector, mag, norm, dot, cross, hat = (_vectors.vector, _vectors.mag, _vectors.norm, _vectors.dot,
                                      _vectors.cross, _vectors.hat)
vec = vector
DRAWN = []


class _Shown:
    def __init__(self, **attributes):
        self.__dict__.update(attributes)
        DRAWN.append(self)


class box(_Shown): pass
class helix(_Shown): pass
class sphere(_Shown): pass
class graph(_Shown): pass


class gcurve(_Shown):
    def __init__(self, **attributes):
        super().__init__(**attributes)
        self.points = []

    def plot(self, *point):
        self.points.append(point)


class color:
    orange = vector(1, 0.6, 0)
    cyan = vector(0, 1, 1)
    green = vector(0, 1, 0)
    magenta = vector(1, 0, 1)
    yellow = vector(1, 1, 0)
    red = vector(1, 0, 0)
    blue = vector(0, 0, 1)
    black = vector(0, 0, 0)

    @staticmethod
    def gray(level):
        return vector(level, level, level)


def rate(frequency):
    return True


def _plain(value):
    if isinstance(value, vector):
        return [value.x, value.y, value.z]
    return value if isinstance(value, (int, float, str)) else repr(value)


@atexit.register
def _report():
    """What was drawn, as JSON in the file $STAND_IN_REPORT: each object's kind and attributes."""
    report = [{"kind": type(shown).__name__, **{key: _plain(value) for key, value in vars(shown).items()
                                                 if key != "points"},
               **({"points": [list(point) for point in shown.points]} if hasattr(shown, "points") else {})}
              for shown in DRAWN]
    with open(os.environ["STAND_IN_REPORT"], "w") as out:
        json.dump(report, out)
'''


def _cyvector() -> str:
    folder = importlib.util.find_spec("vpython").submodule_search_locations[0]
    found = [name for name in os.listdir(folder) if name.startswith("cyvector") and name.endswith(".so")]
    if not found:
        pytest.skip("vpython has no compiled vector class here")
    return os.path.join(folder, found[0])


@pytest.fixture(scope="module")
def stand_in(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("stand_in")
    (folder / "vpython.py").write_text(STAND_IN.replace("{cyvector!r}", repr(_cyvector())), encoding="utf-8")
    return folder


def main_py(*args, cwd=ROOT):
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *args], capture_output=True, text=True,
                          cwd=cwd, timeout=300)


def run_program(path: Path, stand_in: Path, drawn: list | None = None) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """Run a written program under the stand-in vpython; its answers as (t, r, p), one per mass.

    drawn, if given, receives what the program drew: one dict per object (kind, attributes, points).
    """
    report = path.with_suffix(".drawn.json")
    env = {**os.environ, "PYTHONPATH": str(stand_in), "STAND_IN_REPORT": str(report)}
    done = subprocess.run([sys.executable, str(path)], capture_output=True, text=True, env=env,
                          cwd=path.parent, timeout=300)
    assert done.returncode == 0, done.stderr
    answers = []
    for line in done.stdout.splitlines():
        match = ANSWER.search(line)
        if match:
            numbers = [float(x) for x in match.groups()]
            answers.append((numbers[0], np.array(numbers[1:4]), np.array(numbers[4:7])))
    assert answers, f"no answer printed: {done.stdout!r}"
    if drawn is not None:
        drawn.extend(json.loads(report.read_text()))
    return answers


CASES = [
    ("vertical",),
    ("vertical", "--set", "dt=0.01", "--set", "until=5"),
    ("vertical", "--set", "until=4", "--set", "dt=0.01", "--integrator", "euler"),
    ("vertical", "--set", "until=4", "--set", "dt=0.01", "--integrator", "verlet"),
    ("vertical", "--set", "until=4", "--set", "dt=0.01", "--integrator", "rk4"),
    ("vertical", "--preset", "Moon gravity", "--set", "until=3", "--set", "dt=0.02"),
    ("vertical", "--set", "L0=0", "--set", "r0=0.3,-1.2,0.1", "--set", "until=2", "--set", "dt=0.01"),
    ("vertical", "--set", "C=0.5", "--set", "A=0.2", "--set", "rho=1.2", "--set", "F0=3", "--set", "omega=2",
     "--set", "drive_axis=1,1,0", "--set", "until=3", "--set", "dt=0.01", "--integrator", "rk4"),
    ("damped",),
    ("damped", "--set", "until=6", "--set", "dt=0.01"),
    ("damped", "--set", "until=6", "--set", "dt=0.01", "--integrator", "verlet"),
    ("damped", "--set", "until=6", "--set", "dt=0.01", "--integrator", "rk4"),
    ("damped", "--set", "until=6", "--set", "dt=0.01", "--integrator", "euler"),
    ("damped", "--preset", "critical damping", "--set", "until=3", "--set", "dt=0.01"),
    ("driven", "--scenario", "1"),
    ("driven", "--scenario", "2", "--integrator", "verlet"),
    ("driven", "--scenario", "3", "--integrator", "rk4"),
    ("driven", "--scenario", "5", "--set", "until=8"),
    ("regimes",),
    ("regimes", "--integrator", "rk4", "--set", "until=3"),
    ("drag", "--set", "until=5"),
    ("drag", "--preset", "falling, no spring", "--set", "until=3", "--integrator", "verlet"),
    ("pendulum", "--set", "until=5"),
    ("pendulum", "--set", "until=3", "--integrator", "rk4", "--set", "b=0.2"),
    ("integrators",),
    ("integrators", "--set", "dt=0.01", "--set", "until=2"),
    ("resonance", "--set", "until=10", "--set", "settle=0.5"),
]


def engine_counts_steps() -> bool:
    """Whether the engine's time is n·Δt from a step count (as the programs' is), not a running sum.

    Ten steps of 0.1 s summed give 0.9999999999999999 s; counted, 10 × 0.1 = 1.0 s.
    """
    from physics.forces import Spring
    from physics.simulate import run
    from physics.state import make_state

    return run(make_state(r=(1.0, 0, 0), m=1.0), (Spring(k=1.0),), dt=0.1, until=1.0).t[-1] == 1.0


DRIVEN = ("driven", "resonance")
EXACT_CURVES = ("vertical", "damped", "driven", "regimes", "integrators")   # scenes that draw the closed form   # F0 cos(ω t): the only force that reads t


@pytest.mark.parametrize("case", CASES, ids=[" ".join(case) for case in CASES])
def test_program_reaches_the_headless_state(case, stand_in, tmp_path):
    rtol = 1e-12
    if (case[0] in DRIVEN or "F0=3" in case) and not engine_counts_steps():
        # Until the engine counts t = t0 + n·Δt too, its t drifts from the program's n·Δt by
        # round-off, and cos(ω t) with it: the states then agree to about 1e-12 only.
        rtol = 1e-9
    path = tmp_path / "program.py"
    written = main_py(*case, "--vpython", str(path))
    assert written.returncode == 0, written.stderr
    headless = main_py(*case, "--headless", "--json")
    assert headless.returncode == 0, headless.stderr
    expected = json.loads(headless.stdout)
    drawn = []
    answers = run_program(path, stand_in, drawn)
    check_drawing(drawn, expected, answers)
    r_expected = np.atleast_2d(expected["r"])
    p_expected = np.atleast_2d(expected["p"])
    assert len(answers) == len(r_expected)
    for (t, r, p), r_engine, p_engine in zip(answers, r_expected, p_expected):
        assert t == pytest.approx(expected["t"], rel=rtol, abs=1e-12)
        scale_r = np.max(np.abs(r_engine))
        scale_p = max(np.max(np.abs(p_engine)), 1e-300)
        assert np.max(np.abs(r - r_engine)) <= rtol * scale_r, (r, r_engine)
        assert np.max(np.abs(p - p_engine)) <= rtol * scale_p, (p, p_engine)


def check_drawing(drawn, expected, answers):
    """A support box, a helix ending at each sphere, a sphere at each final position, and curves
    with a point per step ending at the final coordinate; the exact curve ends at headless's exact r."""
    kinds = [shown["kind"] for shown in drawn]
    count = len(answers)
    assert kinds.count("box") == 1 and kinds.count("graph") == 1
    assert kinds.count("helix") == count and kinds.count("sphere") == count
    helices = [shown for shown in drawn if shown["kind"] == "helix"]
    spheres = [shown for shown in drawn if shown["kind"] == "sphere"]
    for helix, sphere, (t, r, p) in zip(helices, spheres, answers):
        assert sphere["pos"] == pytest.approx(list(r), abs=0)
        assert np.add(helix["pos"], helix["axis"]) == pytest.approx(list(r), rel=1e-12, abs=1e-12)
    curves = [shown for shown in drawn if shown["kind"] == "gcurve" and shown.get("label") != "exact"
              and shown["color"] != [0, 0, 0]]
    exact = [shown for shown in drawn if shown["kind"] == "gcurve" and shown["color"] == [0, 0, 0]]
    assert len(curves) >= count
    for curve in curves:
        assert len(curve["points"]) == expected["steps"]
        assert curve["points"][-1][0] == answers[0][0]
    view = getattr(catalog.load(expected["scene"]), "VIEW", {})
    axis = "xyz".index(view.get("plot", "y")[0])
    known = [body["exact"]["r"] for body in (expected.get("bodies") or [expected]) if "exact" in body]
    if expected["scene"] in EXACT_CURVES and len(known) == count:
        assert len(exact) == count, "an exact curve for each mass"
    for curve, r_exact in zip(exact, known):
        assert len(curve["points"]) == expected["steps"]
        assert curve["points"][-1][1] == pytest.approx(r_exact[axis], rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
def test_web_vpython_file_is_the_same_program(scene, tmp_path):
    """Web VPython's file differs only in its first line (`Web VPython 3.2`) and in having no imports."""
    desktop, web = tmp_path / "desktop.py", tmp_path / "web.py"
    done = main_py(scene, "--integrator", "rk4", "--vpython", str(desktop), "--webvpython", str(web))
    assert done.returncode == 0, done.stderr
    desktop_lines = desktop.read_text(encoding="utf-8").splitlines()
    web_lines = web.read_text(encoding="utf-8").splitlines()
    assert web_lines[0] == "Web VPython 3.2"
    assert not any(line.startswith(("import ", "from ")) for line in web_lines)
    imports = [line for line in desktop_lines if line.startswith(("import ", "from "))]
    assert imports == ["from vpython import *"]
    assert web_lines[1:] == [line for line in desktop_lines[1:] if line not in imports]


def test_program_reads_like_the_page(tmp_path):
    """The default scene's program: constants with units, one while loop with the page's update, at most ~80 lines."""
    path = tmp_path / "vertical.py"
    assert main_py("vertical", "--vpython", str(path)).returncode == 0
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    assert len(lines) <= 80
    assert "m = 10                   # kg: mass of the block" in lines
    assert not any(line.lstrip().startswith("def ") for line in lines)
    assert sum(line.lstrip().startswith("while ") for line in lines) == 1
    assert any(line.strip().startswith("p = p + Fnet*dt") for line in lines)
    assert any(line.strip().startswith("pos = pos + p/m*dt") for line in lines)
    for scene in ("damped", "driven", "pendulum"):
        for method in ("euler-cromer", "euler", "verlet", "rk4"):
            done = main_py(scene, "--integrator", method, "--vpython", "-")
            assert done.returncode == 0 and len(done.stdout.splitlines()) <= 80, (scene, method)


@pytest.mark.parametrize("args, message", [
    (("vertical", "--vpython", "/nonexistent-folder/spring.py"), "does not exist"),
    (("vertical", "--vpython", "/proc/spring.py"), "cannot write the program"),
    (("vertical", "--vpython", "."), "is a directory"),
    (("vertical", "--set", "kk=3", "--vpython", "OUT"), "unknown constant 'kk'"),
    (("vertical", "--preset", "Mars gravity", "--webvpython", "OUT"), "unknown preset"),
    (("driven", "--scenario", "9", "--vpython", "OUT"), "out of range"),
    (("nosuchscene", "--vpython", "OUT"), "unknown scene"),
    (("vertical", "--set", "m=0", "--vpython", "OUT"), "m must be"),
])
def test_bad_input_gets_one_line_and_no_file(args, message, tmp_path):
    out = tmp_path / "spring.py"
    args = tuple(str(out) if arg == "OUT" else arg for arg in args)
    done = main_py(*args, cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and done.stderr.startswith("error: ") and message in done.stderr
    assert "Traceback" not in done.stderr
    assert list(tmp_path.iterdir()) == []          # no program, no temporary file left behind


def test_read_only_folder_leaves_no_file(tmp_path):
    folder = tmp_path / "handouts"
    folder.mkdir()
    folder.chmod(stat.S_IRUSR | stat.S_IXUSR)
    try:
        if os.access(folder, os.W_OK):
            pytest.skip("running as root: a read-only folder is still writable")
        done = main_py("vertical", "--vpython", str(folder / "spring.py"))
        assert done.returncode == 2 and done.stderr.startswith("error: cannot write the program")
        assert list(folder.iterdir()) == []
    finally:
        folder.chmod(stat.S_IRWXU)


def test_program_replaces_an_old_file_whole(tmp_path):
    """Written through a temporary file renamed over the old one: readable by others like any new file."""
    path = tmp_path / "spring.py"
    path.write_text("old handout\n" * 1000)
    assert main_py("damped", "--vpython", str(path)).returncode == 0
    text = path.read_text(encoding="utf-8")
    assert text.startswith("# damped:") and "old handout" not in text
    assert [p.name for p in tmp_path.iterdir()] == ["spring.py"]
    mask = os.umask(0)
    os.umask(mask)
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~mask      # not mkstemp's private 0600


def test_writer_stays_in_its_layer():
    """export/ imports only physics and scenes: never vpython, the command line or the browser view,
    so that both front ends can use it (checked in a fresh interpreter)."""
    code = ("import sys, export\n"
            "from scenes import catalog\n"
            "for name in catalog.SCENE_NAMES:\n"
            "    export.program(catalog.configure(name), web=True)\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in ('vpython', 'reports', 'browser', 'main')"
            " or m == 'browser.view'))\n")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip().splitlines()[-1] == "[]"


def test_one_bad_path_of_two_leaves_neither_file(tmp_path):
    good = tmp_path / "spring.py"
    done = main_py("vertical", "--vpython", str(good), "--webvpython", str(tmp_path / "no" / "web.py"))
    assert done.returncode == 2 and done.stderr.startswith("error: cannot write the program")
    assert list(tmp_path.iterdir()) == []


def test_program_and_headless_run_together(tmp_path):
    path = tmp_path / "spring.py"
    done = main_py("vertical", "--headless", "--vpython", str(path))
    assert done.returncode == 0 and path.exists()
    assert "r = < 0, -1.73088, 0 > m" in done.stdout

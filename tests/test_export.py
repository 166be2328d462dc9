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

from export.palette import EXACT_COLOUR
from scenes import catalog
from scenes._view import DEFAULT_VIEW

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
class arrow(_Shown): pass
class label(_Shown): pass


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
    if isinstance(value, list):
        return [_plain(item) for item in value]
    return value if isinstance(value, (int, float, str)) else repr(value)


@atexit.register
def _report():
    """What was drawn, as JSON in the file $STAND_IN_REPORT: each object's kind and attributes, and
    last the program's own t, pos and p when it ended, to every digit (kind "state")."""
    import __main__
    report = [{"kind": type(shown).__name__, **{key: _plain(value) for key, value in vars(shown).items()
                                                 if key != "points"},
               **({"points": [list(point) for point in shown.points]} if hasattr(shown, "points") else {})}
              for shown in DRAWN]
    report.append({"kind": "state", **{name: _plain(getattr(__main__, name, None)) for name in ("t", "pos", "p")}})
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


def main_py(*args, cwd=ROOT, timeout=300):
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *args], capture_output=True, text=True,
                          cwd=cwd, timeout=timeout)


def run_program(path: Path, stand_in: Path, drawn: list | None = None,
                printed: list | None = None) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """Run a written program under the stand-in vpython; its answers as (t, r, p), one per mass.

    drawn, if given, receives what the program drew: one dict per object (kind, attributes, points),
    and last its t, pos and p when it ended (kind "state"); printed, the lines of its answer.
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
            if printed is not None:
                printed.append(line)
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
    # rows built from constants that round: a row's rule must still give the engine's numbers
    ("resonance", "--set", "omega_min=0.3", "--set", "omega_max=7.7", "--set", "count=11", "--set", "spacing=0.37",
     "--set", "b_ratio=3", "--set", "until=3", "--set", "settle=0.1", "--set", "periods=0.1"),
    ("regimes", "--set", "k=0.3", "--set", "m=2.7", "--set", "spacing=0.7", "--set", "until=3"),
    ("integrators", "--set", "x0=0.3", "--set", "spacing=0.7"),
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
    drawn, printed = [], []
    answers = run_program(path, stand_in, drawn, printed)
    check_answer(printed, answers, expected)
    t_end, r_end, p_end = final_state(drawn)   # the program runs on past the question time, to watch
    assert t_end >= max(expected["t"], {**DEFAULT_VIEW, **catalog.load(case[0]).VIEW}["window"]) - 1e-9
    ended = main_py(*case, "--headless", "--json", "--until", repr(t_end))
    assert ended.returncode == 0, ended.stderr
    expected = json.loads(ended.stdout)
    check_drawing(drawn, expected, r_end)
    assert t_end == pytest.approx(expected["t"], rel=rtol, abs=1e-12)
    for r, p, r_engine, p_engine in zip(r_end, p_end, np.atleast_2d(expected["r"]), np.atleast_2d(expected["p"])):
        scale_r = np.max(np.abs(r_engine))
        scale_p = max(np.max(np.abs(p_engine)), 1e-300)
        assert np.max(np.abs(r - r_engine)) <= rtol * scale_r, (r, r_engine)
        assert np.max(np.abs(p - p_engine)) <= rtol * scale_p, (p, p_engine)


def check_answer(printed, answers, expected):
    """The printed answer, one line per mass at the question time, is the command line's, digit for
    digit: `at t = 0.2 s: r = < 0, -1.7301, 0 > m, p = < 0, -15.21, 0 > kg·m/s` beside --headless's
    `r = < 0, -1.7301, 0 > m` (it printed -1.7301000000000002)."""
    from export.step_update import number, vector

    r_expected, p_expected = np.atleast_2d(expected["r"]), np.atleast_2d(expected["p"])
    assert len(answers) == len(r_expected) == len(printed)
    for line, r, p in zip(printed, r_expected, p_expected):
        assert f"at t = {number(expected['t'])} s: r = {vector(r, 'm')}, p = {vector(p, 'kg·m/s')}" in line, line


def run_to_end(path: Path, stand_in: Path) -> list[tuple[float, np.ndarray, np.ndarray]]:
    """Run a written program under the stand-in vpython; its own t, pos and p when it ended, to every
    digit, as (t, r, p), one per mass (its printed answer is rounded as the command line's)."""
    drawn = []
    run_program(path, stand_in, drawn)
    t, r, p = final_state(drawn)
    return [(t, r_i, p_i) for r_i, p_i in zip(r, p)]


def final_state(drawn):
    """The program's own t, and each mass's pos and p, when it ended, to every digit (the stand-in's)."""
    state = next(shown for shown in drawn if shown["kind"] == "state")
    return state["t"], np.atleast_2d(state["pos"]), np.atleast_2d(state["p"])


def check_drawing(drawn, expected, final_r):
    """A support box, a helix ending at each sphere, a sphere at each final position, and curves
    with a point per step ending at the final coordinate; the exact curve ends at headless's exact r."""
    kinds = [shown["kind"] for shown in drawn]
    count = len(final_r)
    answers = [(final_state(drawn)[0], r, None) for r in final_r]
    assert kinds.count("box") == 1 and kinds.count("graph") == 1
    assert kinds.count("helix") == count and kinds.count("sphere") == count
    helices = [shown for shown in drawn if shown["kind"] == "helix"]
    spheres = [shown for shown in drawn if shown["kind"] == "sphere"]
    for helix, sphere, (t, r, p) in zip(helices, spheres, answers):
        assert sphere["pos"] == pytest.approx(list(r), abs=0)
        assert np.add(helix["pos"], helix["axis"]) == pytest.approx(list(r), rel=1e-12, abs=1e-12)
    curves = [shown for shown in drawn if shown["kind"] == "gcurve" and shown["color"] != list(EXACT_COLOUR)]
    exact = [shown for shown in drawn if shown["kind"] == "gcurve" and shown["color"] == list(EXACT_COLOUR)]
    assert len(curves) >= count
    for curve in curves:   # from t = 0, then one point a step
        assert len(curve["points"]) == expected["steps"] + 1 and curve["points"][0][0] == 0
        assert curve["points"][-1][0] == answers[0][0]
    view = getattr(catalog.load(expected["scene"]), "VIEW", {})
    axis = "xyz".index(view.get("plot", "y")[0])
    known = [body["exact"]["r"] for body in (expected.get("bodies") or [expected]) if body.get("exact")]
    if expected["scene"] in EXACT_CURVES and len(known) == count:
        assert len(exact) == count, "an exact curve for each mass"
    for curve, r_exact in zip(exact, known):
        assert len(curve["points"]) == expected["steps"]
        assert curve["points"][-1][1] == pytest.approx(r_exact[axis], rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("scene", catalog.SCENE_NAMES)
def test_web_vpython_file_is_the_same_program(scene, tmp_path):
    """Web VPython's file differs only in its first line (`Web VPython 3.2`) and in having no imports
    (and each file's mark line, with its own fingerprint: the first line, after `Web VPython 3.2`)."""
    desktop, web = tmp_path / "desktop.py", tmp_path / "web.py"
    own_methods = catalog.configure(scene).build().integrators is not None   # --integrator is refused there
    choice = () if own_methods else ("--integrator", "rk4")
    done = main_py(scene, *choice, "--vpython", str(desktop), "--webvpython", str(web))
    assert done.returncode == 0, done.stderr
    desktop_lines = desktop.read_text(encoding="utf-8").splitlines()
    web_lines = web.read_text(encoding="utf-8").splitlines()
    for lines in (desktop_lines, web_lines):   # each file's mark and fingerprint (export/marks.py): one line, set aside
        marked = [line for line in lines if line.startswith("# Written by the spring-mass simulator; its fingerprint")]
        assert len(marked) == 1 and lines.index(marked[0]) == (1 if lines is web_lines else 0)
        lines.remove(marked[0])
    assert web_lines[0] == "Web VPython 3.2"
    assert not any(line.startswith(("import ", "from ")) for line in web_lines)
    from export.vpython_program import IMPORTS

    imports = [line for line in desktop_lines if line.startswith(("import ", "from ", "socket."))]
    assert imports == IMPORTS == ["from vpython import *", *IMPORTS[1:]]   # and the lines keeping it on this computer
    assert web_lines[1:] == [line for line in desktop_lines[1:] if line not in imports]
    description = f"# {scene}: {catalog.summary(catalog.load(scene))}"
    assert description in desktop_lines and description in web_lines     # Web VPython keeps it too


def test_program_reads_like_the_page(tmp_path):
    """The default scene's program: constants with units, one while loop with the page's update."""
    path = tmp_path / "vertical.py"
    assert main_py("vertical", "--vpython", str(path)).returncode == 0
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    assert "m = 10                   # kg: mass of the block" in lines
    assert [line for line in lines if line.lstrip().startswith("def ")] == ANSWER_DEFS
    assert sum(line.lstrip().startswith("while ") for line in lines) == 1
    assert any(line.strip().startswith("p = p + Fnet*dt") for line in lines)
    assert any(line.strip().startswith("pos = pos + p/m*dt") for line in lines)


SINGLE_MASS = ("vertical", "damped", "driven", "pendulum")
# The only functions a program defines: how its answer is written, with the command line's digits in
# Python and in Web VPython alike (export/program_answer.py; the rest reads top to bottom).
ANSWER_DEFS = ["def number(x, size=0):", "def vector_text(v):"]


@pytest.mark.parametrize("scene", SINGLE_MASS)
def test_single_mass_programs_stay_short(scene):
    """At most 80 lines, and 10 more for the p and F_net arrows and the see-through ball
    (export/program_arrows.py), and 25 more for the exact curve's cases written as branches (the
    three damping regimes and undamped resonance, export/exact_curve.py: issue 41), for every
    scenario and every integrator (driven's scenario 4 with verlet was 85: the verlet update wrote
    its block of forces three times; with the branches driven's longest is 105)."""
    import export
    from export.program_answer import HELPERS
    from physics.integrators import INTEGRATORS

    module = catalog.load(scene)
    for scenario in [None, *range(1, len(catalog.scenarios(module)) + 1)]:
        setup = catalog.configure(scene, scenario=scenario)
        for method in INTEGRATORS:
            lines = export.program(setup, integrator=method).splitlines()
            # 80, plus the two lines that keep vpython's server on this computer and the t = 0 point
            # (issue 20), the answer's two functions (issue 20: Web VPython's digits), and at most 10
            # lines that draw the p and F_net arrows and make the ball see-through for them (issue 17),
            # and the exact curve's branches (issue 41)
            arrows = sum("arrow" in line or "scale = 1/" in line for line in lines)
            assert len(lines) - arrows <= 83 + 25 + len(HELPERS) and arrows <= 10, \
                (scene, scenario, method, len(lines), arrows)
            assert [line for line in lines if line.lstrip().startswith("def ")] == ANSWER_DEFS


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
    assert main_py("vertical", "--vpython", str(path)).returncode == 0
    path.write_text(path.read_text(encoding="utf-8") + "old handout\n" * 1000)   # a handout of ours, edited
    assert main_py("damped", "--vpython", str(path), "--overwrite").returncode == 0
    text = path.read_text(encoding="utf-8")
    assert text.startswith("# Written by the spring-mass simulator; its fingerprint is sha256:")
    assert "\nfrom vpython import *\n" in text and "\n# damped:" in text and "old handout" not in text
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


# ---- writing files: links, devices, pipes ----

def test_a_symbolic_link_is_followed_not_replaced(tmp_path):
    """The file a link points to is replaced whole; the link stays a link (it used to become a file)."""
    real, link = tmp_path / "real.csv", tmp_path / "link.csv"
    real.write_text("old\n")
    link.symlink_to("real.csv")
    done = main_py("vertical", "--headless", "--csv", str(link), "--overwrite")   # "old" is not a file of ours
    assert done.returncode == 0, done.stderr
    assert link.is_symlink() and os.readlink(link) == "real.csv"
    assert real.read_text().startswith("t,x,y,z")
    program, later = tmp_path / "handout.py", tmp_path / "later.py"   # a link to a file not made yet
    program.symlink_to("later.py")
    assert main_py("damped", "--vpython", str(program)).returncode == 0
    assert program.is_symlink() and "# damped:" in later.read_text(encoding="utf-8")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["handout.py", "later.py", "link.csv", "real.csv"]


@pytest.mark.parametrize("flags", [("--headless", "--csv"), ("--vpython",)])
def test_a_named_pipe_is_refused_at_once(flags, tmp_path):
    """A FIFO is refused with one line before anything opens it (opening it waited for a reader for ever)."""
    fifo = tmp_path / "out.csv"
    os.mkfifo(fifo)
    done = main_py("vertical", *flags, str(fifo), timeout=30)
    assert done.returncode == 2
    assert done.stderr.count("\n") == 1 and "it is a named pipe, not a regular file" in done.stderr
    assert stat.S_ISFIFO(os.stat(fifo).st_mode) and [p.name for p in tmp_path.iterdir()] == ["out.csv"]


def test_a_socket_is_refused(tmp_path):
    import socket

    from export import files

    path = tmp_path / "s"
    with socket.socket(socket.AF_UNIX) as server:
        server.bind(str(path))
        with pytest.raises(files.OutputError, match="it is a socket, not a regular file"):
            files.check_writable(str(path), what="CSV file")
        with pytest.raises(files.OutputError, match="it is a socket"):
            with files.atomic_file(str(path), what="CSV file"):
                pass
    assert [p.name for p in tmp_path.iterdir()] == ["s"]


# ---- big runs and many masses ----

def test_many_steps_are_counted_at_once(tmp_path):
    """dt = 1e-6 s until 1e6 s is 10¹² steps: the writer works their number out, it does not count them
    (that took many minutes, and the page's Download program asks for it too)."""
    path = tmp_path / "long.py"
    done = main_py("vertical", "--set", "dt=1e-6", "--set", "until=1e6", "--vpython", str(path), timeout=60)
    assert done.returncode == 0, done.stderr
    assert "while t < until" in path.read_text(encoding="utf-8")


def test_the_loop_takes_the_steps_of_a_headless_run():
    """The loop's condition stops after steps_to_reach steps, with t = n*dt in floats as the program has it."""
    from types import SimpleNamespace

    from export.vpython_program import _loop_condition
    from physics.simulate import steps_to_reach

    rng = np.random.default_rng(11)
    for _ in range(3000):
        dt = float(rng.choice([0.1, 0.01, 0.02, 0.005, 0.06, 1e-3, 0.3, 0.7])) * float(rng.choice([1, 1, 3, 7]))
        until = round(float(rng.uniform(0, 40)), int(rng.integers(0, 4)))
        condition = _loop_condition(SimpleNamespace(until=until, dt=dt, state=SimpleNamespace(t=0.0)))
        steps, n, t = steps_to_reach(until, dt), 0, 0
        limit = until - 1e-9 * dt if "1e-9*dt" in condition else until
        while (n < steps) if "while n <" in condition else (t < limit):
            n += 1
            t = n * dt
        assert n == steps, (until, dt, condition)


def test_more_masses_than_the_page_draws_are_refused(tmp_path):
    """10⁶ springs hung the writer; over the page's 2,000 masses the program is refused in one line."""
    path = tmp_path / "big.py"
    done = main_py("resonance", "--set", "count=1000", "--set", "curves=3", "--vpython", str(path))
    assert done.returncode == 2 and done.stderr.count("\n") == 1
    assert "3,000 masses are more than the 2,000" in done.stderr and "count" in done.stderr
    assert not path.exists()


# ---- what a teacher reads ----

ROUND_OFF_DIGITS = re.compile(r"\d\.\d*(?:0000000|9999999)\d\b")   # 2.4000000000000004, 0.8999999999999999


@pytest.mark.parametrize("args", [("resonance",), ("integrators", "--set", "x0=0.3", "--set", "spacing=1"),
                                  ("regimes",), ("drag",), ("regimes", "--set", "spacing=0.7", "--set", "x0=0.3")])
def test_a_row_of_masses_is_built_from_the_scene_constants(args):
    """The lists of a row follow the scene's rule from its constants, written as constants and a for
    loop: no line of thousands of characters, no round-off digits, and the constants that set the
    row (spacing, x0, omega_min, ...) are there to edit."""
    done = main_py(*args, "--vpython", "-")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    # the mark line (export/marks.py) is one fixed line that says whose the file is; the rest is the program
    assert lines[0].startswith("# Written by the spring-mass simulator; its fingerprint is sha256:")
    assert max(len(line) for line in lines[1:]) <= 140
    assert not ROUND_OFF_DIGITS.search(done.stdout), ROUND_OFF_DIGITS.search(done.stdout)
    constants = {line.split(" = ")[0] for line in lines if re.match(r"^\w+ = ", line)}
    wanted = {"resonance": {"omega_min", "omega_max", "count", "curves", "spacing", "b", "b_ratio"},
              "integrators": {"x0", "spacing"}, "regimes": {"x0", "spacing", "b", "under_fraction", "over_multiple"},
              "drag": {"x0", "spacing", "b", "C"}}[args[0]]
    assert wanted <= constants, wanted - constants
    assert any(line.startswith("for ") for line in lines[:lines.index("# ---- the objects ----")])


def test_editing_the_constants_changes_the_row(stand_in, tmp_path):
    """A teacher edits omega_max and count in the resonance program: the row follows."""
    path = tmp_path / "resonance.py"
    assert main_py("resonance", "--set", "until=0.1", "--vpython", str(path)).returncode == 0
    text = path.read_text(encoding="utf-8")
    assert re.search(r"^omega_max = 8 ", text, re.M) and re.search(r"^count = 13 ", text, re.M)
    text = re.sub(r"^omega_max = 8 ", "omega_max = 10", text, flags=re.M)
    path.write_text(re.sub(r"^count = 13 ", "count = 5  ", text, flags=re.M), encoding="utf-8")
    done = subprocess.run([sys.executable, str(path)], capture_output=True, text=True, timeout=120,
                          env={**os.environ, "PYTHONPATH": str(stand_in),
                               "STAND_IN_REPORT": str(tmp_path / "drawn.json")})
    assert done.returncode == 0, done.stderr
    omegas = [float(x) for x in re.findall(r"ω = ([0-9.]+) rad/s", done.stdout)]
    assert omegas == [2.0, 4.0, 6.0, 8.0, 10.0] * 3


def test_the_header_gives_the_command_of_this_case():
    """The header's command line configures exactly the case written (it always said
    `python main.py vertical --vpython FILE.py`, whatever --set, --preset or --integrator were)."""
    import shlex

    import export

    cases = [("driven", {"scenario": 4}, "verlet", '--preset "scenario 4" --integrator verlet'),
             ("vertical", {"preset": "Moon gravity", "assignments": ["k=60"]}, None, '--preset "Moon gravity"'),
             ("damped", {"preset": "critical damping"}, "euler-cromer", '--preset "critical damping"'),
             ("integrators", {"assignments": ["x0=0.3", "spacing=1"]}, None, "--set x0=0.3 --set spacing=1"),
             ("resonance", {}, "rk4", "")]
    for scene, options, integrator, expected in cases:
        setup = catalog.configure(scene, **options)
        text = export.program(setup, integrator=integrator)
        command = next(line for line in text.splitlines() if "python main.py" in line).partition(": ")[2]
        assert command.startswith(f"python main.py {scene}") and expected in command, command
        assert "Changed from the scene's defaults" not in text
        words = shlex.split(command)[3:]
        given = {"assignments": [], "preset": None}
        chosen = None
        for flag, value in zip(words[::2], words[1::2]):
            if flag == "--set":
                given["assignments"].append(value)
            elif flag == "--preset":
                given["preset"] = value
            else:
                assert flag == "--integrator"
                chosen = value
        assert catalog.configure(scene, **given).values == setup.values, (scene, command)
        assert setup.build().methods(chosen) == setup.build().methods(integrator)


def test_units_come_from_the_declarations():
    """Every constant's unit is DECLARED's, and a pure number's comment has no unit (it read `# 1: ...`)."""
    import export
    from scenes import DECLARED

    for scene in catalog.SCENE_NAMES:
        text = export.program(catalog.configure(scene))
        assert "# 1:" not in text
        for line in text.splitlines():
            match = re.match(r"^(\w+) = .*?  # (?:([^:]+): )?", line)
            if match and match[1] in DECLARED:
                unit = DECLARED[match[1]].unit
                assert match[2] == (None if unit == "1" else unit), line


def test_the_default_view_is_declared_once():
    """The keys of a scene's VIEW and their defaults live in scenes/_view.py, for the page and the program."""
    from browser import view
    from scenes._view import DEFAULT_VIEW

    assert view.DEFAULT_VIEW is DEFAULT_VIEW


@pytest.mark.parametrize("args", [("vertical",), ("drag", "--set", "until=1"), ("integrators",),
                                  ("resonance", "--set", "until=0.1")])
def test_colours_and_widths_are_the_pages(args, stand_in, tmp_path):
    """Each mass in its palette colour (export/palette.py, as on the page: a single mass's curve was blue
    in the program and orange on the page); the simulation thick and the exact curve thin, made after it
    so that it is drawn on top (it was hidden under a simulated curve of the same width)."""
    from export.palette import EXACT_WIDTH, mass_colours, simulation_width
    from scenes._view import DEFAULT_VIEW

    path = tmp_path / "program.py"
    assert main_py(*args, "--vpython", str(path)).returncode == 0
    drawn = []
    run_program(path, stand_in, drawn)
    setup = catalog.configure(args[0], assignments=[arg for arg in args[2::2]])
    model = setup.build()
    colours = mass_colours(model, {**DEFAULT_VIEW, **setup.module.VIEW})
    spheres = [shown for shown in drawn if shown["kind"] == "sphere"]
    assert [s["color"] for s in spheres] == [pytest.approx(list(c), abs=5e-3) for c in colours]
    curves = [shown for shown in drawn if shown["kind"] == "gcurve"]
    simulated = [c for c in curves if c["color"] != list(EXACT_COLOUR)]
    assert [c["color"] for c in simulated] == [pytest.approx(list(c), abs=5e-3) for c in colours]
    count = model.state.count
    crowded = count > 6
    assert [c["width"] for c in simulated] == [pytest.approx(simulation_width(i, count, crowded=crowded), abs=0.05)
                                               for i in range(count)]
    exact = [i for i, shown in enumerate(drawn) if shown["kind"] == "gcurve" and shown["color"] == list(EXACT_COLOUR)]
    for i in exact:
        assert drawn[i]["width"] == EXACT_WIDTH < min(c["width"] for c in simulated)
        assert i > max(drawn.index(c) for c in simulated)


def test_the_readmes_excerpt_of_a_program_is_what_the_program_writer_writes():
    """Every line docs/handout.md quotes from `main.py damped --vpython out/damped.py` is a line of it."""
    readme = (ROOT / "docs" / "handout.md").read_text(encoding="utf-8")
    start = readme.index("`python main.py damped --vpython out/damped.py` writes, in part:")
    block = readme[start:].split("\n\n")[1]
    quoted = [line[4:] for line in block.splitlines() if line.strip() and line.strip() != "..."]
    written = main_py("damped", "--vpython", "-")
    assert written.returncode == 0, written.stderr
    lines = written.stdout.splitlines()
    assert len(quoted) >= 15 and all(line in lines for line in quoted), \
        [line for line in quoted if line not in lines]

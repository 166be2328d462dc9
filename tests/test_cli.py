"""The real command line, run as a subprocess: answers against hand arithmetic and closed forms,
output formats, and one clear line (exit status 2, no traceback) for every kind of bad input.

The page's Simple Example by hand (m = 10 kg, k = 40 N/m, L0 = 1 m, g = 9.8 m/s², Δt = 0.1 s,
released from rest at y = −1.5 m, so the spring pulls up with k(|y| − L0)):

    step 1: F_net = 40(1.5 − 1) − 10·9.8 = 20 − 98 = −78 N
            p1 = 0 + (−78)(0.1) = −7.8 kg·m/s,   v1 = −0.78 m/s,   y1 = −1.5 + (−0.78)(0.1) = −1.578 m
    step 2: F_net = 40(1.578 − 1) − 98 = 23.12 − 98 = −74.88 N
            p2 = −7.8 + (−74.88)(0.1) = −15.288,  v2 = −1.5288 m/s, y2 = −1.578 − 0.15288 = −1.73088 m
"""
from __future__ import annotations

import csv
import json
import math
import re
import shlex
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

# The Simple Example's constants, as the page states them.
m, k, L0, g, dt = 10.0, 40.0, 1.0, 9.8, 0.1


def cli(*args, code: str | None = None) -> subprocess.CompletedProcess:
    """Run `python main.py ARGS` (or `python -c CODE ARGS`) from the project root."""
    command = [sys.executable, "-c", code, *args] if code else [sys.executable, "main.py", *args]
    return subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=60)


# The headless --json runs the tests below read, started together a few at a time (each process
# mostly waits on its imports, so this keeps the suite quick on two cores).
JSON_RUNS = [
    ("vertical",), ("damped",), ("vertical", "--integrator", "euler"), ("vertical", "--integrator", "rk4"),
    ("vertical", "--set", "k=25", "--set", "r0=0,-2,0", "--until", "0.1"),
    ("driven", "--scenario", "2", "--until", "0"), ("vertical", "--set", "dt=0.001", "--until", "1"),
    ("vertical", "--set", "r0=0.5,-1.5,0"),
]


@lru_cache(maxsize=None)
def json_runs() -> dict:
    with ThreadPoolExecutor(max_workers=4) as pool:
        return dict(zip(JSON_RUNS, pool.map(lambda args: cli(*args, "--headless", "--json"), JSON_RUNS)))


def cli_json(*args) -> dict:
    """The one JSON object that `main.py ARGS --headless --json` prints."""
    done = json_runs()[args] if args in JSON_RUNS else cli(*args, "--headless", "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def y_exact(t: float) -> float:
    """The Simple Example's closed form: y = y_eq + (y0 − y_eq) cos(√(k/m) t), y_eq = −(L0 + mg/k)."""
    y_eq = -(L0 + m * g / k)
    return y_eq + (-1.5 - y_eq) * math.cos(math.sqrt(k / m) * t)


# ---- listing and constants ----

def test_list_names_every_scene_with_a_description_and_the_driven_scenarios():
    done = cli("--list")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    for name in ("vertical", "damped", "driven"):
        line = next(line for line in lines if line.startswith(name + " "))
        assert len(line.split(None, 1)[1]) > 10  # a one-line description follows the name
    assert sum("--scenario" in line for line in lines) >= 5


def test_constants_show_value_unit_and_meaning_after_set():
    done = cli("vertical", "--constants", "--set", "k=25", "--set", "r0=0,-2,0")
    assert done.returncode == 0, done.stderr
    text = done.stdout
    assert "m = 10 kg" in text and "spring constant" in text
    assert "k = 25 N/m" in text and "k = 40 N/m" not in text
    assert "r0 = < 0, -2, 0 > m" in text
    assert "dt = 0.1 s" in text


def test_constants_default_shows_the_page_spring():
    assert "k = 40 N/m" in cli("damped", "--constants").stdout


# ---- the page's examples ----

def test_simple_example_text_answer_matches_hand_arithmetic_and_shows_exact_and_error():
    done = cli("vertical", "--headless")
    assert done.returncode == 0, done.stderr
    text = done.stdout
    assert "t = 0.2 s" in text
    assert "r = < 0, -1.73088, 0 > m" in text
    assert "p = < 0, -15.288, 0 > kg·m/s" in text
    assert "v = < 0, -1.5288, 0 > m/s" in text
    assert f"exact: r = < 0, {y_exact(0.2):.6g}, 0 > m" in text
    assert f"|r − r_exact| = {abs(-1.73088 - y_exact(0.2)):.4g} m" in text
    assert "K = " in text and " J" in text and "W_nc = 0 J" in text


def test_simple_example_json_keys_types_and_hand_values():
    out = cli_json("vertical")
    for key in ("t", "steps", "dt", "integrator", "r", "p", "v", "exact", "energy", "scene", "constants"):
        assert key in out
    assert out["steps"] == 2 and isinstance(out["steps"], int)
    assert out["t"] == pytest.approx(0.2) and out["dt"] == 0.1
    assert out["integrator"] == "euler-cromer"
    for key in ("r", "p", "v"):
        assert isinstance(out[key], list) and len(out[key]) == 3
        assert all(isinstance(x, float) for x in out[key])
    assert out["r"] == pytest.approx([0, -1.578 - 0.15288, 0], abs=1e-12)
    assert out["p"] == pytest.approx([0, -7.8 + (-74.88) * 0.1, 0], abs=1e-12)
    assert out["v"] == pytest.approx([0, -1.5288, 0], abs=1e-12)
    assert out["exact"]["r"][1] == pytest.approx(y_exact(0.2), rel=1e-9)
    assert out["exact"]["error"]["r"] == pytest.approx(abs(-1.73088 - y_exact(0.2)), rel=1e-9)
    assert out["constants"]["k"] == {"value": 40.0, "unit": "N/m", "meaning": out["constants"]["k"]["meaning"]}
    energy = out["energy"]
    # K = |p|²/2m at the final state.
    assert energy["K"] == pytest.approx(15.288**2 / (2 * m))
    assert energy["E"] == pytest.approx(energy["K"] + energy["U"])


def test_middling_example_two_steps_by_hand():
    # The Simple Example plus F = −b v with b = 1 kg/s.
    b = 1.0
    F1 = k * (1.5 - L0) - m * g - b * 0.0      # at rest: no damping force yet, −78 N
    p1 = F1 * dt                                 # −7.8 kg·m/s
    y1 = -1.5 + (p1 / m) * dt                    # −1.578 m
    F2 = k * (-y1 - L0) - m * g - b * (p1 / m)   # 23.12 − 98 + 0.78 = −74.1 N
    p2 = p1 + F2 * dt                            # −15.21 kg·m/s
    y2 = y1 + (p2 / m) * dt                      # −1.7301 m
    out = cli_json("damped")
    assert out["r"] == pytest.approx([0, y2, 0], abs=1e-12)
    assert out["p"] == pytest.approx([0, p2, 0], abs=1e-12)
    assert out["v"] == pytest.approx([0, p2 / m, 0], abs=1e-12)
    assert y2 == pytest.approx(-1.7301)
    assert out["energy"]["W_nc"] < 0  # damping only takes energy away


# ---- options ----

def test_set_changes_constants_and_vectors():
    # k = 25 N/m, start 2 m below the anchor, one step: F_net = 25(2 − 1) − 98 = −73 N.
    out = cli_json("vertical", "--set", "k=25", "--set", "r0=0,-2,0", "--until", "0.1")
    assert out["steps"] == 1
    assert out["p"] == pytest.approx([0, -7.3, 0])
    assert out["r"] == pytest.approx([0, -2 - 0.073, 0])
    assert out["constants"]["k"]["value"] == 25.0


def test_driven_scenario_two_starts_one_metre_from_equilibrium():
    out = cli_json("driven", "--scenario", "2", "--until", "0")
    assert out["steps"] == 0
    L0_driven = out["constants"]["L0"]["value"]
    assert out["r"] == pytest.approx([L0_driven + 1.0, 0, 0])
    assert out["constants"]["x0"]["value"] == 1.0
    assert out["constants"]["b"]["value"] == 0.0


def test_integrator_changes_the_answer():
    # Euler moves with the OLD velocity: y1 = −1.5 (v0 = 0), y2 = −1.5 + (−0.78)(0.1) = −1.578 m.
    euler = cli_json("vertical", "--integrator", "euler")
    assert euler["integrator"] == "euler"
    assert euler["r"] == pytest.approx([0, -1.578, 0], abs=1e-12)
    # RK4 is fourth order: at Δt = 0.1 s its error is far below Euler-Cromer's 0.077 m.
    rk4 = cli_json("vertical", "--integrator", "rk4")
    assert rk4["r"][1] == pytest.approx(y_exact(0.2), abs=1e-4)
    assert rk4["exact"]["error"]["r"] < 1e-4


def test_until_with_small_dt_converges_to_the_exact_answer():
    out = cli_json("vertical", "--set", "dt=0.001", "--until", "1")
    assert out["steps"] == 1000 and out["t"] == pytest.approx(1.0)
    # Euler-Cromer is first order: error of order ω²Δt·amplitude, a few mm here.
    assert out["r"][1] == pytest.approx(y_exact(1.0), abs=0.01)
    assert out["exact"]["error"]["r"] == pytest.approx(abs(out["r"][1] - y_exact(1.0)), rel=1e-6)


def test_until_not_a_multiple_of_dt_says_where_it_stopped():
    done = cli("vertical", "--headless", "--json", "--until", "0.25")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["steps"] == 3 and out["t"] == pytest.approx(0.3)
    assert "3·dt = 0.3 s" in done.stderr


def test_no_exact_value_where_no_closed_form_exists():
    # Pulled sideways: the mass swings like a pendulum, which has no closed form here.
    out = cli_json("vertical", "--set", "r0=0.5,-1.5,0")
    assert "exact" not in out
    assert out["r"][0] != 0.0


# ---- CSV ----

def test_csv_has_one_row_per_step_starting_at_the_initial_state(tmp_path):
    path = tmp_path / "run.csv"
    done = cli("damped", "--headless", "--json", "--until", "1", "--csv", str(path))
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    header, data = rows[0], rows[1:]
    assert ",".join(header).startswith("t,x,y,z,vx,vy,vz,px,py,pz")
    assert {"K", "U", "E", "W_nc"} <= set(header)
    assert len(data) == out["steps"] + 1 == 11
    first = dict(zip(header, map(float, data[0])))
    assert (first["t"], first["x"], first["y"], first["z"]) == (0.0, 0.0, -1.5, 0.0)
    assert (first["vy"], first["py"]) == (0.0, 0.0)
    last = dict(zip(header, map(float, data[-1])))
    assert last["t"] == pytest.approx(out["t"])
    assert [last[c] for c in "xyz"] == pytest.approx(out["r"])
    assert [last["v" + c] for c in "xyz"] == pytest.approx(out["v"])
    assert [last["p" + c] for c in "xyz"] == pytest.approx(out["p"])
    assert last["E"] == pytest.approx(out["energy"]["E"])


# ---- bad input: one line, exit status 2, no traceback ----

# Each kind of bad input through the real command line, as a subprocess.
BAD_INPUTS = [
    (["nosuch"], "unknown scene"),
    (["vertical", "--headless", "--set", "kk=3"], "did you mean 'k'"),
    (["vertical", "--headless", "--set", "k=abc"], "k needs a number"),
    (["vertical", "--headless", "--set", "r0=1,2"], "r0 needs a 3-vector"),
    (["vertical", "--headless", "--set", "k"], "NAME=VALUE"),
    (["vertical", "--headless", "--set", "m=0"], "m must be"),
    (["vertical", "--headless", "--set", "rho=-1.2"], "rho must be"),
    (["vertical", "--headless", "--set", "dt=nan"], "dt must be"),
    (["vertical", "--headless", "--until", "-1"], "--until"),
    (["driven", "--headless", "--scenario", "6"], "scenario 6"),
    (["vertical", "--json"], "--json needs --headless"),
    (["vertical", "--csv", "out.csv"], "--csv needs --headless"),
    (["vertical", "--headless", "--csv", "no/such/folder/out.csv"], "does not exist"),
    (["vertical", "--headless", "--csv", "tests"], "is a directory"),
    (["vertical", "--headless", "--integrator", "leapfrog"], "--integrator"),
    (["vertical", "--steps", "0"], "--steps"),
    # Audit as a class would use it: runs far too long are refused at once, naming the step count.
    (["vertical", "--headless", "--until", "1e6", "--set", "dt=1e-6"], "1,000,000,000,000 steps"),
    (["vertical", "--headless", "--set", "dt=1e-6", "--until", "1e4"], "10,000,000,000 steps"),
    (["vertical", "--headless", "--until", "1e308", "--set", "dt=1e-3"], "--until must be from 0 to 1e6 s (got 1e+308 s)"),
    (["resonance", "--headless", "--until", "1e5", "--set", "count=1000"], "of 3000 masses"),
    (["vertical", "--steps", "100000000"], "--steps 100,000,000"),
    (["vertical", "--steps", "-3"], "--steps"),
    (["vertical", "--headless", "--csv", "-"], "standard output"),
    (["vertical", "--headless", "--csv", "/proc/no-such.csv"], "cannot write CSV file '/proc/no-such.csv'"),
    (["vertical", "--headless", "--plot", "/proc/no-such.png"], "cannot write figure '/proc/no-such.png'"),
    (["vertical", "--headless", "--csv", "README.md/out.csv"], "does not exist"),
    (["vertical", "--headless", "--bogus"], "--bogus"),
    (["vertical", "--headless", "--set", "x0=1"], "unknown constant 'x0'"),
    (["vertical", "--headless", "--set", "v0=1,2,3,4"], "v0 needs a 3-vector"),
    (["vertical", "--headless", "--set", "k=inf"], "k must be from 0 to 1e6 N/m (got inf N/m)"),
    (["vertical", "--headless", "--set", "r0=0,nan,0"], "r0 must be three numbers, each from -10000 to 10000 m (got < 0, nan, 0 > m)"),
    (["vertical", "--headless", "--set", "m=-inf"], "m must be from 1e-6 to 1e6 kg (got -inf kg)"),
]
# The same checks for more values, calling main.main in this process (same code, no start-up cost).
MORE_BAD_INPUTS = [
    (["vertical", "--headless", "--set", "m=-2"], "m must be"),
    (["vertical", "--headless", "--set", "k=-1"], "k must be"),
    (["vertical", "--headless", "--set", "b=-1"], "b must be"),
    (["vertical", "--headless", "--set", "C=-0.5"], "C must be"),
    (["vertical", "--headless", "--set", "A=-1"], "A must be"),
    (["vertical", "--headless", "--set", "dt=0"], "dt must be"),
    (["vertical", "--headless", "--set", "dt=-0.1"], "dt must be"),
    (["vertical", "--headless", "--set", "dt=inf"], "dt must be"),
    (["vertical", "--headless", "--set", "v0=1,x,0"], "v0 needs a 3-vector"),
    (["vertical", "--headless", "--until", "nan"], "--until"),
    (["vertical", "--headless", "--until", "inf"], "--until"),
    (["driven", "--headless", "--scenario", "0"], "scenario 0"),
    (["vertical", "--headless", "--scenario", "1"], "no scenarios"),
    (["vertical", "--headless", "--scenario", "one"], "--scenario"),
    (["vertical", "--steps", "2", "--json"], "--json needs --headless"),
    (["vertical", "--until", "1"], "--until needs --headless"),
    (["vertical", "--headless", "--plot", "tests"], "is a directory"),
]


def assert_one_line_error(code, stdout, stderr, problem, status=2):
    assert code == status, (stdout, stderr)
    assert "Traceback" not in stderr
    lines = stderr.strip().splitlines()
    assert len(lines) == 1, stderr
    assert lines[0].startswith("error:") and problem in lines[0]
    assert stdout == ""


@lru_cache(maxsize=None)
def bad_input_runs() -> dict:
    """Every bad input at once, a few processes at a time (each start-up mostly waits on imports)."""
    keys = [tuple(args) for args, _ in BAD_INPUTS]
    with ThreadPoolExecutor(max_workers=4) as pool:
        return dict(zip(keys, pool.map(lambda args: cli(*args), keys)))


@pytest.mark.parametrize("args, problem", BAD_INPUTS, ids=[" ".join(a) for a, _ in BAD_INPUTS])
def test_bad_input_gives_one_line_and_status_2(args, problem):
    done = bad_input_runs()[tuple(args)]
    assert_one_line_error(done.returncode, done.stdout, done.stderr, problem)


@pytest.mark.parametrize("args, problem", MORE_BAD_INPUTS, ids=[" ".join(a) for a, _ in MORE_BAD_INPUTS])
def test_more_bad_input_gives_one_line_and_status_2(args, problem, capsys, monkeypatch):
    import main

    monkeypatch.chdir(ROOT)
    try:
        code = main.main(args)
    except SystemExit as stop:  # argparse's own errors
        code = stop.code
    out, err = capsys.readouterr()
    assert_one_line_error(code, out, err, problem)


def test_blow_up_names_dt_and_the_limit_and_prints_no_nan():
    done = cli("vertical", "--headless", "--set", "dt=1.5", "--until", "100")
    assert done.returncode == 1
    assert "Traceback" not in done.stderr
    assert "dt = 1.5 s" in done.stderr and "ω·dt < 2" in done.stderr and "dt < 1 s" in done.stderr
    assert "nan" not in done.stdout.lower()


def test_a_run_past_the_stability_limit_is_refused_with_status_1_even_before_it_blows_up():
    # ω = √(40/10) = 2 rad/s, so Δt = 1.2 s gives ω·dt = 2.4 > 2: one step does not blow up yet,
    # but every further step would make it worse, so the README promises status 1 and the reason.
    done = cli("vertical", "--headless", "--set", "dt=1.2", "--until", "1.2")
    assert_one_line_error(done.returncode, done.stdout, done.stderr, "dt = 1.2 s", status=1)
    assert "ω·dt < 2" in done.stderr and "dt < 1 s" in done.stderr


# ---- start-up stays light ----

def test_headless_never_imports_vpython_matplotlib_or_scipy():
    code = ("import runpy, sys\n"
            "sys.argv = ['main.py', 'vertical', '--headless', '--json']\n"
            "try:\n    runpy.run_path('main.py', run_name='__main__')\n"
            "except SystemExit:\n    pass\n"
            "print('LOADED', *sorted(m for m in ('vpython', 'matplotlib', 'scipy') if m in sys.modules))\n")
    done = cli(code=code)
    assert '"r"' in done.stdout, done.stderr  # the run itself happened
    assert done.stdout.strip().splitlines()[-1] == "LOADED"


# ---- the figure ----

def test_plot_writes_a_png(tmp_path):
    path = tmp_path / "damped.png"
    done = cli("damped", "--plot", str(path), "--until", "2")
    assert done.returncode == 0, done.stderr
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "t = 2 s" in done.stdout


def test_plot_without_matplotlib_says_how_to_install_it(tmp_path):
    path = tmp_path / "x.png"
    code = ("import runpy, sys\n"
            "sys.modules['matplotlib'] = None  # as if it were not installed\n"
            f"sys.argv = ['main.py', 'vertical', '--headless', '--plot', {str(path)!r}]\n"
            "runpy.run_path('main.py', run_name='__main__')\n")
    done = cli(code=code)
    assert done.returncode == 2
    assert done.stderr.strip() == f"error: --plot needs matplotlib: {sys.executable} -m pip install matplotlib"
    assert not path.exists()


def test_scene_that_compares_integrators_reports_each_body_and_refuses_integrator():
    done = cli("integrators", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert isinstance(out["integrator"], list) and len(out["bodies"]) == len(out["integrator"])
    for mode in (["--headless"], ["--vpython", "-"], ["--no-browser"]):   # a flag that would do nothing
        refused = cli("integrators", *mode, "--integrator", "rk4")
        assert refused.returncode == 2 and refused.stdout == ""
        assert refused.stderr.splitlines() == [
            "error: scene 'integrators' steps its masses with euler, euler-cromer, verlet, rk4, one each, "
            "so --integrator rk4 would do nothing; leave it out"]
    errors = {name: body["exact"]["error"]["r"] for name, body in zip(out["integrator"], out["bodies"])}
    assert errors["rk4"] < errors["euler-cromer"] < errors["euler"]  # higher order, smaller error


# ---- multi-mass output, in-process (no multi-mass scene exists yet to run through main.py) ----

def two_hanging_masses():
    """Two Simple Examples side by side (anchors 1 m apart), as a scene Setup with labels."""
    from types import SimpleNamespace

    import numpy as np

    from physics.forces import Gravity, Spring
    from physics.state import make_state
    from scenes import Setup
    from scenes import Model

    anchors = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])

    def build():
        return Model(state=make_state(r=anchors + [0.0, -1.5, 0.0], m=[m, m]),
                     forces=(Spring(k=k, L0=L0, anchor=anchors), Gravity(g=g)),
                     dt=dt, until=0.2, anchors=anchors, labels=("left", "right"))
    def extra_json(setup):  # a scene may add its own results to --json
        return {"pair_spacing_m": 1.0}
    return Setup("pair", SimpleNamespace(build=build, extra_json=extra_json, VIEW={}), {}, {})


def test_multi_mass_json_text_and_csv_name_each_body(tmp_path):
    from reports import csv_file, headless, json_report, text as reports_text

    result = headless.simulate(two_hanging_masses())
    out = json.loads(json.dumps(json_report.as_json(result)))
    assert [body["label"] for body in out["bodies"]] == ["left", "right"]
    for body, x in zip(out["bodies"], (0.0, 1.0)):
        assert body["r"] == pytest.approx([x, -1.73088, 0], abs=1e-12)  # each is the Simple Example
        assert body["p"] == pytest.approx([0, -15.288, 0], abs=1e-12)
    assert len(out["r"]) == 2 and len(out["r"][0]) == 3
    assert out["pair_spacing_m"] == 1.0
    text = reports_text.final_report(result)
    assert "left, m = 10 kg:" in text and "right, m = 10 kg:" in text
    assert text.count("r = < ") == 2
    path = tmp_path / "pair.csv"
    csv_file.write_csv(result, str(path))
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == 2 * (out["steps"] + 1)
    assert [row["body"] for row in rows[-2:]] == ["left", "right"]
    assert float(rows[-1]["x"]) == 1.0 and float(rows[-1]["y"]) == pytest.approx(-1.73088)


# ---- the run-length guard, and progress on long runs ----

def test_too_many_steps_says_how_long_a_run_may_be():
    import physics.simulate

    done = bad_input_runs()[("vertical", "--headless", "--until", "1e6", "--set", "dt=1e-6")]
    # 1e6 s / 1e-6 s = 1e12 steps: far beyond the minute a run may take on any computer (60 ps a
    # step; 1e9 steps, as this was, need only 60 ns, and the fast loop takes 0.19 µs at load 17).
    # The message names the steps and the longest --until that fits, measured on this computer.
    assert "dt = 1e-06 s" in done.stderr and "1,000,000,000,000 steps" in done.stderr
    longest = float(re.search(r"at most ([0-9.e+]+) s", done.stderr).group(1))
    assert 1.0 < longest < 1e6 and physics.simulate.MAX_RUN_SECONDS == 60


def test_a_refused_run_leaves_an_existing_csv_file_as_it_was(tmp_path):
    path = tmp_path / "keep.csv"
    path.write_text("the teacher's old data\n")
    # 10¹⁰ steps: 6 ns a step would fit the minute a run may take, far faster than any Python loop
    # (10⁷ steps, as this was, fit on a fast computer, where the run went ahead)
    done = cli("vertical", "--headless", "--set", "dt=1e-6", "--until", "1e4", "--csv", str(path))
    assert_one_line_error(done.returncode, done.stdout, done.stderr, "steps")
    assert path.read_text() == "the teacher's old data\n"
    done = cli("vertical", "--headless", "--csv", str(tmp_path / "new.csv"), "--set", "dt=1e-6", "--until", "1e4")
    assert done.returncode == 2 and not (tmp_path / "new.csv").exists()  # the write check left no file


def test_a_long_run_reports_progress_and_steps_exactly_as_one_run(monkeypatch):
    import io

    import numpy as np

    from reports import headless
    from physics.simulate import run
    from scenes import configure

    import physics.simulate

    setup = configure("damped", assignments=["dt=0.001"])
    model = setup.build()
    whole = run(model.state, model.forces, dt=model.dt, until=5.0, with_energy=True)
    monkeypatch.setattr(physics.simulate, "PROGRESS_EVERY", 0.0)   # a line after every chunk
    stream = io.StringIO()
    parts = headless.simulate(setup, until=5.0, progress=stream).trajectory
    lines = stream.getvalue().splitlines()
    chunk = physics.simulate.CHUNK
    assert len(lines) == 5000 // chunk + 1 and lines[-1].startswith("running: 5,000 of 5,000 steps (100 %), t = 5 s")
    assert lines[0].startswith(f"running: {chunk:,} of 5,000 steps ({100 * chunk // 5000} %)")
    # The same steps from the same states: identical, bit for bit.
    assert np.array_equal(parts.t, whole.t) and np.array_equal(parts.r, whole.r)
    assert np.array_equal(parts.p, whole.p)
    for key in ("K", "U", "E", "W_nc", "E_minus_W_nc"):
        assert parts.energy[key] == pytest.approx(whole.energy[key], rel=1e-12, abs=1e-12)
    assert headless.simulate(setup, until=2.0, progress=None).trajectory.t.size == 2001


# ---- messy input a class will type ----

def test_spaces_and_brackets_in_a_vector_value_are_fine():
    for value in ("r0=0, -1.5, 0", "r0 = < 0, -1.5, 0 >", "r0=(0,-1.5,0)"):
        done = cli("vertical", "--headless", "--set", value)
        assert done.returncode == 0, (value, done.stderr)
        assert "r = < 0, -1.73088, 0 > m" in done.stdout  # the Simple Example, as without --set


# ---- "Δt = 0.1 s: where is the mass at 0.2 s?" ----

def by_hand_y(steps: int, *, dt: float = 0.1, b: float = 0.0) -> float:
    """The page's update for y alone, from rest at y = −1.5 m, `steps` times."""
    y, p = -1.5, 0.0
    for _ in range(steps):
        F = k * (-y - L0) - m * g - b * p / m
        p += F * dt
        y += p / m * dt
    return y


def test_until_and_steps_give_the_same_hand_worked_answer():
    assert by_hand_y(2) == pytest.approx(-1.73088, abs=1e-12)  # the page's two updates by hand
    text = cli("vertical", "--headless", "--set", "dt=0.1", "--until", "0.2")
    assert text.returncode == 0 and text.stderr == ""
    assert "2 steps of dt = 0.1 s" in text.stdout and "t = 0.2 s" in text.stdout
    assert "r = < 0, -1.73088, 0 > m" in text.stdout and "p = < 0, -15.288, 0 > kg·m/s" in text.stdout
    table = cli("vertical", "--steps", "2")
    assert table.returncode == 0 and table.stderr == ""
    last = table.stdout.strip().splitlines()[-1].split()
    assert last[:2] == ["2", "0.2"] and table.stdout.rstrip().endswith("< 0, -1.73088, 0 >")


@pytest.mark.parametrize("dt_text, until_text, steps", [
    ("0.1", "0.3", 3), ("0.01", "1", 100), ("0.1", "0.7", 7), ("0.001", "0.3", 300)])
def test_until_a_multiple_of_dt_takes_exactly_that_many_steps(dt_text, until_text, steps):
    # 0.3 / 0.1 is 2.9999999999999996 in floating point, 0.7 / 0.1 is 6.999999999999999:
    # neither may lose or gain a step, and no "not a multiple of dt" note may appear.
    done = cli("vertical", "--headless", "--json", "--set", f"dt={dt_text}", "--until", until_text)
    assert done.returncode == 0 and done.stderr == "", done.stderr
    out = json.loads(done.stdout)
    assert out["steps"] == steps and out["t"] == pytest.approx(float(until_text), rel=1e-12)
    assert out["r"][1] == pytest.approx(by_hand_y(steps, dt=float(dt_text)), rel=1e-9)


def test_step_count_is_exact_for_every_typed_multiple_of_dt():
    from decimal import Decimal

    from physics.simulate import steps_to_reach

    for dt_text in ("0.1", "0.01", "0.001", "0.05", "0.3", "0.07", "1e-4"):
        dt_ = float(dt_text)
        for n in range(0, 3001):
            until = float(str(Decimal(dt_text) * n))  # what a user types: 0.3, 0.7, 2.1 ...
            assert steps_to_reach(until, dt_) == n, (dt_text, n)


# ---- a stability warning that knows about damping ----

def dt_max_damped(*, omega: float, rate: float) -> float:
    """The largest stable Euler-Cromer dt: the root of (ω·dt)² + 2·(b/m)·dt = 4, s."""
    return (-2 * rate + math.sqrt(4 * rate**2 + 16 * omega**2)) / (2 * omega**2) if omega else 2 / rate


def test_strong_damping_is_named_as_what_limits_dt():
    # ω = √(40/10) = 2 rad/s and b/m = 300/10 = 30 s⁻¹: ω·dt = 0.2 is far inside ω·dt < 2, but
    # (ω·dt)² + 2(b/m)dt = 0.04 + 6 > 4, so Euler-Cromer is unstable at dt = 0.1 s.
    done = cli("damped", "--headless", "--set", "b=300", "--until", "0.2")
    limit = dt_max_damped(omega=2.0, rate=30.0)
    assert_one_line_error(done.returncode, done.stdout, done.stderr, f"dt < {limit:.4g} s", status=1)
    assert "the damping (b/m = 30 s⁻¹) makes" in done.stderr and "ω·dt < 2" not in done.stderr


def test_the_damped_limit_is_where_the_page_update_really_blows_up():
    limit = dt_max_damped(omega=2.0, rate=30.0)  # 0.0664 s
    assert 0.06 < limit < 0.07
    inside = cli("damped", "--headless", "--set", "b=300", "--set", "dt=0.06", "--until", "60")
    assert inside.returncode == 0 and inside.stderr == "", inside.stderr  # no warning either
    outside = cli("damped", "--headless", "--set", "b=300", "--set", "dt=0.07", "--until", "70")
    assert outside.returncode == 1 and "Traceback" not in outside.stderr
    assert f"dt < {limit:.4g} s" in outside.stderr.splitlines()[-1] and "nan" not in outside.stdout.lower()


def test_damping_without_a_spring_still_limits_dt():
    # k = 0: no spring at all, yet b·dt/m = 3 makes each step multiply p by about (1 − 3) = −2.
    done = cli("vertical", "--headless", "--set", "k=0", "--set", "b=300", "--until", "0.2")
    assert_one_line_error(done.returncode, done.stdout, done.stderr,
                          f"dt < {dt_max_damped(omega=0, rate=30.0):.4g} s", status=1)


# ---- an exact value only where the closed form holds ----

def test_no_exact_value_once_the_mass_has_passed_its_anchor():
    # Scenario 1 is resonance: x = t sin(5t)/40 about equilibrium 1 m from the wall (L0 = 1 m),
    # so the swing reaches the wall (s = L0 + x = 0) near t = 41 s. At 60 s the closed form no
    # longer describes the mass; at 40 s it still does.
    late = cli("driven", "--headless", "--json", "--scenario", "1", "--set", "L0=1", "--until", "60")
    assert late.returncode == 0, late.stderr
    out = json.loads(late.stdout)
    assert "exact" not in out and "anchor" in out["exact_note"]
    t_break = out["exact_valid_until"]
    assert 1.0 + t_break * math.sin(5 * t_break) / 40 == pytest.approx(0.0, abs=1e-9)
    grid = np.linspace(0.0, t_break, 200_001)[:-1]
    assert np.all(1.0 + grid * np.sin(5 * grid) / 40 > 0)  # the first time it gets there
    assert out["units"]["exact_valid_until"] == "s"
    text = cli("driven", "--headless", "--scenario", "1", "--set", "L0=1", "--until", "60").stdout
    assert f"exact: none at t = 60 s: the closed form stops holding at t = {t_break:.4g} s" in text
    assert "|r − r_exact|" not in text
    early = cli_json("driven", "--scenario", "1", "--set", "L0=1", "--until", "40")
    assert early["exact"]["r"][0] == pytest.approx(1.0 + 40 * math.sin(200) / 40, abs=1e-9)
    assert "exact_note" not in early


# ---- clean numbers ----

def significant_digits(text: str) -> int:
    mantissa = text.lstrip("-").split("e")[0].replace(".", "").lstrip("0")
    return len(mantissa.rstrip("0")) if "." in text else len(mantissa)


def test_csv_prints_t_with_the_decimals_of_dt_and_15_significant_digits(tmp_path):
    path = tmp_path / "v.csv"
    done = cli("vertical", "--headless", "--csv", str(path), "--until", "15")
    assert done.returncode == 0, done.stderr
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == ["t", "x", "y", "z", "vx", "vy", "vz", "px", "py", "pz", "K", "U", "E", "W_nc"]
    times = [row[0] for row in rows[1:]]
    assert times[:4] == ["0.0", "0.1", "0.2", "0.3"] and times[-1] == "15.0"
    assert times[146] == "14.6"                               # was 14.599999999999964
    assert all(len(t.partition(".")[2]) <= 1 for t in times)  # Δt = 0.1 s: one decimal
    assert rows[2][8] == "-7.8"                               # p_y after one step, by hand
    assert all(significant_digits(field) <= 15 for row in rows[1:] for field in row)


def test_json_reports_the_until_that_was_run_and_a_clean_t():
    done = cli("driven", "--headless", "--scenario", "3", "--until", "10", "--json")
    assert done.returncode == 0, done.stderr
    answer = json.loads(done.stdout)
    assert answer["t"] == 10.0 and '"t": 10.0,' in done.stdout
    assert answer["constants"]["until"]["value"] == 10.0
    numbers = re.findall(r"-?\d+\.\d+(?:e-?\d+)?", done.stdout)
    assert numbers and all(significant_digits(n) <= 15 for n in numbers)


def test_the_step_table_json_has_clean_times_and_momenta():
    done = cli("vertical", "--steps", "3", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    rows = json.loads(done.stdout)["step_table"]
    assert [row["t"] for row in rows] == [0.1, 0.2, 0.3]
    assert rows[0]["p_f"] == [0.0, -7.8, 0.0]


def readme_commands() -> list[tuple[list[str], str]]:
    """Every `python main.py ...` line of the code blocks of the guides that show the command line
    (docs/teaching.md's --list and --constants, docs/homework.md's runs) that runs without a
    browser, as (arguments, comment). The browser commands (no --headless, --steps, --list,
    --constants, --vpython) are left to the browser tests."""
    guides = [(ROOT / "docs" / name).read_text(encoding="utf-8") for name in ("teaching.md", "homework.md")]
    found = []
    for line in "\n".join(guides).splitlines():
        if not line.startswith("    python main.py"):
            continue
        command, _, comment = line.partition("#")
        args = shlex.split(command)[2:]
        if {"--headless", "--steps", "--list", "--constants"} & set(args):
            found.append((args, comment.strip()))
    return found


def test_every_readme_example_does_what_its_comment_says(tmp_path):
    """Each headless example of the guides (readme_commands), run as written: it succeeds, and
    gives what its comment (or the text around it) promises. The `--csv` line once stopped at 0.2 s."""
    commands = readme_commands()
    assert len(commands) >= 7, commands
    for args, comment in commands:
        if "out/damped.csv" in args:
            args[args.index("out/damped.csv")] = str(tmp_path / "damped.csv")
        done = cli(*args)
        assert done.returncode == 0 and done.stderr == "", (args, done.stderr)
        out = done.stdout
        if args == ["--list"]:
            assert all(name in out for name in ("vertical", "damped", "driven", "resonance"))
            assert "--scenario 5" in out                            # "... and the driven scenarios"
        elif "--constants" in args:
            assert "k = 40 N/m" in out and "b = 1 kg/s" in out      # "value, unit, meaning"
            assert "spring constant" in out
        elif "--steps" in args:                                     # the page's two hand-worked steps
            rows = [line.split() for line in out.splitlines() if line[:1].isdigit()]
            assert [row[:2] for row in rows] == [["1", "0.1"], ["2", "0.2"]]
            assert "< 0, -1.578, 0 >" in out and "< 0, -1.73088, 0 >" in out
        elif "--csv" in args:
            rows = (tmp_path / "damped.csv").read_text().splitlines()
            assert "201 rows" in comment and len(rows) - 1 == 201
            assert rows[1].startswith("0.0,") and rows[-1].startswith("20.0,")
        elif "--json" in args:
            answer = json.loads(out)
            assert answer["t"] == float(args[args.index("--until") + 1])
            assert answer["constants"]["b"]["value"] == 2.0            # scenario 3: b = 2 kg/s
        elif "--preset" in args:
            without_run = [arg for arg in args if arg != "--headless"]      # --constants prints, runs nothing
            assert "g = 1.62 m/s²" in cli(*without_run, "--constants").stdout
            assert "t = 0.2 s" in out                                   # and the run went to the question time
        elif "--force" in args:                                     # "a 50 N push up: as g = 4.8"
            same = cli("vertical", "--headless", "--set", "g=4.8").stdout
            position = re.search(r"^r = <.*> m$", same, re.M).group(0)
            assert "t = 0.2 s" in out and position in out, (position, out)
        else:                                                       # "where is the mass at the question time?"
            assert "t = 0.2 s" in out and "r = < 0, -1.73088, 0 > m" in out


@pytest.mark.parametrize("scene", ["vertical", "damped", "driven", "regimes", "drag", "pendulum",
                                   "integrators", "resonance"])
def test_the_step_table_json_has_no_round_off_anywhere(scene):
    """Every number of `--steps 3 --json`, the start included, has at most 15 significant digits
    (drag's start was -1.7646000000000002 m)."""
    done = cli(scene, "--steps", "3", "--headless", "--json")
    assert done.returncode == 0, done.stderr
    numbers = re.findall(r"-?\d+\.\d+(?:e-?\d+)?", done.stdout)
    assert numbers and all(significant_digits(n) <= 15 for n in numbers), \
        [n for n in numbers if significant_digits(n) > 15]


def test_the_plot_draws_the_exact_solution_smooth_even_at_a_coarse_dt(tmp_path, monkeypatch):
    """vertical at Δt = 0.1 s to 0.2 s has 3 step times; the exact curve still gets 2,000 points."""
    pytest.importorskip("matplotlib")
    from reports import headless
    from reports import plotting
    from scenes import catalog

    drawn = []
    import matplotlib.axes
    original = matplotlib.axes.Axes.plot
    monkeypatch.setattr(matplotlib.axes.Axes, "plot",
                        lambda self, *a, **k: drawn.append((a, k)) or original(self, *a, **k))
    result = headless.simulate(catalog.configure("vertical"), progress=None)
    assert len(result.trajectory.t) == 3
    plotting.plot(result, str(tmp_path / "v.png"))
    exact = [a for a, k in drawn if k.get("label") == "exact"]
    assert len(exact) == 1 and len(exact[0][0]) >= 2000


def test_a_program_past_the_stability_limit_is_written_with_a_warning(tmp_path):
    """--headless refuses a Δt past the limit (exit 1); a program to hand out is still written,
    since showing the blow-up may be the lesson, but stderr says what it will do."""
    path = tmp_path / "v.py"
    done = cli("vertical", "--set", "dt=1.5", "--vpython", str(path))
    assert done.returncode == 0 and path.exists()
    warning = done.stderr.splitlines()[0]
    assert warning.startswith("warning: the run would blow up, past the stability limit: dt = 1.5 s")
    assert warning.endswith("; the program is written as asked")
    growing = cli("vertical", "--integrator", "euler", "--vpython", str(path))
    assert growing.returncode == 0 and growing.stderr.startswith("warning: expect the motion to grow")
    quiet = cli("vertical", "--vpython", str(path))
    assert quiet.returncode == 0 and quiet.stderr == f"wrote {path}\n"


# ---- rows: no exact answer for a mass past its anchor; no numpy warnings ----

def test_integrators_past_the_anchor_print_no_exact_answer_and_no_error():
    # x0 = 2 m beyond L0 = 1 m: s = 1 + 2 cos(5t) reaches the wall at cos(5t) = −1/2, t = 2π/15 s,
    # for every method's mass (the same closed form). Past it the 1-D closed form says nothing
    # about the 3-D spring, so no "exact" and no "error" of 1 m for rk4 at Δt = 1 ms.
    args = ("integrators", "--set", "x0=2", "--set", "dt=0.001")
    text = cli(*args, "--headless")
    assert text.returncode == 0, text.stderr
    assert "r_exact" not in text.stdout and "exact: r" not in text.stdout
    t_break = 2 * math.pi / 15
    assert text.stdout.count(f"exact: none at t = 3 s: the closed form stops holding at t = {t_break:.4g} s") == 4
    out = cli_json(*args)
    for body in out["bodies"]:
        assert "exact" not in body and "anchor" in body["exact_note"]
        assert body["exact_valid_until"] == pytest.approx(t_break, abs=1e-9)
    assert out["exact_valid_until"] == pytest.approx(t_break, abs=1e-9) and "4 of 4" in out["exact_note"]
    default = cli_json("integrators")
    assert all("exact" in body and "exact_note" not in body for body in default["bodies"])
    assert "exact_note" not in default


def test_resonance_without_damping_only_the_spring_at_omega0_loses_its_exact_answer():
    # b = 0: at ω = ω0 = 5 rad/s, x = −t sin(5t)/10 along the spring (the drive pushes up), which
    # first reaches the anchor, s = s_eq + x = 1.392 m + x = 0, near t = 14 s. The others beat
    # within ±0.42 m and keep theirs. A(ω0) has no finite value: null, with a note saying why.
    args = ("resonance", "--set", "b=0", "--set", "curves=1")
    done = cli(*args, "--headless", "--json")
    warnings = [line for line in done.stderr.splitlines() if not line.startswith("running: ")]  # progress on a busy machine
    assert done.returncode == 0 and warnings == [], done.stderr      # no RuntimeWarning
    out = json.loads(done.stdout)
    stopped = [i for i, body in enumerate(out["bodies"]) if "exact" not in body]
    assert stopped == [6] and all("exact_note" not in out["bodies"][i] for i in range(13) if i != 6)
    body = out["bodies"][6]
    assert body["label"] == "b = 0 kg/s, ω = 5 rad/s" and "anchor" in body["exact_note"]
    t_break = body["exact_valid_until"]
    s_eq = 1.0 + 9.8 / 25.0
    assert s_eq - t_break * math.sin(5 * t_break) / 10 == pytest.approx(0.0, abs=1e-9)
    grid = np.linspace(0.0, t_break, 100_001)[:-1]
    assert 13 < t_break < 15 and np.all(s_eq - grid * np.sin(5 * grid) / 10 > 0)
    curve = out["resonance"]
    assert curve["exact_amplitude_m"][0][6] is None and None not in curve["exact_amplitude_m"][0][:6]
    assert curve["smooth_exact_amplitude_m"][0].count(None) == 1
    assert "undamped resonance has no steady state" in curve["exact_amplitude_note"]
    assert "notes" not in out                                            # no null without its reason
    text = cli(*args, "--headless")
    assert text.returncode == 0 and all(line.startswith("running: ") for line in text.stderr.splitlines()), text.stderr
    block = text.stdout.split("ω = 5 rad/s")[1].split("ω = 5.5 rad/s")[0]
    assert "exact: none at t = 50 s" in block and "r_exact" not in block
    assert text.stdout.count("|r − r_exact|") == 12


def test_resonance_refuses_a_vanishing_b_in_one_line_without_warnings():
    done = cli("resonance", "--headless", "--set", "b_ratio=1e-3", "--set", "curves=100")
    assert done.returncode == 2 and done.stdout == ""
    assert len(done.stderr.strip().splitlines()) == 1 and "Warning" not in done.stderr
    assert done.stderr.startswith("error: b = 0.5 kg/s with b_ratio = 0.001 over 100 curves")

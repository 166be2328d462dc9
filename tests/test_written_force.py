"""A force written as an expression (`--force "push=vector(0, 50, 0)"`): the engine steps it as it
steps a force of its own, the command line and the programs carry it, and a bad one is one line.

The physics is checked against what it must equal: a force written as a built-in force's law gives
that force's numbers, bit for bit; a constant 50 N push up on vertical's 10 kg mass is gravity of
4.8 m/s² instead of 9.8; its work is F·Δr; the fast loop traces it and agrees with numpy.
"""
from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

from physics.compiled import UntracedWarning
from scenes import catalog
from test_export import check_answer, main_py, run_program, stand_in  # noqa: F401  (a fixture)

PUSH = ("--force", "push=vector(0, 50, 0)")
FORCES = [
    "vector(0, 50, 0)",
    "-0.5*mag(v)*v",
    "-3/mag(r - vector(0,-4,0))**3 * (r - vector(0,-4,0))",
    "-2*hat(v) + 0.1*cross(v, vector(0, 0, 1))",
    "vector(0.2, 0, 0)*exp(-t)*cos(3*t) + 2**(-t)*vector(0, 0, 0.1) - b*v - k*0.01*r + dt*0*p",
    "sqrt(mag(r))*norm(vector(1, 1, 0))*sin(pi*t)*dot(hat(r), vector(0, -1, 0))",
]
METHODS = ["euler-cromer", "euler", "verlet", "rk4"]


def json_run(*args) -> dict:
    done = main_py(*args, "--headless", "--json")
    assert done.returncode == 0, done.stderr
    assert "traced" not in done.stderr      # the fast loop traced it
    return json.loads(done.stdout)


@pytest.mark.parametrize("method", METHODS)
def test_a_push_of_50_newtons_up_is_gravity_of_4_8(method):
    """The issue's check: on vertical's 10 kg mass, m g − 50 N = 10 kg × 4.8 m/s²."""
    case = ("vertical", "--set", "dt=0.01", "--set", "until=3", "--integrator", method)
    pushed, lighter = json_run(*case, *PUSH), json_run(*case, "--set", "g=4.8")
    np.testing.assert_allclose(pushed["r"], lighter["r"], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(pushed["p"], lighter["p"], rtol=1e-12, atol=1e-12)
    assert pushed["exact"] is None and "no closed form with push" in " ".join(pushed["notes"])
    assert pushed["forces_added"] == [{"name": "push", "force": "vector(0, 50, 0)", "unit": "N"}]


@pytest.mark.parametrize("method", METHODS)
def test_a_force_written_as_dampings_law_gives_dampings_numbers(method):
    case = ("damped", "--set", "dt=0.01", "--set", "until=4", "--integrator", method)
    written = json_run(*case, "--set", "b=0", "--force", "brake=-0.7*v")
    own = json_run(*case, "--set", "b=0.7")
    assert written["r"] == own["r"] and written["p"] == own["p"]     # the same arithmetic, in the same order


def test_the_push_does_work_f_dot_delta_r_metered_in_w_nc():
    """A student's force is not conservative: its work is metered. A constant F does F·Δr."""
    out = json_run("vertical", "--set", "dt=0.001", "--set", "until=2", "--integrator", "rk4", *PUSH)
    start = catalog.configure("vertical").values["r0"]
    assert out["energy"]["W_nc"] == pytest.approx(50 * (out["r"][1] - start[1]), rel=1e-6)
    # and the energy principle holds with it: E − W_nc stays what E was at the start
    begun = json_run("vertical", "--set", "dt=0.001", "--set", "until=0", "--integrator", "rk4", *PUSH)
    assert out["energy"]["E_minus_W_nc"] == pytest.approx(begun["energy"]["E"], rel=1e-6)


@pytest.mark.parametrize("text", FORCES)
def test_the_fast_loop_traces_it_and_agrees_with_numpy(text):
    from physics.simulate import Simulation

    setup = catalog.configure("vertical", forces=[f"added={text}"], assignments=["b=0.3", "dt=0.01"])
    model = setup.build()
    with warnings.catch_warnings():
        warnings.simplefilter("error", UntracedWarning)
        fast = Simulation(model.state, model.forces, dt=model.dt)
        fast.advance(400)
    plain = Simulation(model.state, model.forces, dt=model.dt, compiled=False)
    plain.advance(400)
    assert fast.state.t == plain.state.t and np.isfinite(fast.state.r).all()
    np.testing.assert_allclose(fast.state.r, plain.state.r, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(fast.state.p, plain.state.p, rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("text, method", [(text, method) for text in FORCES for method in ("euler-cromer", "rk4")]
                         + [(FORCES[1], "verlet"), (FORCES[3], "verlet")])
def test_the_program_with_the_force_reaches_the_engines_state(text, method, stand_in, tmp_path):  # noqa: F811
    """The handed-out program (run in CPython with vpython's own vector class) prints the command
    line's answer, and its line is the student's force in the program's names."""
    case = ("vertical", "--set", "b=0.3", "--set", "dt=0.01", "--set", "until=2", "--integrator", method,
            "--force", f"added={text}")
    path = tmp_path / "program.py"
    written = main_py(*case, "--vpython", str(path), "--until", "2")
    assert written.returncode == 0, written.stderr
    program = path.read_text(encoding="utf-8")
    assert "F_added = " in program and "+ F_added" in program
    expected = json_run(*case)
    printed = []
    answers = run_program(path, stand_in, printed=printed)
    check_answer(printed, answers, expected)          # digit for digit as the command line writes it


def test_the_programs_header_gives_the_command_that_shows_the_case():
    done = main_py("vertical", "--webvpython", "-", "--force", "wind=-0.5*mag(v)*v", *PUSH, "--set", "k=60")
    assert done.returncode == 0, done.stderr
    assert ('# The same case on the simulator\'s page: python main.py vertical --set k=60 '
            '--force "wind=-0.5*mag(v)*v" --force "push=vector(0, 50, 0)"') in done.stdout
    assert "Fnet = Fspring + Fgravity + F_wind + F_push" in done.stdout
    assert "\nk = 60" in done.stdout


def test_a_force_that_reads_b_puts_b_in_the_constants_block():
    done = main_py("vertical", "--vpython", "-", "--force", "brake=-b*v", "--set", "b=0")
    assert done.returncode == 0, done.stderr
    assert "\nb = 0 " in done.stdout and "F_brake = -b*v" in done.stdout


def test_every_output_carries_it(tmp_path):
    csv_path = tmp_path / "run.csv"
    done = main_py("vertical", "--headless", "--csv", str(csv_path), *PUSH)
    assert done.returncode == 0, done.stderr
    assert "added force push: F = vector(0, 50, 0) N" in done.stdout
    plain = tmp_path / "plain.csv"
    assert main_py("vertical", "--headless", "--csv", str(plain)).returncode == 0
    pushed_rows, plain_rows = csv_path.read_text().splitlines(), plain.read_text().splitlines()
    assert pushed_rows[0] == plain_rows[0]                # the CSV header is a contract
    assert pushed_rows[1] == plain_rows[1]                # the start is the same,
    assert pushed_rows[2] != plain_rows[2]                # the first step is not
    steps = main_py("vertical", "--steps", "1", *PUSH)
    assert "< 0, -28, 0 >" in steps.stdout               # F_net = −k(|L| − L0) − m g + 50 = 20 − 98 + 50
    page = tmp_path / "page.html"
    done = main_py("vertical", "--html", str(page), *PUSH)
    assert done.returncode == 0, done.stderr
    assert "vector(0, 50, 0)" in page.read_text(encoding="utf-8")


@pytest.mark.parametrize("args, said, status", [
    (("--force", "push=vector(2, 0"), "cannot read the force: a ( is not closed", 2),
    (("--force", "push=-0.5*mag(v)"), "is a number, but a force is a vector", 2),
    (("--force", "push=__import__('os')"), "text in quotes is not allowed", 2),
    (("--force", "vector(2, 0, 0)"), "--force needs NAME=EXPRESSION", 2),
    (("--force", "2x=vector(2, 0, 0)"), "a force's name is a word", 2),
    (("--force", "spring=vector(2, 0, 0)"), "the name spring is taken", 2),
    (("--force", "a=vector(2, 0, 0)", "--force", "a=vector(0, 2, 0)"), "the name a is taken", 2),
    (("--force", "pull=-1/mag(r)*r", "--set", "L0=0", "--set", "r0=0,0,0"), "the force pull has no value at t = 0", 2),
    (("--force", "stiff=-1e6*r", "--set", "until=5"), "error:", 1),
    (("--force", "push=vector(2, 0, 0)", "--constants"), "--constants only prints the constants", 2),
    (("--force", "push=vector(2, 0, 0)", "--data", "examples/data/vernier.csv"), "--force adds a force", 2),
])
def test_a_bad_force_is_one_line(args, said, status):
    done = main_py("vertical", "--headless", *[arg for arg in args if arg != "--constants"]) if "--constants" not in args \
        else main_py("vertical", *args)
    if "--data" in args:
        done = main_py("damped", *args)
    assert done.returncode == status, (done.stdout, done.stderr)
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and said in lines[0] and "Traceback" not in done.stderr, done.stderr


def test_a_scene_without_a_constant_says_so():
    done = main_py("integrators", "--headless", "--force", "brake=-b*v")
    assert done.returncode == 2
    assert "the force brake reads b, which this scene does not have" in done.stderr


def test_a_list_is_refused_with_a_force():
    done = main_py("--list", "--force", "push=vector(2, 0, 0)")
    assert done.returncode == 2 and "--list takes no scene or other option (got --force)" in done.stderr

"""The command line against a hostile user: every bad input and every fault ends cleanly.

For each bad input below, across every scene and flag, the program must:

- exit with the stated status (2 for bad input, 1 for a run that blows up),
- print exactly one line on stderr, starting `error:` and naming the problem,
- print no Python traceback, and no inf or nan on stdout,
- print strict JSON (or nothing) where --json was given,
- leave no file behind in the folder it ran in.

The cases call main.run() in-process (the same function `python main.py` runs), from an empty
temporary folder, so 100 cases take a few seconds. What needs a real process, signals and the
last-resort handler, runs as a subprocess at the end.
"""
from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from held_run import held_scene, not_progress, open_gate, wait_for_progress
from test_loopback_server import wait_for_listeners

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import main  # noqa: E402

# (argv, exit status, text the one stderr line must contain)
BAD = [
    # ---- each constant, per scene: out of range, huge, tiny, not finite, not a number ----
    ("vertical --headless --set m=0", 2, "m must be from 1e-6 to 1e6 kg (got 0 kg)"),
    ("vertical --headless --set m=-1", 2, "m must be"),
    ("vertical --headless --set m=1e300", 2, "(got 1e+300 kg)"),
    ("vertical --headless --json --set m=1e300", 2, "m must be"),
    ("vertical --headless --set m=1e-300", 2, "m must be"),
    ("vertical --headless --set m=nan", 2, "m must be"),
    ("vertical --headless --set m=inf", 2, "m must be"),
    ("vertical --headless --set m=abc", 2, "m needs a number (got 'abc')"),
    ("vertical --headless --set m=", 2, "m needs a number"),
    ("vertical --headless --set k=-5", 2, "k must be from 0 to 1e6 N/m"),
    ("vertical --headless --set k=1e300", 2, "k must be"),
    ("vertical --headless --set dt=0", 2, "dt must be from 1e-6 to 1000 s"),
    ("vertical --headless --set dt=-0.1", 2, "dt must be"),
    ("vertical --headless --set dt=1e300", 2, "dt must be"),
    ("vertical --headless --set dt=1e-300", 2, "dt must be"),
    ("vertical --headless --set b=1e200 --until 0", 2, "b must be from 0 to 1e6 kg/s"),
    ("vertical --headless --set b=-1", 2, "b must be"),
    ("vertical --headless --set g=-9.8", 2, "g must be from 0 to 1000 m/s²"),
    ("vertical --headless --set g=1e300", 2, "g must be"),
    ("vertical --headless --set L0=-1", 2, "L0 must be"),
    ("vertical --headless --set C=1e300", 2, "C must be"),
    ("vertical --headless --set A=1e300", 2, "A must be"),
    ("vertical --headless --set rho=-1", 2, "rho must be"),
    ("vertical --headless --set F0=1e300", 2, "F0 must be"),
    ("vertical --headless --set omega=-1", 2, "omega must be"),
    ("vertical --headless --set omega=1e300", 2, "omega must be"),
    ("vertical --headless --set until=-1", 2, "until must be"),
    ("vertical --headless --set until=1e300", 2, "until must be"),
    ("vertical --headless --set r0=0,1e300,0", 2, "r0 must be three numbers, each from -10000 to 10000 m"),
    ("vertical --headless --set r0=0,nan,0", 2, "r0 must be three numbers"),
    ("vertical --headless --set r0=1,2", 2, "r0 needs a 3-vector"),
    ("vertical --headless --set r0=1,2,3,4", 2, "r0 needs a 3-vector"),
    ("vertical --headless --set v0=1e300,0,0", 2, "v0 must be"),
    ("vertical --headless --set anchor=0,0,inf", 2, "anchor must be"),
    ("vertical --headless --set drive_axis=0,0,0", 2, "drive_axis must be"),
    ("vertical --headless --set drive_axis=0,1e-300,0", 2, "not all near 0"),
    ("damped --headless --set b=abc", 2, "b needs a number"),
    ("damped --steps 2 --set m=-1e-9", 2, "m must be"),
    ("driven --headless --set x0=1e300", 2, "x0 must be"),
    ("driven --headless --set omega=1e300", 2, "omega must be"),
    ("driven --headless --set F0=-inf", 2, "F0 must be"),
    ("regimes --headless --set under_fraction=-1", 2, "under_fraction must be"),
    ("regimes --headless --set over_multiple=1e300", 2, "over_multiple must be"),
    ("regimes --headless --set spacing=-1", 2, "spacing must be"),
    ("drag --headless --set C=-0.47", 2, "C must be"),
    ("drag --headless --set rho=1e300", 2, "rho must be"),
    ("drag --headless --set x0=nan", 2, "x0 must be"),
    ("friction --headless --set mu_k=-0.1", 2, "mu_k must be from 0 to 100"),
    ("friction --headless --set mu_s=0.01", 2, "mu_s must be at least mu_k"),
    ("friction --headless --json --set g=0", 2, "friction needs a load N = m g, but g = 0 here"),
    ("friction --headless --set mu_k=inf", 2, "mu_k must be"),
    ("drag --headless --set v0=1,0,0", 2, "unknown constant 'v0'"),
    ("pendulum --headless --set v0=0,0,1e300", 2, "v0 must be"),
    ("pendulum --headless --set r0=abc", 2, "r0 needs a 3-vector"),
    ("integrators --headless --set dt=1e300", 2, "dt must be"),
    ("integrators --headless --set x0=1e300", 2, "x0 must be"),
    ("resonance --headless --set count=1e12", 2, "count must be a whole number from 2 to 10000"),
    ("resonance --headless --set count=2.5", 2, "count must be a whole number"),
    ("resonance --headless --set count=1", 2, "count must be"),
    ("resonance --headless --set curves=0", 2, "curves must be"),
    ("resonance --headless --set curves=1e9", 2, "curves must be"),
    ("resonance --headless --set omega_min=0", 2, "omega_min must be"),
    ("resonance --headless --set omega_max=1", 2, "omega_min < omega_max"),
    ("resonance --headless --json --set settle=1e9", 2, "settle must be"),
    ("resonance --plot r.png --set settle=1e9", 2, "settle must be"),
    ("resonance --headless --set settle=-1", 2, "settle must be"),
    ("resonance --headless --set periods=0", 2, "periods must be"),
    ("resonance --headless --set b_ratio=0", 2, "b_ratio must be"),
    ("resonance --headless --set b_ratio=1000 --set curves=5", 2, "more than the 1e+06 kg/s b may be"),
    ("regimes --headless --set k=1e-320", 2, "k must be 0 or at least 1e-9 N/m in size"),
    ("vertical --headless --set v0=0,1e-300,0", 2, "v0 must be 0 or at least 1e-9 m/s in size"),
    ("vertical --headless --set k=1e-400", 2, "k = 1e-400 is too small for the computer to tell from 0; write 0"),
    ("vertical --headless --set b=-0.5e-999", 2, "b = -0.5e-999 is too small"),
    ("vertical --headless --set r0=0,-1.5,1e-400", 2, "r0 = 1e-400 is too small"),
    ("driven --headless --set x0=-3", 2, "a mass starts at its spring's anchor"),
    ("vertical --vpython x.py --set r0=0,0,0", 2, "a mass starts at its spring's anchor"),
    ("pendulum --no-browser --set r0=0,0,0", 2, "a mass starts at its spring's anchor"),
    # ---- names, scenarios, presets ----
    ("vertical --headless --set kk=3", 2, "unknown constant 'kk'"),
    ("vertical --headless --set k", 2, "--set needs NAME=VALUE"),
    ("vertical --headless --set =5", 2, "--set needs NAME=VALUE"),
    ("vertcal --headless", 2, "unknown scene 'vertcal'"),
    ("vertical --headless --preset Mars", 2, "unknown preset 'Mars'"),
    ("driven --headless --preset scenario", 2, "could be any of"),
    ("driven --headless --scenario 0", 2, "scenario 0 is out of range"),
    ("driven --headless --scenario 6", 2, "scenario 6 is out of range"),
    ("driven --headless --scenario 99999999999999999999", 2, "out of range"),
    ("vertical --headless --scenario 2", 2, "has no scenarios"),
    ("vertical --headless --integrator leapfrog", 2, "invalid choice: 'leapfrog'"),
    ("vertical --headless --bogus", 2, "unrecognized arguments: --bogus"),
    # ---- --until and --steps ----
    ("vertical --headless --until nan", 2, "--until must be"),
    ("vertical --headless --until inf", 2, "--until must be"),
    ("vertical --headless --until -1", 2, "--until must be"),
    ("vertical --headless --until 1e300", 2, "--until must be"),
    ("vertical --headless --until abc", 2, "invalid float value: 'abc'"),
    ("vertical --steps 0", 2, "--steps needs a whole number of 1 or more"),
    ("vertical --steps -5", 2, "--steps needs"),
    ("vertical --steps 1e3", 2, "invalid int value: '1e3'"),
    ("vertical --steps 100000000", 2, "more than the 10,000 rows"),
    ("vertical --steps 2 --until 5", 2, "--until does nothing with --steps alone"),
    ("vertical --headless --set dt=1e-6 --until 1e4", 2, "10,000,000,000 steps"),
    ("vertical --vpython /nonexistent/x.py", 2, "folder '/nonexistent' does not exist"),
    ("vertical --webvpython /tmp", 2, "it is a directory"),
    ("vertical --html /tmp", 2, "it is a directory"),
    ("vertical --html /dev/null", 2, "it is a device, not a regular file"),
    ("vertical --html x.html --webvpython x.html", 2, "--webvpython and --html both write 'x.html'"),
    ("resonance --headless --json --set until=10", 2, "set until to at least"),
    ("resonance --no-browser --set count=10000", 2, "30,000 masses are more than the 2,000 the page can draw"),
    ("resonance --no-browser --set count=2000 --set curves=1 --set dt=1e-6", 2, "so the page would crawl"),
    # ---- flags that conflict, or do nothing in the chosen mode ----
    ("vertical --json", 2, "--json needs --headless"),
    ("vertical --csv x.csv", 2, "--csv needs --headless"),
    ("vertical --until 3", 2, "--until needs --headless, or --vpython or --webvpython"),
    ("vertical --vpython x.py --until -1", 2, "--until must be"),
    ("--list --set k=abc", 2, "--list takes no scene or other option (got --set)"),
    ("--list vertical", 2, "--list takes no scene"),
    ("--list --headless", 2, "--list takes no scene or other option (got --headless)"),
    ("--list --port 8000", 2, "--list takes no scene or other option (got --port)"),
    ("vertical --constants --headless", 2, "--constants only prints the constants, so --headless"),
    ("vertical --constants --port 5000", 2, "so --port would do nothing"),
    ("vertical --constants --json", 2, "so --json would do nothing"),
    ("vertical --forces --headless", 2, "--forces only prints the forces, so --headless would do nothing"),
    ("--list --forces", 2, "--list takes no scene or other option (got --forces)"),
    ("vertical --headless --port 0", 2, "--port is for the browser page"),
    ("vertical --headless --port 8000", 2, "--port is for the browser page"),
    ("vertical --headless --no-browser", 2, "--no-browser is for the browser page"),
    ("vertical --steps 2 --port 8000", 2, "--port is for the browser page"),
    ("vertical --plot x.png --no-browser", 2, "--no-browser is for the browser page"),
    ("vertical --port 0", 2, "--port must be a whole number from 1 to 65535 (got 0)"),
    ("vertical --port 70000", 2, "--port must be a whole number from 1 to 65535"),
    ("vertical --port -1", 2, "--port must be"),
    ("vertical --port abc", 2, "invalid int value: 'abc'"),
    # ---- output files ----
    ("vertical --headless --csv x.png --plot x.png", 2, "--csv and --plot both write 'x.png'"),
    ("vertical --headless --csv x.png --plot ./x.png", 2, "--csv and --plot both write"),
    ("vertical --headless --csv . ", 2, "is a directory"),
    ("vertical --headless --csv /nonexistent-folder/x.csv", 2, "does not exist"),
    ("vertical --headless --csv -", 2, "cannot write CSV file to '-'"),
    ("vertical --plot x.unknownext", 2, "--plot cannot write 'x.unknownext'"),
    ("vertical --headless --json --csv", 2, "expected one argument"),
    # ---- the program writer: collisions, printing, and flags that would do nothing ----
    ("vertical --vpython x.py --webvpython x.py", 2, "--vpython and --webvpython both write 'x.py'"),
    ("vertical --vpython x.py --webvpython ./x.py", 2, "both write"),
    ("vertical --headless --vpython out.csv --csv out.csv", 2, "--csv and --vpython both write 'out.csv'"),
    ("vertical --vpython out.png --plot out.png", 2, "--plot and --vpython both write 'out.png'"),
    ("vertical --vpython - --webvpython -", 2, "--vpython - and --webvpython - would both print"),
    ("vertical --headless --json --vpython -", 2, "--vpython - and --json would both print"),
    ("vertical --steps 2 --vpython -", 2, "--vpython - and --steps would both print"),
    ("vertical --headless --vpython -", 2, "--vpython - and --headless (its report) would both print"),
    ("vertical --constants --vpython x.py", 2, "--constants only prints the constants, so --vpython"),
    ("--list --webvpython x.py", 2, "--list takes no scene or other option (got --webvpython)"),
    ("vertical --vpython x.py --port 8000", 2, "--port is for the browser page, and --vpython only writes"),
    ("vertical --webvpython x.py --no-browser", 2, "--no-browser is for the browser page"),
    ("integrators --headless --integrator rk4", 2, "would do nothing; leave it out"),
    ("integrators --vpython x.py --integrator euler", 2, "would do nothing"),
    ("vertical --headless --overwrite", 2, "--overwrite does nothing without a file to write"),
    ("vertical --vpython vpython.py", 2, "a program called vpython.py cannot run: its `from vpython import *` "
                                         "would import the program itself"),
    ("vertical --vpython VPython.py --webvpython web.py", 2, "a program called VPython.py cannot run"),
    ("--list --overwrite", 2, "--list takes no scene or other option (got --overwrite)"),
    # ---- measured data, the fit and the mystery spring (issue 19; the files: test_measured_cli.py) ----
    ("damped --fit k,b", 2, "--fit needs --data"),
    ("damped --data missing.csv", 2, "missing.csv: cannot read it"),
    ("damped --data missing.csv --data-column 2 --run 0", 2, "--run needs a whole number"),
    ("damped --data missing.csv --coordinate w", 2, "invalid choice"),
    ("damped --data missing.csv --data-sign 2", 2, "invalid choice"),
    ("damped --mystery spring.csv --data-sign -1", 2, "--data-sign needs --data"),
    ("damped --data missing.csv --until 3", 2, "--until does nothing with --data"),
    ("damped --page", 2, "--page needs --data"),
    ("damped --data missing.csv --page", 2, "missing.csv: cannot read it"),
    ("damped --data missing.csv --page --json", 2, "--json does nothing with --data --page"),
    ("damped --data missing.csv --port 8000", 2, "add --page to show the data on the page"),
    ("damped --mystery m.csv --show-answer --seed 1", 2, "separate jobs"),
    ("damped --seed 3 --headless", 2, "--seed needs --mystery or --show-answer"),
    ("damped --show-answer", 2, "--show-answer needs --seed"),
    ("damped --mystery m.csv --json", 2, "--json does nothing with --mystery"),
    ("regimes --mystery m.csv --seed 1", 2, "has 3 masses"),
    ("integrators --show-answer --seed 1", 2, "has 4 masses"),
    ("vertical --arrows p,momentum", 2, "--arrows knows p, F_net, forces, split (got 'momentum')"),
    ("vertical --headless --no-arrows", 2, "--arrows (and --no-arrows) is for the page and the program"),
    ("vertical --headless --projector", 2, "--projector is for the browser page"),
    ("vertical --projector --vpython x.py", 2, "--projector is for the browser page, and --vpython only writes"),
]

# Inputs that would run for minutes or hours: the engine's cost limit (physics.simulate.check_cost)
# refuses them before any step is taken.
TOO_LONG = {
    "resonance --headless --json --set settle=1e6",
    "resonance --plot r.png --set settle=1e6",
    "resonance --headless --set count=10000 --set curves=100",
    "resonance --headless --set omega_min=1e-300",
    "resonance --headless --set omega_min=1e-6 --set omega_max=1e-5",
}
# A run past the stability limit stops with exit status 1 and the reason (the README's promise).
PAST_THE_LIMIT = {
    "vertical --headless --set dt=1.5 --until 10",
    "vertical --headless --json --set dt=1.5 --until 10",
}
LATER = [(argv, 2, "") for argv in sorted(TOO_LONG)] + \
        [(argv, 1, "stability") for argv in sorted(PAST_THE_LIMIT)]

NOT_A_NUMBER = re.compile(r"\b(inf|nan|infinity)\b", re.IGNORECASE)


def strict_json(text: str):
    """json.loads that refuses NaN and Infinity, as strict parsers (JavaScript's JSON.parse) do."""
    def refuse(constant):
        raise ValueError(f"not strict JSON: {constant}")
    return json.loads(text, parse_constant=refuse)


def check_clean_exit(argv, status, expected, code, out, err, folder, before):
    assert code == status, (argv, out, err)
    assert "Traceback" not in err and "Traceback" not in out
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("error:") and expected in lines[0], lines[0]
    assert not NOT_A_NUMBER.search(out), out
    if "--json" in argv and out.strip():
        strict_json(out)
    assert sorted(os.listdir(folder)) == before, "a file was left behind"


@pytest.mark.parametrize("argv, status, expected", [pytest.param(*case, id=case[0]) for case in BAD + LATER])
def test_bad_input_ends_cleanly(argv, status, expected, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    try:
        code = main.run(argv.split())
    except SystemExit as exit:  # argparse's own errors end this way
        code = exit.code
    out, err = capsys.readouterr()
    check_clean_exit(argv, status, expected, code, out, err, tmp_path, [])


def test_there_are_at_least_60_bad_inputs_across_every_scene_and_flag():
    from scenes import SCENE_NAMES

    assert len(BAD) >= 60
    used = " ".join(argv for argv, _, _ in BAD)
    assert all(f"{name} " in used for name in SCENE_NAMES)
    flags = {action.option_strings[-1] for action in main.build_parser()._actions if action.option_strings}
    assert {flag for flag in flags if flag not in used} <= {"--help"}


def test_every_constant_of_every_scene_has_a_declared_range_its_default_obeys():
    from scenes import SCENE_NAMES, configure, load, scenarios
    from scenes import DECLARED, read_constants

    for name in SCENE_NAMES:
        constants = read_constants(load(name))
        assert set(constants) <= set(DECLARED), name
        configure(name)  # the scene file's own values pass the same checks
        for number in range(1, len(scenarios(load(name))) + 1):
            configure(name, scenario=number)


def test_declared_ranges_keep_the_forces_far_from_overflow():
    """The largest products the forces take, with every constant at its bound, stay finite and small."""
    from scenes import DECLARED

    high = {name: max(abs(d.low), abs(d.high)) for name, d in DECLARED.items()}
    v = high["v0"]
    for product in (high["m"] * high["g"], high["k"] * (high["r0"] + high["L0"]), high["b"] * v,
                    0.5 * high["rho"] * high["C"] * high["A"] * v ** 2, 0.5 * high["m"] * v ** 2,
                    high["k"] * high["r0"] ** 2):
        assert product < 1e30
    assert DECLARED["dt"].low >= 1e-6 * 1e-6 * DECLARED["until"].high  # t + dt still moves t


def test_a_file_that_fails_part_way_leaves_the_old_file_untouched(tmp_path):
    from export import files

    path = tmp_path / "run.csv"
    path.write_text("the teacher's old data\n")
    with pytest.raises(RuntimeError):
        with files.atomic_file(str(path), what="CSV file") as temporary:
            Path(temporary).write_text("half a ro")
            raise RuntimeError("the disk filled up")
    assert path.read_text() == "the teacher's old data\n"
    assert os.listdir(tmp_path) == ["run.csv"]


def test_a_file_another_program_holds_open_is_named_as_such_and_left_untouched(tmp_path, monkeypatch):
    """Windows refuses os.replace onto a CSV open in Excel (PermissionError): one line that says
    why, the old file as it was, no temporary file left."""
    from export import files

    path = tmp_path / "run.csv"
    path.write_text("the teacher's old data\n")

    def held_open(source, target):
        raise PermissionError(13, "Permission denied")
    monkeypatch.setattr(files.os, "replace", held_open)
    with pytest.raises(files.OutputError) as refused:
        files.write_text(str(path), "t,x\n", what="CSV file", overwrite=True)
    assert str(refused.value) == (f"cannot write CSV file {str(path)!r}: Permission denied (is the file open in "
                                  f"another program, such as Excel? close it there and run again)")
    assert path.read_text() == "the teacher's old data\n"
    assert os.listdir(tmp_path) == ["run.csv"]


def test_a_file_size_limit_leaves_the_old_csv_untouched_and_no_partial_file(tmp_path):
    import resource

    path = tmp_path / "run.csv"
    path.write_text("the teacher's old data\n")

    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (2000, 2000))

    done = subprocess.run([sys.executable, str(ROOT / "main.py"), "damped", "--headless", "--until", "5",
                           "--csv", str(path)], cwd=tmp_path, capture_output=True, text=True,
                          timeout=60, preexec_fn=limit)
    assert done.returncode == 2, done.stderr
    assert done.stderr.startswith("error: cannot write CSV file") and "Traceback" not in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    assert path.read_text() == "the teacher's old data\n"
    assert os.listdir(tmp_path) == ["run.csv"]


def test_json_with_a_value_that_has_none_is_null_with_a_note():
    from export.step_update import NO_VALUE, number
    from reports.json_report import to_json

    text = to_json({"energy": {"K": float("inf"), "U": 1.0}, "r": [0.0, float("nan"), 0.0]})
    out = strict_json(text)
    assert out["energy"] == {"K": None, "U": 1.0} and out["r"] == [0.0, None, 0.0]
    assert any(note.startswith("energy.K: null") for note in out["notes"])
    assert any(note.startswith("r[1]: null") for note in out["notes"])
    assert number(float("inf")) == number(float("nan")) == NO_VALUE


def test_every_scene_gives_strict_json_and_no_inf_or_nan(tmp_path, monkeypatch, capsys):
    from scenes import SCENE_NAMES

    monkeypatch.chdir(tmp_path)
    for name in SCENE_NAMES:
        until = ["--until", "1"] if name != "resonance" else []
        assert main.run([name, "--headless", "--json", *until]) == 0
        out, err = capsys.readouterr()
        strict_json(out)
        assert not NOT_A_NUMBER.search(out), name
        assert main.run([name, "--headless", *until]) == 0
        out, err = capsys.readouterr()
        assert not NOT_A_NUMBER.search(out), name


def test_the_readme_and_a_blow_up_agree():
    """docs/homework.md (the README's guide to the command line): a run past the stability limit
    stops with exit status 1 and names Δt and the limit."""
    readme = (ROOT / "docs" / "homework.md").read_text(encoding="utf-8")
    assert "stops with exit status 1" in " ".join(readme.split())
    done = subprocess.run([sys.executable, "main.py", "vertical", "--headless", "--set", "dt=1.5",
                           "--until", "10"], cwd=ROOT, capture_output=True, text=True, timeout=60)
    lines = done.stderr.strip().splitlines()
    assert lines[-1].startswith("error:") and "dt" in lines[-1] and "Traceback" not in done.stderr
    assert not NOT_A_NUMBER.search(done.stdout) and done.stdout == ""


# ---- what needs a real process ----

def test_the_last_resort_handler_turns_any_bug_into_one_line_and_status_1(tmp_path):
    code = ("import sys, main\nfrom reports import text\n"
            "def broken(result): raise KeyError('a bug nobody foresaw')\n"
            "text.final_report = broken\n"
            "sys.exit(main.run(['vertical', '--headless']))\n")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.returncode == 1
    assert "Traceback" not in done.stderr and done.stdout == ""
    assert done.stderr.strip().splitlines() == [
        "error: unexpected KeyError: 'a bug nobody foresaw' (a bug in main.py; please report it "
        "with the command you ran)"]


# A run interrupted part-way is the `held` scene of tests/held_run.py: it cannot end before the test
# opens its gate, and it reports its progress before it waits, on any computer. (A fixed 10⁶ rk4
# steps finished in 1.5 s on a quiet, fast one, before the first progress line: issue 28, item 8.)
HELD = ["held", "--headless"]


@pytest.mark.parametrize("signum, status, output", [(signal.SIGINT, 130, "--csv"), (signal.SIGTERM, 143, "--json"),
                                                    (signal.SIGINT, 130, "--plot")])
def test_a_signal_during_a_long_run_ends_cleanly_and_leaves_no_partial_file(signum, status, output, tmp_path):
    env, gate = held_scene(tmp_path / "scenes")
    path = tmp_path / ("run.png" if output == "--plot" else "run.csv")
    path.write_text("the teacher's old data\n")
    extra = {"--json": ["--json"], "--csv": ["--csv", str(path), "--overwrite"],
             "--plot": ["--plot", str(path), "--overwrite"]}[output]
    argv = HELD + extra if output != "--plot" else HELD[:1] + extra
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), *argv], cwd=tmp_path, env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        before = wait_for_progress(process.stderr)   # the run is under way, and cannot end by itself
        assert before[-1].startswith("running:"), before
        process.send_signal(signum)
        out, err = process.communicate(timeout=60)
    finally:
        process.kill()
        process.wait()
    assert process.returncode == status, err
    assert "Traceback" not in err and out == ""
    assert not_progress(err.strip().splitlines()) == [
        f"stopped: {'interrupted (Ctrl-C)' if status == 130 else 'terminated (SIGTERM)'}; no file was left half-written"]
    assert path.read_text() == "the teacher's old data\n"
    assert sorted(os.listdir(tmp_path)) == sorted([path.name, "scenes"])


def test_the_held_run_finishes_once_its_gate_is_open(tmp_path):
    """The scene the tests above interrupt is an ordinary run once the test lets it go on (so what
    they interrupt is a run, not a hang): the same progress line, then the whole CSV file."""
    env, gate = held_scene(tmp_path / "scenes")
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), *HELD, "--csv", "run.csv"], cwd=tmp_path,
                               env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert wait_for_progress(process.stderr)[-1].startswith("running:")
        open_gate(gate)
        out, err = process.communicate(timeout=120)
    finally:
        process.kill()
        process.wait()
    assert process.returncode == 0 and not_progress(err.splitlines()) == [], err
    assert out.startswith("held: 10000 steps of dt = 0.001 s with euler-cromer")
    assert len((tmp_path / "run.csv").read_text().splitlines()) == 1 + 10_001


def test_ctrl_c_while_the_program_is_still_loading_is_one_line_too(tmp_path):
    """Ctrl-C while numpy loads (main.py's imports, after its first lines set the handlers). The
    held run cannot end before the signal, wherever it finds the program."""
    env, gate = held_scene(tmp_path / "scenes")
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), *HELD, "--json"], cwd=tmp_path,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    maps = Path(f"/proc/{process.pid}/maps")
    deadline = time.monotonic() + 30
    while "numpy" not in maps.read_text() and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.005)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=30)
    assert process.returncode == 130, err
    assert "Traceback" not in err and out == ""
    assert len(not_progress(err.splitlines())) == 1, err
    assert sorted(os.listdir(tmp_path)) == ["scenes"]


def test_ctrl_c_while_the_browser_view_waits_for_a_browser_is_one_line_and_status_130(tmp_path):
    """`main.py vertical --no-browser` prints its address and waits; Ctrl-C then ends it like any
    command (it once exited 0 without a word). With a page connected: tests/test_page_lifecycle.py."""
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), "vertical", "--no-browser"], cwd=tmp_path,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert process.stdout.readline().startswith("Open http://127.0.0.1:")
    # into vpython's wait for a browser: both its servers listen (the page's and the websocket's)
    # only once vpython has loaded, just before it waits; a fixed sleep guessed how long loading takes
    wait_for_listeners(process.pid, 2, timeout=120)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=30)
    assert process.returncode == 130, err
    assert err.splitlines() == ["stopped: interrupted (Ctrl-C); no file was left half-written"], err
    assert os.listdir(tmp_path) == []


# ---- issue 20: hardening, round three ----

def run_main(*argv, cwd=None, env=None, timeout=120, **options):
    """`python main.py ARGV` as a user runs it, with extra environment variables."""
    streams = {"stdout": subprocess.PIPE, "stderr": subprocess.PIPE, **options}
    return subprocess.run([sys.executable, str(ROOT / "main.py"), *argv], cwd=cwd or ROOT,
                          env={**os.environ, **(env or {})}, timeout=timeout, **streams)


@pytest.mark.parametrize("encoding, argv", [
    ("ascii", "vertical --headless"), ("ascii", "vertical --headless --json"), ("ascii", "vertical --steps 2"),
    ("ascii", "--list"), ("ascii", "integrators --constants"), ("ascii", "--help"),
    ("ascii", "vertical --headless --set g=-1"), ("cp1252", "damped --steps 2"), ("latin-1", "--help")])
def test_every_output_works_in_a_terminal_that_cannot_write_the_symbols(encoding, argv):
    """A Windows console (cp1252), an ASCII pipe or a latin-1 locale once ended every command with
    'unexpected UnicodeEncodeError': now Δt is written dt, ω omega, √ sqrt, ² ^2, − -."""
    from reports.terminal import spell

    done = run_main(*argv.split(), env={"PYTHONIOENCODING": encoding})
    assert done.returncode == (2 if "g=-1" in argv else 0), done.stderr
    assert b"UnicodeEncodeError" not in done.stderr and b"Traceback" not in done.stderr
    if encoding == "ascii":   # exactly the UTF-8 output, each symbol spelled out
        utf8 = run_main(*argv.split(), env={"PYTHONIOENCODING": "utf-8"})
        assert done.stdout.decode("ascii") == spell(utf8.stdout.decode("utf-8"))
        assert done.stderr.decode("ascii") == spell(utf8.stderr.decode("utf-8"))
    else:
        assert done.stdout.decode(encoding)


def test_the_ascii_spellings_read_as_a_student_would_type_them():
    from reports.terminal import spell

    assert spell("Δt = 0.1 s, ω = √(k/m), g = 9.8 m/s², b/m = 4 s⁻¹, x = −1.7") == \
        "dt = 0.1 s, omega = sqrt(k/m), g = 9.8 m/s^2, b/m = 4 s^-1, x = -1.7"
    assert spell("kg·m/s, L̂, û") == "kg*m/s, L, u"


def test_a_closed_standard_output_is_one_line_and_status_2_not_a_lost_report(tmp_path):
    """`main.py vertical --headless >&-` once printed nothing and exited 0."""
    done = run_main("vertical", "--headless", cwd=tmp_path, stdout=None, preexec_fn=lambda: os.close(1))
    assert done.returncode == 2
    assert done.stderr.decode().splitlines() == [
        "error: cannot print the output: standard output is closed (the command was started with >&- or "
        "without a console); redirect it to a file"]


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full (Linux)")
def test_a_full_disk_under_standard_output_is_one_line_not_a_bug(tmp_path):
    with open("/dev/full", "w") as full:
        done = run_main("vertical", "--headless", "--json", cwd=tmp_path, stdout=full)
    assert done.returncode == 2
    assert done.stderr.decode().splitlines() == ["error: cannot print the output: No space left on device"]


@pytest.mark.parametrize("argv", ["vertical --headless --csv x.csv", "vertical --vpython x.py --webvpython y.py"])
def test_a_relative_path_from_a_deleted_folder_is_one_line_not_a_bug(argv, tmp_path, monkeypatch, capsys):
    folder = tmp_path / "gone"
    folder.mkdir()
    monkeypatch.chdir(folder)
    folder.rmdir()
    assert main.run(argv.split()) == 2
    out, err = capsys.readouterr()
    assert err.splitlines() == [f"error: cannot write {'CSV file' if 'csv' in argv else 'the program'} "
                                f"'x.{'csv' if 'csv' in argv else 'py'}': the folder this command runs in no "
                                f"longer exists; cd to a folder that exists, or give the full path"]
    assert os.listdir(tmp_path) == []


def test_a_misspelt_matplotlib_backend_does_not_stop_the_figure(tmp_path):
    """MPLBACKEND=nonsense made matplotlib refuse to load ('unexpected ValueError'); the figure is
    drawn to a file whatever the backend, so it is left aside."""
    done = run_main("vertical", "--plot", "v.png", cwd=tmp_path, env={"MPLBACKEND": "nonsense"})
    assert done.returncode == 0 and done.stderr == b"", done.stderr
    assert os.listdir(tmp_path) == ["v.png"]


def test_a_broken_matplotlib_is_one_line_naming_it(tmp_path):
    (tmp_path / "matplotlib").mkdir()
    (tmp_path / "matplotlib" / "__init__.py").write_text("raise RuntimeError('half installed')\n")
    done = run_main("vertical", "--plot", "v.png", cwd=tmp_path, env={"PYTHONPATH": str(tmp_path)})
    assert done.returncode == 2
    lines = done.stderr.decode().splitlines()
    assert len(lines) == 1 and lines[0].startswith(
        "error: --plot cannot load matplotlib (RuntimeError: half installed); reinstall it"), lines
    assert os.listdir(tmp_path) == ["matplotlib"]


@pytest.mark.parametrize("argv", ["vertical --vpython main.py", "vertical --headless --csv scenes/damped.py",
                                  "vertical --vpython scenes/_model.py --overwrite", "vertical --plot README.md",
                                  "vertical --webvpython requirements.txt --overwrite"])
def test_the_program_never_writes_over_its_own_files(argv, monkeypatch, capsys):
    """`--vpython main.py` once replaced main.py with the handout (then `main.py --list` ran the
    handout and waited for a browser for ever); `--vpython scenes/_model.py` broke every command."""
    monkeypatch.chdir(ROOT)
    before = {path: (ROOT / path).read_bytes() for path in ("main.py", "scenes/damped.py", "scenes/_model.py",
                                                          "README.md", "requirements.txt")}
    try:
        assert main.run(argv.split()) == 2
    finally:   # the old code wrote over them: put them back
        changed = [path for path, text in before.items() if (ROOT / path).read_bytes() != text]
        for path in changed:
            (ROOT / path).write_bytes(before[path])
    assert changed == []
    out, err = capsys.readouterr()
    what, path = argv.split()[-3:-1] if argv.endswith("--overwrite") else argv.split()[-2:]
    name = path.split("/")[-1]
    why = (f"it is inside the program's own folder {path.split('/')[0]}/, which it never writes into; write it "
           f"in out/ (kept for your files: out/{name}) or outside the program's folder" if "/" in path else
           f"it is beside main.py, in the program's own folder, which holds only the program's files; write it "
           f"in out/ (kept for your files: out/{name}) or outside the program's folder")
    assert err.splitlines() == [f"error: cannot write {dict(csv='CSV file', plot='figure').get(what[2:], 'the program')} "
                                f"{path!r}: {why}"]


def test_a_python_file_the_program_did_not_write_is_replaced_only_with_overwrite(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "mine.py").write_text("print('a student's own program')\n")
    for argv in (["vertical", "--vpython", "mine.py"], ["vertical", "--headless", "--csv", "mine.py"]):
        assert main.run(argv) == 2
        assert capsys.readouterr().err.splitlines() == [
            f"error: cannot write {'the program' if '--vpython' in argv else 'CSV file'} 'mine.py': it is a Python "
            f"file this program did not write; give another name, or add --overwrite to replace it"]
        assert (tmp_path / "mine.py").read_text() == "print('a student's own program')\n"
    assert main.run(["vertical", "--vpython", "mine.py", "--overwrite"]) == 0
    assert main.run(["damped", "--vpython", "mine.py"]) == 0   # now a handout of ours: replaced as asked
    assert "# damped:" in (tmp_path / "mine.py").read_text(encoding="utf-8")
    assert main.run(["damped", "--headless", "--csv", "run.csv"]) == 0
    assert main.run(["damped", "--headless", "--csv", "run.csv"]) == 0   # any other file: replaced as before
    assert sorted(os.listdir(tmp_path)) == ["mine.py", "run.csv"]


def hostile_scenes_folder(folder: Path) -> Path:
    """A teacher's scenes folder with what once hung or broke every command: a handout (its vpython
    server waits for a browser), a scene that sleeps as it loads, a named pipe and a link to
    /dev/stdin called *.py, a 13 MB file, and a scene called catalog.py."""
    done = run_main("vertical", "--vpython", str(folder / "handout.py"))
    assert done.returncode == 0, done.stderr
    (folder / "sleepy.py").write_text('"""Sleeps as it loads."""\nimport time\ntime.sleep(600)\n\n\n'
                                      'def build(**constants):\n    pass\n')
    os.mkfifo(folder / "pipe.py")
    os.symlink("/dev/stdin", folder / "stdin.py")
    (folder / "huge.py").write_text('"""Huge."""\n' + "#" * 13_000_000 + "\n")
    (folder / "catalog.py").write_text((ROOT / "scenes" / "vertical.py").read_text().replace("from ._", "from scenes._"))
    return folder


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes are POSIX")
def test_a_teachers_scenes_folder_is_read_without_running_any_scene(tmp_path):
    """--list read every scene by running it: each of these hung it, or every command; now the
    files are read as text (with a size limit), and a scene runs only when it is asked for."""
    folder = hostile_scenes_folder(tmp_path)
    env = {"SPRING_SCENES": str(folder)}
    started = time.monotonic()
    # the sleepy scene sleeps 600 s as it loads: ending at all, well within that, says it was not run
    # (a bound of 20 s, as this was, measured the computer's speed as much as the program)
    listed = run_main("--list", env=env, timeout=300, stdin=subprocess.DEVNULL)
    assert time.monotonic() - started < 300
    out, err = listed.stdout.decode(), listed.stderr.decode()
    assert listed.returncode == 2 and "Traceback" not in err
    assert "sleepy       Sleeps as it loads." in out and "vertical" in out
    assert not any(name in out for name in ("handout", "pipe", "stdin", "huge", "catalog"))
    assert sorted(err.splitlines()) == sorted([
        f"error: {folder / 'catalog.py'}: the name 'catalog' is taken by the simulator's own code "
        f"(scenes.catalog); rename the file",
        f"error: {folder / 'handout.py'} is not a scene: it has no build function (`def build(**constants):` "
        f"after the constants block)",
        f"error: {folder / 'huge.py'}: it is 13,000,013 bytes, more than a scene file's 1,000,000, so it was not read",
        f"error: {folder / 'pipe.py'}: it is not a regular file, so it was not read",
        f"error: {folder / 'stdin.py'}: it is not a regular file, so it was not read"])
    run = run_main("vertical", "--headless", env=env, timeout=60)
    assert run.returncode == 0 and run.stderr == b""
    for name in ("pipe", "handout", "catalog"):
        chosen = run_main(name, "--headless", env=env, timeout=60)
        assert chosen.returncode == 2 and len(chosen.stderr.splitlines()) == 1, chosen.stderr


def test_the_reserved_scene_names_are_every_name_the_scenes_package_gives_its_own_code():
    import scenes
    from scenes import catalog

    own = {name for name, value in vars(scenes).items() if not name.startswith("_")
           and getattr(value, "__file__", None) not in {str(path) for path in catalog.SCENE_FILES.values()}}
    assert own <= catalog.RESERVED


@pytest.mark.parametrize("body", ["import sys\nsys.exit()\n", "raise SystemExit(3)\n",
                                  "m = 10.0   # kg: mass\n# ---- end of constants ----\n\n\n"
                                  "def build(**constants):\n    raise SystemExit(0)\n"])
def test_a_scene_that_calls_sys_exit_is_a_broken_scene_like_any_other(body, tmp_path):
    """It used to end the program silently: `--list` printed nothing with exit 0, a run just stopped."""
    source = '"""Ends the program."""\n' + body
    if "def build" not in body:
        source += "\n\ndef build(**constants):\n    pass\n"
    (tmp_path / "quits.py").write_text(source)
    env = {"SPRING_SCENES": str(tmp_path)}
    run = run_main("quits", "--headless", env=env)
    lines = run.stderr.decode().splitlines()
    assert run.returncode == 2 and len(lines) == 1, lines
    assert lines[0].startswith(f"error: {tmp_path / 'quits.py'}, line ") and "calls sys.exit()" in lines[0]
    listed = run_main("--list", env=env)
    assert listed.returncode == 0 and b"quits" in listed.stdout and b"vertical" in listed.stdout


@pytest.mark.parametrize("length", [241, 255])
def test_a_legal_long_file_name_is_written(length, tmp_path, monkeypatch, capsys):
    """Names of 241 to 255 bytes were refused ('File name too long'): the temporary file's name was
    the target's plus 15 bytes."""
    monkeypatch.chdir(tmp_path)
    for flag, extension in (("--csv", ".csv"), ("--vpython", ".py")):
        name = "a" * (length - len(extension)) + extension
        argv = ["vertical", "--headless", flag, name] if flag == "--csv" else ["vertical", flag, name]
        assert main.run(argv) == 0, capsys.readouterr().err
        assert (tmp_path / name).stat().st_size > 0
    capsys.readouterr()
    assert len(os.listdir(tmp_path)) == 2


class TerminalStream:
    """A stream that says it is a terminal, as standard error is when a person runs a command."""

    def __init__(self, interrupt_after=None):
        self.text, self.writes, self.interrupt_after = "", 0, interrupt_after

    def isatty(self):
        return True

    def write(self, text):
        self.text += text
        self.writes += 1
        if self.writes == self.interrupt_after:
            raise KeyboardInterrupt

    def flush(self):
        pass


@pytest.mark.parametrize("interrupt_after", [None, 3])
def test_the_progress_line_on_a_terminal_is_ended_so_the_next_line_starts_afresh(interrupt_after, monkeypatch):
    """The redrawn line was never ended: `...t = 5 sdamped: ...`, and the Ctrl-C message glued on too."""
    import physics.simulate
    from reports import headless
    from scenes import configure

    monkeypatch.setattr(physics.simulate, "PROGRESS_EVERY", 0.0)   # a line for every chunk of steps
    stream = TerminalStream(interrupt_after)
    setup = configure("damped")
    try:
        headless.simulate(setup, until=300.0, every_step=False, progress=stream)
    except KeyboardInterrupt:
        assert interrupt_after is not None
    assert stream.text.startswith("\rrunning: ") and stream.text.count("\rrunning: ") >= 2
    assert stream.text.endswith(" s\n") and stream.text.count("\n") == 1


def test_a_suggested_until_fits_with_room_to_spare():
    """The refusal suggested the --until that just fitted the estimate, which was then refused
    (157.691, then 154.67, then 151.147, which ran 95 s against the 60 s limit). Now it fits in half
    the limit by the estimate, rounded down to two digits (a busy machine can run slower than that)."""
    from physics.simulate import RunTooLong, check_cost
    from scenes import configure

    model = configure("vertical", assignments=["dt=1e-5"]).build()
    engine = model.simulation(None)
    with pytest.raises(RunTooLong) as refused:
        check_cost(engine, until=1000.0, limit=0.4)
    suggested = float(re.search(r"at most ([0-9.e+-]+) s with dt", str(refused.value)).group(1))
    assert len(f"{suggested:g}".replace(".", "").lstrip("0")) <= 2   # a value to type: two digits
    per_step = engine.seconds_per_step()
    assert suggested / 1e-5 * per_step <= 0.5 * 0.4 + 1e-9
    assert check_cost(engine, until=suggested, limit=0.4) > 0   # asked again: accepted


def test_a_run_too_long_for_the_scene_to_shorten_suggests_no_until_it_refuses(tmp_path, monkeypatch, capsys):
    """resonance --set count=10000 --csv suggested until ≤ 1.56 s, which the scene itself refuses
    (it measures the amplitudes from t = settle = 40 s on)."""
    monkeypatch.chdir(tmp_path)
    assert main.run(["resonance", "--set", "count=10000", "--headless", "--csv", "r.csv"]) == 2
    line, = capsys.readouterr().err.splitlines()
    assert "more than the 60 s a run may take; use a larger dt or fewer masses (the scene needs --until of at " \
           "least 49.4248 s)" in line and "at most" not in line
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("method", ["euler-cromer", "verlet"])
def test_a_step_exactly_at_the_stability_limit_runs_and_says_what_the_motion_does(method, capsys):
    """ω·Δt = 2 exactly (vertical: ω = 2 rad/s, dt = 1 s) ran silently, and the motion grew; then it
    was refused as a blow-up, which it is not (issue 28, item 6): it runs, with one true sentence
    (tests/test_stability_limit.py checks the motion against the hand-worked sequences)."""
    from physics.stability import _grows, amplification

    assert _grows(float(amplification(method, omega=2.0, rate=0.0, dt=1.0)[0]), 2.0)
    assert not _grows(float(amplification(method, omega=2.0, rate=0.0, dt=0.9999999)[0]), 2.0)
    assert main.run(["vertical", "--headless", "--set", "dt=1", "--until", "10", "--integrator", method]) == 0
    line, = capsys.readouterr().err.splitlines()
    what = ("the position flips sign at every step and stays bounded" if method == "verlet" else
            "the position flips sign at every step and its swing grows by the same amount every step")
    assert line.startswith(f"warning: dt = 1 s is exactly {method}'s stability limit for the spring "
                           f"(ω = 2 rad/s, ω·dt = 2): started from rest, as here, {what}"), line


def test_a_dt_just_past_the_limit_is_printed_with_the_digits_that_show_it(capsys):
    """It read 'dt = 1 s, but … makes dt < 1 s necessary' for dt = 1.0000001 s."""
    assert main.run(["vertical", "--headless", "--set", "dt=1.0000001", "--until", "10"]) == 1
    line, = capsys.readouterr().err.splitlines()
    assert "dt = 1.0000001 s, but the spring" in line and "makes dt < 1 s necessary" in line


def test_a_blow_up_caused_by_drag_names_the_drag(capsys):
    """It said only 'try a smaller dt', where the stability judgement names the drag."""
    assert main.run("vertical --headless --set C=100 --set A=10 --set rho=1000 --until 10".split()) == 1
    line, = capsys.readouterr().err.splitlines()
    assert line.startswith("error: the simulation blew up by t = ")
    assert "dt = 0.1 s, but the drag (its rate ρCA|v|/m grows with the speed) outgrew what euler-cromer can " \
           "follow at this dt; try a smaller dt, or less drag" in line


def test_an_empty_scene_name_is_an_error_not_the_default_scene(capsys):
    """`main.py "" --headless` ran vertical."""
    for name in ("", "  "):
        assert main.run([name, "--headless"]) == 2
        out, err = capsys.readouterr()
        assert out == "" and err.splitlines() == [
            "error: the scene name is empty: give one, like 'vertical' (run 'python main.py --list' to see them)"]


def test_waiting_for_a_browser_is_said_once_not_every_10_s_for_ever(capsys):
    import threading

    from browser.server import start

    reminder = threading.Thread(target=start.remind, args=("http://127.0.0.1:1/", 0.01, threading.Event()),
                                daemon=True)
    reminder.start()
    reminder.join(timeout=30)
    alive = reminder.is_alive()
    assert not alive   # the old reminder never returned
    assert capsys.readouterr().err.splitlines() == [
        "Still waiting for a browser: open http://127.0.0.1:1/ (Ctrl-C to quit)"]


def test_no_browser_on_the_computer_is_said_once_with_how_to_open_the_page(monkeypatch, capsys):
    from browser.server import http_server

    monkeypatch.setattr(http_server.webbrowser, "open", lambda url: False)
    http_server.open_browser("http://127.0.0.1:1/")
    assert capsys.readouterr().err.splitlines() == [
        "No browser was found on this computer: open http://127.0.0.1:1/ in a browser yourself (Ctrl-C to quit)"]


def test_the_resonance_report_has_the_amplitude_table(capsys):
    """`resonance --headless` printed 276 lines of per-mass state and no amplitudes."""
    assert main.run(["resonance", "--headless"]) == 0
    out = capsys.readouterr().out
    assert "steady-state amplitude A (m) against the driving frequency ω, measured from t = 40 s to 49.42 s" in out
    head = next(line for line in out.splitlines() if line.startswith("ω (rad/s)"))
    assert head.split() == ["ω", "(rad/s)", "b", "=", "0.5", "kg/s", "b", "=", "1", "kg/s", "b", "=", "2", "kg/s"]
    row = next(line for line in out.splitlines() if line.startswith("5 "))   # ω = ω0 = 5 rad/s: A = F0/(b ω0)
    assert row.split() == ["5", "0.4", "0.4", "0.2", "0.2", "0.1", "0.1"]
    # the lesson first: the table comes before the 39 masses' states (it came after 276 lines of them)
    lines = out.splitlines()
    assert lines.index(head) < 20 and lines.index(head) < lines.index(next(l for l in lines if l.startswith("  r = ")))


@pytest.mark.parametrize("args, options, message", [
    (("vertical",), {"scenario": "3"}, "scenario needs a whole number, like scenario=3 (got '3')"),
    (("vertical",), {"preset": 3}, "preset needs a name as text, like preset='Moon gravity' (got 3)"),
    (("vertical",), {"integrator": ["rk4"]}, "integrator needs a name as text, like integrator='rk4' (got ['rk4'])"),
    ((123,), {}, "show() needs the scene's name as text, like show('vertical') (got 123)"),
    (("vertical",), {"k": 10**5000}, "k is too large to be a number the program can use (got an integer of about 5000 digits)"),
    (("vertical",), {"k": "60"}, "k needs a number, or three numbers for a vector like r0=(0, -1.2, 0) (got '60')"),
    (("vertical",), {"k": -5}, "k must be from 0 to 1e6 N/m (got -5 N/m)"),
    (("vertical",), {"integrator": "leapfrog"}, "unknown integrator 'leapfrog'"),
])
def test_the_notebooks_show_answers_a_wrong_argument_in_one_line(args, options, message):
    """Wrong types raised TypeErrors from inside (show(123), integrator=["rk4"], k=10**5000), and a
    ConstantError printed a 35-line traceback in the notebook: IPython now shows one line."""
    from browser.notebook import show
    from scenes import ConstantError

    with pytest.raises(ConstantError) as refused:
        show(*args, **options)
    assert message in str(refused.value)
    assert refused.value._render_traceback_() == [f"ConstantError: {refused.value}"]


def test_opening_the_notebook_leaves_git_status_clean():
    """Jupyter writes examples/.ipynb_checkpoints/ when the notebook is opened."""
    done = subprocess.run(["git", "check-ignore", "-q", "examples/.ipynb_checkpoints/scenes-checkpoint.ipynb"],
                          cwd=ROOT)
    assert done.returncode == 0


@pytest.mark.skipif(not Path("/proc/net/tcp").exists(), reason="reads the listening sockets from /proc (Linux)")
def test_a_handed_out_program_serves_its_page_to_this_computer_only(tmp_path):
    """Plain vpython listens on 0.0.0.0 (and serves `GET /../file` from anywhere on the disk): the
    handout's first lines bind its servers to 127.0.0.1. Run with the real vpython, as a student does."""
    from test_loopback_server import listening_sockets, wait_for_listeners
    from browser_support import free_port

    program = tmp_path / "vertical.py"
    assert run_main("vertical", "--vpython", str(program)).returncode == 0
    env = {**os.environ, "VPYTHON_NO_LAUNCH_BROWSER": "1", "VPYTHON_HTTP_PORT": str(free_port())}
    process = subprocess.Popen([sys.executable, str(program)], cwd=tmp_path, env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for_listeners(process.pid, 2, timeout=60)   # its HTTP and websocket servers
        found = listening_sockets(process.pid)
    finally:
        process.kill()
        process.wait(timeout=30)
    assert found and all(address == "127.0.0.1" for _, address, _ in found), found


def test_derived_values_follow_the_values_used(capsys):
    """Comments and --constants kept the defaults' ω = √(k/m) = 5 rad/s and ω Δt = 0.3 after
    --set k=100; drag's falling preset (k = 0) kept 'ω0 ≈ 6.1 rad/s'; resonance --set k=16 said ω0 = 5."""
    def output(*argv):
        assert main.run(list(argv)) == 0
        return capsys.readouterr().out

    text = output("integrators", "--set", "k=100", "--constants")
    assert "so: ω0 = √(k/m) = 10 rad/s, T = 2π/ω0 = 0.6283 s, ω0·dt = 0.6" in text
    assert "5 rad/s" not in text and "0.3" not in text and "1.26" not in text
    text = output("resonance", "--set", "k=16", "--constants")
    assert "ω0 = √(k/m) = 4 rad/s" in text and "5 rad/s" not in text
    k_line, = [line for line in output("drag", "--preset", "falling", "--vpython", "-").splitlines()
               if line.startswith("k = ")]
    assert k_line.startswith("k = 0 ") and "6.1" not in k_line and "rad/s" not in k_line


def test_a_handout_with_changed_constants_does_not_describe_the_defaults_as_its_own(capsys):
    """The vertical program said 'a 10 kg mass' with m = 17.4 below, and the page's Download
    program wrote --set b=52.76362383309168 where the preset's name gives it."""
    assert main.run(["vertical", "--preset", "critical damping", "--set", "m=17.4", "--vpython", "-"]) == 0
    lines = capsys.readouterr().out.splitlines()
    summary = next(n for n, line in enumerate(lines) if line.startswith("# vertical: "))
    assert "a 17.4 kg mass" in lines[summary] and not lines[summary + 1].startswith("# (")   # tests/test_handout.py
    assert "# The same case on the simulator's page: python main.py vertical --preset \"critical damping\" " \
           "--set m=17.4" in lines


def test_a_handout_can_run_longer_than_the_question_time_and_plots_from_t_0(capsys):
    """--until was refused with --vpython (the vertical handout animates 0.2 s, two steps), and the
    program plotted from the first step on, never t = 0."""
    assert main.run(["vertical", "--vpython", "-", "--until", "10"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert any(line.startswith("until = 0.2 ") for line in lines) and any(line.startswith("t_end = 10 ") for line in lines)
    loop = lines.index("while t < t_end:")
    assert "position.plot(t, pos.y)" in lines[:loop]
    assert main.run(["regimes", "--webvpython", "-"]) == 0
    lines = capsys.readouterr().out.splitlines()
    loop = next(n for n, line in enumerate(lines) if line.startswith("while t < t_end"))
    assert lines[loop - 2:loop] == ["for i in range(len(pos)):", "    position[i].plot(t, pos[i].y)"]

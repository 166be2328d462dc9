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
    ("resonance --headless --json --set until=10", 2, "set until to at least"),
    ("resonance --no-browser --set count=10000", 2, "30,000 masses are more than the 2,000 the page can draw"),
    ("resonance --no-browser --set count=2000 --set curves=1 --set dt=1e-6", 2, "so the page would crawl"),
    # ---- flags that conflict, or do nothing in the chosen mode ----
    ("vertical --json", 2, "--json needs --headless"),
    ("vertical --csv x.csv", 2, "--csv needs --headless"),
    ("vertical --until 3", 2, "--until needs --headless"),
    ("--list --set k=abc", 2, "--list takes no scene or other option (got --set)"),
    ("--list vertical", 2, "--list takes no scene"),
    ("--list --headless", 2, "--list takes no scene or other option (got --headless)"),
    ("--list --port 8000", 2, "--list takes no scene or other option (got --port)"),
    ("vertical --constants --headless", 2, "--constants only prints the constants, so --headless"),
    ("vertical --constants --port 5000", 2, "so --port would do nothing"),
    ("vertical --constants --json", 2, "so --json would do nothing"),
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
    ("vertical --arrows p,momentum", 2, "--arrows knows p, F_net, forces, split (got 'momentum')"),
    ("vertical --headless --no-arrows", 2, "--arrows (and --no-arrows) is for the page and the program"),
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
    from reports import headless

    text = headless.to_json({"energy": {"K": float("inf"), "U": 1.0}, "r": [0.0, float("nan"), 0.0]})
    out = strict_json(text)
    assert out["energy"] == {"K": None, "U": 1.0} and out["r"] == [0.0, None, 0.0]
    assert any(note.startswith("energy.K: null") for note in out["notes"])
    assert any(note.startswith("r[1]: null") for note in out["notes"])
    assert headless.number(float("inf")) == headless.number(float("nan")) == headless.NO_VALUE


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
    """README: a run past the stability limit stops with exit status 1 and names Δt and the limit."""
    readme = (ROOT / "README.md").read_text()
    assert "stops with exit status 1" in " ".join(readme.split())
    done = subprocess.run([sys.executable, "main.py", "vertical", "--headless", "--set", "dt=1.5",
                           "--until", "10"], cwd=ROOT, capture_output=True, text=True, timeout=60)
    lines = done.stderr.strip().splitlines()
    assert lines[-1].startswith("error:") and "dt" in lines[-1] and "Traceback" not in done.stderr
    assert not NOT_A_NUMBER.search(done.stdout) and done.stdout == ""


# ---- what needs a real process ----

def test_the_last_resort_handler_turns_any_bug_into_one_line_and_status_1(tmp_path):
    code = ("import sys, main\nfrom reports import headless\n"
            "def broken(result): raise KeyError('a bug nobody foresaw')\n"
            "headless.final_report = broken\n"
            "sys.exit(main.run(['vertical', '--headless']))\n")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert done.returncode == 1
    assert "Traceback" not in done.stderr and done.stdout == ""
    assert done.stderr.strip().splitlines() == [
        "error: unexpected KeyError: 'a bug nobody foresaw' (a bug in main.py; please report it "
        "with the command you ran)"]


# Long enough to be interrupted after the first progress line (1 s of stepping): 10⁷ steps for a
# run that keeps only its end, 10⁶ rk4 steps written row by row (the CSV or figure costs the most;
# rk4 keeps the stepping itself past a second on a fast, quiet computer).
LONG_RUN = ["vertical", "--headless", "--set", "dt=1e-6", "--until", "10"]
LONG_ROWS = ["vertical", "--headless", "--integrator", "rk4", "--set", "dt=1e-5", "--until", "10"]


@pytest.mark.parametrize("signum, status, output", [(signal.SIGINT, 130, "--csv"), (signal.SIGTERM, 143, "--json"),
                                                    (signal.SIGINT, 130, "--plot")])
def test_a_signal_during_a_long_run_ends_cleanly_and_leaves_no_partial_file(signum, status, output, tmp_path):
    path = tmp_path / ("run.png" if output == "--plot" else "run.csv")
    path.write_text("the teacher's old data\n")
    extra = {"--json": ["--json"], "--csv": ["--csv", str(path)], "--plot": ["--plot", str(path)]}[output]
    run = LONG_RUN if output == "--json" else LONG_ROWS
    argv = run + extra if output != "--plot" else [*run[:1], *run[2:], *extra]
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), *argv], cwd=tmp_path,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        first = process.stderr.readline()  # the first progress line: the run is under way
        assert first.startswith("running:"), first
        process.send_signal(signum)
        out, err = process.communicate(timeout=30)
    finally:
        process.kill()
    assert process.returncode == status, err
    assert "Traceback" not in err and out == ""
    assert err.strip().splitlines() == [f"stopped: {'interrupted (Ctrl-C)' if status == 130 else 'terminated (SIGTERM)'}; "
                                        f"no file was left half-written"]
    assert path.read_text() == "the teacher's old data\n"
    assert os.listdir(tmp_path) == [path.name]


def test_ctrl_c_while_the_program_is_still_loading_is_one_line_too(tmp_path):
    """Ctrl-C while numpy loads (main.py's imports, after its first lines set the handlers)."""
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), *LONG_RUN, "--json"], cwd=tmp_path,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    maps = Path(f"/proc/{process.pid}/maps")
    deadline = time.monotonic() + 30
    while "numpy" not in maps.read_text() and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.005)
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=30)
    assert process.returncode == 130, err
    assert "Traceback" not in err and out == ""
    assert len([line for line in err.splitlines() if not line.startswith("running:")]) == 1, err
    assert os.listdir(tmp_path) == []


def test_ctrl_c_while_the_browser_view_waits_for_a_browser_is_one_line_and_status_130(tmp_path):
    """`main.py vertical --no-browser` prints its address and waits; Ctrl-C then ends it like any
    command (it once exited 0 without a word). With a page connected: tests/test_page_lifecycle.py."""
    process = subprocess.Popen([sys.executable, str(ROOT / "main.py"), "vertical", "--no-browser"], cwd=tmp_path,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert process.stdout.readline().startswith("Open http://127.0.0.1:")
    time.sleep(1.0)  # into vpython's wait for a browser
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=30)
    assert process.returncode == 130, err
    assert err.splitlines() == ["stopped: interrupted (Ctrl-C); no file was left half-written"], err
    assert os.listdir(tmp_path) == []

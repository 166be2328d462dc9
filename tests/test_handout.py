"""The handed-out program (issue 20, items 14 and 15): its numbers follow the case it was written
for, it runs long enough to watch, and it prints the command line's answer at the question time.

Programs are run under the stand-in vpython of tests/test_export.py (rate() returns at once).
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

import export
from scenes import catalog
from test_export import final_state, main_py, run_program, stand_in  # noqa: F401 (stand_in is a fixture)


def lines_of(*args) -> list[str]:
    done = main_py(*args, "--vpython", "-")
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


def header(lines: list[str]) -> list[str]:
    return lines[:lines.index("# ---- constants (unit: meaning) ----")]


# ---- item 14: derived values follow the values used ----

def test_the_description_gives_this_cases_mass():
    """The vertical program said 'a 10 kg mass' with m = 17.4 kg below it."""
    top = header(lines_of("vertical", "--set", "m=17.4"))
    assert top[3] == ("# vertical: The page's Simple Example: a 17.4 kg mass hangs on a 40 N/m spring and is "
                      "released from rest at 1.5 m.")
    assert not any("10 kg" in line or "as shipped" in line for line in top)


def test_a_number_no_constant_accounts_for_is_said_to_be_the_shipped_one():
    """`released from rest at 1.5 m` is |r0 − anchor|, no single constant: with r0 changed the
    line stays as shipped and says so, rather than describe another case as this one."""
    top = header(lines_of("vertical", "--set", "r0=0,-2,0"))
    assert "released from rest at 1.5 m" in top[3]
    assert top[4] == "# (Some numbers in that line are the scene's as shipped; this case's constants are below.)"
    for args in [("vertical",), ("vertical", "--set", "m=17.4"), ("driven", "--scenario", "4")]:
        assert not any(line.startswith("# (") for line in header(lines_of(*args))), args


def test_critical_damping_is_written_as_its_rule():
    """The page's Download program (m moved to 17.4, then the preset) wrote b = 52.76362383309168;
    it writes b = 2*sqrt(m*k), names the preset in the header's command and gives b = 52.76 kg/s
    in the description."""
    setup = catalog.configure("damped").with_values(m=17.4).with_preset("critical damping")  # as the page does
    lines = export.program(setup).splitlines()
    assert "52.76362383309168" not in "\n".join(lines)
    assert "b = 2*sqrt(m*k)          # kg/s: critical damping, b = 2√(mk)" in lines
    assert lines.index("b = 2*sqrt(m*k)          # kg/s: critical damping, b = 2√(mk)") > lines.index(
        next(line for line in lines if line.startswith("k = ")))
    assert "linear damping F = −b v with b = 52.76 kg/s." in lines[3]
    command = next(line for line in lines if "python main.py" in line)
    assert command.endswith('python main.py damped --preset "critical damping" --set m=17.4'), command
    assert lines_of("damped", "--set", "m=17.4", "--preset", "critical") == lines


def test_a_b_that_is_not_critical_keeps_its_number():
    lines = lines_of("damped", "--set", "b=40.5")
    assert "b = 40.5                 # kg/s: linear damping constant in F = −b v" in lines
    assert not any("sqrt(m*k)" in line for line in lines if line.startswith("b ="))


@pytest.mark.parametrize("m, k", [(17.4, 40.0), (0.1 + 0.2, 3.3), (1e-6, 1e6), (7.0, 13.0), (2.5e3, 0.37)])
def test_the_written_rule_is_the_presets_float(m, k):
    """2*sqrt(m*k) in the program's arithmetic (a correctly rounded square root, doubled) is the very
    float the preset works out: the program still reaches the engine's state."""
    assert 2 * math.sqrt(m * k) == catalog.resolve({"m": m, "k": k, "b": None})["b"]


def test_a_critically_damped_handout_reaches_the_headless_state(stand_in, tmp_path):  # noqa: F811
    case = ("damped", "--set", "m=17.4", "--preset", "critical damping", "--set", "dt=0.01")
    path = tmp_path / "critical.py"
    assert main_py(*case, "--vpython", str(path)).returncode == 0
    assert "b = 2*sqrt(m*k)" in path.read_text(encoding="utf-8")
    drawn = []
    run_program(path, stand_in, drawn)
    t_end, r_end, p_end = final_state(drawn)
    ended = main_py(*case, "--headless", "--json", "--until", repr(t_end))
    import json
    expected = json.loads(ended.stdout)
    assert np.allclose(r_end[0], expected["r"], rtol=1e-12, atol=1e-12)
    assert np.allclose(p_end[0], expected["p"], rtol=1e-12, atol=1e-12)


# ---- item 15: long enough to watch, the answer at the question time, rounded as the command line ----

def headless_answer(*args) -> str:
    """`at t = 0.2 s: r = < 0, -1.7301, 0 > m, p = < 0, -15.21, 0 > kg·m/s` from --headless's text."""
    done = main_py(*args, "--headless")
    assert done.returncode == 0, done.stderr
    text = done.stdout
    t = re.search(r"^t = (\S+) s$", text, re.M)[1]
    r = re.search(r"^r = (< .* >) m$", text, re.M)[1]
    p = re.search(r"^p = (< .* >) kg·m/s$", text, re.M)[1]
    return f"at t = {t} s: r = {r} m, p = {p} kg·m/s"


@pytest.mark.parametrize("scene, y", [("vertical", "-1.73088"), ("damped", "-1.7301")])
def test_the_homework_handout_runs_to_watch_and_answers_at_the_question_time(scene, y, stand_in, tmp_path):  # noqa: F811
    """vertical and damped ran two steps (the question time, 0.2 s): 0.2 s of animation. They run
    for the graph's 30 s, plot from t = 0, and print the answer at 0.2 s once, as --headless does
    (it printed -1.7301000000000002 where the command line prints -1.7301)."""
    path = tmp_path / f"{scene}.py"
    assert main_py(scene, "--vpython", str(path)).returncode == 0
    drawn, printed = [], []
    run_program(path, stand_in, drawn, printed)
    assert printed == [headless_answer(scene)]
    assert f"r = < 0, {y}, 0 > m" in printed[0] and "0000000" not in printed[0]
    t_end, _, _ = final_state(drawn)
    assert t_end == pytest.approx(30)
    curve = next(shown for shown in drawn if shown["kind"] == "gcurve" and shown.get("label") == "y")
    assert curve["points"][0] == [0, -1.5] and len(curve["points"]) == 301


@pytest.mark.parametrize("until, end", [("5", 5.0), ("0.1", 0.1), ("0.2", 0.2)])
def test_until_sets_when_the_program_stops(until, end, stand_in, tmp_path):  # noqa: F811
    """--until with --vpython was refused; it sets when the program stops. The answer stays at the
    question time (0.2 s), or at the end where --until is earlier, as `--headless --until` answers."""
    path = tmp_path / "vertical.py"
    done = main_py("vertical", "--until", until, "--vpython", str(path))
    assert done.returncode == 0, done.stderr
    text = path.read_text(encoding="utf-8")
    assert ("t_end = 5 " in text) == (end > 0.2)
    drawn, printed = [], []
    run_program(path, stand_in, drawn, printed)
    assert final_state(drawn)[0] == pytest.approx(end)
    question = "0.1" if end < 0.2 else "0.2"
    assert printed == [headless_answer("vertical", "--until", question)]


def test_a_question_at_t_0_is_answered_once(stand_in, tmp_path):  # noqa: F811
    path = tmp_path / "start.py"
    assert main_py("vertical", "--set", "until=0", "--vpython", str(path)).returncode == 0
    printed = []
    run_program(path, stand_in, None, printed)
    assert printed == ["at t = 0 s: r = < 0, -1.5, 0 > m, p = < 0, 0, 0 > kg·m/s"] == \
        [headless_answer("vertical", "--set", "until=0")]


def test_each_mass_is_answered_once_with_rounded_labels(stand_in, tmp_path):  # noqa: F811
    """A row (regimes: its question time 8 s, its graph 30 s): one answer line per mass, at 8 s."""
    path = tmp_path / "regimes.py"
    assert main_py("regimes", "--vpython", str(path)).returncode == 0
    printed = []
    run_program(path, stand_in, None, printed)
    assert len(printed) == catalog.configure("regimes").build().state.count
    assert all(line.partition(": ")[2].startswith("at t = 8 s: r = < ") for line in printed), printed
    assert not any(re.search(r"\d{10}", line) for line in printed), printed


def test_web_vpythons_own_format_writes_the_homework_answers_alike(tmp_path):
    """Web VPython runs str.format with its own code (String.prototype.format in glow.min.js, which
    vpython ships): run under node, it writes vertical's and damped's answers digit for digit as
    Python does. (It truncates rather than rounds the last digit of some numbers below 0.1, so a
    Web VPython answer can differ from --headless there in the sixth digit.)"""
    import importlib.util
    import json
    import shutil
    import subprocess

    node = shutil.which("node")
    glow = Path(importlib.util.find_spec("vpython").submodule_search_locations[0]) / "vpython_libraries" / "glow.min.js"
    if node is None or not glow.exists():
        pytest.skip("needs node and vpython's glow.min.js")
    source = glow.read_text(encoding="utf-8")
    start = source.index("String.prototype.format=function")
    end = source.index("function parse_html", start)
    script = tmp_path / "format.js"
    script.write_text("var pow = Math.pow;\n" + source[start:end] + "\nvar v = JSON.parse(process.argv[2]);\n"
                      "console.log(JSON.stringify(v.map(function (x) { return '{:.6g}'.format(x); })));\n",
                      encoding="utf-8")
    values = []
    for scene in ("vertical", "damped"):
        answer = json.loads(main_py(scene, "--headless", "--json").stdout)
        values += [answer["t"], *answer["r"], *answer["p"]]
    done = subprocess.run([node, str(script), json.dumps(values)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout) == ["{:.6g}".format(x) for x in values]

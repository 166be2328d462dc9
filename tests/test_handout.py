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


MARK = "# Written by the spring-mass simulator; its fingerprint is sha256:"   # export/marks.py's first line


def header(lines: list[str]) -> list[str]:
    """The program's header below its mark line (checked here): the imports and the description."""
    assert lines[0].startswith(MARK), lines[0]
    return lines[1:lines.index("# ---- constants (unit: meaning) ----")]


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
    printed = lines_of("damped", "--set", "m=17.4", "--preset", "critical")
    assert printed[0].startswith(MARK) and printed[1:] == lines   # printed, the program is marked as ours


def test_a_b_that_is_not_critical_keeps_its_number():
    lines = lines_of("damped", "--set", "b=40.5")
    assert "b = 40.5                 # kg/s: linear damping constant in F = −b v" in lines
    assert not any("sqrt(m*k)" in line for line in lines if line.startswith("b ="))


@pytest.mark.parametrize("args", [("drag", "--preset", "falling"), ("drag", "--set", "k=0")])
def test_a_case_without_springs_is_not_described_as_balls_on_springs(args):
    """`drag --preset falling` (k = 0) said "two identical balls on springs, released together"."""
    top = header(lines_of(*args))
    assert "on springs" not in top[3] and "on no spring (k = 0)" in top[3] and "terminal speed" in top[3]
    assert "balls on springs" in header(lines_of("drag"))[3]


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


# ---- the answer's digits, the same in Python and in Web VPython (export/program_answer.py) ----

RSRUN = Path(__file__).parent.parent / "export" / "glowscript" / "RSrun.3.2.min.js"   # Web VPython 3.2's str.format


def edge_values() -> list[float]:
    """Thousands of floats: every exponent, random bit patterns, short decimals, and the exact ties
    (100000.5, 2**-10 = 0.0009765625, 1000005, 12345.75) where rounding to even and away differ."""
    import random
    import struct
    rng = random.Random(20)
    values = [0.0, -0.0, 1e-7, -1e-7, 0.5, 2.5, 100000.5, 2 ** -10, -2 ** -10, 1000005.0, 12345.75,
              999999.5, 9999995.0, 0.1, 1e-4, -1e-4, 9.999995e-5, 99999.95, 999999.4, 1e6, 123456789.0,
              1e300, -1e-300, 5e-324, 1.7976931348623157e308, 0.30000000000000004, -1.7301000000000002,
              1e16, 1e21, 1e100, 1e-100, 0.0123456789, -0.09999995]
    for _ in range(3000):
        kind = rng.random()
        if kind < 0.4:
            x = rng.uniform(-1, 1) * 10.0 ** rng.randint(-9, 9)
        elif kind < 0.7:
            x = struct.unpack("d", struct.pack("Q", rng.getrandbits(64)))[0]
        else:
            x = round(rng.uniform(-1000, 1000), rng.randint(0, 7))
        if math.isfinite(x):
            values.append(x)
    return values


def helpers(replace=None) -> dict:
    """The program's number() and vector_text(), as its text defines them (with `replace` applied)."""
    from export.program_answer import HELPERS
    text = "\n".join(HELPERS)
    for old, new in (replace or {}).items():
        assert old in text
        text = text.replace(old, new)
    names = {}
    exec(text, names)
    return names


def test_the_programs_number_writes_the_command_lines_digits():
    """The handout printed '{:.6g}'.format(x): the command line writes 0 where that writes '-0' or
    round-off (1e-17 beside 1.7), and Web VPython's own 'g' differs. Its number() and vector_text()
    write what export/step_update.py's number() and vector() write, on thousands of values."""
    from types import SimpleNamespace

    from export.step_update import number, vector
    program = helpers()
    values = edge_values()
    assert [program["number"](x) for x in values] == [number(x) for x in values]
    assert program["number"](math.inf) == program["number"](math.nan) == number(math.inf) == "(no value)"
    for v in ([0.0, -1.7301000000000002, 0.0], [1e-17, 1.7, -0.0], [2e-12, 1.0, 0.0], [-3.2e-5, 4e-21, 0.0],
              [100000.5, -2 ** -10, 12345.75], [0.0, 0.0, 0.0]):
        assert program["vector_text"](SimpleNamespace(x=v[0], y=v[1], z=v[2])) == vector(v), v


def test_web_vpythons_format_gives_the_programs_number_the_same_digits(tmp_path):
    """Under node, GlowScript 3.2's own str.format (RSrun.3.2.min.js) writes '{:.6g}' unlike Python
    (1e-7 as '1.00000e-7', 100000.5 as '100001'), but the two formats number() uses, '{:.5e}' and
    '{:.30e}', give it what it needs: with their Web VPython text in place of Python's, number()
    writes Python's '{:.6g}' digit for digit on thousands of values, exact ties included."""
    import json
    import shutil
    import subprocess

    from export.step_update import number
    node = shutil.which("node")
    if node is None:
        pytest.skip("needs node (https://nodejs.org) to run Web VPython's str.format")
    values = edge_values()
    script = tmp_path / "format.js"
    script.write_text(
        "global.window = global;\n"
        "eval(require('fs').readFileSync(process.argv[2], 'utf8'));\n"
        "var values = JSON.parse(require('fs').readFileSync(process.argv[3], 'utf8'));\n"
        "var out = {};\n"
        "['{:.6g}', '{:.5e}', '{:.30e}'].forEach(function (f) {\n"
        "  out[f] = values.map(function (x) { return ρσ_str.format(f, Math.abs(x)); }); });\n"
        "console.log(JSON.stringify(out));\n", encoding="utf-8")
    numbers = tmp_path / "values.json"
    numbers.write_text(json.dumps(values), encoding="utf-8")
    done = subprocess.run([node, str(script), str(RSRUN), str(numbers)], capture_output=True, text=True,
                          timeout=120, encoding="utf-8")
    assert done.returncode == 0, done.stderr
    web = json.loads(done.stdout)
    assert web["{:.6g}"][values.index(1e-7)] == "1.00000e-7" and web["{:.6g}"][values.index(100000.5)] == "100001"
    assert sum(text != f"{abs(x):.6g}" for x, text in zip(values, web["{:.6g}"])) > 100
    seen, where = {}, {x: k for k, x in enumerate(values)}
    program = helpers({'"{:.5e}".format(abs(x))': 'web("{:.5e}", x)', '"{:.30e}".format(abs(x))': 'web("{:.30e}", x)'})
    program["web"] = lambda form, x: seen.setdefault((form, x), web[form][where[x]])
    assert [program["number"](x) for x in values] == [number(x) for x in values]
    assert len(seen) > 2 * len(set(values)) - 10    # the two formats were Web VPython's, for (nearly) every value

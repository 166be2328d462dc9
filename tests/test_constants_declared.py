"""Each constant is declared once (scenes/_constants.py), and a scene's constants block is read strictly.

The declaration carries what every scene shares: unit, symbol, vector or not, the values allowed,
where a slider starts. The scene file keeps the readable line a teacher edits; its unit must agree
with the declaration, and a line that is not `name = value  # unit: meaning` names its file and line.
So does a value that is not a number (three for a vector), a block that lacks a constant its build
needs, and a file that does not run at all; a broken scene file leaves the other scenes usable.
"""
import os
import shutil
import subprocess
import sys
import types
from pathlib import Path

import pytest

from scenes import DECLARED, SCENE_NAMES, ConstantError, catalog, load, read_constants

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("name", SCENE_NAMES)
def test_every_scene_constant_is_declared_with_the_unit_its_comment_shows(name):
    constants = read_constants(load(name))
    assert constants
    for constant in constants.values():
        assert constant.unit == DECLARED[constant.name].unit
        if constant.value is not None:            # None: derived from the others (driven r0)
            assert constant.is_vector == isinstance(constant.value, tuple)


def scene_from(source: str):
    module = types.ModuleType("scenes.a_teachers_edit")
    module.__file__ = "scenes/a_teachers_edit.py"
    exec(compile(source, module.__file__, "exec"), module.__dict__)
    import linecache
    linecache.cache[module.__file__] = (len(source), None, source.splitlines(True), module.__file__)
    return module


BLOCK = "m = 10.0   # kg: mass\n{line}\n# ---- end of constants ----\n\ndef build(**c):\n    pass\n"


@pytest.mark.parametrize("line, problem", [
    ("k = 40.0   # N/m spring constant", "k needs a comment with its unit and meaning, separated by a colon"),
    ("k = 40.0", "k needs a comment"),
    ("k = 40.0   # N: spring constant", "the unit of k is N/m, not 'N'"),
    ("kk = 40.0   # N/m: spring constant", "kk is not a constant any scene knows"),
    ("k, b = 40.0, 1.0   # N/m: two at once", "expected one name, an = sign and a value"),
])
def test_a_malformed_line_names_the_file_the_line_and_what_is_expected(line, problem):
    with pytest.raises(ConstantError) as error:
        read_constants(scene_from(BLOCK.format(line=line)))
    message = str(error.value)
    assert message.startswith("scenes/a_teachers_edit.py, line 2: ") and problem in message
    assert "`name = value  # unit: meaning`" in message and len(message.splitlines()) == 1


def test_a_well_formed_block_reads_units_and_meanings():
    constants = read_constants(scene_from(BLOCK.format(line="k = 40.0   # N/m: spring constant")))
    assert [(c.name, c.value, c.unit, c.meaning) for c in constants.values()] == [
        ("m", 10.0, "kg", "mass"), ("k", 40.0, "N/m", "spring constant")]


def test_the_page_takes_symbols_and_slider_starts_from_the_declarations():
    from browser.view import slider_range, symbol

    assert symbol("omega") == "ω" and symbol("rho") == "ρ" and symbol("k") == "k"
    assert slider_range("b", 1.0)[0] == 0.0           # 0 switches damping off: the slider reaches it
    assert slider_range("k", 40.0)[0] == pytest.approx(4.0)   # k must stay positive: a tenth of it


@pytest.mark.parametrize("line, problem", [
    ('k = "40"   # N/m: spring constant', "k needs a number, like 40.0, not text in quotes"),
    ("k = True   # N/m: spring constant", "k needs a number, like 40.0, not True"),
    ("k = None   # N/m: spring constant", "k needs a number, like 40.0, not None"),
    ("k = (40, 0, 0)   # N/m: spring constant", "k needs a number, like 40.0, not (40, 0, 0)"),
    ("r0 = (0, '-1.5', 0)   # m: start position", "r0 needs three numbers in parentheses"),
    ("r0 = (0, -1.5)   # m: start position", "r0 needs three numbers in parentheses"),
    ("v0 = [0, 0, 0]   # m/s: start velocity", "v0 needs three numbers in parentheses, like (0, -1.5, 0), not [0"),
    ("v0 = None   # m/s: start velocity", "v0 needs three numbers in parentheses, like (0, -1.5, 0), not None"),
])
def test_a_value_that_is_not_a_number_names_the_file_the_line_and_that_a_number_is_expected(line, problem):
    with pytest.raises(ConstantError) as error:
        read_constants(scene_from(BLOCK.format(line=line)))
    message = str(error.value)
    assert message.startswith("scenes/a_teachers_edit.py, line 2: ") and problem in message
    assert "must be from" not in message and len(message.splitlines()) == 1


@pytest.mark.parametrize("line, value", [
    ("b = None   # kg/s: damping (None: critical)", None), ("r0 = None   # m: worked out", None),
    ("count = 13   # 1: springs", 13), ("drive_axis = (1, 0, 0)   # 1: direction", (1, 0, 0)),
])
def test_numbers_vectors_and_none_where_declared_are_read_as_they_are(line, value):
    constants = read_constants(scene_from(BLOCK.format(line=line)))
    assert constants[line.split()[0]].value == value


def without(name: str, source: str) -> str:
    """A scene file's source with the line of one constant taken out."""
    return "".join(line for line in source.splitlines(True) if not line.startswith(f"{name} = "))


def vertical_without(name: str) -> str:
    """scenes/vertical.py without one constant's line, its imports made absolute (for scene_from)."""
    return without(name, (ROOT / "scenes" / "vertical.py").read_text().replace("from ._", "from scenes._"))


def integrators_with(line: str) -> str:
    source = (ROOT / "scenes" / "integrators.py").read_text().replace("from ._", "from scenes._")
    return source.replace("# ---- end of constants ----", f"{line}\n# ---- end of constants ----")


@pytest.mark.parametrize("source, problem", [
    (vertical_without("m"), "the constants block has no line for m (build needs it); "
                            "add one like `m = value  # kg: meaning`"),
    (vertical_without("r0"), "the constants block has no line for r0 (build needs it)"),
    (integrators_with("b = 1.0   # kg/s: damping"), "the constants block has a line for b, which build does not take"),
])
def test_a_constants_block_that_does_not_fit_build_is_named_before_anything_runs(source, problem):
    """vertical's build(**constants) hands them to build_single_mass: what that needs is needed."""
    module = scene_from(source)
    with pytest.raises(ConstantError) as error:
        catalog.check_build(module, read_constants(module))
    assert str(error.value).startswith(f"scenes/a_teachers_edit.py: {problem}")


def test_a_single_mass_scene_without_a_line_for_a_force_constant_has_that_force_off():
    """Single-mass scenes take the forces' constants from the forces: b left out of vertical's block
    takes its declared default, 0, which switches damping off (physics/forces/: Declared.default)."""
    module = scene_from(vertical_without("b"))
    constants = read_constants(module)
    catalog.check_build(module, constants)
    offered = catalog.force_constants(module, constants)
    assert offered["b"].value == 0.0 and offered["b"].unit == "kg/s"
    values = {**{name: c.value for name, c in offered.items()}, **{name: c.value for name, c in constants.items()}}
    labels = [force.LABEL for force in module.build(**values).forces]
    assert labels == ["spring", "gravity"]
    with_b = module.build(**{**values, "b": 2.0}).forces
    assert [force.LABEL for force in with_b] == ["spring", "gravity", "damping"]


def test_every_scene_has_a_line_for_each_constant_its_build_needs_and_no_other():
    for name in SCENE_NAMES:
        module = load(name)
        catalog.check_build(module, read_constants(module))


def main_py(*args, cwd=ROOT, scenes_folder=None) -> subprocess.CompletedProcess:
    env = {**os.environ, "SPRING_SCENES": str(scenes_folder or "")}
    return subprocess.run([sys.executable, *args], cwd=cwd, env=env, capture_output=True, text=True, timeout=60)


def one_error_line(done) -> str:
    assert "Traceback" not in done.stderr + done.stdout
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), done.stderr
    return lines[0]


def test_a_typo_in_one_scene_file_is_one_line_naming_it_and_the_other_scenes_still_run(tmp_path):
    """D-1: `b = 1.0.` in scenes/damped.py used to break every command with a SyntaxError traceback."""
    project = tmp_path / "project"
    for part in ("physics", "scenes", "export", "lab", "reports", "browser", "cli"):
        shutil.copytree(ROOT / part, project / part, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "main.py", project)
    damped = project / "scenes" / "damped.py"
    lines = damped.read_text().splitlines(True)
    number = next(n for n, line in enumerate(lines, start=1) if line.startswith("b = "))
    lines[number - 1] = lines[number - 1].replace("b = 1.0", "b = 1.0.", 1)
    damped.write_text("".join(lines))

    broken = main_py("main.py", "damped", "--headless", cwd=project)
    assert broken.returncode == 2 and broken.stdout == ""
    assert one_error_line(broken).startswith(f"error: scenes/damped.py, line {number}: invalid syntax (got: b = 1.0.")
    assert main_py("main.py", "vertical", "--headless", cwd=project).returncode == 0
    listed = main_py("main.py", "--list", cwd=project)
    assert listed.returncode == 2
    assert one_error_line(listed).startswith(f"error: scenes/damped.py, line {number}: invalid syntax")
    names = [line.split()[0] for line in listed.stdout.splitlines() if line.strip() and not line.startswith(" ")]
    assert "vertical" in names and "driven" in names and "damped" not in names
    assert main_py("-c", "import main", cwd=project).returncode == 0


def test_a_broken_file_in_a_teachers_folder_is_one_line_naming_it_and_the_other_scenes_still_run(tmp_path):
    """D-1 with SPRING_SCENES: a scene that fails as it runs (a NameError) is named with its line
    when it is asked for; --list reads the files as text without running them (issue 20), so it
    lists it."""
    (tmp_path / "oops.py").write_text('"""A scene with a typo."""\nm = 10.0   # kg: mass\nk = fourty   # N/m: spring\n'
                                      '\n\ndef build(**constants):\n    pass\n')
    (tmp_path / "plain.py").write_text((ROOT / "scenes" / "vertical.py").read_text().split('"""', 2)[2])
    listed = main_py("main.py", "--list", scenes_folder=tmp_path)
    assert listed.returncode == 0 and "vertical" in listed.stdout and "A scene with a typo." in listed.stdout
    assert "plain" in listed.stdout   # a scene without a docstring is listed with no description
    message = f"error: {tmp_path / 'oops.py'}, line 3: NameError: name 'fourty' is not defined (got: k = fourty"
    run = main_py("main.py", "oops", "--headless", scenes_folder=tmp_path)
    assert run.returncode == 2 and one_error_line(run).startswith(message)
    assert main_py("main.py", "vertical", "--headless", scenes_folder=tmp_path).returncode == 0
    assert main_py("-c", "import main", scenes_folder=tmp_path).returncode == 0


K_LINE = next(number for number, line in enumerate((ROOT / "scenes" / "vertical.py").read_text().splitlines(), 1)
              if line.startswith("k = 40.0 "))


@pytest.mark.parametrize("edit, expected", [
    (lambda source: without("m", source), "novel.py: the constants block has no line for m (build needs it)"),
    (lambda source: source.replace("k = 40.0 ", 'k = "40" '), f"novel.py, line {K_LINE}: k needs a number"),
])
def test_a_teachers_constants_block_that_does_not_fit_is_one_line_naming_the_file(tmp_path, edit, expected):
    """D-2: these used to be `unexpected TypeError` (exit 1) and `k must be from 0 to 1e6 N/m (got 40 N/m)`."""
    (tmp_path / "novel.py").write_text(edit((ROOT / "scenes" / "vertical.py").read_text()))
    done = main_py("main.py", "novel", "--headless", scenes_folder=tmp_path)
    assert done.returncode == 2 and done.stdout == ""
    assert one_error_line(done).startswith(f"error: {tmp_path}{os.sep}{expected}")


def test_a_scene_file_saved_as_latin_1_names_the_line_that_is_not_utf_8(tmp_path):
    """Python runs it (the é is in a comment), but its text cannot be read: this used to be
    `unexpected OSError: could not get source code`."""
    (tmp_path / "novel.py").write_bytes('"""Une masse."""\nm = 10.0   # kg: masse du bloc (é)\n\n\n'
                                        'def build(**constants):\n    pass\n'.encode("latin-1"))
    done = main_py("main.py", "novel", "--constants", scenes_folder=tmp_path)
    assert done.returncode == 2
    assert one_error_line(done) == (f"error: {tmp_path}{os.sep}novel.py, line 2: the file is not UTF-8 text "
                                    f"(byte 0xe9); save it as UTF-8")


def test_a_value_out_of_its_range_in_the_file_names_the_file_and_the_line():
    """`k = -40` in a teacher's edit: the range message, with where to mend it."""
    with pytest.raises(ConstantError) as error:
        read_constants(scene_from(BLOCK.format(line="k = -40.0   # N/m: spring constant")))
    assert str(error.value) == "scenes/a_teachers_edit.py, line 2: k must be from 0 to 1e6 N/m (got -40 N/m)"

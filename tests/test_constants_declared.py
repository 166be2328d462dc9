"""Each constant is declared once (scenes/_constants.py), and a scene's constants block is read strictly.

The declaration carries what every scene shares: unit, symbol, vector or not, the values allowed,
where a slider starts. The scene file keeps the readable line a teacher edits; its unit must agree
with the declaration, and a line that is not `name = value  # unit: meaning` names its file and line.
"""
import types

import pytest

from scenes import DECLARED, SCENE_NAMES, ConstantError, load, read_constants


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

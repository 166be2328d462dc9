"""Issue 16, items 4 and 8: the command line's reports split by job, each check made once.

- A scene's hooks (VIEW, measure_window, extra_json, extra_text, view_graph) are read from its
  file once, into Setup.hooks; a hook that is not a function is one error naming the file.
- A headless run's cost is checked once, and Δt judged once, before the run.
- JSON numbers are cleaned to 15 digits as whole arrays, bit for bit as clean() cleans each one,
  and a non-finite number is still null with a note naming its place.

(The 450-line cap on main.py, reports/ and cli/ is retired by issue 26: modules are split by job,
never to fit a line count.)
"""
import json
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import main
from export.number_blocks import SHORTEST_BLOCK, clean_array, float_block
from export.numbers import clean
from scenes import ConstantError, Setup, catalog

ROOT = Path(__file__).resolve().parent.parent


# ---- the scene's hooks, read once ----

def test_a_scene_s_hooks_are_read_from_its_file_once():
    setup = catalog.configure("resonance")
    module = setup.module
    assert setup.hooks.view is module.VIEW
    assert setup.hooks.measure_window is module.measure_window
    assert setup.hooks.extra_json is module.extra_json and setup.hooks.extra_text is module.extra_text
    assert setup.hooks.view_graph is module.view_graph
    assert setup.with_values(until=60.0).hooks is setup.hooks     # carried over, not read again
    settle, periods, omega_min = (setup.values[name] for name in ("settle", "periods", "omega_min"))
    assert setup.hooks.measuring(setup.values) == pytest.approx((settle, settle + periods * 2 * math.pi / omega_min))


def test_a_scene_without_hooks_has_none():
    hooks = catalog.configure("vertical").hooks
    assert hooks.measure_window is hooks.extra_json is hooks.extra_text is hooks.view_graph is None
    assert hooks.measuring({}) is None and hooks.view["plot"] == "y"


@pytest.mark.parametrize("name", ["extra_json", "measure_window", "extra_text", "view_graph"])
def test_a_hook_that_is_not_a_function_is_one_error_naming_the_file(name):
    module = SimpleNamespace(__file__=str(ROOT / "scenes" / "mine.py"), build=lambda: None, VIEW={}, **{name: 3.0})
    with pytest.raises(ConstantError, match=rf"mine\.py: {name} must be a function"):
        Setup("mine", module, {}, {})


def test_a_view_that_is_not_a_dict_is_one_error_naming_the_file():
    module = SimpleNamespace(__file__=str(ROOT / "scenes" / "mine.py"), build=lambda: None, VIEW=["y"])
    with pytest.raises(ConstantError, match=r"mine\.py: VIEW must be a dict"):
        Setup("mine", module, {}, {})


def test_the_json_report_calls_the_hook_setup_holds(capsys):
    """The hooks come from Setup.hooks: a scene's extra_json added after configuring is not probed for."""
    from reports import headless, json_report

    setup = catalog.configure("vertical")
    setup.module.extra_json = lambda result: {"probed": True}   # too late: the hooks were read
    try:
        out = json_report.as_json(headless.simulate(setup, progress=None))
    finally:
        del setup.module.extra_json
    assert "probed" not in out


# ---- each check once ----

def count_calls(monkeypatch, owner, name):
    calls = []
    real = getattr(owner, name)

    def counted(*args, **kwargs):
        calls.append(name)
        return real(*args, **kwargs)
    monkeypatch.setattr(owner, name, counted)
    return calls


def test_the_run_s_cost_is_checked_once(monkeypatch, tmp_path, capsys):
    from reports import headless

    calls = count_calls(monkeypatch, headless, "check_cost")
    assert main.main(["vertical", "--headless", "--csv", str(tmp_path / "run.csv")]) == 0
    assert calls == ["check_cost"]
    assert (tmp_path / "run.csv").read_text().startswith("t,x,y,z,")


def test_a_too_long_run_is_refused_before_the_step_table_prints(capsys):
    """--steps with --csv: the run is checked before the table prints, so nothing is half done."""
    status = main.main(["vertical", "--steps", "2", "--headless", "--csv", "-", "--until", "1e9"])
    captured = capsys.readouterr()
    assert status == 2 and captured.out == ""
    assert captured.err.startswith("error: ") and "--until" in captured.err


def test_dt_is_judged_once(monkeypatch):
    """One judgement (physics.accuracy.judge_dt) gives stability and accuracy; it is not judged again."""
    from reports import headless

    judgements = count_calls(monkeypatch, headless, "judge_dt")
    stability_alone = count_calls(monkeypatch, headless, "judge")
    model = catalog.configure("vertical", assignments=["dt=0.3"]).build()
    warning = headless.stability_warning(model, model.methods())
    assert warning.startswith("warning: Δt = 0.3 s is stable but inaccurate")
    assert judgements == ["judge_dt"] and stability_alone == []


def test_the_masses_expected_to_run_away_are_judged_on_their_own():
    """integrators: euler grows at every Δt beside the others; the others are judged without it."""
    from physics.simulate import BlowUpError
    from reports import headless

    model = catalog.configure("integrators").build()
    assert "euler is unstable on a spring at every dt" in headless.stability_warning(model, model.methods())
    big = catalog.configure("integrators", assignments=["dt=0.41"]).build()  # past euler-cromer's 0.4 s
    with pytest.raises(BlowUpError, match="euler-cromer"):
        headless.stability_warning(big, big.methods())


# ---- JSON numbers, cleaned as arrays ----

def same_bits(a, b) -> bool:
    return np.array_equal(np.asarray(a, dtype=float).view(np.int64), np.asarray(b, dtype=float).view(np.int64))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=1, max_size=200))
def test_clean_array_is_clean_bit_for_bit(values):
    """Finite numbers as clean() gives them; inf and nan kept as they are (to_json makes them null)."""
    assert same_bits(clean_array(values), [clean(x) if math.isfinite(x) else x for x in values])


@pytest.mark.parametrize("scale", [1.0, 1e-3, 1e-7, 1e-12, 1e7, 1e14, 1e15, 1e22, 1e300])
def test_clean_array_is_clean_bit_for_bit_at_every_size(scale):
    values = np.random.default_rng(7).normal(size=20_000) * scale
    assert same_bits(clean_array(values), [clean(x) for x in values.tolist()])


def test_clean_array_breaks_ties_as_the_decimal_text_does():
    """x·10^s exactly halfway between two 15-digit numbers: half to even, as '%.15g' rounds."""
    k = np.random.default_rng(3).integers(10**12, 10**14, 20_000).astype(float)
    ties = np.concatenate([k + 0.5, -(k + 0.5), k / 4 + 0.125, k + 0.25, k + 0.75, k / 8 + 1 / 16])
    assert same_bits(clean_array(ties), [clean(x) for x in ties.tolist()])
    assert clean_array([123456789012345.5, 123456789012344.5]).tolist() == [123456789012346.0, 123456789012344.0]
    assert clean_array([0.1 + 0.2, -7.800000000000001, -0.0]).tolist() == [0.3, -7.8, -0.0]


def test_float_block_takes_only_long_lists_of_floats():
    long = [0.5] * SHORTEST_BLOCK
    assert float_block(long).shape == (SHORTEST_BLOCK,)
    assert float_block([[0.5, 1.5]] * SHORTEST_BLOCK).shape == (SHORTEST_BLOCK, 2)
    for not_a_block in (long[:-1], long[:-1] + [1], long[:-1] + [None], [[0.5]] * SHORTEST_BLOCK + [[0.5, 1.0]], []):
        assert float_block(not_a_block) is None


def test_a_long_list_with_a_non_finite_number_is_null_there_with_a_note():
    from export.step_update import cleaned
    from reports.json_report import to_json

    values = [0.1 + 0.2] * 50
    values[7], rows = math.inf, [[1.0, 2.0, math.nan]] * 20
    out = json.loads(to_json(cleaned({"a": values, "rows": rows, "n": [1] * 40})))
    assert out["a"][7] is None and out["a"][6] == 0.3 and out["rows"][19] == [1.0, 2.0, None]
    assert out["n"] == [1] * 40                       # whole numbers stay whole
    assert [note.split(":")[0] for note in out["notes"]] == ["a[7]"] + [f"rows[{i}][2]" for i in range(20)]


"""The step table (`python main.py SCENE --steps N`): the first momentum updates, checked against
the arithmetic a student does by hand for the page's Simple and Middling Examples.

    F_net = k(|y| − L0) − m g − b v_y          (spring up, gravity down, damping against v)
    p_f = p_i + F_net Δt,   v_f = p_f / m,   y_f = y_i + v_f Δt
"""
from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

m, k, L0, g, dt = 10.0, 40.0, 1.0, 9.8, 0.1
VECTOR = re.compile(r"<\s*([^<>]*?)\s*>")


def cli(*args) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "main.py", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=60)


def by_hand(*, b: float, steps: int = 2):
    """The page's update written out for y alone, from rest at y = −1.5 m: rows of (t, F, p, v, y)."""
    y, p, t, rows = -1.5, 0.0, 0.0, []
    for _ in range(steps):
        F = k * (-y - L0) - m * g - b * (p / m)
        p = p + F * dt
        y = y + (p / m) * dt
        t = t + dt
        rows.append((t, F, p, p / m, y))
    return rows


def table_rows(text: str):
    """The table's data rows as (step, t, F_net, p_f, v_f, r_f) with vectors as float lists."""
    rows = []
    for line in text.splitlines():
        if not re.match(r"^\d+\s", line):
            continue
        vectors = [[float(x) for x in group.split(",")] for group in VECTOR.findall(line)]
        step, t = line.split()[:2]
        rows.append((int(step), float(t), *vectors))
    return rows


def test_hand_arithmetic_is_the_page_numbers():
    # The Simple Example as the page works it: −78 N then −74.88 N, ending at y = −1.73088 m.
    (_, F1, p1, v1, y1), (_, F2, p2, v2, y2) = by_hand(b=0.0)
    assert (F1, p1, y1) == pytest.approx((-78.0, -7.8, -1.578))
    assert (F2, p2, v2, y2) == pytest.approx((-74.88, -15.288, -1.5288, -1.73088))


@pytest.mark.parametrize("scene, b", [("vertical", 0.0), ("damped", 1.0)])
def test_two_steps_match_hand_arithmetic(scene, b):
    done = cli(scene, "--steps", "2")
    assert done.returncode == 0, done.stderr
    header = next(line for line in done.stdout.splitlines() if line.startswith("step"))
    for column in ("t (s)", "F_net (N)", "p_f (kg·m/s)", "v_f (m/s)", "r_f (m)"):
        assert column in header
    assert "F(t_i, r_i, v_i)" in done.stdout  # says which force the p update used
    rows = table_rows(done.stdout)
    assert len(rows) == 2
    for (step, t, F_net, p_f, v_f, r_f), (t_hand, F, p, v, y) in zip(rows, by_hand(b=b)):
        assert t == pytest.approx(t_hand)
        assert F_net == pytest.approx([0, F, 0], abs=1e-9)
        assert p_f == pytest.approx([0, p, 0], abs=1e-9)
        assert v_f == pytest.approx([0, v, 0], abs=1e-9)
        assert r_f == pytest.approx([0, y, 0], abs=1e-9)
    if b:
        assert rows[1][2][1] == pytest.approx(-74.1)  # 23.12 N − 98 N + 0.78 N of damping


@pytest.mark.parametrize("integrator", ["verlet", "rk4"])
def test_json_table_obeys_the_momentum_update_for_other_methods(integrator):
    # For every method, F_net is the force the p update used: p_f = p_i + F_net Δt on every row.
    done = cli("driven", "--headless", "--json", "--steps", "3", "--scenario", "3", "--integrator", integrator)
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    assert out["integrator"] == integrator and out["units"]["F_net"] == "N"
    rows = out["step_table"]
    assert "rows" not in out and out["steps"] == 3
    assert [row["step"] for row in rows] == [1, 2, 3]
    dt_driven = out["dt"]
    p_i = out["start"]["p"][0]
    for row in rows:
        assert row["p_f"] == pytest.approx([p + F * dt_driven for p, F in zip(p_i, row["F_net"])])
        assert row["v_f"] == pytest.approx([p / out["m"][0] for p in row["p_f"]])
        p_i = row["p_f"]


def test_multi_mass_table_has_a_row_per_body_per_step():
    from reports import step_table
    from tests.test_cli import two_hanging_masses

    table = step_table.step_table(two_hanging_masses(), steps=2)
    assert [(row["step"], row["body"]) for row in table["rows"]] == \
        [(1, "left"), (1, "right"), (2, "left"), (2, "right")]
    text = step_table.format_step_table(table)
    header = next(line for line in text.splitlines() if line.startswith("step"))
    assert header.split()[:2] == ["step", "body"]
    assert sum(bool(re.match(r"^\d+\s+(left|right)\s", line)) for line in text.splitlines()) == 4
    (_, F1, *_), (_, F2, p2, v2, y2) = by_hand(b=0.0)
    right = table["rows"][3]
    assert right["F_net"] == pytest.approx([0, F2, 0]) and right["r_f"] == pytest.approx([1, y2, 0])


def test_the_table_is_for_hand_checking_and_refuses_a_huge_one_in_one_line():
    from reports import step_table
    from scenes import ConstantError
    from tests.test_cli import two_hanging_masses

    # Two masses: each step is two rows, so MAX_TABLE_ROWS / 2 steps fit and one more does not.
    steps = step_table.MAX_TABLE_ROWS // 2
    assert len(step_table.step_table(two_hanging_masses(), steps=steps)["rows"]) == 2 * steps
    with pytest.raises(ConstantError) as refused:
        step_table.step_table(two_hanging_masses(), steps=steps + 1)
    message = str(refused.value)
    assert "\n" not in message and f"of 2 masses, {2 * (steps + 1):,} rows" in message
    assert "--csv" in message

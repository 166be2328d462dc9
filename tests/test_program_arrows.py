"""The handed-out program's p and F_net arrows (export/program_arrows.py), run under the stand-in
vpython of tests/test_export.py: the page's colours and scales, and at the end of the run each arrow
is scale × the program's own final p and F_net, parallel to the engine's."""
from __future__ import annotations

import numpy as np
import pytest

from export.arrows import choose_scales
from export.palette import ARROW_COLOURS
from physics.forces import net_force
from physics.state import velocity
from reports import headless
from scenes import catalog
from test_export import final_state, main_py, run_program, stand_in  # noqa: F401 (stand_in is a fixture)


@pytest.mark.parametrize("args", [("vertical",), ("damped", "--set", "until=3"), ("pendulum", "--set", "until=2"),
                                  ("driven", "--scenario", "3", "--integrator", "rk4", "--set", "until=4"),
                                  ("regimes", "--arrows", "p,F_net", "--set", "until=2")])
def test_the_programs_arrows_end_on_the_final_p_and_F_net(args, stand_in, tmp_path):  # noqa: F811
    scene, rest = args[0], args[1:]
    assignments = [rest[n + 1] for n in range(len(rest)) if rest[n] == "--set"]
    scenario = int(rest[rest.index("--scenario") + 1]) if "--scenario" in rest else None
    integrator = rest[rest.index("--integrator") + 1] if "--integrator" in rest else None
    setup = catalog.configure(scene, assignments=assignments, scenario=scenario)
    path = tmp_path / "program.py"   # ending at the question time, as the headless run below does
    done = main_py(*args, "--vpython", str(path), "--until", repr(setup.values["until"]))
    assert done.returncode == 0, done.stderr
    drawn = []
    run_program(path, stand_in, drawn)
    t_end, r_end, p_end = final_state(drawn)   # the program's own, to every digit
    answers = [(t_end, r, p) for r, p in zip(r_end, p_end)]
    model = setup.build()
    scales = choose_scales(model, integrator=integrator)
    result = headless.simulate(setup, model=model, integrator=integrator, every_step=True, progress=None)
    traj = result.trajectory
    p, r = traj.p[-1], traj.r[-1]
    F = net_force(model.forces, traj.t[-1], r, velocity(p, traj.m), traj.m)
    # the force the page's update used in the last step: F(t_i, r_i, v_i) at its start
    F_last = net_force(model.forces, traj.t[-2], traj.r[-2], velocity(traj.p[-2], traj.m), traj.m)
    arrows = [shown for shown in drawn if shown["kind"] == "arrow"]
    count = model.state.count
    p_arrows, F_arrows = arrows[:count], arrows[count:]
    assert len(F_arrows) == count
    for i in range(count):
        assert p_arrows[i]["color"] == pytest.approx(list(ARROW_COLOURS["p"]))
        assert F_arrows[i]["color"] == pytest.approx(list(ARROW_COLOURS["F_net"]))
        assert np.allclose(p_arrows[i]["pos"], answers[i][1], rtol=1e-5, atol=1e-9)
        # p: exactly the program's final p (which is the engine's) at the page's scale
        assert np.allclose(p_arrows[i]["axis"], answers[i][2] / scales.p_unit, rtol=1e-5, atol=1e-9)
        assert np.allclose(np.array(p_arrows[i]["axis"]) * scales.p_unit, p[i], rtol=1e-5, atol=1e-6)
        # F_net: the force of the last update, parallel to the engine's final F_net
        axis = np.array(F_arrows[i]["axis"])
        cosine = axis @ F[i] / (np.linalg.norm(axis) * np.linalg.norm(F[i]))
        assert cosine > 0.99, (i, axis, F[i])
        if result.methods[i] == "euler-cromer":   # exactly the force of the last update
            assert np.allclose(axis * scales.F_unit, F_last[i], rtol=1e-6, atol=1e-9)
        else:                                     # rk4: its last slope's force, near the final one
            assert np.linalg.norm(axis) * scales.F_unit == pytest.approx(np.linalg.norm(F[i]), rel=0.1)
    text = path.read_text()
    assert f"pscale = 1/{scales.p_unit:g}" in text and f"{scales.p_unit:g} kg·m/s" in text
    assert f"Fscale = 1/{scales.F_unit:g}" in text


def test_no_arrows_writes_none(stand_in, tmp_path):  # noqa: F811
    path = tmp_path / "program.py"
    assert main_py("vertical", "--no-arrows", "--vpython", str(path)).returncode == 0
    drawn = []
    run_program(path, stand_in, drawn)
    assert not [shown for shown in drawn if shown["kind"] == "arrow"] and "arrow" not in path.read_text()

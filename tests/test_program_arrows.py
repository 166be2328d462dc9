"""The handed-out program's arrows (export/program_arrows.py), run under the stand-in vpython of
tests/test_export.py: the page's colours and scales, and at the end of the run each arrow is
scale × the program's own final p and F_net, parallel to the engine's; each force tip to tail
ends at F_net's tip, and F∥ + F⊥ = F_net with F⊥ across p."""
from __future__ import annotations

import numpy as np
import pytest

from export.arrows import SEE_THROUGH, choose_scales
from scenes._view import DEFAULT_VIEW
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
    scales = choose_scales(model, view={**DEFAULT_VIEW, **setup.hooks.view}, integrator=integrator)
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
    # the balls see-through, as on the page, so an arrow shorter than the radius is not hidden
    balls = [shown for shown in drawn if shown["kind"] == "sphere"]
    assert len(balls) == count and all(ball.get("opacity") == SEE_THROUGH for ball in balls), balls
    text = path.read_text()
    assert f"pscale = 1/{scales.p_unit:g}" in text and f"{scales.p_unit:g} kg·m/s" in text
    assert f"Fscale = 1/{scales.F_unit:g}" in text


def test_no_arrows_writes_none(stand_in, tmp_path):  # noqa: F811
    path = tmp_path / "program.py"
    assert main_py("vertical", "--no-arrows", "--vpython", str(path)).returncode == 0
    drawn = []
    run_program(path, stand_in, drawn)
    assert not [shown for shown in drawn if shown["kind"] == "arrow"] and "arrow" not in path.read_text()
    assert all("opacity" not in shown for shown in drawn if shown["kind"] == "sphere")   # solid, as on the page


@pytest.mark.parametrize("args", [("vertical", "--set", "until=3"), ("pendulum", "--set", "until=2"),
                                  ("regimes", "--set", "until=2"),
                                  ("driven", "--scenario", "3", "--integrator", "rk4", "--set", "until=4")])
def test_the_programs_forces_and_split_arrows_are_the_pages(args, stand_in, tmp_path):  # noqa: F811
    """`--arrows forces,split`: the program draws each force on its own thin grey arrow, tip to tail,
    ending at F_net's tip, named beside its middle, and F∥ (sky blue) and F⊥ (white), each
    labelled at its tip with its size in N, in the page's colours and at the page's force scale;
    at the end F⊥ is across the final p, F∥ + F⊥ = F_net, and each force is the engine's force of
    the last update (euler-cromer) at that scale."""
    from export.arrows import force_name, forces_each, split

    path = tmp_path / "program.py"
    web = tmp_path / "web.py"
    rest = args[1:]
    setup = catalog.configure(args[0], assignments=[rest[n + 1] for n in range(len(rest)) if rest[n] == "--set"],
                              scenario=int(rest[rest.index("--scenario") + 1]) if "--scenario" in rest else None)
    done = main_py(*args, "--arrows", "p,F_net,forces,split", "--vpython", str(path), "--webvpython", str(web),
                   "--until", repr(setup.values["until"]))   # ending at the question time, as the engine's run below
    assert done.returncode == 0, done.stderr
    drawn = []
    run_program(path, stand_in, drawn)
    t_end, r_end, p_end = final_state(drawn)   # the program's own, to every digit
    answers = [(t_end, r, p) for r, p in zip(r_end, p_end)]
    integrator = rest[rest.index("--integrator") + 1] if "--integrator" in rest else None
    model = setup.build()
    scales = choose_scales(model, view={**DEFAULT_VIEW, **setup.hooks.view}, integrator=integrator,
                           forces=True)   # each force drawn: the page's scale with them on
    traj = headless.simulate(setup, model=model, integrator=integrator, every_step=True, progress=None).trajectory
    m, count, kinds = traj.m, model.state.count, len(model.forces)
    each_last = forces_each(model.forces, traj.t[-2], traj.r[-2], velocity(traj.p[-2], m), m)
    along, across = split(net_force(model.forces, traj.t[-1], traj.r[-1], velocity(traj.p[-1], m), m), traj.p[-1])

    def arrows(kind):
        return [shown for shown in drawn
                if shown["kind"] == "arrow" and shown["color"] == pytest.approx(list(ARROW_COLOURS[kind]))]
    F_arrows, force_arrows = arrows("F_net"), arrows("forces")
    par, perp = arrows("F_par"), arrows("F_perp")
    labels = {kind: [shown for shown in drawn if shown["kind"] == "label"
                     and shown["color"] == pytest.approx(list(ARROW_COLOURS[kind]))]
              for kind in ("forces", "F_par", "F_perp")}
    assert [len(labels[kind]) for kind in labels] == [count * kinds, count, count]
    assert len(F_arrows) == len(par) == len(perp) == count and len(force_arrows) == count * kinds
    for i in range(count):
        r, p = answers[i][1], answers[i][2]
        F = np.array(F_arrows[i]["axis"])
        mine = force_arrows[i * kinds:(i + 1) * kinds]
        assert np.allclose(mine[0]["pos"], r, atol=1e-9)
        for a, b in zip(mine, mine[1:]):   # tip to tail
            assert np.allclose(np.array(a["pos"]) + a["axis"], b["pos"], atol=1e-9)
        assert np.allclose(np.array(mine[-1]["pos"]) + mine[-1]["axis"], r + F, atol=1e-9)   # ends at F_net's tip
        names = labels["forces"][i * kinds:(i + 1) * kinds]   # each force named, as on the page, beside its middle
        assert [label["text"] for label in names] == [force_name(force) for force in model.forces]
        for n, (label, a) in enumerate(zip(names, mine)):
            assert np.allclose(label["pos"], np.array(a["pos"]) + 0.5 * np.array(a["axis"]), atol=1e-9)
            assert label["height"] >= 18 and label["box"] is False
            # every other name on the left: a hanging mass's spring and gravity lie along one line
            assert (label["xoffset"] < 0, label["align"]) == ((True, "right") if n % 2 else (False, "left"))
        assert all(a["shaftwidth"] < F_arrows[i]["shaftwidth"] for a in mine)               # thin, as on the page
        if integrator is None:   # euler-cromer: each force of the last update, at the page's scale
            for n in range(kinds):
                assert np.allclose(np.array(mine[n]["axis"]) * scales.F_unit, each_last[n][i], rtol=1e-6, atol=1e-9)
        F_par, F_perp = np.array(par[i]["axis"]), np.array(perp[i]["axis"])
        assert np.allclose(par[i]["pos"], r) and np.allclose(perp[i]["pos"], r)
        assert np.allclose(F_par + F_perp, F, atol=1e-12)
        assert abs(F_perp @ p) <= 1e-9 * max(1.0, np.linalg.norm(F_perp) * np.linalg.norm(p))   # across p
        assert abs(F_par @ p) == pytest.approx(np.linalg.norm(F_par) * np.linalg.norm(p), rel=1e-9)  # along p
        for label, part, symbol in ((labels["F_par"][i], F_par, "F∥"), (labels["F_perp"][i], F_perp, "F⊥")):
            assert np.allclose(label["pos"], r + part, atol=1e-9) and label["height"] >= 18   # at its tip
            assert label["text"] == f"{symbol} = {np.linalg.norm(part) * scales.F_unit:.2f} N"
        assert labels["F_perp"][i]["yoffset"] < 0 < labels["F_par"][i]["yoffset"]   # short ones apart
        # parallel to the engine's own split of the final F_net along the final p
        for drawn_part, engine_part in ((F_par, along[i]), (F_perp, across[i])):
            size = np.linalg.norm(engine_part) / scales.F_unit
            if size > 0.05 * np.linalg.norm(F):
                assert drawn_part @ engine_part / scales.F_unit > 0.98 * np.linalg.norm(drawn_part) * size
    # the Web VPython program: what GlowScript 3.2 reads, an if statement, not a conditional
    # expression; no f-strings
    code = [line.split("#")[0] for line in web.read_text().splitlines()]
    assert code[0].startswith("Web VPython 3.2") and ".axis = Fscale*Fpar" in web.read_text()
    assert '.text = "F∥ = {:.2f} N".format(mag(Fpar))' in web.read_text()   # str.format, as the answer's print
    assert "Fpar = dot(Fnet, phat)*phat" in [line.strip() for line in code]
    assert all(line.strip().startswith("if ") for line in code if " if " in f" {line.strip()} ")
    assert not any('f"' in line or "f'" in line for line in code)


def test_web_vpythons_own_format_writes_the_split_labels_alike(tmp_path):
    """The F∥ and F⊥ labels are written with "F∥ = {:.2f} N".format(mag(Fpar)): Web VPython runs
    str.format with its own code (String.prototype.format in glow.min.js, which vpython ships).
    Run under node, it writes a pendulum run's |F∥| and |F⊥| (0.001 N to 20 N) as Python does,
    and so as the page does. (With '{:.3g}' it wrote 7 of 401 otherwise: 0.3135 as 0.314.)"""
    from export.arrows import PART_DIGITS
    import importlib.util
    import json
    import shutil
    import subprocess
    from pathlib import Path

    from export.arrows import sampled, split

    node = shutil.which("node")
    glow = Path(importlib.util.find_spec("vpython").submodule_search_locations[0]) / "vpython_libraries" / "glow.min.js"
    if node is None or not glow.exists():
        pytest.skip("needs node and vpython's glow.min.js")
    source = glow.read_text(encoding="utf-8")
    start = source.index("String.prototype.format=function")
    end = source.index("function parse_html", start)
    script = tmp_path / "format.js"
    written = "console.log(JSON.stringify(v.map(function (x) { return 'F∥ = %s N'.format(x); })));\n" % PART_DIGITS
    script.write_text("var pow = Math.pow;\n" + source[start:end] + "\nvar v = JSON.parse(process.argv[2]);\n" + written,
                      encoding="utf-8")
    _, p, F = sampled(catalog.configure("pendulum").build())
    along, across = split(F.reshape(-1, 3), p.reshape(-1, 3))
    sizes = [float(x) for x in np.concatenate([np.linalg.norm(along, axis=1), np.linalg.norm(across, axis=1)])]
    sizes = [x for x in sizes if x > 1e-3]
    assert len(sizes) > 200 and max(sizes) > 5
    done = subprocess.run([node, str(script), json.dumps(sizes)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout) == [f"F∥ = {PART_DIGITS} N".format(x) for x in sizes]

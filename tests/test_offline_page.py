"""The offline page's file, without a browser: GlowScript's files pinned and unchanged, their
licences in NOTICE and in every page, the command line's --html (its options applied, its files
protected), the size bound, and which constants a page may change (those whose new value, written
into the constants block, gives the program the writer writes for it).

tests/test_offline_page_browser.py runs the pages in Chromium.
"""
from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

import pytest

from export import offline_page
from export.offline_page import LIBRARIES, MAX_BYTES, _code, page, settable
from export.vpython_program import program
from scenes import catalog
from scenes._view import DEFAULT_VIEW
from test_export import main_py

ROOT = Path(__file__).resolve().parent.parent
GLOWSCRIPT = ROOT / "export" / "glowscript"


def page_data(text: str) -> dict:
    """The data a page's script reads (#offline-data)."""
    found = re.search(r'<script type="application/json" id="offline-data">(.*?)</script>', text, re.S)
    return json.loads(found[1])


@pytest.fixture(scope="module")
def vertical_page(tmp_path_factory) -> str:
    path = tmp_path_factory.mktemp("page") / "vertical.html"
    done = main_py("vertical", "--html", str(path))
    assert done.returncode == 0, done.stderr
    assert done.stderr.strip() == f"wrote {path}"
    return path.read_text(encoding="utf-8")


def test_glowscripts_files_are_the_pinned_ones_and_kept_once():
    """Each vendored file's sha256 is its pin (GlowScriptOffline3.2.zip's file), and the RSrun the
    node test reads is that copy: tests/glowscript/ holds no second one."""
    for name, pinned in LIBRARIES:
        assert hashlib.sha256((GLOWSCRIPT / name).read_bytes()).hexdigest() == pinned, name
    assert sorted(path.name for path in GLOWSCRIPT.glob("*.js")) == sorted(name for name, _ in LIBRARIES)
    assert not (ROOT / "tests" / "glowscript").exists()
    assert "Copyright (C) 2011 by David Scherer and Bruce Sherwood" in (GLOWSCRIPT / "LICENSE.txt").read_text()


def test_a_changed_glowscript_file_is_refused(tmp_path, monkeypatch):
    """A page is never written from a file that is not the pinned one (a bad checkout, an edit)."""
    copy = tmp_path / "glowscript"
    copy.mkdir()
    for name, _ in LIBRARIES:
        (copy / name).write_bytes((GLOWSCRIPT / name).read_bytes())
    (copy / "RSrun.3.2.min.js").write_bytes((GLOWSCRIPT / "RSrun.3.2.min.js").read_bytes() + b"\n")
    monkeypatch.setattr(offline_page, "GLOWSCRIPT", str(copy))
    with pytest.raises(offline_page.ProgramError, match="RSrun.3.2.min.js is not GlowScript 3.2's file"):
        offline_page.library("RSrun.3.2.min.js")


def test_the_notice_and_every_page_carry_the_licences(vertical_page):
    """NOTICE names GlowScript's MIT licence with RapydScript-NG's BSD licence and every library
    bundled in glow.3.2.min.js, with its copyright line; a page carries NOTICE in a comment."""
    notice = (GLOWSCRIPT / "NOTICE").read_text()
    for needed in ("Copyright (C) 2011 by David Scherer and Bruce Sherwood", "Kovid Goyal", "Alexander Tsepkov",
                   "jQuery v1.12.0", "jQuery UI v1.11.4", "plotly.js 1.39.4", "Plotly, Inc", "d3 3.5.17",
                   "Michael Bostock", "mapbox-gl 0.45.0", "Mapbox", "earcut", "Flot 0.7", "Ole Laursen",
                   "jquery.mousewheel 3.1.11", "Brandon Aaron", "poly2tri", "opentype.js", "Frederik De Bleser",
                   "glMatrix", "acorn", "Permission is hereby granted", "Redistribution and use in source",
                   "ISC licence", "zlib licence"):
        assert needed in notice, needed
    comment = vertical_page[vertical_page.index("<!--\nThis file holds GlowScript"):]
    comment = comment[:comment.index("-->")]
    for needed in ("David Scherer and Bruce Sherwood", "Kovid Goyal", "plotly.js 1.39.4", "d3 3.5.17",
                   "mapbox-gl 0.45.0", "earcut", "Flot 0.7", "jquery.mousewheel", "poly2tri", "opentype.js"):
        assert needed in comment, needed


def test_the_page_holds_everything_it_needs_within_the_size_bound(vertical_page):
    """Every GlowScript file is inside whole (no script or style is loaded from elsewhere), the
    program is inside, and the file is at most 7 MB."""
    assert len(vertical_page.encode("utf-8")) <= MAX_BYTES
    for name, _ in LIBRARIES:
        assert (GLOWSCRIPT / name).read_text(encoding="utf-8") in vertical_page, name
    assert not re.search(r"<(script|link|img|iframe)[^>]*\b(src|href)=", vertical_page)
    data = page_data(vertical_page)
    assert data["programs"]["euler-cromer"].startswith("Web VPython 3.2\n")
    assert sorted(data["programs"]) == ["euler", "euler-cromer", "rk4", "verlet"]


def test_the_page_is_written_for_the_options_given(tmp_path):
    """--set, --preset, --integrator and --arrows (and --scenario) are the page's start."""
    path = tmp_path / "moon.html"
    done = main_py("damped", "--preset", "Moon gravity", "--set", "k=55", "--integrator", "rk4",
                   "--arrows", "forces", "--html", str(path))
    assert done.returncode == 0, done.stderr
    text = path.read_text(encoding="utf-8")
    data = page_data(text)
    assert data["integrator"] == "rk4"
    assert data["constants"]["k"]["written"] == 55 and data["constants"]["g"]["written"] == 1.62
    assert "\nk = 55 " in data["programs"]["rk4"] and "\ng = 1.62 " in data["programs"]["rk4"]
    assert 'id="arrow-forces" checked' in text and 'id="arrow-p">' in text
    path = tmp_path / "driven.html"
    assert main_py("driven", "--scenario", "4", "--html", str(path)).returncode == 0
    assert "\nF0 = 2 " in page_data(path.read_text(encoding="utf-8"))["programs"]["euler-cromer"]


def test_no_file_it_did_not_write_is_replaced(tmp_path):
    """An HTML file of someone else's is kept unless --overwrite; its own page is replaced."""
    theirs = tmp_path / "lesson.html"
    theirs.write_text("<html>my lesson</html>")
    done = main_py("vertical", "--html", str(theirs))
    assert done.returncode == 2 and "did not write" in done.stderr and "--overwrite" in done.stderr
    assert theirs.read_text() == "<html>my lesson</html>"
    assert main_py("vertical", "--html", str(theirs), "--overwrite").returncode == 0
    assert theirs.read_text(encoding="utf-8").split("\n")[1].startswith("<!-- Written by the spring-mass simulator;")
    done = main_py("damped", "--html", str(theirs))   # its own page now: replaced without asking
    assert done.returncode == 0, done.stderr
    done = main_py("vertical", "--html", str(tmp_path / "no such folder" / "x.html"))
    assert done.returncode == 2 and "does not exist" in done.stderr


def _changed_program(scene: str, name: str, value: float) -> list[str]:
    setup = catalog.configure(scene)
    return _code(program(setup.with_values(**{name: value}), web=True, arrows=(), page=True, header=False), name)


def test_a_page_offers_a_constant_only_where_its_line_alone_changes():
    """vertical's m, k, L0, g, dt and until can change over their sliders' spans; damped's b down to
    0 (the damping line then adds nothing); a force switched off in the file (pendulum's b), a
    start worked out from a constant (driven's x0) and a label naming a value (regimes' b) cannot."""
    def offered(scene):
        setup = catalog.configure(scene)
        view = {**DEFAULT_VIEW, **setup.hooks.view}
        return {found.name: (found.file_low, found.file_high) for found in settable(setup, view=view)}

    vertical = offered("vertical")
    assert {"m", "k", "L0", "g", "dt", "until"} <= set(vertical)
    assert vertical["k"] == (4.0, 120.0) and vertical["m"] == (1.0, 30.0)
    assert offered("damped")["b"] == (0.0, 3.0)
    assert "b" not in offered("pendulum") and "x0" not in offered("driven") and "b" not in offered("regimes")
    # what "offered" means: the program for a new value is the file's but for the constant's own line
    base = _code(program(catalog.configure("vertical"), web=True, arrows=(), page=True, header=False), "k")
    assert _changed_program("vertical", "k", 100.0) == base
    pendulum = _code(program(catalog.configure("pendulum"), web=True, arrows=(), page=True, header=False), "b")
    assert _changed_program("pendulum", "b", 0.5) != pendulum


def test_the_offline_program_reports_to_the_page_and_finds_the_question_step_itself():
    """The page's program: the controls section after the constants, the report after each update,
    every kind of arrow written, and the question time's step from until and dt as it runs."""
    text = program(catalog.configure("damped"), web=True, page=True)
    lines = text.splitlines()
    controls = next(n for n, line in enumerate(lines) if line.startswith("page = offline_page()"))
    assert lines.index("dt = 0.1                 # s: time step Δt of the momentum update") < controls
    assert controls < lines.index("# ---- the objects ----")
    assert "n_until = ceil(until/dt - 1e-9)" in text and "    if n == n_until:" in text
    assert "page.stepped(0, n + 1, m, Fnet, p, pos, [Fspring, Fgravity, Fdamping])" in text   # each force for the description
    assert '"forces": forcearrows + forcelabels' in text and '"split": [pararrow, perparrow' in text
    handout = program(catalog.configure("damped"), web=True)
    assert "offline_page" not in handout and "n_until" not in handout


def test_page_writes_within_its_size_for_every_scene():
    """Every scene's page, written in process, is under 7 MB and holds a program per method it can use."""
    for scene in catalog.SCENE_NAMES:
        text = page(catalog.configure(scene))
        assert len(text.encode("utf-8")) <= MAX_BYTES, scene
        data = page_data(text)
        assert data["programs"] and all(p.startswith("Web VPython 3.2\n") for p in data["programs"].values())

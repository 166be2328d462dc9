"""physics/, the scenes, export/ and the command line's reports never import vpython.

Creating a vpython object starts a web server and waits for a browser, so a headless run that
imported it by accident could hang a classroom laptop or CI. Each check runs in a fresh Python
process (this test process may already have imported anything), with a timeout.
"""
import subprocess
import sys
from pathlib import Path


ROOT = Path(__file__).resolve().parent.parent
REPORT = "\nprint(sorted(name for name in sys.modules if name.split('.')[0] == 'vpython'))\n"


def modules_loaded_by(code: str) -> str:
    """Run `code` in a fresh interpreter at the project root; the vpython modules it loaded."""
    done = subprocess.run([sys.executable, "-c", "import sys\n" + code + REPORT], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip().splitlines()[-1]


def test_physics_and_every_scene_import_and_build_without_vpython():
    loaded = modules_loaded_by(
        "import physics, physics.energy, physics.exact, physics.forces, physics.integrators\n"
        "import physics.simulate, physics.state, physics.stability, physics.compiled\n"
        "from scenes import catalog\n"
        "for name in catalog.SCENE_NAMES:\n"
        "    catalog.load(name)\n"
        "    catalog.configure(name).build()\n"
        "print('scenes:', catalog.SCENE_NAMES)\n")
    assert loaded == "[]"


def test_the_notebook_module_imports_without_vpython():
    """browser.notebook imports vpython only inside show(), in a running notebook."""
    assert modules_loaded_by("import browser.notebook\n") == "[]"


def test_the_reports_and_export_import_without_vpython():
    assert modules_loaded_by("import reports.headless, reports.plotting, export, export.palette\n") == "[]"


def test_a_headless_command_line_run_does_not_import_vpython():
    loaded = modules_loaded_by(
        "import runpy\n"
        "sys.argv = ['main.py', 'vertical', '--headless']\n"
        "try:\n"
        "    runpy.run_path('main.py', run_name='__main__')\n"
        "except SystemExit as stop:\n"
        "    assert not stop.code, stop.code\n")
    assert loaded == "[]"


def test_the_check_itself_would_see_vpython():
    """A stand-in module named vpython must show up, or the checks above prove nothing. (Importing
    the real vpython would start its server and open a browser.)"""
    assert modules_loaded_by("sys.modules['vpython'] = type(sys)('vpython')\n") == "['vpython']"

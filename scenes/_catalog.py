"""The scenes, their presets, and turning a scene name plus overrides into a ready Model.

A scene is any module in this folder whose name does not start with "_" (those are the shared
builders), plus any in the folders named by the environment variable SPRING_SCENES (separated
like PATH): a teacher's own scenes, kept outside the project. Nothing lists them by hand; a scene
may set MENU_ORDER (a number; lower comes first, default 100) to place itself in --list and in the
page's scene menu. MENU_ORDER is read from the file without running it, and a scene file runs only
when that scene is asked for, so a typo in one file is one error naming its line and leaves the
other scenes usable. --list reads each scene's description and scenarios the same way. A file that
is not a regular file (a named pipe), is bigger than MAX_SCENE_BYTES, has no build function (a
handed-out program) or has a name the package's own code uses is left out, with why (SKIPPED).
Importing a scene module never imports vpython; the browser is separate.

A preset is a named set of constant changes, kept as data: `(label, {name: value})`. The same
list feeds the command line (`--preset NAME`) and the page's preset menu. Every scene offers the
ones that make sense for it:

- "Moon gravity", "Earth gravity", "Jupiter gravity" (g = 1.62, 9.8, 24.79 m/s²), where gravity is
  switched on (a horizontal scene on a table has g = 0 and gets none);
- "critical damping", b = 2√(mk) for the m and k of the moment, where the scene has b and k;
- "scenario N: ..." for each of the scene's numbered SCENARIOS (the page's driven examples). A
  scenario is a whole case, as the book gives it: it sets every constant of the scene, the scene
  file's value where the scenario names none (m and k too, so a slider moved before it does not
  carry over), except how the run is computed (Δt and the question time: `numerical` in
  scenes/_constants.py);
- then the scene's own PRESETS, which may also replace one of the above by using its label.

In a preset, b = None means "critical": :func:`resolve` turns it into 2√(mk) once m and k are known.
"""
from __future__ import annotations

import ast
import difflib
import importlib
import inspect
import linecache
import os
import stat
import sys
import textwrap
import traceback
from dataclasses import dataclass
from pathlib import Path

from physics.exact import critical_damping
from physics.forces import FORCES, declared_constants

from ._hooks import SceneHooks
from ._constants import (DECLARED, END_OF_CONSTANTS, ConstantError, Constant, check_value, parse_assignments,
                         read_constants, shown_path)
from ._model import Model
from ._written import add_written, parse_force_option

DEFAULT_SCENE = "vertical"
EXTRA_FOLDERS = "SPRING_SCENES"   # environment variable: more folders of scenes, like PATH
FOLDERS = [Path(__file__).parent] + [Path(folder).absolute() for folder in
                                     filter(None, os.environ.get(EXTRA_FOLDERS, "").split(os.pathsep))]

# A teacher's folders come after this one in the package's search path, so `import scenes.NAME`
# finds a teacher's scene as it finds ours (ours first when two share a name, as in SCENE_FILES).
sys.modules[__package__].__path__.extend(str(folder) for folder in FOLDERS[1:])


MAX_SCENE_BYTES = 1_000_000   # a scene file is a page of text; a bigger file is not read at all
# Names the scenes package already gives to its own code: a scene file called `catalog.py` would
# replace `scenes.catalog` when it runs (tests/test_adversarial.py checks this list is complete).
RESERVED = {"catalog", "load", "configure", "presets", "resolve", "scenarios", "summary", "find_preset",
            "check_value", "format_value", "parse_assignments", "read_constants", "DECLARED", "Constant",
            "ConstantError", "Model", "Setup", "CRITICAL_DAMPING", "DEFAULT_SCENE", "GRAVITY_PRESETS",
            "SCENE_NAMES"}


def _source(path: Path) -> bytes:
    """A scene file's text, read without running it; OSError if it is not a regular file (a named
    pipe or a link to /dev/stdin would wait for ever), or too big to be a scene."""
    info = os.stat(path)   # follows a link to what it points at
    if not stat.S_ISREG(info.st_mode):
        raise OSError("it is not a regular file, so it was not read")
    if info.st_size > MAX_SCENE_BYTES:
        raise OSError(f"it is {info.st_size:,} bytes, more than a scene file's {MAX_SCENE_BYTES:,}, "
                      f"so it was not read")
    with open(path, "rb") as file:
        return file.read(MAX_SCENE_BYTES + 1)


def _scene_files() -> tuple[dict[str, Path], dict[str, str]]:
    """Every scene's name and file, from the first folder that has a file of that name; and the
    files left out, with why (not a regular file, too big, a name the program's code has taken, or
    a program that is not a scene: it has no build function)."""
    found, skipped = {}, {}
    for folder in FOLDERS:
        for path in sorted(folder.glob("[!_]*.py")):
            if path.stem in found or path.stem in skipped:
                continue
            try:
                tree = _tree(path)
            except OSError as problem:
                skipped[path.stem] = f"{shown_path(path)}: {problem}"
                continue
            except Exception:   # a syntax error: listed, and named when the scene is asked for
                tree = None
            if path.stem in RESERVED:
                skipped[path.stem] = (f"{shown_path(path)}: the name {path.stem!r} is taken by the "
                                      f"simulator's own code (scenes.{path.stem}); rename the file")
            elif tree is not None and not _defines_build(tree):
                skipped[path.stem] = (f"{shown_path(path)} is not a scene: it has no build function "
                                      f"(`def build(**constants):` after the constants block)")
            else:
                found[path.stem] = path
    return found, skipped


_TREES: dict[Path, ast.Module] = {}


def _tree(path: Path) -> ast.Module:
    """The file's syntax tree, read once (never run): OSError or SyntaxError as they come."""
    if path not in _TREES:
        _TREES[path] = ast.parse(_source(path), filename=str(path))
    return _TREES[path]


def _defines_build(tree: ast.Module) -> bool:
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name == "build":
            return True
        if isinstance(node, ast.Assign) and any(getattr(target, "id", None) == "build" for target in node.targets):
            return True
        if isinstance(node, (ast.Import, ast.ImportFrom)) and any(
                (alias.asname or alias.name) == "build" for alias in node.names):
            return True
    return False


def _assigned(tree: ast.Module, name: str):
    """The literal value of the file's last top-level `name = ...`, or None (not there, or not a literal)."""
    value = None
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(target, "id", None) == name for target in node.targets):
            try:
                value = ast.literal_eval(node.value)
            except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
                value = None
    return value


def _menu_order(path: Path):
    """A scene's MENU_ORDER, read from its file without running it: 100 where it sets no number
    (or the file cannot be read at all; load() says why when the scene is asked for)."""
    try:
        order = _assigned(_tree(path), "MENU_ORDER")
    except Exception:  # whatever is in one file, the other scenes stay usable
        return 100
    return order if isinstance(order, (int, float)) and not isinstance(order, bool) else 100


def describe(name: str) -> tuple[str, list[str]]:
    """A scene's one-line description and its scenarios' labels, read from its file without running
    it (--list): ConstantError for an unknown scene or a file that is not valid Python."""
    if name not in SCENE_FILES:
        load(name)   # says why
    path = SCENE_FILES[name]
    try:
        tree = _tree(path)
    except Exception as problem:
        raise ConstantError(_broken_file_message(path, problem)) from None
    doc = ast.get_docstring(tree) or ""
    scenarios = _assigned(tree, "SCENARIOS")
    labels = [item[0] for item in scenarios if isinstance(item, (tuple, list)) and item and
              isinstance(item[0], str)] if isinstance(scenarios, (list, tuple)) else []
    return (doc.strip().splitlines() or [""])[0], labels


SCENE_FILES, SKIPPED = _scene_files()
SCENE_NAMES = sorted(SCENE_FILES, key=lambda name: (_menu_order(SCENE_FILES[name]), name))

GRAVITY_PRESETS = {                # m/s², the strength of gravity at the surface
    "Moon gravity": {"g": 1.62},
    "Earth gravity": {"g": 9.8},
    "Jupiter gravity": {"g": 24.79},
}
CRITICAL_DAMPING = "critical damping"


def load(name: str):
    """The scene module called `name`, run the first time it is asked for.

    Raises ConstantError with the closest name for an unknown scene, and with the file, the line and
    what is wrong for a scene file that cannot run: a typo in one scene leaves the others usable.
    """
    if not name.strip():
        raise ConstantError(f"the scene name is empty: give one, like {DEFAULT_SCENE!r} "
                            f"(run 'python main.py --list' to see them)")
    if name in SKIPPED:
        raise ConstantError(SKIPPED[name])
    if name not in SCENE_NAMES:
        close = difflib.get_close_matches(name, SCENE_NAMES, n=1, cutoff=0.5)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise ConstantError(f"unknown scene {name!r}{hint} (run 'python main.py --list' to see them)")
    try:
        return importlib.import_module(f"{__package__}.{name}")
    except (Exception, SystemExit) as problem:  # anything a scene file can get wrong, from a typo to sys.exit()
        raise ConstantError(_broken_file_message(SCENE_FILES[name], problem)) from None


def _broken_file_message(path: Path, problem: Exception) -> str:
    """`scenes/damped.py, line 13: invalid syntax (got: b = 1.0.)`: where a scene file failed, and why."""
    if isinstance(problem, SyntaxError):
        where, line, what = problem.filename or path, problem.lineno, problem.msg
        text = problem.text or ""
    else:   # the last line of this file that ran: the assignment, call or import that failed
        lines = [frame.lineno for frame in traceback.extract_tb(problem.__traceback__)
                 if os.path.abspath(frame.filename) == os.path.abspath(path)]
        what = (f"{type(problem).__name__}: {problem}" if not isinstance(problem, SystemExit) else
                "it calls sys.exit() (raises SystemExit), which would end the whole program; a scene "
                "file only sets its constants and defines build")
        where, line = path, lines[-1] if lines else None
        text = linecache.getline(str(path), line) if line else ""
    message = f"{shown_path(where)}{f', line {line}' if line else ''}: {what}"
    if text.strip():
        message += f" (got: {text.strip()})"
    return " ".join(message.split())


def _keywords(function) -> tuple[set[str], set[str] | None]:
    """The keyword arguments `function` needs, and all those it takes (None: any at all).

    Where it hands its `**constants` on (`build(**constants)` calling `build_single_mass(**constants)`),
    what the function called needs and takes counts as its own.
    """
    parameters = inspect.signature(function).parameters.values()
    named = {p.name for p in parameters if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)}
    needs = {p.name for p in parameters if p.name in named and p.default is p.empty}
    rest = next((p.name for p in parameters if p.kind is p.VAR_KEYWORD), None)
    if rest is None:
        return needs, named
    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(function)))
    except (OSError, TypeError, SyntaxError):   # no source to read: trust it takes what it is given
        return needs, None
    takes = []
    for call in ast.walk(tree):
        if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name) and any(
                keyword.arg is None and getattr(keyword.value, "id", None) == rest for keyword in call.keywords)):
            continue
        callee = function.__globals__.get(call.func.id)
        if not inspect.isfunction(callee):
            takes.append(None)
            continue
        given = {keyword.arg for keyword in call.keywords if keyword.arg}
        callee_needs, callee_takes = _keywords(callee)
        needs |= callee_needs - given
        takes.append(None if callee_takes is None else callee_takes - given)
    if not takes or None in takes:
        return needs, None
    return needs, named | set.intersection(*takes)


def check_build(module, constants: dict[str, Constant]) -> None:
    """Raise ConstantError, naming the scene file, unless its constants block has a line for each
    constant its build function needs and for none it does not take: found before anything runs."""
    where = shown_path(module.__file__) if getattr(module, "__file__", None) else module.__name__
    if not callable(getattr(module, "build", None)):
        raise ConstantError(f"{where}: a scene file needs a build function, `def build(**constants):` "
                            f"after the constants block")
    needs, takes = _keywords(module.build)
    missing = sorted(needs - set(constants), key=str.casefold)
    unused = sorted(set(constants) - takes, key=str.casefold) if takes is not None else []
    if missing:
        one = len(missing) == 1
        unit = DECLARED[missing[0]].unit if missing[0] in DECLARED else "unit"
        raise ConstantError(f"{where}: the constants block has no line{'' if one else 's'} for "
                            f"{', '.join(missing)} (build needs {'it' if one else 'them'}); add "
                            f"{'one' if one else 'each'} like `{missing[0]} = value  # {unit}: meaning` "
                            f"above `{END_OF_CONSTANTS}`")
    if unused:
        one = len(unused) == 1
        raise ConstantError(f"{where}: the constants block has a line for {', '.join(unused)}, which build "
                            f"does not take; remove {'it' if one else 'them'} or add "
                            f"{'it' if one else 'them'} to build's arguments")


def summary(module) -> str:
    """The first line of a scene's docstring: its one-line description ("" if it has none)."""
    return ((module.__doc__ or "").strip().splitlines() or [""])[0]


def scenarios(module) -> list:
    """The scene's numbered scenarios as (label, overrides), possibly empty."""
    return list(getattr(module, "SCENARIOS", []))


def presets(scene, *, whole: bool = True) -> list[tuple[str, dict]]:
    """The scene's presets in menu order, as (label, overrides); `scene` is a module or a Setup.

    A scenario's overrides are its whole case (the scene file's constants, then its own changes);
    whole=False gives only the changes it names, as its label reads.
    """
    module = getattr(scene, "module", scene)
    block = read_constants(module)
    defaults = {name: constant.value for name, constant in listed_constants(module, block).items()}
    case = {name: value for name, value in defaults.items()
            if not (name in DECLARED and DECLARED[name].numerical)}
    found = {}
    if defaults.get("g"):  # gravity is switched on, so its strength matters
        found.update(GRAVITY_PRESETS)
    if "b" in defaults and "k" in defaults:
        found[CRITICAL_DAMPING] = {"b": None}
    for number, (label, overrides) in enumerate(scenarios(module), start=1):
        found[f"scenario {number}: {label}"] = {**case, **overrides} if whole else overrides
    found.update(getattr(module, "PRESETS", {}))
    return [(label, dict(overrides)) for label, overrides in found.items()]


def find_preset(scene, name: str) -> tuple[str, dict]:
    """The preset called `name` (any case; a unique beginning such as "moon" or "scenario 3" is enough).

    Raises ConstantError naming the closest preset and listing them all.
    """
    options = presets(scene)
    labels = [label for label, _ in options]
    wanted = name.strip().casefold()
    exact = [option for option in options if option[0].casefold() == wanted]
    starts = [option for option in options if option[0].casefold().startswith(wanted)] if wanted else []
    if exact or len(starts) == 1:
        return (exact or starts)[0]
    scene_name = getattr(scene, "name", None) or getattr(scene, "__name__", "").rpartition(".")[2]
    if not options:
        raise ConstantError(f"scene {scene_name!r} has no presets")
    if len(starts) > 1:
        raise ConstantError(f"preset {name!r} could be any of {', '.join(repr(o[0]) for o in starts)}; "
                            f"give more of its name")
    folded = {label.casefold(): label for label in labels}
    close = difflib.get_close_matches(wanted, list(folded), n=1, cutoff=0.5)
    hint = f"; did you mean {folded[close[0]]!r}?" if close else ""
    raise ConstantError(f"unknown preset {name!r} for scene {scene_name!r}{hint} "
                        f"(presets: {', '.join(repr(label) for label in labels)})")


def resolve(values: dict) -> dict:
    """The values with b = None ("critical") replaced by b = 2√(mk) for their m and k, kg/s."""
    if "b" in values and values["b"] is None and "m" in values and "k" in values:
        return {**values, "b": float(critical_damping(m=values["m"], k=values["k"]))}
    return values


@dataclass(frozen=True)
class Setup:
    """A scene with its constants resolved: module, constants (with units), chosen values, and
    what the scene file gives beyond them (hooks: VIEW, measure_window, extra_json, ...; read
    from the module once, scenes/_hooks.py); and the forces written as expressions that are
    added to it, as text: ((name, expression), ...) (--force, the pages' Add a force; _written.py)."""

    name: str
    module: object
    constants: dict[str, Constant]
    values: dict
    hooks: SceneHooks = None
    written: tuple = ()

    def __post_init__(self):
        if self.hooks is None:
            object.__setattr__(self, "hooks", SceneHooks.of(self.module))

    def build(self) -> Model:
        """The scene's model. A ValueError is the physics refusing these constants; anything else
        (a teacher's typo inside build, a sys.exit()) is a ConstantError naming the file and line."""
        try:
            model = self.module.build(**self.values)
        except ValueError:
            raise
        except (Exception, SystemExit) as problem:
            raise ConstantError(_broken_file_message(Path(self.module.__file__), problem)) from None
        return add_written(model, self.written, self.values)

    def with_values(self, **changes) -> "Setup":
        return Setup(self.name, self.module, self.constants, resolve({**self.values, **changes}), self.hooks,
                     self.written)

    def with_written(self, written) -> "Setup":
        """These values with these written forces, ((name, expression), ...), instead of any before."""
        return Setup(self.name, self.module, self.constants, self.values, self.hooks, tuple(written))

    def with_preset(self, name: str) -> "Setup":
        """These values with the preset's changes (critical damping from the m and k set now)."""
        return self.with_values(**find_preset(self, name)[1])


def force_constants(module, constants: dict[str, Constant]) -> dict[str, Constant]:
    """The forces' constants a scene takes beyond its constants block, at their declared defaults
    (each switches its force off: b = 0): every force's, where the scene's build takes any
    constant it is given (`build(**constants)` handing them to build_single_mass), else none.
    `--set` may give them (friction's too, which then says in one line why it needs a table)."""
    if _keywords(module.build)[1] is not None:
        return {}
    return {name: Constant(name, declared.default, declared.unit, declared.meaning)
            for name, declared in declared_constants().items()
            if name not in constants and declared.default is not None}


def listed_constants(module, constants: dict[str, Constant]) -> dict[str, Constant]:
    """The scene's constants as --constants, --json and the page list them: its block, and every
    constant of every force it accepts beyond the block (a force a single-mass scene can switch on:
    Force.SINGLE_MASS), at its declared default, switched off. Each extra one stands after the
    constant declared before it (physics/forces/: k, L0, anchor, g, b, C, A, ρ, F0, ω, ...), so a
    scene file that leaves its switched-off forces out lists them where a file that copied them
    would: b after g, drive_axis after ω."""
    offered = force_constants(module, constants)
    if not offered:
        return dict(constants)
    accepted = {name for cls in FORCES if cls.SINGLE_MASS for name in cls.CONSTANTS}   # friction needs a table
    canonical = list(declared_constants())
    order = list(constants)
    for name in canonical:
        if name not in offered or name not in accepted:
            continue
        before = [other for other in canonical[:canonical.index(name)] if other in order]
        place = (order.index(before[-1]) + 1 if before else
                 max((i + 1 for i, other in enumerate(order) if other in canonical), default=0))
        order.insert(place, name)
    return {name: constants[name] if name in constants else offered[name] for name in order}


def configure(name: str, *, assignments=(), scenario: int | None = None, preset: str | None = None,
              forces=()) -> Setup:
    """Defaults from the scene file, then the scenario's changes, the preset's, and `--set NAME=VALUE` ones;
    and the forces written as `NAME=EXPRESSION` (--force), added after the scene's own.

    A preset's b = None (critical damping) is worked out last, from the final m and k. The setup's
    constants are the scene's block, every constant of a force it accepts (listed_constants: on or
    switched off) and any other constant set; its values hold every constant the scene takes
    (force_constants).
    """
    module = load(name)
    block = read_constants(module)
    check_build(module, block)
    constants = listed_constants(module, block)
    offered = {**constants, **force_constants(module, block)}
    values = {key: constant.value for key, constant in offered.items()}
    if scenario is not None:
        options = scenarios(module)
        if not options:
            raise ConstantError(f"scene {name!r} has no scenarios")
        if not 1 <= scenario <= len(options):
            raise ConstantError(f"scenario {scenario} is out of range: scene {name!r} has scenarios 1 to {len(options)}")
        values.update(options[scenario - 1][1])
    if preset is not None:
        values.update(find_preset(module, preset)[1])
    assigned = parse_assignments(assignments, offered)
    values.update(assigned)
    for key, value in values.items():  # the file's own values and the presets' obey the same ranges
        check_value(key, tuple(value) if isinstance(value, list) else value, offered[key].unit)
    shown = {**constants, **{key: offered[key] for key in assigned if key not in constants}}
    try:
        written = tuple(parse_force_option(text) for text in forces)
    except ValueError as problem:
        raise ConstantError(str(problem)) from None
    return Setup(name, module, shown, resolve(values), written=written)

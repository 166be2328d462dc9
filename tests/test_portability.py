"""Issue 20, item 7: nothing of ours needs a POSIX-only module or call without a fallback (many teachers
use Windows and macOS).

Modules that exist only on POSIX systems (resource, fcntl, termios, pwd, grp, pty) are imported only
inside `try: ... except ImportError:`, and os.getloadavg (missing on Windows) is called in one
place that says "n/a" without it. benchmarks/ imported resource at the top of benchmarks/common.py
and called os.getloadavg in four places: `python -m benchmarks` could not start on Windows.
"""
from __future__ import annotations

import ast
import os
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
POSIX_ONLY = {"resource", "fcntl", "termios", "pwd", "grp", "pty", "posix"}
OURS = ["main.py", "physics", "scenes", "export", "browser", "reports", "lab", "cli", "benchmarks"]


def our_modules():
    for name in OURS:
        path = ROOT / name
        yield from [path] if path.is_file() else sorted(path.rglob("*.py"))


def unguarded_imports(tree: ast.AST) -> list[str]:
    """POSIX-only modules imported outside a try whose handlers catch ImportError."""
    guarded = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Try) and any(
                isinstance(handler.type, ast.Name) and handler.type.id in ("ImportError", "ModuleNotFoundError")
                for handler in node.handlers):
            guarded.update(id(inner) for statement in node.body for inner in ast.walk(statement))
    found = []
    for node in ast.walk(tree):
        names = ([alias.name for alias in node.names] if isinstance(node, ast.Import)
                 else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
        found += [name for name in names if name.split(".")[0] in POSIX_ONLY and id(node) not in guarded]
    return found


def test_posix_only_modules_are_imported_with_a_fallback():
    found = {}
    for path in our_modules():
        names = unguarded_imports(ast.parse(path.read_text(encoding="utf-8")))
        if names:
            found[str(path.relative_to(ROOT))] = names
    assert found == {}


def test_the_load_average_is_read_in_one_place():
    calls = [str(path.relative_to(ROOT)) for path in our_modules() if "getloadavg" in path.read_text(encoding="utf-8")]
    assert calls == [os.path.join("benchmarks", "common.py")]


def test_the_benchmarks_run_their_figures_without_resource_or_a_load_average(monkeypatch):
    """As on Windows: no resource module, no os.getloadavg."""
    from benchmarks import common

    monkeypatch.setattr(common, "resource", None)
    monkeypatch.delattr(os, "getloadavg")
    assert common.load_average() == common.load_average(every=True) == "n/a"
    wall, cpu, out = common.process_time(["-c", "print('ran')"])
    assert out == "ran\n" and cpu == wall > 0

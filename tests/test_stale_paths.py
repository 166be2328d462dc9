"""Issue 37, item 4: no comment, docstring, message or guide names a file of the project that is not there.

physics/forces.py became the package physics/forces/ two stops ago, and nine places, one of them
an error message, still sent the reader to it. This test reads every comment and string of the
project's code (tokenize: code is left out, so an import is not read as a path) and every guide,
finds each path into one of the project's folders (`physics/forces/base.py`, `docs/lab.md`,
`scenes/`), and checks that it exists. A placeholder in capitals (`scenes/NAME.py`) is a pattern,
not a path. The tests are left out: they name the files they make in temporary folders.
"""
from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
FOLDERS = ("physics", "scenes", "browser", "reports", "export", "lab", "cli", "tests", "benchmarks", "examples", "docs")
PATH = re.compile(r"(?<![\w./\\-])((?:" + "|".join(FOLDERS) + r")/(?:[\w.-]+/)*[\w.-]*)")
CODE = ("physics", "scenes", "browser", "reports", "export", "lab", "cli", "benchmarks", "examples")
# The speed engineer's measurement logs (issue 37 item 5 moves their history out of docs/).
LOGS = {"docs/performance.md", "docs/long_run.md"}


def code_files() -> list[Path]:
    found = [ROOT / "main.py"]
    for folder in CODE:
        found += [path for path in (ROOT / folder).rglob("*") if path.suffix in (".py", ".js", ".css")
                  and "glowscript" not in path.parts and "__pycache__" not in path.parts]
    return sorted(found)


def guides() -> list[Path]:
    return sorted(path for path in [ROOT / "README.md", *(ROOT / "docs").glob("*.md")]
                  if path.relative_to(ROOT).as_posix() not in LOGS)


def words(path: Path) -> list[tuple[int, str]]:
    """(line, text) of what a reader reads in the file: a Python file's comments and strings, all of
    any other file."""
    text = path.read_text(encoding="utf-8")
    if path.suffix != ".py":
        return [(number, line) for number, line in enumerate(text.splitlines(), start=1)]
    return words_of(text)


def stale(path: Path) -> list[str]:
    missing = []
    for line, text in words(path):
        for found in PATH.findall(text):
            named = found.rstrip(".")
            if re.search(r"(^|/)[A-Z][A-Z_]*(\.\w+)?$", named) or "*" in named:   # scenes/NAME.py: a pattern
                continue
            target = ROOT / named
            if not (target.exists() or target.with_suffix(".py").exists()):
                missing.append(f"{path.relative_to(ROOT)}:{line}: {named}")
    return missing


@pytest.mark.parametrize("path", code_files() + guides(), ids=lambda path: str(path.relative_to(ROOT)))
def test_every_path_it_names_exists(path):
    assert stale(path) == []


def test_the_check_finds_the_issues_stale_path():
    """The old module, named in a comment and in a message, is found; a placeholder is not."""
    text = '# see physics/forces.py\nraise ValueError("declared in physics/forces.py")\nx = "scenes/NAME.py"\n'
    lines = [(number, found) for number, string in words_of(text) for found in PATH.findall(string)]
    assert [found for _, found in lines] == ["physics/forces.py", "physics/forces.py", "scenes/NAME.py"]
    assert not (ROOT / "physics" / "forces.py").exists()


def words_of(text: str) -> list[tuple[int, str]]:
    return [(token.start[0], token.string) for token in tokenize.generate_tokens(io.StringIO(text).readline)
            if token.type in (tokenize.COMMENT, tokenize.STRING)]

"""The documents name files and functions that exist, and every command they show runs as shown.

README.md is where a newcomer starts and each guide in docs/ is where a reader goes next; a path
or a name in them that has moved away sends the reader nowhere, and a command that fails there
loses the reader at once. So every `python main.py ...` line of their code blocks that needs no
browser is run here, as a user would type it, in a folder of its own.
"""
import importlib
import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
GUIDES = ["README.md", "docs/model.md", "docs/teaching.md", "docs/homework.md", "docs/lab.md",
          "docs/handout.md", "docs/architecture.md"]
DOCS = GUIDES + ["docs/performance.md", "benchmarks/results/README.md"]
PATH = re.compile(r"`((?:physics|scenes|browser|reports|export|lab|cli|tests|benchmarks|examples|docs)/[\w./-]*)`")
NAME = re.compile(r"`((?:physics|scenes|browser|reports|export|lab)\.\w+(?:\.\w+)?)`")
LINK = re.compile(r"\]\(((?!https?:|#)[^)#\s]+)")
README_LIMIT = 10 * 1024      # bytes: a front door read in two minutes (pymunk's is 6.3 KB)
# What makes a command need no browser: the rest open the page, which the browser tests cover.
HEADLESS = {"--headless", "--steps", "--list", "--constants", "--plot", "--data", "--mystery",
            "--show-answer", "--vpython", "--webvpython", "--html"}
EXPLAINS_ONLY = {"docs/model.md", "docs/architecture.md"}     # guides that show no command to run
QUICK_CHECK = 'python -m pytest -m "not browser"'


@pytest.mark.parametrize("doc", DOCS)
def test_every_path_a_document_names_exists(doc):
    text = (ROOT / doc).read_text(encoding="utf-8")
    paths = set(PATH.findall(text))
    placeholder = re.compile(r"/[A-Z]+\.")                     # scenes/NAME.py: any name
    missing = [path for path in sorted(paths)
               if not placeholder.search(path) and not (ROOT / path.rstrip("/")).exists()]
    assert not missing, missing


@pytest.mark.parametrize("doc", DOCS)
def test_every_link_between_the_documents_leads_somewhere(doc):
    text = (ROOT / doc).read_text(encoding="utf-8")
    here = (ROOT / doc).parent
    missing = [link for link in LINK.findall(text) if not (here / link).exists()]
    assert not missing, missing


def anchors(doc: Path) -> set[str]:
    """The anchors GitHub gives a document's headings: lower case, punctuation dropped, spaces as -."""
    headings = re.findall(r"^#+ (.+)$", doc.read_text(encoding="utf-8"), flags=re.MULTILINE)
    return {re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-") for heading in headings}


@pytest.mark.parametrize("doc", DOCS)
def test_every_link_to_a_section_finds_its_heading(doc):
    text = (ROOT / doc).read_text(encoding="utf-8")
    here = (ROOT / doc).parent
    links = re.findall(r"\]\(((?!https?:)[^)#\s]*)#([^)\s]+)\)", text)
    missing = [f"{path}#{anchor}" for path, anchor in links
               if anchor not in anchors((here / path) if path else (ROOT / doc))]
    assert not missing, missing


@pytest.mark.parametrize("doc", GUIDES)
def test_every_module_attribute_a_document_names_exists(doc):
    text = (ROOT / doc).read_text(encoding="utf-8")
    for dotted in sorted(set(NAME.findall(text))):
        module, _, attribute = dotted.rpartition(".")
        try:
            found = importlib.import_module(dotted)        # a module: physics.simulate
        except ImportError:
            found = getattr(importlib.import_module(module), attribute, None)
        assert found is not None, dotted


def test_the_readme_is_a_front_door_that_links_every_guide():
    readme = (ROOT / "README.md").read_bytes()
    assert len(readme) <= README_LIMIT, len(readme)
    text = readme.decode("utf-8")
    for guide in GUIDES[1:]:
        assert f"]({guide})" in text, guide


def test_the_readme_reads_in_the_issues_order():
    """What it is, one screenshot (a committed image), the set-up, a tour for each of the four
    readers, then where to read more (issue 31)."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    headings = re.findall(r"^## (.+)$", text, flags=re.MULTILINE)
    assert headings == ["Set up on a fresh machine", "A teacher on a projector", "A student checking homework",
                        "A lab class with measured data", "A teacher handing out a program or an offline page",
                        "Read more"], headings
    images = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert len(images) == 1 and (ROOT / images[0]).is_file(), images
    assert text.index("![") < text.index("## Set up")


def test_the_readme_sets_up_as_ci_does_and_names_the_browser_suite():
    """The README's second set-up command is the one `.ci/run` runs, word for word: the tests
    that need no browser (QUICK_CHECK); and the README names the browser suite's own command."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    ci_command = next(line for line in ci.splitlines() if line.startswith("apt-get update"))
    assert f"\n    {ci_command}\n" in readme
    assert "    python3 -m venv .venv && .venv/bin/pip install -r requirements.txt && .venv/bin/python main.py\n" in readme
    assert ci_command.endswith(QUICK_CHECK.replace("python", ".venv/bin/python", 1))
    assert "\n    .venv/bin/python -m pytest -m browser\n" in readme


def test_the_notebook_tells_the_guides_jupyter_command():
    teaching = (ROOT / "docs" / "teaching.md").read_text(encoding="utf-8")
    command = next(line.strip() for line in teaching.splitlines() if "jupyter notebook --config" in line)
    notebook = json.loads((ROOT / "examples" / "scenes.ipynb").read_text(encoding="utf-8"))
    first = "".join(notebook["cells"][0]["source"])
    assert command in first
    assert all(not cell.get("outputs") for cell in notebook["cells"])  # committed without outputs


def shown_commands(doc: str) -> list[list[str]]:
    """Every `python main.py ...` line of a code block in a guide that needs no browser, as its
    arguments, in the order shown. A line ends at its comment."""
    found = []
    for line in (ROOT / doc).read_text(encoding="utf-8").splitlines():
        if not line.startswith("    python main.py"):
            continue
        args = shlex.split(line.partition("  #")[0])[2:]
        if HEADLESS & set(args) and "--page" not in args:
            found.append(args)
    return found


@pytest.mark.parametrize("doc", GUIDES)
def test_every_command_a_guide_shows_runs_as_shown(doc, tmp_path):
    """The guide's commands, in order, in an empty folder of their own (so a file one writes, a
    mystery spring, is there for the next to read) with examples/ reachable by the same relative
    paths: each exits 0, or 3 where a fit cannot be trusted, with no traceback. Every file they
    write lands in that folder, never in the project's tree."""
    commands = shown_commands(doc)
    assert commands or doc in EXPLAINS_ONLY, f"{doc} shows no command to run"
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    (tmp_path / "out").mkdir()   # the guides write into out/, which the program makes in its own folder
    env = {**os.environ, "PYTHONIOENCODING": "utf-8"}
    failed = []
    for args in commands:
        done = subprocess.run([sys.executable, str(ROOT / "main.py"), *args], cwd=tmp_path, env=env,
                              capture_output=True, text=True, encoding="utf-8", timeout=600)
        allowed = (0, 3) if "--fit" in args else (0,)       # 3: a fit whose numbers cannot be trusted
        if done.returncode not in allowed or "Traceback" in done.stderr:
            failed.append((" ".join(args), done.returncode, done.stderr.strip()[-300:]))
    assert not failed, failed

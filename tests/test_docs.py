"""The documents name files and functions that exist, and the notebook gives the README's command.

README.md and docs/architecture.md are where a newcomer starts; a path or a name in them that has
moved away sends the reader nowhere.
"""
import importlib
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ["README.md", "docs/architecture.md", "docs/performance.md", "docs/long_run.md"]
PATH = re.compile(r"`((?:physics|scenes|browser|reports|export|tests|benchmarks|examples|docs)/[\w./-]*)`")
NAME = re.compile(r"`((?:physics|scenes|browser|reports|export)\.\w+(?:\.\w+)?)`")


@pytest.mark.parametrize("doc", DOCS)
def test_every_path_a_document_names_exists(doc):
    text = (ROOT / doc).read_text(encoding="utf-8")
    paths = set(PATH.findall(text))
    assert paths or doc.startswith("docs/long") or doc.startswith("docs/perf")
    placeholder = re.compile(r"/[A-Z]+\.")                     # scenes/NAME.py: any name
    missing = [path for path in sorted(paths)
               if not placeholder.search(path) and not (ROOT / path.rstrip("/")).exists()]
    assert not missing, missing


@pytest.mark.parametrize("doc", ["README.md", "docs/architecture.md"])
def test_every_module_attribute_a_document_names_exists(doc):
    text = (ROOT / doc).read_text(encoding="utf-8")
    for dotted in sorted(set(NAME.findall(text))):
        module, _, attribute = dotted.rpartition(".")
        try:
            found = importlib.import_module(dotted)        # a module: physics.simulate
        except ImportError:
            found = getattr(importlib.import_module(module), attribute, None)
        assert found is not None, dotted


def test_the_notebook_tells_the_readmes_jupyter_command():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    command = next(line.strip() for line in readme.splitlines() if "jupyter notebook --config" in line)
    notebook = json.loads((ROOT / "examples" / "scenes.ipynb").read_text(encoding="utf-8"))
    first = "".join(notebook["cells"][0]["source"])
    assert command in first
    assert all(not cell.get("outputs") for cell in notebook["cells"])  # committed without outputs

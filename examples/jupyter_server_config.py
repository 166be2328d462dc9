"""Jupyter settings for the example notebook, loaded by the README's command:

    .venv/bin/jupyter notebook --config=examples/jupyter_server_config.py examples/scenes.ipynb

* Saving a notebook (Jupyter also saves on its own every two minutes) keeps its cells but not
  what running them produced: outputs, execution counts and the kernel's version details. So
  examples/scenes.ipynb stays as committed, and `git status` stays clean after a lesson.
* The server also runs for root (a classroom computer set up as root), which Jupyter otherwise
  refuses without --allow-root.
"""

COMMITTED_LANGUAGE_INFO = {"name": "python"}


def keep_cells_not_outputs(model, **_):
    """Jupyter's pre-save hook: drop outputs and execution counts, and the kernel's language details."""
    if model.get("type") != "notebook" or not isinstance(model.get("content"), dict):
        return
    notebook = model["content"]
    for cell in notebook.get("cells", []):
        if cell.get("cell_type") == "code":
            cell["outputs"] = []
            cell["execution_count"] = None
        cell["metadata"] = {}
    notebook.setdefault("metadata", {})["language_info"] = dict(COMMITTED_LANGUAGE_INFO)


c = get_config()  # noqa: F821 (Jupyter defines get_config for its config files)
c.ContentsManager.pre_save_hook = keep_cells_not_outputs
c.ServerApp.allow_root = True

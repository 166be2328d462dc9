"""vpython's own vector class, loaded WITHOUT running vpython/__init__.py.

`import vpython.cyvector` would first run vpython/__init__.py, which creates a canvas, starts a
web server and blocks until a browser connects. So we locate the vpython package without
importing it (importlib.util.find_spec on a top-level name only reads the file system) and load
the compiled vector module (cyvector, Cython) straight from its file. If the extension cannot be
loaded, we load the pure-Python vpython/vector.py by path instead. Either way no canvas exists.

    vector, mag, norm, kind = load_vector()   # kind: "cyvector" or "vector.py"

It also holds the reference every speed figure is set against: the page's own program (its
Simple Example, scenes/vertical.py), written the way a classroom program is, stepped at a fine
Δt. Run as a process it is what a student's program costs, start-up included:

    python -m benchmarks.page_vector --steps 1000000     # prints {"steps", "r", "kind"} as JSON
"""
from __future__ import annotations

import argparse
import importlib.machinery
import importlib.util
import json
import os
import sys
import threading

_LOADED = None


def _vpython_folder() -> str | None:
    spec = importlib.util.find_spec("vpython")
    if spec is None or not spec.submodule_search_locations:
        return None
    return list(spec.submodule_search_locations)[0]


def _load_file(name: str, path: str, loader=None):
    spec = importlib.util.spec_from_file_location(name, path, loader=loader)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _load_cyvector(folder: str):
    for suffix in importlib.machinery.EXTENSION_SUFFIXES:
        path = os.path.join(folder, "cyvector" + suffix)
        if os.path.exists(path):
            # The module's init function is PyInit_cyvector, so its own name must end in "cyvector".
            return _load_file("cyvector", path, importlib.machinery.ExtensionFileLoader("cyvector", path))
    raise ImportError("no compiled cyvector in " + folder)


def load_vector():
    """(vector, mag, norm, kind) from vpython, or ImportError if vpython is not installed.

    Raises RuntimeError if loading it imported the vpython package itself or started a thread
    (which is what creating a canvas does): the benchmark must never start a server.
    """
    global _LOADED
    if _LOADED is not None:
        return _LOADED
    folder = _vpython_folder()
    if folder is None:
        raise ImportError("vpython is not installed")
    threads_before = threading.active_count()
    try:
        module, kind = _load_cyvector(folder), "cyvector"
    except ImportError:
        module, kind = _load_file("_page_vector", os.path.join(folder, "vector.py")), "vector.py"
    if "vpython" in sys.modules or threading.active_count() != threads_before:
        raise RuntimeError("loading vpython's vector imported vpython itself (a canvas and server would start)")
    _LOADED = (module.vector, module.mag, module.norm, kind)
    return _LOADED


# The page's Simple Example (scenes/vertical.py), stepped finely: 10⁶ steps reach t = 100 s.
k = 40.0                # N/m
m = 10.0                # kg
L0 = 1.0                # m
g = 9.8                 # m/s², along −y
r0 = (0.0, -1.5, 0.0)   # m, from rest
anchor = (0.0, 0.0, 0.0)
dt = 1e-4               # s


def page_style_loop(steps: int):
    """The classroom program, with vpython's vector (no canvas is created): its final position."""
    vector, mag, norm, _ = load_vector()
    pos = vector(*r0)
    p = vector(0, 0, 0)
    top = vector(*anchor)
    g_vec = vector(0, -g, 0)
    t = 0
    for _ in range(steps):
        L = pos - top
        F = -k * (mag(L) - L0) * norm(L) + m * g_vec
        p = p + F * dt
        pos = pos + p / m * dt
        t = t + dt
    return (pos.x, pos.y, pos.z)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.page_vector",
                                     description="The page's loop with vpython's vector, as a process.")
    parser.add_argument("--steps", type=int, default=1_000_000, help="Euler-Cromer steps of dt = 1e-4 s")
    steps = parser.parse_args(argv).steps
    print(json.dumps({"steps": steps, "r": page_style_loop(steps), "kind": load_vector()[3]}))
    return 0


if __name__ == "__main__":
    sys.exit(main())

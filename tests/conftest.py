"""Shared helpers for the physics tests, offered as fixtures.

- ``observed_order``: the order p of a method from errors at several Δt, fitting error ∝ Δt^p.
- ``line_oscillators``: a batch of independent masses on L0 = 0 springs at the origin, moving
  along x with no gravity. Each row is its own m x'' + b x' + k x = F0 cos(ω t), the equation
  physics.exact.oscillator solves, so one numpy run checks many parameter sets at once.
- ``oscillation_energy``: E − E_equilibrium along a single-mass trajectory, from physics.energy,
  computed for all samples at once.
"""
from __future__ import annotations

import os

import numpy as np
import pytest

from physics.energy import kinetic, potential
from physics.forces import Driving, LinearDamping, Spring
from physics.state import State, make_state


def _observed_order(dts, errors) -> float:
    """Slope of log(error) against log(Δt): halving Δt divides the error by 2^p."""
    return float(np.polyfit(np.log(dts), np.log(errors), 1)[0])


def _line_oscillators(*, m, k, b=0.0, x0=0.0, v0=0.0, F0=0.0, omega=0.0):
    """(state, forces) for len(m) masses; every parameter is a number or one value per mass."""
    m, k, b, x0, v0, F0, omega = np.broadcast_arrays(*(np.atleast_1d(np.asarray(a, dtype=float))
                                                      for a in (m, k, b, x0, v0, F0, omega)))
    along_x = np.array([1.0, 0.0, 0.0])
    state = make_state(r=x0[:, None] * along_x, v=v0[:, None] * along_x, m=m)
    forces = (Spring(k=k, L0=0.0), LinearDamping(b=b), Driving(F0=F0, omega=omega))
    return state, forces


def _oscillation_energy(trajectory, forces, r_equilibrium) -> np.ndarray:
    """E(t) − E at rest at equilibrium, J, for a one-mass trajectory (n samples).

    The n samples are treated as n masses of one State, so physics.energy works on them in one call.
    """
    m = np.full(len(trajectory.t), trajectory.m[0])
    samples = State(t=0.0, r=trajectory.r[:, 0, :], p=trajectory.p[:, 0, :], m=m)
    E = kinetic(samples) + potential(samples, forces)
    rest = make_state(r=r_equilibrium, m=trajectory.m[0])
    return E - potential(rest, forces)[0]


@pytest.fixture(scope="session")
def observed_order():
    return _observed_order


@pytest.fixture(scope="session")
def line_oscillators():
    return _line_oscillators


@pytest.fixture(scope="session")
def oscillation_energy():
    return _oscillation_energy


# ---- one Chromium per test module ----

@pytest.fixture(scope="module")
def browser():
    """Headless Chromium with the project's arguments (tests/browser_support.py), launched once per
    test module on the run's one Playwright driver; each test opens its own pages, each page in a
    context of its own. Skips, with the reason, where Chromium, Playwright or Pillow is missing.

    Per module, not per run: one Chromium kept for a whole run (issue 31's first try) let its GPU
    process (software WebGL) grow busier with every page it had drawn, to nearly two cores with
    one idle page open after an hour, and a page of test_offline_page_browser.py then waited for
    ever. A module's Chromium is closed, GPU process and all, when the module ends."""
    import browser_support

    sync_api, _ = browser_support.require_browser()
    with browser_support.launched(sync_api) as chromium:
        yield chromium


@pytest.fixture(scope="session", autouse=True)
def _playwright_stopped():
    """Stop the run's Playwright driver at the end, if it started (a run without browser tests
    starts none)."""
    yield
    import sys

    support = sys.modules.get("browser_support")
    if support is not None:
        support.stop_all()


# ---- a hang guard for the browser tests ----

# A browser test waits for events only (tests/browser_support.py's PATIENCE each), and asks for the
# simulated time it needs (Jump to t) instead of watching the animation reach it, so a healthy one
# takes seconds to a minute or two. This limit, above pyproject's 300 s for every test, is for the
# few that also start a notebook server or a second program first; a test that reaches it hangs.
BROWSER_TIMEOUT = 600   # s


def pytest_collection_modifyitems(config, items):
    """A browser test may set up a notebook server and a browser before its first step (a test run
    alone by its id does all that itself): it gets BROWSER_TIMEOUT instead of pyproject's 300 s."""
    for item in items:
        if item.get_closest_marker("browser") and not item.get_closest_marker("timeout"):
            item.add_marker(pytest.mark.timeout(BROWSER_TIMEOUT))


# ---- using the project leaves the repository as it was ----

def _git_status() -> str | None:
    """`git status --porcelain` of the project, or None outside a git checkout."""
    import subprocess
    from pathlib import Path

    try:
        done = subprocess.run(["git", "status", "--porcelain", "--untracked-files=all"],
                              cwd=Path(__file__).resolve().parent.parent, capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return None
    return done.stdout if done.returncode == 0 else None


def pytest_sessionstart(session):
    session.config._git_status_before = _git_status()


def pytest_sessionfinish(session, exitstatus):
    """Fail the run if the tests changed, added or removed a file the repository tracks or sees
    (screenshots, notebook outputs, scratch files belong in /tmp)."""
    before = getattr(session.config, "_git_status_before", None)
    after = _git_status()
    if before is not None and after is not None and after != before:
        changed = sorted(set(after.splitlines()) ^ set(before.splitlines()))
        if os.environ.get("UPDATE_SCREENSHOTS") == "1":  # asked for: regenerating docs/screenshots/
            changed = [line for line in changed if "docs/screenshots/" not in line]
        if not changed:
            return
        print("\nerror: the test run changed the repository (git status --porcelain):\n  "
              + "\n  ".join(changed), flush=True)
        session.exitstatus = 1

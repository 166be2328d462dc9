"""What the page's controls ask the frame loop to do: one small named type per kind of click.

A click arrives on vpython's server thread. The control only queues one of these messages
(browser/controls.py), and the frame loop (browser/view.py's SceneView) carries the queued
messages out between frames, in the order they were made, with one handler per type
(`SceneView.carry_out`). A new button is one type here, the control that queues it, and one
handler in the view:

    @dataclass(frozen=True)
    class CopyLink:
        '''Copy the address of this page.'''

    vp.button(text="Copy link", bind=lambda _: put(CopyLink()))

    @carry_out.register
    def _copy_link(self, message: CopyLink, batch: Batch) -> None: ...

Nothing here imports vpython.
"""
from __future__ import annotations

from dataclasses import dataclass, field


# ---- the run ----

@dataclass(frozen=True)
class RunOrPause:
    """Run if paused, pause if running (the Run/Pause button, key Space)."""


@dataclass(frozen=True)
class Step:
    """Pause, and take one step of Δt, drawn and written out (the Step button, key →)."""


@dataclass(frozen=True)
class Reset:
    """Back to the exact initial state, t = 0 (the Reset button, key R)."""


@dataclass(frozen=True)
class JumpTo:
    """Take the run to the time typed in the "Jump to t" box, drawn once and paused there (the
    Jump button, key J; browser/jump.py). `text` is the box's text, "2.5" or "2.5 s": the view
    reads it, so a bad entry is one sentence on the page. A t before now starts again from 0."""
    text: str


@dataclass(frozen=True)
class Describe:
    """Say the motion in words in the live region (the Describe button, key D; export/description.py)."""


@dataclass(frozen=True)
class ChooseSpeed:
    """Simulated time runs at this speed × wall time: a label of browser/controls.py's SPEEDS, `2×`."""
    label: str


# ---- what runs: each restarts the run from t = 0 ----

@dataclass(frozen=True)
class SetConstant:
    """A slider moved: constant `name` takes `value`, in its unit."""
    name: str
    value: float


@dataclass(frozen=True)
class ChooseIntegrator:
    """Another integrator from the menu, by its name in physics/integrators.py."""
    name: str


@dataclass(frozen=True)
class ChoosePreset:
    """A preset from the menu, by its label (the menu's prompt chooses none)."""
    label: str


@dataclass(frozen=True)
class ChooseScene:
    """Another scene from the menu, by its name."""
    name: str


@dataclass(frozen=True)
class AddForce:
    """The Add a force box (browser/force_box.py): add the force `name` written as `text`, an
    expression of the program's names, read by physics/expression.py's grammar."""
    name: str
    text: str


@dataclass(frozen=True)
class RemoveForce:
    """Remove the added force `name` (its Remove button in the Add a force box)."""
    name: str


@dataclass(frozen=True)
class ResetForces:
    """Back to the forces the scene was opened with (the box's Back to the file's program)."""


# ---- what is drawn ----

@dataclass(frozen=True)
class ShowArrows:
    """A check box of the arrows on each mass (export/arrows.py's ARROWS: p, F_net, ...)."""
    kind: str
    shown: bool


# ---- measuring (the Measure panel, browser/measure_panel.py) ----

@dataclass(frozen=True)
class StartStopwatch:
    """Start the stopwatch, or stop it if it runs (key S)."""


@dataclass(frozen=True)
class LapStopwatch:
    """Note the stopwatch's reading as a lap (key L)."""


@dataclass(frozen=True)
class ClearStopwatch:
    """Set the stopwatch back to 0 (key C)."""


@dataclass(frozen=True)
class ShowPeriod:
    """The check box of the period: measured from the motion, and the formula's."""
    shown: bool


@dataclass(frozen=True)
class ShowLine:
    """A check box of a line in the 3-D view: "natural", "equilibrium" or "marker"
    (browser/reference_lines.py)."""
    kind: str
    shown: bool


@dataclass(frozen=True)
class MoveMarker:
    """The mouse pressed or dragged on the 3-D view at (x, y, z), m: the marker line goes there."""
    x: float
    y: float
    z: float


@dataclass(frozen=True)
class ChooseGraph:
    """What the graph place under the position graph shows: "energy", "phase" or "bars"."""
    kind: str


# ---- files ----

@dataclass(frozen=True)
class DownloadCsv:
    """Hand the graphed samples to the browser as a CSV file."""


@dataclass(frozen=True)
class DownloadProgram:
    """Hand the scene, as chosen now, to the browser as a VPython program."""


@dataclass(frozen=True)
class DownloadOfflinePage:
    """Hand the scene, as chosen now, to the browser as one HTML file that runs offline
    (export/offline_page.py: what `main.py SCENE --html FILE.html` writes)."""


@dataclass(frozen=True)
class FitData:
    """Fit the constants to the measured data loaded (browser/data_panel.py)."""


@dataclass
class Batch:
    """What the messages of one frame leave for the frame loop to do after the last of them.

    Constants and an integrator chosen in one frame restart the run once, with all of them; a
    new scene or preset builds new controls, and the messages after it were made on the old
    ones, so they are dropped (page_built).

    now         the frame's wall-clock time, s (Reset restarts the clock from it)
    changes     constants set by sliders, by name
    integrator  the integrator chosen, or None
    page_built  a new scene or preset built the page again: the rest of the batch is dropped
    """

    now: float
    changes: dict = field(default_factory=dict)
    integrator: str | None = None
    page_built: bool = False

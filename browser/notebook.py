"""Show a scene in a Jupyter notebook cell, through vpython's notebook mode.

    from browser.notebook import show
    show("vertical")                       # the page's Simple Example
    show("vertical", k=60, dt=0.01)        # any constant, in the scene's units
    show("driven", scenario=3)             # one of the scene's numbered scenarios
    show("damped", integrator="rk4")       # any integrator from physics.integrators
    show("vertical", preset="Moon gravity")  # any preset of the scene's preset menu

The cell returns at once and the scene keeps running under it, with the same controls as
``python main.py NAME``: Run/Pause, Step, Reset, the sliders, the integrator, speed, scene and
preset menus, Download CSV and the graphs. The scene menu switches scene in place, inside the same
cell, as it does in the browser. Other cells can run meanwhile. Running show() again, in the same cell or another, stops the scene that was running
(its 3-D view and graphs are removed, its caption says it stopped) and starts the new one where
show() ran. One scene runs at a time in a kernel.

How it works. In a notebook, vpython 7.6.5 does not start its own web server. The kernel sends
the drawing to the page over a Jupyter comm; the page sends clicks, and every ~33 ms a request for
updates, back through the Jupyter server (jupyter-server-proxy) to a small websocket server that
vpython starts inside the kernel. vpython makes that server listen on every network interface and
accept any Origin; show() binds it to localhost, where the proxy connects. A task on the kernel's
event loop hands the page's messages to vpython, which answers each request with what changed,
and calls ``SceneView.frame()``, the frame the browser view runs in its loop. The page's requests
for updates stand in for the loopback server's contact time (NotebookLink.seconds_since_contact),
so a tab the browser has frozen stops the clock as it does in the browser view.

vpython's websocket server stops for good when the page that first connected goes away (a reload,
or the notebook closed and reopened). Then show() says so: restart the kernel and run again.

Needs Jupyter Notebook 7 or JupyterLab 4 with the jupyterlab-vpython extension; vpython 7.6.5
(requirements.txt) installs all of them. The classic notebook (6.x) is not supported. Importing
this module does not import vpython.
"""
from __future__ import annotations

import asyncio
import contextlib
import importlib
import json
import queue
import sys
import time
import traceback

from export.arrows import parse_arrows
from physics.integrators import DEFAULT_INTEGRATOR, INTEGRATORS

from .clock import check_live_cost

from scenes import catalog
from scenes import ConstantError

_live = None  # the scene running in this kernel: (task, view)


class PageGone(RuntimeError):
    """The notebook page vpython was connected to has gone: shown as its one-line message."""

    def _render_traceback_(self) -> list[str]:
        """IPython shows these lines instead of a traceback: the message is all the student needs."""
        return [f"{type(self).__name__}: {self}"]


class ShowError(ConstantError):
    """A bad argument to show(): an unknown name, a value of the wrong type or out of its range."""

    def _render_traceback_(self) -> list[str]:
        """IPython shows this line instead of a 35-line traceback."""
        return [f"ConstantError: {self}"]


def _checked_arguments(name, scenario, preset, integrator, constants) -> list[str]:
    """show()'s arguments as --set assignments, after checking their types (ShowError if wrong):
    a teacher's show(123) or show("vertical", k="60") gets one line, not a TypeError from inside."""
    def number(value) -> bool:
        return isinstance(value, (int, float)) and not isinstance(value, bool)

    if not isinstance(name, str):
        raise ShowError(f"show() needs the scene's name as text, like show({catalog.DEFAULT_SCENE!r}) (got {name!r})")
    if scenario is not None and not (isinstance(scenario, int) and not isinstance(scenario, bool)):
        raise ShowError(f"scenario needs a whole number, like scenario=3 (got {scenario!r})")
    for what, value in (("preset", preset), ("integrator", integrator)):
        if value is not None and not isinstance(value, str):
            raise ShowError(f"{what} needs a name as text, like {what}={'Moon gravity' if what == 'preset' else 'rk4'!r} "
                            f"(got {value!r})")
    assignments = []
    for key, value in constants.items():
        parts = list(value) if isinstance(value, (tuple, list)) else [value]
        if not parts or not all(number(part) for part in parts):
            raise ShowError(f"{key} needs a number, or three numbers for a vector like r0=(0, -1.2, 0) (got {value!r})")
        try:
            floats = [float(part) for part in parts]
        except OverflowError:   # an int like 10**5000: too large for any constant
            big = max(abs(part) for part in parts if isinstance(part, int))
            raise ShowError(f"{key} is too large to be a number the program can use (got an integer of "
                            f"about {big.bit_length() * 0.30103:.0f} digits)") from None
        assignments.append(f"{key}={','.join(repr(x) for x in floats)}")
    return assignments


class NotebookLink:
    """vpython's connection to the notebook page, from the kernel's side: what the page sent, and when."""

    def __init__(self):
        from vpython.rate_control import ws_queue
        from vpython.vpython import baseObj

        self._queue, self._glow = ws_queue, baseObj.glow
        self._last_contact = time.monotonic()

    def pump(self) -> None:
        """Hand each message from the page to vpython: a click runs its binding, and a request
        for updates is answered with everything changed since the last one."""
        while True:
            try:
                data = self._queue.get_nowait()
            except queue.Empty:
                return
            self._last_contact = time.monotonic()
            for event in json.loads(data):  # one at a time, as vpython's own rate() does
                self._glow.handle_msg({"content": {"data": [event]}})

    def seconds_since_contact(self) -> float:
        """The page asks for updates while it is visible, so a hidden tab stops the clock."""
        return time.monotonic() - self._last_contact


def show(name: str = catalog.DEFAULT_SCENE, *, scenario: int | None = None, preset: str | None = None,
         integrator: str | None = None, arrows=None, **constants) -> None:
    """Show scene `name` in this cell, with any constants changed, and keep it running.

    scenario    one of the scene's numbered scenarios (as --scenario N)
    preset      the label of one of its presets (as --preset), applied before the constants
    integrator  a name from physics.integrators.INTEGRATORS (default: the scene's own, else euler-cromer)
    arrows      the arrows on each mass, as --arrows: ("p", "F_net"), () for none (default: the scene's)
    constants   any of the scene's constants, in its units; a vector as three numbers

    Raises ConstantError (a ValueError) for an unknown scene, constant or integrator or a bad
    value, before anything is drawn; RuntimeError outside a Jupyter notebook, or when the page
    vpython was connected to has gone.
    """
    global _live
    assignments = _checked_arguments(name, scenario, preset, integrator, constants)
    if arrows is not None:
        try:
            arrows = parse_arrows(",".join(arrows))
        except (ValueError, TypeError) as problem:
            raise ShowError(str(problem)) from None
    try:
        setup = catalog.configure(name, scenario=scenario, preset=preset, assignments=assignments)
        if integrator is not None and integrator not in INTEGRATORS:
            raise ConstantError(f"unknown integrator {integrator!r} (choose from {', '.join(INTEGRATORS)})")
        model = setup.build()
        integrator = integrator or model.default_integrator or DEFAULT_INTEGRATOR
        check_live_cost(model, integrator)
    except ValueError as problem:   # ConstantError, or the physics refusing these constants: one line
        raise ShowError(str(problem)) from None
    _require_notebook()
    _require_live_page()
    stop()
    vp = _vpython_for_this_cell()
    from .view import SceneView

    link = NotebookLink()
    view = SceneView(setup=setup, model=model, integrator=integrator, server=link, preset=preset,
                     arrows=arrows)
    task = asyncio.get_running_loop().create_task(_animate(view, link))
    task.add_done_callback(_report_failure)
    _live = (task, view)


def stop() -> None:
    """Stop the running scene, if any.

    Its 3-D view and graphs are removed, as a browser keeps only a few WebGL canvases alive at
    once; its caption stays and says that it stopped.
    """
    global _live
    if _live is None:
        return
    task, view = _live
    _live = None
    task.cancel()
    view.close("<b>Stopped:</b> show() ran again, so this scene no longer updates.")


async def _animate(view, link) -> None:
    while True:
        link.pump()
        await asyncio.sleep(view.frame())


def _report_failure(task) -> None:
    if not task.cancelled() and task.exception() is not None:
        traceback.print_exception(task.exception(), file=sys.stderr)


def _require_notebook() -> None:
    shell = getattr(sys.modules.get("IPython"), "get_ipython", lambda: None)()
    if type(shell).__name__ != "ZMQInteractiveShell":
        raise RuntimeError("browser.notebook.show() runs in a Jupyter notebook; "
                           "elsewhere use: python main.py NAME")


def _require_live_page() -> None:
    connection = sys.modules.get("vpython.with_notebook")
    if connection is not None and not connection.t.is_alive():  # t: its websocket server's thread
        raise PageGone("the notebook page vpython was connected to has gone (reloaded or "
                       "reopened): restart the kernel (Kernel > Restart Kernel), then run the cells again")


def _vpython_for_this_cell():
    """vpython, with a new canvas in the output of the cell that is running.

    vpython shows a canvas in the output of the cell that creates it. `import vpython` creates
    the default one, vpython.scene, which SceneView draws on; a later show() makes a new canvas
    and makes it vpython.scene.
    """
    first = "vpython" not in sys.modules
    vp = importlib.import_module("vpython")
    if "vpython.with_notebook" not in sys.modules:
        with _loopback_websocket():
            importlib.import_module("vpython.with_notebook")  # returns once the page has connected
    if not first:
        vp.scene = vp.canvas()
    return vp


@contextlib.contextmanager
def _loopback_websocket():
    """While vpython.with_notebook starts its websocket server, bind it to localhost only.

    vpython calls tornado's listen(port) with no address, which listens on every interface.
    jupyter-server-proxy, which carries the page's messages, connects to localhost.
    """
    from tornado.tcpserver import TCPServer

    real_listen = TCPServer.listen

    def listen(self, port, address=None, *args, **kwargs):
        if not address and sys._getframe(1).f_globals.get("__name__") == "vpython.with_notebook":
            address = "localhost"
        return real_listen(self, port, address, *args, **kwargs)

    TCPServer.listen = listen
    try:
        yield
    finally:
        TCPServer.listen = real_listen

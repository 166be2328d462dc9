"""start(): serve vpython's page on 127.0.0.1, and return once a browser page has connected.

The port is bound and listening before the URL is printed, and vpython's HTTP server takes over
that very socket: a browser pointed at the URL at once connects, and its request waits in the
socket's queue while vpython loads. Importing vpython's server blocks until a browser connects
(vpython waits in a silent loop), so start() reminds on stderr, once, if none has come after a while.
"""

from __future__ import annotations

import errno
import importlib
import os
import signal
import socket
import sys
import threading

from .patches import patched
from .state import LOOPBACK, ServerError, ServerInfo, ServerState

LISTEN_QUEUE = 64  # connections that may wait for the HTTP server (a browser opens several)

_current: ServerState | None = None  # the server start() made (one per process)


def interrupted() -> bool:
    """True if the user pressed Ctrl-C, as opposed to the page closing.

    Both end the program the same way, with SystemExit(0) from vpython's SIGINT handler (its
    websocket sends SIGINT to its own process when the page closes); the command line tells them
    apart with this, to exit with status 130 after a Ctrl-C as it does everywhere else.
    """
    return _current is not None and _current.interrupted


def start(*, port: int | None = None, open_browser: bool = True,
          remind_after: float = 10.0) -> ServerInfo:
    """Serve the VPython page on 127.0.0.1 and return once a browser page has connected.

    port None picks a free port. A busy or invalid port raises ServerError before vpython is
    imported (vpython itself would swallow the bind error and crash later with a NameError).
    Call this before anything else makes a vpython object: the servers start only once.
    Ctrl-C, or closing the page once connected, ends the program with status 0.
    """
    global _current
    if "vpython.no_notebook" in sys.modules:
        raise ServerError("vpython's server is already running; call start() before making "
                          "any vpython object")
    state = _current = ServerState.on(reserve(port), open_browser=open_browser)
    http_port = state.reservation.getsockname()[1]
    waiting = threading.Event()
    # Until vpython installs its own SIGINT handler, Ctrl-C only sets a flag: a KeyboardInterrupt
    # raised in the middle of importing numpy/pkg_resources can be swallowed or turned into
    # another error, leaving the program waiting for a browser.
    previous_handler = signal.signal(signal.SIGINT, lambda *_: setattr(state, "interrupted", True))
    try:
        announce(state, remind_after, waiting)
        import_vpython_servers(state)
    except Exception as exc:
        if state.interrupted:  # our SystemExit landed in one of vpython's bare `except: pass`
            raise SystemExit(0) from None
        signal.signal(signal.SIGINT, previous_handler)
        if state.bind_error is not None:
            raise ServerError(f"cannot serve on port {http_port}: {state.bind_error.strerror}; "
                              "pick another with --port") from exc
        raise
    finally:
        waiting.set()
        if not state.handed_over:
            state.reservation.close()
    return ServerInfo(url=state.url, http_port=http_port, socket_port=state.socket_port, life=state.life,
                      uploads=state.uploads)


def announce(state: ServerState, remind_after: float, waiting: threading.Event) -> None:
    """Print the URL, and remind on stderr once if `waiting` is not set after `remind_after` s."""
    os.environ["VPYTHON_HTTP_PORT"] = str(state.reservation.getsockname()[1])
    os.environ["VPYTHON_NO_LAUNCH_BROWSER"] = "1"  # we open 127.0.0.1 ourselves
    print(f"Opening {state.url} in your browser" if state.open_browser else f"Open {state.url} in a browser",
          flush=True)
    if remind_after and remind_after > 0:
        threading.Thread(target=remind, args=(state.url, remind_after, waiting),
                         name="vpython-wait-reminder", daemon=True).start()


def import_vpython_servers(state: ServerState) -> None:
    """Import vpython, then start its servers with our corrections; returns once a page connected."""
    with patched(state):
        importlib.import_module("vpython")  # slow (numpy, pkg_resources); no server yet
        if state.interrupted:
            raise SystemExit(0)
        # Starts both servers, then blocks until the page has fetched "/" and connected.
        importlib.import_module("vpython.no_notebook")


def reserve(port: int | None) -> socket.socket:
    """Bind and listen on 127.0.0.1:port (0 = any free one) now, to fail early with a clear message.

    vpython's HTTP server later serves from this same socket (see http_server.py), so the URL
    works from the moment it is printed: connections made while vpython still loads wait in the
    listen queue. Holding the port also keeps vpython's own pick of a free websocket port off it.
    """
    if port is None:
        port = 0
    elif isinstance(port, bool) or not isinstance(port, int) or not 1 <= port <= 65535:
        raise ServerError(f"invalid port {port!r}: use a whole number from 1 to 65535")
    sock = socket.socket()
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as HTTPServer does
    try:
        sock.bind((LOOPBACK, port))
    except OSError as exc:
        sock.close()
        raise ServerError(f"port {port} {_refused_because(exc)}; pick another with --port") from None
    sock.listen(LISTEN_QUEUE)
    return sock


def _refused_because(exc: OSError) -> str:
    if exc.errno == errno.EADDRINUSE:
        return "is already in use"
    if exc.errno == errno.EACCES:
        return "needs administrator rights"
    return f"cannot be used ({exc.strerror})"


def remind(url: str, every: float, stop: threading.Event) -> None:
    """Say once, `every` seconds after the address was printed, that no browser has come (a line
    every 10 s without end buried the address)."""
    if not stop.wait(every):
        print(f"Still waiting for a browser: open {url} (Ctrl-C to quit)",
              file=sys.stderr, flush=True)

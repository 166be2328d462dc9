"""Every point where vpython 7.6.5 is corrected, in one place.

vpython's two servers are made by the import-time code of ``vpython/no_notebook.py``, so the
corrections must be in place while start() imports that module (later would be too late); they
are undone as soon as the import returns. vpython's own objects are recognised by the module
that defined them (``made_by_vpython``); anything else passes through unchanged.

====================================  =====================================  ========================================
Patched while vpython.no_notebook     What vpython 7.6.5 does                What we do instead
imports
====================================  =====================================  ========================================
``http.server.HTTPServer``            binds ``('', port)``: every network    serves from the socket start() bound on
                                      interface; its handler glues the       127.0.0.1; answers only "/", "/status",
                                      requested path onto the current        "/loading" and vpython's own files, by
                                      directory without checking it, so any  exact name, to requests addressed to
                                      .html/.js/.png/... on the disk can be  127.0.0.1:PORT or localhost:PORT
                                      read (``/../secret.png``)              (``http_server.py``)
``BaseEventLoop.create_server``,      binds ``'0.0.0.0'``; accepts any       binds 127.0.0.1; refuses foreign
for vpython's websocket factory       Origin; *any* closed connection (a     Origins and second tabs; only the page's
                                      bare TCP connect, a refused            own connection may end the program, once
                                      handshake) sends SIGINT to the         it has not come back (``websocket.py``,
                                      process, so any web page can stop it   ``lifecycle.py``)
``threading.Thread``, for threads     its server threads are not daemons     makes them daemons
running vpython's or our server       (except on Windows), so a Ctrl-C
                                      before the page connects would hang
                                      at exit
``signal.signal``, for vpython's      its handler stops both servers, which  a plain SystemExit(0) until the page has
SIGINT handler                        may be half made before the page       connected (``sigint_handler``)
                                      connects (NameError, or a shutdown()
                                      that waits forever)
====================================  =====================================  ========================================

Two of vpython's module variables are also set where vpython's own code would have set them:
``no_notebook.httpserving = True`` when "/" is fetched (vpython's do_GET does that, and its
import waits for it), and ``vpython.baseObj.sent = True`` after each message (vpython leaves
it clear if the page closes mid-reply, and every new object would then wait for it forever).
"""

from __future__ import annotations

import asyncio.base_events
import contextlib
import http.server
import signal
import threading

from .http_server import http_server_class
from .state import ServerState
from .websocket import create_server_wrapper, made_by_vpython


@contextlib.contextmanager
def patched(state: ServerState):
    """While vpython starts its servers: loopback servers, daemon threads, a safe Ctrl-C."""
    loop_class = asyncio.base_events.BaseEventLoop
    saved = (http.server.HTTPServer, loop_class.create_server, threading.Thread, signal.signal)
    server_class = http_server_class(state)
    http.server.HTTPServer = server_class
    loop_class.create_server = create_server_wrapper(saved[1], state)
    threading.Thread = daemon_thread_class(saved[2], server_class)
    signal.signal = sigint_setter(saved[3], state)
    try:
        yield
    finally:
        http.server.HTTPServer, loop_class.create_server, threading.Thread, signal.signal = saved


def daemon_thread_class(real_thread, server_class):
    """threading.Thread, making daemons of the threads that run vpython's servers."""

    class Thread(real_thread):
        def __init__(self, *args, **kwargs):
            target = kwargs.get("target")
            if made_by_vpython(target) or isinstance(getattr(target, "__self__", None), server_class):
                kwargs["daemon"] = True
            real_thread.__init__(self, *args, **kwargs)  # not super(): threading.Timer calls this too

    return Thread


def sigint_setter(real_signal, state: ServerState):
    """signal.signal, wrapping vpython's SIGINT handler in sigint_handler."""

    def set_signal(signum, handler):
        if signum != signal.SIGINT or not made_by_vpython(handler):
            return real_signal(signum, handler)
        previous = real_signal(signum, sigint_handler(handler, state))
        if state.interrupted:  # Ctrl-C while vpython was loading; no server started yet
            raise SystemExit(0)
        return previous

    return set_signal


def sigint_handler(vpython_handler, state: ServerState):
    """vpython's SIGINT handler once the page is connected; a plain exit before that.

    vpython's handler (stop both servers, sys.exit(0)) is also how it quits when the page
    closes: its websocket onClose sends SIGINT to the process. Before the page connects,
    its servers may be half made (NameError, or a shutdown() that waits forever).
    """
    def handler(signum, frame):
        if state.life.connected:
            state.interrupted = state.interrupted or not state.life.page_closed
            return vpython_handler(signum, frame)
        state.interrupted = True
        raise SystemExit(0)  # our patches made vpython's threads daemons: nothing to stop

    return handler

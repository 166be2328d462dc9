"""Start VPython's browser view on this computer only (127.0.0.1), without its two holes.

VPython 7.6.5 (outside Jupyter) runs its own two servers, started by the module-level code of
``vpython/no_notebook.py`` when that module is first imported, which vpython does when the first
object other than the canvas is made (``import vpython`` alone does not start them):

* an HTTP server for the page (``glowcomm.html``) and its scripts, fonts and textures;
* a websocket server that the page talks to about every 17 ms.

Both listen on every network interface (``''`` and ``'0.0.0.0'``), and:

1. The HTTP handler glues the requested path onto the current directory (then onto its library
   folders) without checking it, so anyone who can reach the port can read any
   .html/.js/.css/.png/.jpg/.ttf/.otf/.ico file on the disk:
   ``curl --path-as-is http://HOST:PORT/../secret.png``.
2. The websocket server accepts any Origin, and when *any* connection to it closes, even a bare
   TCP connect or a refused handshake, it sends SIGINT to its own process. So any web page the
   user visits, or any machine on the network, can stop the program.

We don't fork vpython. ``start()`` imports ``vpython.no_notebook`` itself, with temporary
patches in place (its servers are made by import-time code, so later would be too late):

* ``http.server.HTTPServer`` becomes a server bound to 127.0.0.1 whose handler answers ``/``
  (vpython's page) and the files that exist in vpython's own ``vpython_libraries/`` (and its
  ``images/``) and ``vpython_data/`` folders, looked up by exact name. Anything else is 404, so no
  path can climb out, and nothing is served from the current directory.
* asyncio's ``create_server``, for vpython's websocket factory only, binds 127.0.0.1 and uses a
  protocol subclass that refuses foreign Origins, lets only a connection that really opened stop
  the program, and notes when the page last spoke (``ServerInfo.last_contact()``).
* vpython's server threads are made daemons and its SIGINT handler is wrapped, so that Ctrl-C
  also quits cleanly before the page has connected (vpython's own handler can raise NameError
  or wait forever if its servers are only half made).

That import blocks until a browser connects (vpython waits in a silent loop), so ``start()``
prints the URL first and reminds on stderr while it waits. The port is bound and listening before
the URL is printed, and vpython's HTTP server takes over that very socket: a browser pointed at the
URL at once connects, and its request waits in the socket's queue while vpython loads. Once connected, vpython's own SIGINT
handler ends the program with status 0 on Ctrl-C or when the page is closed (its websocket
onClose sends SIGINT to its own process).

Importing this module does not import vpython.
"""

from __future__ import annotations

import contextlib
import errno
import importlib
import math
import os
import signal
import socket
import sys
import threading
import time
import webbrowser
from dataclasses import dataclass, field
from urllib.parse import unquote

LOOPBACK = "127.0.0.1"
LISTEN_QUEUE = 64  # connections that may wait for the HTTP server (a browser opens several)

# What the page may fetch besides "/", by file extension.
_CONTENT_TYPES = {
    ".html": "text/html",
    ".js": "application/javascript",
    ".css": "text/css",
    ".png": "image/png",
    ".gif": "image/gif",
    ".jpg": "image/jpeg",
    ".ttf": "font/ttf",
    ".otf": "font/otf",
    ".ico": "image/x-icon",
}

_Thread = threading.Thread  # the real one, also while _patched replaces it
_current: "_State | None" = None  # the server start() made (one per process)
_last_contact: float | None = None  # time.monotonic() of the page's last message
_page_loads = 0  # how many times a page has connected: a reload connects again
_page_built = 1  # the page load the scene has been built on (the first page gets it as it is made)
CLOSE_GRACE = 0.5  # s: after the page closes, the program ends this long after, unless it comes back
RELOAD_WAIT = 20.0  # s: how long a reload (the page fetched again as it closed) may take to connect
RELOAD_FETCH = 5.0  # s: a page fetched this long before the open page closed counts as its reload
REPORT_EVERY = 5.0  # s: refused connections are summed up on stderr at most this often


# Added to vpython's page: when its websocket closes, say why on the page instead of leaving it
# blank or frozen (vpython's own page only tries window.close(), which browsers ignore for a tab
# the user opened). /status tells a second tab ("busy") from a program that has ended.
TAB_SCRIPT = """<script>
(function () {
  var Real = window.WebSocket;
  function say(html) {
    var box = document.getElementById('tab-message') || document.createElement('div');
    box.id = 'tab-message';
    box.style.cssText = 'position:fixed;top:0;left:0;right:0;z-index:1000;padding:16px;' +
      'background:#fff4c2;color:#222;font:20px sans-serif;border-bottom:2px solid #c90';
    box.innerHTML = html;
    document.body.appendChild(box);
  }
  window.WebSocket = function (url, protocols) {
    var ws = protocols === undefined ? new Real(url) : new Real(url, protocols);
    var opened = false;
    ws.addEventListener('open', function () { opened = true; });
    ws.addEventListener('close', function () {
      fetch('/status', {cache: 'no-store'}).then(function (r) { return r.text(); }).then(function (t) {
        if (t === 'busy') {
          say('This scene is already open in another tab. Use that tab, or close it and reload this one.');
        } else if (opened) {
          say('The connection to the program was lost. Reload this tab to see the scene again.');
        } else {
          say('This page could not connect to the program. Reload this tab to try again.');
        }
      }, function () {
        say('The program has ended, so this page no longer changes. ' +
            'Run <code>python main.py</code> again to start it.');
      });
    });
    return ws;
  };
  window.WebSocket.prototype = Real.prototype;
  ['CONNECTING', 'OPEN', 'CLOSING', 'CLOSED'].forEach(function (k) { window.WebSocket[k] = Real[k]; });
})();
</script>
"""


class ServerError(RuntimeError):
    """The view cannot start: a bad or busy port, or vpython was imported too early."""


@dataclass(frozen=True)
class ServerInfo:
    """Where the view is served, and when the page last spoke."""

    url: str
    http_port: int
    socket_port: int

    def last_contact(self) -> float:
        """time.monotonic() of the page's last message (or of its connecting, before any).

        The page asks for updates about every 17 ms while it is visible; browsers slow or stop
        that when the tab is hidden, so a scene can use this to pause its clock.
        """
        return _last_contact if _last_contact is not None else time.monotonic()

    def seconds_since_contact(self) -> float:
        return time.monotonic() - self.last_contact()

    def page_loads(self) -> int:
        """How many times a page has connected; it goes up when the tab is reloaded, and the
        reloaded page is empty until the scene is built on it again."""
        return _page_loads

    def page_built(self, load: int) -> None:
        """The scene has been built again for page load `load`: send that page its updates.

        Until then a reloaded page is answered with no updates at all, since vpython's queue
        still holds changes to objects of the old page, which the new one would choke on.
        """
        global _page_built
        _page_built = load


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
    if "vpython.no_notebook" in sys.modules:
        raise ServerError("vpython's server is already running; call start() before making "
                          "any vpython object")
    global _current
    state = _current = _State(reservation=_reserve(port))
    http_port = state.reservation.getsockname()[1]
    state.url = url = f"http://{LOOPBACK}:{http_port}/"
    state.origins = {f"http://{host}:{http_port}" for host in (LOOPBACK, "localhost")}
    state.hosts = {f"{host}:{http_port}" for host in (LOOPBACK, "localhost")}
    state.refusals = _Refusals()
    state.open_browser = open_browser
    waiting = threading.Event()
    # Until vpython installs its own SIGINT handler, Ctrl-C only sets a flag: a KeyboardInterrupt
    # raised in the middle of importing numpy/pkg_resources can be swallowed or turned into
    # another error, leaving the program waiting for a browser.
    previous_handler = signal.signal(signal.SIGINT, lambda *_: setattr(state, "interrupted", True))
    try:
        os.environ["VPYTHON_HTTP_PORT"] = str(http_port)
        os.environ["VPYTHON_NO_LAUNCH_BROWSER"] = "1"  # we open 127.0.0.1 ourselves
        print(f"Opening {url} in your browser" if open_browser else f"Open {url} in a browser",
              flush=True)
        if remind_after and remind_after > 0:
            threading.Thread(target=_remind, args=(url, remind_after, waiting),
                             name="vpython-wait-reminder", daemon=True).start()
        with _patched(state):
            importlib.import_module("vpython")  # slow (numpy, pkg_resources); no server yet
            if state.interrupted:
                raise SystemExit(0)
            # Starts both servers, then blocks until the page has fetched "/" and connected.
            importlib.import_module("vpython.no_notebook")
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
    return ServerInfo(url=url, http_port=http_port, socket_port=state.socket_port)


@dataclass
class _State:
    reservation: socket.socket
    handed_over: bool = False  # the HTTP server has taken the reservation socket over
    url: str = ""
    origins: set[str] = field(default_factory=set)  # the page's own Origin header values
    open_browser: bool = False
    socket_port: int = 0
    bind_error: OSError | None = None
    connected: bool = False  # the page's websocket has opened
    interrupted: bool = False  # the user pressed Ctrl-C (before or after the page connected)
    page_closed: bool = False  # the page closed and did not come back: vpython's SIGINT ends the program
    hosts: set[str] = field(default_factory=set)  # Host header values the HTTP server answers
    pages: set = field(default_factory=set)  # open websocket connections of the page (at most one)
    closing: object = None  # the timer that ends the program once the last page has closed
    fetched: float = -math.inf  # time.monotonic() when the page ("/") was last fetched
    fetched_while_open: float = -math.inf  # ... while a page was connected: a reload, or a second tab
    refusals: "_Refusals | None" = None


def _reserve(port: int | None) -> socket.socket:
    """Bind and listen on 127.0.0.1:port (0 = any free one) now, to fail early with a clear message.

    vpython's HTTP server later serves from this same socket (see _http_server_class), so the URL
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
        if exc.errno == errno.EADDRINUSE:
            reason = "is already in use"
        elif exc.errno == errno.EACCES:
            reason = "needs administrator rights"
        else:
            reason = f"cannot be used ({exc.strerror})"
        raise ServerError(f"port {port} {reason}; pick another with --port") from None
    sock.listen(LISTEN_QUEUE)
    return sock


class _Refusals:
    """Refused connections and ignored messages, summed up on stderr at most every REPORT_EVERY s.

    A hostile page can knock thousands of times a second; the teacher's terminal gets one line
    every few seconds saying how many, and why, instead of one line each. The first line waits
    GATHER s, so that one burst is one line.
    """

    GATHER = 1.0  # s

    def __init__(self, stream=None, every: float = REPORT_EVERY):
        self.stream, self.every = stream, every
        self.lock = threading.Lock()
        self.counts: dict[str, int] = {}
        self.last_report = -math.inf
        self.pending = False

    def add(self, reason: str) -> None:
        with self.lock:
            self.counts[reason] = self.counts.get(reason, 0) + 1
            if self.pending:
                return
            self.pending = True
            wait = max(self.GATHER, self.last_report + self.every - time.monotonic())
        # threading.Timer would not do: while vpython loads, threading.Thread is patched.
        _Thread(target=lambda: (time.sleep(wait), self.report()), name="refusal-report", daemon=True).start()

    def report(self) -> None:
        with self.lock:
            counts, self.counts, self.pending = self.counts, {}, False
            self.last_report = time.monotonic()
        if counts:
            total = sum(counts.values())
            parts = "; ".join(f"{count} {reason}" for reason, count in counts.items())
            print(f"note: refused {total} connection{'s' if total != 1 else ''} or message"
                  f"{'s' if total != 1 else ''} ({parts}); the page here is unaffected",
                  file=self.stream or sys.stderr, flush=True)


def _remind(url: str, every: float, stop: threading.Event) -> None:
    """Say once, `every` seconds after the address was printed, that no browser has come (a line
    every 10 s without end buried the address)."""
    if not stop.wait(every):
        print(f"Still waiting for a browser: open {url} (Ctrl-C to quit)",
              file=sys.stderr, flush=True)


def _open_browser(url: str) -> None:
    """Ask the system's browser to open the page; if there is none, say so once, and how to open it."""
    if not webbrowser.open(url):
        print(f"No browser was found on this computer: open {url} in a browser yourself "
              f"(Ctrl-C to quit)", file=sys.stderr, flush=True)


@contextlib.contextmanager
def _patched(state: _State):
    """While vpython starts its servers: loopback servers, daemon threads, a safe Ctrl-C."""
    import asyncio.base_events
    import http.server

    saved = (http.server.HTTPServer, asyncio.base_events.BaseEventLoop.create_server,
             threading.Thread, signal.signal)
    real_thread, real_signal = threading.Thread, signal.signal

    class Thread(real_thread):
        # vpython's server threads are not daemons (except on Windows), so a Ctrl-C before the
        # page connects, when vpython's handler can't stop them cleanly yet, would hang at exit.
        def __init__(self, *args, **kwargs):
            if sys._getframe(1).f_globals.get("__name__") == "vpython.no_notebook":
                kwargs["daemon"] = True
            super().__init__(*args, **kwargs)

    def set_signal(signum, handler):
        if signum != signal.SIGINT or getattr(handler, "__module__", "") != "vpython.no_notebook":
            return real_signal(signum, handler)
        previous = real_signal(signum, _sigint_handler(handler, state))
        if state.interrupted:  # Ctrl-C while vpython was loading; no server started yet
            raise SystemExit(0)
        return previous

    http.server.HTTPServer = _http_server_class(state)
    asyncio.base_events.BaseEventLoop.create_server = _create_server(saved[1], state)
    threading.Thread = Thread
    signal.signal = set_signal
    try:
        yield
    finally:
        (http.server.HTTPServer, asyncio.base_events.BaseEventLoop.create_server,
         threading.Thread, signal.signal) = saved


def _sigint_handler(vpython_handler, state: _State):
    """vpython's SIGINT handler once the page is connected; a plain exit before that.

    vpython's handler (stop both servers, sys.exit(0)) is also how it quits when the page
    closes: its websocket onClose sends SIGINT to the process. Before the page connects,
    its servers may be half made (NameError, or a shutdown() that waits forever).
    """
    def handler(signum, frame):
        if state.connected:
            state.interrupted = state.interrupted or not state.page_closed
            return vpython_handler(signum, frame)
        state.interrupted = True
        raise SystemExit(0)  # our patches made vpython's threads daemons: nothing to stop

    return handler


def _http_server_class(state: _State):
    from http.server import ThreadingHTTPServer

    class LoopbackHTTPServer(ThreadingHTTPServer):
        """Replaces vpython's HTTPServer(('', port), serveHTTP)."""

        daemon_threads = True

        def __init__(self, address, handler_class):
            # Serve from the socket start() bound and has listened on since it printed the URL
            # (vpython asks for ('', port); we ignore the address). No new bind, so no bind error.
            try:
                super().__init__((LOOPBACK, 0), _safe_handler(handler_class, state), bind_and_activate=False)
            except OSError as exc:
                state.bind_error = exc  # vpython swallows it; start() reports it
                raise
            self.socket.close()
            self.socket, state.handed_over = state.reservation, True
            self.server_address = self.socket.getsockname()
            self.server_name, self.server_port = LOOPBACK, self.server_address[1]
            if state.open_browser:  # the page's first request queues until serve_forever
                _open_browser(state.url)

        def handle_error(self, request, client_address):
            # socketserver prints a traceback for any error in a request. A browser that drops
            # a connection mid-reply (a reload, a closed tab) is normal; anything else is one line.
            problem = sys.exc_info()[1]
            if not isinstance(problem, (ConnectionError, TimeoutError)):
                print(f"note: a request to the page's server failed: {type(problem).__name__}: {problem}",
                      file=sys.stderr, flush=True)

        def serve_forever(self, poll_interval=0.05):
            # vpython's quit path calls shutdown(), which waits for this loop to notice; with
            # the default 0.5 s poll that alone could take half a second.
            super().serve_forever(poll_interval)

    return LoopbackHTTPServer


def _safe_handler(vpython_handler, state: _State):
    """vpython's request handler, answering only "/", "/status" and vpython's library and data
    files, and only to requests addressed to this program's own host name and port."""
    package_dir = os.path.dirname(sys.modules[vpython_handler.__module__].__file__)
    files = {}  # URL path -> file on disk
    for folder, prefix in (("vpython_data", "/"), ("vpython_libraries", "/"),
                           (os.path.join("vpython_libraries", "images"), "/images/")):
        for entry in os.scandir(os.path.join(package_dir, folder)):
            if entry.is_file() and os.path.splitext(entry.name)[1] in _CONTENT_TYPES:
                files[prefix + entry.name] = entry.path

    vpython_server = sys.modules[vpython_handler.__module__]
    page = vpython_server.glowcomm.replace("</head>", TAB_SCRIPT + "</head>", 1)

    class SafeHandler(vpython_handler):
        timeout = 10  # seconds; drop idle connections

        def do_GET(self):
            # A page from another site can point a DNS name at 127.0.0.1 (DNS rebinding); its
            # requests then carry that name as Host, so only our own names are answered.
            if self.headers.get("Host", "") not in state.hosts:
                state.refusals.add("with a Host header other than this program's")
                return self.send_error(421, "this server answers only " + " or ".join(sorted(state.hosts)))
            path = unquote(self.path.split("?", 1)[0])
            if path == "/":
                vpython_server.httpserving = True  # what vpython's own handler notes: the page was fetched
                state.fetched = time.monotonic()
                if state.pages:
                    state.fetched_while_open = state.fetched
                return self._send(page.encode("utf-8"), "text/html; charset=utf-8", fresh=True)
            if path == "/status":  # asked by the page when its websocket closed: which message to show
                return self._send(b"busy" if state.pages else b"free", "text/plain", fresh=True)
            file = files.get(path)  # exact names only: "..", "%2e%2e", "//", "\\" never match
            if file is None:
                return self.send_error(404)
            with open(file, "rb") as f:
                self._send(f.read(), _CONTENT_TYPES[os.path.splitext(file)[1]])

        def _send(self, body: bytes, content_type: str, *, fresh: bool = False) -> None:
            self.send_response(200)
            self.send_header("Content-Type", content_type)
            self.send_header("Content-Length", str(len(body)))
            if fresh:  # the page names this run's websocket port; /status changes
                self.send_header("Cache-Control", "no-store")
            self.end_headers()
            self.wfile.write(body)

    return SafeHandler


def _create_server(original, state: _State):
    """asyncio's create_server, binding vpython's websocket server to 127.0.0.1 only."""

    async def create_server(loop, protocol_factory, host=None, port=None, *args, **kwargs):
        protocol = getattr(protocol_factory, "protocol", None)
        if getattr(protocol, "__module__", None) != "vpython.no_notebook":
            return await original(loop, protocol_factory, host, port, *args, **kwargs)
        protocol_factory.protocol = _guarded_protocol(protocol, state)
        server = await original(loop, protocol_factory, LOOPBACK, port, *args, **kwargs)
        state.socket_port = server.sockets[0].getsockname()[1]
        return server

    return create_server


class _Quiet:
    """A logger that says nothing: what matters is summed up by _Refusals instead."""

    def __getattr__(self, name):
        return lambda *args, **kwargs: None


def _guarded_protocol(vpython_protocol, state: _State):
    import asyncio

    from autobahn.exception import Disconnected
    from autobahn.websocket.types import ConnectionDeny
    from vpython.vpython import baseObj

    class GuardedWSserver(vpython_protocol):
        opened = False
        log = _Quiet()  # autobahn would print a line for every refused or dropped connection

        def onConnect(self, request):
            # Browsers always send Origin; a page from anywhere else must not drive (or stop) us.
            if request.origin not in state.origins:
                state.refusals.add("from another web page or program")
                raise ConnectionDeny(ConnectionDeny.FORBIDDEN, "origin not allowed")
            # A second tab would take half of the page's updates: it gets a message instead
            # (TAB_SCRIPT asks /status), and closing it does not end the program.
            if state.pages:
                state.refusals.add("from a second tab of the page")
                state.fetched_while_open = -math.inf  # that fetch was this tab's, not a reload's
                raise ConnectionDeny(409, "the page is already open in another tab")
            return super().onConnect(request)

        def onOpen(self):
            global _last_contact, _page_loads
            if state.pages:  # two tabs raced through onConnect: the first one keeps the page
                state.refusals.add("from a second tab of the page")
                self.sendClose(code=1000, reason="the page is already open in another tab")
                return
            if state.closing is not None:  # the page came back (a reload) before the program ended
                state.closing.cancel()
                state.closing = None
            state.fetched_while_open = -math.inf  # any reload it marked has now connected
            self.opened = state.connected = True
            state.pages.add(self)
            _last_contact = time.monotonic()
            _page_loads += 1
            super().onOpen()

        async def onMessage(self, data, isBinary):
            global _last_contact
            if not self.opened:
                return
            _last_contact = time.monotonic()
            if _page_loads > _page_built:  # a reloaded page, not built yet: "nothing new" keeps it asking
                self.sendMessage(b"trigger", isBinary=False)
                return
            try:
                await super().onMessage(data, isBinary)
            except Disconnected:  # the page closed while vpython was replying; onClose follows
                pass
            except Exception:  # not something the page sends: ignored, and counted
                state.refusals.add("message the page could not have sent, ignored")
            finally:
                # vpython clears this while it copies its updates and sets it once they are sent;
                # left clear (the page closed mid-reply), every new vpython object would wait forever.
                baseObj.sent = True

        def onClose(self, wasClean, code, reason):
            # vpython's onClose sends SIGINT to the process; autobahn calls it for every lost
            # connection, even refused ones. Only the page's own connection may end the program,
            # and only if no page connects again within CLOSE_GRACE (a reload closes, then connects).
            if not self.opened:
                return
            state.pages.discard(self)
            if state.pages:
                return
            closed, loop = time.monotonic(), asyncio.get_event_loop()

            def end_unless_back():
                if state.pages:
                    return
                # A reload fetches the page again before the old one closes (a busy browser may
                # take a second between the two; some browsers close first); its scripts may
                # take seconds to load before it connects, so wait for it (within reason).
                reloading = state.fetched_while_open > closed - RELOAD_FETCH or state.fetched > closed
                if reloading and time.monotonic() - closed < RELOAD_WAIT:
                    state.closing = loop.call_later(0.1, end_unless_back)
                    return
                state.page_closed = True  # the SIGINT vpython sends itself now is not a Ctrl-C
                super(GuardedWSserver, self).onClose(wasClean, code, reason)

            state.closing = loop.call_later(CLOSE_GRACE, end_unless_back)

    return GuardedWSserver

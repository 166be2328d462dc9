"""The page's HTTP server: vpython's, on 127.0.0.1 only, answering only what the page needs.

It serves "/" (vpython's page, with tab.js added at the top of its head), "/status" and
"/loading" (asked by tab.js), takes a POST to "/data" (the bytes of a file the page's Load data
button read, from the page's own Origin only, at most lab.readers.MAX_BYTES), and the files that exist in vpython's own ``vpython_libraries/``
(and its ``images/``) and ``vpython_data/`` folders, looked up by exact name. Anything else is
404, so no path can climb out, and nothing is served from the current directory. Only requests
addressed to this program's own host name and port are answered (421 otherwise).
"""

from __future__ import annotations

import os
import sys
import webbrowser
from http.server import ThreadingHTTPServer
from pathlib import Path
from urllib.parse import unquote

from lab.readers import MAX_BYTES

from .state import LOOPBACK, ServerState

# What the page may fetch besides "/", by file extension.
CONTENT_TYPES = {
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
TAB_SCRIPT = Path(__file__).with_name("tab.js")


def open_browser(url: str) -> None:
    """Ask the system's browser to open the page; if there is none, say so once, and how to open it."""
    if not webbrowser.open(url):
        print(f"No browser was found on this computer: open {url} in a browser yourself "
              f"(Ctrl-C to quit)", file=sys.stderr, flush=True)


def http_server_class(state: ServerState):
    """A class to stand in for vpython's HTTPServer, serving from the socket start() reserved."""

    class LoopbackHTTPServer(ThreadingHTTPServer):
        """Replaces vpython's HTTPServer(('', port), serveHTTP)."""

        daemon_threads = True

        def __init__(self, address, handler_class):
            # Serve from the socket start() bound and has listened on since it printed the URL
            # (vpython asks for ('', port); we ignore the address). No new bind, so no bind error.
            try:
                super().__init__((LOOPBACK, 0), safe_handler(handler_class, state), bind_and_activate=False)
            except OSError as exc:
                state.bind_error = exc  # vpython swallows it; start() reports it
                raise
            self.socket.close()
            self.socket, state.handed_over = state.reservation, True
            self.server_address = self.socket.getsockname()
            self.server_name, self.server_port = LOOPBACK, self.server_address[1]
            if state.open_browser:  # the page's first request queues until serve_forever
                open_browser(state.url)

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


def page_files(package_dir: str) -> dict[str, str]:
    """URL path -> file on disk, for every file the page may fetch from vpython's folders."""
    files = {}
    for folder, prefix in (("vpython_data", "/"), ("vpython_libraries", "/"),
                           (os.path.join("vpython_libraries", "images"), "/images/")):
        for entry in os.scandir(os.path.join(package_dir, folder)):
            if entry.is_file() and os.path.splitext(entry.name)[1] in CONTENT_TYPES:
                files[prefix + entry.name] = entry.path
    return files


def browser_loads_it(headers) -> bool:
    """Whether a request for "/" is a browser loading the page (a tab, a reload).

    A fetch that no page follows (curl, a script, a browser's prefetch) must not make the
    program wait for a reload when the open page closes. Browsers say which is which in
    Sec-Fetch-Mode (Chrome 76, Firefox 90, Safari 16.4 and later); with an older one, the page's
    first script asks for "/loading" as it starts, which counts instead.
    """
    prefetch = "prefetch" in headers.get("Sec-Purpose", "") + headers.get("Purpose", "")
    return headers.get("Sec-Fetch-Mode") == "navigate" and not prefetch


def safe_handler(vpython_handler, state: ServerState):
    """vpython's request handler, answering only "/", "/status", "/loading" and vpython's library
    and data files, and only to requests addressed to this program's own host name and port."""
    vpython_server = sys.modules[vpython_handler.__module__]
    files = page_files(os.path.dirname(vpython_server.__file__))
    script = "<script>\n" + TAB_SCRIPT.read_text(encoding="utf-8") + "</script>\n"
    page = vpython_server.glowcomm.replace("<head>", "<head>\n" + script, 1).encode("utf-8")

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
                if browser_loads_it(self.headers):
                    state.life.fetched_by_browser()
                return self._send(page, "text/html; charset=utf-8", fresh=True)
            if path == "/loading":  # tab.js: a page fetched here is starting in a browser
                state.life.fetched_by_browser()
                return self._send(b"", "text/plain", fresh=True)
            if path == "/status":  # asked by the page when its websocket closed: which message to show
                return self._send(b"busy" if state.life.busy() else b"free", "text/plain", fresh=True)
            file = files.get(path)  # exact names only: "..", "%2e%2e", "//", "\\" never match
            if file is None:
                return self.send_error(404)
            with open(file, "rb") as f:
                self._send(f.read(), CONTENT_TYPES[os.path.splitext(file)[1]])

        def do_POST(self):
            # Only the page itself may send a file: our own Host (DNS rebinding) and our own
            # Origin (a form on another site can POST to 127.0.0.1, but not with our Origin).
            if self.headers.get("Host", "") not in state.hosts or \
                    self.headers.get("Origin", "") not in state.origins:
                state.refusals.add("a file sent from another web page or program")
                return self.send_error(403)
            if unquote(self.path.split("?", 1)[0]) != "/data":
                return self.send_error(404)
            try:
                size = int(self.headers.get("Content-Length", ""))
            except ValueError:
                return self.send_error(411)
            if not 0 <= size <= MAX_BYTES:
                self.close_connection = True
                return self._send(f"the file is {size / 1e6:.0f} MB, more than the {MAX_BYTES // 2**20} MB "
                                  f"this program reads".encode(), "text/plain", status=413)
            raw = self.rfile.read(size)
            state.uploads.put(upload_name(self.headers.get("X-File-Name", "")), raw)
            return self._send(b"", "text/plain", fresh=True)

        def _send(self, body: bytes, content_type: str, *, fresh: bool = False, status: int = 200) -> None:
            self.send_response(status)
            self.send_header("Content-Type", content_type)
            self.send_header("Content-Length", str(len(body)))
            if fresh:  # the page names this run's websocket port; /status changes
                self.send_header("Cache-Control", "no-store")
            self.end_headers()
            self.wfile.write(body)

    return SafeHandler


def upload_name(header: str) -> str:
    """The name a sent file is called in messages: its base name (the page sends it URL-encoded),
    printable characters only, at most 80 of them; "the file" if there is none."""
    name = os.path.basename(unquote(header).replace("\\", "/"))
    name = "".join(c for c in name if c.isprintable())[:80].strip()
    return name or "the file"

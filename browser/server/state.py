"""What the loopback server knows, in one object (ServerState), and what start() hands back.

ServerState is made by start() and shared by the main thread, vpython's HTTP server threads and
its websocket event loop. Its addresses are written once, before any server runs; what changes
while they run is guarded by a lock: the page's life cycle (PageLife, with its own lock) and the
tally of refusals (Refusals).
"""

from __future__ import annotations

import math
import queue
import socket
import sys
import threading
import time
from dataclasses import dataclass, field

from .lifecycle import PageLife

LOOPBACK = "127.0.0.1"
REPORT_EVERY = 5.0  # s: refused connections are summed up on stderr at most this often


class ServerError(RuntimeError):
    """The view cannot start: a bad or busy port, or vpython was imported too early."""


class Refusals:
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
        timer = threading.Timer(wait, self.report)
        timer.daemon = True
        timer.start()

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


@dataclass(frozen=True)
class Upload:
    """A file the page's Load data button sent: its name (as the student's computer calls it) and bytes."""

    name: str
    raw: bytes


class Uploads:
    """Files the page sent (its Load data button: POST /data), waiting for the frame loop.

    The HTTP server's threads put an Upload; the frame loop takes them between frames. Only
    the newest file counts, so a student who picks twice in quick succession gets the second.
    """

    def __init__(self):
        self.waiting: queue.SimpleQueue = queue.SimpleQueue()

    def put(self, name: str, raw: bytes) -> None:
        self.waiting.put(Upload(name=name, raw=raw))

    def newest(self) -> Upload | None:
        """The newest file sent since the last call, None if none."""
        newest = None
        while True:
            try:
                newest = self.waiting.get_nowait()
            except queue.Empty:
                return newest


@dataclass
class ServerState:
    """Everything the loopback server knows about this run (one per process)."""

    reservation: socket.socket  # bound and listening on 127.0.0.1 since the URL was printed
    open_browser: bool = False
    url: str = ""
    origins: set[str] = field(default_factory=set)  # the page's own Origin header values
    hosts: set[str] = field(default_factory=set)  # Host header values the HTTP server answers
    handed_over: bool = False  # the HTTP server has taken the reservation socket over
    socket_port: int = 0
    bind_error: OSError | None = None
    interrupted: bool = False  # the user pressed Ctrl-C (before or after the page connected)
    life: PageLife = field(default_factory=PageLife)
    refusals: Refusals = field(default_factory=Refusals)
    uploads: Uploads = field(default_factory=Uploads)

    @classmethod
    def on(cls, reservation: socket.socket, *, open_browser: bool) -> "ServerState":
        """The state of a server about to serve from `reservation`, and the names it answers to."""
        port = reservation.getsockname()[1]
        names = (LOOPBACK, "localhost")
        return cls(reservation=reservation, open_browser=open_browser,
                   url=f"http://{LOOPBACK}:{port}/",
                   origins={f"http://{host}:{port}" for host in names},
                   hosts={f"{host}:{port}" for host in names})


@dataclass(frozen=True)
class ServerInfo:
    """Where the view is served, and when the page last spoke."""

    url: str
    http_port: int
    socket_port: int
    life: PageLife = field(repr=False, compare=False)
    uploads: Uploads = field(default_factory=Uploads, repr=False, compare=False)

    def last_contact(self) -> float:
        """time.monotonic() of the page's last message (or of its connecting, before any).

        The page asks for updates about every 17 ms while it is visible; browsers slow or stop
        that when the tab is hidden, so a scene can use this to pause its clock.
        """
        last = self.life.last_contact
        return last if last is not None else time.monotonic()

    def seconds_since_contact(self) -> float:
        return time.monotonic() - self.last_contact()

    def page_loads(self) -> int:
        """How many times a page has connected; it goes up when the tab is reloaded, and the
        reloaded page is empty until the scene is built on it again."""
        return self.life.loads

    def page_built(self, load: int) -> None:
        """The scene has been built again for page load `load`: send that page its updates.

        Until then a reloaded page is answered with no updates at all, since vpython's queue
        still holds changes to objects of the old page, which the new one would choke on.
        """
        self.life.scene_built(load)

    def uploaded(self) -> Upload | None:
        """The newest file the page's Load data button sent since the last call, None if none."""
        return self.uploads.newest()

"""The page's life cycle: one open page, its reloads, a second tab, and the end when it closes.

- **Open.** The first page to connect is *the* page; the program counts its loads (a reload
  connects again) and notes when it last spoke.
- **Second tab.** While a page is open, another connection is refused (it would take half of
  the updates); its tab shows a message, and closing it changes nothing.
- **Reload.** A browser reloading the tab fetches "/" again shortly before the old page closes
  (a busy browser may take a second between the two; some browsers close first), and the new
  page may take seconds to load its scripts before it connects. So after the page closes the
  program waits CLOSE_GRACE s, and longer (up to RELOAD_WAIT s) if a browser fetched the page
  within RELOAD_FETCH s before the close, or after it.
- **Close.** Otherwise the program ends: vpython's own onClose sends SIGINT to the process.

Only a browser loading the page counts as a fetch (browser/server/http_server.py tells): a bare
``GET /`` from curl or a prefetch, which no page follows, made the program wait 20 s to end.

The HTTP server's threads, the websocket's event loop and the main thread all use one
PageLife, so each change is made holding its lock.
"""

from __future__ import annotations

import math
import threading
import time

CLOSE_GRACE = 0.5  # s: after the page closes, the program ends this long after, unless it comes back
RELOAD_WAIT = 20.0  # s: how long a reload (the page fetched again as it closed) may take to connect
RELOAD_FETCH = 5.0  # s: a page fetched this long before the open page closed counts as its reload
RECHECK = 0.1  # s: while a reload is awaited, how often to look whether it has connected


class PageLife:
    """Which page is open, when a browser last fetched it, and when it last spoke."""

    def __init__(self):
        self.lock = threading.Lock()
        self.pages: set = set()  # open websocket connections of the page (at most one)
        self.connected = False  # a page's websocket has opened
        self.page_closed = False  # the page closed and did not come back: the program ends
        self.closing = None  # the event loop's timer that ends the program after the last close
        self.fetched = -math.inf  # time.monotonic() when a browser last fetched the page
        self.fetched_while_open = -math.inf  # ... while a page was connected: a reload, or a second tab
        self.last_contact: float | None = None  # time.monotonic() of the page's last message
        self.loads = 0  # how many times a page has connected: a reload connects again
        self.built = 1  # the page load the scene has been built on (the first page gets it as it is made)

    def fetched_by_browser(self) -> None:
        """A browser is loading the page: while a page is open, that is a reload or a second tab."""
        with self.lock:
            self.fetched = time.monotonic()
            if self.pages:
                self.fetched_while_open = self.fetched

    def busy(self) -> bool:
        """A page is open: another tab must not connect."""
        with self.lock:
            return bool(self.pages)

    def refuse_second_tab(self) -> bool:
        """True if a page is open, so a new connection is a second tab (its fetch was no reload)."""
        with self.lock:
            if self.pages:
                self.fetched_while_open = -math.inf
            return bool(self.pages)

    def open(self, page) -> bool:
        """The page's websocket opened; False if another page got there first (two tabs raced)."""
        with self.lock:
            if self.pages:
                return False
            if self.closing is not None:  # the page came back (a reload) before the program ended
                self.closing.cancel()
                self.closing = None
            self.fetched_while_open = -math.inf  # any reload it marked has now connected
            self.connected = True
            self.pages.add(page)
            self.last_contact = time.monotonic()
            self.loads += 1
            return True

    def spoke(self) -> bool:
        """The page sent a message; False while a reloaded page waits for the scene to be rebuilt."""
        with self.lock:
            self.last_contact = time.monotonic()
            return self.loads <= self.built

    def scene_built(self, load: int) -> None:
        with self.lock:
            self.built = load

    def close(self, page, loop, end) -> None:
        """The page's websocket closed: call end() on the event loop `loop` unless it comes back."""
        with self.lock:
            self.pages.discard(page)
            if self.pages:
                return
            closed = time.monotonic()
            self.closing = loop.call_later(CLOSE_GRACE, self._end_unless_back, closed, loop, end)

    def _end_unless_back(self, closed: float, loop, end) -> None:
        with self.lock:
            if self.pages:
                return
            if self._reload_due(closed) and time.monotonic() - closed < RELOAD_WAIT:
                self.closing = loop.call_later(RECHECK, self._end_unless_back, closed, loop, end)
                return
            self.page_closed = True  # the SIGINT vpython sends itself now is not a Ctrl-C
        end()

    def _reload_due(self, closed: float) -> bool:
        return self.fetched_while_open > closed - RELOAD_FETCH or self.fetched > closed

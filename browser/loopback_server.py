"""Start VPython's browser view on this computer only (127.0.0.1), without its two holes.

The server lives in the package browser/server/ (its __init__ has the map); this module keeps
the names the rest of the program imports. Importing it does not import vpython.
"""

from .server.lifecycle import CLOSE_GRACE, RELOAD_FETCH, RELOAD_WAIT
from .server.start import LISTEN_QUEUE, interrupted, start
from .server.state import LOOPBACK, REPORT_EVERY, ServerError, ServerInfo

__all__ = ["CLOSE_GRACE", "LISTEN_QUEUE", "LOOPBACK", "RELOAD_FETCH", "RELOAD_WAIT", "REPORT_EVERY",
           "ServerError", "ServerInfo", "interrupted", "start"]

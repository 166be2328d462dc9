"""The page's websocket: vpython's server, on 127.0.0.1 only, talking only to its own page.

vpython's WSserver protocol is subclassed: a foreign Origin or a second tab is refused, only the
page's own connection may end the program when it closes (browser/server/lifecycle.py decides
when), and the page's messages note when it last spoke.
"""

from __future__ import annotations

import asyncio

from .state import LOOPBACK, ServerState

VPYTHON_SERVER = "vpython.no_notebook"  # the module whose import-time code starts vpython's servers


def made_by_vpython(thing) -> bool:
    """Whether a function or class was defined by vpython's server module."""
    return getattr(thing, "__module__", None) == VPYTHON_SERVER


def create_server_wrapper(original, state: ServerState):
    """asyncio's create_server, binding vpython's websocket server to 127.0.0.1 only."""

    async def create_server(loop, protocol_factory, host=None, port=None, *args, **kwargs):
        protocol = getattr(protocol_factory, "protocol", None)
        if not made_by_vpython(protocol):
            return await original(loop, protocol_factory, host, port, *args, **kwargs)
        protocol_factory.protocol = guarded_protocol(protocol, state)
        server = await original(loop, protocol_factory, LOOPBACK, port, *args, **kwargs)
        state.socket_port = server.sockets[0].getsockname()[1]
        return server

    return create_server


class Quiet:
    """A logger that says nothing: what matters is summed up by Refusals instead."""

    def __getattr__(self, name):
        return lambda *args, **kwargs: None


def guarded_protocol(vpython_protocol, state: ServerState):
    """vpython's websocket protocol, refusing foreign pages and second tabs."""
    from autobahn.exception import Disconnected
    from autobahn.websocket.types import ConnectionDeny
    from vpython.vpython import baseObj

    life = state.life

    class GuardedWSserver(vpython_protocol):
        opened = False
        log = Quiet()  # autobahn would print a line for every refused or dropped connection

        def onConnect(self, request):
            # Browsers always send Origin; a page from anywhere else must not drive (or stop) us.
            if request.origin not in state.origins:
                state.refusals.add("from another web page or program")
                raise ConnectionDeny(ConnectionDeny.FORBIDDEN, "origin not allowed")
            # A second tab would take half of the page's updates: it gets a message instead
            # (tab.js asks /status), and closing it does not end the program.
            if life.refuse_second_tab():
                state.refusals.add("from a second tab of the page")
                raise ConnectionDeny(409, "the page is already open in another tab")
            return super().onConnect(request)

        def onOpen(self):
            if not life.open(self):  # two tabs raced through onConnect: the first one keeps the page
                state.refusals.add("from a second tab of the page")
                self.sendClose(code=1000, reason="the page is already open in another tab")
                return
            self.opened = True
            super().onOpen()

        async def onMessage(self, data, isBinary):
            if not self.opened:
                return
            if not life.spoke():  # a reloaded page, not built yet: "nothing new" keeps it asking
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
            # and only once it has not come back (a reload closes, then connects again).
            if not self.opened:
                return
            end = lambda: super(GuardedWSserver, self).onClose(wasClean, code, reason)
            life.close(self, asyncio.get_event_loop(), end)

    return GuardedWSserver

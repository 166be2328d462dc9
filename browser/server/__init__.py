"""VPython's browser view, served on this computer only (127.0.0.1), without its two holes.

VPython 7.6.5 (outside Jupyter) runs two servers, started by the module-level code of
``vpython/no_notebook.py`` when that module is first imported, which vpython does when the first
object other than the canvas is made (``import vpython`` alone does not start them): an HTTP
server for the page (``glowcomm.html``) and its scripts, fonts and textures, and a websocket
server that the page talks to about every 17 ms. Both listen on every network interface; the
HTTP server reads files from anywhere on the disk, and any connection to the websocket, even
one refused, stops the program. We don't fork vpython: start() imports its server module with
corrections in place, listed with what each corrects in ``patches.py``.

- ``start.py``: start(), which reserves the port, prints the URL and imports vpython's servers.
- ``state.py``: ServerState, everything one run knows, shared by the threads; ServerInfo.
- ``http_server.py``: the page's files, on 127.0.0.1, to this program's own host name only, and
  the file the page's Load data button sends (POST /data, from the page's own Origin only).
- ``websocket.py``: the page's websocket, to the page's own Origin only.
- ``lifecycle.py``: one open page, its reloads, a second tab, the end when it closes.
- ``tab.js``: added to the page: says why when the page stops (a second tab, a program ended).

Importing this package does not import vpython.
"""

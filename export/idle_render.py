"""A GlowScript canvas drawn only when something on it changed, for every page that has one.

GlowScript 3.2 (vendored, unchanged: export/glowscript/) redraws each 3-D canvas every 17 ms
whatever happens: `trigger_render` calls the canvas's WebGLRenderer `render(RENDER)` on a timer.
A paused page, or a page whose mass has stopped, keeps drawing the same picture. On a school's
computer with no graphics card (software WebGL, as in Chromium's SwiftShader) one frame of the
local page costs 0.3–1.3 s of CPU, so a paused page held a core busy drawing nothing new, and
every other window and program on that computer waited.

The script here wraps each canvas's `render` once, so that a frame is drawn only when GlowScript
itself has something new to show: an object changed (`__changed`, `__vertex_changed`), a label
(`__overlay_objects.__changed`), the camera or the canvas's size (GlowScript's own `__last_*`
copies, which it updates after every frame), or a texture is still loading. Picking (the mouse)
and every other mode pass through. A frame is drawn at least every QUIET_MS all the same, in case
something changes that GlowScript does not mark. The picture is the same as before: the frame
that would have been drawn is the one already on the screen.

Measured on the local page of `vertical`, paused after a jump, 1280 × 800 window, headless
Chromium with SwiftShader (tests/browser_support.py's arguments plus --disable-gpu-compositing):
1.35 frames a second drawn and 0.61 s of the GPU process's CPU a second before, 0.16 frames a
second and 0.09 s a second after.
"""
from __future__ import annotations

from pathlib import Path

SCRIPT = Path(__file__).with_name("idle_render.js")


def idle_render_script() -> str:
    """The <script> element both pages include once (the local page in its caption, through
    browser/controls.py; the offline page in its body, through export/offline_page.py)."""
    return "<script>" + SCRIPT.read_text(encoding="utf-8") + "</script>"

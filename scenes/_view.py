"""What a scene's VIEW may name, and what each key is when the scene does not name it.

A scene file ends with VIEW, a few lines naming what to draw; both front ends that draw a scene
(the page, browser/view.py, and the VPython program, export/vpython_program.py) read it as
``{**DEFAULT_VIEW, **VIEW}``:

    support  "ceiling" or "wall": what the springs hang from
    plot     the coordinate that moves: "x", "y", "z" or "xyz"
    trail    each mass's path over the last 15 s
    exact    False hides the exact curve
    sliders  the constants that get one (else m, k and the forces switched on)
    coils    turns per helix
    window   seconds the graphs show before they scroll
"""
from __future__ import annotations

DEFAULT_VIEW = {"support": "ceiling", "plot": "y", "trail": False, "exact": True, "coils": 12,
                "window": 30.0}

"""What a scene's VIEW may name, and what each key is when the scene does not name it.

A scene file ends with VIEW, a few lines naming what to draw; both front ends that draw a scene
(the page, browser/view.py, and the VPython program, export/vpython_program.py) read it as
``{**DEFAULT_VIEW, **VIEW}``:

    support  "ceiling" or "wall": what the springs hang from
    plot     the coordinate that moves: "x", "y", "z" or "xyz"
    trail    each mass's path over the last 15 s
    exact    False hides the exact curve
    sliders  the scene's own constants that get a slider (m, x0, Δt), beside those each force
             declares for itself while it is on (k, b, C, F0, ω, μ_k: scenes/_sliders.py); a
             force's constant named here gets one even while its force is off (the pendulum's b)
    coils    turns per helix
    window   seconds the graphs show before they scroll
    hold     True: the graphs stop at `window` seconds instead of scrolling, so a motion that
             settles (regimes) keeps its start in view
    graphed  a function of the model giving the masses the position graph shows (resonance: a few
             chosen springs, not all 39); None: every mass
    arrows   the arrows drawn on each mass when the page opens (export/arrows.py): "p", "F_net",
             "forces", "split"; `--arrows` and the page's check boxes change them
    error    seconds of a graph of log₁₀ of the largest |x − x_exact| over the last period, of each
             mass (browser/error_envelope.py; integrators: each method's order
             and how its error grows); None: no such graph. Only where the model has an exact solution
    energy_note  a function of the configured scene giving one line shown under the energy graph
             (resonance: what the energy's spikes are); None: no line
    rows     a function of the model giving each mass's row (resonance: one row of springs per b);
             a row's masses share its colour (export/palette.py mass_colours)
"""
from __future__ import annotations

MAX_DRAWN_MASSES = 2000     # a sphere and a helix each: more would stall the page on a school laptop

DEFAULT_VIEW = {"support": "ceiling", "plot": "y", "trail": False, "exact": True, "coils": 12,
                "window": 30.0, "hold": False, "graphed": None, "arrows": (),
                "error": None, "energy_note": None}

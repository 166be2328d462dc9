"""The page's Simple Example: a 10 kg mass hangs on a 40 N/m spring and is released from rest at 1.5 m.

Question: where is the mass after 0.2 s? With Δt = 0.1 s, two momentum updates by hand give
y = −1.73088 m; the exact answer is y = −1.65393 m, and the iteration approaches it as Δt shrinks.
"""
from ._single_mass import build_single_mass

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
# A force with no line here is off. To switch one on, add its line, like
#     b = 1.0  # kg/s: linear damping constant in F = −b v
# or give it for one run (--set); `python main.py vertical --constants` lists every force's.
m = 10.0                   # kg: mass of the block
k = 40.0                   # N/m: spring constant (stiffness)
L0 = 1.0                   # m: relaxed length of the spring
g = 9.8                    # m/s²: strength of gravity, acting along −y (y is up)
anchor = (0, 0, 0)         # m: top end of the spring, fixed to the ceiling
r0 = (0, -1.5, 0)          # m: start position, below the anchor (the spring stretched)
v0 = (0, 0, 0)             # m/s: start velocity (released from rest)
dt = 0.1                   # s: time step Δt of the momentum update
until = 0.2                # s: question time: where is the mass then?
# ---- end of constants ----

MENU_ORDER = 1               # where it stands in --list and the page's scene menu


def build(**constants):
    """The hanging mass with spring and gravity (and any force a constant switches on)."""
    return build_single_mass(**constants)


VIEW = {"support": "ceiling", "plot": "y", "arrows": ("p", "F_net"),
        "sliders": ["m"]}
LAB = {"fit": ("k", "b"), "hidden": ("k", "b")}   # what Fit fits, what a mystery spring hides

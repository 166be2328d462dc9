"""The page's Middling Example: the Simple Example plus linear damping F = −b v with b = 1 kg/s.

Question: where is the mass after 0.2 s now? The damping force is small at first because the mass
starts at rest, so the answer barely differs from the undamped one this early.
"""
from ._single_mass import build_single_mass

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
# A force with no line here is off. To switch one on, add its line, like
#     F0 = 1.0  # N: driving force amplitude in F = F0 cos(ω t)
# or give it for one run (--set); `python main.py damped --constants` lists every force's.
m = 10.0                   # kg: mass of the block
k = 40.0                   # N/m: spring constant (stiffness)
L0 = 1.0                   # m: relaxed length of the spring
g = 9.8                    # m/s²: strength of gravity, acting along −y (y is up)
b = 1.0                    # kg/s: linear damping constant in F = −b v
anchor = (0, 0, 0)         # m: top end of the spring, fixed to the ceiling
r0 = (0, -1.5, 0)          # m: start position, below the anchor (the spring stretched)
v0 = (0, 0, 0)             # m/s: start velocity (released from rest)
dt = 0.1                   # s: time step Δt of the momentum update
until = 0.2                # s: question time: where is the mass then?
# ---- end of constants ----

MENU_ORDER = 2               # where it stands in --list and the page's scene menu


def build(**constants):
    """The hanging mass with spring, gravity and linear damping."""
    return build_single_mass(**constants)


VIEW = {"support": "ceiling", "plot": "y", "arrows": ("p", "F_net"),
        "sliders": ["m"]}
LAB = {"fit": ("k", "b"), "hidden": ("k", "b")}   # what Fit fits, what a mystery spring hides

"""The page's Difficult Example: a 4 kg mass on a 100 N/m spring, horizontal, driven by F0 cos(ω t).

The natural angular frequency is ω0 = √(k/m) = 5 rad/s. The page writes its driving frequencies as
"5 Hz" and "4 Hz", but they are angular frequencies in rad/s: scenario 1 (ω = 5 rad/s, b = 0) is
exact resonance, where the amplitude grows without bound as F0 t / (2 m ω0). Pick one of the page's
five scenarios with --scenario N.
"""
import numpy as np

from ._single_mass import build_single_mass

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
# A force with no line here is off. To switch one on, add its line, like
#     b = 2.0  # kg/s: linear damping constant in F = −b v
# or give it for one run (--set); `python main.py driven --constants` lists every force's.
m = 4.0                    # kg: mass of the block
k = 100.0                  # N/m: spring constant (stiffness)
L0 = 3.0                   # m: relaxed length of the spring (long enough that no scenario reaches the wall)
g = 0.0                    # m/s²: strength of gravity (off: the spring lies on a frictionless table)
F0 = 1.0                   # N: driving force amplitude in F = F0 cos(ω t)
omega = 5.0                # rad/s: driving angular frequency ω (rad/s, not Hz; f = ω / 2π)
drive_axis = (1, 0, 0)     # 1: direction of the driving force
anchor = (0, 0, 0)         # m: the spring's fixed end, on the wall
x0 = 0.0                   # m: start displacement from equilibrium along x
r0 = None                  # m: start position (default: anchor + (L0 + x0) along x)
v0 = (0, 0, 0)             # m/s: start velocity
dt = 0.01                  # s: time step Δt of the momentum update
until = 20.0               # s: how long to run
# ---- end of constants ----

MENU_ORDER = 3               # where it stands in --list and the page's scene menu

# The page's five scenarios, each changing the one before it.
SCENARIOS = [
    ("b = 0, F0 = 1 N, x0 = 0, ω = 5 rad/s: exact resonance", {"b": 0.0, "F0": 1.0, "x0": 0.0, "omega": 5.0}),
    ("as 1, with x0 = 1 m", {"b": 0.0, "F0": 1.0, "x0": 1.0, "omega": 5.0}),
    ("as 2, with b = 2 kg/s", {"b": 2.0, "F0": 1.0, "x0": 1.0, "omega": 5.0}),
    ("as 3, with F0 = 2 N", {"b": 2.0, "F0": 2.0, "x0": 1.0, "omega": 5.0}),
    ("as 4, with ω = 4 rad/s", {"b": 2.0, "F0": 2.0, "x0": 1.0, "omega": 4.0}),
]


def build(*, x0, r0, anchor, L0, **constants):
    """The horizontal driven oscillator; the mass starts x0 from equilibrium unless r0 is given."""
    if r0 is None:
        r0 = tuple(np.asarray(anchor, dtype=float) + (L0 + x0) * np.array([1.0, 0.0, 0.0]))
    return build_single_mass(r0=r0, anchor=anchor, L0=L0, **constants)


VIEW = {"support": "wall", "plot": "x", "arrows": ("p", "F_net"),
        "sliders": ["m"]}
LAB = {"fit": ("k", "b"), "hidden": ("k", "b")}   # what Fit fits, what a mystery spring hides

"""The 3-D spring pendulum: a mass on a spring from the ceiling, pulled sideways and down, released.

This is the page's VPython program with every vector in 3-D. The momentum update is the same,

    F_net = −k (|L| − L0) L̂ + m g,   L = r − anchor
    p_f = p_i + F_net Δt,   v_f = p_f / m,   r_f = r_i + v_f Δt

but now the spring both stretches (bouncing, ω_s = √(k/m)) and swings (a pendulum of length
s_eq = L0 + m g / k, ω_p ≈ √(g / s_eq)). The two motions trade energy back and forth; with the
default k the bounce is about twice the swing frequency (ω_s ≈ 2 ω_p), where that exchange is
strongest. A small sideways push along z makes the path a genuinely 3-D rosette, drawn as a trail.
With no damping, E = K + U_spring + U_gravity stays constant. There is no closed form.
"""
from ._single_mass import build_single_mass

# ---- constants: edit these (unit: meaning); 0 switches a force off ----
# A force with no line here is off. To switch one on, add its line, like
#     b = 0.5  # kg/s: linear damping constant in F = −b v
# or give it for one run (--set); `python main.py pendulum --constants` lists every force's.
m = 1.0                    # kg: mass of the bob
k = 30.0                   # N/m: spring constant (stiffness)
L0 = 1.0                   # m: relaxed length of the spring
g = 9.8                    # m/s²: strength of gravity, acting along −y (y is up)
anchor = (0, 0, 0)         # m: top end of the spring, fixed to the ceiling
r0 = (0.4, -1.5, 0)        # m: start position, pulled sideways (x) and down (y)
v0 = (0, 0, 0.3)           # m/s: start velocity, a small push along z to make the motion 3-D
dt = 0.005                 # s: time step Δt of the momentum update
until = 30.0               # s: how long to run
# ---- end of constants ----

MENU_ORDER = 6               # where it stands in --list and the page's scene menu



def build(**constants):
    """The spring pendulum: spring, gravity, and any force a constant switches on."""
    return build_single_mass(label="bob", **constants)


VIEW = {"support": "ceiling", "plot": "xyz", "trail": True, "sliders": ["m", "g", "b"], "arrows": ("p", "F_net")}

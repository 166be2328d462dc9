"""The handed-out program's answer line, written with the command line's digits in Python and in Web VPython.

    at t = 0.2 s: r = < 0, -1.7301, 0 > m, p = < 0, -15.21, 0 > kg·m/s

is what `python main.py damped --headless` writes (export/step_update.py's number and vector:
SIGNIFICANT digits, '{:.6g}', 0 for '-0' and for components below 1e-12 of the vector's largest).
The program writes it with two small functions of its own, because Web VPython 3.2's str.format
(RapydScript's, in GlowScript's RSrun.3.2.min.js) is not Python's: '{:.6g}' writes 1e-7 as
'1.00000e-7', rounds an exact tie away from zero (100000.5 → '100001', Python '100000') and keeps
'-0'. What both runtimes do alike is '{:.5e}' (6 digits, correctly rounded; only the exponent's
width differs) and '{:.30e}' (31 digits: enough to see an exact tie), plus slicing and rstrip; the
functions build Python's 'g' from those. tests/test_handout.py checks them against number() on
thousands of values, in CPython and with GlowScript's own format under node.
"""
from __future__ import annotations

from .step_update import SIGNIFICANT

_DIGITS = SIGNIFICANT
_TIE = "5" + "0" * (30 - _DIGITS)       # the digits after the last kept one, in '{:.30e}', at an exact tie

HELPERS = [
    "",
    "# ---- how the answer is written: as the simulator's command line writes it ----",
    "def number(x, size=0):",
    f'    """x to {_DIGITS} significant digits, as Python\'s \'{{:.{_DIGITS}g}}\' writes it, here and in Web VPython',
    "    (whose own 'g' differs); 0 for round-off (below 1e-12 of size), \"(no value)\" for inf or nan.\"\"\"",
    "    if x - x != 0:",
    '        return "(no value)"',
    "    if x == 0 or abs(x) < 1e-12*size:",
    '        return "0"',
    f'    s = "{{:.{_DIGITS - 1}e}}".format(abs(x))     # d.ddddde-07: {_DIGITS} digits, correctly rounded',
    '    exact = "{:.30e}".format(abs(x))',
    f'    if exact[{_DIGITS + 1}:32] == "{_TIE}" and exact[{_DIGITS}] in "02468":',
    f"        s = exact[:{_DIGITS + 1}] + exact[32:]     # an exact tie goes to the even digit, as in Python",
    f"    digits, power = s[0] + s[2:{_DIGITS + 1}], int(s[{_DIGITS + 2}:])",
    f"    if power < -4 or power >= {_DIGITS}:",
    "        power_digits = str(abs(power))",
    "        if len(power_digits) == 1:",
    '            power_digits = "0" + power_digits',
    f'        text = (digits[0] + "." + digits[1:]).rstrip("0").rstrip(".") + "e" + s[{_DIGITS + 2}] + power_digits',
    "    elif power < 0:",
    '        text = ("0." + "000"[:-1 - power] + digits).rstrip("0")',
    "    else:",
    '        text = (digits[:power + 1] + "." + digits[power + 1:]).rstrip("0").rstrip(".")',
    "    if x < 0:",
    '        text = "-" + text',
    "    return text",
    "",
    "def vector_text(v):",
    '    """< x, y, z >, each as number() writes it."""',
    "    size = max(abs(v.x), abs(v.y), abs(v.z))",
    '    return "< " + number(v.x, size) + ", " + number(v.y, size) + ", " + number(v.z, size) + " >"',
]


def answer_line(i: str) -> str:
    """The expression of the answer's text for the mass `pos{i}`, `p{i}` ("" or "[i]")."""
    return f'"at t = " + number(t) + " s: r = " + vector_text(pos{i}) + " m, p = " + vector_text(p{i}) + " kg·m/s"'


def labelled(symbol: str, name: str, unit: str, last: bool) -> str:
    """`"ω = " + number(omega[i]) + " rad/s:"`: a value that names a mass in the answer."""
    return f'"{symbol} = " + number({name}) + "{unit}{":" if last else ","}"'

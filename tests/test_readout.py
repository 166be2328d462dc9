"""The page's error readout in plain decimals with units (browser/readout.py): `+1.24 nm`, not
`+1.24e-09 m` (issue 18, item 6: plain decimals wherever a student reads)."""
import math
import re

import pytest
from hypothesis import given, strategies as st

from browser.clock import LiveRun
from browser.graphs import Graphs
from browser.readout import ROUND_OFF, length_text, units_kept
from physics.accuracy import accuracy_message
from browser.view import DEFAULT_VIEW
from scenes import catalog
from test_trail import stand_in_vpython

SIZES = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "nm": 1e-9, "pm": 1e-12}
PLAIN = re.compile(r"^([+−]?)(\d+(?:\.\d+)?)\u00a0(m|mm|µm|nm|pm)$")   # a no-break space before the unit


def metres(text: str) -> float:
    """A length as written by length_text, back in metres."""
    sign, number, unit = PLAIN.match(text).groups()
    return (-1 if sign == "−" else 1) * float(number) * SIZES[unit]


@pytest.mark.parametrize("value, text", [
    (1.24e-9, "+1.24 nm"), (-1.24e-9, "−1.24 nm"), (0.0124, "+12.4 mm"), (0.153, "+0.153 m"),
    (2.5e-5, "+25.0 µm"), (9.9996e-4, "+1.00 mm"), (3.2e-12, "+3.20 pm"), (1234.5, "+1230 m"),
    (0.0, "0 m")])
def test_hand_worked_lengths(value, text):
    assert length_text(value, signed=True) == text.replace(" ", "\u00a0")


def test_round_off_and_not_a_number_are_said_in_words():
    assert length_text(3e-16) == ROUND_OFF
    assert length_text(float("nan")) == length_text(float("inf")) == "not a number"


@given(st.floats(min_value=1e-12, max_value=1e4) | st.floats(min_value=-1e4, max_value=-1e-12))
def test_every_length_is_a_plain_decimal_within_its_rounding(value):
    text = length_text(value, signed=True)
    assert PLAIN.match(text), text                 # no exponent, no inf, no nan
    assert math.isclose(metres(text), value, rel_tol=5.1e-3), (value, text)
    digits = PLAIN.match(text).group(2).replace(".", "").lstrip("0")
    assert 3 <= len(digits) <= 5, text             # three significant digits (padded with 0s from 1000 m up)


def test_the_page_writes_a_tiny_error_in_nanometres_not_with_an_exponent():
    """damped with rk4: after 2 s the simulation is within nanometres of the exact solution."""
    setup = catalog.configure("damped")
    model = setup.build()
    graphs = Graphs(stand_in_vpython(), setup=setup, model=model, view={**DEFAULT_VIEW, **setup.module.VIEW})
    live = LiveRun(model, integrator="rk4", sample_every=0.05)
    graphs.plot(live.restart(), live, matter=[0], redraw=True)
    graphs.plot(live.advance(round(2.0 / model.dt)), live, matter=[0])
    readout = graphs.error_readout(live, matter=[0])
    assert "e-" not in readout and "e+" not in readout, readout
    written = readout.split(" = ")[1]
    error = float(live.state.r[0][graphs.axes[0]] - model.exact([live.state.t])[0][0][0][graphs.axes[0]])
    assert 0 < abs(error) < 1e-3     # so the readout must use a unit smaller than the metre
    assert written == length_text(error, signed=True)
    assert math.isclose(metres(written), error, rel_tol=5.1e-3)


def test_the_status_line_joins_each_number_to_its_unit_and_leaves_the_tags_alone():
    """The page's status line (browser/controls.py) wrapped `330` and `%` onto two lines; the page
    joins each number to its unit with a no-break space, and the sentence physics/ writes for the
    command line keeps its plain spaces (a console that is not UTF-8 prints it too)."""
    said = accuracy_message(dt=0.9, error=3.3, window=9.42, advised=0.01)
    assert "330 %" in said and "\u00a0" not in said
    shown = units_kept(f"<b style='font-size:150%'>Stopped:</b> {said}")
    assert shown.startswith("<b style='font-size:150%'>Stopped:</b> ")            # a tag is left alone
    for glued in ("0.9\u00a0s", "9.42\u00a0s", "330\u00a0%", "0.01\u00a0s", "1\u00a0%"):
        assert glued in shown
    assert not re.search(r"\d (%|[^\W\d_])", shown)                                 # no number left apart
    assert shown.replace("\u00a0", " ") == f"<b style='font-size:150%'>Stopped:</b> {said}"
    assert units_kept("k = 1e-05 N/m") == "k = 1e-05\u00a0N/m"

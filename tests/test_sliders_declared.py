"""A force declares its own sliders ("a slider when on", Declared.slider), so no scene names them.

scenes/_sliders.py slider_names is the one rule every front end reads: each constant whose force
declares a slider for it gets one wherever that force is in the scene's model, and a scene's VIEW
names only its own constants (m, x0, Δt) or a force's it offers while that force is off.
"""
from __future__ import annotations

import pytest

from physics.forces import FORCES
from scenes import catalog
from scenes._sliders import slider_names


def _cases():
    for name in catalog.SCENE_NAMES:
        setup = catalog.configure(name)
        yield pytest.param(setup, id=name)
        for label, _ in catalog.presets(setup):
            yield pytest.param(setup.with_preset(label), id=f"{name}-{label}")


def _plain(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


@pytest.mark.parametrize("setup", list(_cases()))
def test_every_force_that_is_on_brings_its_declared_sliders_in_the_constants_order(setup):
    model = setup.build()
    declared = {name for force in model.forces for name, d in type(force).CONSTANTS.items() if d.slider}
    names = slider_names(setup, setup.hooks.view)
    expected = {name for name in declared if name in setup.constants and _plain(setup.values[name])}
    assert expected <= set(names)
    order = list(setup.constants)
    assert names == sorted(names, key=order.index)
    assert len(names) == len(set(names))


def test_a_force_switched_on_by_a_preset_gets_its_slider_and_loses_it_when_off():
    setup = catalog.configure("vertical")
    assert "b" not in slider_names(setup, setup.hooks.view)            # damping off: no slider
    critical = setup.with_preset("critical damping")
    assert "b" in slider_names(critical, critical.hooks.view)          # on: b = 2√(mk)
    driven = catalog.configure("vertical", assignments=["F0=1", "omega=3"])
    assert {"F0", "omega"} <= set(slider_names(driven, driven.hooks.view))


@pytest.mark.parametrize("name", catalog.SCENE_NAMES)
def test_no_scene_names_a_slider_its_force_already_declares(name):
    setup = catalog.configure(name)
    view = setup.hooks.view
    assert "sliders_when_on" not in view
    on = {type(force) for force in setup.build().forces}
    named_by_force = {constant for cls in on for constant, d in cls.CONSTANTS.items() if d.slider}
    assert not set(view.get("sliders") or ()) & named_by_force, (
        f"{name}'s VIEW names a slider its force declares; leave it to the force")


def test_the_page_forces_declare_the_lesson_sliders():
    declared = {cls.__name__: sorted(n for n, d in cls.CONSTANTS.items() if d.slider) for cls in FORCES}
    assert declared["Spring"] == ["k"] and declared["LinearDamping"] == ["b"]
    assert declared["QuadraticDrag"] == ["C"] and declared["Driving"] == ["F0", "omega"]
    assert declared["Friction"] == ["mu_k"]

"""Bad input gives a clear exception naming the field and value, never a crash."""

import math

import numpy as np
import pytest

import beltrs
from beltrs import Pulley, SceneError, TimeStepError
from beltrs.scenes import hustrulid_loop


def build(scene):
    return beltrs.Simulation(scene)


def test_negative_mass_names_field_and_value():
    scene = hustrulid_loop()
    scene.pulleys[1].mass = -600.0
    with pytest.raises(SceneError, match=r"pulleys\[1\]\.mass = -600: must be > 0"):
        build(scene)


def test_zero_belt_mass():
    scene = hustrulid_loop()
    scene.belt.mass_per_length = 0.0
    with pytest.raises(SceneError, match=r"belt\.mass_per_length = 0: must be > 0"):
        build(scene)


def test_nan_anywhere():
    scene = hustrulid_loop()
    scene.pulleys[0].center = (0.0, math.nan)
    with pytest.raises(SceneError, match=r"pulleys\[0\]\.center\[1\] = NaN: must be a finite number"):
        build(scene)


def test_overlapping_pulleys():
    scene = hustrulid_loop()
    scene.pulleys[1].center = (0.0, 92.0)
    with pytest.raises(SceneError, match=r"pulleys\[1\]\.center = \[0, 92\]: overlaps pulleys\[0\]"):
        build(scene)


def test_element_longer_than_smallest_pulley_can_hold():
    scene = hustrulid_loop(elements=40)  # 5.8 m elements on 5 m pulleys
    with pytest.raises(SceneError, match=r"belt\.elements = 40: elements of 5\.78\d+ m are longer"):
        build(scene)


def test_belt_too_short_for_its_path():
    scene = hustrulid_loop()
    scene.belt.length = 200.0
    with pytest.raises(SceneError, match=r"belt\.length = 200: the belt is too short"):
        build(scene)


def test_time_step_above_stability_limit():
    limit = beltrs.Simulation(hustrulid_loop()).dt_limit
    with pytest.raises(TimeStepError, match=r"solver\.time_step = 0\.01 s exceeds the stability limit"):
        build(hustrulid_loop(time_step=0.01))
    # Just below the limit is accepted.
    assert build(hustrulid_loop(time_step=0.99 * limit)).dt == pytest.approx(0.99 * limit)


def test_unknown_key_in_scene_dict():
    d = hustrulid_loop().to_dict()
    d["pulleys"][0]["radious"] = 5.0
    with pytest.raises(SceneError, match=r"pulleys\[0\]\.radious = 'radious': unknown key"):
        beltrs._beltrs.Simulation(d)


def test_wrong_type():
    d = hustrulid_loop().to_dict()
    d["belt"]["elements"] = "many"
    with pytest.raises(SceneError, match=r"belt\.elements = 'many': expected a whole number"):
        beltrs._beltrs.Simulation(d)


def test_kinetic_above_static_friction():
    scene = hustrulid_loop(friction=beltrs.Friction(static=0.3, kinetic=0.4))
    with pytest.raises(SceneError, match=r"kinetic_coefficient = 0\.4: must not exceed the static coefficient 0\.3"):
        build(scene)


def test_blow_up_stops_with_error_and_keeps_results():
    sim = beltrs.Simulation(hustrulid_loop())
    sim.run(0.01, record_every=1)
    # An absurd (finite) gravity drives the state to infinity within a few steps.
    scene = hustrulid_loop()
    scene.gravity = 1e250
    sim.set_scene(scene)
    with pytest.raises(
        beltrs.DivergenceError,
        match=r"non-finite at t = [0-9.e-]+ s \(step \d+\): (position|velocity|force) [xy] of node \d+",
    ) as err:
        sim.run(1.0, record_every=1)
    partial = err.value.result
    assert len(partial) >= 1
    assert np.all(np.isfinite(partial.time))
    assert sim.last_result is partial


def test_scene_without_pulleys():
    with pytest.raises(SceneError, match=r"pulleys = 1 pulley\(s\): a closed belt path needs at least 2"):
        build(beltrs.Scene(pulleys=[Pulley(center=(0.0, 0.0))]))

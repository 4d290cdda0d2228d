"""The compiled model (beltrs.compile, Simulation.model): only the stages a scene needs,
and the optional per-stage profile."""

import dataclasses
import time

import numpy as np
import pytest

import beltrs
from beltrs import Brake, Drive, Friction, Idler, SceneError, TimeStepError
from beltrs.scenes import hustrulid_loop

ALL_STAGES = (
    "axial_damped",
    "bending",
    "pulley_contact",
    "idler_contact",
    "drives",
    "pulley_friction",
    "idler_friction",
    "brakes",
)


def every_effect() -> beltrs.Scene:
    """Case H with every effect on: gravity, EI, damping, contact and friction on both
    pulleys, two idlers with friction, a takeup, a drive and a brake."""
    scene = hustrulid_loop(friction=Friction(0.5, 0.4), damping_ratio=0.05)
    scene.pulleys[0].drive = Drive.constant(1e4)
    scene.pulleys[1].brake = Brake(capacity=[1e3])
    scene.idlers = [Idler(center=(5.0635, 50.0), friction=Friction(0.3)), Idler(center=(-5.0635, 50.0))]
    return scene


def _no_gravity(s):
    s.gravity = 0.0


def _no_bending(s):
    s.belt.bending_stiffness = 0.0


def _no_damping(s):
    s.belt.damping_ratio = 0.0


def _no_idlers(s):
    s.idlers = []


def _idler_mu_zero(s):
    s.idlers[0].friction = Friction(0.0)


def _pulley_mu_zero(s):
    for p in s.pulleys:
        p.friction = Friction(0.0)


def _pulley_friction_none(s):
    for p in s.pulleys:
        p.friction = Friction(model="none")


def _no_drive(s):
    s.pulleys[0].drive = None


def _no_brake(s):
    s.pulleys[1].brake = None


def _no_takeup(s):
    s.pulleys[1].takeup = None


def _no_pulley_contact(s):
    for p in s.pulleys:
        p.contact_stiffness = 0.0
        p.friction = None


@pytest.mark.parametrize(
    ("switch_off", "removed", "added"),
    [
        # The weights are part of the axial pass and takeups move with the integrator:
        # neither is a stage, so switching them off leaves the list as it is.
        (_no_gravity, set(), set()),
        (_no_bending, {"bending"}, set()),
        (_no_damping, {"axial_damped"}, {"axial"}),
        (_no_idlers, {"idler_contact", "idler_friction"}, set()),
        (_idler_mu_zero, {"idler_friction"}, set()),
        (_pulley_mu_zero, {"pulley_friction"}, set()),
        (_pulley_friction_none, {"pulley_friction"}, set()),
        (_no_drive, {"drives"}, set()),
        (_no_brake, {"brakes"}, set()),
        (_no_takeup, set(), set()),
        (_no_pulley_contact, {"pulley_contact", "pulley_friction"}, set()),
    ],
    ids=lambda f: f.__name__.strip("_") if callable(f) else None,
)
def test_an_effect_switched_off_compiles_no_stage(switch_off, removed, added):
    """Switching one effect off removes exactly its stage(s) and keeps the order of the rest:
    no idlers -> no idler stage, µ = 0 -> no friction stage, EI = 0 -> no bending stage,
    damping 0 -> 'axial' instead of 'axial_damped'."""
    assert beltrs.compile(every_effect()).stages == ALL_STAGES
    scene = every_effect()
    switch_off(scene)
    model = beltrs.compile(scene)
    expected = tuple("axial" if s == "axial_damped" and "axial" in added else s for s in ALL_STAGES)
    assert model.stages == tuple(s for s in expected if s not in removed)
    assert all(model.has_stage(s) for s in model.stages) and not any(model.has_stage(s) for s in removed)


def test_the_plainest_scene_runs_only_the_axial_stage():
    scene = hustrulid_loop(bending=False)
    scene.gravity = 0.0
    scene.pulleys[1].takeup = None
    _no_pulley_contact(scene)
    assert beltrs.compile(scene).stages == ("axial",)


def test_compile_and_simulation_model_agree():
    scene = every_effect()
    model = beltrs.compile(scene)
    sim = beltrs.Simulation(scene)
    assert sim.model.stages == model.stages == tuple(sim.stages)
    assert (sim.model.dt, sim.model.dt_limit, sim.model.dt_cause) == (model.dt, model.dt_limit, model.dt_cause)
    assert model.dt == pytest.approx(0.5 * model.dt_limit, rel=1e-12)  # default fraction 0.5
    assert model.nodes == sim.nodes == 89
    assert model.path_length == pytest.approx(200.0 + 10.0 * np.pi, rel=1e-12)
    assert model.wrap_angles == pytest.approx((np.pi, np.pi), rel=1e-12)
    np.testing.assert_array_equal(model.rest_length, sim.rest_length)
    np.testing.assert_array_equal(model.node_mass, sim.node_mass)
    assert model.scene is scene


def test_model_is_read_only_and_follows_set_scene():
    sim = beltrs.Simulation(hustrulid_loop())
    model = sim.model
    with pytest.raises(dataclasses.FrozenInstanceError):
        model.dt = 1.0
    with pytest.raises(ValueError):
        model.rest_length[0] = 1.0
    assert "pulley_friction" not in model.stages
    sim.set_friction(0, Friction(0.5))
    assert "pulley_friction" in sim.model.stages
    assert "pulley_friction" not in model.stages  # the old snapshot is unchanged


def test_compile_raises_the_scene_errors():
    scene = hustrulid_loop()
    scene.pulleys[0].radius = -1.0
    with pytest.raises(SceneError, match=r"pulleys\[0\]\.radius = -1: must be > 0"):
        beltrs.compile(scene)
    with pytest.raises(TimeStepError):
        beltrs.compile(hustrulid_loop(time_step=1.0))


# --- per-stage profile --------------------------------------------------------------------


def test_profile_is_off_by_default_and_empty_when_off():
    sim = beltrs.Simulation(every_effect())
    sim.step(50)
    assert sim.profile() == {}
    sim.set_profiling(True)
    sim.step(10)
    assert sim.profile() != {}
    sim.set_profiling(False)
    sim.step(10)
    assert sim.profile() == {}


def test_profile_times_each_compiled_stage():
    sim = beltrs.Simulation(every_effect())
    sim.set_profiling(True)
    assert sim.profile() == dict.fromkeys(ALL_STAGES, 0.0)  # zeroed when turned on
    t0 = time.perf_counter()
    sim.step(500)
    wall = time.perf_counter() - t0
    first = sim.profile()
    # One entry per compiled stage, in the order they run.
    assert tuple(first) == sim.model.stages == ALL_STAGES
    assert all(t >= 0.0 for t in first.values())
    # Every stage did some work in 500 steps, and the stages are part of the step, so their
    # times add up to less than the wall time of the call.
    assert all(t > 0.0 for t in first.values()), first
    assert sum(first.values()) <= wall
    # Times accumulate over further steps, and turning profiling on again zeroes them.
    sim.step(100)
    second = sim.profile()
    assert all(second[s] >= first[s] for s in first)
    sim.set_profiling(True)
    assert set(sim.profile().values()) == {0.0}


def test_profile_follows_the_stages_after_set_scene():
    sim = beltrs.Simulation(hustrulid_loop())
    sim.set_profiling(True)
    sim.step(20)
    assert set(sim.profile()) == {"axial", "bending", "pulley_contact"}
    sim.set_friction(0, Friction(0.5))
    sim.step(20)
    assert tuple(sim.profile()) == sim.model.stages
    assert sim.profile()["pulley_friction"] > 0.0

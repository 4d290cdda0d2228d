"""Warnings for common mistakes (docs/warnings.md): each fires on the mistake, stays quiet
on the corrected scene, and belongs to the BeltrsWarning hierarchy users filter on."""

import copy
import dataclasses
import math
import warnings

import numpy as np
import pytest

import beltrs
from beltrs import Belt, Drive, Idler, Pulley, Scene, StartCurve
from beltrs.diagnostics import IDLER_GAP_LIMIT, RELAXED_RESIDUAL_LIMIT, equilibrium_residual
from beltrs.scenes import guo_wang_conveyor, hustrulid_loop

CATEGORIES = [
    beltrs.NotRelaxedWarning,
    beltrs.DriveDirectionWarning,
    beltrs.IdlerContactWarning,
    beltrs.AccuracyWarning,
]


def test_one_hierarchy_users_can_filter():
    for category in CATEGORIES:
        assert issubclass(category, beltrs.BeltrsWarning) and issubclass(category, UserWarning)
    sim = beltrs.Simulation(hustrulid_loop())
    with warnings.catch_warnings():
        warnings.simplefilter("error", beltrs.BeltrsWarning)  # escalate every beltrs warning
        with pytest.raises(beltrs.NotRelaxedWarning):
            sim.run(0.01)
    sim = beltrs.Simulation(hustrulid_loop())
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.simplefilter("ignore", beltrs.NotRelaxedWarning)  # or silence one kind
        sim.run(0.01)
    assert not caught


def test_running_an_unrelaxed_scene_warns_once_and_a_relaxed_one_does_not():
    sim = beltrs.Simulation(hustrulid_loop())
    # The placement: the belt hangs unsupported and the takeup pulls unbalanced.
    assert equilibrium_residual(sim) > 50 * RELAXED_RESIDUAL_LIMIT
    with pytest.warns(beltrs.NotRelaxedWarning, match=r"far from static equilibrium.*Call sim.stabilise\(\)") as rec:
        sim.run(0.05)
    assert rec[0].filename == __file__  # points at the user's line, not inside beltrs
    sim.run(0.05)  # once: the run is under way now
    relaxed = beltrs.Simulation(hustrulid_loop())
    relaxed.stabilise()
    assert equilibrium_residual(relaxed) < RELAXED_RESIDUAL_LIMIT / 100
    relaxed.run(0.05)  # no warning (pytest turns any into an error)


def test_the_unrelaxed_start_is_what_the_warning_says():
    """The mistake the warning is for: from the placement the belt falls onto its pulleys and
    the first 0.5 s shows far higher tensions than the relaxed scene."""
    placed = beltrs.Simulation(hustrulid_loop())
    with pytest.warns(beltrs.NotRelaxedWarning):
        wild = placed.run(0.5, node_position=False, node_velocity=False)
    relaxed = beltrs.Simulation(hustrulid_loop())
    relaxed.stabilise()
    calm = relaxed.run(0.5, node_position=False, node_velocity=False)
    assert np.ptp(wild.takeup_travel[:, 1]) > 100 * np.ptp(calm.takeup_travel[:, 1])


def test_a_starting_curve_against_the_path_direction_warns():
    scene = guo_wang_conveyor(StartCurve(shape="harrison", speed=2.0, ramp=10.0), length=60.0, element_length=0.4)
    beltrs.Simulation(scene)  # the right sign (the factory turns the head clockwise): quiet
    head = scene.pulley_index("head")
    wrong = copy.deepcopy(scene)
    curve = wrong.pulleys[head].drive.start_curve
    wrong.pulleys[head].drive.start_curve = dataclasses.replace(curve, speed=-curve.speed)
    with pytest.warns(
        beltrs.DriveDirectionWarning,
        match=r"pulleys\[1\]\.drive\.start_curve\.speed = 2\.0: runs the belt backwards.*give speed the sign -",
    ):
        beltrs.Simulation(wrong)
    # The same through set_drive on a running simulation.
    sim = beltrs.Simulation(scene)
    with pytest.warns(beltrs.DriveDirectionWarning, match=r"pulleys\[1\]\.drive\.start_curve\.speed = 2\.0"):
        sim.set_drive("head", wrong.pulleys[head].drive)
    # Without loads the scene has no path direction: either sign is quiet.
    wrong.loads = []
    beltrs.Simulation(wrong)


def test_an_idler_far_from_the_belt_warns():
    scene = beltrs.scenes.idler_conveyor(length=20.0)
    n = len(scene.idlers)
    r = Idler().radius
    # The carry strand runs at y = 0.5 m (pulley radius): one more roll 1.6 m above it.
    scene.idlers = scene.idlers + [Idler(center=(10.3, 0.5 + r + 1.6))]
    sim = beltrs.Simulation(scene)
    with pytest.warns(beltrs.IdlerContactWarning, match=rf"1 idler\(s\) will never touch the belt: idlers\[{n}\] at "
                      r"\(10\.3, 2\.16\d*\) \(1\.6\d* m\)"):
        sim.stabilise(tolerance=1e-5)
    res = sim.run(0.2)
    assert np.all(res.idler_force[:, n] == 0) and np.all(res.idler_force[:, :n].sum(axis=1) > 0)  # it never does
    scene.idlers = scene.idlers[:n]
    beltrs.Simulation(scene).stabilise(tolerance=1e-5)  # the conveyor's own idlers: quiet
    assert IDLER_GAP_LIMIT == 0.1


def test_idlers_on_a_curved_profile_are_judged_after_relaxation():
    """Concave-curve idlers sit well below the belt's initial straight line; the belt sags
    onto them when relaxed, so they are not reported."""
    scene = beltrs.scenes.concave_conveyor()
    sim = beltrs.Simulation(scene)
    sim.stabilise(tolerance=1e-5)


def _speed_drive_loop(**belt):
    return Scene(
        belt=Belt(axial_stiffness=1e6, mass_per_length=10.0, length=(20.0 + 2 * math.pi) * 0.995, **belt),
        pulleys=[
            Pulley(name="drive", center=(0.0, 0.0), radius=1.0, contact_stiffness=1e7,
                   drive=Drive(start_curve=StartCurve(shape="harrison", speed=2.0, ramp=1.0))),
            Pulley(name="tail", center=(10.0, 0.0), radius=1.0, contact_stiffness=1e7),
        ],
        gravity=0.0,
    )


def test_the_default_mesh_under_a_running_belt_warns():
    with pytest.warns(beltrs.AccuracyWarning, match=r"belt\.elements = None: .* 30 degrees .*chordal ripple"):
        beltrs.Simulation(_speed_drive_loop())
    beltrs.Simulation(_speed_drive_loop(elements=240))  # chosen explicitly: quiet
    beltrs.Simulation(_speed_drive_loop(max_element_angle=math.radians(7.0)))  # fine mesh: quiet

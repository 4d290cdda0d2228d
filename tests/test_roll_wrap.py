"""Wrap contact on the idler rolls (``belt.idler_contact = "wrap"``, issue 12; kernels in
rust/tests/roll_wrap.rs, docs/wrap-contact.md "The rolls' chordal action"): the key, its
refusals, and the rolls carrying the belt with it as with the segment contact."""

from dataclasses import replace

import pytest

import beltrs
from beltrs.conveyor import Conveyor, DriveSpec


def conveyor(idler_contact: str = "wrap", length: float = 30.0) -> beltrs.Scene:
    """A level builder conveyor at steady running (ST1250, 500 t/h at 2 m/s), wrap contact
    on the drums, spans placed in their sag."""
    curve = beltrs.StartCurve("harrison", speed=2.0, ramp=4.0)
    c = Conveyor(profile=[(0.0, 0.0), (length, 0.0)], belt="ST1250", capacity=500.0, speed=2.0,
                 start="running", drives=[DriveSpec("head", start_curve=curve)])
    s = c.scene()
    return replace(s, belt=replace(s.belt, pulley_contact="wrap", idler_contact=idler_contact),
                   initial=replace(s.initial, sag=True))


def test_idler_contact_key_round_trips_and_bad_values_name_the_field(tmp_path):
    assert beltrs.Scene().belt.idler_contact == "segment"
    scene = conveyor()
    path = tmp_path / "s.toml"
    scene.save(path)
    assert beltrs.load_scene(path).belt.idler_contact == "wrap"
    with pytest.raises(beltrs.SceneError, match=r"idler_contact.*\"segment\" or \"wrap\""):
        beltrs.Simulation(replace(scene, belt=replace(scene.belt, idler_contact="wrapped")))


def test_wrap_on_rolls_needs_a_closed_node_belt():
    scene = conveyor()
    rigid = replace(scene, belt=replace(scene.belt, formulation="rigid_body", pulley_contact="nodes"))
    with pytest.raises(beltrs.SceneError, match=r"belt\.idler_contact = \"?wrap\"?.*rigid_body"):
        beltrs.Simulation(rigid)
    r = 0.25
    hoist = beltrs.Scene(
        belt=beltrs.Belt(axial_stiffness=2e6, mass_per_length=0.6, idler_contact="wrap",
                         start=beltrs.BeltEnd.anchor((-1.5, r)), end=beltrs.BeltEnd.hanging((r, -3.0), 200.0)),
        pulleys=[beltrs.Pulley(name="sheave", center=(0.0, 0.0), radius=r, mass=20.0, wrap="cw")])
    with pytest.raises(beltrs.SceneError, match=r"belt\.idler_contact.*closed loop"):
        beltrs.Simulation(hoist)


def test_the_rolls_carry_the_same_weight_with_either_contact():
    # The belt running over its rolls (spans placed in their sag; bent over each roll with
    # wrap contact on the rolls): the rolls' normal forces, averaged over 0.3 s, add up to
    # the weight they carry, the same with either contact. Measured: 29.8 kN (segment) and
    # 30.5 kN (wrap) on this 30 m conveyor; 3 % covers the two placements' different start
    # transients over so short a run (one carry roll lost from under the belt would cost 3.5 %).
    totals = []
    for kind in ("segment", "wrap"):
        scene = conveyor(kind)
        res = beltrs.Simulation(scene).run(0.3, record_interval=0.01, tension=False, node_position=False,
                                           node_velocity=False)
        assert res.idler_force.min() >= 0.0
        totals.append(res.idler_force.sum(axis=1).mean())
    assert totals[1] == pytest.approx(totals[0], rel=0.03), totals

"""The opt-in recording of contact forces per belt point (issue 11): ``Result.contact_normal``,
``contact_friction`` and ``contact_angle`` ([n, P, E] each, docs/results.md), the wrap-angle
profile :meth:`beltrs.Result.contact_profile`, and every bad input."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import beltrs
from beltrs import Drive, Friction, Simulation, SceneError
from beltrs.result import DIMS, UNITS
from beltrs.scene_file import save_scene
from tiny_scene import tiny_scene


def driven_scene(formulation: str = "node_kelvin_voigt", model: str = "stick_force") -> beltrs.Scene:
    """The tiny two-pulley loop with friction on both pulleys and a torque on the head."""
    scene = tiny_scene(formulation=formulation, elements=40)
    friction = Friction(static=0.5, kinetic=0.4, model=model)
    tail, head = scene.pulleys
    return replace(
        scene,
        pulleys=[
            replace(tail, friction=friction),
            replace(head, friction=friction, drive=Drive(time=[0.0, 0.01], torque=[0.0, 200.0])),
        ],
    )


@pytest.fixture(scope="module", params=["node_kelvin_voigt", "rigid_body"])
def run(request) -> beltrs.Result:
    sim = Simulation(driven_scene(request.param))
    sim.stabilise()
    return sim.run(0.05, record_interval=1e-3, contact_forces=True)


def test_shapes_units_and_sums(run: beltrs.Result) -> None:
    """[n, P, E] arrays; the per-point forces add up to the per-pulley sums at every instant;
    zeros and NaN angles off the pulleys; the angle is the point's about the centre."""
    n, p, e = len(run.time), run.pulley_speed.shape[1], run.node_position.shape[1]
    for name in ("contact_normal", "contact_friction", "contact_angle"):
        assert getattr(run, name).shape == (n, p, e)
        assert DIMS[name] == ("time", "pulley", "node")
    assert UNITS["contact_normal"] == UNITS["contact_friction"] == "N" and UNITS["contact_angle"] == "rad"
    np.testing.assert_allclose(run.contact_normal.sum(axis=2), run.normal_force, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(run.contact_friction.sum(axis=2), run.friction_force, rtol=1e-12, atol=1e-9)
    on = ~np.isnan(run.contact_angle)
    assert np.array_equal(on.sum(axis=2), run.contact_nodes)
    assert np.all(run.contact_normal[~on] == 0) and np.all(run.contact_friction[~on] == 0)
    assert np.all(run.contact_normal[on] >= 0)
    rel = run.node_position[:, None, :, :] - run.pulley_position[:, :, None, :]
    angle = np.arctan2(rel[..., 1], rel[..., 0])
    np.testing.assert_allclose(run.contact_angle[on], angle[on], rtol=0, atol=1e-12)  # atan2 of two libms
    # The drive torque is on: friction acts on the head (not a vacuous sum of zeros).
    assert np.abs(run.friction_force[-1, 1]) > 10.0


def test_contact_forces_are_opt_in_and_change_nothing(run: beltrs.Result) -> None:
    """Off by default (None, and no bytes per sample); switched on, the motion is the same
    bit for bit."""
    scene = driven_scene()
    a, b = Simulation(scene), Simulation(scene)
    a.stabilise()
    b.stabilise()
    ra = a.run(0.01, record_interval=1e-3)
    rb = b.run(0.01, record_interval=1e-3, contact_forces=True)
    assert ra.contact_normal is None and ra.contact_friction is None and ra.contact_angle is None
    assert np.array_equal(ra.tension, rb.tension) and np.array_equal(ra.pulley_speed, rb.pulley_speed)
    e, p = ra.node_position.shape[1], 2
    assert a.sample_bytes(contact_forces=True) - a.sample_bytes() == 24 * p * e


def test_creep_friction_per_point_sums() -> None:
    sim = Simulation(driven_scene(model="creep"))
    sim.stabilise()
    res = sim.run(0.03, record_interval=1e-3, contact_forces=True)
    np.testing.assert_allclose(res.contact_friction.sum(axis=2), res.friction_force, rtol=1e-12, atol=1e-9)
    assert np.abs(res.friction_force[-1, 1]) > 10.0


def test_save_load_and_xarray_keep_the_channel(tmp_path, run: beltrs.Result) -> None:
    path = run.save(tmp_path / "r.npz")
    back = beltrs.load_result(path)
    assert back == run
    assert np.array_equal(back.contact_angle, run.contact_angle, equal_nan=True)
    pytest.importorskip("xarray")
    ds = run.to_xarray()
    assert ds.contact_normal.dims == ("time", "pulley", "node")
    assert ds.contact_angle.attrs["units"] == "rad"


def test_contact_profile_runs_along_the_direction_of_travel(run: beltrs.Result) -> None:
    """The head drives: friction on the belt points along the travel there (positive); the
    tail is driven by the belt: negative. Wrap angles from 0 to about pi."""
    head = run.contact_profile("head", start=0.02, bins=8)
    tail = run.contact_profile(0, start=0.02, bins=8)
    assert head.count.sum() > 0 and tail.count.sum() > 0
    assert -0.5 < head.angle[0] < 0.5 < math.pi - 0.5 < head.angle[-1] < math.pi + 0.5
    assert np.nansum(head.friction * head.count) > 0 > np.nansum(tail.friction * tail.count)
    assert head.direction == tail.direction  # both wrapped the same way round
    assert 0 <= head.origin < 2 * math.pi


def test_bad_input_is_a_scene_error(run: beltrs.Result) -> None:
    sim = Simulation(tiny_scene())
    sim.stabilise()
    with pytest.raises(SceneError, match=r"contact_forces = 'yes': must be True or False"):
        sim.run(0.001, contact_forces="yes")
    with pytest.raises(SceneError, match="contact_forces = 1: must be True or False"):
        sim.sample_bytes(contact_forces=1)
    plain = sim.run(0.001)
    with pytest.raises(SceneError, match="contact forces were not recorded; run with contact_forces=True"):
        plain.contact_profile(0)
    for bad, match in [
        ("nope", r"pulley = 'nope': no pulley of that name"),
        (5, r"pulley = 5: must be a pulley name or an index from 0 to 1"),
        (-1, r"pulley = -1"),
        (True, r"pulley = True"),
    ]:
        with pytest.raises(SceneError, match=match):
            run.contact_profile(bad)
    for kw, match in [
        (dict(bins=0), r"bins = 0: must be an integer >= 1"),
        (dict(bins=2.5), r"bins = 2.5"),
        (dict(start=float("nan")), r"start = nan: must be a finite time"),
        (dict(end="x"), r"end = 'x'"),
        (dict(start=0.04, end=0.01), r"end = 0.01: must not be before start = 0.04"),
        (dict(start=10.0, end=11.0), r"no belt point touches pulley"),
    ]:
        with pytest.raises(SceneError, match=match):
            run.contact_profile(1, **kw)


def test_scene_file_recording_channel(tmp_path) -> None:
    """``channels = [..., "contact_forces"]`` in the [recording] table opts in; a misspelt
    channel names the known ones."""
    scene = driven_scene()
    scene.recording = beltrs.Recording(duration=0.005, channels=("tension", "contact_forces"))
    kw = scene.recording.run_kwargs()
    assert kw["contact_forces"] is True and kw["node_position"] is False
    path = tmp_path / "s.toml"
    save_scene(scene, path)
    back = beltrs.load_scene(path)
    assert back.recording.channels == ("tension", "contact_forces")
    sim = Simulation(back)
    sim.stabilise()
    res = sim.run(back.recording.duration, **back.recording.run_kwargs())
    assert res.contact_normal is not None and res.node_position is None
    scene.recording = beltrs.Recording(channels=("contact_force",))
    with pytest.raises(SceneError, match=r'recording\.channels\[0\] = "contact_force": unknown channel, did you mean '
                                         r'"contact_forces"\? \(known: tension, node_position, node_velocity, '
                                         r'contact_forces\)'):
        Simulation(scene)

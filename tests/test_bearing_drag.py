"""Bearing drag on pulleys (``Pulley.bearing_damping``, N*m*s/rad; drives/bearing.rs):
the Python API, scene files, bad input, and the exponential coast-down of a free pulley."""

import math

import numpy as np
import pytest

import beltrs
from beltrs import Belt, Drive, Pulley, Scene, SceneError

INERTIA = 4.0  # kg*m^2
DAMPING = 2.0  # N*m*s/rad: b/I = 0.5 1/s


def free_pulley(damping: float = DAMPING) -> Scene:
    """A belt loop without gravity; pulley 1 does not touch the belt (contact stiffness 0)
    and is spun up by a drive of 8 N*m for 0.5 s, then coasts on its bearings."""
    return Scene(
        belt=Belt(axial_stiffness=1e6, mass_per_length=10.0, elements=100),
        pulleys=[
            Pulley(center=(0.0, 0.0), radius=0.5, inertia=INERTIA),
            Pulley(
                center=(5.0, 0.0),
                radius=0.5,
                inertia=INERTIA,
                contact_stiffness=0.0,
                bearing_damping=damping,
                drive=Drive(time=[0.0, 0.5, 0.5 + 1e-9], torque=[8.0, 8.0, 0.0]),
            ),
        ],
        gravity=0.0,
    )


def test_a_coasting_pulley_slows_down_exponentially():
    sim = beltrs.Simulation(free_pulley())
    assert "bearing_drag" in sim.stages
    with pytest.warns(beltrs.NotRelaxedWarning):  # started from the placement, on purpose
        sim.run(0.6)
    res = sim.run(2.0, record_interval=0.1)
    w = res.pulley_speed[:, 1]
    # omega(t) = omega(t0) * exp(-b (t - t0) / I): the log-speed falls on a straight line of
    # slope -b/I. Explicit drag decays by (1 - h) per step against exp(-h), h = b*dt/I: a
    # relative slope error of about h/2; allow h.
    slope = np.polyfit(res.time, np.log(w), 1)[0]
    h = DAMPING / INERTIA * sim.dt
    assert slope == pytest.approx(-DAMPING / INERTIA, rel=h)
    assert res.time[-1] == pytest.approx(2.6, abs=1e-12)
    assert w[-1] / w[0] == pytest.approx(math.exp(-1.0), rel=1e-4)


def test_without_bearing_damping_the_pulley_keeps_its_speed():
    sim = beltrs.Simulation(free_pulley(0.0))
    assert "bearing_drag" not in sim.stages
    with pytest.warns(beltrs.NotRelaxedWarning):  # started from the placement, on purpose
        sim.run(0.6)
    res = sim.run(1.0, record_interval=0.1)
    assert np.ptp(res.pulley_speed[:, 1]) == 0.0


def test_bearing_damping_round_trips_through_a_scene_file(tmp_path):
    scene = free_pulley()
    path = tmp_path / "s.toml"
    scene.save(path)
    assert "bearing_damping = 2.0" in path.read_text()
    assert beltrs.load_scene(path).pulleys[1].bearing_damping == DAMPING


@pytest.mark.parametrize("value", [-1.0, math.nan, math.inf])
def test_bad_bearing_damping_names_the_field(value):
    scene = free_pulley(value)
    with pytest.raises(SceneError, match=r"pulleys\[1\]\.bearing_damping"):
        beltrs.Simulation(scene)

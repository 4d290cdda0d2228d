"""Static relaxation of a loaded decline: no equilibrium without friction, refused up front.

Found by outaudit (session 13): on the builder's 40 m conveyor falling 6 m at 400 t/h,
``stabilise()`` ground through 400 000 steps (residual 6.9e-2) and 5 M steps at the
default tolerance (1.18e-1) without converging. Without belt friction nothing holds a closed
belt from running round its pulleys, and the material on the carry strand pulls it downhill
with m'_L·g·Δh = 55.6 kg/m · 9.81 · 5.25 m ≈ 2.87 kN (loaded from 5 m to the head).
"""

import pytest

import beltrs
from beltrs.conveyor import Conveyor, DriveSpec


def _decline(capacity):
    c = Conveyor(profile=[(0, 0), (40, -6.0)], belt="ST1250", capacity=capacity, speed=2.0,
                 drives=[DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=2.0, ramp=1.5),
                                   control="ideal")])
    return beltrs.Simulation(c.scene())


def test_loaded_decline_relaxation_is_refused_fast_by_name():
    sim = _decline(400.0)
    with pytest.raises(beltrs.BeltrsError, match=r"friction = false: gravity pulls the belt round") as e:
        sim.stabilise(tolerance=1e-5, max_steps=400_000, progress=False)
    # The pull named is the material's: m'_L g Δh = (400/7.2) · 9.81 · 5.25 m = 2861 N on the
    # design path; the nodes' discretisation puts it within 1 %.
    pull = float(str(e.value).split("with ")[1].split(" N")[0])
    assert pull == pytest.approx(400 / 7.2 * 9.81 * 6 * 35 / 40, rel=0.01)
    # This error is raised before the first relaxation step (before the fix: "did not
    # converge" after the 400 000 steps).


def test_empty_decline_still_relaxes():
    # The belt's own weight has no net pull round a closed loop: this one has an equilibrium.
    report = _decline(0.0).stabilise(tolerance=1e-5, max_steps=100_000, progress=False)
    assert report["converged"]

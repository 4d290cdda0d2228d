"""Static relaxation of a loaded decline: no equilibrium without friction, refused up front.

Found by outaudit (session 13): on the builder's 40 m conveyor falling 6 m at 400 t/h,
``stabilise()`` ground through 400 000 steps (residual 6.9e-2) and 5 M steps at the
default tolerance (1.18e-1) without converging. Without belt friction nothing holds a closed
belt from running round its pulleys, and the material on the carry strand pulls it downhill
with m'_L·g·Δh = 55.6 kg/m · 9.81 · 5.25 m ≈ 2.87 kN (loaded from 5 m to the head).

With friction (session 14) the relaxation holds a stopped conveyor's drive, brake and
holdback pulleys at rest (``PulleyModel::rest_hold``), so friction on the held drum carries
that pull, as on a real conveyor standing on its brakes. Before, the drums turned freely
while relaxing and ``stabilise(friction=True)`` did not converge either (residual 8.3e-4
after 10⁶ steps).
"""

import dataclasses

import numpy as np
import pytest

import beltrs
from beltrs.conveyor import Conveyor, DriveSpec


def _conveyor(capacity, drop=-6.0):
    c = Conveyor(profile=[(0, 0), (40, drop)], belt="ST1250", capacity=capacity, speed=2.0,
                 drives=[DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=2.0, ramp=1.5),
                                   control="ideal")])
    return c.scene()


def _decline(capacity):
    return beltrs.Simulation(_conveyor(capacity))


def _pull(sim):
    """Gravity's pull along the closed node belt, N: the sum over the nodes of m·g along
    the tangent from the node's two neighbours (the engine's up-front check, in the node
    order's sense)."""
    x = sim.state()["node_position"]
    t = np.roll(x, -1, axis=0) - np.roll(x, 1, axis=0)
    t /= np.linalg.norm(t, axis=1)[:, None]
    return float(np.sum(-sim.node_masses() * 9.81 * t[:, 1]))


def _without_running_resistance(scene):
    return dataclasses.replace(scene, idlers=[dataclasses.replace(d, resistance=0.0) for d in scene.idlers])


def _head(scene):
    return [p.name for p in scene.pulleys].index("head")


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


@pytest.mark.parametrize("drop", [-6.0, 6.0], ids=["decline", "incline"])
def test_loaded_slope_relaxes_with_friction_on_the_held_drive_drum(drop):
    # The idlers' running resistance is taken out here: as a quasi-static friction it locks
    # in a share of the pull that depends on the relaxation's path (see the next test), so
    # the drum alone balances what is left, and that is the whole pull.
    scene = _without_running_resistance(_conveyor(400.0, drop))
    sim = beltrs.Simulation(scene)
    angle0 = sim.state()["pulley_angle"].copy()
    report = sim.stabilise(friction=True, tolerance=1e-7, max_steps=400_000, progress=False)
    assert report["converged"]  # before the fix: "did not converge" (the drums ran round)
    head = _head(scene)
    torque = report["holding_torque"]
    free = [j for j in range(len(scene.pulleys)) if j != head]
    # Only the drive pulley is held; the tail and the other pulleys turn freely.
    assert torque[head] != 0.0 and np.all(torque[free] == 0.0)
    pull = _pull(sim)
    assert abs(pull) == pytest.approx(400 / 7.2 * 9.81 * abs(drop) * 35 / 40, rel=0.01)
    # The held drum's reaction balances the pull and opposes it: T/r = -pull within 1 %.
    # Measured -0.41 % (decline) and +0.39 % (incline). The rest is the belt's bending
    # springs and the idler kinks, whose forces the tangent sum does not see exactly: with
    # EI = 0 the decline reads +0.16 %. A 0.1 kN error in either sense would fail.
    assert torque[head] / scene.pulleys[head].radius == pytest.approx(-pull, rel=0.01)
    # The belt does not creep round: the held drum has not turned and the free tail drum
    # has turned by the belt's stretch only (measured 0.2 mm at its surface; a belt running
    # round, as before the fix, turns it by metres).
    angle = sim.state()["pulley_angle"]
    assert angle[head] == angle0[head]
    for j in free:
        assert abs(angle[j] - angle0[j]) * scene.pulleys[j].radius < 1e-3


@pytest.mark.parametrize("drop", [-6.0, 6.0], ids=["decline", "incline"])
def test_loaded_slope_relaxes_with_friction_at_the_builder_defaults(drop):
    # As the builder makes it, with the idlers' running resistance (f = 0.02): the
    # relaxation converges, and the drum takes the pull less what the resisting idlers
    # hold at rest. They can hold at most f·(N + m_R·g) each, and their normal forces sum
    # to at most the belt's and material's weight W on this straight profile, so the drum's
    # share lies within f·W + Σ f·m_R·g = 0.92 kN of the pull (measured: the idlers took
    # -0.29 kN on the decline, +0.52 kN on the incline).
    scene = _conveyor(400.0, drop)
    sim = beltrs.Simulation(scene)
    report = sim.stabilise(friction=True, tolerance=1e-5, max_steps=400_000, progress=False)
    assert report["converged"]
    head = _head(scene)
    weight = float(np.sum(sim.node_masses()) * 9.81)
    f = max(d.resistance for d in scene.idlers)
    bound = f * weight + sum(d.resistance * d.rotating_mass * 9.81 for d in scene.idlers)
    held = report["holding_torque"][head] / scene.pulleys[head].radius
    pull = _pull(sim)
    assert abs(held + pull) <= bound, (held, pull, bound)
    # The drum does take the pull, not the idlers alone.
    assert abs(held) > 0.5 * abs(pull)


def test_loaded_incline_relaxes_on_a_holdback():
    # A holdback alone holds the incline's backward pull (it stops the head turning
    # backwards); the result is the drive-held one's.
    scene = _without_running_resistance(_conveyor(400.0, 6.0))
    head = _head(scene)
    pulleys = list(scene.pulleys)
    pulleys[head] = dataclasses.replace(pulleys[head], drive=None, holdback=beltrs.Holdback(forward="cw"))
    scene = dataclasses.replace(scene, pulleys=pulleys)
    sim = beltrs.Simulation(scene)
    report = sim.stabilise(friction=True, tolerance=1e-7, max_steps=400_000, progress=False)
    assert report["converged"]
    assert report["holding_torque"][head] / scene.pulleys[head].radius == pytest.approx(-_pull(sim), rel=0.01)


def test_relaxing_without_friction_holds_nothing():
    report = _decline(0.0).stabilise(tolerance=1e-5, max_steps=100_000, progress=False)
    assert np.all(report["holding_torque"] == 0.0)

"""Starting from the static design state (scene ``initial``, beltrs.design_start,
Conveyor(start=...)): the placement against the tensions it was given, a running start in
its own steady state, the agreement of the dynamic drive tensions with beltrs.statics, the
rigid-body limit F = M_eq·a (thesis §1.4), the takeup travel of a loaded start against
the change in the belt's elastic length, and bad input on every path."""

import functools
from dataclasses import replace
import math

import numpy as np
import pytest

import beltrs
from beltrs import design_start, statics
from beltrs.conveyor import BeltClass, Conveyor, DriveSpec, TakeupSpec
from beltrs.scene_file import dumps_scene, loads_scene


def loop_scene(**initial):
    """Two 0.5 m pulleys 4 m apart, no gravity, EA = 1 MN, 100 elements."""
    return beltrs.Scene(
        belt=beltrs.Belt(axial_stiffness=1e6, mass_per_length=2.0, elements=100, damping_ratio=0.05),
        pulleys=[
            beltrs.Pulley(name="left", center=(0.0, 0.0), radius=0.5, contact_stiffness=1e8),
            beltrs.Pulley(name="right", center=(4.0, 0.0), radius=0.5, contact_stiffness=1e8),
        ],
        gravity=0.0,
        recording=beltrs.Recording(stabilise=False),
        initial=beltrs.Initial(**initial),
    )


def test_uniform_design_tension_is_placed_exactly():
    # 10 kN everywhere: every element, on the spans and on the wraps (where the nodes sink
    # by N/k into the penalty contact), reads 10 kN, and stays so (a belt in equilibrium).
    scene = loop_scene(tension=(10e3,))
    sim = beltrs.Simulation(scene)
    t = sim.tensions()
    np.testing.assert_allclose(t, 10e3, rtol=2e-3)
    # the unstretched length: path / (1 + T/EA), less the polygon's shortfall on the drums
    # (elements of 0.22 rad: θ²/24 = 2e-3 of the 3.1 m of wraps)
    path = 2 * 4.0 + 2 * math.pi * 0.5
    assert sim.rest_length.sum() == pytest.approx(path / 1.01, rel=1e-3)
    sim.run(0.05, record_interval=0.01, tension=False, node_position=False, node_velocity=False)
    # in equilibrium, it stays so: measured ±0.6 % (the nodes where the belt runs onto a
    # drum sink by their share of the contact only approximately)
    np.testing.assert_allclose(sim.tensions(), 10e3, rtol=1e-2)


def test_tension_table_is_followed_and_speed_set():
    # Tension rising linearly round the loop from 5 to 15 kN and back: each element's
    # tension equals the table at its middle; every node moves at 3 m/s along the path,
    # each pulley at 3 / 0.5 rad/s (counter-clockwise wraps).
    path = 2 * 4.0 + 2 * math.pi * 0.5
    scene = loop_scene(tension=(5e3, 15e3), distance=(0.0, path / 2), speed=3.0)
    sim = beltrs.Simulation(scene)
    x = sim.state()["node_position"]
    t = sim.tensions()
    rest = sim.rest_length
    # arc length of each element's middle: cumulative stretched lengths
    chord = np.linalg.norm(np.roll(x, -1, axis=0) - x, axis=1)
    mid = np.cumsum(chord) - chord / 2
    expect = np.interp(mid, [0, path / 2, path], [5e3, 15e3, 5e3])
    np.testing.assert_allclose(t, expect, rtol=0, atol=60.0)  # 0.4 % of 15 kN: drum-edge nodes
    assert np.all(rest == rest[0])
    v = np.linalg.norm(sim.state()["node_velocity_half_step"], axis=1)
    np.testing.assert_allclose(v, 3.0, rtol=1e-6)
    np.testing.assert_allclose(sim.state()["pulley_speed"], 6.0, rtol=1e-12)


@pytest.mark.parametrize("control", ["vfd", "ideal"])
def test_running_start_of_case_g_is_steady(control):
    """Case G shortened to 120 m, started at running speed from DIN 22101's tensions: the
    drive tensions hold their design values through a 2 s settle (no relaxation at all).
    Both drives: the builder's default VFD starts from the design state's holding torque
    (docs/drives.md, "Drives at a design start") and answers the belt's own settle with its
    finite bandwidth; the ideal speed follower holds the drum exactly. DIN's tensions are
    the same answer for both, plus the running belt's m'_G·v² (98 N, 0.2 %) the placement
    now carries (docs/design-start.md, "Running at speed: the belt's m'·v²"). Measured
    (session 14) against DIN + m'_G·v²: T1 +0.25 %, T2 -0.15 % (VFD); +0.24 %, -0.18 %
    (ideal). (Session 11, placed at DIN's tensions, against DIN: +0.46 / +0.05 %.)"""
    scene = beltrs.scenes.guo_wang_conveyor(length=120.0, start="running", control=control)
    din = beltrs.scenes.guo_wang_statics(length=120.0)
    sim = beltrs.Simulation(scene)
    probes = [(110.0, 0.4), (110.0, -0.4)]
    data = beltrs.analysis.probe_run(sim, probes, 2.0, 0.005)
    t = data["time"]
    late = t >= 1.0
    t1, t2 = data["tension"][late].mean(axis=0)
    # DIN at the probes: 10 m before the head on the carry (loop distance 120 - 0.8 - 10),
    # 10 m after it on the return; running, plus the belt's m'_G·v² = 24.5 x 2² = 98 N (the
    # gravity takeup, beltrs.design_start.running_tension)
    spin = beltrs.design_start.running_tension(24.5, 2.0)
    d1, d2 = din.along(120.0 - 0.8 - 10.0) + spin, din.along(120.0 - 0.8 + 10.0) + spin
    print(f"case G 120 m running ({control}): T1 {t1 / d1 - 1:+.2%}, T2 {t2 / d2 - 1:+.2%} against DIN + m'v^2")
    assert t1 == pytest.approx(d1, rel=0.03)
    assert t2 == pytest.approx(d2, rel=0.03)
    speed = -data["pulley_speed"][:, 1] * 0.4
    if control == "ideal":
        np.testing.assert_allclose(speed, 2.0, rtol=1e-9)
    else:
        # the PI's band (as tests/test_conveyor.py's steady running): measured 0.068 % at
        # worst, 0.014 % after 1 s
        np.testing.assert_allclose(speed, 2.0, rtol=5e-3)


# --- the builder --------------------------------------------------------------------------
L = 150.0


def short(**kw):
    kw.setdefault("drives", [DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=2.0, ramp=4.0))])
    return Conveyor(profile=[(0, 0), (L, 0)], belt="ST1250", capacity=400.0, speed=2.0, **kw)


def test_builder_running_start_agrees_with_statics_within_3_percent():
    """Issue 12's agreement target at default settings: a builder conveyor started at
    running speed from its design state, T1 and T2 at the drive (10 m from the drum, mean
    of the last 2 s of a 4 s run) against Conveyor.statics() at the same places plus the
    running belt's m'_G·v² (89.6 N, 0.6 %; docs/design-start.md, "Running at speed: the
    belt's m'·v²"). Measured (session 14): T1 +0.64 %, T2 -0.64 %."""
    c = short(start="running")
    p = c.statics()
    sim = beltrs.Simulation(c.scene())
    r = c.radius
    data = beltrs.analysis.probe_run(sim, [(L - 10.0, 0.0), (L - 10.0, -2 * r)], 4.0, 0.005)
    window = data["time"] >= 2.0
    t1, t2 = data["tension"][window].mean(axis=0)
    spin = c.belt_mass * c.speed**2  # the running belt's m'_G·v², 89.6 N (gravity takeup)
    d1, d2 = p.along(L - 10.0) + spin, p.along(L + 10.0) + spin
    print(f"builder 150 m running: T1 {t1 / d1 - 1:+.2%}, T2 {t2 / d2 - 1:+.2%} against DIN + m'v^2")
    assert t1 == pytest.approx(d1, rel=0.03)
    assert t2 == pytest.approx(d2, rel=0.03)


def test_running_start_at_8_m_s_carries_the_belts_m_v2_and_holds_the_takeup():
    """docs/design-start.md, "Running at speed: the belt's m'·v²": the 50 m builder
    conveyor (ST1250, m'_G = 22.39 kg/m, 500 t/h, gravity takeup at the tail) started at
    8 m/s. The belt wrapping the takeup drum presses on it with (T − m'_G·v²)/R, so the
    carriage balances 2·(T − m'_G·v²): running, the tension is DIN's plus m'_G·v² = 1433 N
    (9 % of T1 here), and the placement puts it there.

    Measured (session 14, /tmp/spin/measure.py, probes 10 m either side of the head drum
    every 5 ms over 3 s): at t = 0 T1, T2 = DIN + m'_G·v² to 0.01 %; the mean of 1-3 s
    +0.68 % / -0.66 %; the takeup's mean travel over 1-3 s -0.20 mm (its 0.25 s means
    -0.35 ... -0.08 mm: the belt settles, it does not drift). Placed at DIN's tensions (the
    fix undone) the tensions still rise to DIN + m'_G·v² (+0.58 % / -0.82 %) because the
    carriage moves: its mean travel is +1.14 mm (m'_G·v²·loop/(2·EA) = 0.88 mm, plus the
    ringing it starts), at t = 0 the probes read 8.4 % / 9.4 % under this reference.

    Tolerances: 0.1 % at t = 0 (the node placement, as the rest start); 3 % on the 1-3 s
    mean (issue 12's target); |mean travel| < 0.5 mm, about half the shift m'_G·v² would
    cause (0.88 mm predicted, 1.14 mm measured without the term) and 2.5 x what the placed
    belt settles by (0.20 mm), so the test fails without the fix on both counts."""
    v, length = 8.0, 50.0
    c = Conveyor(profile=[(0.0, 0.0), (length, 0.0)], belt="ST1250", capacity=500.0, speed=v, start="running",
                 drives=[DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=v, ramp=4.0))])
    s = c.scene()
    assert s.belt.mass_per_length == c.belt_mass  # m'_G: the belt alone, material is a Load
    spin = beltrs.design_start.running_tension(c.belt_mass, v)
    assert spin == pytest.approx(c.belt_mass * v**2, rel=1e-12) and spin > 1400.0
    p = c.statics()
    d = np.array([p.along(length - 10.0), p.along(length + 10.0)]) + spin
    sim = beltrs.Simulation(s)
    tail = s.pulley_index("tail")
    assert s.pulleys[tail].takeup is not None
    data = beltrs.analysis.probe_run(sim, [(length - 10.0, 0.0), (length - 10.0, -2 * c.radius)], 3.0, 0.005)
    t, r = data["time"], data["tension"]
    travel = data["takeup_travel"][t >= 1.0, tail].mean()
    print(f"50 m at 8 m/s: t = 0 {(r[0] / d - 1).round(5)}, 1-3 s {(r[t >= 1.0].mean(axis=0) / d - 1).round(4)},"
          f" takeup mean travel {travel * 1e3:.3f} mm")
    np.testing.assert_allclose(r[0], d, rtol=1e-3)
    np.testing.assert_allclose(r[t >= 1.0].mean(axis=0), d, rtol=0.03)
    assert abs(travel) < 0.5e-3


def test_running_tension_by_takeup_kind():
    # A screw takeup fixes the belt's length: no m'_G·v² on top (its drums unload instead);
    # a winch at its set force acts as the counterweight. At rest nothing is added.
    from beltrs import design_start

    assert design_start.running_tension(20.0, 5.0, "gravity") == 500.0
    assert design_start.running_tension(20.0, -5.0, "winch") == 500.0
    assert design_start.running_tension(20.0, 5.0, "fixed") == 0.0
    assert design_start.running_tension(20.0, 0.0) == 0.0
    fixed = short(start="running", takeup=TakeupSpec("tail", kind="fixed", tension=20e3))
    gravity = short(start="running", takeup=TakeupSpec("tail", tension=20e3))
    tf, tg = np.array(fixed.initial().tension), np.array(gravity.initial().tension)
    np.testing.assert_allclose(tg - tf, gravity.belt_mass * 2.0**2, rtol=1e-9)
    # Conveyor.statics(running=True): the same term on the tables (default unchanged)
    din, run = gravity.statics(), gravity.statics(running=True)
    np.testing.assert_allclose(run.tension - din.tension, gravity.belt_mass * 2.0**2, rtol=1e-12)
    assert run.drive("head").force == pytest.approx(din.drive("head").force, rel=1e-12)
    assert run.drive("head").slack - din.drive("head").slack == pytest.approx(gravity.belt_mass * 4.0, rel=1e-12)
    np.testing.assert_array_equal(fixed.statics(running=True).tension, fixed.statics().tension)
    with pytest.raises(beltrs.SceneError, match=r"running = 'yes': must be True or False"):
        gravity.statics(running="yes")
    with pytest.raises(beltrs.SceneError, match=r"takeup = 'screw': must be 'gravity', 'winch' or 'fixed'"):
        design_start.running_tension(20.0, 5.0, "screw")
    with pytest.raises(beltrs.SceneError, match=r"belt_mass = -1"):
        design_start.running_tension(-1.0, 5.0)


@pytest.mark.parametrize("control", ["vfd", "ideal"])
def test_builder_rest_start_holds_still(control):
    # At rest from the standstill tensions on a loaded incline with a vertical curve, the
    # drive holding: the drums hold the belt (no creep along the path), and in 0.5 s the
    # belt only settles into its sag between the rolls: the mean tension moves by under 1 %,
    # the takeup by millimetres. Both drives: the ideal speed follower holds its drum
    # exactly; the builder's default VFD holds it through its PI loop, which answers the
    # belt's settle (the holding torque moves by about 30 N·m) with a small motion of the
    # drum: measured 1.3e-3 rad/s at most, 6.7e-5 rad in all (0.02 mm at the drum's
    # surface). Measured alike for both: mean tension +0.33 %, takeup 0.98 mm.
    c = Conveyor(profile=[(0, 0), (60, 3), (120, 3)], curve_radii=[400.0], belt="EP630/4", capacity=150.0,
                 speed=1.5, takeup=TakeupSpec("tail", tension=20e3),
                 drives=[DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=1.5, ramp=3.0,
                                                                          start=10.0), control=control)])
    s = c.scene()
    assert [p.name for p in s.pulleys] == ["tail", "head"]  # no guides: placed along the profile
    sim = beltrs.Simulation(s)
    t0 = sim.tensions().copy()
    angle0 = sim.state()["pulley_angle"][s.pulley_index("head")]
    # the standstill tensions: the takeup's plus the lifts (DIN 22101 with f = 0)
    rest = beltrs.statics.tensions(design_start.at_rest(c.loop()), c.belt_mass, statics.DIN22101(0.0))
    assert t0.max() == pytest.approx(rest.max, rel=0.01)
    res = sim.run(0.5, record_interval=0.05, tension=True, node_position=False, node_velocity=False)
    assert abs(res.tension[-1].mean() / t0.mean() - 1) < 0.01
    head = s.pulley_index("head")
    if control == "ideal":
        assert np.abs(res.pulley_speed[:, head]).max() < 1e-6  # rad/s: held by its drive
    else:
        # held by the PI: the drum's surface moves by a fraction of a millimetre (a tenth of
        # the takeup's bound below); its speed well below the tail's
        creep = abs(sim.state()["pulley_angle"][head] - angle0) * s.pulleys[head].radius
        assert creep < 5e-4, creep
        assert np.abs(res.pulley_speed[:, head]).max() < 5e-3  # rad/s
    assert np.abs(res.pulley_speed[:, 1 - head]).max() < 0.05  # the tail turns as the takeup settles
    assert abs(res.takeup_travel[-1, 0]) < 5e-3


# --- rigid-body limit ---------------------------------------------------------------------
@pytest.mark.parametrize("control", ["vfd", "ideal"])
def test_slow_start_of_a_stiff_belt_approaches_f_equals_m_a(control):
    """Thesis §1.4 (CEMA): a rigid belt accelerated at a needs F = M_eq·a over its running
    resistance R. Integrated from rest (the work-energy form, which averages out the node
    polygon's ripple on the drums): drive work W = ½·M_eq·v_d² + R·x, v_d the drum's
    surface speed and x the distance it has run. A 30 m conveyor with a belt 10 x stiffer
    than ST1250 (EA = 833 MN: its wave crosses the 62 m loop in 14 ms, 1/140 of the 2 s
    Harrison start) on 1 m drums (elements of 17°, a small ripple); R measured at steady
    running, from the design state at speed (no start to ring down). M_eq from the scene
    alone: belt, rolls I/r², drums I/r² with the drive's inertia, which holds the motor's
    rotor J·i² (the catalogue law at 50 kW, 1500 rpm: J = 0.705 kg·m², 4348 of the
    9552 kg of M_eq, so a law that left the rotor out would read 46 % low; session 10's
    law: 0.617 kg·m², 3808 of 9012 kg, the figures below the same to the digits given).

    Both drives: the builder's default VFD (a PI speed loop with the rotor) and the ideal
    speed follower. The law is the same for both (the rigid body does not care what turns
    the drum); what differs is where the drum is when the ramp ends: the ideal follower
    has it at v and x = v·T/2 exactly, while the PI loop (type 2) lags during the ramp and
    overshoots after it (v_d = 2.023 m/s at 2 s, 2.0009 at 2.5 s, within 10⁻⁴ by 3 s), so
    W is compared with the drum's own v_d and x (with the curve's v and v·T/2 instead the
    VFD would read +2.3 % at 2 s, +0.1 % at 2.5 s). Tolerance 1 %: what a stiff belt still
    stores and rings with; measured (2 s and 4 s ramps, at the ramp's end and up to 2 s
    after) within ±2·10⁻⁴ for both drives."""
    stiff = BeltClass("ST1250 x 10", strength=1.25e6, carcass_mass=9.74, carcass_thickness=0.0045,
                      modulus=8.33e8, top_cover=0.006, bottom_cover=0.005, cord_diameter=0.0045)
    ramp, v = 2.0, 2.0

    def conveyor(start):
        return Conveyor(profile=[(0, 0), (30, 0)], belt=stiff, speed=v, capacity=0.0, start=start,
                        pulley_radius=1.0, takeup=TakeupSpec("tail", tension=20e3),
                        drives=[DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=v, ramp=ramp),
                                          power=50e3, control=control)])

    quiet = dict(tension=False, node_position=False, node_velocity=False)
    running = beltrs.Simulation(conveyor("running").scene())
    running.run(1.0, record_interval=1.0, **quiet)
    w0 = running.state()["drive_work"]
    running.run(3.0, record_interval=1.0, **quiet)
    resistance = (running.state()["drive_work"] - w0) / (v * 3.0)  # N
    c = conveyor("rest")
    scene = c.scene()
    sim = beltrs.Simulation(scene)
    head = scene.pulley_index("head")
    r = scene.pulleys[head].radius
    angle0 = sim.state()["pulley_angle"][head]
    belt = float(np.sum(sim.rest_length)) * c.belt_mass
    rolls = sum(d.inertia / d.radius**2 for d in scene.idlers)
    drums = sum((p.inertia + (p.drive.inertia if p.drive else 0.0)) / p.radius**2 for p in scene.pulleys)
    m_eq = belt + rolls + drums
    assert m_eq == pytest.approx(c.moving_mass(), rel=0.01)  # the builder's own CEMA M_eq
    rotor = c.motor_inertia("head") * (c.drives[0].motor_speed * r / v) ** 2 / r**2  # J·i²/r², kg
    assert scene.pulleys[head].drive.inertia / r**2 == pytest.approx(rotor, rel=1e-12)
    assert rotor > 0.4 * m_eq  # measured 4348 of 9552 kg: the check sees the rotor
    # DIN's F_U: measured 382.3 N against 391.1 (−2.3 %; the drum ripple and the rolls'
    # resistance over the real path)
    assert resistance == pytest.approx(c.statics().effective, rel=0.1)
    fits = []
    for t in (ramp, ramp + 1.0):  # the ramp's end and 1 s after (the PI settled)
        sim.run(t - sim.time, record_interval=t - sim.time, **quiet)
        state = sim.state()
        work = state["drive_work"]  # J
        v_d = -state["pulley_speed"][head] * r  # the drum's surface speed, m/s
        distance = -(state["pulley_angle"][head] - angle0) * r  # m
        if control == "ideal":  # exactly on the curve: v and v·T/2 (a Harrison ramp is symmetric)
            # (the state's speed is at the last half step, Δt/2 before the ramp's end: 1e-10)
            assert v_d == pytest.approx(v, rel=1e-9)
            assert distance == pytest.approx(v * ramp / 2 + v * (t - ramp), rel=1e-6)
        fits.append(2 * (work - resistance * distance) / v_d**2)
    assert fits == pytest.approx([m_eq, m_eq], rel=0.01)


# --- takeup travel ------------------------------------------------------------------------
def test_takeup_travel_of_a_loaded_start_is_half_the_elastic_stretch():
    """During a loaded start the gravity takeup takes up what the belt stretches: its travel
    is half the change of the belt's elastic length ∫ΔT/EA ds (two strands on the takeup
    pulley), at every sample, through the takeup's bounce (an 8 t counterweight on a soft
    EP belt: it overshoots to several times its steady travel).

    100 m, EP630/4 (EA = 6.3 MN), 400 t/h at 2 m/s, a 40 kN takeup; from the design state at
    rest, 0.5 s of settling before a 2 s Harrison start, both travel and stretch counted
    from there. The drive is the builder's default, the VFD (PI speed loop with the motor's
    rotor, 32 kW: J = 0.334 kg·m²); the law is the drive's business only through the
    tensions it causes, so it is the same for the ideal follower. Tolerance 5 % of the peak
    travel: the rest is geometry, not elasticity: the spans' sag shortens as the tension
    rises (its share of the length change, EA·q²·a²/(12·T³), is 0.9 % on the loaded carry at
    40 kN; 7 % at 20 kN, which is why the takeup is heavy here) and the belt's transverse
    motion. Measured (session 11, the spans placed in their sag): VFD 95.3 mm peak travel
    at 1.90 s against 95.0 mm, +0.34 % at the peak and 0.34 % of the peak at worst over the
    samples beyond a fifth of it; the ideal follower (``control="ideal"``) +0.34 % and
    0.34 % alike (95.3 mm at 1.88 s). (The figures written here before: 1.7 % and 2.3 %.)"""
    settle, ramp, length = 0.5, 2.0, 100.0
    c = Conveyor(profile=[(0, 0), (length, 0)], belt="EP630/4", capacity=400.0, speed=2.0,
                 takeup=TakeupSpec("tail", tension=40e3),
                 drives=[DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=2.0, ramp=ramp,
                                                                          start=settle))])
    scene = c.scene()
    sim = beltrs.Simulation(scene)
    res = sim.run(settle + ramp + 1.0, record_interval=0.02, tension=True, node_position=False,
                  node_velocity=False)
    ea = scene.belt.axial_stiffness
    k0 = int(np.searchsorted(res.time, settle - 1e-9))
    stretch = (res.tension - res.tension[k0]) @ sim.rest_length / ea  # m, change of elastic length
    tail = scene.pulley_index("tail")
    # along the pull, away from the conveyor: it takes up the stretch
    travel = res.takeup_travel[:, tail] - res.takeup_travel[k0, tail]
    peak = float(np.abs(travel).max())
    k = int(np.argmax(np.abs(travel)))
    assert travel[k] > 0.05  # m: a real stretch, far above the settling (0.013 mm measured)
    assert travel[k] == pytest.approx(stretch[k] / 2, rel=0.05)
    big = np.abs(travel) > 0.2 * peak
    assert big.sum() > 20
    assert np.max(np.abs(travel[big] - stretch[big] / 2)) < 0.05 * peak


# --- bad input ------------------------------------------------------------------------------
@pytest.mark.parametrize("initial, match", [
    (dict(tension=()), r"initial.tension = \[\]: give at least one"),
    (dict(tension=(-1.0,)), r"initial.tension\[0\] = -1: must be ≥ 0"),
    (dict(tension=(1.0, 2.0)), r"initial.distance = \[\]: give a distance"),
    (dict(tension=(1.0, 2.0), distance=(0.0,)), r"initial.distance = 1 values: needs as many"),
    (dict(tension=(1.0, 2.0), distance=(3.0, 1.0)), r"initial.distance\[1\] = 1: must increase"),
    (dict(tension=(1.0, 2.0), distance=(0.0, 99.0)), r"initial.distance\[1\] = 99: must be below the path length"),
    (dict(tension=(5e5,)), r"initial.tension\[0\] = 500000: stretches the belt"),
    (dict(tension=(1.0,), speed=math.nan), r"initial.speed = NaN: must be a finite"),
    (dict(tension=(1.0,), path=((0.0, 0.5, 0.0), (4.0, 0.5, 0.0), (4.0, -0.5, 0.0))),
     r"initial.path\[0\]\[2\] = 0: the path turns"),
    (dict(tension=(1.0,), path=((0.0, 0.0, 0.1), (4.0, 0.0, 0.1))), r"initial.path\[0\].*more than 179°"),
    (dict(tension=(1.0,), path=((-0.2, 1, 0.2), (5, 1, 0.2), (5, -1, 0.2), (-0.2, -1, 0.2))),
     r"initial.path = .*the belt would start inside it"),
    (dict(tension=(1.0,), path=((-1, 1, 5.0), (5, 1, 5.0), (5, -1, 5.0), (-1, -1, 5.0))),
     r"initial.path\[1\]\[2\] = 5: the arcs at corners 0 and 1 need"),
    (dict(tension=(1.0,), path=((0.0, 0.0, 1.0),)), r"initial.path = 1 corner: a closed path needs"),
])
def test_bad_initial_is_a_scene_error_on_every_path(initial, match, tmp_path):
    scene = loop_scene(**initial)
    with pytest.raises(beltrs.SceneError, match=match):
        beltrs.Simulation(scene)
    # the same scene as a dict and as a TOML file
    with pytest.raises(beltrs.SceneError, match=match):
        beltrs.Simulation(beltrs.Scene.from_dict(scene.to_dict()))
    path = tmp_path / "s.toml"
    scene.save(path)
    with pytest.raises(beltrs.SceneError, match=match):
        beltrs.Simulation(beltrs.load_scene(path))


def test_initial_excludes_length_and_relaxation():
    s = loop_scene(tension=(1e3,))
    s.belt.length = 11.0
    with pytest.raises(beltrs.SceneError, match=r"belt.length = 11: give belt.length or an \[initial\]"):
        beltrs.Simulation(s)
    s = loop_scene(tension=(1e3,))
    s.recording.stabilise = True
    with pytest.raises(beltrs.SceneError, match=r"recording.stabilise = true: must be false with an \[initial\]"):
        beltrs.Simulation(s)
    with pytest.raises(beltrs.SceneError, match=r"initial.tensoin = 'tensoin': unknown key, did you mean 'tension'"):
        beltrs.Scene.from_dict({"initial": {"tensoin": [1.0]}})
    with pytest.raises(beltrs.SceneError, match=r"initial.speed"):
        beltrs.Scene.from_dict({"initial": {"tension": [1.0], "speed": "fast"}})


def test_initial_round_trips_through_toml(tmp_path):
    s = loop_scene(tension=(5e3, 15e3), distance=(0.0, 5.0), speed=-1.5)
    path = tmp_path / "s.toml"
    s.save(path)
    back = beltrs.load_scene(path)
    assert back == s and back.initial.speed == -1.5


@pytest.mark.parametrize("kw, match", [
    (dict(start="moving"), r"start = 'moving': must be one of 'rest', 'running'"),
])
def test_builder_bad_start(kw, match):
    with pytest.raises(beltrs.SceneError, match=match):
        short(**kw).scene()
    with pytest.raises(beltrs.SceneError, match=match):
        beltrs.conveyor.loads('[conveyor]\nstart = "moving"\n')


def test_design_start_helpers_bad_input():
    p = short().statics()
    with pytest.raises(beltrs.SceneError, match=r"profile = 3: expected a beltrs.statics.TensionProfile"):
        design_start.tension_table(3, [design_start.Wrap("tail", 0.0, 1.0)], 10.0)
    with pytest.raises(beltrs.SceneError, match=r"pieces\[0\] = 'x': expected a beltrs.design_start.Run or Wrap"):
        design_start.tension_table(p, ["x"], 10.0)
    with pytest.raises(beltrs.SceneError, match=r"pieces\[0\].end = 1.0: must exceed start"):
        design_start.tension_table(p, [design_start.Run(2.0, 1.0, 0.0, 1.0)], 10.0)
    with pytest.raises(beltrs.SceneError, match=r"path_length = -1: must be > 0"):
        design_start.tension_table(p, [design_start.Run(0.0, 1.0, 0.0, 1.0)], -1)
    with pytest.raises(beltrs.SceneError, match=r"label = 'pulley: in': no such place"):
        design_start.tension_table(p, [design_start.Wrap("pulley", 0.0, 1.0)], 10.0)
    with pytest.raises(beltrs.SceneError, match=r"speed = inf: must be finite"):
        design_start.initial(p, [design_start.Run(0.0, 1.0, 0.0, 1.0)], 10.0, speed=math.inf)
    with pytest.raises(beltrs.SceneError, match=r"start = 'x': must be None, 'rest' or 'running'"):
        beltrs.scenes.guo_wang_conveyor(length=50.0, start="x")


# --- sag placement (initial.sag) ----------------------------------------------------------

def _span_sags(x, pitch, spans):
    """(x of the lowest carry node, its depth below the roll tops) in each carry span."""
    out = []
    for k in spans:
        xa = 0.5 * pitch + pitch * k
        m = (x[:, 1] > -0.2) & (x[:, 0] > xa) & (x[:, 0] < xa + pitch)
        j = np.flatnonzero(m)[np.argmin(x[m, 1])]
        out.append((x[j, 0] - xa, -x[j, 1]))
    return np.array(out)


def test_builder_places_the_spans_in_their_sag():
    # A level 60 m builder conveyor at rest (ST1250, 500 t/h at 2 m/s: q = 1055 N/m on the
    # loaded carry, T = 14 kN, a = 1.2 m, elements of 0.21 m). The placement is the discrete
    # belt's statics (kernel tests: model/design_tests.rs); here, each span's lowest node
    # against the parabola q·x·(a − x)/(2T) at its abscissa. The belt over a roll is one
    # straight element whose nodes sit up to θ·l/2 above the continuous curve (θ = q·a/2T,
    # l the element) plus R·θ²/2 for its tilt on a roll of radius R: 4.1 mm of the 11.6 mm
    # mid-span sag at these long elements, so the reading spreads from span to span by
    # where the nodes fall (measured 7.8–9.9 mm); that is the tolerance. In 0.5 s at rest the
    # sags then move by under a fifth of q·a²/(8T) (measured 0.9 mm: the drive holds and
    # the takeup settles), where the straight placement's spans sink by all of it.
    c = Conveyor(profile=[(0, 0), (60, 0)], belt="ST1250", capacity=500.0, speed=2.0)
    scene = c.scene()
    assert scene.initial.sag is True  # the builders' default (docs/design-start.md)
    q = (c.belt_mass + c.material_mass) * 9.81
    a = c.carry.pitch
    spans = range(15, 33)  # 18.6–40.2 m: loaded, away from the drums
    moved = {}
    for sag in (True, False):
        sim = beltrs.Simulation(replace(scene, initial=replace(scene.initial, sag=sag)))
        x0 = sim.state()["node_position"]
        carry = (x0[:, 1] > -0.2) & (x0[:, 0] > 20) & (x0[:, 0] < 40)
        t = float(sim.tensions()[carry].mean())
        theta, el = q * a / (2 * t), float(sim.rest_length[0])
        mid = q * a * a / (8 * t)
        before = _span_sags(x0, a, spans)
        if sag:
            assert t == pytest.approx(14e3, rel=1e-3)
            parabola = q * before[:, 0] * (a - before[:, 0]) / (2 * t)
            bound = theta * el / 2 + 0.0635 * theta**2 / 2
            assert np.all(np.abs(before[:, 1] - parabola) < bound), (before, parabola, bound)
            assert np.all(before[:, 1] > 0.5 * mid)
        else:
            assert np.abs(before[:, 1]).max() < 1e-9  # straight from roll to roll
        sim.run(0.5, record_interval=0.05, tension=False, node_position=False, node_velocity=False)
        after = _span_sags(sim.state()["node_position"], a, spans)
        moved[sag] = np.abs(after[:, 1] - before[:, 1]).max() / mid
    assert moved[True] < 0.2 and moved[False] > 0.25, moved


def test_initial_sag_round_trips_and_bad_values_name_the_field(tmp_path):
    s = loop_scene(tension=(5e3,))
    assert s.initial.sag is False
    s.initial = replace(s.initial, sag=True)
    path = tmp_path / "s.toml"
    s.save(path)
    assert "sag = true" in path.read_text()
    back = beltrs.load_scene(path)
    assert back == s and back.initial.sag is True
    for bad in ("yes", 1, None):
        with pytest.raises(beltrs.SceneError, match=r"initial.sag"):
            beltrs.Simulation(replace(s, initial=replace(s.initial, sag=bad)))
    with pytest.raises(beltrs.SceneError, match=r"initial.sag = 'yes': expected true or false"):
        beltrs.Scene.from_dict({"initial": {"tension": [1.0], "sag": "yes"}})
    path.write_text(path.read_text().replace("sag = true", 'sag = "no"'))
    with pytest.raises(beltrs.SceneError, match=r"initial.sag"):
        beltrs.load_scene(path)


# --- the rigid-body belt (issue 12) -------------------------------------------------------
def test_rigid_body_design_start_of_case_g_holds_din_tensions_at_rest():
    """Case G at 60 m with Guo & Wang's rigid bodies, started at rest from DIN 22101's
    standstill tensions (``start="rest"``, the drive holding until 5 s), probes 10 m either
    side of the head drum, the spans placed in their sag (``initial.sag``, the builder's
    default for both formulations). At t = 0 the joints carry DIN's tensions to 0.1 % (the
    placement's joint error, Rust tests ``rigid_design_start_carries_its_tension_and_stays_
    at_rest``: 0.085 %, ``rigid_sag_placement_hangs_the_spans_and_holds_the_joints``:
    0.03 %; measured here 50 000.00 / 50 000.00 N at the builder's 0.1185 m bodies,
    49 999.98 / 50 000.00 N at 0.196 m).

    Over the first second at rest, measured at 0.1185 m bodies (session 13): rigid −0.52 % /
    +0.03 % at 1 s, at most 0.52 % over the second. Earlier, at 0.196 m bodies and before
    the wrap joints' landing: rigid −0.08 % / −0.43 % at 1 s, at most 0.43 %
    over the second (placed straight, before the sag placement: −1.67 % / +0.65 % at 1 s,
    3.6 % at most); the node belt of the same scene 0.09 %. The rigid belt's rest is the
    node belt's 0.09 % plus what its transition bodies at the drums' tangent points give
    (each spans the strand's line and the wrap's vertex circle: out of balance by up to
    8 kN at t = 0 on the 0.4 m drums' 30° bodies, the same with or without sag): a ringing
    that settles into a static shift of about ±0.2 % held by the rolls' resistance (the
    carry's tension then falls 4.5 N/m towards the head). Asserted here: the node belt
    within 0.5 % over the second; the rigid start within 1 % over the whole second (a start
    placed straight fails that: 3.6 %) is the next test's."""
    runs = rigid_and_node_rest_runs()
    din = runs["node_kelvin_voigt"][0]  # the node placement is exact to the table (1e-6)
    np.testing.assert_allclose(runs["rigid_body"][0], din, rtol=1e-3)
    node_off = np.abs(runs["node_kelvin_voigt"][-1] / din - 1).max()
    assert node_off < 0.005, node_off


def test_rigid_body_design_start_of_case_g_stays_within_1_percent_over_the_first_second():
    """The rigid start of the test above within 1 % of DIN over the whole second (see its
    docstring), with the builder's wrap joints and bodies (0.1185 m since session 13).

    Measured (session 13) with both of that session's changes: the wrap joints' C² fades of
    1 % with the landing kept out of them (``design_rigid::landings``), and the builders'
    rigid bodies of at most 0.3 x the drum radius (docs/kubas.md "The bodies' length on the
    drums"): 0.59 % at 0.1185 m, and at the lengths around it, off the pitches, 0.1148 /
    0.1244 / 0.1297 / 0.14 / 0.1477 m 0.21 / 0.12 / 0.34 / 0.16 / 0.73 % (lead, merge; the
    same probes): under 1 % at every phase tried, hence the strict xfail lifted. Each change
    alone did not: the shorter bodies with the 4 % C¹ fades read 0.52 % here but 0.11-2.10 %
    around it (0.1148 m 2.10 %, 0.105 m 2.03 %, 0.1297 m 2.10 %); the fades at 0.196 m read
    1.07 % (below).

    Before, at 0.196 m bodies, measured (session 12):
    0.71 % (the probes every 0.1 s; main before: +2.15 % / -1.76 % at 0.1 s, a strict xfail).

    The wrap joints' placement (``design_rigid::Landing``, docs/design-start.md, "Where the
    strands meet the drums"): each strand runs straight onto one joint of the drum's vertex
    circle, sunk by its own bend's load, instead of bending where its line meets the circle
    wherever the joints fall (which, at some phases of the bodies on the 0.4 m drums, bent
    the body spanning that point at both its joints: two wrap joints active at once). The
    transient still depends on the phase, less: max over the second for body lengths
    0.2 / 0.198 / 0.196 / 0.195 / 0.19 m, 1.11 / 1.17 / 0.71 / 0.80 / 0.99 % (main: 0.47 /
    0.64 / 2.15 / 1.09 / 1.50 %; plain joints, placed as before, 0.44 / 0.47 / 0.44 / 0.59 /
    0.47 %): what is left is the wrap joint's bend couple x'(psi)*T on the strand's last
    body (up to 420 N*m on case G), which the placement does not balance (docs/kubas.md,
    "Wrap joints"). Asserted at the default, 1 %, the issue's target for the start.

    Merged with the drums taking back the rigid contact's moment (session 12, docs/kubas.md,
    "The contact's moment on the drum"), the lead measured 1.014 % (each branch alone: this
    one 0.71 %, the moment's with main's placement 1.065 %): hence the strict xfail then.

    What the 1 % is on main a7cf348 (session 12, rigidrun; probes every 5 ms): not a
    ringing but the VFD giving way. Its PI is primed (drives/prime.rs) with the head drum's
    holding torque from the t = 0 forces, 440.7 N*m, including the rigid contact's moment
    at t = 0; once the transition bodies have settled (within 0.1 s) the drum needs about
    115 N*m (the ideal follower's mean, 88-127 per 0.1 s). The PI's integral takes the
    difference as an angle: the head drum turns 0.34 mrad in the first 0.2 s, 0.17 mm of
    belt go from the carry to the return, and the rolls hold the carry's deficit: the carry
    probe sits at -0.85 % from 0.4 s on (return +0.03 %). With ``control="ideal"`` the same
    start reads 0.26 % (0.75 / 0.56 / 0.26 / 0.35 / 0.82 % for 0.19 / 0.195 / 0.196 / 0.198
    / 0.2 m bodies; the VFD 1.01 / 1.93 / 1.02 / 2.04 / 1.03 %). Priming from the strands'
    joint tensions at the drum instead (tried, not kept) read 0.43 % at 0.196 m but 1.32 /
    1.91 / 1.94 / 0.74 % at the other lengths: the settle's torque depends on the phase, so
    the placement has to balance the transition bodies (the bend couple) for the prime to
    be right.

    Session 13 (wrap joints' fades 1 % with a C² step, the landing kept out of the fades,
    ``design_rigid::landings``): 1.07 % at 0.196 m; 0.81 / 1.06 / 0.95 / 0.82 % at 0.19 /
    0.195 / 0.198 / 0.2 m (before: 1.01 / 1.93 / 2.04 / 1.03 %). Less phase-dependent, the
    default not yet under 1 %: the bend couple (up to (R - rho)*T on the strand's last body)
    is still left to the settle. With stick-force friction's arms (session 13, docs/kubas.md,
    "The contact's moment on the drum"): 1.062 % (main edfc824 1.072 %)."""
    runs = rigid_and_node_rest_runs()
    din = runs["node_kelvin_voigt"][0]
    off = np.abs(runs["rigid_body"] / din - 1).max()
    assert off < 0.01, off


def test_rigid_body_running_design_start_of_case_g_holds_the_static_tensions():
    """Issue 12, "at steady running, the dynamic drive tensions agree with the static
    calculation within 3 %", for the rigid belt (builder defaults: wrap joints, 0.1185 m
    bodies since session 13): case G at 60 m started at 2 m/s from DIN 22101's running tensions, T1 and T2
    10 m either side of the head drum, every 5 ms over 2 s, against ``guo_wang_statics``
    at the same places plus the running belt's m'_G·v² = 98 N (0.2 %, which the placement
    carries since session 14: docs/design-start.md, "Running at speed: the belt's m'·v²")
    (as ``test_running_start_of_case_g_is_steady`` for the node belt).

    Measured (session 14, against DIN + m'_G·v², 0.1185 m bodies): at t = 0 +0.015 % /
    -0.005 %, the second second's mean +0.21 % / -0.19 %, the 0.25 s windows' means within
    0.30 %; the 5 ms readings' ripple 0.86 / 1.46 % rms.

    Measured at the builder's 0.1185 m bodies (session 13, placed at DIN, against DIN): at
    t = 0 0.015 % at most, the second second's mean 0.41 % at most, the 0.25 s windows'
    means within 0.57 %; the 5 ms readings' ripple 0.89 % rms, 2.4 % at worst.

    Measured at 0.196 m bodies (session 12, main a7cf348 + this test): at t = 0 +0.011 % / -0.005 % (the
    placement); mean of the second second +0.43 % / +0.05 % (node belt +0.40 % / +0.03 %);
    the means of the eight 0.25 s windows at most 0.73 % off (node belt 0.53 %): no drift.
    The probes' instantaneous readings carry the rigid chain's running ripple at multiples
    of v/l (2 m/s over 0.196 m bodies = 10.2 Hz; lines at 20.4, 30.6, 40.8 and 61.2 Hz of
    0.25-0.5 kN), 1.5 % rms (node belt 0.2 %), 6.4 % at worst: the next test's strict xfail
    then.

    Tolerances: 0.1 % at t = 0 (the rigid placement's joint error on the strands, see the
    rest start above); 3 % on the second second's mean, the issue's target; 1 % on each
    0.25 s window's mean, the issue's 1 % for a design start (each window spans 2.5 periods
    of v/l and 5-15 of the higher lines; with plain joints, whose v/l ripple is 12 % rms,
    the windows' means reach 2.7 %, so this can fail)."""
    scene = beltrs.scenes.guo_wang_conveyor(length=60.0, start="running", formulation="rigid_body")
    din = beltrs.scenes.guo_wang_statics(length=60.0)
    # DIN at the probes: 10 m before the head on the carry (loop distance 60 - 0.8 - 10),
    # 10 m after it on the return; running, plus the belt's m'_G·v² = 98 N (gravity takeup)
    d = np.array([din.along(60.0 - 0.8 - 10.0), din.along(60.0 - 0.8 + 10.0)]) + 24.5 * 2.0**2
    sim = beltrs.Simulation(scene)
    data = beltrs.analysis.probe_run(sim, [(50.0, 0.4), (50.0, -0.4)], 2.0, 0.005)
    t, r = data["time"], data["tension"]
    windows = [r[(t >= a) & (t < a + 0.25)].mean(axis=0) / d - 1 for a in np.arange(0.0, 2.0, 0.25)]
    second = r[t >= 1.0].mean(axis=0) / d - 1
    print(f"rigid case G running: t = 0 {(r[0] / d - 1).round(5)}, second second {second.round(5)},"
          f" windows at most {np.abs(windows).max():.4%}, 5 ms ripple rms {(r[t >= 1.0] / d - 1).std(axis=0).round(4)}")
    np.testing.assert_allclose(r[0], d, rtol=1e-3)
    np.testing.assert_allclose(r[t >= 1.0].mean(axis=0), d, rtol=0.03)
    for a in np.arange(0.0, 2.0, 0.25):
        window = (t >= a) & (t < a + 0.25)
        np.testing.assert_allclose(r[window].mean(axis=0), d, rtol=0.01, err_msg=f"window from {a} s")


def test_rigid_body_running_design_start_of_case_g_stays_within_3_percent():
    """``start="running"`` counterpart of the rest start above: case G at 60 m running at
    2 m/s from DIN 22101's running tensions, probes 10 m either side of the head drum every
    0.1 s over 2 s, instantaneous readings against their readings at t = 0 (51 212 / 49 811
    N, DIN + the running belt's m'_G·v² = 98 N, session 14; both belts). The node belt
    holds 0.42 % (last second's mean +0.17 / -0.21 %); the rigid belt 2.63 % (session 14,
    with m'_G·v² placed; 2.51 % in session 13, placed at DIN: a phase's figure, below).
    Before session 14 (placed at DIN): 51 112 / 49 713 N, node belt 0.75 %.

    Measured (session 13) at the builders' 0.1185 m bodies (at most 0.3 x the drum radius,
    docs/kubas.md "The bodies' length on the drums") with the wrap joints' C² fades of 1 %:
    2.51 % (lead, merge), so it passes at the default, and the strict xfail is lifted. It is
    a phase's figure, not the length's, and stays open: on main acacffb (session 14) the
    lengths around it, 0.1148 / 0.1244 / 0.1297 / 0.14 / 0.1477 m, read 1.57 / 2.89 / 2.70 /
    4.62 / 3.10 % (session 13: 1.52 / 5.66 / 2.72 / 4.57 / 3.07 %; with the 4 % C¹ fades
    0.1185 m 2.03 %, 0.1243 m 4.03 %, 0.095 m 1.30 %). The 5 ms record's ripple over the
    second second is 0.4-1.8 % rms at those lengths (0.86 / 1.47 % carry / return at
    0.1185 m), 2.7-5.2 % at worst (the larger probe), with the means of every 0.25 s
    window within 0.46-0.65 % of DIN (the test above).

    The ripple's mechanism (session 14, docs/kubas.md "The running ripple's mechanism";
    not the chord's a², not the drive, the drums' friction or the belt's damping): (1) on
    the drums, the strand's end rides the corner of the bodies' polygon, up and down by
    R_e - rho = l²/(8R) (4.3 mm measured at 0.1185 m, 6.5 mm at 0.1477 m) at every body
    passing, which the wrap joint (it corrects the draw, not the height) leaves: two
    straight strands between the drums with no rolls, gravity or load keep 0.42-0.57 % rms
    at five of the six lengths, the same at half the speed (geometric, not inertial); (2)
    the rolls' segment contact on the polygon of the mass centres adds lines at v/l, 3 and
    5 v/l (up to 1 kN; the node belt given the same segment contact instead of its roll
    wrap reads up to 3.95 % rms, at 0.1244 m, where roll wrap gives it 0.28 %). The loop's
    longitudinal modes answer whichever harmonic of v/l falls near them (about 34 Hz on the
    bare loop at 2 m/s and 1 m/s; ten times the belt's damping leaves that line), hence the
    scatter with the length, and the 0.1 s samples read the lines crest or trough by the
    phase.

    Measured at 0.196 m bodies on main a7cf348 (session 12, after the drums took back the
    rigid contact's moment, docs/kubas.md): wrap joints 3.70 % at most (+3.70 % carry at
    1.5 s, +3.26 % return at 1.3 s), last second's mean +1.82 / +1.00 %. Earlier in session
    12, before the moment was returned: 10.6 %, mean -8.2 / -5.9 % (plain joints 15.3 %),
    which looked like a drift. It is none: sampled every 5 ms the same probes' means hold
    DIN to 0.73 % in every 0.25 s window (test above); the 0.1 s samples read the rigid
    chain's running ripple (1.5 % rms, 6.4 % at worst, lines at 2, 3, 4 and 6 v/l; v/l =
    10.2 Hz aliases to 0.2 Hz at this sampling, a slow wander on a 2 s record). Asserted:
    the issue's 3 % on the instantaneous readings, which needs that ripple below it.

    Session 13 (the wrap joints' fades 1 % with a C² step, the landing kept out of them):
    5.97 % at 1.1 s. The ripple itself fell (every 5 ms over the second second: 1.32 / 1.45
    % rms, 5.50 % at worst, windows' means within 0.63 %); the 0.1 s samples hit other
    crests of it. With stick-force friction's arms (session 13): 6.01 % (main edfc824
    5.97 %)."""
    scene = beltrs.scenes.guo_wang_conveyor(length=60.0, start="running", formulation="rigid_body")
    sim = beltrs.Simulation(scene)
    r = beltrs.analysis.probe_run(sim, [(50.0, 0.4), (50.0, -0.4)], 2.0, 0.1)["tension"]
    off = np.abs(r / r[0] - 1).max()
    assert off < 0.03, off


@functools.lru_cache(maxsize=1)
def rigid_and_node_rest_runs() -> dict:
    """Probe tensions over the first second of the 60 m case G at rest, both belts."""
    probes = [(50.0, 0.4), (50.0, -0.4)]
    curve = beltrs.StartCurve("harrison", speed=2.0, ramp=10.0, start=5.0)
    runs = {}
    for f in ("rigid_body", "node_kelvin_voigt"):
        scene = beltrs.scenes.guo_wang_conveyor(curve, length=60.0, start="rest", formulation=f)
        assert scene.initial.sag
        sim = beltrs.Simulation(scene)
        if f == "rigid_body":
            # Every joint at t = 0 against the standstill's 50 kN. On the strands the walk's
            # chords on the sagged curve are exact to the closure and the turns' factor of
            # the last pass: 1e-5 (measured 0.12 N, 2.4e-6). The joints next to the drums'
            # tangent points carry design_rigid's transition error, which grows with the
            # bodies' angle (0.085 % with 10.6° bodies in the Rust kernel test; here the
            # builder's 17° bodies (0.1185 m) on the 0.4 m drums, measured 183 N, 0.37 %;
            # 350 N, 0.7 % with the 30° bodies of 0.196 m before session 13): 1 %.
            joints = sim.tensions()
            x = sim.state()["node_position"]
            middle = 0.5 * (x[:, 0] + np.roll(x[:, 0], -1))  # joint e joins bodies e, e + 1
            strand = (middle > 1.0) & (middle < 59.0)
            assert strand.sum() > 500
            np.testing.assert_allclose(joints[strand], 50e3, rtol=1e-5)
            np.testing.assert_allclose(joints, 50e3, rtol=0.01)
        runs[f] = beltrs.analysis.probe_run(sim, probes, 1.0, 0.1)["tension"]
    return runs


def test_rigid_body_design_start_takes_sag_and_names_bad_input():
    """``initial.sag`` with rigid bodies: accepted (no longer refused); a value that is no
    boolean named, from a dataclass and from a file."""
    s = beltrs.scenes.guo_wang_conveyor(length=60.0, start="rest", formulation="rigid_body")
    assert s.initial.sag is True
    beltrs.Simulation(s)
    for bad in ("yes", 1.5, None):
        with pytest.raises(beltrs.SceneError, match=r"initial\.sag"):
            beltrs.Simulation(replace(s, initial=replace(s.initial, sag=bad)))
    with pytest.raises(beltrs.SceneError, match=r"initial\.sag = 'yes'"):
        loads_scene(dumps_scene(s).replace("sag = true", 'sag = "yes"'))

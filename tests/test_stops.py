"""Stops and takeups (docs/stops-takeups.md): power failure and coasting, brakes with a
torque or a deceleration target, holdbacks, winch / screw / locking takeups, from Python,
from scene files and from the conveyor builder; and every bad input on every path.

The exact kernels and the small-loop answers (brake stopping time, deceleration rate,
holdback torque, winch force and speed limit, travel stops, locks) are in
rust/tests/stops.rs; here the same features are driven from Python on conveyors."""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import replace

import numpy as np
import pytest

import beltrs
from beltrs import Belt, Brake, Drive, Friction, Holdback, Idler, Pulley, Scene, SceneError, StartCurve
from beltrs.conveyor import Conveyor, DriveSpec, StopSpec, TakeupSpec

G = 9.81


# --- coasting: run-down time against the rigid belt -----------------------------------------
def coasting_conveyor(f: float = 0.05, rotating_mass: float = 30.0) -> Scene:
    """A level 20 m loop (0.5 m drums, 10 kg/m, EA = 5 MN, 0.3 % short: ~15 kN pretension)
    on frictionless idler rolls every metre under both strands, each with DIN running
    resistance f and a rotating mass; a speed-controlled head drive starts it to 2 m/s."""
    r, span = 0.5, 20.0
    path = 2 * span + 2 * math.pi * r
    lag = Friction(static=0.5, kinetic=0.5)
    drive = Drive(start_curve=StartCurve(speed=-2.0, ramp=1.0, start=0.2))
    xs = np.arange(1.0, span, 1.0)
    rolls = [Idler(center=(x, r - 0.0635), resistance=f, rotating_mass=rotating_mass) for x in xs]
    rolls += [Idler(center=(x, -r - 0.0635), resistance=f, rotating_mass=rotating_mass) for x in xs]
    return Scene(
        belt=Belt(axial_stiffness=5e6, mass_per_length=10.0, length=path * 0.997, elements=200, damping_ratio=0.1),
        pulleys=[
            Pulley(name="tail", center=(0.0, 0.0), radius=r, mass=100.0, inertia=10.0, friction=lag,
                   contact_stiffness=1e8),
            Pulley(name="head", center=(span, 0.0), radius=r, mass=100.0, inertia=10.0, friction=lag,
                   contact_stiffness=1e8, drive=drive),
        ],
        idlers=rolls,
    )


# The drive trips at 18 s: its force in steady running is averaged over 2-18 s, two periods of
# the takeup's slow swing on this short conveyor. Over 4 s windows the mean drive force swings
# by +-70 N (measured, roll wrap: 1599.6, 1735.7, 1671.3, 1696.6 N over 2-6, 6-10, 10-14, 14-18
# s; segment rolls 1641.2, 1750.2, 1661.0, 1720.9): the 2-6 s window this test used read
# -7.1 % (roll wrap) and -4.6 % (segment) of DIN from where the swing stood at 6 s.
TRIP = 18.0


@pytest.fixture(scope="module")
def coasting_run():
    """A level 40 m builder conveyor (EP630/4, 200 t/h at 1.5 m/s, DIN f = 0.05) whose drive
    trips at TRIP = 18 s."""
    c = Conveyor(profile=[(0.0, 0.0), (40.0, 0.0)], belt="EP630/4", capacity=200.0, speed=1.5, f=0.05,
                 drives=[DriveSpec("head", start_curve=StartCurve("harrison", speed=1.5, ramp=1.0, start=0.5))],
                 stop=StopSpec(time=TRIP))
    scene = c.scene()
    sim = beltrs.Simulation(scene)
    sim.stabilise(tolerance=1e-5, max_steps=400_000)
    # 8 s after the trip: the run-down (5.1 s with the motor's rotor, session 10) and 1 s at rest.
    res = sim.run(TRIP + 8.0, record_interval=0.01, tension=False, node_position=False, node_velocity=False)
    return c, scene, sim, res


def test_coasting_conveyor_runs_at_din_22101s_resistance(coasting_run):
    """F, what the drive supplies in steady running, against DIN 22101's F_U (which the
    builder's idlers are meant to reproduce), within 6 %. Measured (roll wrap, the default
    since session 9) 1675.8 against 1721.9 N (-2.7 %; segment rolls 1693.3, -1.7 %); in
    session 12 1686.4 N (-2.1 %), the same with session 10's and session 12's motor law."""
    c, scene, sim, res = coasting_run
    head = scene.pulley_index("head")
    t = res.time
    steady = (t > 2.0) & (t < TRIP)  # 16 s: the takeup's slow swing averages out (TRIP)
    force = -res.drive_torque[steady, head].mean() / c.radius
    print(f"coasting conveyor: drive force {force:.1f} N, DIN 22101 F_U {c.statics().effective:.1f} N")
    assert force == pytest.approx(c.statics().effective, rel=0.06)


def test_coasting_run_down_time(coasting_run):
    """Power fails at 1.5 m/s: the conveyor runs down under its running resistance F in
    t = M_eq·v/F (rigid belt; M_eq = Conveyor.moving_mass(): belt, material, turning rolls,
    drums, and since session 10 the motor's rotor, the catalogue law's 0.131 kg*m^2 geared to
    the drum, which turns with it: 1434 of M_eq's 5638 kg; session 10's law 0.129, 1415 of
    5619). F is what the drive supplied in
    steady running (its agreement with DIN 22101's F_U is the test above); the speed falls
    linearly at F/M_eq."""
    c, scene, sim, res = coasting_run
    head = scene.pulley_index("head")
    t, v = res.time, -res.pulley_speed[:, head] * c.radius
    steady = (t > 2.0) & (t < TRIP)  # 16 s: the takeup's slow swing averages out (TRIP)
    force = -res.drive_torque[steady, head].mean() / c.radius
    m_eq = c.moving_mass()
    # The belt rings on its rolls (±0.1 m/s): fit the run-down line where it is clear of
    # both ends.
    coast = (t > TRIP + 0.3) & (v > 0.3)
    slope, intercept = np.polyfit(t[coast], v[coast], 1)
    predicted = m_eq * 1.5 / force
    stopped = t[(t > TRIP) & (v < 0.01)][0] - TRIP
    print(f"deceleration {-slope:.4f} m/s², F/M_eq {force / m_eq:.4f} m/s²; run-down {stopped:.3f} s, "
          f"rigid belt {predicted:.3f} s")
    # Measured (roll wrap, the default since session 9, F averaged over 2-18 s): the belt
    # decelerates 2.0 % slower than F/M_eq (0.3907 against 0.3986 m/s²) and is at rest 1.1 %
    # later (3.805 against 3.763 s); with the builder's VFD and the motor's rotor (session 10)
    # 2.9 % slower (0.2913 against 0.3000 m/s²) and 1.9 % later (5.093 against 5.000 s);
    # session 12's motor law (the rotor 1.4 % heavier): 2.9 % slower (0.2904 against 0.2991)
    # and 2.0 % later (5.113 against 5.015 s).
    # With F over 2-6 s the session-9 run read 1.1 % faster and 5.4 % sooner: that F stood on
    # the takeup's slow swing (TRIP). Allowed: 5 % and 10 %.
    assert -slope == pytest.approx(force / m_eq, rel=0.05)
    assert stopped == pytest.approx(predicted, rel=0.10)
    # At rest afterwards (the running resistance is stick-capable) and the drive has no
    # torque from the trip on.
    after = t > TRIP + predicted + 1.0
    assert after.sum() > 50
    # The belt rings elastically on its rolls at rest (±0.03 m/s at the drum), about zero.
    assert abs(v[after].mean()) < 0.005
    assert np.all(np.abs(v[after]) < 0.05)
    assert np.all(res.drive_torque[t > TRIP + 1e-9, head] == 0.0)


def test_coasting_without_power_off_keeps_running():
    # The contrast: the same run without a power failure is held at 2 m/s by its drive.
    sim = beltrs.Simulation(coasting_conveyor())
    sim.stabilise(tolerance=1e-6)
    res = sim.run(3.0, record_interval=0.01, tension=False, node_position=False, node_velocity=False)
    assert -res.pulley_speed[-1, 1] * 0.5 == pytest.approx(2.0, rel=1e-6)


# --- a loaded incline: stop, brake, holdback, lock --------------------------------------------
RISE = 6.0
SPAN = 40.0


def incline(**kw) -> Conveyor:
    """A 40 m EP630/4 conveyor rising 6 m, 400 t/h at 1.5 m/s, no running resistance
    (f = 0: so the state at rest is statically determinate), started over 1 s from 1 s."""
    curve = StartCurve("harrison", speed=1.5, ramp=1.0, start=1.0)
    base = dict(profile=[(0.0, 0.0), (SPAN, RISE)], belt="EP630/4", capacity=400.0, speed=1.5, f=0.0,
                drives=[DriveSpec("head", start_curve=curve)])
    base.update(kw)
    return Conveyor(**base)


def incline_run(c: Conveyor, duration: float, elements: int | None = None):
    """Run from the placed belt: the drive holds its drum at rest until its curve begins
    (1 s), while the belt settles on its rolls under gravity (a loaded incline has no
    frictionless static state to relax to, and the relaxation with friction does not reach
    the tolerance here). `elements`: the belt's element count (default: the builder's)."""
    scene = c.scene(elements=elements)
    sim = beltrs.Simulation(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", beltrs.NotRelaxedWarning)  # the settling is the first second
        res = sim.run(duration, record_interval=0.005, node_velocity=False)
    return scene, sim, res


@pytest.fixture(scope="module")
def held_incline():
    """Twice the builder's element count: 0.082 m elements, 15° of wrap each on the 0.315 m
    drums. At the builder's 0.164 m (30° of wrap per element) the node polygon on each wrap
    holds a tension step at rest that depends on where the nodes sit on the drum (radial
    contact forces at nodes that do not bisect the chords' kink; and the bending stiffness's
    cogging), which the holdback carries: measured (14 s run, mean from 6 s) −1293.7 N·m at
    503 elements (−1262.2 with no bending stiffness) against −1207.3 at 1006 and the exact
    −1203.6. The tail drum's mean torque is zero (−2.5 N·m) while the mean tension across
    its wrap steps by 343 N (belt weight over the wrap: 91 N). Which node phase the belt
    stops in is set by the start state, so this was 0.3 % from the old relaxed start and
    7.5 % from the design start (docs/stops-takeups.md). That was nodal contact: with wrap
    contact (the builder's default) the wrap holds no such step (the drums' contact pushes
    along the belt by under 2 N at rest) and the holdback reads −1208.3 N·m at 503 elements,
    −1215.0 at 1006; what is left is the carry rolls' push along the belt (docs/stops-takeups.md)."""
    c = incline(stop=StopSpec(time=2.5), holdback="head", takeup=TakeupSpec(lock_on_stop=True))
    scene = c.scene()
    return (c, *incline_run(c, 14.0, elements=2 * scene.belt.elements))


def test_holdback_holds_a_loaded_incline(held_incline):
    """The drive trips at 2.5 s; the belt coasts up the incline to rest and would run
    back; the holdback catches it. Its head drum never turns backwards, and at rest the
    holdback takes the material's downhill pull: r·q·g·H, H the rise of the loaded zone
    (the belt's own weight cancels round the loop, and with f = 0 nothing else holds)."""
    c, scene, sim, res = held_incline
    head = scene.pulley_index("head")
    omega = res.pulley_speed[:, head]
    t = res.time
    assert omega.min() < -2.9  # it ran (1.5 m/s on a 0.5 m drum, clockwise)
    # Never backwards. (Recorded speeds are centred on the sample time with the step's net
    # torque, whose balance at a hold is exact up to rounding: 1e-9 rad/s.)
    assert omega.max() <= 1e-9, omega.max()
    # At rest it is held exactly, but for a little forward creep when the belt ringing on its
    # rolls pulls the drum forwards (the holdback allows that): most samples exactly 0.
    rest = t > 6.0
    creep = -np.sum(omega[rest]) * 0.005 * c.radius  # m of belt over the drum, forwards
    exact = np.mean(np.abs(omega[rest]) < 1e-9)
    print(f"held exactly at {exact:.0%} of the samples; forward creep {creep * 1e3:.2f} mm")
    assert np.mean(np.abs(omega[rest]) < 1e-9) > 0.9
    assert 0.0 <= creep < 0.01
    q = c.material_mass
    slope = RISE / math.hypot(SPAN, RISE)
    loaded = SPAN * math.hypot(1, RISE / SPAN) - c.loading  # loading point to the head
    expected = -c.radius * q * G * loaded * slope
    # The loaded belt rings on its rolls against the held drum (±1 kN·m, periods of 1-2 s,
    # lightly damped): average the holding torque over 8 s (from 6 s, the belt at rest).
    held = res.brake_torque[t > 6.0, head].mean()
    print(f"holdback torque {held:.1f} N·m, expected {expected:.1f} N·m")
    assert expected == pytest.approx(-c.radius * c.material_lift())
    # The zone's ends sit on nodes: one element of material rise either way; and 1 % for
    # what is left of the ringing in the mean (measured: +0.9 %; the rolls' push along the
    # belt, 21 N in a run before the sag placement's drum ends were mended, is 0.55 % of it:
    # test_brake_holds_the_materials_pull_on_a_decline).
    le = sim.path_length / sim.nodes
    tol = c.radius * q * G * le * slope + 0.01 * abs(expected)
    assert held == pytest.approx(expected, abs=tol)
    assert np.all(res.brake_torque[:, head] <= 0.0)  # it only ever pushes forwards (cw)


def test_holdback_bounds_reverse_travel(held_incline):
    """After the stop the belt at the tail turns back only by the elastic settling: the
    carry strand takes the material's pull, ΔT ≈ q·g·H, stretching by ΔT·L/EA."""
    c, scene, sim, res = held_incline
    tail = scene.pulley_index("tail")
    angle = np.cumsum(res.pulley_speed[:, tail] * np.diff(res.time, prepend=res.time[0]))
    # The tail drum turns clockwise (negative) forwards; reverse is a rise of the angle
    # after its lowest point.
    low = np.argmin(angle)
    back = (angle[low:].max() - angle[low]) * c.radius
    q = c.material_mass
    stretch = q * G * RISE * SPAN / c.belt_class.axial_stiffness(c.width)
    print(f"belt ran back {back * 1e3:.2f} mm at the tail; elastic stretch {stretch * 1e3:.2f} mm")
    assert back < 2.0 * stretch + 1e-3


def test_takeup_locks_when_the_stop_begins(held_incline):
    c, scene, sim, res = held_incline
    tail = scene.pulley_index("tail")
    travel = res.takeup_travel[:, tail]
    after = res.time >= 2.5 + 0.005
    assert np.ptp(travel[after]) == 0.0
    assert np.ptp(travel[res.time < 2.5]) > 1e-4  # it moved during the start


def test_without_a_holdback_the_incline_runs_back():
    c = incline(stop=StopSpec(time=2.5))
    scene, sim, res = incline_run(c, 7.0)
    omega = res.pulley_speed[:, scene.pulley_index("head")]
    assert omega.max() > 0.1  # backwards


@pytest.fixture(scope="module")
def braked_decline():
    """A loaded decline (the material drives the belt: a regenerative conveyor) whose drive
    trips at 3 s, with a controlled brake on the head drum (0.3 m/s², the builder's capacity
    for it); 16 s at twice the builder's elements, as for the held incline: at 30° of wrap
    per element the node polygon passing over the drums (nodal contact) drove the belt's
    ringing, and the brake sat at its capacity a quarter of the time (measured at 503
    elements: on the ramp 66 %).

    The drive is the builder's before session 10, the ideal speed follower without motor
    inertia (``control="ideal", inertia=0``): these tests check the brake's ramp from exactly
    1.5 m/s at the trip and its held torque at rest. With the default VFD (session 10) the
    drum was 0.28 % fast at the trip (the PI still settling 2 s after its 1 s ramp: the brake's
    ramp measured 0.0042 m/s above the test's), and the held torque read 1182.9 and 1185.1
    against 1203.6 N·m (-1.7 %, -1.5 %) in the tests' windows, the rotor (10x the drum's
    inertia at the drum) ringing down more slowly; not re-designed for the VFD in session 10."""
    c = Conveyor(profile=[(0.0, RISE), (SPAN, 0.0)], belt="EP630/4", capacity=400.0, speed=1.5, f=0.0,
                 drives=[DriveSpec("head", start_curve=StartCurve("harrison", speed=1.5, ramp=1.0, start=1.0),
                                   control="ideal", inertia=0.0)],  # see braked_decline
                 stop=StopSpec(time=3.0, brake="head", deceleration=0.3))
    return (c, *incline_run(c, 16.0, elements=2 * c.scene().belt.elements))


def test_deceleration_brake_on_a_decline(braked_decline):
    """The brake stops the belt along its ramp and holds it at rest."""
    c, scene, sim, res = braked_decline
    head = scene.pulley_index("head")
    brake = scene.pulleys[head].brake
    assert brake.applied == 3.0 and brake.deceleration == 0.3
    assert brake.torque == pytest.approx(c.brake_torque_for(0.3))
    assert c.material_lift() < 0  # downhill
    v = -res.pulley_speed[:, head] * c.radius
    t = res.time
    # The ramp 1.5 − 0.3·(t − 3): with the brake torque inside its range the drum is on it
    # (the recorded speed is centred on the sample: half a step of ramp, a·Δt/2); at the
    # capacity (the belt ringing on its rolls asks for more) above it, with none below it.
    # Most of the time on it.
    cap = brake.torque
    running = (t > 3.05) & (t < 3.0 + 1.5 / 0.3 - 0.05)
    ramp = 1.5 - 0.3 * (t - 3.0)
    torque = res.brake_torque[:, head]
    assert np.all(torque[running] >= 0.0)  # it only opposes the clockwise motion
    # A sample next to one at the capacity is not on the ramp either: its speed is centred on
    # it, half from the step that saturated (measured: 5.2e-5 m/s off at 5.898 s, next to
    # the capacity sample at 5.903 s, against 1.4e-5 for the ramp's own half step).
    sat = torque == cap
    beside = np.roll(sat, 1) | np.roll(sat, -1)
    inside = running & (torque > 0.0) & (torque < cap) & ~beside
    tol = 0.3 * sim.dt + 1e-9
    np.testing.assert_allclose(v[inside], ramp[inside], atol=tol)
    assert np.all(v[running & (torque == cap)] >= ramp[running & (torque == cap)] - tol)
    assert np.all(v[running & (torque == 0.0)] <= ramp[running & (torque == 0.0)] + tol)
    print(f"decline: on the ramp {inside.sum() / running.sum():.0%} of the time")
    assert inside.sum() > 0.7 * running.sum()
    # At rest it holds, exactly at most samples; the ringing belt pulls it past its capacity
    # now and then (stick-slip, millimetres).
    rest = t > 3.0 + 1.5 / 0.3 + 0.2
    assert np.mean(np.abs(v[rest]) < 1e-9) > 0.9
    assert np.all(np.abs(v[rest]) < 0.01)
    assert np.all(res.brake_torque[rest, head] <= cap)


def held_torque(res, head: int) -> float:
    """The brake's held torque at rest, N·m: the mean from 9 s to the end (7 s), Hann-weighted.

    The belt at rest rings (brake torque ±300 N·m rms at 9–16 s, lines at 1.0–2.0 Hz, decaying
    over tens of seconds), and a plain mean over a window that holds no whole number of its
    periods keeps up to A/(π·f·T) of each line. Measured (session 11, the decline below at the
    builder's elements run on to 48 s): the plain mean over 9–16 s 1185.5 N·m, over 4 s
    blocks from 8 to 48 s 1168–1210 N·m, Hann-weighted over 16–48 s 1196.9; Hann-weighted
    over 9–16 s 1197.4. The Hann weight's leakage falls as (f·T)⁻³: a few N·m here."""
    t = res.time
    window = t > 9.0
    weight = np.hanning(window.sum())
    return float(weight @ res.brake_torque[window, head] / weight.sum())


def test_brake_holds_the_materials_pull_on_a_decline(braked_decline):
    """Holding: the material's pull on the drum, r·|m'_L·g·ΔH|, averaged over the belt's
    ringing (7 s from 9 s, Hann-weighted: :func:`held_torque`); within one element of material
    rise and 1 %. Measured (session 11, main 5179f03 and the drums' stick-slip law):
    1202.3 N·m against 1203.6 (−0.1 %). The plain mean over the same 7 s, which this test
    took until session 11, read 1188.7 (old friction law; a strict xfail, 0.013 N·m outside
    the tolerance) and 1188.8 (the stick-slip law): its 14 N·m were the ringing's remainder,
    not the rolls' push this docstring blamed (docs/stops-takeups.md, "The held torque's
    window"). Measured at the builders' default roll wrap contact (session 9), plain mean:
    1188.9 against 1203.6 N·m (−1.2 %).
    Before, with the segment contact on the rolls, 1185.5 (−1.5 %, a strict xfail; with nodal
    contact and the straight placement 1208.5, +0.4 %, from two errors that cancelled). The
    budget of that segment-contact rest state (tensions and node positions averaged over the
    same 7 s; docs/stops-takeups.md): the brake carries the weight along the loop, 3800 N
    (the zone's ends on nodes: −21 N against the 3821 N pull), less a push of the carry rolls
    along the belt against the travel, 45 N, each roll's share following the phase of its
    element, ∝ (1 − 2γ) (the rolls' chordal action, which roll wrap removes); the tail
    drum's wrap pushes along the belt by 0.4 N (nodal contact: 57 N, its polygon step)."""
    c, scene, sim, res = braked_decline
    head = scene.pulley_index("head")
    held = held_torque(res, head)
    want = c.radius * abs(c.material_lift())
    le = sim.path_length / sim.nodes
    tol = c.radius * c.material_mass * G * le * RISE / SPAN + 0.01 * want
    print(f"decline: holding {held:.1f} N·m, material's pull {want:.1f} N·m")
    assert held == pytest.approx(want, abs=tol)


def test_rolls_measured_along_the_belt_remove_the_decline_push():
    """The segment contact's miss above (a strict xfail until roll wrap became the builders'
    default) is the idler rolls' chordal action: a straight element over a roll
    (``idler_contact = "segment"``) pushes the belt along itself by R(R − w)(1 − 2γ)/(2T)
    (docs/stops-takeups.md). Measuring the elements over a roll along the belt's path over it
    (``idler_contact = "wrap"``, rust/src/contact/roll_wrap.rs, set here by hand as the
    default is) puts the roll's load through its centre at every node phase, and the same
    conveyor at the builder's own element count holds the material's pull within the same
    tolerance as above: measured (session 11, :func:`held_torque`) 1197.4 against
    1203.6 N·m (−0.5 %). Plain means over 9–16 s, as this test read until session 11:
    1186.1 (−1.5 %, old friction law, 0.14 N·m inside the tolerance), 1185.5 (the drums'
    stick-slip law, 0.4 N·m outside; Hann-weighted 1197.7 and 1197.4); 1191.7 in session 8;
    with segment contact −1.5 % at twice the elements. The residual is under the tolerance's
    one element of material rise (17.7 N·m here) plus 1 %."""
    c = Conveyor(profile=[(0.0, RISE), (SPAN, 0.0)], belt="EP630/4", capacity=400.0, speed=1.5, f=0.0,
                 drives=[DriveSpec("head", start_curve=StartCurve("harrison", speed=1.5, ramp=1.0, start=1.0),
                                   control="ideal", inertia=0.0)],  # see braked_decline
                 stop=StopSpec(time=3.0, brake="head", deceleration=0.3))
    scene = c.scene()
    scene = replace(scene, belt=replace(scene.belt, idler_contact="wrap"))
    sim = beltrs.Simulation(scene)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", beltrs.NotRelaxedWarning)
        res = sim.run(16.0, record_interval=0.005, node_velocity=False)
    head = scene.pulley_index("head")
    held = held_torque(res, head)
    want = c.radius * abs(c.material_lift())
    le = sim.path_length / sim.nodes
    tol = c.radius * c.material_mass * G * le * RISE / SPAN + 0.01 * want
    print(f"decline, builder's elements: holding {held:.1f} N·m, material's pull {want:.1f} N·m")
    assert held == pytest.approx(want, abs=tol)


# --- takeups from the builder -------------------------------------------------------------
def test_builder_takeup_kinds():
    # Each kind pulls with its own conveyor's chosen tension: since session 13 the choice
    # counts the start's dynamics, which differ by kind (a fixed takeup does not swing, a
    # winch's carriage has no counterweight's mass): 14, 15 and 14 kN here (DIN's rules alone
    # 14 kN for all three).
    c = incline(takeup=TakeupSpec(kind="winch", max_speed=0.1))
    t = c.scene().pulleys[0].takeup
    assert (t.kind, t.force, t.max_speed, t.counterweight) == ("winch", 2 * c.takeup_tension(), 0.1, 0.0)
    c = incline(takeup=TakeupSpec(kind="fixed"))
    t = c.scene().pulleys[0].takeup
    assert (t.kind, t.force) == ("fixed", 2 * c.takeup_tension())
    c = incline()
    t = c.scene().pulleys[0].takeup
    assert t.kind == "gravity" and t.counterweight == pytest.approx(2 * c.takeup_tension() / G)


def test_winch_takeup_respects_its_speed_limit_in_a_start():
    """A winch limited to 2 cm/s on the tail of a hard start: the carriage never moves
    faster, and once it catches up the pull is back at the set force."""
    c = incline(takeup=TakeupSpec(kind="winch", max_speed=0.02))
    # (the start needs ~0.05 m of takeup travel at 1 s: the limit binds)
    scene, sim, res = incline_run(c, 6.0)
    tail = scene.pulley_index("tail")
    speed = np.diff(res.takeup_travel[:, tail]) / np.diff(res.time)
    assert np.all(np.abs(speed) <= 0.02 * (1 + 1e-9)), np.abs(speed).max()
    assert np.abs(speed).max() > 0.019  # the limit bound during the start
    tu = sim.scene.pulleys[tail].takeup
    assert tu.force == pytest.approx(2 * c.takeup_tension())
    # The belt's pull on the carriage along its line balances the winch's force (and the
    # drum's weight component) once the carriage has caught up.
    d = np.array(tu.direction)
    belt = -(res.pulley_force[:, tail] @ d)
    want = tu.force - sim.scene.pulleys[tail].mass * G * d[1]
    last = res.time > res.time[-1] - 0.5
    print(f"winch: belt pull {belt[last].mean():.0f} N, set {want:.0f} N")
    assert belt[last].mean() == pytest.approx(want, rel=0.01)


def test_conveyor_toml_with_stop_and_takeup(tmp_path):
    text = """
[conveyor]
profile = [[0.0, 0.0], [40.0, 4.0]]
belt = "EP630/4"
capacity = 200.0
speed = 1.5
holdback = "head"

[conveyor.takeup]
kind = "winch"
max_speed = 0.1
lock_on_stop = true

[conveyor.stop]
time = 12.0
brake = "head"
brake_torque = 3000.0
brake_delay = 0.5
brake_rise = 0.2
"""
    c = beltrs.conveyor.loads(text)
    scene = c.scene()
    head = scene.pulleys[scene.pulley_index("head")]
    assert head.drive.power_off == 12.0
    assert (head.brake.torque, head.brake.applied, head.brake.rise) == (3000.0, 12.5, 0.2)
    assert head.holdback == Holdback(forward="cw")
    assert scene.pulleys[0].takeup.lock_on_stop
    beltrs.Simulation(scene)  # compiles
    # The recording runs past the stop.
    assert scene.recording.duration > 12.0
    path = tmp_path / "s.toml"
    scene.save(path)
    assert beltrs.load_scene(path) == scene


# --- bad input on every path ----------------------------------------------------------------
def small() -> Scene:
    scene = coasting_conveyor()
    scene.idlers = scene.idlers[:4]
    return scene


def every_form(d: dict) -> list[str]:
    """The messages for the scene dict ``d`` from the engine's dict reader, the
    dataclasses and a TOML file."""
    out = []
    for make in (
        lambda: beltrs._beltrs.Simulation(d),
        lambda: beltrs.Simulation(Scene.from_dict(d)),
        lambda: beltrs.Simulation(Scene.from_toml(Scene.from_dict(d).to_toml())),
    ):
        try:
            make()
        except SceneError as err:
            out.append(str(err))
    return out


@pytest.mark.parametrize(
    ("pulley", "key", "table", "message"),
    [
        (0, "brake", {"deceleration": 0.5},
         r"pulleys\[0\]\.brake\.deceleration = 0\.5: needs pulleys\[0\]\.brake\.torque"),
        (0, "brake", {"applied": 3.0}, r"pulleys\[0\]\.brake\.applied = 3: needs pulleys\[0\]\.brake\.torque"),
        (0, "brake", {"torque": -5.0}, r"pulleys\[0\]\.brake\.torque = -5: must be > 0"),
        (0, "brake", {"torque": 5.0, "rise": -1.0}, r"pulleys\[0\]\.brake\.rise = -1: must be ≥ 0"),
        (0, "brake", {"torque": 5.0, "deceleration": 0.0}, r"pulleys\[0\]\.brake\.deceleration = 0: must be > 0"),
        (0, "brake", {"torque": 5.0, "time": [0.0, 1.0], "capacity": [0.0, 9.0]},
         r"pulleys\[0\]\.brake\.capacity = \[0\.0, 9\.0\]: give pulleys\[0\]\.brake\.torque or the time/capacity"),
        (1, "brake", {"torque": 5.0, "applied": 1.0},
         r"pulleys\[1\]\.brake = a brake: .*give the drive a power_off and the brake a torque applied no earlier"),
        (0, "holdback", {}, r"pulleys\[0\]\.holdback\.forward = missing: required"),
        (0, "holdback", {"forward": "cw", "capacity": -1.0}, r"pulleys\[0\]\.holdback\.capacity = -1: must be > 0"),
        (1, "holdback", {"forward": "ccw"},
         r"pulleys\[1\]\.holdback\.forward = \"ccw\": the drive's start_curve\.speed"),
        (0, "holdback", {"forward": "up"}, r"pulleys\[0\]\.holdback\.forward = \"up\": expected \"ccw\" or \"cw\""),
        (0, "takeup", {"kind": "wench", "force": 5.0},
         r"pulleys\[0\]\.takeup\.kind = \"wench\": unknown takeup kind, did you mean \"winch\""),
        (0, "takeup", {"kind": "winch"}, r"pulleys\[0\]\.takeup\.force = missing: required for a winch takeup"),
        (0, "takeup", {"kind": "fixed"}, r"pulleys\[0\]\.takeup\.force = missing: required for a fixed takeup"),
        (0, "takeup", {"force": 5.0},
         r"pulleys\[0\]\.takeup\.force = 5: a gravity takeup pulls with its counterweight"),
        (0, "takeup", {"kind": "winch", "force": 5.0, "counterweight": 2.0},
         r"pulleys\[0\]\.takeup\.counterweight = 2: a winch takeup has no counterweight"),
        (0, "takeup", {"max_speed": 0.5}, r"pulleys\[0\]\.takeup\.max_speed = 0\.5: limits a winch only"),
        (0, "takeup", {"kind": "winch", "force": 5.0, "max_speed": -0.5},
         r"pulleys\[0\]\.takeup\.max_speed = -0\.5: must be > 0"),
        (0, "takeup", {"lock_on_stop": True}, r"pulleys\[0\]\.takeup\.lock_on_stop = true: the scene has no stop"),
        (0, "takeup", {"kind": "fixed", "force": 5.0, "lock_on_stop": True},
         r"pulleys\[0\]\.takeup\.lock_on_stop = true: a fixed \(screw\) takeup is always locked"),
        (0, "takeup", {"lock_on_stop": "yes"}, r"pulleys\[0\]\.takeup\.lock_on_stop = 'yes': expected true or false"),
    ],
)
def test_bad_stops_and_takeups_on_every_path(pulley, key, table, message):
    d = small().to_dict()
    d["pulleys"][pulley][key] = table
    if key == "takeup":
        d["pulleys"][pulley][key] = {"direction": [-1.0, 0.0], **table}
    messages = every_form(d)
    assert len(messages) == 3, messages
    for m in messages:
        assert re.match(message, m), m


@pytest.mark.parametrize("value", [math.nan, math.inf, "soon"])
def test_bad_power_off_on_every_path(value):
    d = small().to_dict()
    d["pulleys"][1]["drive"]["power_off"] = value
    messages = every_form(d)
    assert len(messages) == 3, messages
    shown = {"soon": "'soon'"}.get(value, "NaN" if value != value else "inf")
    for m in messages:
        assert m.startswith(f"pulleys[1].drive.power_off = {shown}: "), m


def test_bad_method_arguments():
    sim = beltrs.Simulation(small())
    with pytest.raises(SceneError, match=r"brake = 5: must be a beltrs\.Brake or None"):
        sim.set_brake("head", 5)
    with pytest.raises(SceneError, match=r"holdback = 'cw': must be a beltrs\.Holdback or None"):
        sim.set_holdback(0, "cw")
    with pytest.raises(SceneError, match=r"pulley = 'middle': no pulley of that name"):
        sim.set_brake("middle", Brake(torque=5.0))
    with pytest.raises(SceneError, match=r"at = 'now': must be a number"):
        sim.power_off(at="now")
    with pytest.raises(SceneError, match=r"at = nan: must be a finite number"):
        sim.power_off("head", at=math.nan)
    with pytest.raises(SceneError, match=r"pulleys\[0\]\.drive = None: this pulley has no drive"):
        sim.power_off("tail")
    with pytest.raises(SceneError, match=r"pulleys\[0\]\.brake\.torque = -1: must be > 0"):
        sim.set_brake("tail", Brake(torque=-1.0))
    with pytest.raises(SceneError, match=r"pulleys\[0\]\.holdback\.forward = missing: required"):
        sim.set_holdback("tail", Holdback())


def test_methods_stop_a_running_conveyor():
    """power_off and set_brake during a run: the brake stops the belt and holds it."""
    sim = beltrs.Simulation(coasting_conveyor())
    sim.stabilise(tolerance=1e-6)
    sim.run(1.5, tension=False, node_position=False, node_velocity=False)
    sim.power_off()
    sim.set_brake("head", Brake(torque=300.0, applied=sim.time))
    sim.set_holdback("tail", Holdback(forward="cw"))
    assert "brakes" in sim.stages and "holdbacks" in sim.stages
    res = sim.run(2.0, tension=False, node_position=False, node_velocity=False)
    assert np.all(np.abs(res.pulley_speed[-20:, 1]) < 1e-9)
    assert sim.state()["pulley_speed"][1] == 0.0
    assert res.pulley_speed[:, 0].max() <= 1e-9


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        (dict(stop=StopSpec(time=math.nan)), r"stop\.time = nan: must be finite"),
        (dict(stop=StopSpec(time=1.0, brake="middle", brake_torque=5.0)), r"stop\.brake = 'middle': must be"),
        (dict(stop=StopSpec(time=1.0, brake="head")), r"stop\.brake_torque = None: give the brake torque"),
        (dict(stop=StopSpec(time=1.0, deceleration=0.3)), r"stop\.deceleration = 0\.3: needs stop\.brake"),
        (dict(stop=StopSpec(time=1.0, brake_delay=0.3)), r"stop\.brake_delay = 0\.3: needs stop\.brake"),
        (dict(stop=StopSpec(time=1.0, brake="head", brake_torque=-1.0)), r"stop\.brake_torque = -1\.0: must be > 0"),
        (dict(stop=StopSpec(time=1.0, brake="head", deceleration=0.0)), r"stop\.deceleration = 0\.0: must be > 0"),
        (dict(stop="soon"), r"stop = 'soon': expected a beltrs\.conveyor\.StopSpec"),
        (dict(holdback="middle"), r"holdback = 'middle': must be"),
        (dict(takeup=TakeupSpec(kind="spring")), r"takeup\.kind = 'spring': must be one of"),
        (dict(takeup=TakeupSpec(max_speed=0.1)), r"takeup\.max_speed = 0\.1: limits a winch only"),
        (dict(takeup=TakeupSpec(kind="winch", max_speed=0.0)), r"takeup\.max_speed = 0\.0: must be > 0"),
        (dict(takeup=TakeupSpec(lock_on_stop=True)), r"takeup\.lock_on_stop = True: needs a stop"),
        (dict(takeup=TakeupSpec(kind="fixed", lock_on_stop=True), stop=StopSpec(time=1.0)),
         r"takeup\.lock_on_stop = True: a fixed \(screw\) takeup is always locked"),
    ],
)
def test_bad_builder_input(kw, match):
    with pytest.raises(SceneError, match=match):
        incline(**kw).scene()


def test_bad_builder_toml():
    with pytest.raises(SceneError, match=r"conveyor\.stop\.tme = 'tme': unknown key, did you mean 'time'\?"):
        beltrs.conveyor.loads("[conveyor]\n[conveyor.stop]\ntme = 3.0\n")
    with pytest.raises(SceneError, match=r"stop\.brake_rise = -1\.0: must be >= 0"):
        beltrs.conveyor.loads("[conveyor]\n[conveyor.stop]\ntime = 3.0\nbrake = 'head'\nbrake_torque = 1.0\n"
                              "brake_rise = -1.0\n")


@pytest.mark.parametrize("kind", ["motor", "controller"])
def test_power_off_switches_off_motors_and_controllers(kind):
    """A power failure cuts every kind of drive: a DOL motor is switched off (its torque is
    0 from the trip on) and a PI speed controller gives no torque (and stops integrating)."""
    from tiny_scene import tiny_scene

    from beltrs import Motor, SpeedController

    scene = tiny_scene()
    if kind == "motor":
        drive = Drive(motor=Motor(rated_power=2e3, rated_speed=150.0, synchronous_speed=157.08, gear_ratio=20.0),
                      power_off=0.5)
    else:
        drive = Drive(start_curve=StartCurve(speed=1.0, ramp=0.2), controller=SpeedController(), power_off=0.5)
    scene.pulleys[1].drive = drive
    scene.pulleys[1].friction = Friction(static=0.5)
    sim = beltrs.Simulation(scene)
    sim.stabilise()
    res = sim.run(1.0, record_interval=0.01, tension=False, node_position=False, node_velocity=False)
    t = res.time
    assert np.abs(res.drive_torque[t < 0.5, 1]).max() > 1.0
    assert np.all(res.drive_torque[t > 0.5 + 1e-9, 1] == 0.0)

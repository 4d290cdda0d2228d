"""Stops and takeups (docs/stops-takeups.md): power failure and coasting, brakes with a
torque or a deceleration target, holdbacks, winch / screw / locking takeups, from Python,
from scene files and from the conveyor builder; and every bad input on every path.

The exact kernels and the small-loop answers (brake stopping time, deceleration rate,
holdback torque, winch force and speed limit, travel stops, locks) are in
rust/tests/stops.rs; here the same features are driven from Python on conveyors."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import beltrs
from beltrs import Belt, Brake, Drive, Friction, Holdback, Idler, Pulley, Scene, SceneError, StartCurve, Takeup
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
    rolls = [Idler(center=(x, r - 0.0635), resistance=f, rotating_mass=rotating_mass) for x in np.arange(1.0, span, 1.0)]
    rolls += [Idler(center=(x, -r - 0.0635), resistance=f, rotating_mass=rotating_mass) for x in np.arange(1.0, span, 1.0)]
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


def test_coasting_run_down_time():
    """Power fails at 2 m/s: the belt runs down under the idlers' running resistance
    F = f·Σ(N + m_R·g) in t = M_eq·v/F (M_eq: belt plus the drums' I/r²; the rolls have no
    friction, so they do not turn). The normal forces are taken from the run (their sum is
    the belt's weight on the rolls, tension-dependent at the ends of the strands)."""
    scene = coasting_conveyor()
    head = scene.pulleys[1]
    head.drive = Drive(start_curve=head.drive.start_curve, power_off=2.0)
    sim = beltrs.Simulation(scene)
    sim.stabilise(tolerance=1e-6)
    res = sim.run(5.0, record_interval=0.005, tension=False, node_position=False, node_velocity=False)
    omega = res.pulley_speed[:, 1]
    t = res.time
    before = (t > 1.5) & (t < 2.0)
    v0 = -omega[before].mean() * 0.5
    assert v0 == pytest.approx(2.0, rel=1e-3)
    coasting = (t > 2.0) & (omega < -0.02)
    normal = res.idler_force[coasting].mean(axis=0)
    f, m_r = 0.05, 30.0
    force = f * np.sum(normal + m_r * G)
    m_eq = 10.0 * scene.belt.length + 2 * 10.0 / 0.5**2
    predicted = m_eq * v0 / force
    # Stopped: the drum's speed falls below 1 % of the running speed.
    stop = t[(t > 2.0) & (-omega * 0.5 < 0.01 * v0)][0] - 2.0
    print(f"run-down {stop:.3f} s, rigid belt {predicted:.3f} s (F = {force:.0f} N, M_eq = {m_eq:.0f} kg)")
    # 1 % of v0 is 1 % of the run-down; the belt's stretch changes by ΔT·L/EA as the
    # drive's pull is released (the belt's front and back stop ~0.1 s apart): 3 %.
    assert stop == pytest.approx(0.99 * predicted, rel=0.03)
    # And it stays stopped: the running resistance is stick-capable.
    assert np.all(np.abs(omega[t > 2.0 + stop + 0.3]) < 0.01 * v0 / 0.5)
    # The drive supplies nothing after the power-off (no viscous load).
    assert np.all(res.drive_torque[t > 2.0 + 1e-9, 1] == 0.0)


def test_coasting_without_power_off_keeps_running():
    # The contrast: the same run without a power failure is held at 2 m/s by its drive.
    sim = beltrs.Simulation(coasting_conveyor())
    sim.stabilise(tolerance=1e-6)
    res = sim.run(3.0, record_interval=0.01, tension=False, node_position=False, node_velocity=False)
    assert -res.pulley_speed[-1, 1] * 0.5 == pytest.approx(2.0, rel=1e-6)


# --- a loaded incline: stop, brake, holdback, lock --------------------------------------------
RISE = 4.0
SPAN = 40.0


def incline(**kw) -> Conveyor:
    """A 40 m EP630/4 conveyor rising 4 m, 200 t/h at 1.5 m/s, no running resistance
    (f = 0: so the state at rest is statically determinate), started over 1 s from 0.5 s."""
    curve = StartCurve("harrison", speed=1.5, ramp=1.0, start=0.5)
    base = dict(profile=[(0.0, 0.0), (SPAN, RISE)], belt="EP630/4", capacity=200.0, speed=1.5, f=0.0,
                drives=[DriveSpec("head", start_curve=curve)])
    base.update(kw)
    return Conveyor(**base)


def incline_run(c: Conveyor, duration: float):
    scene = c.scene()
    sim = beltrs.Simulation(scene)
    sim.stabilise(friction=True, tolerance=1e-5, max_steps=400_000)
    res = sim.run(duration, record_interval=0.005, node_velocity=False)
    return scene, sim, res


@pytest.fixture(scope="module")
def held_incline():
    c = incline(stop=StopSpec(time=2.5), holdback="head", takeup=TakeupSpec(lock_on_stop=True))
    return (c, *incline_run(c, 7.0))


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
    rest = t > t[-1] - 1.0
    assert np.all(np.abs(omega[rest]) < 1e-9)
    assert sim.state()["pulley_speed"][head] == 0.0  # the state itself: exactly at rest
    q = c.material_mass
    slope = RISE / math.hypot(SPAN, RISE)
    loaded = SPAN * math.hypot(1, RISE / SPAN) - c.loading  # loading point to the head
    expected = -c.radius * q * G * loaded * slope
    held = res.brake_torque[rest, head]
    print(f"holdback torque {held.mean():.1f} N·m, expected {expected:.1f} N·m")
    # The zone's ends sit on nodes: one element of material rise either way.
    le = sim.path_length / sim.nodes
    tol = c.radius * q * G * le * slope
    assert held.mean() == pytest.approx(expected, abs=tol)
    assert np.ptp(held) < 0.05 * abs(expected)


def test_holdback_bounds_reverse_travel(held_incline):
    """After the stop the belt at the tail turns back only by the elastic settling: the
    carry strand takes the material's pull, ΔT ≈ q·g·H, stretching by ΔT·L/EA."""
    c, scene, sim, res = held_incline
    tail = scene.pulley_index("tail")
    angle = np.cumsum(res.pulley_speed[:, tail]) * np.diff(res.time, prepend=res.time[0])
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
    scene, sim, res = incline_run(c, 5.0)
    omega = res.pulley_speed[:, scene.pulley_index("head")]
    assert omega.max() > 0.1  # backwards


def test_deceleration_brake_on_the_incline():
    """A controlled brake (0.3 m/s²) on the head drum from the power-off: the drum slows at
    the set rate, unless the load slows it faster (uphill it does: the brake then supplies
    nothing), and holds at rest."""
    c = incline(stop=StopSpec(time=2.5, brake="head", deceleration=0.3))
    scene, sim, res = incline_run(c, 6.0)
    head = scene.pulley_index("head")
    brake = scene.pulleys[head].brake
    assert brake.applied == 2.5 and brake.deceleration == 0.3
    assert brake.torque == pytest.approx(2 * c.moving_mass() * 0.3 * c.radius)
    v = -res.pulley_speed[:, head] * c.radius
    t = res.time
    stopping = (t > 2.6) & (v > 0.05)
    rate = -np.diff(v[stopping]) / np.diff(t[stopping])
    # Never faster than the set rate where the brake acts (it only slows at its rate);
    # uphill the material slows the belt at g·H/L·(q/(M_eq/L)) on its own, faster or not.
    acting = res.brake_torque[stopping, head][1:] != 0.0
    assert np.all(np.abs(rate[acting] - 0.3) < 0.01), rate[acting]
    assert np.all(res.brake_torque[:, head] >= 0.0)  # it only opposes the (clockwise) motion
    assert np.all(np.abs(v[t > t[-1] - 0.5]) < 1e-9)
    assert sim.state()["pulley_speed"][head] == 0.0


# --- takeups from the builder -------------------------------------------------------------
def test_builder_takeup_kinds():
    c = incline(takeup=TakeupSpec(kind="winch", max_speed=0.1))
    t = c.scene().pulleys[0].takeup
    assert (t.kind, t.force, t.max_speed, t.counterweight) == ("winch", 2 * c.takeup_tension(), 0.1, 0.0)
    t = incline(takeup=TakeupSpec(kind="fixed")).scene().pulleys[0].takeup
    assert (t.kind, t.force) == ("fixed", 2 * c.takeup_tension())
    t = incline().scene().pulleys[0].takeup
    assert t.kind == "gravity" and t.counterweight == pytest.approx(2 * c.takeup_tension() / G)


def test_winch_takeup_respects_its_speed_limit_in_a_start():
    """A winch limited to 2 cm/s on the tail of a hard start: the carriage never moves
    faster, and once it catches up the pull is back at the set force."""
    c = incline(takeup=TakeupSpec(kind="winch", max_speed=0.02))
    scene, sim, res = incline_run(c, 4.0)
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
        (0, "brake", {"deceleration": 0.5}, r"pulleys\[0\]\.brake\.deceleration = 0\.5: needs pulleys\[0\]\.brake\.torque"),
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
        (1, "holdback", {"forward": "ccw"}, r"pulleys\[1\]\.holdback\.forward = \"ccw\": the drive's start_curve\.speed"),
        (0, "holdback", {"forward": "up"}, r"pulleys\[0\]\.holdback\.forward = 'up': expected \"ccw\" or \"cw\""),
        (0, "takeup", {"kind": "wench", "force": 5.0}, r"pulleys\[0\]\.takeup\.kind = 'wench': .*did you mean \"winch\""),
        (0, "takeup", {"kind": "winch"}, r"pulleys\[0\]\.takeup\.force = missing: required for a winch takeup"),
        (0, "takeup", {"kind": "fixed"}, r"pulleys\[0\]\.takeup\.force = missing: required for a fixed takeup"),
        (0, "takeup", {"force": 5.0}, r"pulleys\[0\]\.takeup\.force = 5: a gravity takeup pulls with its counterweight"),
        (0, "takeup", {"kind": "winch", "force": 5.0, "counterweight": 2.0},
         r"pulleys\[0\]\.takeup\.counterweight = 2: a winch takeup has no counterweight"),
        (0, "takeup", {"max_speed": 0.5}, r"pulleys\[0\]\.takeup\.max_speed = 0\.5: limits a winch only"),
        (0, "takeup", {"kind": "winch", "force": 5.0, "max_speed": -0.5}, r"pulleys\[0\]\.takeup\.max_speed = -0\.5: must be > 0"),
        (0, "takeup", {"lock_on_stop": True}, r"pulleys\[0\]\.takeup\.lock_on_stop = true: the scene has no stop"),
        (0, "takeup", {"kind": "fixed", "force": 5.0, "lock_on_stop": True},
         r"pulleys\[0\]\.takeup\.lock_on_stop = true: a fixed \(screw\) takeup is always locked"),
        (0, "takeup", {"lock_on_stop": "yes"}, r"pulleys\[0\]\.takeup\.lock_on_stop = 'yes': expected a boolean"),
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
    with pytest.raises(SceneError, match=r"at = 'now': must be a finite number"):
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

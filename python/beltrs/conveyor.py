"""A belt conveyor in a few lines: the engineer's description (profile, belt class,
capacity and speed, idlers, drives, takeup) turned into a :class:`beltrs.Scene` with the
numerical settings chosen for the user, and into the matching static calculation
(:mod:`beltrs.statics`). Tutorial and the reasons for every choice: ``docs/conveyor-builder.md``.

.. code-block:: python

    import beltrs
    from beltrs.conveyor import Conveyor, DriveSpec

    c = Conveyor(profile=[(0, 0), (600, 0), (1000, 25)], curve_radii=[1500],
                 belt="ST1250", width=1.0, speed=4.0, capacity=1500.0,
                 drives=[DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=4.0, ramp=30.0))])
    scene = c.scene()            # a beltrs.Scene: belt, pulleys, idlers, load, drive, takeup
    din = c.statics()            # DIN 22101 tensions at every point (beltrs.statics)
    sim = beltrs.Simulation(scene)

Or from a TOML file with a ``[conveyor]`` table (:func:`load`); the scene it builds is an
ordinary scene (``scene.save(...)`` writes a scene file).

Geometry and signs: x along the conveyor from the tail, y up. The carry strand runs on top
from the tail (station 0) to the head (the last station); the belt travels clockwise round
the pulleys, so drive speeds and torques are negative in the engine's counter-clockwise
convention (the builder converts: give speeds positive).

SI units throughout; a capacity is in t/h (the unit engineers use), converted at once.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Optional, Sequence, Union

import numpy as np

from . import statics
from ._beltrs import SceneError
from .layout import Profile, idlers_along
from .design_start import START_KINDS, TAKEUP_KINDS
from .scene import (Belt, Brake, Drive, Friction, Holdback, Initial, Load, Motor, Pulley, Recording, Scene, Solver,
                    SpeedController, StartCurve, Takeup, TorqueFollow)
from .statics import check

if TYPE_CHECKING:
    from .start_grip import StartRatio

__all__ = [
    "BELTS",
    "BeltClass",
    "Conveyor",
    "DriveSpec",
    "IdlerSet",
    "StopSpec",
    "TakeupSpec",
    "load",
    "loads",
    "motor_rotor_inertia",
    "pulley_radius_for",
]

RUBBER_DENSITY = 1150.0  #: kg/m³, cover and core rubber (typical 1100-1200)
STEEL_DENSITY = 7850.0  #: kg/m³
CORD_FILL = 0.6  #: steel fraction of a cord's circumscribed circle (stranded 7x7 / 7x19 cords)


@dataclass(frozen=True)
class BeltClass:
    """A conveyor belt type: strength, carcass and stiffness per metre of belt width.

    Attributes:
        name: designation, e.g. ``"ST1250"`` or ``"EP630/4"``.
        strength: rated (minimum breaking) strength k_N, N per m of width (ST1250:
            1.25e6 N/m = 1250 N/mm).
        carcass_mass: carcass (cords or plies with their rubber) per m², kg/m².
        carcass_thickness: m (steel cord: the cord diameter; fabric: the plies).
        modulus: axial stiffness per metre of width, N/m (EA of a 1 m wide belt, N per unit
            strain).
        top_cover, bottom_cover: default cover thicknesses, m.
        cord_diameter: steel cord diameter, m (0 for fabric belts); sets the minimum
            pulley diameter (:func:`pulley_radius_for`).
    """

    name: str
    strength: float
    carcass_mass: float
    carcass_thickness: float
    modulus: float
    top_cover: float
    bottom_cover: float
    cord_diameter: float = 0.0

    def mass_per_length(self, width: float, top_cover: Optional[float] = None,
                        bottom_cover: Optional[float] = None) -> float:
        """Belt mass per metre, kg/m: width × (carcass + rubber density × covers)."""
        top = self.top_cover if top_cover is None else top_cover
        bottom = self.bottom_cover if bottom_cover is None else bottom_cover
        return width * (self.carcass_mass + RUBBER_DENSITY * (top + bottom))

    def axial_stiffness(self, width: float) -> float:
        """EA of a belt ``width`` m wide, N."""
        return self.modulus * width


def _steel(kn: int, d_mm: float, pitch_mm: float, top: float = 0.006, bottom: float = 0.005) -> BeltClass:
    d, t = d_mm * 1e-3, pitch_mm * 1e-3
    steel = CORD_FILL * math.pi * d * d / 4 / t  # m² of steel per m of width
    return BeltClass(
        name=f"ST{kn}", strength=kn * 1e3,
        carcass_mass=RUBBER_DENSITY * d + (STEEL_DENSITY - RUBBER_DENSITY) * steel,
        carcass_thickness=d, modulus=0.1 * kn * 1e3 / 0.0015, top_cover=top, bottom_cover=bottom,
        cord_diameter=d,
    )


def _fabric(kn: int, plies: int, ply_mm: float, top: float = 0.006, bottom: float = 0.002) -> BeltClass:
    s = plies * ply_mm * 1e-3
    return BeltClass(
        name=f"EP{kn}/{plies}", strength=kn * 1e3, carcass_mass=RUBBER_DENSITY * s, carcass_thickness=s,
        modulus=0.1 * kn * 1e3 / 0.010, top_cover=top, bottom_cover=bottom,
    )


#: The catalogue: **typical values**, not a manufacturer's data sheet (catalogues differ by
#: 10-20 %; use your belt's data via :class:`BeltClass` for a design).
#:
#: * Steel cord (ST, DIN 22131 / ISO 15236 classes): cord diameter and pitch as typically
#:   published for DIN 22131 belts; carcass = core rubber over the cord diameter plus the
#:   steel (60 % of each cord's circle); covers 6 + 5 mm. Modulus from an elastic elongation
#:   of 0.15 % at the reference load of 10 % of k_N (steel cord belts: 0.1-0.25 %), i.e.
#:   EA ≈ 67 × k_N per metre of width.
#: * Fabric EP (polyester-polyamide plies, DIN 22102 / ISO 14890 classes): plies of
#:   1.0-1.6 mm by ply strength, rubber-density carcass; covers 6 + 2 mm. Modulus from an
#:   elastic elongation of 1.0 % at 10 % of k_N (DIN 22102 allows up to 1.5 % total,
#:   permanent part included), i.e. EA = 10 × k_N per metre of width.
BELTS: dict[str, BeltClass] = {b.name: b for b in [
    _steel(630, 3.0, 10.0), _steel(800, 3.85, 15.0), _steel(1000, 3.85, 12.0), _steel(1250, 4.5, 14.0),
    _steel(1600, 5.85, 15.0), _steel(2000, 5.85, 12.0), _steel(2500, 7.0, 15.0), _steel(3150, 8.0, 15.0),
    _steel(3500, 8.6, 15.0), _steel(4000, 9.0, 15.0), _steel(4500, 9.7, 16.0), _steel(5000, 10.9, 17.0),
    _steel(5400, 11.3, 17.0),
    _fabric(400, 3, 1.1), _fabric(500, 3, 1.2), _fabric(630, 3, 1.4), _fabric(630, 4, 1.2),
    _fabric(800, 4, 1.4), _fabric(1000, 4, 1.6),
]}

#: Standard drum diameters, m (DIN 22101 / ISO 1536 series), the builder rounds up to.
DRUM_DIAMETERS = (0.4, 0.5, 0.63, 0.8, 1.0, 1.25, 1.4, 1.6, 1.8, 2.0)


def pulley_radius_for(belt: BeltClass) -> float:
    """Drive drum radius chosen for ``belt``, m: DIN 22101's minimum drum diameter
    D ≥ C_Tr · d (C_Tr = 145 for steel cord with d the cord diameter, 108 for EP fabric with d
    the carcass thickness), rounded up to the next standard diameter (:data:`DRUM_DIAMETERS`)."""
    need = 145.0 * belt.cord_diameter if belt.cord_diameter > 0 else 108.0 * belt.carcass_thickness
    for d in DRUM_DIAMETERS:
        if d >= need * (1 - 1e-9):
            return d / 2
    return math.ceil(need * 10) / 20


@dataclass
class IdlerSet:
    """Idler stations of one strand.

    Attributes:
        pitch: spacing along the strand, m, > 0.
        troughing: troughing angle of the side rolls, rad (0 for a flat return roll). The
            engine is planar: troughing does not change the dynamics; it is recorded for
            the user and for CEMA/DIN look-ups. Default 35° (carry), 0 (return).
        rotating_mass: rotating mass of the rolls of one station, kg, >= 0 (DIN's m'_R =
            this / pitch). Default 20 kg (three 133 mm rolls for a 1 m belt).
        roll_diameter: m. Default 0.133.
    """

    pitch: float = 1.2
    troughing: float = math.radians(35.0)
    rotating_mass: float = 20.0
    roll_diameter: float = 0.133

    def validate(self, where: str) -> None:
        check(f"{where}.pitch", self.pitch, positive=True, unit="m")
        check(f"{where}.troughing", self.troughing, high=math.pi / 2, unit="rad")
        check(f"{where}.rotating_mass", self.rotating_mass, unit="kg per station")
        check(f"{where}.roll_diameter", self.roll_diameter, positive=True, unit="m")


def _return_default() -> IdlerSet:
    return IdlerSet(pitch=3.0, troughing=0.0, rotating_mass=15.0)


LOCATIONS = ("head", "tail")

#: Takeup tensions chosen with the start's dynamics (:meth:`Conveyor.takeup_tension`), by the
#: conveyor's repr: a scene asks for it several times, each a few rounds of the lumped model.
_START_GRIP_CACHE: dict[str, float] = {}
CONTROLS = ("vfd", "ideal")


def check_control(where: str, control: object) -> str:
    """``control`` if it names a drive's control (:data:`CONTROLS`), else a SceneError
    naming ``where``, the value and the rule."""
    if control not in CONTROLS:
        raise SceneError(f"{where} = {control!r}: must be \"vfd\" (a PI speed controller with the motor's "
                         "inertia) or \"ideal\" (the ideal speed follower)")
    return control

#: The catalogue law of :func:`motor_rotor_inertia`: J = MOTOR_INERTIA_COEFF · T_r^MOTOR_INERTIA_EXP
#: (kg·m², T_r the rated torque in N·m), a least-squares fit in log-log of 133 IEC low-voltage
#: cage motors, 2-8 poles, 0.75-315 kW, 2.5-2412 N·m (tests/data/motor_inertia_catalogue.csv;
#: docs/drives.md, "Motor inertia").
MOTOR_INERTIA_COEFF = 1.405e-4
MOTOR_INERTIA_EXP = 1.4785


def motor_rotor_inertia(rated_power: float, rated_speed: float) -> float:
    """Rotor inertia of an IEC low-voltage cage induction motor, kg·m², from its rated power
    (W) and rated speed (rad/s): J = 1.405e-4 · T_r^1.4785 with T_r = rated_power /
    rated_speed in N·m, fitted to makers' catalogue data (docs/drives.md, "Motor inertia":
    133 motors of 2-8 poles, 0.75-315 kW, 2.5-2412 N·m, tests/data/motor_inertia_catalogue.csv;
    log rms error 0.35, the spread of the catalogues themselves between motors of the same
    rated torque; a 150 kW motor: 3.6 kg·m² at 1500 rpm, 6.5 at 1000 rpm). Outside 2.5-2412
    N·m the power law is extrapolated, without a warning: give the data sheet's inertia for
    larger motors when you have it."""
    p = check("rated_power", rated_power, positive=True, unit="W")
    n = check("rated_speed", rated_speed, positive=True, unit="rad/s")
    return MOTOR_INERTIA_COEFF * (p / n) ** MOTOR_INERTIA_EXP


@dataclass
class DriveSpec:
    """A drive at a pulley.

    Attributes:
        location: ``"head"`` or ``"tail"``. Default "head".
        share: its part of the steady peripheral force in the static calculation, in (0, 1];
            the shares of all drives add up to 1. Default 1.
        start_curve: the starting curve (belt speed, positive, m/s). Default None: Harrison,
            10 s to the conveyor's speed. It is the speed controller's reference (``control``);
            several speed-controlled drives share the load by the belt's elasticity and their
            controllers' ``droop``, not by a set share.
        power: rated motor power, W, > 0. Default None: chosen (:meth:`Conveyor.motor_power`):
            the larger of 1.25 × share × F_U × v (steady running with a 25 % margin) and
            the rigid-body start force share × (M_eq · a_max + F_U) × v / (0.9 ×
            ``torque_limit``) (the start curve followed within the torque limit with 10 %
            to spare), rounded up to 1 kW.
        torque_limit: the motor's current limit, × its rated torque. Default 1.6.
        inertia: motor rotor (and coupling) inertia at the motor shaft, kg·m², >= 0, turning
            at the motor's rated speed ``motor_speed`` (counted at the drum as inertia ×
            ratio², ratio = motor_speed / drum speed, the gearbox). Default None: the
            catalogue law :func:`motor_rotor_inertia` of the rated torque power /
            ``motor_speed`` (a 150 kW motor: 3.6 kg·m² at 1500 rpm, 6.5 at 1000 rpm); 0
            for a drive with a ``motor`` (its own ``rotor_inertia`` counts) and for none.
        motor_speed: rated motor speed, rad/s. Default 1500 rpm.
        control: ``"vfd"`` (default): a variable-speed drive, a PI speed controller with the
            torque limit and the motor's inertia, ``controller`` or else
            :class:`beltrs.SpeedController` with its default gains (tuned on the whole
            conveyor's rigid-body inertia, the motor's included); ``"ideal"``: the ideal
            speed follower (infinite bandwidth: the drum follows the start curve exactly
            while the torque is within the limit), which needs no ``controller``. The ideal
            follower with ``inertia=0`` is the builder's drive before session 10. Not for a
            drive with a ``motor`` (started direct on line) or a ``follow`` master (both
            refuse ``"ideal"``).
        controller: the PI speed controller's settings (:class:`beltrs.SpeedController`) for
            ``control="vfd"``; with its ``droop``, speed-controlled drives share load in
            proportion to rated torque / droop. Default None: ``SpeedController()``.
        follow: location of a master drive this one follows (master-slave torque
            sharing, :class:`beltrs.TorqueFollow`): it applies share / master's share of
            the master's torque (the drums have one radius). The master needs a
            ``controller``; a follower has no ``start_curve``. Default None.
        motor: an induction motor started direct on line (:class:`beltrs.Motor`) instead
            of speed control: the builder sets its ``gear_ratio`` (the belt at ``speed``
            at the motor's rated speed) and ``rotation`` (the drum's clockwise sense);
            ``power`` is then its rated power. Default None.
        flywheel: flywheel on the drive's high-speed shaft, kg*m^2, >= 0 (at the motor's
            rated speed ``motor_speed``, or the ``motor``'s). Default 0.
    """

    location: str = "head"
    share: float = 1.0
    start_curve: Optional[StartCurve] = None
    power: Optional[float] = None
    torque_limit: float = 1.6
    inertia: Optional[float] = None
    motor_speed: float = 1500.0 * 2 * math.pi / 60
    control: str = "vfd"
    controller: Optional[SpeedController] = None
    follow: Optional[str] = None
    motor: Optional[Motor] = None
    flywheel: float = 0.0

    def validate(self, where: str) -> None:
        if self.location not in LOCATIONS:
            raise SceneError(f"{where}.location = {self.location!r}: must be \"head\" or \"tail\"")
        check(f"{where}.share", self.share, positive=True, high=1.0, unit="share of F_U")
        if self.power is not None:
            check(f"{where}.power", self.power, positive=True, unit="W")
        check(f"{where}.torque_limit", self.torque_limit, positive=True, unit="x rated torque")
        if self.inertia is not None:
            check(f"{where}.inertia", self.inertia, unit="kg*m^2")
        check(f"{where}.motor_speed", self.motor_speed, positive=True, unit="rad/s")
        check_control(f"{where}.control", self.control)
        if self.control == "ideal" and self.controller is not None:
            raise SceneError(f"{where}.control = \"ideal\": the ideal speed follower has no controller; leave "
                             "controller out, or use control = \"vfd\"")
        if self.start_curve is not None and not isinstance(self.start_curve, StartCurve):
            raise SceneError(f"{where}.start_curve = {self.start_curve!r}: expected a beltrs.StartCurve")
        if self.controller is not None and not isinstance(self.controller, SpeedController):
            raise SceneError(f"{where}.controller = {self.controller!r}: expected a beltrs.SpeedController")
        check(f"{where}.flywheel", self.flywheel, unit="kg*m^2")
        if self.motor is not None:
            if not isinstance(self.motor, Motor):
                raise SceneError(f"{where}.motor = {self.motor!r}: expected a beltrs.Motor")
            if self.start_curve is not None or self.controller is not None or self.follow is not None:
                raise SceneError(f"{where}.motor: a motor started direct on line runs on its own curve; "
                                 "leave start_curve, controller and follow out")
            if self.control != "vfd":
                raise SceneError(f"{where}.control = {self.control!r}: a motor started direct on line has no "
                                 "speed control; leave control out")
        if self.follow is not None:
            if self.follow not in LOCATIONS or self.follow == self.location:
                raise SceneError(f"{where}.follow = {self.follow!r}: must be the location of another drive "
                                 f"(\"head\" or \"tail\")")
            if self.start_curve is not None or self.controller is not None or self.control != "vfd":
                raise SceneError(f"{where}.follow = {self.follow!r}: a follower takes its torque from its master; "
                                 "leave start_curve, control and controller out")


@dataclass
class TakeupSpec:
    """A takeup on the head or tail pulley, pulling in line with the strands (the pulley
    slides away from the conveyor; each strand then carries exactly half the pull;
    ``docs/stops-takeups.md``).

    Attributes:
        location: ``"tail"`` (default) or ``"head"``.
        tension: tension it holds in each strand, N, > 0. Default None: chosen (see
            :meth:`Conveyor.takeup_tension`).
        travel: travel allowed each way from the start, m (hard stops). Default inf.
        kind: ``"gravity"`` (default: a counterweight of 2 x tension / g), ``"winch"``
            (pulls with 2 x tension, no faster than ``max_speed``) or ``"fixed"`` (a screw
            takeup, tightened to 2 x tension when the scene is stabilised, locked in runs).
        max_speed: winch speed limit, m/s, > 0. Winch only. Default inf.
        lock_on_stop: lock the carriage when the conveyor's ``stop`` begins. Needs a
            ``stop``; not for a fixed takeup. Default False.
    """

    location: str = "tail"
    tension: Optional[float] = None
    travel: float = math.inf
    kind: str = "gravity"
    max_speed: float = math.inf
    lock_on_stop: bool = False

    def validate(self, where: str) -> None:
        if self.location not in LOCATIONS:
            raise SceneError(f"{where}.location = {self.location!r}: must be \"head\" or \"tail\"")
        if self.tension is not None:
            check(f"{where}.tension", self.tension, positive=True, unit="N per strand")
        check(f"{where}.travel", self.travel, positive=True, finite=False, unit="m")
        if self.kind not in TAKEUP_KINDS:
            raise SceneError(f"{where}.kind = {self.kind!r}: must be one of {', '.join(map(repr, TAKEUP_KINDS))}")
        check(f"{where}.max_speed", self.max_speed, positive=True, finite=False, unit="m/s")
        if self.max_speed != math.inf and self.kind != "winch":
            raise SceneError(f"{where}.max_speed = {self.max_speed!r}: limits a winch only (kind = {self.kind!r})")
        if not isinstance(self.lock_on_stop, bool):
            raise SceneError(f"{where}.lock_on_stop = {self.lock_on_stop!r}: must be True or False")
        if self.lock_on_stop and self.kind == "fixed":
            raise SceneError(f"{where}.lock_on_stop = True: a fixed (screw) takeup is always locked in a run")


@dataclass
class StopSpec:
    """A stop of the conveyor during the run (``docs/stops-takeups.md``): every drive loses
    power at ``time`` and the belt coasts; with a ``brake`` location a brake is applied
    ``brake_delay`` later on that drum, with a torque target (``brake_torque``) or a
    deceleration target (``deceleration``, up to ``brake_torque``).

    Attributes:
        time: time the drives lose power, s (simulated time of the run), finite.
        brake: ``"head"`` or ``"tail"``: the drum with the brake. Default None (coast).
        brake_torque: braking torque at the drum, N*m, > 0. Default None: with a
            ``deceleration``, :meth:`Conveyor.brake_torque_for` (1.5 x (M_eq x a + the
            material's pull on the slope) x drum radius); needed without one.
        deceleration: belt deceleration target at the drum, m/s^2, > 0. Default None (a
            torque brake).
        brake_delay: time from the power failure to the brake's application, s, >= 0.
            Default 0.
        brake_rise: time the brake torque takes to build up, s, >= 0. Default 0.
    """

    time: float = 0.0
    brake: Optional[str] = None
    brake_torque: Optional[float] = None
    deceleration: Optional[float] = None
    brake_delay: float = 0.0
    brake_rise: float = 0.0

    def validate(self, where: str) -> None:
        check(f"{where}.time", self.time, low=-math.inf, unit="s")
        brake_keys = {"brake_torque": self.brake_torque, "deceleration": self.deceleration}
        if self.brake is None:
            for key, value in brake_keys.items():
                if value is not None:
                    raise SceneError(f"{where}.{key} = {value!r}: needs {where}.brake (the drum with the brake)")
            for key in ("brake_delay", "brake_rise"):
                if getattr(self, key) != 0.0:
                    raise SceneError(f"{where}.{key} = {getattr(self, key)!r}: needs {where}.brake "
                                     "(the drum with the brake)")
            return
        if self.brake not in LOCATIONS:
            raise SceneError(f"{where}.brake = {self.brake!r}: must be \"head\", \"tail\" or None (coast)")
        if self.brake_torque is not None:
            check(f"{where}.brake_torque", self.brake_torque, positive=True, unit="N*m")
        if self.deceleration is not None:
            check(f"{where}.deceleration", self.deceleration, positive=True, unit="m/s^2")
        elif self.brake_torque is None:
            raise SceneError(f"{where}.brake_torque = None: give the brake torque (N*m) or a deceleration (m/s^2)")
        check(f"{where}.brake_delay", self.brake_delay, unit="s")
        check(f"{where}.brake_rise", self.brake_rise, unit="s")


@dataclass
class Conveyor:
    """A belt conveyor described as an engineer does (``docs/conveyor-builder.md``).

    Attributes:
        profile: stations (distance, elevation), m, along the carry strand from the tail
            pulley (first) to the head pulley (last): where the belt's centre line runs on
            the carry idlers. At least two; distances increasing.
        curve_radii: vertical curve radius at each interior station, m (concave or convex,
            tangent to both neighbouring straights, :class:`beltrs.layout.Profile`). A
            station where the slope changes needs a radius larger than the drum diameter.
            Default: none (no interior stations).
        belt: a :data:`BELTS` name (``"ST1250"``, ``"EP630/4"``) or a :class:`BeltClass`.
            Default "ST1250".
        width: belt width, m. Default 1.0.
        top_cover, bottom_cover: cover thicknesses, m. Default: the belt class's.
        speed: belt speed, m/s, > 0. Default 2.
        capacity: material flow, t/h, >= 0. m'_L = capacity / (3.6 · speed) kg/m on the
            loaded carry strand. Default 0.
        loading: loading point, m along the carry profile from the tail. Default 5.
        discharge: discharge point, m along the carry profile. Default None (the head).
        carry: carry idlers. Default :class:`IdlerSet` (1.2 m, 35°, 20 kg).
        returns: return idlers. Default 3 m, flat, 15 kg.
        f: DIN 22101 artificial friction coefficient at every idler. Default 0.02.
        drives: :class:`DriveSpec` list. Default one head drive.
        takeup: :class:`TakeupSpec`. Default a tail gravity takeup with a chosen tension.
        stop: :class:`StopSpec`: power failure (and brake) during the run. Default None.
        holdback: ``"head"`` or ``"tail"``: a holdback (backstop) on that drum against
            the belt running back, e.g. on an incline. Default None.
        pulley_radius: head and tail drum radius, m. Default None: :func:`pulley_radius_for`.
        lagging: belt friction on the drums, (static, kinetic). Default (0.4, 0.35), rubber
            lagging.
        element_length: element length, m. Default None: the smaller of a quarter of the
            carry pitch and 30° of arc on the drums, shortened where needed so that neither
            idler pitch is within an eighth of a whole number of elements (the rolls'
            gravity cogging would add up in phase: :func:`beltrs.layout.element_length_off_pitches`;
            a quarter of the carry pitch is a whole 4, so drums above 1.146 m take 0.291 m
            instead of 0.3 m with the default 1.2 m and 3 m pitches). The rigid-body belt's
            bodies at most 0.3 × the drum radius before that (0.1185 m on the default 0.4 m
            drums, where their chordal action on the drums is small: case G's 60 m start
            +1.46 % raw over the peak below 2 Hz, 30° bodies +4.71 %; the 300 m conveyor of
            tests/conveyor_300.py +3.32 %, 30° bodies +4.74 %; about 2.7× the run's cost,
            :func:`beltrs.layout.belt_element_length`); a longer explicit rigid body length
            warns (:class:`beltrs.AccuracyWarning`).
        damping_ratio: belt's axial damping, fraction of critical per element. Default 0.05.
        gravity: m/s². Default 9.81.
        start: the design state the scene starts from (:class:`beltrs.Initial`,
            ``docs/design-start.md``): ``"rest"`` (default; the standstill tensions, the
            takeup's and the lifts', drives holding, belt at rest) or ``"running"`` (the
            steady-running tensions of :meth:`statics`, belt, drums and rolls at
            ``speed``, the drives' start curves already ended). Either way the belt is
            placed along the profile, stretched to those tensions, with the takeup where
            the scene puts it: no relaxation.
        formulation: the belt model (:attr:`beltrs.Belt.formulation`):
            ``"node_kelvin_voigt"`` (default, Hustrulid's nodes) or ``"rigid_body"``
            (Kubas's and Guo & Wang's rigid bodies, the same element length, mass, EA, EI).
            The rigid-body belt starts from its own design placement (every joint at its
            design tension, bodies on a drum resting on their ends; docs/design-start.md).
    """

    profile: Sequence[Sequence[float]] = ((0.0, 0.0), (100.0, 0.0))
    curve_radii: Sequence[float] = ()
    belt: Union[str, BeltClass] = "ST1250"
    width: float = 1.0
    top_cover: Optional[float] = None
    bottom_cover: Optional[float] = None
    speed: float = 2.0
    capacity: float = 0.0
    loading: float = 5.0
    discharge: Optional[float] = None
    carry: IdlerSet = field(default_factory=IdlerSet)
    returns: IdlerSet = field(default_factory=_return_default)
    f: float = 0.02
    drives: list[DriveSpec] = field(default_factory=lambda: [DriveSpec()])
    takeup: TakeupSpec = field(default_factory=TakeupSpec)
    stop: Optional[StopSpec] = None
    holdback: Optional[str] = None
    pulley_radius: Optional[float] = None
    lagging: Sequence[float] = (0.4, 0.35)
    element_length: Optional[float] = None
    damping_ratio: float = 0.05
    gravity: float = 9.81
    start: str = "rest"
    formulation: str = "node_kelvin_voigt"

    # --- derived quantities -------------------------------------------------------------
    @property
    def belt_class(self) -> BeltClass:
        """The :class:`BeltClass` (looked up by name)."""
        if isinstance(self.belt, BeltClass):
            return self.belt
        if isinstance(self.belt, str) and self.belt in BELTS:
            return BELTS[self.belt]
        raise SceneError(f"belt = {self.belt!r}: unknown belt class (known: {', '.join(BELTS)}), "
                         "or give a beltrs.conveyor.BeltClass")

    @property
    def belt_mass(self) -> float:
        """m'_G, kg/m."""
        return self.belt_class.mass_per_length(self.width, self.top_cover, self.bottom_cover)

    @property
    def material_mass(self) -> float:
        """m'_L = capacity / (3.6 · speed), kg/m (capacity t/h, speed m/s)."""
        return self.capacity / (3.6 * self.speed)

    @property
    def radius(self) -> float:
        """Head and tail drum radius, m."""
        return pulley_radius_for(self.belt_class) if self.pulley_radius is None else float(self.pulley_radius)

    @property
    def carry_profile(self) -> Profile:
        """The carry strand's :class:`beltrs.layout.Profile`."""
        return Profile(self.profile, list(self.curve_radii) if len(self.profile) > 2 else None)

    @property
    def chosen_element_length(self) -> float:
        """Element length the scene uses, m (``element_length``, or the choice documented
        there)."""
        if self.element_length is not None:
            return float(self.element_length)
        from .layout import belt_element_length

        target = min(self.carry.pitch / 4, self.radius * math.pi / 6)
        return belt_element_length(target, [self.carry.pitch, self.returns.pitch],
                                   formulation=self.formulation, drum_radius=self.radius)

    def validate(self) -> None:
        """Check every field; raise :class:`beltrs.SceneError` naming the first bad one."""
        pts = self.profile
        if hasattr(pts, "tolist"):
            pts = pts.tolist()
        if isinstance(pts, (str, bytes)) or not isinstance(pts, Sequence) or len(pts) < 2:
            raise SceneError(f"profile = {pts!r}: need at least two stations (distance, elevation), m")
        for i, p in enumerate(pts):
            if isinstance(p, (str, bytes)) or not isinstance(p, Sequence) or len(p) != 2:
                raise SceneError(f"profile[{i}] = {p!r}: expected (distance, elevation), m")
            check(f"profile[{i}][0]", p[0], low=-math.inf, unit="m")
            check(f"profile[{i}][1]", p[1], low=-math.inf, unit="m")
            if i and not float(p[0]) > float(pts[i - 1][0]):
                raise SceneError(f"profile[{i}][0] = {p[0]!r}: station distances must increase "
                                 f"(the previous is {pts[i - 1][0]!r})")
        for name, cls in (("carry", IdlerSet), ("returns", IdlerSet), ("takeup", TakeupSpec)):
            if not isinstance(getattr(self, name), cls):
                raise SceneError(f"{name} = {getattr(self, name)!r}: expected a beltrs.conveyor.{cls.__name__}")
        if not isinstance(self.drives, (list, tuple)) or not all(isinstance(d, DriveSpec) for d in self.drives):
            raise SceneError(f"drives = {self.drives!r}: expected a list of beltrs.conveyor.DriveSpec")
        for name in ("curve_radii", "lagging"):
            value = getattr(self, name)
            if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
                raise SceneError(f"{name} = {value!r}: expected a list of numbers")
        for i, radius in enumerate(self.curve_radii):
            check(f"curve_radii[{i}]", radius, unit="m")
        if len(self.curve_radii) != max(0, len(pts) - 2):
            raise SceneError(f"curve_radii = {list(self.curve_radii)!r}: need one radius per interior station "
                             f"({len(pts) - 2})")
        self.belt_class  # a known class, or a SceneError naming it
        check("width", self.width, positive=True, unit="m")
        for name in ("top_cover", "bottom_cover"):
            if getattr(self, name) is not None:
                check(name, getattr(self, name), unit="m")
        check("speed", self.speed, positive=True, unit="m/s")
        check("capacity", self.capacity, unit="t/h")
        check("f", self.f, unit="dimensionless")
        check("damping_ratio", self.damping_ratio, unit="fraction of critical")
        check("gravity", self.gravity, positive=True, unit="m/s^2")
        self.carry.validate("carry")
        self.returns.validate("returns")
        if self.pulley_radius is not None:
            check("pulley_radius", self.pulley_radius, positive=True, unit="m")
        if self.element_length is not None:
            check("element_length", self.element_length, positive=True, unit="m")
        if len(self.lagging) != 2:
            raise SceneError(f"lagging = {self.lagging!r}: expected (static, kinetic)")
        mus = check("lagging[0]", self.lagging[0], unit="dimensionless")
        muk = check("lagging[1]", self.lagging[1], unit="dimensionless")
        if muk > mus:
            raise SceneError(f"lagging[1] = {muk!r}: the kinetic coefficient must be <= the static {mus!r}")
        if not self.drives:
            raise SceneError("drives = []: a conveyor needs at least one drive")
        for i, d in enumerate(self.drives):
            d.validate(f"drives[{i}]")
        for i, d in enumerate(self.drives):
            if d.follow is not None:
                master = next((m for m in self.drives if m.location == d.follow), None)
                if (master is None or master.control != "vfd" or master.motor is not None
                        or master.follow is not None):
                    raise SceneError(f"drives[{i}].follow = {d.follow!r}: the master must be a drive there with a "
                                     "PI speed controller (control = \"vfd\"), not itself a follower")
        places = [d.location for d in self.drives]
        if len(set(places)) != len(places):
            raise SceneError(f"drives = {places!r}: one drive per pulley (a second motor on one drum is "
                             "one drive with the summed power)")
        shares = sum(d.share for d in self.drives)
        if abs(shares - 1) > 1e-9:
            raise SceneError(f"drives[*].share = {[d.share for d in self.drives]!r}: must add up to 1")
        self.takeup.validate("takeup")
        if self.stop is not None:
            if not isinstance(self.stop, StopSpec):
                raise SceneError(f"stop = {self.stop!r}: expected a beltrs.conveyor.StopSpec or None")
            self.stop.validate("stop")
        if self.takeup.lock_on_stop and self.stop is None:
            raise SceneError("takeup.lock_on_stop = True: needs a stop (Conveyor.stop) to lock on")
        if self.holdback is not None and self.holdback not in LOCATIONS:
            raise SceneError(f"holdback = {self.holdback!r}: must be \"head\", \"tail\" or None")
        prof = self.carry_profile  # validates the curve radii (SceneError naming them)
        r = self.radius
        for i, radius in enumerate(self.curve_radii):
            if _turn(pts, i + 1) != 0.0 and not radius > 2 * r:
                raise SceneError(f"curve_radii[{i}] = {radius!r}: the slope changes at station {i + 1}; its "
                                 f"curve radius must exceed the drum diameter {2 * r:g} m (the return strand "
                                 "runs a drum diameter below the carry strand)")
        length = prof.length
        check("loading", self.loading, high=length, unit=f"m along the carry profile, <= {length:.6g}")
        if self.discharge is not None:
            check("discharge", self.discharge, low=self.loading, high=length,
                  unit=f"m along the carry profile, after loading, <= {length:.6g}")
        pitch = max(self.carry.pitch, self.returns.pitch)
        if pitch > 0.5 * length:
            raise SceneError(f"carry.pitch, returns.pitch = {self.carry.pitch!r}, {self.returns.pitch!r}: "
                             f"the strands ({length:.6g} m) need at least two idlers")
        le = self.chosen_element_length
        if self.start not in START_KINDS:
            raise SceneError(f"start = {self.start!r}: must be one of {', '.join(map(repr, START_KINDS))} (the "
                             "design state the scene starts from)")
        from .scenes import check_formulation

        check_formulation(self.formulation)
        if le > self.carry.pitch / 2:
            raise SceneError(f"element_length = {le!r}: must be at most half the carry pitch "
                             f"({self.carry.pitch / 2:g} m) for the belt to rest on each idler "
                             "(a quarter or less is advised, docs/stability.md)")

    # --- the static calculation ---------------------------------------------------------
    def loop(self, takeup_tension: Optional[float] = None) -> list[Union[statics.Section, statics.Point]]:
        """The belt loop as :mod:`beltrs.statics` sections and points, in the direction of
        travel from the tail: tail pulley, carry sections (split at the loading and
        discharge points and at the profile's straights and curves), head pulley, return
        sections. Pulley wraps have no length; the idlered strands run the profile's whole
        length (the builder puts idlers from half a pitch after the tail to half a pitch
        before the head)."""
        self.validate()
        prof = self.carry_profile
        ml = self.material_mass
        t_up = self.takeup_tension() if takeup_tension is None else takeup_tension
        v = self.speed
        cuts = sorted({0.0, prof.length, float(self.loading),
                       float(prof.length if self.discharge is None else self.discharge)}
                      | set(_piece_ends(prof)))
        discharge = prof.length if self.discharge is None else float(self.discharge)
        carry, back = [], []
        for a, b in zip(cuts[:-1], cuts[1:]):
            if b - a <= 1e-9:
                continue
            lift = float(prof.point(b)[0][1] - prof.point(a)[0][1])
            loaded = ml if (self.loading <= a and b <= discharge + 1e-9) else 0.0
            carry.append((a, statics.Section(b - a, lift, "carry", loaded, self.carry.rotating_mass / self.carry.pitch,
                                             self.carry.pitch, name=f"carry {a:.6g}-{b:.6g} m")))
            back.append(statics.Section(b - a, -lift, "return", 0.0, self.returns.rotating_mass / self.returns.pitch,
                                        self.returns.pitch, name=f"return {b:.6g}-{a:.6g} m"))
        share = {d.location: d.share for d in self.drives}
        tu = self.takeup.location

        def pulley(name: str) -> statics.Point:
            return statics.Point(name, drive=share.get(name, 0.0), takeup=t_up if tu == name else None)

        items: list[Union[statics.Section, statics.Point]] = [pulley("tail")]
        for a, s in carry:
            if a == self.loading and ml > 0:
                items.append(statics.Point("loading", resistance=ml * v * v))
            items.append(s)
        items.append(pulley("head"))
        items.extend(reversed(back))
        return items

    def statics(self, method: Optional[statics.Method] = None,
                takeup_tension: Optional[float] = None, running: bool = False) -> statics.TensionProfile:
        """Steady-running tensions at every point (:func:`beltrs.statics.tensions`) by
        ``method`` (default DIN 22101 with this conveyor's ``f``). Distances run from the
        tail pulley along the carry strand, then back along the return strand.

        ``running``: False (default) gives the standard's tensions, which leave out the
        belt's m'_G·v²; True adds it (N) to every tension and to each drive's T1 and T2
        (:func:`beltrs.design_start.running_tension`: with a gravity or winch takeup; a
        fixed takeup adds nothing), the tensions the running belt carries and
        ``start="running"`` places (docs/statics.md, "The belt's m'·v²")."""
        running = statics.check_flag("running", running)
        method = statics.DIN22101(self.f, self.gravity) if method is None else method
        profile = statics.tensions(self.loop(takeup_tension), self.belt_mass, method)
        if not running:
            return profile
        from .design_start import running_tension

        extra = running_tension(self.belt_mass, self.speed, self.takeup.kind)
        return replace(profile, tension=profile.tension + extra,
                       drives=[replace(d, tight=d.tight + extra, slack=d.slack + extra) for d in profile.drives])

    def liftoff_radii(self) -> list[tuple[int, str, float, float]]:
        """Concave vertical curves against lift-off at steady running: for each concave curve
        (the slope increasing in the direction of the head) and each strand, (station index,
        strand, radius, minimum radius), m. A belt of weight m'_G·g per metre under tension T
        lifts off a concave curve of radius R when T > m'_G·g·R (DIN 22101; the empty belt,
        the worst case), so R_min = T / (m'_G·g) with T the DIN 22101 tension at the curve's
        middle. The return strand runs a drum diameter further from the centre (R + 2r).
        Starts raise T above steady running: keep a margin (a dynamic run shows it)."""
        self.validate()
        pts = [tuple(map(float, q)) for q in self.profile]
        prof = self.carry_profile
        p = self.statics()
        weight = self.belt_mass * self.gravity
        out = []
        s = 0.0
        k = 0
        for piece in prof._pieces:
            if piece.curvature != 0.0:
                k += 1
            if piece.curvature > 0:
                # station index of this curve: the k-th curved interior station
                station = [i for i in range(1, len(pts) - 1) if _turn(pts, i) != 0.0][k - 1]
                mid = s + piece.length / 2
                radius = 1.0 / piece.curvature
                out.append((station, "carry", radius, float(p.along(mid)) / weight))
                out.append((station, "return", radius + 2 * self.radius,
                            float(p.along(2 * prof.length - mid)) / weight))
            s += piece.length
        return out

    def takeup_tension(self, start_dynamics: bool = True) -> float:
        """Takeup tension per strand, N: ``takeup.tension``, or the smallest that meets
        DIN 22101's two minimum-tension rules (with the design values stated here) and
        keeps the belt on the drive drum through the start's dynamics:

        * grip at every drive in a start: T2 ≥ F_A,i / (e^{µ·θ} − 1), with F_A,i the
          drive's share of the larger of DIN's starting force 1.5 · F_U and the rigid-belt
          start force M_eq · a_max + F_U (:meth:`start_force`) less the motors' part of
          M_eq (a rotor is accelerated through its own shaft, not through the drum's grip
          on the belt), µ the lagging's kinetic coefficient and θ = π (a simple head or
          tail drum), and T2 the slack side's tension in the start: its steady-running
          value less a_max times the moving mass the belt carries from the drive's slack
          side to the takeup (the strand between them is accelerated by that tension
          difference, and the takeup holds only its own end: a head drive's return strand
          with its rolls to a tail takeup; DIN 22101 takes the start's tension distribution
          the same way);
        * sag between idlers: T ≥ (m'_G + m'_L) · g · a / (8 · h_rel) on the carry strand
          and m'_G · g · a_r / (8 · h_rel) on the return strand, h_rel = 1 % of the pitch;
        * grip through the start's dynamics (``start_dynamics``, default True): T₁/T₂ at the
          drive drum at most e^{µ·θ} at every instant of the start in the lumped model of
          :meth:`start_grip` (the belt held on the drum, the strands elastic and sagging,
          the takeup's mass swinging, the drive's speed loop following the start curve):
          the rigid belt's start force leaves out the strands' and the takeup's swing,
          which asks the drum for more (the 300 m conveyor of the tests: T₁/T₂ 3.59 at the
          15 kN of the two rules above in the builder's 10 s start, 3.30 at 28 kN in a 4 s
          start, against e^{0.35·π} = 3.00; docs/conveyor-builder.md "Takeup tension").
          The tensions are linear in the takeup's, so the model's answer is the rise that
          brings the worst instant to e^{µ·θ}; the counterweight and the spans' stiffness
          move with it, so it is iterated to its fixed point (two or three rounds, a few
          milliseconds each). Not applied where :meth:`start_grip` is None (several drives,
          a motor started direct on line);

        rounded up to the next kN.
        """
        start_dynamics = statics.check_flag("start_dynamics", start_dynamics)
        if self.takeup.tension is not None:
            return float(self.takeup.tension)
        base = 10e3  # any level: tensions are linear in it
        p = self.statics(takeup_tension=base)
        g = self.gravity
        grip = math.exp(self.lagging[1] * math.pi) - 1
        starting = max(1.5 * p.effective, self._rigid_start(self._moving_mass_without_motors(), p.effective))
        share = {d.location: d.share for d in self.drives}
        a_max = max(self._peak_acceleration(d) for d in self.drives)
        raise_by = 0.0
        for d in p.drives:
            slack = d.slack - a_max * self._mass_to_takeup(d.name)
            raise_by = max(raise_by, share[d.name] * starting / grip - slack)
        h = 0.01
        sag_carry = (self.belt_mass + self.material_mass) * g * self.carry.pitch / (8 * h)
        sag_return = self.belt_mass * g * self.returns.pitch / (8 * h)
        carry_min = min(t for t, lab in zip(p.tension, p.label) if lab.startswith(("tail", "carry", "loading")))
        return_min = min(t for t, lab in zip(p.tension, p.label) if lab.startswith(("head", "return")))
        raise_by = max(raise_by, sag_carry - carry_min, sag_return - return_min)
        floor = tension = base + raise_by
        with np.printoptions(threshold=sys.maxsize):  # every field in full (no "..." in long arrays)
            key = repr(self)  # the choice is a function of the fields alone
        if start_dynamics and key in _START_GRIP_CACHE:
            return _START_GRIP_CACHE[key]
        for _ in range(20 if start_dynamics else 0):  # the start's overshoot: the lumped model's fixed point
            start = self.start_grip(tension)
            if start is None:
                break
            rise = start.takeup_for(grip + 1)
            if tension + rise <= floor:  # the two rules above hold the belt already
                tension = floor
                break
            tension += rise
            if abs(rise) < 1.0:  # N
                break
        chosen = float(math.ceil(tension / 1e3) * 1e3)
        if start_dynamics:
            if len(_START_GRIP_CACHE) >= 64:
                _START_GRIP_CACHE.pop(next(iter(_START_GRIP_CACHE)))
            _START_GRIP_CACHE[key] = chosen
        return chosen

    def start_grip(self, takeup_tension: Optional[float] = None) -> Optional[StartRatio]:
        """The drive drum's tensions through the start, the belt held on the drum: the
        lumped model of :mod:`beltrs.start_grip` (the two strands as ten elements each of EA
        in series with their spans' sag, their moving mass, both drums, the takeup's
        carriage, the drive's PI speed loop or ideal follower, the idlers' running
        resistance) along the drive's start curve, from its time 0 to the curve's end plus
        one period of the loop's lowest mode. ``takeup_tension`` N per strand, default
        :meth:`takeup_tension`. Returns a :class:`beltrs.start_grip.StartRatio` (its
        ``ratio`` is T₁/T₂ at the drum against time; the belt slides where it exceeds
        e^{µ_k·π}), or None where the model does not apply: a drive that is not speed
        controlled (a ``motor`` started direct on line, a ``follow`` drive) or more than one
        drive. Tens of milliseconds."""
        from .design_start import at_rest
        from .start_grip import Loop, start_ratio

        if len(self.drives) != 1 or self.drives[0].motor is not None or self.drives[0].follow is not None:
            return None
        d = self.drives[0]
        t_up = self.takeup_tension() if takeup_tension is None else \
            float(check("takeup_tension", takeup_tension, positive=True, unit="N"))
        g, r, mg = self.gravity, self.radius, self.belt_mass
        length = self.carry_profile.length
        discharge = length if self.discharge is None else float(self.discharge)
        ml = self.material_mass * (discharge - float(self.loading)) / length  # spread over the strand
        roll_c = self.carry.rotating_mass / self.carry.pitch
        roll_r = self.returns.rotating_mass / self.returns.pitch
        n = 10  # elements per strand: the takeup mode within 0.1 % of 30 (tests/test_takeup_swing.py)
        rest = statics.tensions(at_rest(self.loop(t_up)), mg, statics.DIN22101(0.0, g))
        le = length / n
        mid = (np.arange(n) + 0.5) * le
        tail_first = self.takeup.location == "tail"  # rest distances run from the takeup
        carry_at = mid if tail_first else length + mid
        return_at = length + mid if tail_first else mid
        powers = self._powers()
        ratio = self._shaft_speed(d) / (self.speed / r)
        drum = 0.8 * self._drum_mass() + mg * math.pi * r
        rotor = self._shaft_inertia(d, powers[d.location]) * ratio**2 / r**2
        kp = ki = None
        if d.control == "vfd":
            pi = d.controller if d.controller is not None else SpeedController()
            mass = self.moving_mass() if pi.inertia is None else pi.inertia / r**2  # J/r², the loop's tuning
            kp = 2 * pi.damping_ratio * pi.bandwidth * mass if pi.proportional_gain is None \
                else pi.proportional_gain / r**2
            ki = pi.bandwidth**2 * mass if pi.integral_gain is None else pi.integral_gain / r**2
        takeup_mass = {"gravity": 2 * t_up / g + self._drum_mass(), "winch": self._drum_mass(),
                       "fixed": None}[self.takeup.kind]
        loop = Loop(length=length, ea=self.belt_class.axial_stiffness(self.width),
                    carry_mass=mg + ml + 0.8 * roll_c, return_mass=mg + 0.8 * roll_r,
                    carry_weight=(mg + ml) * g, return_weight=mg * g,
                    carry_pitch=self.carry.pitch, return_pitch=self.returns.pitch,
                    carry_resistance=self.f * g * (mg + ml + roll_c), return_resistance=self.f * g * (mg + roll_r),
                    carry_rest=rest.along(carry_at), return_rest=rest.along(return_at),
                    drive=d.location, drive_mass=drum + rotor, pulley_mass=drum,
                    takeup=self.takeup.location, takeup_mass=takeup_mass, kp=kp, ki=ki)
        curve = self._curve(d)

        def speed(t: np.ndarray) -> np.ndarray:
            return np.abs(curve.speed_at(t))

        return start_ratio(loop, speed, curve.end, periods=1.0, acceleration=self._peak_acceleration(d))

    # --- the scene ----------------------------------------------------------------------
    def scene(self, *, elements: Optional[int] = None, time_step_fraction: float = 0.5,
              duration: Optional[float] = None, method: Optional[statics.Method] = None) -> Scene:
        """The :class:`beltrs.Scene` of this conveyor (choices: ``docs/conveyor-builder.md``),
        starting from its design state (``start``; :meth:`initial`): no relaxation needed.

        Pulleys, in belt order: "tail", "head". The belt is placed along the profile (its
        straights and vertical curves, the return strand a drum diameter below) through
        ``scene.initial.path``, stretched to the design tensions, its spans on the rolls in
        their static sag (``scene.initial.sag``). The node belt meets the drums and the
        rolls with wrap contact (``belt.pulley_contact = "wrap"``, ``belt.idler_contact =
        "wrap"``: no chordal ripple on a held drum, no chordal action of the rolls,
        ``docs/wrap-contact.md``; 1.6-1.8x the wall time of the segment contact on the
        rolls); the rigid-body belt with wrap joints on the drums (docs/kubas.md, "Wrap
        joints") and the segment contact
        on the rolls.

        Args:
            elements: belt elements; overrides the chosen element length. Default None.
            time_step_fraction: of the stability limit. Default 0.5.
            duration: ``recording.duration``, s. Default: the longest start curve + 5 s
                (``start="rest"``), 5 s (``"running"``); with a ``stop``, at least the stop
                time + 1.5 x the rigid-belt coasting time M_eq v / F_U + 5 s.
            method: the static calculation a running start takes its tensions from
                (:class:`beltrs.statics.DIN22101` or :class:`~beltrs.statics.CEMA`).
                Default DIN 22101 with this conveyor's ``f`` (the resistance the engine's
                idlers apply, so that the run starts in its own steady state). A start at
                rest has no running resistance whatever the method.
        """
        self.validate()
        prof = self.carry_profile
        pts = [tuple(map(float, p)) for p in self.profile]
        r = self.radius
        bc = self.belt_class
        mg, ml = self.belt_mass, self.material_mass
        d0 = _unit(pts[0], pts[1])
        d1 = _unit(pts[-2], pts[-1])
        tail_c = (pts[0][0] + r * d0[1], pts[0][1] - r * d0[0])  # r to the right of travel
        head_c = (pts[-1][0] + r * d1[1], pts[-1][1] - r * d1[0])
        lag = Friction(static=float(self.lagging[0]), kinetic=float(self.lagging[1]))
        t_up = self.takeup_tension()
        pdyn = self.statics()
        by_loc = {d.location: d for d in self.drives}
        drum_mass = self._drum_mass()
        running = self.start == "running"
        pulleys: dict[str, Pulley] = {}
        for name, c, direction in (("tail", tail_c, (-d0[0], -d0[1])), ("head", head_c, d1)):
            drive = by_loc.get(name)
            takeup = None
            if self.takeup.location == name:
                takeup = self._takeup(t_up, direction)
            engine_drive = None if drive is None else self._drive(drive, pdyn, r)
            curve = None if engine_drive is None else engine_drive.start_curve
            if curve is not None and running:  # already at speed: the curve has ended
                engine_drive = replace(engine_drive, start_curve=replace(
                    curve, start=-(curve.prestart + curve.ramp)))
            pulleys[name] = Pulley(
                name=name, center=_round(c), radius=r, mass=drum_mass, inertia=0.8 * drum_mass * r * r,
                friction=lag, contact_stiffness=1e8, takeup=takeup, drive=engine_drive)
            self._stop_on(pulleys, name)
        plist = [pulleys["tail"], pulleys["head"]]

        le = self.chosen_element_length
        if self.element_length is not None and self.formulation == "rigid_body":
            from .layout import check_rigid_body_length

            check_rigid_body_length(le, r)  # longer than l <= 0.3 R: warned (docs/kubas.md)
        # Half-critical contact damping for one node on the rolls: c = 2*0.5*sqrt(k*m).
        k_roll = 1e8
        c_carry = math.sqrt(k_roll * (mg + ml) * le)
        c_return = math.sqrt(k_roll * mg * le)
        roll_friction = Friction(static=0.5, kinetic=0.5)

        def rolls(s: IdlerSet, damping: float) -> dict[str, Any]:
            rr = s.roll_diameter / 2
            return dict(radius=rr, contact_stiffness=k_roll, contact_damping=damping, friction=roll_friction,
                        resistance=self.f, rotating_mass=s.rotating_mass, inertia=0.8 * s.rotating_mass * rr * rr)

        idlers = idlers_along(prof, self.carry.pitch, **rolls(self.carry, c_carry))
        idlers += idlers_along(prof, self.returns.pitch, offset=-2 * r, **rolls(self.returns, c_return))
        loads = []
        if ml > 0:
            start = prof.point(self.loading)[0]
            end = prof.point(prof.length if self.discharge is None else self.discharge)[0]
            loads.append(Load(mass_per_length=ml, start=_round(start), end=_round(end)))
        path = 2 * prof.length + 2 * math.pi * r  # near enough for the element count
        from .scenes import conveyor_contact, conveyor_idler_contact

        belt = Belt(axial_stiffness=bc.axial_stiffness(self.width), mass_per_length=mg,
                    bending_stiffness=20.0 * self.width, damping_ratio=self.damping_ratio,
                    elements=elements if elements is not None else math.ceil(path / le),
                    formulation=self.formulation, pulley_contact=conveyor_contact(self.formulation),
                    idler_contact=conveyor_idler_contact(self.formulation))
        longest = max((self._curve(d).end for d in self.drives), default=0.0)
        if duration is None:
            duration = 5.0 if running else longest + 5.0
            if self.stop is not None:
                # Run past the stop for 1.5 x the rigid-belt coasting time M_eq v / F_U (+ 5 s).
                coast = self.moving_mass() * self.speed / max(self._running_force(), 1.0)
                duration = max(duration, float(self.stop.time) + 1.5 * coast + 5.0)
        return Scene(belt=belt, pulleys=plist, idlers=idlers, loads=loads, gravity=self.gravity,
                     solver=Solver(time_step_fraction=time_step_fraction),
                     recording=Recording(duration=duration, interval=0.05, channels=("tension", "node_position"),
                                         stabilise=False),
                     initial=self.initial(method))

    def design_path(self) -> list[tuple[float, float, float]]:
        """The belt's path as corners (x, y, radius), m, in the engine's node order
        (:attr:`beltrs.Initial.path`): from the tail drum's top (where the carry strand
        meets it) round the tail (two 90° corners of the drum radius), along the return
        strand (the profile a drum diameter lower; a curve of radius R there has R + 2r when
        concave, R − 2r when convex), round the head and back along the carry profile (its
        stations with their curve radii). Node order runs against the direction of travel,
        as on the pulleys' own path."""
        self.validate()
        pts = [np.array(tuple(map(float, p))) for p in self.profile]
        r = self.radius
        radii = [float(x) for x in self.curve_radii]

        def left(d: tuple[float, float]) -> np.ndarray:
            return np.array([-d[1], d[0]])

        d0, d1 = _unit(pts[0], pts[1]), _unit(pts[-2], pts[-1])
        a = pts[0] - np.array(d0) * r
        corners = [(a, r), (a - 2 * r * left(d0), r)]
        curved = [i for i in range(1, len(pts) - 1) if _turn(pts, i) != 0.0]
        for i in curved:  # the return strand, tail to head
            na, nb = left(_unit(pts[i - 1], pts[i])), left(_unit(pts[i], pts[i + 1]))
            miter = (na + nb) / (1 + float(na @ nb))
            concave = _turn(pts, i) > 0
            corners.append((pts[i] - 2 * r * miter, radii[i - 1] + (2 * r if concave else -2 * r)))
        b = pts[-1] + np.array(d1) * r
        corners += [(b - 2 * r * left(d1), r), (b, r)]
        for i in reversed(curved):  # the carry strand, head to tail
            corners.append((pts[i], radii[i - 1]))
        return [(float(p[0]), float(p[1]), float(rad)) for p, rad in corners]

    def initial(self, method: Optional[statics.Method] = None) -> Initial:
        """The design state of :meth:`scene` (:class:`beltrs.Initial`), as ``start`` says:
        the tensions of :meth:`statics` (``"running"``; ``method`` as :meth:`scene`; plus the
        belt's m'_G·v² with a gravity or winch takeup,
        :func:`beltrs.design_start.running_tension`) or of
        the loop at standstill (``"rest"``: :func:`beltrs.design_start.at_rest`, DIN 22101
        with f = 0), laid on :meth:`design_path`: each strand's static sections on its run
        of the path, each drum's point on its wrap (a drive's T1 → T2 drop spread by the
        capstan law), node order against travel (speed −``speed`` when running); the spans
        on rolls placed in their static sag (``sag = True``)."""
        from . import design_start

        corners = self.design_path()
        length = design_start.path_length(corners)
        r = self.radius
        lp = self.carry_profile.length
        if self.start == "running":
            method = statics.DIN22101(self.f, self.gravity) if method is None else method
            profile = self.statics(method)
        else:
            profile = statics.tensions(design_start.at_rest(self.loop()), self.belt_mass,
                                       statics.DIN22101(0.0, self.gravity))
        wrap = math.pi * r
        back = length - 2 * wrap - lp  # the return run's length on the path
        tail = 0.0 if self.takeup.location == "tail" else lp  # loop distance of the tail
        head = (tail + lp) % (2 * lp)
        pieces = [
            design_start.Wrap("tail", path_in=wrap, path_out=0.0),
            design_start.Run(head, head + lp, path_start=wrap + back, path_end=wrap),
            design_start.Wrap("head", path_in=2 * wrap + back, path_out=wrap + back),
            design_start.Run(tail, tail + lp, path_start=length, path_end=2 * wrap + back),
        ]
        speed = -self.speed if self.start == "running" else 0.0
        # The spans go in their sag (node belt and rigid bodies, docs/design-start.md); running,
        # the belt carries its m'_G·v² above the statics' tensions (gravity or winch takeup).
        return design_start.initial(profile, pieces, length, speed=speed, path=corners, sag=True,
                                    belt_mass=self.belt_mass, takeup=self.takeup.kind)

    def _takeup(self, t_up: float, direction: tuple[float, float]) -> Takeup:
        """The takeup pulling with 2 x ``t_up`` (N) along ``direction``."""
        spec = self.takeup
        travel = float(spec.travel)
        limits = dict(direction=direction, travel_min=-travel, travel_max=travel, lock_on_stop=spec.lock_on_stop)
        if spec.kind == "gravity":
            return Takeup(counterweight=2 * t_up / self.gravity, **limits)
        return Takeup(kind=spec.kind, force=2 * t_up, max_speed=spec.max_speed, **limits)

    def _stop_on(self, pulleys: dict[str, Pulley], name: str) -> None:
        """Add the stop's power failure, brake and the holdback to drum ``name``."""
        p = pulleys[name]
        changes: dict[str, Any] = {}
        stop = self.stop
        if stop is not None and p.drive is not None:
            changes["drive"] = replace(p.drive, power_off=float(stop.time))
        if stop is not None and stop.brake == name:
            torque = stop.brake_torque
            if torque is None:
                torque = self.brake_torque_for(float(stop.deceleration))
            changes["brake"] = Brake(torque=float(torque), deceleration=stop.deceleration,
                                     applied=float(stop.time) + float(stop.brake_delay), rise=float(stop.brake_rise))
        if self.holdback == name:
            changes["holdback"] = Holdback(forward="cw")  # the builder's drums turn clockwise
        if changes:
            pulleys[name] = replace(p, **changes)

    def material_lift(self) -> float:
        """Pull of the material along the belt on the loaded length, N: m'_L · g · ΔH, ΔH the
        rise from the loading to the discharge point (negative on a decline): what a
        holdback or a brake must hold at rest."""
        prof = self.carry_profile
        end = prof.length if self.discharge is None else float(self.discharge)
        rise = float(prof.point(end)[0][1]) - float(prof.point(float(self.loading))[0][1])
        return self.material_mass * self.gravity * rise

    def brake_torque_for(self, deceleration: float) -> float:
        """Brake torque at a drum for a stop at ``deceleration`` (m/s²), N·m: 1.5 × (M_eq · a
        + |m'_L · g · ΔH|) × drum radius, the rigid belt's braking force plus the material's
        pull on the slope (:meth:`material_lift`), with 50 % margin."""
        a = check("deceleration", deceleration, positive=True, unit="m/s^2")
        return 1.5 * (self.moving_mass() * a + abs(self.material_lift())) * self.radius

    def _curve(self, d: DriveSpec) -> StartCurve:
        if d.follow is not None:  # a follower runs on its master's curve
            d = next(m for m in self.drives if m.location == d.follow)
        curve = d.start_curve or StartCurve(shape="harrison", speed=self.speed, ramp=10.0)
        if curve.speed is None or not curve.speed > 0:
            raise SceneError(f"start_curve.speed = {curve.speed!r}: give the belt speed, positive (m/s); the "
                             "builder turns it into the drum's clockwise sense")
        creep = None if curve.creep_speed is None else -curve.creep_speed
        return replace(curve, speed=-curve.speed, creep_speed=creep)

    def _drive(self, d: DriveSpec, p: statics.TensionProfile, r: float) -> Drive:
        if d.motor is not None:
            speed = d.motor.rated_speed
            if speed is None or not speed > 0:
                raise SceneError(f"motor.rated_speed = {speed!r}: give the motor's rated speed, rad/s, > 0")
            ratio = speed / (self.speed / r)
            motor = replace(d.motor, gear_ratio=ratio, rotation="cw")
            return Drive(motor=motor, inertia=self._motor_inertia(d, 0.0) * ratio**2, flywheel=d.flywheel)
        powers = self._powers()
        power = powers[d.location]
        ratio = d.motor_speed / (self.speed / r)
        rated = power / d.motor_speed * ratio  # N*m at the drum
        inertia = (self._motor_inertia(d, power) + d.flywheel) * ratio**2
        if d.follow is not None:
            master = next(m for m in self.drives if m.location == d.follow)
            return Drive(follow=TorqueFollow(master=d.follow, ratio=d.share / master.share),
                         max_torque=d.torque_limit * rated, inertia=inertia)
        controller = None
        if d.control == "vfd":
            controller = d.controller if d.controller is not None else SpeedController()
        return Drive(start_curve=self._curve(d), max_torque=d.torque_limit * rated, inertia=inertia,
                     controller=controller)

    def motor_power(self, location: str = "head") -> float:
        """Rated power of the drive at ``location``, W (given, or chosen as
        :class:`DriveSpec` says)."""
        self._drive_at(location)
        return self._powers()[location]

    def motor_inertia(self, location: str = "head") -> float:
        """Motor inertia of the drive at ``location`` at its motor shaft, kg·m² (given as
        ``inertia``, or :func:`motor_rotor_inertia` of its rated power and speed; a DOL
        ``motor``'s ``rotor_inertia`` not included)."""
        d = self._drive_at(location)
        return self._motor_inertia(d, self._powers()[location])

    def _drive_at(self, location: str) -> DriveSpec:
        for d in self.drives:
            if d.location == location:
                return d
        raise SceneError(f"location = {location!r}: no drive there (drives: {[d.location for d in self.drives]})")

    @staticmethod
    def _motor_inertia(d: DriveSpec, power: float) -> float:
        """The drive's ``inertia`` (kg·m² at the motor shaft), or the catalogue law's for
        ``power`` W at ``motor_speed`` (none beside a DOL ``motor``)."""
        if d.inertia is not None:
            return float(d.inertia)
        if d.motor is not None or power == 0.0:  # no motor inertia: a DOL motor's own, or the power iteration's start
            return 0.0
        return motor_rotor_inertia(power, d.motor_speed)

    def _powers(self) -> dict[str, float]:
        """Every drive's rated power, W, by location: given, or chosen as :class:`DriveSpec`
        says. The start force counts the motors' inertia, which the catalogue law takes
        from the power: iterated from no motor inertia to the fixed point (whole kW; two or
        three rounds)."""
        given = {}
        for d in self.drives:
            if d.motor is not None and d.motor.rated_power is not None:
                given[d.location] = float(d.motor.rated_power)
            elif d.power is not None:
                given[d.location] = float(d.power)
        if len(given) == len(self.drives):
            return given
        running = self._running_force()
        base = self._moving_mass_without_motors()
        powers = {d.location: given.get(d.location, 0.0) for d in self.drives}
        for _ in range(50):
            start = self._rigid_start(base + self._motors_mass(powers), running)
            new = dict(given)
            for d in self.drives:
                if d.location not in given:
                    need = max(1.25 * d.share * running, d.share * start / (0.9 * d.torque_limit)) * self.speed
                    new[d.location] = float(math.ceil(max(need, 1.0) / 1e3) * 1e3)
            if new == powers:
                break
            powers = new
        return powers

    def moving_mass(self) -> float:
        """M_eq, every moving mass reduced to the belt line, kg (CEMA's rigid-belt start,
        thesis §1.4): belt over both strands and the drum wraps, material on the loaded
        length, idler rolls (I/r² = 0.8 × rotating mass, thin tubes), the two drums
        (0.8 × mass) and the drives' motor inertia through the gearbox."""
        return self._moving_mass_without_motors() + self._motors_mass(self._powers())

    def _moving_mass_without_motors(self) -> float:
        r = self.radius
        wraps = self.belt_mass * 2 * math.pi * r
        drums = 2 * 0.8 * self._drum_mass()
        return self._strand_mass("carry") + self._strand_mass("return") + wraps + drums

    def _strand_mass(self, strand: str) -> float:
        """Moving mass of one strand reduced to the belt line, kg: its belt, its idler rolls
        at 0.8 of their rotating mass per pitch (thin tubes, I/r²) and, on the carry strand,
        the material from loading to discharge."""
        length = self.carry_profile.length
        idlers = self.carry if strand == "carry" else self.returns
        mass = (self.belt_mass + 0.8 * idlers.rotating_mass / idlers.pitch) * length
        if strand == "carry":
            discharge = length if self.discharge is None else float(self.discharge)
            mass += self.material_mass * (discharge - float(self.loading))
        return mass

    def _mass_to_takeup(self, drive: str) -> float:
        """Moving mass on the belt's path from ``drive``'s slack side to the takeup, kg
        (:meth:`_strand_mass`, as in the start force): none where both are at the same drum;
        a head drive's return strand to a tail takeup; a tail drive's carry strand, with its
        material, to a head takeup."""
        if drive == self.takeup.location:
            return 0.0
        return self._strand_mass("return" if drive == "head" else "carry")

    def _motors_mass(self, powers: dict[str, float]) -> float:
        """The drives' high-speed shafts reduced to the belt line, kg: I·ratio²/r²."""
        return sum(self._shaft_inertia(d, powers[d.location]) * (self._shaft_speed(d) / self.speed) ** 2
                   for d in self.drives)

    @staticmethod
    def _shaft_speed(d: DriveSpec) -> float:
        """Rated speed of the drive's high-speed shaft, rad/s."""
        if d.motor is not None and d.motor.rated_speed is not None:
            return float(d.motor.rated_speed)
        return float(d.motor_speed)

    @classmethod
    def _shaft_inertia(cls, d: DriveSpec, power: float) -> float:
        """Inertia on the drive's high-speed shaft that turns with the belt, kg*m^2: motor
        and coupling (``inertia``, or the catalogue law's for ``power`` W), flywheel, and a
        rigidly geared DOL motor's rotor."""
        rotor = 0.0
        if d.motor is not None and d.motor.coupling is None:
            rotor = float(d.motor.rotor_inertia)
        return cls._motor_inertia(d, power) + float(d.flywheel) + rotor

    def start_force(self) -> float:
        """Peak drive force of a rigid-belt start along the drives' curves, N:
        M_eq · a_max + F_U (:func:`beltrs.din22101.rigid_start_force`), a_max the largest
        acceleration of any drive's start curve."""
        return self._rigid_start(self.moving_mass(), self._running_force())

    def _rigid_start(self, mass: float, running: float) -> float:
        """``mass`` (kg) accelerated at the steepest drive curve's a_max against ``running``
        (N): :func:`beltrs.din22101.rigid_start_force`, N."""
        from .din22101 import rigid_start_force

        a_max = max(self._peak_acceleration(d) for d in self.drives)
        return rigid_start_force(mass, a_max, running)

    def _running_force(self) -> float:
        """DIN 22101's F_U, N (independent of the takeup tension)."""
        return self.statics(takeup_tension=10e3).effective

    def _peak_acceleration(self, d: DriveSpec) -> float:
        curve = self._curve(d)
        t = np.linspace(curve.start, curve.end, 2001)
        return float(np.max(np.abs(curve.acceleration_at(t))))

    def _drum_mass(self) -> float:
        """Drum mass, kg: case G's 800 kg for a 0.8 m drum of a 1 m belt, scaled with the
        drum's surface (radius × width)."""
        return 800.0 * (self.radius / 0.4) * self.width


def _unit(a: Sequence[float], b: Sequence[float]) -> tuple[float, float]:
    dx, dy = float(b[0]) - float(a[0]), float(b[1]) - float(a[1])
    n = math.hypot(dx, dy)
    return dx / n, dy / n


def _turn(pts: Sequence[Sequence[float]], i: int) -> float:
    """Signed turn of the profile at station i, rad (positive: concave, counter-clockwise)."""
    a, b = _unit(pts[i - 1], pts[i]), _unit(pts[i], pts[i + 1])
    phi = math.atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1])
    return 0.0 if abs(phi) < 1e-12 else phi


def _round(p: Sequence[float]) -> tuple[float, float]:
    return (round(float(p[0]), 9), round(float(p[1]), 9))


def _piece_ends(prof: Profile) -> list[float]:
    out, s = [], 0.0
    for piece in prof._pieces:
        s += piece.length
        out.append(s)
    return out


# --- TOML -------------------------------------------------------------------------------
def loads(text: str) -> Conveyor:
    """A :class:`Conveyor` from the text of a TOML file with a ``[conveyor]`` table (keys:
    the Conveyor fields; ``[conveyor.carry]``, ``[conveyor.returns]``, ``[conveyor.takeup]``,
    ``[conveyor.stop]`` tables; ``[[conveyor.drives]]`` with an optional ``start_curve`` table). Unknown keys
    and wrong types raise :class:`beltrs.SceneError` naming the path."""
    from .scene_file import _need_reader

    if not isinstance(text, str):
        raise SceneError(f"conveyor text = {text!r}: expected the text of a TOML file (str)")
    toml = _need_reader()
    try:
        data = toml.loads(text)
    except toml.TOMLDecodeError as err:
        raise SceneError(f"conveyor file: not valid TOML: {err}") from None
    except RecursionError:
        raise SceneError("conveyor file: nested too deeply to read") from None
    if not isinstance(data, dict) or set(data) != {"conveyor"}:
        keys = sorted(data) if isinstance(data, dict) else data
        raise SceneError(f"conveyor file: top-level keys {keys!r}: expected exactly one [conveyor] table")
    return _read(data["conveyor"])


def load(path: Any) -> Conveyor:
    """A :class:`Conveyor` from a TOML file (see :func:`loads`); ``.scene()`` builds it."""
    import os

    if not isinstance(path, (str, os.PathLike)):
        raise SceneError(f"conveyor file = {path!r}: expected a path (str or os.PathLike)")
    try:
        with open(os.fspath(path), encoding="utf-8") as fh:
            text = fh.read()
    except (OSError, UnicodeDecodeError) as exc:
        raise SceneError(f"conveyor file {os.fspath(path)!r}: {getattr(exc, 'strerror', None) or exc}") from None
    return loads(text)


def _read(table: Any) -> Conveyor:
    from .scene import unknown_key_message

    def fields_of(cls: type, data: Any, path: str) -> dict[str, Any]:
        if not isinstance(data, dict):
            raise SceneError(f"{path} = {data!r}: expected a table")
        known = [f for f in cls.__dataclass_fields__]
        for k in data:
            if k not in known:
                raise SceneError(unknown_key_message(f"{path}.{k}", k, known))
        return dict(data)

    kw = fields_of(Conveyor, table, "conveyor")
    for key, cls in (("carry", IdlerSet), ("returns", IdlerSet), ("takeup", TakeupSpec), ("stop", StopSpec)):
        if key in kw:
            kw[key] = cls(**fields_of(cls, kw[key], f"conveyor.{key}"))
    if "drives" in kw:
        if not isinstance(kw["drives"], list):
            raise SceneError(f"conveyor.drives = {kw['drives']!r}: expected a list of [[conveyor.drives]] tables")
        drives = []
        for i, d in enumerate(kw["drives"]):
            dk = fields_of(DriveSpec, d, f"conveyor.drives[{i}]")
            from .scene import _read_dataclass

            if "start_curve" in dk:
                dk["start_curve"] = _read_dataclass(StartCurve, dk["start_curve"], f"conveyor.drives[{i}].start_curve")
            if "motor" in dk:
                dk["motor"] = _read_dataclass(Motor, dk["motor"], f"conveyor.drives[{i}].motor")
            if "controller" in dk:
                where = f"conveyor.drives[{i}].controller"
                dk["controller"] = _read_dataclass(SpeedController, dk["controller"], where)
            drives.append(DriveSpec(**dk))
        kw["drives"] = drives
    for key in ("profile", "curve_radii", "lagging"):
        if key in kw and not isinstance(kw[key], list):
            raise SceneError(f"conveyor.{key} = {kw[key]!r}: expected a list")
    c = Conveyor(**kw)
    c.validate()
    return c

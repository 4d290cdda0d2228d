"""Scene description: plain dataclasses, SI units throughout.

A :class:`Scene` is data only. :class:`beltrs.Simulation` validates and compiles it in the
Rust engine; every error names the field (e.g. ``pulleys[1].radius``), the value and the
rule broken. ``Scene.to_dict()`` gives the exact form the engine reads; unknown keys in
that form are errors, never ignored. ``Scene.from_dict()`` reads that form back strictly
(unknown keys, with a "did you mean" suggestion, and wrong types raise
:class:`beltrs.SceneError`), and ``Scene.save()`` / :func:`beltrs.load_scene` write and
read the same structure as a TOML scene file (``docs/scene-format.md``).

There is one schema, the engine's (``rust/src/scene``): the defaults of these dataclasses
are the engine's own (``beltrs._beltrs.scene_defaults()``), their fields must be exactly
the engine's keys (checked when this module is imported), and every key and type is
checked by the engine's reader, whichever form a scene comes in.

Constructing any of these classes normalises what it is given, so that a scene built in
Python and the same scene read from a file compare equal: integers and NumPy scalars in
float fields become ``float``, and sequences (lists, NumPy arrays) in sequence fields
become tuples of ``float``. Values of the wrong type are left as given and reported when
the scene is compiled or saved.
"""

from __future__ import annotations

import collections.abc
import numbers
import os
import typing
from dataclasses import MISSING, dataclass, field, fields, is_dataclass
from typing import Any, Callable, Mapping, Optional, Sequence, Union

from ._beltrs import check_scene, check_scene_table, scene_defaults, unknown_key_rule

__all__ = [
    "Belt",
    "BeltEnd",
    "Brake",
    "Drive",
    "FluidCoupling",
    "Friction",
    "Holdback",
    "Initial",
    "Idler",
    "Load",
    "NonlinearContact",
    "Motor",
    "Pulley",
    "Recording",
    "Scene",
    "Solver",
    "SpeedController",
    "StartCurve",
    "Takeup",
    "TorqueFollow",
]


#: The engine's defaults of every table of the scene format (one dict per table).
ENGINE_DEFAULTS: dict[str, dict[str, Any]] = scene_defaults()


#: Deepest nesting :meth:`_Table.to_dict` follows (the format itself is 5 levels deep);
#: anything deeper is handed to the engine as it is, which refuses it by name.
_MAX_DEPTH = 16


def _engine_table(table: str) -> Callable[[type], type]:
    """Class decorator, applied before ``@dataclass``: give each annotated field the
    engine's default for key ``table``.``name``, and refuse (at import) a class whose fields
    are not exactly the engine's keys."""

    def apply(cls: type) -> type:
        defaults = ENGINE_DEFAULTS[table]
        names = list(cls.__dict__.get("__annotations__", {}))
        if set(names) != set(defaults):
            missing, extra = sorted(set(defaults) - set(names)), sorted(set(names) - set(defaults))
            raise ImportError(
                f"beltrs.{cls.__name__} does not match the engine's {table!r} table: "
                f"declare {missing}, remove {extra} (see 'Adding a scene field' in docs/scene-format.md)"
            )
        hints = typing.get_type_hints(cls)
        for name in names:
            value, tp = defaults[name], hints[name]
            if typing.get_origin(tp) is list:
                setattr(cls, name, field(default_factory=list))
            elif isinstance(value, dict):
                setattr(cls, name, field(default_factory=tp))  # a sub-table present by default
            elif isinstance(value, list):
                setattr(cls, name, tuple(value))
            else:
                setattr(cls, name, value)
        cls._engine_table = table  # type: ignore[attr-defined]
        return cls

    return apply


class _Table:
    """Base of the scene dataclasses: the plain-data form."""

    def to_dict(self) -> dict[str, Any]:
        """The plain-data form the engine reads: dicts, lists and values as they are (a
        value of the wrong type is passed on for the engine to name)."""
        return _plain(self, 0)


@dataclass
@_engine_table("friction")
class Friction(_Table):
    """Belt friction on a pulley or idler.

    Two models (``docs/belt-drives.md``, "Creep friction"):

    * ``"stick_force"`` (default): stick-force friction (Hustrulid's thesis eq. 4.76-4.94):
      a contact sticks while the force that holds it is within mu_s * N, and slides with
      mu_k * N otherwise.
    * ``"creep"``: Kubas's (2014) creep-rate friction (eq. 12-19) on pulleys: the friction
      coefficient is a smooth function mu(Delta, v) of the creep displacement Delta of the
      contact point (a memory kept in the state and in checkpoints) and of the relative
      speed v. Below ``transition_speed`` the contact creeps and mu rises to mu_s (with
      Delta up to ``creep_limit`` and with v); from 1.5 * ``transition_speed`` it slides
      at mu_k. Pulleys only (an idler with it is refused). Runs under both integrators:
      central differences apply it with a stick limit (no step restriction), RKF45
      (``Solver(integrator="rkf45")``) integrates the memory with the state and resolves
      the law as it is, so a small ``transition_speed`` costs RKF45 small steps.

    Attributes:
        static: static coefficient mu_s, dimensionless, >= kinetic. Default 0 (no friction
            stage is compiled when every body has mu_s = 0).
        kinetic: kinetic coefficient mu_k, dimensionless. Default: equal to ``static``.
        model: ``"stick_force"`` (default), ``"creep"`` or ``"none"`` (no coefficients
            allowed).
        transition_speed: creep model only: Delta_v, m/s, > 0. Default None: 1e-3 m/s
            (creep below it, sliding at mu_k above 1.5 * Delta_v; slip arcs of belt drives
            and conveyors slide at 1e-2 m/s and more).
        creep_limit: creep model only: Delta_max, the creep displacement at which mu
            reaches mu_s, m, > 0. Default None: 1e-4 m (0.1 mm, the presliding displacement
            of a rubber cover).
    """

    static: float
    kinetic: Optional[float]
    model: str
    transition_speed: Optional[float]
    creep_limit: Optional[float]

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("takeup")
class Takeup(_Table):
    """A takeup: the pulley translates on a line (thesis eq. 4.63), pulled by a
    counterweight (``kind="gravity"``), a winch (``"winch"``) or set by a screw
    (``"fixed"``); see ``docs/stops-takeups.md``.

    Attributes:
        kind: ``"gravity"`` (default): the counterweight's weight pulls. ``"winch"``: a
            winch pulls with ``force`` while the carriage moves no faster than
            ``max_speed``. ``"fixed"``: a screw takeup, locked in dynamic runs;
            :meth:`beltrs.Simulation.stabilise` tightens it to ``force`` (the screw is set at
            rest).
        counterweight: counterweight mass, kg, >= 0; it moves with the pulley. Gravity
            takeups only. Default 0.
        direction: unit vector of the pull, dimensionless. Default (0, -1) (hanging).
        travel_min: lowest travel along ``direction`` from the start, m (hard stop, <= 0).
            Default -inf.
        travel_max: highest travel, m (>= 0). Default +inf.
        force: pull of a winch or screw takeup along ``direction``, N, > 0 (twice the strand
            tension when both strands run parallel to the line). Required for those kinds,
            refused for a gravity takeup. Default None.
        max_speed: winch speed limit, m/s, > 0: the carriage never moves faster; at the
            limit the tension departs from ``force``. Winch only. Default inf.
        lock_on_stop: lock the carriage where it is when the scene's first stop begins (the
            earliest drive ``power_off`` or brake ``applied`` time). Default False.
    """

    kind: str
    counterweight: float
    direction: tuple[float, float]
    travel_min: float
    travel_max: float
    force: Optional[float]
    max_speed: float
    lock_on_stop: bool

    def __post_init__(self) -> None:
        _normalise(self)


#: Shapes of a starting curve (:class:`StartCurve`).
START_SHAPES = ("harrison", "nordell", "cubic", "linear")


@dataclass
@_engine_table("start_curve")
class StartCurve(_Table):
    """Starting curve of a speed-controlled drive (Guo & Wang 2020 §4; ``docs/drives.md``):
    the belt speed at the drive pulley surface against time.

    With tau = (t - t0)/T the fraction of a ramp of duration T begun at t0, each shape is
    v0 * s(tau): ``"harrison"`` s = (1 - cos(pi*tau))/2; ``"nordell"`` s = 2*tau^2 for
    tau <= 1/2, -1 + 4*tau - 2*tau^2 beyond (speed and acceleration continuous);
    ``"cubic"`` s = 3*tau^2 - 2*tau^3; ``"linear"`` s = tau.

    Before ``start`` the speed is 0. With ``prestart`` > 0 the drive first runs up to
    ``creep_speed`` over ``creep_ramp`` seconds (same shape) and holds it; the main ramp,
    from the creep speed (0 without a pre-start) to ``speed`` over ``ramp`` seconds, begins
    at ``start + prestart``. Afterwards the speed stays at ``speed``.

    Attributes:
        shape: ``"harrison"`` (default), ``"nordell"``, ``"cubic"`` or ``"linear"``.
        speed: final belt speed v0 at the drive pulley surface, m/s, counter-clockwise
            positive (pulley speed = speed / radius). Required: finite, non-zero.
        ramp: duration T of the main ramp, s, > 0. Required.
        start: time the curve begins, s (absolute simulated time). Default 0.
        prestart: duration of the pre-start (delay) section, s, >= 0. Default 0 (none).
        creep_speed: speed held during the pre-start, m/s, between 0 and ``speed`` (same
            sign). Default None: 10 % of ``speed``. Only with ``prestart`` > 0.
        creep_ramp: duration of the run-up to the creep speed, s, in (0, ``prestart``].
            Default None: ``prestart``/2. Only with ``prestart`` > 0.
    """

    shape: str
    speed: Optional[float]
    ramp: Optional[float]
    start: float
    prestart: float
    creep_speed: Optional[float]
    creep_ramp: Optional[float]

    def __post_init__(self) -> None:
        _normalise(self)

    def evaluate(self, t: Any) -> tuple[Any, Any]:
        """Belt speed (m/s) and acceleration (m/s^2) at time(s) ``t`` (s), computed by the
        engine's own formulas (exact, analytic). A scalar gives floats, a sequence or array
        gives arrays of its shape.

        Raises:
            beltrs.SceneError: a field breaks its rule (named ``start_curve.<field>``).
        """
        import numpy as np

        from ._beltrs import start_curve_eval

        times = np.asarray(t, dtype=float)
        speed, accel = start_curve_eval(self.to_dict(), times.ravel().tolist())
        if times.ndim == 0:
            return float(speed[0]), float(accel[0])
        return speed.reshape(times.shape), accel.reshape(times.shape)

    def speed_at(self, t: Any) -> Any:
        """Belt speed at time(s) ``t`` (s), m/s (see :meth:`evaluate`)."""
        return self.evaluate(t)[0]

    def acceleration_at(self, t: Any) -> Any:
        """Belt acceleration at time(s) ``t`` (s), m/s^2 (see :meth:`evaluate`)."""
        return self.evaluate(t)[1]

    @property
    def end(self) -> float:
        """Time the curve reaches ``speed`` for good, s: start + prestart + ramp."""
        return float(self.start) + float(self.prestart) + float(self.ramp or 0.0)


@dataclass
@_engine_table("controller")
class SpeedController(_Table):
    """PI speed controller of a speed-controlled drive (``docs/drives.md``): a real VFD
    beside the ideal speed follower. The drive's ``start_curve`` is its reference and its
    ``max_torque`` the torque limit.

    The motor torque is T = clamp((Kp*(w_ref - w) + Ki*I) / (1 + Kp*delta), +-max_torque),
    dI/dt = w_ref - w - delta*T, with conditional integration while limited (anti-windup).

    Attributes:
        bandwidth: speed-loop bandwidth w_c, rad/s, > 0. Default 10 (1.6 Hz).
        damping_ratio: damping ratio zeta of the rigid loop, > 0. Default 1.
        inertia: inertia J the default gains are tuned on, kg*m^2, > 0. Default None: the
            rigid-body inertia of the whole conveyor reflected to this pulley (belt and
            material, every pulley and idler roll as I*(r/r_k)^2), divided by the torque
            the drives give per unit of this controller's output (the number of PI drives
            plus their followers' ratios).
        proportional_gain: Kp, N*m*s/rad, > 0. Default None: 2*zeta*w_c*J.
        integral_gain: Ki, N*m/rad, >= 0. Default None: w_c^2*J.
        torque_time_constant: first-order lag of the torque (current) loop, s, >= 0 and
            below Kp/Ki. Default 0.
        droop: speed droop, dimensionless, in [0, 1): the reference falls by droop*|w0| at
            ``rated_torque`` (w0 the curve's final pulley speed). Default 0.
        rated_torque: torque at which the speed falls by ``droop``, N*m, > 0; required with
            droop > 0 and refused without. Default None.
    """

    bandwidth: float
    damping_ratio: float
    inertia: Optional[float]
    proportional_gain: Optional[float]
    integral_gain: Optional[float]
    torque_time_constant: float
    droop: float
    rated_torque: Optional[float]

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("follow")
class TorqueFollow(_Table):
    """Master-slave torque sharing (``docs/drives.md``): the drive applies ``ratio`` times
    the motor torque of the drive on pulley ``master`` each step (within its own
    ``max_torque``), in the sense that drives the belt the same way. The master is a PI
    speed-controlled drive or a torque-table drive (not an ideal speed follower, not a
    follower).

    Attributes:
        master: name of the master drive's pulley. Required.
        ratio: follower torque / master torque, dimensionless, > 0. Default 1.
    """

    master: Optional[str]
    ratio: float

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("coupling")
class FluidCoupling(_Table):
    """Constant-fill fluid coupling between a DOL motor and its gearbox
    (``docs/drives.md``): T = rated_torque * (n_p/rated_speed)^2 * phi(s), n_p the faster
    shaft's speed (it pumps), s = (n_in - n_out)/n_p, phi(s) = (s/s_r)(1+b)/(1+b*s/s_r)
    with b = (1 - k*s_r)/(k - 1): phi(s_r) = 1, phi(1) = k. Odd in the slip.

    Attributes:
        rated_torque: torque at the rated slip and input speed, N*m, > 0. Default None:
            the motor's rated torque.
        rated_speed: input speed of the rated point, rad/s, > 0. Default None: the motor's
            rated speed.
        rated_slip: s_r, in (0, 1). Default 0.03.
        stall_torque_ratio: k, torque at stall (output at rest) / rated torque at the same
            input speed, in (1, 1/rated_slip). Default 5.
        slip: slips of a torque table that replaces the hyperbola (the maker's curve),
            dimensionless, strictly increasing in [0, 1], at least two. Default None.
        torque: the table's torques, N*m, passed at input speed ``rated_speed`` (the
            motor's rated speed by default): finite, >= 0, non-decreasing, 0 at a slip of 0,
            > 0 at the last slip. Linear between the points, from (0, 0) to the first, held
            beyond the last; T = (n_p/rated_speed)^2 * torque(s), odd in s. With a table,
            leave ``rated_torque``, ``rated_slip`` and ``stall_torque_ratio`` out.
            Default None.
    """

    rated_torque: Optional[float]
    rated_speed: Optional[float]
    rated_slip: float
    stall_torque_ratio: float
    slip: Optional[Sequence[float]]
    torque: Optional[Sequence[float]]

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("motor")
class Motor(_Table):
    """Induction motor started direct on line (``docs/drives.md``): a torque-speed curve
    at the motor shaft, through a gearbox of ratio ``gear_ratio`` (and optionally a
    :class:`FluidCoupling`) to the pulley.

    Kloss curve (default): T(s) = 2*T_b/(s/s_b + s_b/s), slip s = (n_s - n)/n_s, through
    the rated point (T_r = rated_power/rated_speed) with T_b = k*T_r and
    s_b = s_r*(k + sqrt(k^2 - 1)). Kloss underestimates the locked-rotor torque of real
    (deep-bar, double-cage) motors: give the data sheet's curve as ``speed``/``torque``.

    Attributes:
        rated_power: rated shaft power, W, > 0. Required.
        rated_speed: rated speed at the motor shaft, rad/s, > 0 (1485 rpm = 155.5 rad/s).
            Required.
        synchronous_speed: rad/s, > rated_speed (4-pole 50 Hz: 157.08). Required.
        breakdown_torque_ratio: k = breakdown / rated torque of the Kloss curve, > 1.
            Default 2.5.
        speed: motor speeds of a torque table, rad/s, strictly increasing; replaces the
            Kloss curve (linear between points, held beyond the ends). Default None.
        torque: the table's motor torques, N*m. Default None.
        gear_ratio: motor speed / pulley speed, > 0. Default 1.
        rotation: sense in which the motor turns the pulley, ``"ccw"`` (default) or ``"cw"``.
        rotor_inertia: rotor (and coupling pump side) inertia at the motor shaft, kg*m^2,
            >= 0; counted gear_ratio^2 * rotor_inertia at the pulley when rigid; > 0 with a
            coupling (the motor is then a body of its own). Default 0.
        start: time the motor is switched on, s. Default 0.
        coupling: fluid coupling between motor and gearbox. Default None (rigid).
    """

    rated_power: Optional[float]
    rated_speed: Optional[float]
    synchronous_speed: Optional[float]
    breakdown_torque_ratio: float
    speed: Optional[Sequence[float]]
    torque: Optional[Sequence[float]]
    gear_ratio: float
    rotation: str
    rotor_inertia: float
    start: float
    coupling: Optional[FluidCoupling]

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("drive")
class Drive(_Table):
    """A drive on a pulley, torque-controlled or speed-controlled.

    Torque-controlled (thesis eq. 4.66): T(t, w) = f(t) * g(w) - viscous * w.

    Speed-controlled (``start_curve`` given; ``docs/drives.md``): a motor under speed
    control (a VFD) supplies each step the torque that makes the pulley follow the curve
    (pulley speed = curve speed / radius), if that torque is within +-``max_torque``;
    otherwise it supplies +-``max_torque`` and the pulley moves freely under it (it falls
    behind and catches up at the limit). ``viscous`` then acts as a load torque; the torque
    table must be zero (left at its default) and ``speed``/``speed_factor`` absent. A pulley
    with a speed-controlled drive cannot also have a brake. The recorded drive torque (and
    the drive work) is the motor's torque plus the load torque.

    Attributes:
        time: abscissae of f, s, strictly increasing. Default [0].
        torque: f(t), N*m, counter-clockwise positive; piecewise linear, held beyond the
            ends. Default [0].
        speed: abscissae of g, rad/s. Default: none (g = 1).
        speed_factor: g(w), dimensionless (e.g. a motor curve). Default: none.
        viscous: load torque per unit speed, N*m*s/rad. Default 0.
        inertia: motor and gearbox inertia added to the pulley, kg*m^2. Default 0.
        start_curve: the starting curve of a speed-controlled drive. Default None
            (torque-controlled).
        max_torque: torque limit of a speed-controlled drive's motor (e.g. its breakdown
            torque), N*m, > 0. Default inf (no limit). Only with ``start_curve`` or
            ``follow``.
        controller: a PI speed controller (:class:`SpeedController`) following
            ``start_curve``. Default None: the ideal speed follower.
        follow: master-slave torque sharing (:class:`TorqueFollow`). Default None.
        motor: an induction motor started direct on line (:class:`Motor`), the drive's
            torque. Default None.
        flywheel: flywheel on the drive's high-speed shaft (driven side of a coupling),
            kg*m^2, >= 0; counts gear_ratio^2 * flywheel at the pulley (gear ratio of
            ``motor``, 1 without one). Default 0.
        power_off: time the motor loses power (a power failure or a stop), s, absolute
            simulated time: from then on it supplies no torque (no torque table, no
            speed-controlled hold, no PI controller or follower torque; a DOL motor is
            switched off and its rotor coasts) and the pulley coasts; the load torque
            -viscous*omega stays. Default None (never). ``docs/stops-takeups.md``.
    """

    time: Sequence[float]
    torque: Sequence[float]
    speed: Optional[Sequence[float]]
    speed_factor: Optional[Sequence[float]]
    viscous: float
    inertia: float
    start_curve: Optional[StartCurve]
    max_torque: float
    controller: Optional[SpeedController]
    follow: Optional[TorqueFollow]
    motor: Optional[Motor]
    flywheel: float
    power_off: Optional[float]

    def __post_init__(self) -> None:
        _normalise(self)

    @classmethod
    def constant(cls, torque: float, **kw: Any) -> "Drive":
        """A constant torque, N*m."""
        return cls(time=[0.0], torque=[torque], **kw)

    @classmethod
    def pulse(cls, torque: float, duration: float, start: float = 0.0, **kw: Any) -> "Drive":
        """``torque`` (N*m) from ``start`` for ``duration`` seconds, zero otherwise.

        The switching edges take 1e-9 s, i.e. they fall inside one step.
        """
        eps = 1e-9
        t0, t1 = start, start + duration
        if start > 0:
            times = [0.0, t0, t0 + eps, t1, t1 + eps]
            values = [0.0, 0.0, torque, torque, 0.0]
        else:
            times = [t0, t1, t1 + eps]
            values = [torque, torque, 0.0]
        return cls(time=times, torque=values, **kw)


@dataclass
@_engine_table("brake")
class Brake(_Table):
    """A brake: a friction torque that opposes the pulley's rotation and holds it at rest
    up to its capacity (stick/slip: it never reverses the motion and never chatters at
    rest; ``docs/stops-takeups.md``). Give either the ``time``/``capacity`` table or a
    ``torque`` applied at ``applied`` (built up over ``rise``); with ``deceleration`` too,
    the brake supplies only the torque (up to ``torque``) that slows the belt at the pulley
    surface at that rate.

    Attributes:
        time: abscissae of the capacity table, s. Default [0].
        capacity: braking/holding torque capacity against time, N*m, >= 0. Default [0].
            Leave the table at its default with ``torque``.
        torque: braking torque from ``applied`` on, N*m, > 0. Default None (the table).
        deceleration: deceleration target of the belt at the pulley surface, m/s^2, > 0;
            only with ``torque`` (the brake's capacity). Default None (a torque brake).
        applied: time the brake is applied, s (absolute simulated time); released before.
            Only with ``torque``. Default 0.
        rise: time the torque takes to build up from 0 (linear), s, >= 0. Only with
            ``torque``. Default 0.
    """

    time: Sequence[float]
    capacity: Sequence[float]
    torque: Optional[float]
    deceleration: Optional[float]
    applied: float
    rise: float

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("holdback")
class Holdback(_Table):
    """A holdback (backstop): a one-way clutch on a pulley that lets it turn forwards
    freely and stops it turning backwards, e.g. on an inclined conveyor after a stop
    (``docs/stops-takeups.md``). Its torque is recorded with the brake's
    (``Result.brake_torque``).

    Attributes:
        forward: ``"ccw"`` or ``"cw"``, the sense the pulley turns when the conveyor runs
            forward (the head drive of a conveyor carrying towards +x on its top strand
            turns ``"cw"``). Required.
        capacity: largest torque it takes against reverse rotation, N*m, > 0. Default inf.
    """

    forward: Optional[str]
    capacity: float

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("nonlinear_contact")
class NonlinearContact(_Table):
    """Kubas's (2014) damped nonlinear belt-pulley contact (eq. 4-11), a pulley's
    ``nonlinear_contact``, in place of the linear penalty law:
    N = c1*p^2 + c2*p + delta(p)*b*pdot for penetration p > 0, N = 0 otherwise, where
    delta(p) = d^2 (3 - 2d), d = p/p_max clamped to [0, 1], brings the damping in smoothly,
    and N is never negative (a contact never pulls). Works with both belt formulations;
    it acts at the nodes (node belt) or at the bodies' mass centres (rigid-body belt).
    Defaults: Kubas's case K values (docs/kubas.md).

    Attributes:
        quadratic_stiffness: c1, N/m^2, >= 0. Default 3.0256e9.
        linear_stiffness: c2, N/m, >= 0 (c1 + c2 > 0). Default 6.5e5.
        damping: b, N*s/m, >= 0, fully in at p >= p_max. Default 300.
        damping_depth: p_max, m, > 0. Default 1e-3.
    """

    quadratic_stiffness: float
    linear_stiffness: float
    damping: float
    damping_depth: float

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("pulley")
class Pulley(_Table):
    """A pulley the belt wraps (thesis §4.2).

    Attributes:
        center: centre (x, y), m.
        radius: radius to the belt centre line, m. Default 0.5.
        mass: pulley mass, kg. Default 100.
        inertia: polar inertia, kg*m^2. Default None = mass * radius^2 (thesis code).
        wrap: ``"ccw"`` if the belt runs counter-clockwise round it in node order, else
            ``"cw"``. Default "ccw".
        friction: belt friction. Default None (frictionless). Needs contact_stiffness > 0.
        contact_stiffness: penalty stiffness per metre of penetration, N/m, >= 0. Default
            1e9. 0 means no contact with this pulley: the belt passes through it (its
            drive, brake and takeup then act on the pulley alone, and friction on it is
            refused, having no normal force to act with); with 0 on every pulley no
            ``pulley_contact`` stage is compiled.
        contact_damping: normal contact damping, N*s/m, >= 0, on the approach speed only.
            Default None: from ``contact_damping_ratio``. Give one or the other, not both.
        contact_damping_ratio: normal contact damping as a fraction zeta of critical,
            dimensionless, >= 0: c = 2 zeta sqrt(k m), k the contact stiffness and m the
            belt's node mass (mass_per_length * element length, without material). Default
            None: 0.2 (``DEFAULT_CONTACT_DAMPING_RATIO``) unless ``contact_damping`` is
            given. Undamped contact (0) with friction lets the belt bounce off the pulley
            and gets a :class:`beltrs.UndampedContactWarning` (docs/belt-drives.md).
        bearing_damping: linear viscous drag of the bearings, N*m*s/rad, >= 0: torque
            -b*omega on the pulley (a free pulley spins down as omega0*exp(-b*t/I)), e.g.
            for coasting stops. Default 0 (no ``bearing_drag`` stage).
        takeup: gravity takeup, if the pulley translates. Default None.
        drive: drive torque. Default None.
        brake: brake. Default None.
        holdback: holdback against reverse rotation (:class:`Holdback`). Default None.
        name: label for messages and results; unique unless empty. Default "".
        nonlinear_contact: Kubas's nonlinear contact law (:class:`NonlinearContact`) in
            place of the linear one. Default None (linear). With it, leave
            ``contact_stiffness`` at its default and give no ``contact_damping`` or
            ``contact_damping_ratio`` (the law has its own; refused otherwise).
    """

    center: tuple[float, float]
    radius: float
    mass: float
    inertia: Optional[float]
    wrap: str
    friction: Optional[Friction]
    contact_stiffness: float
    contact_damping: Optional[float]
    contact_damping_ratio: Optional[float]
    bearing_damping: float
    takeup: Optional[Takeup]
    drive: Optional[Drive]
    brake: Optional[Brake]
    holdback: Optional[Holdback]
    name: str
    nonlinear_contact: Optional[NonlinearContact]

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("idler")
class Idler(_Table):
    """An idler roll touching the belt centre line (thesis eq. 4.95-4.117).

    Attributes:
        center: centre (x, y), m.
        radius: radius, m. Default 0.0635.
        inertia: rotating inertia, kg*m^2. Default 0.01.
        contact_stiffness: N/m. Default 1e8.
        contact_damping: normal contact damping, N*s/m, >= 0. Default None: from
            ``contact_damping_ratio``. Give one or the other, not both.
        contact_damping_ratio: normal contact damping as a fraction of critical,
            c = 2 zeta sqrt(k m) with m the belt's node mass. Default None: 0.2 unless
            ``contact_damping`` is given.
        friction: belt friction. Default None (the roll never turns).
        resistance: running resistance, DIN 22101's artificial friction coefficient f,
            dimensionless, >= 0. The belt meets a tangential force at the contact point
            opposing its motion over the ground, up to f * (N + rotating_mass * g), N the
            contact normal force; below that limit it holds the belt (stick). Summed over a
            strand on idlers this is DIN's main resistance F_H. 0 on every idler compiles no
            ``running_resistance`` stage. Default 0. See docs/loads.md.
        rotating_mass: rotating mass of the roll, kg, >= 0; its weight adds to the bearing
            load in the resistance limit (the roll's inertia is ``inertia``). Default 0.
    """

    center: tuple[float, float]
    radius: float
    inertia: float
    contact_stiffness: float
    contact_damping: Optional[float]
    contact_damping_ratio: Optional[float]
    friction: Optional[Friction]
    resistance: float
    rotating_mass: float

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("load")
class Load(_Table):
    """Bulk material on the belt between a loading and a discharge point (docs/loads.md).

    The material moves with the belt: each step the belt points nearest ``start`` and
    ``end`` are tracked, and each node carries the material on its tributary length inside
    the zone between them (node masses change during a run: ``Simulation.node_masses()``).
    Material enters at rest along the belt (the belt pays its momentum, DIN 22101's
    acceleration resistance Q*v) and leaves with the belt's velocity.

    Attributes:
        mass_per_length: material per metre of unstretched belt, kg/m, finite, >= 0 (a
            volumetric feeder: the same at any belt speed). Default 0.
        start: loading point (x, y), m, within 1 m of the initial belt path (e.g. under the
            tail chute on the carry strand). Default (0, 0).
        end: discharge point (x, y), m, within 1 m of the belt path (e.g. the head pulley's
            top tangent point). The loaded zone is the run of belt between the two points
            that does not wrap a pulley (by more than 10 degrees); if both runs or neither
            do, the scene is refused as ambiguous.
    """

    mass_per_length: float
    start: tuple[float, float]
    end: tuple[float, float]

    def __post_init__(self) -> None:
        _normalise(self)


#: How an end of an open belt is held (:class:`BeltEnd`).
END_HOLDS = ("anchor", "force", "mass")


@dataclass
@_engine_table("belt_end")
class BeltEnd(_Table):
    """One end of an open belt (``Belt.start``, ``Belt.end``; docs/open-belts.md).

    A belt with both ends is open: it runs from ``start.point`` round the pulleys in the
    order listed to ``end.point``. Without them it is a closed loop.

    Attributes:
        point: where the end is placed, (x, y), m: the belt runs straight from here to its
            tangent point on the first pulley (start), or from the last pulley to here
            (end). Must lie outside every pulley. Required.
        hold: ``"anchor"`` (default): fixed at ``point``; ``"force"``: pulled by a
            constant ``force`` along the initial end span, away from the pulley;
            ``"mass"``: a hanging ``mass`` (a hoist's load) under the scene's gravity.
        force: with hold ``"force"``: the pull at t = 0, N, > 0. Default None.
        force_rate: with hold ``"force"``: its rate of change, N/s, finite: the pull is
            force + force_rate * t (absolute simulated time), never below 0 (a slowly loaded
            capstan, a winch taking up load). Default None: a constant pull.
        mass: with hold ``"mass"``: the hanging mass, kg, > 0. Default None.
    """

    point: Optional[tuple[float, float]]
    hold: str
    force: Optional[float]
    force_rate: Optional[float]
    mass: Optional[float]

    def __post_init__(self) -> None:
        _normalise(self)

    @classmethod
    def anchor(cls, point: Sequence[float]) -> "BeltEnd":
        """An end fixed at ``point`` (m)."""
        return cls(point=point, hold="anchor")

    @classmethod
    def pulled(cls, point: Sequence[float], force: float, force_rate: Optional[float] = None) -> "BeltEnd":
        """An end at ``point`` (m) pulled by ``force`` (N) away from its pulley, rising at
        ``force_rate`` (N/s) if given."""
        return cls(point=point, hold="force", force=force, force_rate=force_rate)

    @classmethod
    def hanging(cls, point: Sequence[float], mass: float) -> "BeltEnd":
        """An end at ``point`` (m) carrying a hanging ``mass`` (kg)."""
        return cls(point=point, hold="mass", mass=mass)


@dataclass
@_engine_table("belt")
class Belt(_Table):
    """Belt properties (thesis §4.1).

    Attributes:
        axial_stiffness: EA, N. Default 7.62e6.
        mass_per_length: mass per unstretched metre, kg/m. Default 100.
        bending_stiffness: EI, N*m^2; 0 compiles no bending stage. Default 0.
        damping_ratio: axial damping as a fraction of one element's critical damping
            (thesis eq. 4.3); 0 compiles undamped axial springs. Default 0.
        damping_time: Voigt damping of the belt material as a retardation time
            tau = eta/E, s, >= 0 (Guo & Wang 2020: sigma = E*eps + eta*d(eps)/dt): each
            element's damping is tau times its stiffness, b = tau*EA/l (and tau*EI/l for
            the rigid bodies' torsional spring-dampers). Not with ``damping_ratio`` > 0.
            Default None: damping from ``damping_ratio``.
        loss_factor: loss factor tan delta of the belt material, dimensionless, in [0, 1]:
            each element becomes a Zener (standard linear solid) element, its Kelvin-Voigt
            spring with a Maxwell arm in parallel whose loss factor peaks at this value at
            ``loss_frequency`` (docs/wrap-contact.md, "A viscoelastic belt").
            ``axial_stiffness`` stays the relaxed (static) EA; the instantaneous stiffness
            is (1 + r) EA, r = 2 eta^2 + 2 eta sqrt(1 + eta^2), and sets the explicit step.
            Node belt under central differences only (a SceneError otherwise). Default 0:
            no arm.
        loss_frequency: frequency at which the loss factor peaks, Hz, > 0. Default 5
            (a long conveyor's longitudinal strand modes, 1-20 Hz; tan delta is above half
            its peak from about f/3.7 to 3.7 f).
        length: unstretched length, m. Default None = length of the initial path.
        elements: number of elements (nodes - 1 for an open belt). Default None = fewest
            with each element at most ``max_element_angle`` of arc on the smallest pulley
            and, while ``max_element_angle`` is at its default, on each pulley with friction
            mu_s over a wrap theta at most sqrt(12 ln(1.005)/(mu_s theta (1 + mu_s^2))) rad
            of arc: the node-discrete Euler-Eytelwein ratio within 0.5 %
            (docs/belt-drives.md).
        max_element_angle: rad. Default pi/6 (30 degrees, thesis §6.1); at most pi/3. Used
            only when ``elements`` is None. While at its default, the ``"rigid_body"``
            formulation's bodies span at most half of it (15 degrees: their polygon round
            a pulley holds a^2/12 more belt than the arc; docs/open-belts.md).
        tension_only: if True a slack element carries no compression. Default False.
        max_placement_strain: largest strain, dimensionless, > 0, at which the belt may be
            placed on its initial path, |path length / length - 1|; a belt stretched (or
            compressed) more is refused as too short (too long) for its path, usually a
            unit slip. Raise it for a pre-strained elastic drive belt (the belt-drive
            literature's benchmarks are pre-strained 5.26 %). Default 0.1.
        formulation: ``"node_kelvin_voigt"`` (Hustrulid's nodes; default) or
            ``"rigid_body"`` (Kubas's and Guo & Wang's chain of rigid bodies, x, y and phi
            each, joined by translational and torsional Kelvin-Voigt spring-dampers). The
            rigid bodies take the node belt's rules and parameters: ``elements`` bodies
            (or as many as ``max_element_angle`` asks) of length l = length/elements,
            mass ``mass_per_length``*l, inertia m*l^2/12; spring-dampers
            c_x = EA/l, c_phi = EI/l, damped at ``damping_ratio`` of critical
            (b_x = 2 zeta sqrt(c_x m), b_phi = 2 zeta sqrt(c_phi I)); mass centres where
            the node belt has its nodes. An open belt (``start``/``end``) of N bodies
            has N + 2 belt points (its two end points, each joined to its body's outer end
            by half a joint: stiffness and damping 2 c_x, 2 b_x) and N + 1 joints
            (``Result.tension`` columns); docs/open-belts.md. Not with ``tension_only``
            or loads (refused).
        pulley_contact: how the belt meets the pulleys: ``"nodes"`` (Hustrulid's nodal
            penalty contact, thesis eq. 4.70-4.75; the belt round a pulley is a chord
            polygon, with the chordal ripple of a chain on a sprocket on a held drum) or
            ``"wrap"`` (elements on a pulley measured along their path round it, tangents
            and arc: the strand leaves on the tangent, raw tension peaks without the ripple;
            docs/wrap-contact.md). With ``formulation = "rigid_body"``, ``"wrap"`` gives
            the bodies wrap joints: the joint where a strand meets a drum measured along
            the string's path, so the strand is drawn at R*omega instead of the bodies'
            polygon's speed (docs/kubas.md, "Wrap joints"). Default "nodes" (the conveyor
            builders, :class:`beltrs.conveyor.Conveyor` and
            :func:`beltrs.scenes.guo_wang_conveyor`, set "wrap" for both formulations); an
            open belt takes "nodes" only.
        idler_contact: how the belt meets the idler rolls: ``"segment"`` (Hustrulid's
            centre-line penalty contact of the straight elements, thesis eq. 4.95-4.102; a
            straight element over a roll lifts its nodes off the belt's path when the roll is
            under its middle: the rolls' chordal action at the node-passing frequency) or
            ``"wrap"`` (an element over a roll measured along its path over it, tangents and
            arc: the nodes on the belt's path at every phase; docs/wrap-contact.md, "The
            rolls' chordal action"). Default "segment"; ``"wrap"`` needs the node belt and a
            closed loop. With ``initial.sag`` the spans are placed bent over each roll.
        start: the first end of an open belt (:class:`BeltEnd`); give ``start`` and
            ``end`` together. Default None: a closed loop. An open belt takes no design
            start (``Scene.initial``).
        end: the last end of an open belt. Default None. An open belt of n elements has
            n + 1 nodes; ``Result.tension`` then has n columns (``"rigid_body"``: n bodies,
            n + 2 belt points and n + 1 joints).
    """

    axial_stiffness: float
    mass_per_length: float
    bending_stiffness: float
    damping_ratio: float
    length: Optional[float]
    elements: Optional[int]
    max_element_angle: float
    tension_only: bool
    formulation: str
    max_placement_strain: float
    pulley_contact: str
    idler_contact: str
    damping_time: Optional[float]
    loss_factor: float
    loss_frequency: float
    start: Optional[BeltEnd]
    end: Optional[BeltEnd]

    def __post_init__(self) -> None:
        _normalise(self)

    @classmethod
    def from_material(
        cls, youngs_modulus: float, width: float, thickness: float, mass_per_length: float, **kw: Any
    ) -> "Belt":
        """Belt from E (Pa), width (m) and thickness (m): EA = E*w*t, EI = E*w*t^3/12."""
        return cls(
            axial_stiffness=youngs_modulus * width * thickness,
            bending_stiffness=youngs_modulus * width * thickness**3 / 12.0,
            mass_per_length=mass_per_length,
            **kw,
        )


@dataclass
@_engine_table("solver")
class Solver(_Table):
    """Time stepping.

    Attributes:
        time_step: fixed step, s. Default None = ``time_step_fraction`` x stability limit;
            a step above the limit is refused.
        time_step_fraction: in (0, 1]; used only when ``time_step`` is None. Default 0.5
            (the thesis ran at half its limit).
        integrator: ``"central_difference"`` (default: explicit, at the automatic stable
            step) or ``"rkf45"`` (adaptive Runge-Kutta-Fehlberg 4(5), Kubas's integrator;
            ``Result.steps_accepted`` / ``steps_rejected`` count its steps). Under
            ``"rkf45"`` the effects solved for a fixed step are refused with a SceneError:
            stick-force friction (use the creep-rate friction model), speed-controlled
            drives, brakes, idler running resistance and loads; ``time_step`` too.
        relative_tolerance: RKF45's relative tolerance per step, dimensionless, > 0.
            Default 1e-8: positions are of the size of the scene while the physics is in
            deformations 1e-3 to 1e-5 of it (at 1e-6 a conservative drive's energy drifted
            by 1.8e-4 in 2 ms, at 1e-8 by 8e-7).
        absolute_tolerance: RKF45's absolute tolerance per step, in each component's SI
            unit (m, rad, m/s, rad/s), >= 0. Default 1e-11.
    """

    time_step: Optional[float]
    time_step_fraction: float
    integrator: str
    relative_tolerance: float
    absolute_tolerance: float

    def __post_init__(self) -> None:
        _normalise(self)


#: Optional large arrays a run can record (``Recording.channels``), each the name of a
#: keyword of :meth:`beltrs.Simulation.run`; every other array of :class:`beltrs.Result` is
#: always recorded. All but ``"contact_forces"`` are recorded by default
#: (``ENGINE_DEFAULTS["recording"]["channels"]``).
CHANNELS = ("tension", "node_position", "node_velocity", "contact_forces")


@dataclass
@_engine_table("recording")
class Recording(_Table):
    """How a scene is run and what is recorded (the ``[recording]`` table of a scene file,
    used by ``beltrs run``; :meth:`beltrs.Simulation.run` takes the same settings as
    arguments, see :meth:`run_kwargs`).

    Attributes:
        duration: simulated time of the run, s, >= 0. Default 1.
        interval: sample about every this many seconds (rounded to whole steps), s, > 0.
            Default None: every ``every`` steps, or, if ``every`` is None too, the default
            of :meth:`beltrs.Simulation.run` (:meth:`~beltrs.Simulation.default_record_interval`:
            from the belt's wave speed and the shortest strand, at most 0.01 s).
        every: sample every this many steps, >= 1. Give ``interval`` or ``every``, not
            both. Default None.
        channels: optional large arrays to record, from ``"tension"``,
            ``"node_position"``, ``"node_velocity"`` and ``"contact_forces"`` (the normal
            and friction force of every belt point on every pulley with its angle,
            ``Result.contact_normal``/``contact_friction``/``contact_angle``, ``[n, P, E]``
            each). Default: the first three (contact forces are opt-in).
        stabilise: relax to static equilibrium (:meth:`beltrs.Simulation.stabilise`)
            before the run. Default True.
        stabilise_friction: keep belt friction on while relaxing; only with ``stabilise``
            (alone it would have no effect, and is refused). Default False.
    """

    duration: float
    interval: Optional[float]
    every: Optional[int]
    channels: tuple[str, ...]
    stabilise: bool
    stabilise_friction: bool

    def __post_init__(self) -> None:
        _normalise(self)

    def run_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of :meth:`beltrs.Simulation.run` (all but ``duration``)."""
        kw: dict[str, Any] = {name: name in self.channels for name in CHANNELS}
        if self.every is not None:
            kw["record_every"] = self.every
        elif self.interval is not None:
            kw["record_interval"] = self.interval
        return kw


@dataclass
@_engine_table("initial")
class Initial(_Table):
    """The design state a run starts from (the ``[initial]`` table; ``docs/design-start.md``):
    the belt placed already stretched to its design tensions (``beltrs.statics``), along a
    given path if need be, at rest or moving, with no static relaxation. Builders make it
    for you: :meth:`beltrs.conveyor.Conveyor.scene` (``start=``),
    :func:`beltrs.design_start.initial`.

    The belt's unstretched length then follows from the tensions (∫ ds / (1 + T/EA) over the
    path; ``belt.length`` must be left None), node i sits where the stretched elements
    before it end (deeper on a drum by its contact penetration), every node moves at
    ``speed`` along the path, each pulley the path runs round and each idler with friction
    turns with the belt; takeups start where the scene puts them. ``recording.stabilise``
    must be False (the relaxation would undo the design state).

    Attributes:
        tension: design tension, N, finite, >= 0, at each ``distance`` (piecewise linear,
            periodic round the loop); one value: the same everywhere. Required.
        distance: m along the initial path from node 0, in node order, strictly
            increasing, from >= 0 to below the path length. Default () (only with one
            tension).
        speed: belt speed along the path in node order, m/s (negative: against node
            order). Default 0 (at rest).
        path: corners (x, y, radius), m, in node order, closing on the first: straight
            spans joined by arcs of each corner's radius (a drum's wrap, a vertical curve);
            a turn needs a radius > 0 and less than 179 degrees (a 180-degree wrap is two
            corners); node 0 sits where corner 0's arc begins; the path may not pass inside
            a pulley or idler. Default (): the pulleys' tangent path.
        sag: place each straight span that rests on idler rolls in its static sag under
            the weight of belt and material at the design tension (the discrete form of
            q*x*(a - x)/(2*T) between the rolls, each roll pressed by the span it carries;
            ``docs/design-start.md``). False: straight from roll to roll (the spans then
            sink into their sag at the start of the run). Default False (the conveyor
            builders' design starts set True; ``docs/design-start.md``).
    """

    tension: tuple[float, ...]
    distance: tuple[float, ...]
    speed: float
    path: tuple[tuple[float, float, float], ...]
    sag: bool

    def __post_init__(self) -> None:
        _normalise(self)


@dataclass
@_engine_table("scene")
class Scene(_Table):
    """A whole scene. Pulleys are listed in the order the belt meets them.

    Attributes:
        belt: belt properties.
        pulleys: pulleys in belt order (the loop closes from the last to the first).
        idlers: idlers, any order.
        loads: bulk material loads (:class:`Load`), any order. Default none.
        gravity: m/s^2, acting in -y; 0 compiles no gravity stage. Default 9.81.
        solver: time stepping.
        recording: how ``beltrs run`` runs the scene and what it records.
        initial: the design state to start from (:class:`Initial`). Default None: the belt
            placed unstretched on the pulleys' path at rest, relaxed before a run.
    """

    belt: Belt
    pulleys: list[Pulley]
    idlers: list[Idler]
    loads: list[Load]
    gravity: float
    solver: Solver
    recording: Recording
    initial: Optional[Initial]

    def __post_init__(self) -> None:
        _normalise(self)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> "Scene":
        """Read the plain-data form (``to_dict()``, or a parsed scene file) strictly.

        Absent keys take their defaults; ``None`` is accepted where the default is None.

        Raises:
            beltrs.SceneError: an unknown key (naming its full path, with a "did you
                mean" suggestion) or a value of the wrong type (naming the field, the
                value and the expected type).
        """
        check_scene(data)
        return _from_dict(cls, data)

    def to_toml(self) -> str:
        """This scene as the text of a TOML scene file (``docs/scene-format.md``)."""
        from .scene_file import dumps_scene

        return dumps_scene(self)

    @classmethod
    def from_toml(cls, text: str) -> "Scene":
        """Read a scene from the text of a TOML scene file (see :func:`beltrs.load_scene`)."""
        from .scene_file import loads_scene

        return loads_scene(text)

    def save(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Write this scene to a TOML file; :func:`beltrs.load_scene` reads back an equal
        scene (floats are written with ``repr``, which round-trips exactly). The file is
        written to a temporary name and renamed, so a crash never leaves half a file.

        Raises:
            beltrs.SceneError: a field holds a value of the wrong type.
        """
        from .scene_file import save_scene

        save_scene(self, path)

    def pulley_index(self, name: str) -> int:
        """Index of the pulley called ``name``."""
        for i, p in enumerate(self.pulleys):
            if p.name == name:
                return i
        raise KeyError(f"no pulley named {name!r} (names: {[p.name for p in self.pulleys]})")


# --- reading and normalisation ------------------------------------------------------
_HINTS: dict[type, dict[str, Any]] = {}


def _hints(cls: type) -> dict[str, Any]:
    """Resolved field types of a scene dataclass, in field order."""
    h = _HINTS.get(cls)
    if h is None:
        resolved = typing.get_type_hints(cls)
        h = {f.name: resolved[f.name] for f in fields(cls)}
        _HINTS[cls] = h
    return h


def _plain(value: Any, depth: int) -> Any:
    if depth > _MAX_DEPTH:
        return value
    if is_dataclass(value) and not isinstance(value, type):
        return {f.name: _plain(getattr(value, f.name), depth + 1) for f in fields(value)}
    if isinstance(value, (list, tuple)):
        return [_plain(v, depth + 1) for v in value]
    return value


def _is_sequence(value: Any) -> bool:
    return not isinstance(value, (str, bytes, Mapping)) and hasattr(value, "__iter__") and hasattr(value, "__len__")


def _coerce(tp: Any, value: Any) -> Any:
    """``value`` in the canonical form of annotation ``tp`` if it fits, else as given (the
    engine names it when the scene is compiled or saved). Never raises."""
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if origin is Union:
        if value is None:
            return None
        return _coerce(next(a for a in args if a is not type(None)), value)
    if tp is float:
        if type(value) is not float and isinstance(value, numbers.Real) and not isinstance(value, bool):
            try:
                return float(value)
            except (OverflowError, ValueError, TypeError):
                return value
        return value
    if tp is int:
        if type(value) is not int and isinstance(value, numbers.Integral) and not isinstance(value, bool):
            return int(value)
        return value
    if origin in (tuple, collections.abc.Sequence) and args:
        if not _is_sequence(value):
            return value
        try:
            items = list(value)
        except Exception:  # a broken sequence: the engine names it
            return value
        item = args[0]
        return tuple(_coerce(item, v) for v in items)
    if origin is list and args and is_dataclass(args[0]):
        if not _is_sequence(value):
            return value
        items = [_coerce(args[0], v) for v in value]
        if isinstance(value, list) and all(a is b for a, b in zip(items, value)):
            return value  # already a list of scene objects: keep the caller's list
        return items
    if is_dataclass(tp):
        if isinstance(value, Mapping) and all(isinstance(k, str) for k in value) and set(value) <= set(_hints(tp)):
            return tp(**value)
        return value
    return value


def _normalise(obj: Any) -> None:
    """Bring each field of a freshly built scene object to its canonical type (see the
    module docstring); a value of the wrong type is left alone for the engine to report."""
    for name, tp in _hints(type(obj)).items():
        value = getattr(obj, name)
        new = _coerce(tp, value)
        if new is not value:
            object.__setattr__(obj, name, new)


def _from_dict(cls: type, data: Mapping[str, Any]) -> Any:
    """``cls`` built from a dict form already checked by the engine."""
    return cls(**{k: _coerce(tp, data[k]) for k, tp in _hints(cls).items() if k in data})


def _read_dataclass(cls: type, data: Any, path: str) -> Any:
    """``cls`` (a scene dataclass) read strictly from its dict form, messages naming paths
    from ``path``: the engine checks keys and types (its table ``cls._engine_table``)."""
    if isinstance(data, cls):
        return data
    check_scene_table(cls._engine_table, data, path)  # type: ignore[attr-defined]
    return _from_dict(cls, data)


def unknown_key_message(path: str, key: Any, known: Sequence[str]) -> str:
    """``path = 'key': unknown key, did you mean 'x'? (known keys here: ...)``, with the
    engine's suggestion (for tables read in Python, e.g. ``beltrs.conveyor``'s)."""
    return f"{path} = {str(key)!r}: {unknown_key_rule(str(key), [str(k) for k in known])}"


def field_default(cls: type, name: str) -> Any:
    """The default value of field ``name`` of a scene dataclass (the engine's default)."""
    for f in fields(cls):
        if f.name == name:
            if f.default is not MISSING:
                return f.default
            if f.default_factory is not MISSING:
                return f.default_factory()
            break
    raise KeyError(name)

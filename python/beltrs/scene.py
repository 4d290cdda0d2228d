"""Scene description: plain dataclasses, SI units throughout.

A :class:`Scene` is data only. :class:`beltrs.Simulation` validates and compiles it in the
Rust engine; every error names the field (e.g. ``pulleys[1].radius``), the value and the
rule broken. ``Scene.to_dict()`` gives the exact form the engine reads; unknown keys in
that form are errors, never ignored. ``Scene.from_dict()`` reads that form back strictly
(unknown keys, with a "did you mean" suggestion, and wrong types raise
:class:`beltrs.SceneError`), and ``Scene.save()`` / :func:`beltrs.load_scene` write and
read the same structure as a TOML scene file (``docs/scene-format.md``).

Constructing any of these classes normalises what it is given, so that a scene built in
Python and the same scene read from a file compare equal: integers and NumPy scalars in
float fields become ``float``, and sequences (lists, NumPy arrays) in sequence fields
become tuples of ``float``. Values of the wrong type are left as given and reported when
the scene is compiled or saved.
"""

from __future__ import annotations

import collections.abc
import difflib
import math
import numbers
import os
import typing
from dataclasses import MISSING, asdict, dataclass, field, fields, is_dataclass
from typing import Any, Mapping, Optional, Sequence, Union

from ._beltrs import SceneError

__all__ = [
    "Belt",
    "Brake",
    "Drive",
    "Friction",
    "Idler",
    "Load",
    "Pulley",
    "Recording",
    "Scene",
    "Solver",
    "StartCurve",
    "Takeup",
]


@dataclass
class Friction:
    """Belt friction on a pulley or idler (stick-force model, thesis eq. 4.76-4.94).

    Attributes:
        static: static coefficient mu_s, dimensionless, >= kinetic. Default 0 (no friction
            stage is compiled when every body has mu_s = 0).
        kinetic: kinetic coefficient mu_k, dimensionless. Default: equal to ``static``.
        model: ``"stick_force"`` (default) or ``"none"`` (no coefficients allowed). The
            creep model is not implemented yet: ``"creep"`` is refused with a message
            saying so.
    """

    static: float = 0.0
    kinetic: Optional[float] = None
    model: str = "stick_force"

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        # kinetic None means "equal to static"; the engine applies that default itself.
        return {"model": self.model, "static": self.static, "kinetic": self.kinetic}


@dataclass
class Takeup:
    """Gravity takeup: the pulley translates on a line (thesis eq. 4.63).

    Attributes:
        counterweight: counterweight mass, kg. Default 0.
        direction: unit vector of the pull, dimensionless. Default (0, -1) (hanging).
        travel_min: lowest travel along ``direction`` from the start, m (hard stop, <= 0).
            Default -inf.
        travel_max: highest travel, m (>= 0). Default +inf.
    """

    counterweight: float = 0.0
    direction: tuple[float, float] = (0.0, -1.0)
    travel_min: float = -math.inf
    travel_max: float = math.inf

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "counterweight": self.counterweight,
            "direction": list(self.direction),
            "travel_min": self.travel_min,
            "travel_max": self.travel_max,
        }


#: Shapes of a starting curve (:class:`StartCurve`).
START_SHAPES = ("harrison", "nordell", "cubic", "linear")


@dataclass
class StartCurve:
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

    shape: str = "harrison"
    speed: Optional[float] = None
    ramp: Optional[float] = None
    start: float = 0.0
    prestart: float = 0.0
    creep_speed: Optional[float] = None
    creep_ramp: Optional[float] = None

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "shape": self.shape,
            "speed": self.speed,
            "ramp": self.ramp,
            "start": self.start,
            "prestart": self.prestart,
            "creep_speed": self.creep_speed,
            "creep_ramp": self.creep_ramp,
        }

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
class Drive:
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
            torque), N*m, > 0. Default inf (no limit). Only with ``start_curve``.
    """

    time: Sequence[float] = (0.0,)
    torque: Sequence[float] = (0.0,)
    speed: Optional[Sequence[float]] = None
    speed_factor: Optional[Sequence[float]] = None
    viscous: float = 0.0
    inertia: float = 0.0
    start_curve: Optional[StartCurve] = None
    max_torque: float = math.inf

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

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {
            "time": [float(t) for t in self.time],
            "torque": [float(t) for t in self.torque],
            "viscous": self.viscous,
            "inertia": self.inertia,
            "start_curve": None if self.start_curve is None else self.start_curve.to_dict(),
            "max_torque": self.max_torque,
        }
        if self.speed is not None or self.speed_factor is not None:
            d["speed"] = None if self.speed is None else [float(w) for w in self.speed]
            d["speed_factor"] = None if self.speed_factor is None else [float(g) for g in self.speed_factor]
        return d


@dataclass
class Brake:
    """Coulomb brake that holds the pulley at rest up to its capacity.

    Attributes:
        time: abscissae, s. Default [0].
        capacity: braking/holding torque capacity, N*m, >= 0. Default [0].
    """

    time: Sequence[float] = (0.0,)
    capacity: Sequence[float] = (0.0,)

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        return {"time": [float(t) for t in self.time], "capacity": [float(c) for c in self.capacity]}


@dataclass
class Pulley:
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
        takeup: gravity takeup, if the pulley translates. Default None.
        drive: drive torque. Default None.
        brake: brake. Default None.
        name: label for messages and results; unique unless empty. Default "".
    """

    center: tuple[float, float] = (0.0, 0.0)
    radius: float = 0.5
    mass: float = 100.0
    inertia: Optional[float] = None
    wrap: str = "ccw"
    friction: Optional[Friction] = None
    contact_stiffness: float = 1e9
    contact_damping: Optional[float] = None
    contact_damping_ratio: Optional[float] = None
    takeup: Optional[Takeup] = None
    drive: Optional[Drive] = None
    brake: Optional[Brake] = None
    name: str = ""

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "center": [float(c) for c in self.center],
            "radius": self.radius,
            "mass": self.mass,
            "inertia": self.inertia,
            "wrap": self.wrap,
            "friction": None if self.friction is None else self.friction.to_dict(),
            "contact_stiffness": self.contact_stiffness,
            "contact_damping": self.contact_damping,
            "contact_damping_ratio": self.contact_damping_ratio,
            "takeup": None if self.takeup is None else self.takeup.to_dict(),
            "drive": None if self.drive is None else self.drive.to_dict(),
            "brake": None if self.brake is None else self.brake.to_dict(),
        }


@dataclass
class Idler:
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

    center: tuple[float, float] = (0.0, 0.0)
    radius: float = 0.0635
    inertia: float = 0.01
    contact_stiffness: float = 1e8
    contact_damping: Optional[float] = None
    contact_damping_ratio: Optional[float] = None
    friction: Optional[Friction] = None
    resistance: float = 0.0
    rotating_mass: float = 0.0

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "center": [float(c) for c in self.center],
            "radius": self.radius,
            "inertia": self.inertia,
            "contact_stiffness": self.contact_stiffness,
            "contact_damping": self.contact_damping,
            "contact_damping_ratio": self.contact_damping_ratio,
            "friction": None if self.friction is None else self.friction.to_dict(),
            "resistance": self.resistance,
            "rotating_mass": self.rotating_mass,
        }


@dataclass
class Load:
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

    mass_per_length: float = 0.0
    start: tuple[float, float] = (0.0, 0.0)
    end: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "mass_per_length": self.mass_per_length,
            "start": [float(c) for c in self.start],
            "end": [float(c) for c in self.end],
        }


@dataclass
class Belt:
    """Belt properties (thesis §4.1).

    Attributes:
        axial_stiffness: EA, N. Default 7.62e6.
        mass_per_length: mass per unstretched metre, kg/m. Default 100.
        bending_stiffness: EI, N*m^2; 0 compiles no bending stage. Default 0.
        damping_ratio: axial damping as a fraction of one element's critical damping
            (thesis eq. 4.3); 0 compiles undamped axial springs. Default 0.
        length: unstretched length, m. Default None = length of the initial path.
        elements: number of elements. Default None = fewest with each element at most
            ``max_element_angle`` of arc on the smallest pulley.
        max_element_angle: rad. Default pi/6 (30 degrees, thesis §6.1); at most pi/3. Used
            only when ``elements`` is None.
        tension_only: if True a slack element carries no compression. Default False.
        max_placement_strain: largest strain, dimensionless, > 0, at which the belt may be
            placed on its initial path, |path length / length - 1|; a belt stretched (or
            compressed) more is refused as too short (too long) for its path, usually a
            unit slip. Raise it for a pre-strained elastic drive belt (the belt-drive
            literature's benchmarks are pre-strained 5.26 %). Default 0.1.
        formulation: ``"node_kelvin_voigt"`` (Hustrulid). Default.
    """

    axial_stiffness: float = 7.62e6
    mass_per_length: float = 100.0
    bending_stiffness: float = 0.0
    damping_ratio: float = 0.0
    length: Optional[float] = None
    elements: Optional[int] = None
    max_element_angle: float = math.pi / 6
    tension_only: bool = False
    formulation: str = "node_kelvin_voigt"
    max_placement_strain: float = 0.1

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

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass
class Solver:
    """Time stepping.

    Attributes:
        time_step: fixed step, s. Default None = ``time_step_fraction`` x stability limit;
            a step above the limit is refused.
        time_step_fraction: in (0, 1]; used only when ``time_step`` is None. Default 0.5
            (the thesis ran at half its limit).
    """

    time_step: Optional[float] = None
    time_step_fraction: float = 0.5

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


#: Optional large arrays a run can record (``Recording.channels``); every other array of
#: :class:`beltrs.Result` is always recorded.
CHANNELS = ("tension", "node_position", "node_velocity")


@dataclass
class Recording:
    """How a scene is run and what is recorded (the ``[recording]`` table of a scene file,
    used by ``beltrs run``; :meth:`beltrs.Simulation.run` takes the same settings as
    arguments, see :meth:`run_kwargs`).

    Attributes:
        duration: simulated time of the run, s, >= 0. Default 1.
        interval: sample about every this many seconds (rounded to whole steps), s, > 0.
            Default None: every ``every`` steps, or every 0.01 s if ``every`` is None too.
        every: sample every this many steps, >= 1. Give ``interval`` or ``every``, not
            both. Default None.
        channels: optional large arrays to record, from ``"tension"``,
            ``"node_position"``, ``"node_velocity"``. Default: all three.
        stabilise: relax to static equilibrium (:meth:`beltrs.Simulation.stabilise`)
            before the run. Default True.
        stabilise_friction: keep belt friction on while relaxing; only with ``stabilise``
            (alone it would have no effect, and is refused). Default False.
    """

    duration: float = 1.0
    interval: Optional[float] = None
    every: Optional[int] = None
    channels: tuple[str, ...] = CHANNELS
    stabilise: bool = True
    stabilise_friction: bool = False

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        return {
            "duration": self.duration,
            "interval": self.interval,
            "every": self.every,
            "channels": list(self.channels),
            "stabilise": self.stabilise,
            "stabilise_friction": self.stabilise_friction,
        }

    def run_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of :meth:`beltrs.Simulation.run` (all but ``duration``)."""
        kw: dict[str, Any] = {name: name in self.channels for name in CHANNELS}
        if self.every is not None:
            kw["record_every"] = self.every
        else:
            kw["record_interval"] = 0.01 if self.interval is None else self.interval
        return kw


@dataclass
class Scene:
    """A whole scene. Pulleys are listed in the order the belt meets them.

    Attributes:
        belt: belt properties.
        pulleys: pulleys in belt order (the loop closes from the last to the first).
        idlers: idlers, any order.
        loads: bulk material loads (:class:`Load`), any order. Default none.
        gravity: m/s^2, acting in -y; 0 compiles no gravity stage. Default 9.81.
        solver: time stepping.
        recording: how ``beltrs run`` runs the scene and what it records.
    """

    belt: Belt = field(default_factory=Belt)
    pulleys: list[Pulley] = field(default_factory=list)
    idlers: list[Idler] = field(default_factory=list)
    loads: list[Load] = field(default_factory=list)
    gravity: float = 9.81
    solver: Solver = field(default_factory=Solver)
    recording: Recording = field(default_factory=Recording)

    def __post_init__(self) -> None:
        _normalise(self)

    def to_dict(self) -> dict[str, Any]:
        """The plain-data form the engine reads (``Scene.from_dict`` reads it back)."""
        return {
            "belt": self.belt.to_dict(),
            "pulleys": [p.to_dict() for p in self.pulleys],
            "idlers": [d.to_dict() for d in self.idlers],
            "loads": [ld.to_dict() for ld in self.loads],
            "gravity": self.gravity,
            "solver": self.solver.to_dict(),
            "recording": self.recording.to_dict(),
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> "Scene":
        """Read the plain-data form (``to_dict()``, or a parsed scene file) strictly.

        Absent keys take their defaults; ``None`` is accepted where the default is None.

        Raises:
            beltrs.SceneError: an unknown key (naming its full path, with a "did you
                mean" suggestion) or a value of the wrong type (naming the field, the
                value and the expected type).
        """
        return _read_dataclass(cls, data, "")

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


# --- strict reading and normalisation ---------------------------------------------------
_HINTS: dict[type, dict[str, Any]] = {}


def _hints(cls: type) -> dict[str, Any]:
    """Resolved field types of a scene dataclass, in field order."""
    h = _HINTS.get(cls)
    if h is None:
        resolved = typing.get_type_hints(cls)
        h = {f.name: resolved[f.name] for f in fields(cls)}
        _HINTS[cls] = h
    return h


def _join(path: str, key: str) -> str:
    return key if not path else f"{path}.{key}"


def _type_error(path: str, value: Any, expected: str) -> SceneError:
    return SceneError(f"{path or 'scene'} = {value!r}: expected {expected}")


def unknown_key_message(path: str, key: Any, known: Sequence[str]) -> str:
    """``path = 'key': unknown key, did you mean 'x'? (known keys here: ...)``; the same
    text (and the same suggestion, difflib's closest match) as the engine's dict reader."""
    known = sorted(set(known))
    close = difflib.get_close_matches(str(key), known, n=1)
    hint = f", did you mean {close[0]!r}?" if close else ""
    return f"{path} = {key!r}: unknown key{hint} (known keys here: {', '.join(known)})"


def _is_sequence(value: Any) -> bool:
    return not isinstance(value, (str, bytes, Mapping)) and hasattr(value, "__iter__") and hasattr(value, "__len__")


def _read_value(tp: Any, value: Any, path: str) -> Any:
    """``value`` checked against the annotation ``tp`` and converted to its canonical form."""
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if origin is Union:
        inner = [a for a in args if a is not type(None)]
        if value is None and len(inner) < len(args):
            return None
        return _read_value(inner[0], value, path)
    if tp is float:
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise _type_error(path, value, "a number")
        return float(value)
    if tp is int:
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise _type_error(path, value, "a whole number")
        return int(value)
    if tp is bool:
        if not isinstance(value, bool):
            raise _type_error(path, value, "true or false")
        return value
    if tp is str:
        if not isinstance(value, str):
            raise _type_error(path, value, "a string")
        return value
    if origin is tuple and len(args) == 2 and args[1] is not Ellipsis:
        if not _is_sequence(value) or len(value) != 2:
            raise _type_error(path, value, "[x, y]")
        return tuple(_read_value(float, v, f"{path}[{i}]") for i, v in enumerate(value))
    if origin in (tuple, collections.abc.Sequence) and args:
        item = args[0]
        what = "a list of strings" if item is str else "a list of numbers"
        if not _is_sequence(value):
            raise _type_error(path, value, what)
        return tuple(_read_value(item, v, f"{path}[{i}]") for i, v in enumerate(value))
    if origin is list and args and is_dataclass(args[0]):
        if not isinstance(value, (list, tuple)):
            raise _type_error(path, value, "a list of tables")
        items = [_read_dataclass(args[0], v, f"{path}[{i}]") for i, v in enumerate(value)]
        if isinstance(value, list) and all(a is b for a, b in zip(items, value)):
            return value  # already a list of scene objects: keep the caller's list
        return items
    if is_dataclass(tp):
        return _read_dataclass(tp, value, path)
    raise TypeError(f"{path}: no reader for annotation {tp!r}")  # a bug in this module


def _read_dataclass(cls: type, data: Any, path: str) -> Any:
    if isinstance(data, cls):
        return data
    if not isinstance(data, Mapping):
        raise _type_error(path, data, "a table")
    hints = _hints(cls)
    for key in data:
        if key not in hints:
            raise SceneError(unknown_key_message(_join(path, str(key)), key, list(hints)))
    kwargs = {name: _read_value(tp, data[name], _join(path, name)) for name, tp in hints.items() if name in data}
    return cls(**kwargs)


def _normalise(obj: Any) -> None:
    """Bring each field of a freshly built scene object to its canonical type (see the
    module docstring); a value of the wrong type is left alone for the engine to report."""
    for name, tp in _hints(type(obj)).items():
        value = getattr(obj, name)
        try:
            new = _read_value(tp, value, name)
        except SceneError:
            continue
        if new is not value:
            object.__setattr__(obj, name, new)


def field_default(cls: type, name: str) -> Any:
    """The default value of field ``name`` of a scene dataclass."""
    for f in fields(cls):
        if f.name == name:
            if f.default is not MISSING:
                return f.default
            if f.default_factory is not MISSING:
                return f.default_factory()
            break
    raise KeyError(name)

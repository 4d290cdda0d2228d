"""Scene description: plain dataclasses, SI units throughout.

A :class:`Scene` is data only. :class:`beltrs.Simulation` validates and compiles it in the
Rust engine; every error names the field (e.g. ``pulleys[1].radius``), the value and the
rule broken. ``Scene.to_dict()`` gives the exact form the engine reads; unknown keys in
that form are errors, never ignored.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from typing import Any, Optional, Sequence

__all__ = [
    "Belt",
    "Brake",
    "Drive",
    "Friction",
    "Idler",
    "Pulley",
    "Scene",
    "Solver",
    "Takeup",
]


@dataclass
class Friction:
    """Belt friction on a pulley or idler (stick-force model, thesis eq. 4.76-4.94).

    Attributes:
        static: static coefficient mu_s, dimensionless, >= kinetic. Default 0 (no friction
            stage is compiled when every body has mu_s = 0).
        kinetic: kinetic coefficient mu_k, dimensionless. Default: equal to ``static``.
        model: ``"stick_force"`` (default) or ``"none"``.
    """

    static: float = 0.0
    kinetic: Optional[float] = None
    model: str = "stick_force"

    def to_dict(self) -> dict[str, Any]:
        kinetic = self.static if self.kinetic is None else self.kinetic
        return {"model": self.model, "static": self.static, "kinetic": kinetic}


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

    def to_dict(self) -> dict[str, Any]:
        return {
            "counterweight": self.counterweight,
            "direction": list(self.direction),
            "travel_min": self.travel_min,
            "travel_max": self.travel_max,
        }


@dataclass
class Drive:
    """Drive torque T(t, w) = f(t) * g(w) - viscous * w (thesis eq. 4.66).

    Attributes:
        time: abscissae of f, s, strictly increasing. Default [0].
        torque: f(t), N*m, counter-clockwise positive; piecewise linear, held beyond the
            ends. Default [0].
        speed: abscissae of g, rad/s. Default: none (g = 1).
        speed_factor: g(w), dimensionless (e.g. a motor curve). Default: none.
        viscous: load torque per unit speed, N*m*s/rad. Default 0.
        inertia: motor and gearbox inertia added to the pulley, kg*m^2. Default 0.
    """

    time: Sequence[float] = (0.0,)
    torque: Sequence[float] = (0.0,)
    speed: Optional[Sequence[float]] = None
    speed_factor: Optional[Sequence[float]] = None
    viscous: float = 0.0
    inertia: float = 0.0

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
        friction: belt friction. Default None (frictionless).
        contact_stiffness: penalty stiffness per metre of penetration, N/m. Default 1e9.
        contact_damping: normal contact damping, N*s/m. Default 0.
        takeup: gravity takeup, if the pulley translates. Default None.
        drive: drive torque. Default None.
        brake: brake. Default None.
        name: label for messages. Default "".
    """

    center: tuple[float, float] = (0.0, 0.0)
    radius: float = 0.5
    mass: float = 100.0
    inertia: Optional[float] = None
    wrap: str = "ccw"
    friction: Optional[Friction] = None
    contact_stiffness: float = 1e9
    contact_damping: float = 0.0
    takeup: Optional[Takeup] = None
    drive: Optional[Drive] = None
    brake: Optional[Brake] = None
    name: str = ""

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
        contact_damping: N*s/m. Default 0.
        friction: belt friction. Default None (the roll never turns).
    """

    center: tuple[float, float] = (0.0, 0.0)
    radius: float = 0.0635
    inertia: float = 0.01
    contact_stiffness: float = 1e8
    contact_damping: float = 0.0
    friction: Optional[Friction] = None

    def to_dict(self) -> dict[str, Any]:
        return {
            "center": [float(c) for c in self.center],
            "radius": self.radius,
            "inertia": self.inertia,
            "contact_stiffness": self.contact_stiffness,
            "contact_damping": self.contact_damping,
            "friction": None if self.friction is None else self.friction.to_dict(),
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
        max_element_angle: rad. Default pi/6 (30 degrees, thesis §6.1); at most pi/3.
        tension_only: if True a slack element carries no compression. Default False.
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
        time_step_fraction: in (0, 1]. Default 0.5 (the thesis ran at half its limit).
    """

    time_step: Optional[float] = None
    time_step_fraction: float = 0.5

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)


@dataclass
class Scene:
    """A whole scene. Pulleys are listed in the order the belt meets them.

    Attributes:
        belt: belt properties.
        pulleys: pulleys in belt order (the loop closes from the last to the first).
        idlers: idlers, any order.
        gravity: m/s^2, acting in -y; 0 compiles no gravity stage. Default 9.81.
        solver: time stepping.
    """

    belt: Belt = field(default_factory=Belt)
    pulleys: list[Pulley] = field(default_factory=list)
    idlers: list[Idler] = field(default_factory=list)
    gravity: float = 9.81
    solver: Solver = field(default_factory=Solver)

    def to_dict(self) -> dict[str, Any]:
        """The plain-data form the engine reads."""
        return {
            "belt": self.belt.to_dict(),
            "pulleys": [p.to_dict() for p in self.pulleys],
            "idlers": [d.to_dict() for d in self.idlers],
            "gravity": self.gravity,
            "solver": self.solver.to_dict(),
        }

    def pulley_index(self, name: str) -> int:
        """Index of the pulley called ``name``."""
        for i, p in enumerate(self.pulleys):
            if p.name == name:
                return i
        raise KeyError(f"no pulley named {name!r} (names: {[p.name for p in self.pulleys]})")

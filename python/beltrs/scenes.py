"""Built-in scenes."""

from __future__ import annotations

import math
from typing import Optional

from .scene import Belt, Drive, Friction, Idler, Pulley, Recording, Scene, Solver, Takeup

__all__ = ["hustrulid_loop", "hustrulid_torque_pulse", "idler_conveyor"]


def hustrulid_loop(
    elements: int = 89,
    *,
    contact_stiffness: float = 2e8,
    friction: Optional[Friction] = None,
    damping_ratio: float = 0.0,
    counterweight: float = 30_000.0,
    bending: bool = True,
    time_step: Optional[float] = None,
    time_step_fraction: float = 0.5,
) -> Scene:
    """Case H: Hustrulid's two-pulley vertical loop (thesis chapter 6, reference-cases.md).

    Upper pulley at (0, 100) m, radius 5 m, 600 kg, inertia 15 000 kg*m^2, fixed centre.
    Lower pulley at (0, 0), the same, as a vertical gravity takeup with a 30 000 kg
    counterweight. Belt E = 300 MPa, 1 m x 0.0254 m (EA = 7.62 MN, EI = 409.7 N*m^2),
    100 kg/m, placed unstretched on the 231.416 m path.

    Args:
        elements: number of belt elements (89 = 2.600 m, a 30 degree arc).
        contact_stiffness: belt-pulley penalty stiffness, N per metre of penetration.
            Default 2e8: the thesis code's KC = 1e9 N in its law f = KC (R - a)/R with
            R = 5 m. The largest nodal force (~0.13 MN at 89 elements) then penetrates
            0.65 mm, which moves the takeup by about 1 mm (0.03 % of the answer). Stiffer
            contact (the thesis text's 1e12) shrinks the step and slows the static
            relaxation (the contact/belt stiffness ratio sets its conditioning) for no gain
            in these answers.
        friction: pulley friction (both pulleys). Default None (frictionless, as in the
            exact statics).
        damping_ratio: axial damping, fraction of critical. Default 0.
        counterweight: takeup counterweight, kg. Default 30 000.
        bending: include EI. Default True.
        time_step: fixed step, s. Default None (automatic).
        time_step_fraction: fraction of the stability limit. Default 0.5.
    """
    e, w, t = 300e6, 1.0, 0.0254
    belt = Belt.from_material(e, w, t, 100.0, elements=elements, damping_ratio=damping_ratio)
    if not bending:
        belt.bending_stiffness = 0.0
    common = dict(radius=5.0, mass=600.0, inertia=15_000.0, contact_stiffness=contact_stiffness)
    return Scene(
        belt=belt,
        pulleys=[
            Pulley(name="upper", center=(0.0, 100.0), friction=friction, **common),  # type: ignore[arg-type]
            Pulley(
                name="takeup",
                center=(0.0, 0.0),
                friction=friction,
                takeup=Takeup(counterweight=counterweight),
                **common,  # type: ignore[arg-type]
            ),
        ],
        solver=Solver(time_step=time_step, time_step_fraction=time_step_fraction),
    )


def hustrulid_torque_pulse(elements: int = 89) -> Scene:
    """Case H with the thesis §6.4.2 torque pulse: 400 kN*m on the upper pulley for
    0.07 s from t = 0, friction mu_s = 0.5, mu_k = 0.4 on both pulleys; stabilised without
    friction (the thesis' order), then 3.6 s recorded every 0.01 s (tension and node
    positions). The same run as ``python -m beltrs demo``.
    """
    friction = Friction(static=0.5, kinetic=0.4)
    scene = hustrulid_loop(elements, friction=friction)
    scene.pulleys[0].drive = Drive.pulse(4e5, 0.07)
    scene.recording = Recording(duration=3.6, interval=0.01, channels=("tension", "node_position"))
    return scene


def idler_conveyor(
    length: float = 100.0,
    *,
    carry_spacing: float = 1.2,
    return_spacing: float = 3.0,
    pulley_radius: float = 0.5,
    counterweight: float = 2000.0,
    drive_torque: float = 2000.0,
    ramp_time: float = 2.0,
    no_load_speed: float = 2.0,
    friction: Optional[Friction] = None,
    idler_friction: Optional[Friction] = None,
) -> Scene:
    """A horizontal belt conveyor on idlers: head drive, tail gravity takeup.

    Tail pulley ("tail") at (0, 0) on a horizontal takeup pulled in -x by a counterweight
    (its rope runs over a sheave: the pull is counterweight x g, the strands carry half
    each). Head pulley ("head") at (``length``, 0), driven. Both pulleys: radius
    ``pulley_radius``, belt friction ``friction``. The belt runs counter-clockwise in node
    order (bottom strand towards the head); the drive turns the head pulley clockwise, so
    the carry (top) strand moves towards the head. Carry idlers under the top strand every
    ``carry_spacing``, return idlers under the bottom strand every ``return_spacing``, each
    touching the straight belt centre line (the belt sags onto them under gravity).

    Belt: a 1 m wide EP 630/4 fabric belt, EA = 6.3 MN (about 10 x its rated strength),
    EI = 20 N*m^2, 14 kg/m, 5 % damping, elements of at most 45 degrees of arc on the
    pulleys. Penalty contact 1e8 N/m on pulleys and idlers; 1000 N*s/m contact damping on
    the idlers (light, about 2 % of critical for one node), so that the belt settles on
    them instead of bouncing.

    Drive: f(t) ramps linearly from 0 to ``drive_torque`` (N*m, clockwise) over
    ``ramp_time`` (s), times a straight motor line g(w) falling from 1 at rest to 0 at
    ``no_load_speed`` (rad/s, clockwise): with no material load the belt approaches
    ``no_load_speed`` x ``pulley_radius`` m/s.

    Args:
        length: centre distance between the pulleys, m. Default 100.
        carry_spacing: carry idler pitch, m. Default 1.2.
        return_spacing: return idler pitch, m. Default 3.0.
        pulley_radius: m. Default 0.5.
        counterweight: takeup counterweight, kg. Default 2000 (9.8 kN per strand).
        drive_torque: full drive torque, N*m. Default 2000.
        ramp_time: s. Default 2.
        no_load_speed: rad/s. Default 2 (1 m/s belt speed).
        friction: belt friction on both pulleys. Default mu_s = 0.35, mu_k = 0.3.
        idler_friction: belt friction on the idlers (turns the rolls). Default mu = 0.3.
    """
    if friction is None:
        friction = Friction(static=0.35, kinetic=0.3)
    if idler_friction is None:
        idler_friction = Friction(static=0.3, kinetic=0.3)
    r = pulley_radius
    roll = 0.0635
    belt = Belt(
        axial_stiffness=6.3e6,
        mass_per_length=14.0,
        bending_stiffness=20.0,
        damping_ratio=0.05,
        max_element_angle=math.pi / 4,
    )
    drive = Drive(
        time=[0.0, ramp_time],
        torque=[0.0, -drive_torque],
        speed=[-no_load_speed, 0.0],
        speed_factor=[0.0, 1.0],
    )
    common = dict(radius=r, contact_stiffness=1e8, friction=friction)
    pulleys = [
        Pulley(name="tail", center=(0.0, 0.0), mass=500.0,
               takeup=Takeup(counterweight=counterweight, direction=(-1.0, 0.0)), **common),  # type: ignore[arg-type]
        Pulley(name="head", center=(length, 0.0), mass=800.0, drive=drive, **common),  # type: ignore[arg-type]
    ]

    def row(y: float, pitch: float) -> list[Idler]:
        count = math.floor((length - 2 * r) / pitch)
        x0 = 0.5 * (length - (count - 1) * pitch)  # centred between the pulleys
        # round(): keep idler positions like 1.4 exact in scene files (no 1.3999999999999986).
        return [
            Idler(
                center=(round(x0 + i * pitch, 9), y),
                radius=roll,
                contact_stiffness=1e8,
                contact_damping=1000.0,
                friction=idler_friction,
            )
            for i in range(count)
        ]

    idlers = row(r - roll, carry_spacing) + row(-r - roll, return_spacing)
    return Scene(
        belt=belt,
        pulleys=pulleys,
        idlers=idlers,
        recording=Recording(duration=8.0, interval=0.01, channels=("tension", "node_position")),
    )


def concave_conveyor(
    *,
    flat: float = 30.0,
    incline_length: float = 40.0,
    incline: float = math.radians(5.0),
    curve_radius: float = 40.0,
    pulley_radius: float = 1.0,
    carry_pitch: float = 1.0,
    return_pitch: float = 4.0,
    counterweight: float = 1000.0,
    drive: Optional[Drive] = None,
) -> Scene:
    """A conveyor whose carry strand runs level, then up a concave vertical curve onto an
    incline: the layout where a fast start lifts the belt off its idlers.

    Tail pulley ("tail") at (0, 0) on a horizontal gravity takeup pulled in -x (the strands
    carry counterweight x g / 2 each); the carry strand leaves its top at (0, R), runs
    ``flat`` m level, turns up through a circular curve of ``curve_radius`` onto an incline
    of ``incline`` rad, ``incline_length`` m long (vertex to vertex), and wraps the head
    pulley ("head"), which is driven clockwise. Carry idlers follow that profile every
    ``carry_pitch`` m; return idlers follow it one pulley diameter lower every
    ``return_pitch`` m (built with :func:`beltrs.layout.idlers_along`). In static
    equilibrium the belt lies on the curve's idlers while its tension T < rho*g*R_c (7.8 kN
    here, against ~5.1 kN at rest); a start that raises it beyond lifts the belt off them.

    Belt: EA = 10 MN, 20 kg/m, EI = 50 N*m^2, 5 % damping, elements of 15 degrees of arc on
    the pulleys (0.26 m, a quarter of the carry pitch: a polygonal belt running over rolls
    moves up and down by about (load per pitch / T) * l / 4 each time a node passes, 2.5 mm
    here, so the element must be short against the pitch for lift-off to stand out).
    Penalty contact 1e8 N/m; the idlers have belt friction 0.3 (the rolls turn) and 3e4 N*s/m
    contact damping, about half of critical for a 5 kg node on 1e8 N/m (2*sqrt(k*m) =
    4.5e4): on lightly damped penalty contact that rattle builds up (docs/stability.md). The
    pulleys: mu_s 0.35, mu_k 0.3.

    Args:
        flat: level carry length before the curve's vertex, m. Default 30.
        incline_length: from the curve's vertex to the head tangent point, m. Default 40.
        incline: incline angle, rad. Default 5 degrees. The straight chord between the
            pulleys (the initial placement) must lie less than a pulley diameter above the
            profile, or the return strand starts above the carry idlers.
        curve_radius: concave curve radius, m. Default 40.
        pulley_radius: both pulleys, m. Default 1.
        carry_pitch, return_pitch: idler pitches, m. Defaults 1 and 4.
        counterweight: takeup counterweight, kg. Default 1000.
        drive: head drive (clockwise torque is negative). Default none.
    """
    from .layout import Profile, idlers_along

    r = pulley_radius
    end = (flat + incline_length * math.cos(incline), r + incline_length * math.sin(incline))
    carry = Profile([(0.0, r), (flat, r), end], curve_radii=[curve_radius])
    head = (end[0] + r * math.sin(incline), end[1] - r * math.cos(incline))
    friction = Friction(static=0.35, kinetic=0.3)
    common = dict(radius=r, contact_stiffness=1e8, friction=friction)
    pulleys = [
        Pulley(name="tail", center=(0.0, 0.0), mass=500.0,
               takeup=Takeup(counterweight=counterweight, direction=(-1.0, 0.0)), **common),  # type: ignore[arg-type]
        Pulley(name="head", center=(round(head[0], 9), round(head[1], 9)), mass=800.0, drive=drive, **common),  # type: ignore[arg-type]
    ]
    rolls = dict(contact_stiffness=1e8, contact_damping=3e4, friction=Friction(static=0.3, kinetic=0.3))
    clear = 2.0 * r  # keep idlers off the pulleys
    idlers = idlers_along(carry, carry_pitch, start=clear, end=carry.length - clear, **rolls)
    idlers += idlers_along(carry, return_pitch, offset=-2 * r, start=clear, end=carry.length - clear, **rolls)
    belt = Belt(
        axial_stiffness=1e7,
        mass_per_length=20.0,
        bending_stiffness=50.0,
        damping_ratio=0.05,
        max_element_angle=math.pi / 12,
    )
    return Scene(belt=belt, pulleys=pulleys, idlers=idlers)

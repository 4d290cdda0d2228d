"""Scenes used by the benchmark and the accuracy study (not part of the package).

- :func:`kubas_drive`: case K (docs/reference-cases.md, Kubas 2014 §4) as far as the node
  model can carry it: a two-pulley poly-V drive with stick-force friction (the Kubas
  creep-rate friction and nonlinear contact are not implemented yet).
- :func:`conveyor`: a long horizontal conveyor with a head drive, a tail gravity takeup and
  carry and return idlers, belt supported by idlers everywhere (no strand crossing).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Optional

import beltrs
from beltrs import Belt, Drive, Friction, Idler, Pulley, Scene, Solver, Takeup

# --- case K -------------------------------------------------------------------------------
KUBAS_RADIUS = 0.027  # m
KUBAS_CENTRES = 0.515  # m
KUBAS_EA = 1.52e5  # N: c_tra read per unit strain (reference-cases.md: the per-SDE reading,
# EA = 1216 N, would give 45 % creep against the paper's ~1.5 %)
KUBAS_MASS = 0.096  # kg/m
KUBAS_TORQUE = 15.0  # N*m, reached at 0.3 s
KUBAS_RAMP = 0.3  # s
KUBAS_PRELOAD = 550.0  # N

PULLEY_FRICTION = Friction(static=0.35, kinetic=0.3)


def kubas_drive(
    elements: int = 150,
    *,
    contact_stiffness: float = 1e7,
    time_step_fraction: float = 0.5,
    damping_ratio: float = 0.1,
    preload: float = KUBAS_PRELOAD,
    calibrate: bool = True,
) -> Scene:
    """Case K with the node model: pulleys r = 0.027 m, centres 0.515 m, inertia
    2.4e-4 kg*m^2, belt 0.096 kg/m, EA = 1.52e5 N, EI = c_tor * l = 0.026 N*m/rad x 8 mm,
    mu_s = 1.05, mu_k = 1.0, no gravity (the paper's drive is horizontal and light).

    Drive pulley at the origin: torque ramps linearly to 15 N*m at 0.3 s. Driven pulley at
    (0.515, 0): a resistance torque proportional to speed, 15 N*m at 8*pi rad/s (a drive
    with only a viscous term). The preload is an initial strain: the unstretched length is
    set so that the belt at rest carries ``preload`` N; with ``calibrate`` one stabilised
    trial corrects for the chord polygon and the contact penetration (both slacken it).

    Args:
        elements: belt elements (Kubas: 150 bodies, 8 mm). Default 150.
        contact_stiffness: N/m per node. Default 1e7 (Kubas' c2 = 6.5e5 N/m, on a node
            carrying ~T*theta = 160 N, sinks 0.25 mm and takes 200 N off the preload; 1e7
            sinks 16 um).
        time_step_fraction: of the stability limit. Default 0.5.
        damping_ratio: axial damping, fraction of critical per element. Default 0.1
            (Kubas' b_tra = 20.5 N*s/m on an 8 mm element of 7.7e-4 kg with
            k = EA/l = 1.9e7 N/m is 0.085 of critical).
        preload: belt tension at rest, N. Default 550.
        calibrate: correct the length once from a stabilised trial. Default True.
    """
    path = 2 * KUBAS_CENTRES + 2 * math.pi * KUBAS_RADIUS
    belt = Belt(
        axial_stiffness=KUBAS_EA,
        mass_per_length=KUBAS_MASS,
        bending_stiffness=0.026 * 0.008,
        damping_ratio=damping_ratio,
        length=path / (1 + preload / KUBAS_EA),
        elements=elements,
    )
    friction = Friction(static=1.05, kinetic=1.0)
    common = dict(radius=KUBAS_RADIUS, mass=0.5, inertia=2.4e-4, friction=friction, contact_stiffness=contact_stiffness)
    scene = Scene(
        belt=belt,
        pulleys=[
            Pulley(
                name="drive",
                center=(0.0, 0.0),
                drive=Drive(time=[0.0, KUBAS_RAMP], torque=[0.0, KUBAS_TORQUE]),
                **common,  # type: ignore[arg-type]
            ),
            Pulley(
                name="driven",
                center=(KUBAS_CENTRES, 0.0),
                drive=Drive(viscous=KUBAS_TORQUE / (8 * math.pi)),
                **common,  # type: ignore[arg-type]
            ),
        ],
        gravity=0.0,
        solver=Solver(time_step_fraction=time_step_fraction),
    )
    if calibrate:
        trial = beltrs.Simulation(scene)
        try:
            trial.stabilise(tolerance=1e-4, max_steps=300_000)
        except beltrs.BeltrsError:
            pass  # the relaxation can stall near 1e-4 (docs/performance.md); the mean tension is settled
        at_rest = float(trial.tensions().mean())
        length = scene.belt.length * (1 - (preload - at_rest) / KUBAS_EA)
        scene = replace(scene, belt=replace(belt, length=length))
    return scene


# --- a realistic long conveyor --------------------------------------------------------------
def conveyor(
    length: float = 500.0,
    nodes: int = 5000,
    *,
    radius: float = 0.4,
    carry_spacing: float = 1.5,
    return_spacing: float = 3.0,
    counterweight: float = 4000.0,
    drive_torque: float = 10_000.0,
    ramp: float = 10.0,
    belt_speed: float = 4.0,
    friction: Optional[Friction] = PULLEY_FRICTION,
    time_step_fraction: float = 0.5,
) -> Scene:
    """A horizontal belt conveyor, ``length`` m between pulley centres.

    Belt: 1 m wide steel-cord (about ST1250): EA = 60 MN, 25 kg/m, EI = 0. Head (drive)
    pulley at (0, 0) and tail pulley at (``length``, 0), both of ``radius`` m (0.4),
    1000 kg, inertia m*r^2. The belt goes counter-clockwise: the carry strand is on top
    (y = +r) and moves towards the head; the return strand is underneath (y = −r).
    The tail pulley is a horizontal gravity takeup pulling +x with ``counterweight`` kg
    (4000 kg: about 19.6 kN in each strand at rest). Carry idlers every ``carry_spacing``
    m (1.5) and return idlers every ``return_spacing`` m (3.0), radius 0.0635 m, centres
    one radius below each strand so that their tops touch it: the belt rests on them and
    sags 3 mm (carry) and 14 mm (return) between them at 20 kN.

    Drive: torque on the head pulley ramped linearly from 0 to ``drive_torque`` N*m over
    ``ramp`` s, times a motor curve that falls from 1 at 95 % to 0 at the speed giving
    ``belt_speed`` m/s. 10 kN*m accelerates the 50 t belt at about 0.5 m/s^2; T1/T2 stays
    below the capstan limit e^(0.3 pi) = 2.6 of the head pulley's friction (mu_s 0.35,
    mu_k 0.3 by default). No material and no running resistance (not modelled yet).

    Args:
        length: centre distance, m. Default 500 (5000 nodes of 0.2 m: 29 degrees of arc
            on the pulleys).
        nodes: belt elements. Default 5000.
        friction: pulley friction (both pulleys); None makes a frictionless loop (the
            drive can then not move the belt). Idlers are frictionless (their rolls do
            not turn; the belt slides on them).
        drive_torque: N*m; 0 removes the drive.
        time_step_fraction: of the stability limit. Default 0.5.
    """
    r_idler = 0.0635
    omega = belt_speed / radius
    drive = None
    if drive_torque > 0:
        drive = Drive(
            time=[0.0, ramp],
            torque=[0.0, drive_torque],
            speed=[0.0, 0.95 * omega, omega],
            speed_factor=[1.0, 1.0, 0.0],
        )
    pulley = dict(radius=radius, mass=1000.0, inertia=1000.0 * radius**2, friction=friction, contact_stiffness=1e8)
    carry = [
        Idler(center=(x, radius - r_idler), radius=r_idler)
        for x in _positions(length, carry_spacing, radius)
    ]
    ret = [
        Idler(center=(x, -radius - r_idler), radius=r_idler)
        for x in _positions(length, return_spacing, radius)
    ]
    return Scene(
        belt=Belt(axial_stiffness=60e6, mass_per_length=25.0, elements=nodes),
        pulleys=[
            Pulley(name="head", center=(0.0, 0.0), drive=drive, **pulley),  # type: ignore[arg-type]
            Pulley(
                name="tail",
                center=(length, 0.0),
                takeup=Takeup(counterweight=counterweight, direction=(1.0, 0.0)),
                **pulley,  # type: ignore[arg-type]
            ),
        ],
        idlers=carry + ret,
        solver=Solver(time_step_fraction=time_step_fraction),
    )


def _positions(length: float, spacing: float, radius: float) -> list[float]:
    """Idler stations from one spacing after the head to one spacing before the tail."""
    count = int(math.floor((length - 2 * radius) / spacing))
    first = 0.5 * (length - (count - 1) * spacing)
    return [first + k * spacing for k in range(count)]


def strands_apart(node_position, length: float, radius: float) -> float:
    """Smallest vertical gap, m, between the carry and the return strand over the free
    length (|x − ends| > 2 r): positive means the carry strand is everywhere above."""
    import numpy as np

    x = np.asarray(node_position)
    free = (x[:, 0] > 2 * radius) & (x[:, 0] < length - 2 * radius)
    top = x[free & (x[:, 1] > 0)]
    bottom = x[free & (x[:, 1] <= 0)]
    # Sample both strands on a common grid and compare.
    grid = np.linspace(2 * radius + 1, length - 2 * radius - 1, 2000)
    t = np.interp(grid, *top[np.argsort(top[:, 0])].T)
    b = np.interp(grid, *bottom[np.argsort(bottom[:, 0])].T)
    return float((t - b).min())

"""Case K side by side with Exudyn (an optional benchmark, not in CI).

Run from the repository root with beltrs and exudyn installed (``pip install . exudyn``)::

    python benches/peer_exudyn.py [--duration 1.0] [--exudyn-step 1e-4] [--no-exudyn]
                                  [--prototype]

Case K (docs/kubas.md, reference-cases.md): two pulleys r = 0.027 m, 0.515 m apart,
inertia 2.4e-4 kg*m^2; belt 0.096 kg/m, EA = 1.52e5 N (c_tra per unit strain), preload
~550 N; drive torque ramped to 15 N*m at 0.3 s; resistance on the driven pulley
proportional to speed, 15 N*m at 8*pi rad/s; mu = 1.0 (kinetic). Steady answers:
T1 - T2 = M/r = 555.6 N; driven speed 8*pi rad/s; slip from creep theory
(T1 - T2)/(EA + T1) = 0.36 %.

Printed for each engine, in one run: wall time of the dynamic run (set-up and preload
calibration reported separately), T1 - T2 (tight minus slack span tension, averaged over
the last 40 % of the run), T1 + T2, the pulley speeds and the slip 1 - w2/w1.

- beltrs, node model: ``bench_scenes.kubas_drive`` through the Python API (stick-force
  friction, linear contact; the Kubas contact and creep friction are not in the engine yet).
- beltrs, rigid-body prototype (``--prototype``): runs the ``kubas_case_k`` cargo example
  (Kubas's rigid bodies, nonlinear contact, creep friction, RKF45, outside Simulation) and
  prints its figures. It needs ``cargo`` and is slow with the paper's creep parameters
  (docs/kubas.md).
- Exudyn: 150 ObjectANCFCable2D elements on the reeving curve of the two circles with
  ObjectContactFrictionCircleCable2D against each pulley (penalty contact, regularised
  Coulomb friction with a tangential bristle stiffness), generalised-alpha with a fixed step.
  Its contact parameters are per metre of belt and chosen from Kubas's: contact stiffness
  c2/l (his linear term per body length), so the belt sinks about as far as in his model.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_scenes import KUBAS_CENTRES, KUBAS_EA, KUBAS_MASS, KUBAS_RADIUS, KUBAS_RAMP, KUBAS_TORQUE  # noqa: E402

PRELOAD = 555.0  # N, "slightly above 550 N"
INERTIA = 2.4e-4  # kg*m^2
RESISTANCE = KUBAS_TORQUE / (8 * math.pi)  # N*m*s/rad
EXACT_DIFF = KUBAS_TORQUE / KUBAS_RADIUS


def figures(name: str, wall: float, t1: float, t2: float, w1: float, w2: float, extra: str = "") -> dict:
    slip = 1.0 - w2 / w1
    creep = (t1 - t2) / (KUBAS_EA + t1)
    print(f"-- {name}")
    print(f"   wall {wall:.1f} s {extra}")
    err = 100 * (t1 - t2 - EXACT_DIFF) / EXACT_DIFF
    print(f"   T1 - T2 {t1 - t2:.1f} N ({err:+.2f} % of M/r = {EXACT_DIFF:.1f} N)")
    print(f"   T1 + T2 {t1 + t2:.1f} N (2 x preload {2 * PRELOAD:.0f} N)")
    print(f"   speeds {w1:.3f} / {w2:.3f} rad/s, slip {100 * slip:.3f} % (creep theory {100 * creep:.3f} %)")
    return {"wall": wall, "diff": t1 - t2, "sum": t1 + t2, "slip": slip}


def span_tensions(mid: np.ndarray, tension: np.ndarray) -> tuple[float, float]:
    """Median tension of the elements whose midpoints lie in the middle 60 % of each span
    (samples x elements arrays), averaged over samples: (tight, slack)."""
    along = mid[..., 0] / KUBAS_CENTRES
    inside = (along > 0.2) & (along < 0.8)
    top = [np.median(t[i & (m[:, 1] > 0)]) for m, t, i in zip(mid, tension, inside)]
    bottom = [np.median(t[i & (m[:, 1] < 0)]) for m, t, i in zip(mid, tension, inside)]
    a, b = float(np.mean(top)), float(np.mean(bottom))
    return max(a, b), min(a, b)


# --- beltrs, node model ----------------------------------------------------------------------
def run_beltrs(duration: float) -> dict:
    import beltrs
    from bench_scenes import kubas_drive

    t0 = time.perf_counter()
    scene = kubas_drive(150, preload=PRELOAD)
    sim = beltrs.Simulation(scene)
    try:
        sim.stabilise(tolerance=1e-4, max_steps=300_000)
    except beltrs.BeltrsError:
        pass  # the relaxation can stall near 1e-4 (docs/performance.md); the belt is settled
    setup = time.perf_counter() - t0
    t0 = time.perf_counter()
    res = sim.run(duration, record_every=20, node_velocity=False)
    wall = time.perf_counter() - t0
    keep = res.time >= 0.6 * res.time[-1]
    x = res.node_position[keep]
    mid = 0.5 * (x + np.roll(x, -1, axis=1))
    t1, t2 = span_tensions(mid, res.tension[keep])
    w = np.abs(res.pulley_speed[keep])
    return figures(
        f"beltrs node model ({sim.nodes} nodes, dt {sim.dt:.2e} s)",
        wall,
        t1,
        t2,
        float(w[:, 0].mean()),
        float(w[:, 1].mean()),
        f"for {duration} s simulated (set-up and stabilisation {setup:.1f} s)",
    )


# --- beltrs, rigid-body prototype ------------------------------------------------------------
def run_prototype(duration: float) -> None:
    print("-- beltrs rigid-body prototype (cargo run --release --example kubas_case_k, dv = 0.05 m/s)")
    # The paper's creep range (dv = 1e-5 m/s) needs ~1e-10 s steps (docs/kubas.md): run at
    # dv = 0.05 m/s, where T1 - T2 and the slip no longer move with dv.
    env = dict(os.environ, KUBAS_READING="strain", KUBAS_DV="0.05")
    out = subprocess.run(
        ["cargo", "run", "--release", "-q", "--example", "kubas_case_k", "--", str(duration)],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
    )
    print("   " + out.stdout.strip().replace("\n", "\n   "))
    if out.returncode != 0:
        print("   failed:", out.stderr.strip()[-400:])


# --- Exudyn ----------------------------------------------------------------------------------
def run_exudyn(duration: float, step: float, segments: int) -> dict:
    sys.exudynFast = True  # type: ignore[attr-defined]  # Exudyn's release build without range checks
    import exudyn as exu
    import exudyn.itemInterface as ei
    from exudyn.beams import CreateReevingCurve, PointsAndSlopes2ANCFCable2D

    t0 = time.perf_counter()
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    r, d, n = KUBAS_RADIUS, KUBAS_CENTRES, 150
    curve = CreateReevingCurve([[[0.0, 0.0], r, "L"], [[d, 0.0], r, "L"]], closedCurve=True, numberOfANCFnodes=n)
    ea = KUBAS_EA
    l_el = curve["totalLength"] / n
    # Axial damping: Kubas's b_tra = 20.5 N*s/m per 8 mm SDE is b_tra*l per unit strain rate.
    template = ei.ObjectANCFCable2D(
        massPerLength=KUBAS_MASS,
        axialStiffness=ea,
        bendingStiffness=0.026 * l_el,
        axialDamping=20.5 * l_el,
        referenceAxialStrain=-PRELOAD / ea,
        useReducedOrderIntegration=2,
    )
    nodes, cables = PointsAndSlopes2ANCFCable2D(
        mbs, curve["ancfPointsSlopes"], curve["elementLengths"], template, firstNodeIsLastNode=True
    )[:2]
    ground = mbs.AddNode(ei.NodePointGround())
    g_coord = mbs.AddMarker(ei.MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    pulleys, rigid_markers, rot_markers = [], [], []
    for centre in ([0.0, 0.0, 0.0], [d, 0.0, 0.0]):
        node = mbs.AddNode(ei.NodeRigidBody2D(referenceCoordinates=centre))
        body = mbs.AddObject(ei.ObjectRigidBody2D(mass=0.5, inertia=INERTIA, nodeNumber=node))
        for c in (0, 1):
            m = mbs.AddMarker(ei.MarkerNodeCoordinate(nodeNumber=node, coordinate=c))
            mbs.AddObject(ei.CoordinateConstraint(markerNumbers=[g_coord, m]))
        pulleys.append(node)
        rigid_markers.append(mbs.AddMarker(ei.MarkerBodyRigid(bodyNumber=body)))
        rot_markers.append(mbs.AddMarker(ei.MarkerNodeCoordinate(nodeNumber=node, coordinate=2)))

    def drive(mbs_, t, load):
        return KUBAS_TORQUE * min(t / KUBAS_RAMP, 1.0)

    mbs.AddLoad(ei.LoadCoordinate(markerNumber=rot_markers[0], load=0.0, loadUserFunction=drive))
    mbs.AddObject(ei.CoordinateSpringDamper(markerNumbers=[g_coord, rot_markers[1]], stiffness=0.0, damping=RESISTANCE))
    # Per metre of belt: Kubas's linear contact term c2 per body length l; damping his b at
    # the ramp value delta ~ 0.06 of a 0.15 mm penetration, per metre. Friction as in
    # Exudyn's belt-drive examples: bristle stiffness 0.2 of the contact stiffness and a
    # velocity penalty 1e-4 s times the bristle stiffness.
    k_contact = 6.5e5 / 0.008
    d_contact = 0.06 * 300.0 / 0.008
    k_friction = 0.2 * k_contact
    for j, pm in enumerate(rigid_markers):
        for c in cables:
            mc = mbs.AddMarker(ei.MarkerBodyCable2DShape(bodyNumber=c, numberOfSegments=segments))
            data = mbs.AddNode(
                ei.NodeGenericData(
                    initialCoordinates=[0.1] * segments + [-2] * segments + [0.0] * segments,
                    numberOfDataCoordinates=3 * segments,
                )
            )
            mbs.AddObject(
                ei.ObjectContactFrictionCircleCable2D(
                    markerNumbers=[pm, mc],
                    nodeNumber=data,
                    numberOfContactSegments=segments,
                    contactStiffness=k_contact,
                    contactDamping=d_contact,
                    frictionVelocityPenalty=1e-4 * k_friction,
                    frictionStiffness=k_friction,
                    frictionCoefficient=1.0,
                    circleRadius=r,
                    useSegmentNormals=False,
                )
            )
    speed = exu.OutputVariableType.AngularVelocity
    sensors = [
        mbs.AddSensor(ei.SensorNode(nodeNumber=p, storeInternal=True, outputVariableType=speed)) for p in pulleys
    ]
    force = [
        mbs.AddSensor(
            ei.SensorBody(
                bodyNumber=c,
                localPosition=[0.5 * l_el, 0, 0],
                storeInternal=True,
                outputVariableType=exu.OutputVariableType.ForceLocal,
            )
        )
        for c in cables
    ]
    where = [
        mbs.AddSensor(
            ei.SensorBody(
                bodyNumber=c,
                localPosition=[0.5 * l_el, 0, 0],
                storeInternal=True,
                outputVariableType=exu.OutputVariableType.Position,
            )
        )
        for c in cables
    ]
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.timeIntegration.endTime = duration
    s.timeIntegration.numberOfSteps = int(round(duration / step))
    s.timeIntegration.generalizedAlpha.spectralRadius = 0.8
    s.timeIntegration.newton.useModifiedNewton = True
    s.timeIntegration.discontinuous.iterationTolerance = 0.1
    s.timeIntegration.discontinuous.maxIterations = 2
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 2e-3
    s.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    s.parallel.numberOfThreads = 1
    s.show.statistics = False
    setup = time.perf_counter() - t0
    t0 = time.perf_counter()
    ok = mbs.SolveDynamic(s, showHints=False)
    wall = time.perf_counter() - t0
    if ok is False:
        print("   Exudyn reported a failed solve")
    w = [mbs.GetSensorStoredData(sn) for sn in sensors]
    tt = w[0][:, 0]
    keep = tt >= 0.6 * tt[-1]
    w1 = float(np.abs(w[0][keep, 3]).mean())
    w2 = float(np.abs(w[1][keep, 3]).mean())
    ten = np.stack([mbs.GetSensorStoredData(f)[:, 1] for f in force], axis=1)[keep]
    pos = np.stack([mbs.GetSensorStoredData(p)[:, 1:3] for p in where], axis=1)[keep]
    t1, t2 = span_tensions(pos, ten)
    return figures(
        f"Exudyn {exu.__version__} (150 ANCF elements, generalised-alpha, h = {step:g} s, {segments} contact segments)",
        wall,
        t1,
        t2,
        w1,
        w2,
        f"for {duration} s simulated (set-up {setup:.1f} s)",
    )


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--duration", type=float, default=1.0, help="simulated time, s (default 1)")
    ap.add_argument("--exudyn-step", type=float, default=1e-4, help="Exudyn time step, s (default 1e-4)")
    ap.add_argument("--segments", type=int, default=2, help="Exudyn contact segments per element (default 2)")
    ap.add_argument("--no-exudyn", action="store_true", help="skip Exudyn")
    ap.add_argument("--prototype", action="store_true", help="also run the rigid-body prototype (slow)")
    args = ap.parse_args(argv)
    print(f"case K, {args.duration} s simulated; exact T1 - T2 = M/r = {EXACT_DIFF:.1f} N")
    b = run_beltrs(args.duration)
    if args.prototype:
        run_prototype(args.duration)
    if not args.no_exudyn:
        e = run_exudyn(args.duration, args.exudyn_step, args.segments)
        print(f"== wall time Exudyn / beltrs node model: {e['wall'] / b['wall']:.1f}x")


if __name__ == "__main__":
    main()

"""Case K against Exudyn at matched error (an optional benchmark, not in CI).

Run from the repository root with beltrs and exudyn installed (``pip install .[peer]``, the
optional extra that brings Exudyn; not in CI)::

    python benches/peer_exudyn.py                 # all ladders and the matched-error table
    python benches/peer_exudyn.py --quick         # two rungs per ladder (a smoke run)
    python benches/peer_exudyn.py --codes node,exudyn --exudyn 75:1e-4,150:1e-4 --json out.json
    # the published run (docs/kubas.md), pinned to one core at raised priority:
    nice -n -10 taskset -c 1 python benches/peer_exudyn.py --codes node,wrap,exudyn --duration 1.0 \
        --window 0.3 --block 0.1 --node 150,300,600 --wrap 50,75,100,150 --exudyn 75:1e-4,100:1e-4 --repeat 3

Case K (docs/kubas.md, reference-cases.md): two pulleys r = 0.027 m, 0.515 m apart,
inertia 2.4e-4 kg*m^2; belt 0.096 kg/m, EA = 1.52e5 N (c_tra per unit strain), preload
about 550 N; drive torque ramped to 15 N*m over ``RAMP`` s; resistance on the driven pulley
proportional to speed, 15 N*m at 8*pi rad/s; mu_s = 1.05, mu_k = 1.0. One scenario for every
code: by default ramp 0.05 s, run 0.15 s, averages over the last 0.05 s (a smoke scenario:
the node model's slip has not settled by then); the published run (docs/kubas.md) uses
``--duration 1.0 --window 0.3 --block 0.1``, long enough for every code's slip to settle
(the 0.1 s block averages printed per rung show it). The pulleys follow the torque within
I/c = 0.4 ms; the paper's 0.3 s ramp changes nothing in the steady state.

Errors (each code, each rung):

- **T1 - T2** against the exact M/r = 555.6 N (the drive pulley's balance in steady
  running, whatever the belt model): |T1 - T2 - M/r|.
- **Slip** 1 - w2/w1 against creep theory, (M/r)/(EA + T1) with the run's own T1
  (docs/belt-drives.md): the steady answer of an elastic belt on rigid pulleys with Coulomb
  friction, the physics all three models approximate. Creep theory rather than each model's
  own converged slip, because the models' converged slips differ (Kubas's soft nonlinear
  contact adds the sink difference (p1 - p2)/r, ~0.1-0.4 points, docs/kubas.md): an error
  against one's own limit would reward a model for converging to a different answer. The
  error against each ladder's finest rung is printed too.

Ladders (error against wall time), all in this one process, one thread:

- beltrs node model (``bench_scenes.kubas_drive``: stick-force friction, linear contact
  1e7 N/m per node, central differences at half the stable step): element counts.
- the same with wrap contact (``wrap``: ``belt.pulley_contact = "wrap"``, docs/wrap-contact.md;
  no chord polygon on the pulleys): element counts (at least 45, the elements no longer than
  the pulley radius).
- beltrs rigid-body model (``beltrs.scenes.kubas_case_k``: Kubas's bodies and nonlinear
  contact, creep friction, central differences): body counts.
- Exudyn: ObjectANCFCable2D elements on the reeving curve, ObjectContactFrictionCircleCable2D
  against each pulley (penalty contact, regularised Coulomb friction with a bristle
  stiffness, as in Exudyn's belt-drive examples), generalised-alpha with a fixed step:
  the (elements, step) pairs of ``--exudyn`` (default 50 and 75 elements at h = 1e-4 s). Its contact is
  per metre of belt, from Kubas's c2 per body length (the belt sinks about as far as in his
  model); its preload is a reference strain -T0/EA (no calibration for the contact sink, so
  T1 + T2 comes out above twice 555 N, docs/kubas.md).

Wall time per answer = build + (beltrs: static relaxation) + the run + the read-out. With
``--repeat N`` the rungs run interleaved (the first rung of every code, then the second, ...)
N times over, so that a change of the machine's load falls on every code; each rung's wall is
the median of its N (the answers are deterministic and are kept from the first).
Matched error: for each Exudyn rung, the cheapest beltrs rung whose errors in T1 - T2 *and*
in slip are both at most Exudyn's; the ratio of the two wall times.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Callable, Optional

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_scenes import KUBAS_CENTRES, KUBAS_EA, KUBAS_MASS, KUBAS_RADIUS, KUBAS_TORQUE  # noqa: E402

PRELOAD = 555.0  # N, "slightly above 550 N"
INERTIA = 2.4e-4  # kg*m^2
RESISTANCE = KUBAS_TORQUE / (8 * math.pi)  # N*m*s/rad
EXACT_DIFF = KUBAS_TORQUE / KUBAS_RADIUS  # N
RAMP = 0.05  # s
DURATION = 0.15  # s
WINDOW = 0.05  # s
BLOCK = 0.05  # s, the history's averaging blocks
SAMPLE = 1e-3  # s between samples


@dataclass
class Rung:
    """One run of one code at one setting."""

    code: str
    setting: str
    wall: float  # s, build + relax + run + read-out
    wall_run: float  # s, the dynamic run alone
    t1: float  # N
    t2: float  # N
    w1: float  # rad/s
    w2: float  # rad/s
    steps: int = 0
    nodes: int = 0  # beltrs: nodes (or bodies) of the belt; 0 for Exudyn
    history: list = field(default_factory=list)  # [t_end (s), T1 - T2 (N), slip] per block
    walls: list = field(default_factory=list)  # wall of every repetition, s (``wall`` is their median)

    @property
    def diff(self) -> float:
        return self.t1 - self.t2

    @property
    def slip(self) -> float:
        return 1.0 - self.w2 / self.w1

    @property
    def creep(self) -> float:
        """Creep theory's slip with this run's T1, (M/r)/(EA + T1)."""
        return EXACT_DIFF / (KUBAS_EA + self.t1)

    @property
    def err_diff(self) -> float:
        return abs(self.diff - EXACT_DIFF)

    @property
    def err_slip(self) -> float:
        return abs(self.slip - self.creep)


def span_series(mid: np.ndarray, tension: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Median tension of the elements whose midpoints lie in the middle 60 % of each span
    (samples x elements arrays), per sample: (tight, slack)."""
    along = mid[..., 0] / KUBAS_CENTRES
    inside = (along > 0.2) & (along < 0.8)
    top = np.array([np.median(t[i & (m[:, 1] > 0)]) for m, t, i in zip(mid, tension, inside)])
    bottom = np.array([np.median(t[i & (m[:, 1] < 0)]) for m, t, i in zip(mid, tension, inside)])
    return (top, bottom) if top.mean() >= bottom.mean() else (bottom, top)


def averages(t: np.ndarray, tight: np.ndarray, slack: np.ndarray, w1: np.ndarray, w2: np.ndarray) -> dict:
    """Means over the last ``WINDOW`` s, and the history of T1 - T2 and slip per ``BLOCK`` s."""
    keep = t >= t[-1] - WINDOW - 1e-9
    history = []
    for end in np.arange(BLOCK, t[-1] + 1e-9, BLOCK):
        b = (t > end - BLOCK + 1e-9) & (t <= end + 1e-9)
        if b.any():
            history.append([round(float(end), 6), float((tight[b] - slack[b]).mean()),
                            float(1.0 - w2[b].mean() / w1[b].mean())])
    return {"t1": float(tight[keep].mean()), "t2": float(slack[keep].mean()), "w1": float(w1[keep].mean()),
            "w2": float(w2[keep].mean()), "history": history}


# --- beltrs ------------------------------------------------------------------------------------
def node_scene(elements: int, contact: str = "nodes"):
    """The node model of case K (stick-force friction), with this scenario's ramp; ``contact``
    is the belt's ``pulley_contact`` ("nodes": nodal contact, "wrap": wrap contact)."""
    from beltrs import Drive
    from bench_scenes import kubas_drive

    scene = kubas_drive(elements, preload=PRELOAD, calibrate=False)
    drive = Drive(time=[0.0, RAMP], torque=[0.0, KUBAS_TORQUE])
    return replace(
        scene,
        belt=replace(scene.belt, pulley_contact=contact),
        pulleys=[replace(scene.pulleys[0], drive=drive), scene.pulleys[1]],
    )


def rigid_scene(bodies: int, integrator: Optional[dict] = None):
    """Kubas's rigid-body case K with creep friction (Delta_v 1 mm/s, Delta_max 0.1 mm)."""
    import beltrs

    scene = beltrs.scenes.kubas_case_k(ramp_time=RAMP)
    creep = beltrs.Friction(model="creep", static=1.05, kinetic=1.0)
    solver = replace(scene.solver, **(integrator or {}))
    return replace(
        scene,
        belt=replace(scene.belt, elements=bodies),
        pulleys=[replace(p, friction=creep) for p in scene.pulleys],
        solver=solver,
    )


def run_beltrs(code: str, setting: str, make: Callable[[], object]) -> Rung:
    import beltrs

    t0 = time.perf_counter()
    sim = beltrs.Simulation(make())
    try:
        sim.stabilise(tolerance=1e-4, max_steps=300_000, progress=False)
    except beltrs.BeltrsError:
        pass  # the relaxation can stall near 1e-4 (docs/performance.md); the belt is settled
    t_run = time.perf_counter()
    res = sim.run(DURATION, record_interval=SAMPLE, node_velocity=False, progress=False)
    wall_run = time.perf_counter() - t_run
    x = res.node_position
    # Midpoints of consecutive points (nodes, or the rigid bodies' mass centres next to a joint).
    mid = 0.5 * (x + np.roll(x, -1, axis=1))
    tight, slack = span_series(mid, res.tension)
    w = np.abs(res.pulley_speed)
    avg = averages(np.asarray(res.time), tight, slack, w[:, 0], w[:, 1])
    steps = int(res.steps_accepted) or int(round(DURATION / sim.dt))
    nodes = int(x.shape[1])
    return Rung(code, setting, time.perf_counter() - t0, wall_run, steps=steps, nodes=nodes, **avg)


# --- Exudyn ------------------------------------------------------------------------------------
def run_exudyn(elements: int, step: float, contact_scale: float = 1.0, segments: int = 2) -> Rung:
    sys.exudynFast = True  # type: ignore[attr-defined]  # Exudyn's release build without range checks
    import exudyn as exu
    import exudyn.itemInterface as ei
    from exudyn.beams import CreateReevingCurve, PointsAndSlopes2ANCFCable2D

    t0 = time.perf_counter()
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    r, d, n = KUBAS_RADIUS, KUBAS_CENTRES, elements
    curve = CreateReevingCurve([[[0.0, 0.0], r, "L"], [[d, 0.0], r, "L"]], closedCurve=True, numberOfANCFnodes=n)
    ea = KUBAS_EA
    l_el = curve["totalLength"] / n
    # Axial damping: Kubas's b_tra = 20.5 N*s/m per 8 mm SDE is b_tra*l per unit strain rate;
    # bending: c_tor = 0.026 N*m/rad per 8 mm joint is EI = c_tor*l.
    template = ei.ObjectANCFCable2D(
        massPerLength=KUBAS_MASS,
        axialStiffness=ea,
        bendingStiffness=0.026 * 0.008,
        axialDamping=20.5 * 0.008,
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
        return KUBAS_TORQUE * min(t / RAMP, 1.0)

    mbs.AddLoad(ei.LoadCoordinate(markerNumber=rot_markers[0], load=0.0, loadUserFunction=drive))
    mbs.AddObject(ei.CoordinateSpringDamper(markerNumbers=[g_coord, rot_markers[1]], stiffness=0.0, damping=RESISTANCE))
    # Per metre of belt: Kubas's linear contact term c2 per body length (8 mm); damping his b
    # at the ramp value delta ~ 0.06 of a 0.15 mm penetration, per metre. Friction as in
    # Exudyn's belt-drive examples: bristle stiffness 0.2 of the contact stiffness and a
    # velocity penalty 1e-4 s times the bristle stiffness.
    k_contact = contact_scale * 6.5e5 / 0.008
    d_contact = math.sqrt(contact_scale) * 0.06 * 300.0 / 0.008
    k_friction = 0.2 * k_contact
    for pm in rigid_markers:
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

    def body_sensor(c: int, kind) -> int:
        return mbs.AddSensor(
            ei.SensorBody(bodyNumber=c, localPosition=[0.5 * l_el, 0, 0], storeInternal=True, outputVariableType=kind)
        )

    force = [body_sensor(c, exu.OutputVariableType.ForceLocal) for c in cables]
    where = [body_sensor(c, exu.OutputVariableType.Position) for c in cables]
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.timeIntegration.endTime = DURATION
    s.timeIntegration.numberOfSteps = int(round(DURATION / step))
    s.timeIntegration.generalizedAlpha.spectralRadius = 0.8
    s.timeIntegration.newton.useModifiedNewton = True
    s.timeIntegration.discontinuous.iterationTolerance = 0.1
    s.timeIntegration.discontinuous.maxIterations = 2
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = SAMPLE
    s.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    s.parallel.numberOfThreads = 1
    s.show.statistics = False
    t_run = time.perf_counter()
    ok = mbs.SolveDynamic(s, showHints=False)
    wall_run = time.perf_counter() - t_run
    if ok is False:
        print(f"   Exudyn reported a failed solve at {elements} elements, h = {step:g} s", flush=True)
    w = [mbs.GetSensorStoredData(sn) for sn in sensors]
    tt = w[0][:, 0]
    ten = np.stack([mbs.GetSensorStoredData(f)[:, 1] for f in force], axis=1)
    pos = np.stack([mbs.GetSensorStoredData(p)[:, 1:3] for p in where], axis=1)
    tight, slack = span_series(pos, ten)
    avg = averages(tt, tight, slack, np.abs(w[0][:, 3]), np.abs(w[1][:, 3]))
    setting = f"{elements} el, h {step * 1e6:g} us" + (f", contact x{contact_scale:g}" if contact_scale != 1 else "")
    return Rung("exudyn", setting, time.perf_counter() - t0, wall_run, steps=int(round(DURATION / step)), **avg)


# --- ladders and the matched-error table -----------------------------------------------------
def ladders(quick: bool, exudyn: str, node_counts: str = "75,150,300,600",
            rigid_counts: str = "75,150,300",
            wrap_counts: str = "50,75,100,150") -> dict[str, list[tuple[str, Callable[[], Rung]]]]:
    node = [int(v) for v in node_counts.split(",")][:2 if quick else None]
    rigid = [int(v) for v in rigid_counts.split(",")][:2 if quick else None]
    wrap = [int(v) for v in wrap_counts.split(",")][:2 if quick else None]
    pairs = [(int(a), float(b)) for a, b in (x.split(":") for x in exudyn.split(","))]
    out: dict[str, list[tuple[str, Callable[[], Rung]]]] = {
        "node": [(f"{n} el", lambda n=n: run_beltrs("node", f"{n} el", lambda: node_scene(n))) for n in node],
        "wrap": [
            (f"{n} el", lambda n=n: run_beltrs("wrap", f"{n} el", lambda: node_scene(n, "wrap"))) for n in wrap
        ],
        "rigid_body": [
            (f"{n} bodies", lambda n=n: run_beltrs("rigid_body", f"{n} bodies", lambda: rigid_scene(n))) for n in rigid
        ],
        "exudyn": [(f"{n} el", lambda n=n, h=h: run_exudyn(n, h)) for n, h in pairs],
    }
    return out


def table(rungs: list[Rung]) -> str:
    finest = {}
    for r in rungs:
        finest[r.code] = r  # the last rung of each code's first ladder is its finest mesh
    lines = [
        "| code | setting | wall (s) | walls (s) | run, first (s) | T1 (N) | T2 (N) | T1 - T2 (N) | error (N) "
        "| slip (%) | creep theory (%) | slip error (%) | vs own finest (%) |",
        "|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rungs:
        own = abs(r.slip - finest[r.code].slip)
        lines.append(
            f"| {r.code} | {r.setting} | {r.wall:.2f} | {', '.join(f'{w:.2f}' for w in r.walls)} "
            f"| {r.wall_run:.2f} | {r.t1:.1f} | {r.t2:.1f} | {r.diff:.1f} "
            f"| {r.err_diff:.2f} | {100 * r.slip:.4f} | {100 * r.creep:.4f} | {100 * r.err_slip:.4f} "
            f"| {100 * own:.4f} |"
        )
    return "\n".join(lines)


def matched(rungs: list[Rung], code: str) -> tuple[str, list[float]]:
    """For each Exudyn rung, the cheapest ``code`` rung at least as accurate in both errors."""
    mine = [r for r in rungs if r.code == code]
    lines = [
        f"| Exudyn rung | its errors (N; % slip) | wall (s) | cheapest {code} rung as accurate | its errors "
        "| wall (s) | ratio |",
        "|---|---|---:|---|---|---:|---:|",
    ]
    ratios = []
    for e in (r for r in rungs if r.code == "exudyn"):
        ok = [m for m in mine if m.err_diff <= e.err_diff and m.err_slip <= e.err_slip]
        if ok:
            b = min(ok, key=lambda m: m.wall)
            ratios.append(e.wall / b.wall)
            lines.append(
                f"| {e.setting} | {e.err_diff:.2f}; {100 * e.err_slip:.4f} | {e.wall:.1f} | {b.setting} "
                f"| {b.err_diff:.2f}; {100 * b.err_slip:.4f} | {b.wall:.2f} | {e.wall / b.wall:.1f}x |"
            )
        else:
            lines.append(
                f"| {e.setting} | {e.err_diff:.2f}; {100 * e.err_slip:.4f} | {e.wall:.1f} | none in the ladder | | | |"
            )
    return "\n".join(lines), ratios


def main(argv: Optional[list[str]] = None) -> list[Rung]:
    global RAMP, DURATION, WINDOW, BLOCK
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="two rungs per ladder (smoke run)")
    ap.add_argument("--codes", default="node,wrap,rigid_body,exudyn", help="comma-separated subset to run")
    ap.add_argument("--json", help="write the rungs to this JSON file")
    ap.add_argument("--exudyn", default="50:1e-4,75:1e-4",
                    help="Exudyn rungs as elements:step pairs, s (default 50:1e-4,75:1e-4)")
    ap.add_argument("--ramp", type=float, default=RAMP, help=f"torque ramp, s (default {RAMP})")
    ap.add_argument("--duration", type=float, default=DURATION, help=f"simulated time, s (default {DURATION})")
    ap.add_argument("--window", type=float, default=WINDOW, help=f"averaging window at the end, s (default {WINDOW})")
    ap.add_argument("--block", type=float, default=BLOCK, help=f"history blocks, s (default {BLOCK})")
    ap.add_argument("--node", default="75,150,300,600", help="node-model element counts")
    ap.add_argument("--rigid", default="75,150,300", help="rigid-body counts")
    ap.add_argument("--wrap", default="50,75,100,150", help="node-model element counts with wrap contact")
    ap.add_argument("--repeat", type=int, default=1,
                    help="run every rung this many times, the codes' rungs interleaved; walls are medians")
    args = ap.parse_args(argv)
    RAMP, DURATION, WINDOW, BLOCK = args.ramp, args.duration, args.window, args.block
    codes = args.codes.split(",")
    started = time.perf_counter()
    print(time.strftime("started %Y-%m-%d %H:%M:%S UTC", time.gmtime()) + f"; load average {os.getloadavg()}")
    print(f"case K: ramp {RAMP} s, run {DURATION} s, averages over the last {WINDOW} s; "
          f"exact T1 - T2 = M/r = {EXACT_DIFF:.1f} N", flush=True)
    # Interleaved: the first rung of every code, then the second, ..., so that a change of the
    # machine's load during the run falls on both codes; repeated ``--repeat`` times.
    chosen = {c: lad for c, lad in ladders(args.quick, args.exudyn, args.node, args.rigid, args.wrap).items()
              if c in codes}
    jobs = [(c, lad[i]) for i in range(max(map(len, chosen.values()), default=0))
            for c, lad in chosen.items() if i < len(lad)]
    order = {(c, name): k for k, (c, (name, _)) in enumerate(sorted(jobs, key=lambda j: codes.index(j[0])))}
    found: dict[tuple[str, str], Rung] = {}
    rungs: list[Rung] = []
    for rep in range(args.repeat):
        for code, (name, run) in jobs:
            r = run()
            key = (code, name)
            if key in found:  # the answers are deterministic: keep the first, add the wall
                found[key].walls.append(r.wall)
            else:
                r.walls = [r.wall]
                found[key] = r
            print(f"  [{rep + 1}/{args.repeat}, load {os.getloadavg()[0]:.1f}] {code} {r.setting}: wall {r.wall:.2f} s "
                  f"(run {r.wall_run:.2f}), T1 - T2 {r.diff:.1f} N, "
                  f"slip {100 * r.slip:.4f} % (creep theory {100 * r.creep:.4f} %)"
                  + (f"; {r.steps} steps x {r.nodes} nodes, {1e9 * r.wall_run / (r.steps * r.nodes):.0f} ns per "
                     "node-step" if r.nodes else ""), flush=True)
            if rep == 0:
                print("    per " + f"{BLOCK:g} s block (end s: T1 - T2 N, slip %): "
                      + ", ".join(f"{t:.3g}: {d:.1f}, {100 * sl:.3f}" for t, d, sl in r.history), flush=True)
            rungs = [found[k] for k in sorted(found, key=order.__getitem__)]
            for x in rungs:
                x.wall = float(np.median(x.walls))
            if args.json:  # after every rung, so that a long run interrupted keeps what it measured
                Path(args.json).write_text(json.dumps([dict(x.__dict__) for x in rungs], indent=1))
    print()
    print(table(rungs))
    for code in ("node", "wrap", "rigid_body"):
        if code in codes and "exudyn" in codes:
            text, ratios = matched(rungs, code)
            print()
            print(text)
    try:
        import exudyn

        version = exudyn.__version__
    except ImportError:
        version = "not installed"
    import beltrs

    print(time.strftime("ended %Y-%m-%d %H:%M:%S UTC", time.gmtime()) + f"; load average {os.getloadavg()}")
    print(f"\nbeltrs {beltrs.__version__}, Exudyn {version}; whole run {time.perf_counter() - started:.0f} s")
    if args.json:
        Path(args.json).write_text(json.dumps([dict(r.__dict__) for r in rungs], indent=1))
    return rungs


if __name__ == "__main__":
    main()

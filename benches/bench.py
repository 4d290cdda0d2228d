"""Speed benchmarks for the beltrs engine (a script that prints figures, not a test).

Run from the repository root, with beltrs installed (``pip install .``)::

    python benches/bench.py [--quick] [--repeats N] [--json out.json]

Options:
    --quick             fast smoke run for CI: 3 repeats and shorter runs, and the long
                        loop's stabilisation gets a budget of about 60 s (past it the loop
                        is stepped from its initial placement instead).
    --repeats N         timed repeats per figure; the median is reported (default 5, or 3
                        with --quick).
    --json PATH         also write the headline figures (and every sample) as JSON.
    --stabilise-budget S
                        wall-time budget, s, for stabilising the long loop (default: none,
                        or 60 with --quick).

What it measures (all on one thread: the engine is single-threaded and every call here is
made in turn from the main thread; timings use ``time.perf_counter``):

1. Node-steps per second of ``Simulation.step`` (no recording) on case H,
   ``beltrs.scenes.hustrulid_loop(89)``, after ``stabilise()``, frictionless and with pulley
   friction (mu_s = 0.3, mu_k = 0.25). node-steps/s = nodes * steps / wall.
2. The same on a long two-pulley loop of 5000 nodes (radius 0.5 m pulleys about 653 m
   apart, EA = 7.62 MN, 20 kg/m, horizontal gravity takeup of 5000 kg, contact stiffness
   1e8 N/m), after stabilising it; the stabilisation time is reported too. With no idlers
   the equilibrium is two deep catenaries (about 227 m of sag, the takeup pulled about
   229 m in); it is a load for the engine, not a realistic conveyor.
3. Wall time of thesis §6.4.2: case H stabilised, a 400 kN*m torque on the upper pulley for
   0.07 s, run for 3.6 s recording every 0.01 s; at the automatic step and at the
   thesis's fixed step of 0.00036 s. Thesis anchor: about 15 minutes on a 486
   (about 1e3 node-steps/s); target: under 0.1 s.
4. A per-stage profile (``Simulation.set_profiling``) of 5000 steps of case H with friction.
5. Issue 4 targets, node-steps/s of step(): (1) a frictionless loop of 1e4 nodes (the
   conveyor geometry below, 1 km, with idlers, no friction, no drive), (2) case H with
   friction (section 1), (3) a 5000-node, 500 m conveyor with carry and return idlers, head
   drive and tail gravity takeup (``bench_scenes.conveyor``), (4) case K with the node model
   (``bench_scenes.kubas_drive``). Targets 2e7 (1) and 1e7 (2-4).
6. The NumPy reference (``numpy_ref.py``) against beltrs on the same state: ``repeats``
   interleaved samples, the median rates and the median ratio (with its range).
7. Scaling: ns per node-step against nodes at one fixed step.
8. Wall time against simulated time for a 1 km conveyor start-up (1e4 nodes, drive torque
   ramped over 10 s; 1 s with --quick).
9. Peak memory of the process (``resource.getrusage`` ru_maxrss).
10. Friction cost (issue 11): case H loops of 1250 to 1e4 elements with pulley friction,
   unrelaxed, per-stage profile: ns per contact node of the pulley-contact and friction
   stages against ns per node of all other stages (a free node), and their ratio
   (target <= 5x). ``--friction-only`` runs just this section.

Tables give the median wall time, the spread of the repeats about it (fastest/slowest, %)
and, for throughput, the rate of the fastest repeat ("best"), which is the steadier figure
on a machine shared with other work. It ends with a Markdown table of the headline figures,
ready to paste into the README.
"""

from __future__ import annotations

import argparse
import resource
import json
import math
import os
import platform
import statistics
import sys
import time
from collections.abc import Callable
from contextlib import suppress
from typing import Any

import numpy as np

import beltrs
from beltrs import Belt, Drive, Friction, Pulley, Scene, Simulation, Takeup

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_scenes import conveyor, kubas_drive, strands_apart  # noqa: E402
from numpy_ref import compare_speed  # noqa: E402

FRICTION = Friction(static=0.3, kinetic=0.25)

# Thesis §6.4.2 run (Hustrulid): 3.6 s at 0.00036 s = 10 000 steps of 89 nodes took about
# 15 minutes on a 486, i.e. about 1e3 node-steps/s.
THESIS_DURATION = 3.6
THESIS_TIME_STEP = 0.00036
THESIS_WALL = 15 * 60.0
THESIS_TORQUE = 4e5
THESIS_PULSE = 0.07
TARGET_WALL = 0.1

LONG_NODES = 5000
LONG_RADIUS = 0.5


# --- small helpers ----------------------------------------------------------------------
def timed(fn: Callable[[], Any]) -> float:
    """Wall time of one call, s."""
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def summary(samples: list[float]) -> dict[str, Any]:
    """Median, min and max of wall-time samples, s."""
    return {
        "median": statistics.median(samples),
        "min": min(samples),
        "max": max(samples),
        "samples": samples,
    }


def si(x: float, unit: str = "") -> str:
    """A number with an SI prefix, e.g. 3.08e7 -> '30.8 M'."""
    for scale, prefix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if abs(x) >= scale:
            return f"{x / scale:.3g} {prefix}{unit}"
    return f"{x:.3g} {unit}".rstrip()


def seconds(x: float) -> str:
    """A duration in readable units."""
    if x < 1e-3:
        return f"{x * 1e6:.1f} us"
    if x < 1.0:
        return f"{x * 1e3:.2f} ms"
    if x < 120.0:
        return f"{x:.2f} s"
    return f"{x / 60:.1f} min"


def spread(s: dict[str, Any]) -> str:
    """'min-max' of a timing summary, as +/- percent about the median."""
    med = s["median"]
    return f"-{(med - s['min']) / med * 100:.0f}/+{(s['max'] - med) / med * 100:.0f} %"


def table(headers: list[str], rows: list[list[str]], markdown: bool = False) -> str:
    """Columns aligned; the first column left-aligned, the others right-aligned."""
    cells = [headers, *rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(headers))]

    def line(r: list[str]) -> str:
        parts = [r[i].ljust(w) if i == 0 else r[i].rjust(w) for i, w in enumerate(widths)]
        return ("| " + " | ".join(parts) + " |") if markdown else "  ".join(parts)

    if markdown:
        rule = "| " + " | ".join(("-" * w if i == 0 else "-" * (w - 1) + ":") for i, w in enumerate(widths)) + " |"
    else:
        rule = "  ".join("-" * w for w in widths)
    return "\n".join([line(headers), rule] + [line(r) for r in rows])


def heading(title: str) -> None:
    print(f"\n== {title} " + "=" * max(0, 76 - len(title)), flush=True)


# --- 1. case H throughput -----------------------------------------------------------------
def bench_case_h(friction: Friction | None, steps: int, repeats: int) -> dict[str, Any]:
    """node-steps/s of step() on stabilised case H."""
    sim = Simulation(beltrs.scenes.hustrulid_loop(89, friction=friction))
    stab_wall = timed(sim.stabilise)
    return {**throughput(sim, steps, repeats), "stabilise_wall": stab_wall}


# --- 2. long loop -----------------------------------------------------------------------
def long_loop_scene(nodes: int = LONG_NODES) -> Scene:
    """Two pulleys, radius 0.5 m, centres (0, 0) and (L, 0), with L chosen so that
    ``nodes`` elements are exactly 30 degrees of arc (r*pi/6 = 0.2618 m) each, the default
    rule; the second pulley is a horizontal gravity takeup."""
    element = LONG_RADIUS * math.pi / 6
    span = (nodes * element - 2 * math.pi * LONG_RADIUS) / 2  # 652.93 m for 5000 nodes
    common: dict[str, Any] = {"radius": LONG_RADIUS, "contact_stiffness": 1e8}
    return Scene(
        belt=Belt(axial_stiffness=7.62e6, mass_per_length=20.0, elements=nodes),
        pulleys=[
            Pulley(name="head", center=(0.0, 0.0), **common),
            Pulley(
                name="tail",
                center=(span, 0.0),
                takeup=Takeup(counterweight=5000.0, direction=(1.0, 0.0)),
                **common,
            ),
        ],
        gravity=9.81,
    )


def bench_long_loop(steps: int, repeats: int, budget: float | None) -> dict[str, Any]:
    """Stabilise the long loop (within ``budget`` s if given), then time step()."""
    scene = long_loop_scene()
    max_steps = 5_000_000  # Simulation.stabilise's default
    if budget is not None:
        # Turn the time budget into a step budget from a short relaxation on a throwaway copy.
        probe = Simulation(scene)
        n_probe = 2000
        t0 = time.perf_counter()
        with suppress(beltrs.BeltrsError):  # raised when not converged, as expected here
            probe.stabilise(max_steps=n_probe)
        rate = n_probe / (time.perf_counter() - t0)
        max_steps = max(n_probe, min(max_steps, int(budget * rate)))

    sim = Simulation(scene)
    info: dict[str, Any] = {
        "nodes": sim.nodes,
        "span": scene.pulleys[1].center[0],
        "path_length": sim.path_length,
        "element_length": sim.path_length / sim.nodes,
        "dt": sim.dt,
        "dt_cause": sim.dt_cause,
        "stages": sim.stages,
        "stabilise_max_steps": max_steps,
    }
    t0 = time.perf_counter()
    try:
        report = sim.stabilise(max_steps=max_steps)
        converged, relax_steps, residual = True, int(report["steps"]), float(report["residual"])
    except beltrs.BeltrsError as err:
        converged, relax_steps, residual = False, max_steps, None
        info["stabilise_error"] = str(err)
    stab_wall = time.perf_counter() - t0
    info.update(
        stabilise_wall=stab_wall,
        stabilise_converged=converged,
        stabilise_steps=relax_steps,
        stabilise_residual=residual,
        stabilise_node_steps_per_s=sim.nodes * relax_steps / stab_wall,
    )
    if converged:
        travel = sim.takeup_travel
        pos = sim.state()["node_position"]
        info["takeup_travel"] = float(travel[1])
        info["lowest_node_y"] = float(pos[:, 1].min())
        info["stepped_from"] = "equilibrium"
    else:
        sim = Simulation(scene)  # skip: step from the initial placement
        info["stepped_from"] = "initial placement"

    sim.step(200)  # warm-up, untimed
    walls = [timed(lambda: sim.step(steps)) for _ in range(repeats)]
    s = summary(walls)
    info.update(
        steps=steps,
        wall=s,
        node_steps_per_s=sim.nodes * steps / s["median"],
        best_node_steps_per_s=sim.nodes * steps / s["min"],
    )
    return info


# --- 3. thesis §6.4.2 ---------------------------------------------------------------------
def bench_thesis_run(time_step: float | None, repeats: int) -> dict[str, Any]:
    """Wall time of the §6.4.2 torque-pulse run (a fresh stabilised case H per repeat)."""
    walls = []
    peak_tension = peak_speed = math.nan
    for _ in range(repeats):
        sim = Simulation(beltrs.scenes.hustrulid_loop(89, time_step=time_step))
        sim.stabilise()
        sim.set_drive(0, Drive.pulse(THESIS_TORQUE, THESIS_PULSE, start=sim.time))
        t0 = time.perf_counter()
        res = sim.run(THESIS_DURATION, record_interval=0.01)
        walls.append(time.perf_counter() - t0)
        assert res.tension is not None
        peak_tension = float(res.tension.max())
        peak_speed = float(abs(res.pulley_speed[:, 0]).max())
    steps = round(THESIS_DURATION / sim.dt)
    s = summary(walls)
    return {
        "nodes": sim.nodes,
        "dt": sim.dt,
        "steps": steps,
        "samples_recorded": len(res),
        "wall": s,
        "node_steps_per_s": sim.nodes * steps / s["median"],
        "speedup_vs_thesis": THESIS_WALL / s["median"],
        "under_target": s["median"] < TARGET_WALL,
        "peak_tension": peak_tension,
        "peak_upper_pulley_speed": peak_speed,
    }


# --- 4. per-stage profile -----------------------------------------------------------------
def bench_profile(steps: int, repeats: int) -> dict[str, Any]:
    """Per-stage seconds (medians over repeats) for case H with friction."""
    sim = Simulation(beltrs.scenes.hustrulid_loop(89, friction=FRICTION))
    sim.stabilise()
    sim.step(1000)  # warm-up, untimed
    plain = [timed(lambda: sim.step(steps)) for _ in range(repeats)]
    profiled, stage_samples = [], []
    for _ in range(repeats):
        sim.set_profiling(True)  # zeroes the counters
        profiled.append(timed(lambda: sim.step(steps)))
        stage_samples.append(sim.profile())
    sim.set_profiling(False)
    stages = {k: statistics.median(p[k] for p in stage_samples) for k in sim.stages}
    return {
        "nodes": sim.nodes,
        "steps": steps,
        "stages": stages,
        "wall_plain": summary(plain),
        "wall_profiled": summary(profiled),
    }


# --- 5-9. targets of issue 4 ------------------------------------------------------------------
def peak_memory_mb() -> float:
    """Peak resident memory of this process so far, MB (getrusage ru_maxrss, kB on Linux)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def throughput(sim: Simulation, steps: int, repeats: int) -> dict[str, Any]:
    """node-steps/s of step() (median and best of ``repeats``)."""
    sim.step(max(10, steps // 10))  # warm-up, untimed
    walls = [timed(lambda: sim.step(steps)) for _ in range(repeats)]
    s = summary(walls)
    return {
        "nodes": sim.nodes,
        "steps": steps,
        "dt": sim.dt,
        "dt_cause": sim.dt_cause,
        "stages": sim.stages,
        "wall": s,
        "node_steps_per_s": sim.nodes * steps / s["median"],
        "best_node_steps_per_s": sim.nodes * steps / s["min"],
    }


def bench_frictionless_loop(nodes: int, steps: int, repeats: int) -> dict[str, Any]:
    """(1) The conveyor geometry (1 km, 0.2 m elements at 1e4 nodes) with idlers but no
    friction and no drive, stepped from its initial placement (it settles on the idlers)."""
    scene = conveyor(nodes * 0.1, nodes, friction=None, drive_torque=0.0)
    return throughput(Simulation(scene), steps, repeats)


def bench_conveyor(nodes: int, steps: int, repeats: int) -> dict[str, Any]:
    """(3) Conveyor with idlers, head drive and tail takeup, stabilised (tolerance 1e-3),
    then stepped while the drive ramps up."""
    length = nodes * 0.1
    sim = Simulation(conveyor(length, nodes))
    t0 = time.perf_counter()
    rep = sim.stabilise(tolerance=1e-3, max_steps=300_000)
    stab = time.perf_counter() - t0
    out = throughput(sim, steps, repeats)
    out.update(
        idlers=len(sim.scene.idlers),
        stabilise_wall=stab,
        stabilise_steps=rep["steps"],
        strand_gap=strands_apart(sim.state()["node_position"], length, 0.4),
    )
    return out


def bench_kubas(steps: int, repeats: int) -> dict[str, Any]:
    """(4) Case K with the node model (150 elements, friction, drive and load)."""
    sim = Simulation(kubas_drive())
    sim.stabilise()
    sim.step(int(0.2 / sim.dt))  # into the torque ramp: friction working
    return throughput(sim, steps, repeats)


def bench_startup(duration: float, chunk: float) -> dict[str, Any]:
    """1 km conveyor (1e4 nodes of 0.2 m), stabilised, drive torque ramped over 10 s: wall
    time against simulated time, run in chunks."""
    sim = Simulation(conveyor(1000.0, 10_000))
    t0 = time.perf_counter()
    rep = sim.stabilise(tolerance=1e-3, max_steps=300_000)
    stab = time.perf_counter() - t0
    rows = []
    wall = 0.0
    while sim.time < duration - 0.5 * chunk:
        res = sim.run(chunk, record_interval=0.05, tension=False, node_position=False, node_velocity=False)
        wall += res.wall_time
        rows.append({"time": sim.time, "wall": wall, "belt_speed": float(res.pulley_speed[-1, 0] * 0.4)})
    return {
        "nodes": sim.nodes,
        "dt": sim.dt,
        "dt_cause": sim.dt_cause,
        "stabilise_wall": stab,
        "stabilise_steps": rep["steps"],
        "rows": rows,
        "strand_gap": strands_apart(sim.state()["node_position"], 1000.0, 0.4),
        "max_tension": float(sim.tensions().max()),
    }


def bench_scaling(sizes: list[int], steps: int) -> list[dict[str, Any]]:
    """Cost per node-step against nodes at one fixed step (the smallest stable one)."""
    scenes = [conveyor(n * 0.1, n, friction=None, drive_torque=0.0) for n in sizes]
    dt = min(Simulation(sc).dt for sc in scenes)
    out = []
    for n, sc in zip(sizes, scenes):
        sc.solver = beltrs.Solver(time_step=dt)
        r = throughput(Simulation(sc), max(20, steps * sizes[0] // n), 3)
        out.append({"nodes": n, "dt": dt, "ns_per_node_step": 1e9 / r["best_node_steps_per_s"], **r})
    return out


def bench_numpy(repeats: int) -> list[dict[str, Any]]:
    """beltrs against benches/numpy_ref.py on the same state (case H 89 nodes; a 1e4-node
    loop without idlers): ``repeats`` interleaved samples (each times NumPy, then beltrs,
    from the current state); the medians of each rate and of the per-sample ratios."""
    sim = Simulation(beltrs.scenes.hustrulid_loop(89))
    sim.stabilise()
    scene = conveyor(1000.0, 10_000, friction=None, drive_torque=0.0)
    scene.idlers = []
    out = []
    for case, s, steps in (("case H, 89 nodes", sim, 2000), ("loop, 1e4 nodes, no idlers", Simulation(scene), 200)):
        samples = [compare_speed(s, steps) for _ in range(repeats)]
        row: dict[str, Any] = {"case": case, "nodes": samples[0]["nodes"], "samples": samples}
        for key in ("beltrs_node_steps_per_s", "numpy_node_steps_per_s", "ratio"):
            row[key] = statistics.median(r[key] for r in samples)
        row["ratio_min"] = min(r["ratio"] for r in samples)
        row["ratio_max"] = max(r["ratio"] for r in samples)
        out.append(row)
    return out



def contact_nodes(sim: Simulation, scene: Scene) -> int:
    """Nodes touching a pulley now: inside its radius (the penalty acts on penetration)."""
    st = sim.state()
    x = st["node_position"]
    count = 0
    for j, p in enumerate(scene.pulleys):
        c = np.asarray(p.center, dtype=float)
        if p.takeup is not None:
            c = c + st["takeup_travel"][j] * np.asarray(p.takeup.direction, dtype=float)
        count += int(np.count_nonzero(np.hypot(*(x - c).T) < p.radius))
    return count


def bench_friction_cost(sizes: list[int], steps: int) -> list[dict[str, Any]]:
    """Issue 11: the cost of a contact node with friction against a free node, in one run.

    Case H loops of ``sizes`` elements with pulley friction (mu_s 0.3, mu_k 0.25), stepped
    unrelaxed from their placement (the settling belt slips on both pulleys: the friction
    solve's worst case). Per-stage profile over ``steps`` steps: the pulley-contact and
    pulley-friction stages per contact node, every other stage per node (a free node's
    cost), and the ratio (free + contact + friction)/free for a node in contact."""
    out = []
    for n in sizes:
        scene = beltrs.scenes.hustrulid_loop(n, friction=FRICTION)
        sim = Simulation(scene)
        sim.step(200)  # into contact and slipping, untimed
        # Three profiled rounds; each stage's fastest round (the machine is shared: the
        # minimum is the cost without preemption).
        rounds, counts = [], []
        chunk = max(1, steps // 10)
        for _ in range(3):
            sim.set_profiling(True)  # zeroes the counters
            for _ in range(10):
                sim.step(chunk)
                counts.append(contact_nodes(sim, scene))
            rounds.append(sim.profile())
        sim.set_profiling(False)
        prof = {k: min(p[k] for p in rounds) for k in rounds[0]}
        done = 10 * chunk
        cn = statistics.mean(counts)
        contact = prof.get("pulley_contact", 0.0)
        friction = prof.get("pulley_friction", 0.0)
        free = sum(prof.values()) - contact - friction
        free_ns = 1e9 * free / (done * sim.nodes)
        contact_ns = 1e9 * contact / (done * cn)
        friction_ns = 1e9 * friction / (done * cn)
        out.append(
            {
                "nodes": sim.nodes,
                "contact_nodes": cn,
                "steps": done,
                "free_ns": free_ns,
                "contact_ns": contact_ns,
                "friction_ns": friction_ns,
                "ratio": (free_ns + contact_ns + friction_ns) / free_ns,
            }
        )
    return out

def print_friction_cost(rows: list[dict[str, Any]]) -> None:
    print(
        table(
            ["nodes", "contact nodes", "free node ns", "contact ns/c.node", "friction ns/c.node", "c.node/free"],
            [
                [
                    str(r["nodes"]),
                    f"{r['contact_nodes']:.0f}",
                    f"{r['free_ns']:.1f}",
                    f"{r['contact_ns']:.1f}",
                    f"{r['friction_ns']:.1f}",
                    f"{r['ratio']:.2f}x",
                ]
                for r in rows
            ],
        )
    )
    print("target (issue 11): a contact node with friction costs <= 5x a free node")


# --- report -------------------------------------------------------------------------------
def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="fast smoke run (CI)")
    ap.add_argument("--repeats", type=int, default=None, help="timed repeats (default 5, 3 with --quick)")
    ap.add_argument("--json", metavar="PATH", help="write the figures as JSON to PATH")
    ap.add_argument(
        "--stabilise-budget",
        type=float,
        default=None,
        metavar="S",
        help="wall budget for stabilising the long loop, s (default none, 60 with --quick)",
    )
    ap.add_argument(
        "--friction-only",
        action="store_true",
        help="run only section 10 (friction cost per contact node) and exit",
    )
    args = ap.parse_args(argv)
    repeats = args.repeats if args.repeats is not None else (3 if args.quick else 5)
    if repeats < 1:
        ap.error("--repeats must be >= 1")
    budget = args.stabilise_budget if args.stabilise_budget is not None else (60.0 if args.quick else None)
    h_steps = 5000 if args.quick else 20000
    long_steps = 500 if args.quick else 3000
    profile_steps = 5000

    friction_sizes = [1250, 2500, 5000, 10_000]
    friction_steps = 500 if args.quick else 2000
    if args.friction_only:
        heading("10. Friction cost per contact node (case H loops with friction, unrelaxed)")
        print_friction_cost(bench_friction_cost(friction_sizes, friction_steps))
        return 0

    started = time.perf_counter()
    meta = {
        "beltrs": beltrs.__version__,
        "python": platform.python_version(),
        "platform": platform.platform(),
        "machine": platform.machine(),
        "processor": platform.processor(),
        "quick": args.quick,
        "repeats": repeats,
    }
    print(f"beltrs {meta['beltrs']}  Python {meta['python']}  {meta['platform']}")
    print(f"mode: {'quick' if args.quick else 'full'}, {repeats} repeats, medians reported, one thread")
    if hasattr(os, "getloadavg"):
        load, cpus = os.getloadavg()[0], os.cpu_count() or 1
        meta.update(load_average=load, cpus=cpus)
        if load > 0.5:
            print(f"note: load average {load:.2f} on {cpus} CPUs at start: other work may inflate the timings")

    # 1. case H
    heading("1. Case H (89 nodes), step() without recording, after stabilise()")
    case_h = bench_case_h(None, h_steps, repeats)
    case_hf = bench_case_h(FRICTION, h_steps, repeats)
    rows = []
    for name, r in (("frictionless", case_h), ("friction 0.3/0.25", case_hf)):
        rows.append(
            [
                name,
                str(r["nodes"]),
                str(r["steps"]),
                f"{r['dt'] * 1e3:.4f}",
                seconds(r["wall"]["median"]),
                spread(r["wall"]),
                si(r["node_steps_per_s"]),
                si(r["best_node_steps_per_s"]),
                f"{r['wall']['median'] / r['steps'] * 1e6:.2f}",
            ]
        )
    print(
        table(["case H", "nodes", "steps", "dt ms", "median wall", "spread", "node-steps/s", "best", "us/step"], rows)
    )
    print(f"stages: {', '.join(case_hf['stages'])}")

    # 2. long loop
    heading(f"2. Long loop ({LONG_NODES} nodes), step() without recording")
    long = bench_long_loop(long_steps, repeats, budget)
    print(
        f"span {long['span']:.1f} m, path {long['path_length']:.2f} m, element {long['element_length']:.4f} m, "
        f"dt {long['dt'] * 1e3:.4f} ms ({long['dt_cause']})"
    )
    if long["stabilise_converged"]:
        print(
            f"stabilise: {seconds(long['stabilise_wall'])}, {long['stabilise_steps']} relaxation steps "
            f"({si(long['stabilise_node_steps_per_s'])} node-steps/s), residual {long['stabilise_residual']:.2e}; "
            f"takeup travel {long['takeup_travel']:.1f} m, lowest node y {long['lowest_node_y']:.1f} m"
        )
    else:
        print(
            f"stabilise: NOT converged within {long['stabilise_max_steps']} steps "
            f"({seconds(long['stabilise_wall'])}); stepping from the initial placement instead"
        )
    print(
        table(
            ["long loop", "nodes", "steps", "median wall", "spread", "node-steps/s", "best", "us/step"],
            [
                [
                    f"from {long['stepped_from']}",
                    str(long["nodes"]),
                    str(long["steps"]),
                    seconds(long["wall"]["median"]),
                    spread(long["wall"]),
                    si(long["node_steps_per_s"]),
                    si(long["best_node_steps_per_s"]),
                    f"{long['wall']['median'] / long['steps'] * 1e6:.1f}",
                ]
            ],
        )
    )

    # 3. thesis §6.4.2
    heading("3. Thesis §6.4.2: 400 kN*m on the upper pulley for 0.07 s, run 3.6 s")
    auto = bench_thesis_run(None, repeats)
    fixed = bench_thesis_run(THESIS_TIME_STEP, repeats)
    rows = []
    for name, r in (("automatic dt", auto), ("thesis dt 0.36 ms", fixed)):
        rows.append(
            [
                name,
                f"{r['dt'] * 1e3:.4f}",
                str(r["steps"]),
                seconds(r["wall"]["median"]),
                spread(r["wall"]),
                si(r["node_steps_per_s"]),
                f"{r['speedup_vs_thesis']:.3g}x",
                "yes" if r["under_target"] else "NO",
                f"{r['peak_tension'] / 1e3:.1f}",
            ]
        )
    rows.append(["thesis (486)", "0.3600", "10000", "~15 min", "", si(89 * 10000 / THESIS_WALL), "1x", "", ""])
    print(
        table(
            ["run", "dt ms", "steps", "median wall", "spread", "node-steps/s", "vs 486", "< 0.1 s", "peak T kN"],
            rows,
        )
    )
    print(f"record_interval 0.01 s: {auto['samples_recorded']} / {fixed['samples_recorded']} samples recorded")
    print("anchor: about 15 minutes on a 486 (~1e3 node-steps/s); target under 0.1 s")

    # 4. profile
    heading(f"4. Profile: case H with friction, {profile_steps} steps")
    prof = bench_profile(profile_steps, repeats)
    wall = prof["wall_profiled"]["median"]
    plain = prof["wall_plain"]["median"]
    total = sum(prof["stages"].values())
    steps, node_steps = prof["steps"], prof["nodes"] * prof["steps"]

    def prof_row(name: str, v: float, of_stages: str, of_wall: str) -> list[str]:
        return [name, f"{v * 1e3:.3f}", f"{v / steps * 1e6:.3f}", f"{v / node_steps * 1e9:.1f}", of_stages, of_wall]

    rows = [prof_row(k, v, f"{v / total * 100:.1f} %", f"{v / wall * 100:.1f} %") for k, v in prof["stages"].items()]
    rows.append(prof_row("sum of stages", total, "100.0 %", f"{total / wall * 100:.1f} %"))
    rows.append(prof_row("outside stages", wall - total, "", f"{(wall - total) / wall * 100:.1f} %"))
    rows.append(prof_row("wall, profiling on", wall, "", "100.0 %"))
    rows.append(prof_row("wall, profiling off", plain, "", f"{plain / wall * 100:.1f} %"))
    print(table(["stage", "ms", "us/step", "ns/node-step", "share of stages", "share of wall"], rows))
    print(
        f"profiling costs +{(wall / plain - 1) * 100:.0f} % (two clock reads per stage per step, counted partly in the "
        "stages); 'outside stages' is the integration, bookkeeping and the timer calls themselves"
    )

    # 5-9. issue 4 targets
    heading("5. Throughput targets (single thread, step() without recording)")
    loop = bench_frictionless_loop(10_000, 300 if args.quick else 2000, repeats)
    conv = bench_conveyor(5000, 300 if args.quick else 2000, repeats)
    kub = bench_kubas(2000 if args.quick else 20000, repeats)
    rows = []
    for name, r, target in (
        ("(1) frictionless loop + idlers, 1e4 nodes", loop, 2e7),
        ("(2) case H with friction, 89 nodes", case_hf, 1e7),
        ("(3) conveyor, idlers + drive + friction, 5000 nodes", conv, 1e7),
        ("(4) case K (node model), 150 nodes", kub, 1e7),
    ):
        rows.append(
            [name, f"{r['dt'] * 1e6:.2f}", si(r["node_steps_per_s"]), si(r["best_node_steps_per_s"]), si(target),
             "yes" if r["node_steps_per_s"] >= target else "NO"]
        )
    print(table(["scene", "dt us", "node-steps/s", "best", "target", "met"], rows))
    print(f"conveyor: {conv['idlers']} idlers, stabilised in {seconds(conv['stabilise_wall'])} "
          f"({conv['stabilise_steps']} steps, tolerance 1e-3); strands at least {conv['strand_gap']:.3f} m apart; "
          f"dt limited by {conv['dt_cause']}")
    print(f"loop: dt limited by {loop['dt_cause']}")

    heading("6. NumPy reference (benches/numpy_ref.py), same state, same scene, interleaved repeats")
    npr = bench_numpy(repeats)
    print(table(["case", "beltrs node-steps/s (median)", "NumPy node-steps/s (median)", "ratio (median)",
                 "ratio range"],
                [[r["case"], si(r["beltrs_node_steps_per_s"]), si(r["numpy_node_steps_per_s"]),
                  f"{r['ratio']:.0f}x", f"{r['ratio_min']:.0f}-{r['ratio_max']:.0f}x"] for r in npr]))

    heading("7. Scaling with nodes (fixed dt, conveyor loop without friction)")
    sizes = [1250, 2500, 5000] if args.quick else [1250, 2500, 5000, 10000, 20000, 40000]
    scal = bench_scaling(sizes, 400 if args.quick else 4000)
    print(table(["nodes", "steps", "wall", "node-steps/s (best)", "ns/node-step"],
                [[str(r["nodes"]), str(r["steps"]), seconds(r["wall"]["min"]), si(r["best_node_steps_per_s"]),
                  f"{r['ns_per_node_step']:.1f}"] for r in scal]))

    heading("8. 1 km conveyor start-up (1e4 nodes), drive torque ramped over 10 s")
    start = bench_startup(1.0 if args.quick else 10.0, 0.5 if args.quick else 1.0)
    print(f"dt {start['dt'] * 1e6:.2f} us ({start['dt_cause']}); stabilise {seconds(start['stabilise_wall'])} "
          f"({start['stabilise_steps']} steps); strands at least {start['strand_gap']:.3f} m apart at the end")
    print(table(["simulated s", "wall s", "wall / simulated", "belt speed m/s"],
                [[f"{r['time']:.1f}", f"{r['wall']:.2f}", f"{r['wall'] / r['time']:.2f}", f"{r['belt_speed']:.3f}"]
                 for r in start["rows"]]))

    heading("10. Friction cost per contact node (case H loops with friction, unrelaxed)")
    fric = bench_friction_cost(friction_sizes, friction_steps)
    print_friction_cost(fric)

    heading("9. Peak memory")
    mem = peak_memory_mb()
    print(f"peak resident memory of this process (getrusage ru_maxrss): {mem:.0f} MB")

    # summary
    elapsed = time.perf_counter() - started
    heading("Summary (Markdown)")
    md_rows = [
        ["Case H, 89 nodes, frictionless: step()", f"{si(case_h['node_steps_per_s'])} node-steps/s"],
        ["Case H, 89 nodes, friction 0.3/0.25: step()", f"{si(case_hf['node_steps_per_s'])} node-steps/s"],
        [f"Long loop, {long['nodes']} nodes: step()", f"{si(long['node_steps_per_s'])} node-steps/s"],
        [
            f"Long loop, {long['nodes']} nodes: stabilise()",
            (
                f"{seconds(long['stabilise_wall'])} ({long['stabilise_steps']} steps)"
                if long["stabilise_converged"]
                else f"not converged in {seconds(long['stabilise_wall'])}"
            ),
        ],
        [
            f"Thesis §6.4.2 run, automatic dt ({auto['steps']} steps)",
            f"{seconds(auto['wall']['median'])} ({auto['speedup_vs_thesis']:.3g}x the 486)",
        ],
        [
            f"Thesis §6.4.2 run, dt 0.36 ms ({fixed['steps']} steps)",
            f"{seconds(fixed['wall']['median'])} ({fixed['speedup_vs_thesis']:.3g}x the 486)",
        ],
        ["Thesis §6.4.2 on a 486 (Hustrulid)", "~15 min (~1e3 node-steps/s)"],
        ["(1) Frictionless loop with idlers, 1e4 nodes", f"{si(loop['node_steps_per_s'])} node-steps/s"],
        ["(3) Conveyor, 5000 nodes, idlers + drive + friction", f"{si(conv['node_steps_per_s'])} node-steps/s"],
        ["(4) Case K, 150 nodes, node model", f"{si(kub['node_steps_per_s'])} node-steps/s"],
        *[[f"beltrs / NumPy, {r['case']} (median of {repeats})", f"{r['ratio']:.0f}x"] for r in npr],
        [f"1 km start-up, 1e4 nodes, {start['rows'][-1]['time']:.0f} s simulated",
         f"{start['rows'][-1]['wall']:.1f} s wall"],
        ["Peak memory (whole bench)", f"{mem:.0f} MB"],
    ]
    print(table(["Benchmark (one thread, median)", "Figure"], md_rows, markdown=True))
    print(f"\nbench wall time: {seconds(elapsed)}")

    if args.json:
        out = {
            "meta": {**meta, "bench_wall": elapsed},
            "headline": {
                "case_h_node_steps_per_s": case_h["node_steps_per_s"],
                "case_h_friction_node_steps_per_s": case_hf["node_steps_per_s"],
                "long_loop_node_steps_per_s": long["node_steps_per_s"],
                "long_loop_stabilise_wall": long["stabilise_wall"],
                "long_loop_stabilise_converged": long["stabilise_converged"],
                "thesis_run_wall_auto_dt": auto["wall"]["median"],
                "thesis_run_wall_fixed_dt": fixed["wall"]["median"],
                "thesis_run_steps_auto_dt": auto["steps"],
                "thesis_run_steps_fixed_dt": fixed["steps"],
            },
            "case_h": case_h,
            "case_h_friction": case_hf,
            "long_loop": long,
            "thesis_6_4_2": {"automatic_dt": auto, "fixed_dt": fixed, "thesis_wall_486": THESIS_WALL},
            "profile": prof,
            "frictionless_loop": loop,
            "conveyor": conv,
            "case_k": kub,
            "numpy": npr,
            "scaling": scal,
            "startup_1km": start,
            "friction_cost": fric,
            "peak_memory_mb": mem,
        }
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(out, fh, indent=2)
        print(f"figures written to {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Cost of the pulley contact (issue 12): node-steps/s of ``Simulation.step`` for the
scenes of benches/bench.py sections 1 (case H, frictionless and with friction) and 5 (the
1e4-node loop, the 5000-node conveyor, case K), in one process. Run it with two builds
(e.g. two venvs) in turn, several times, to compare them on a shared machine:

    python benches/ripple_cost.py [--repeats 5] [--quick]

Prints one line per scene: nodes, dt, median and best node-steps/s; then the same build's
cost of wrap contact (``belt.pulley_contact = "wrap"``) against nodal contact on case H with
friction and on the 5000-node conveyor, interleaved repeats in one process.
"""

from __future__ import annotations

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(__file__))
import bench  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--wrap-only", action="store_true", help="only the wrap/nodes comparison")
    args = ap.parse_args(argv)
    r = args.repeats
    q = args.quick
    if args.wrap_only:
        wrap_cost(r, q)
        return 0
    rows = [
        ("1 case H frictionless", bench.bench_case_h(None, 5000 if q else 20000, r)),
        ("1 case H friction", bench.bench_case_h(bench.FRICTION, 5000 if q else 20000, r)),
        ("5 loop 1e4 nodes", bench.bench_frictionless_loop(10_000, 300 if q else 2000, r)),
        ("5 conveyor 5000 nodes", bench.bench_conveyor(5000, 300 if q else 2000, r)),
        ("5 case K node model", bench.bench_kubas(2000 if q else 20000, r)),
    ]
    import beltrs

    print(f"beltrs {beltrs.__file__}  load {os.getloadavg()[0]:.1f}")
    for name, x in rows:
        print(f"{name:24s} nodes {x['nodes']:6d} dt {x['dt'] * 1e6:9.3f} us  median {x['node_steps_per_s']:.4g}"
              f"  best {x['best_node_steps_per_s']:.4g} node-steps/s")
    if "pulley_contact" in beltrs.Belt.__dataclass_fields__:
        wrap_cost(r, q)
    return 0


def wrap_cost(repeats: int, quick: bool) -> None:
    """node-steps/s with nodal and with wrap contact, same scenes, interleaved."""
    from dataclasses import replace

    import beltrs
    from bench_scenes import conveyor

    scenes = {
        "case H friction": (beltrs.scenes.hustrulid_loop(89, friction=bench.FRICTION), 5000 if quick else 20000),
        "conveyor 5000 nodes": (conveyor(500.0, 5000), 300 if quick else 2000),
    }
    for name, (scene, steps) in scenes.items():
        sims = {}
        for contact in ("nodes", "wrap"):
            sim = beltrs.Simulation(replace(scene, belt=replace(scene.belt, pulley_contact=contact)))
            sim.stabilise(tolerance=1e-3, max_steps=300_000)
            sim.step(steps // 10)
            sims[contact] = sim
        walls = {c: [] for c in sims}
        for _ in range(repeats):
            for c, sim in sims.items():
                walls[c].append(bench.timed(lambda: sim.step(steps)))
        rate = {c: sims[c].nodes * steps / min(w) for c, w in walls.items()}
        print(f"{name:24s} best node-steps/s: nodes {rate['nodes']:.4g}, wrap {rate['wrap']:.4g}, "
              f"wrap/nodes {rate['wrap'] / rate['nodes']:.3f}")


if __name__ == "__main__":
    sys.exit(main())

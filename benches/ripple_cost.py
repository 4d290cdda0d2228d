"""Cost of the pulley contact (issue 12): node-steps/s of ``Simulation.step`` for the
scenes of benches/bench.py sections 1 (case H, frictionless and with friction) and 5 (the
1e4-node loop, the 5000-node conveyor, case K), in one process. Run it with two builds
(e.g. two venvs) in turn, several times, to compare them on a shared machine:

    python benches/ripple_cost.py [--repeats 5] [--quick]

Prints one line per scene: nodes, dt, median and best node-steps/s.
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
    args = ap.parse_args(argv)
    r = args.repeats
    q = args.quick
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
    return 0


if __name__ == "__main__":
    sys.exit(main())

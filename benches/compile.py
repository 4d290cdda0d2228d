"""Compile time per element (a script that prints figures, not a test).

Run from the repository root, with beltrs installed::

    python benches/compile.py [--repeats N] [--sizes 1000,10000,...]

Compiles a two-pulley loop (radius 1 m, centres 4 km apart, so that the element count is
set by ``belt.elements``) at each size and prints the median wall time per element, µs.
Compiling should be linear in the element count: the figure should not grow with the size.
Before the chord placement was rewritten (docs/runtime.md, "Scale guards") it was
100-180 µs per element.
"""

from __future__ import annotations

import argparse
import statistics
import time

from beltrs import _beltrs


def scene(elements: int) -> dict:
    return {
        "belt": {"elements": elements},
        "pulleys": [{"center": [0.0, 0.0], "radius": 1.0}, {"center": [0.0, 4000.0], "radius": 1.0}],
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--sizes", default="10000,30000,100000,300000,1000000")
    args = ap.parse_args()
    print(f"{'elements':>10} {'µs/element':>11} {'total s':>8}")
    for n in (int(x) for x in args.sizes.split(",")):
        walls = []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            _beltrs.Simulation(scene(n))
            walls.append(time.perf_counter() - t0)
        wall = statistics.median(walls)
        print(f"{n:>10} {wall / n * 1e6:>11.2f} {wall:>8.2f}", flush=True)


if __name__ == "__main__":
    main()

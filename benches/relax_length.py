"""Static relaxation of the 300 m builder conveyor (tests/conveyor_300.py) against the belt's
element or body length: FIRE steps, restarts and wall time of ``Simulation.stabilise``
(docs/stability.md, "The rigid-body belt's relaxation and its body length"). Prints one
JSON line per length; a script, not a test.

    python benches/relax_length.py                         # rigid body, default length
    python benches/relax_length.py 0.1 0.1185 0.15 0.209   # several body lengths, m
    python benches/relax_length.py 0.209 --friction        # relaxing with friction
    python benches/relax_length.py default --formulation node_kelvin_voigt
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
import warnings

import beltrs

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
from conveyor_300 import conveyor_300  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("lengths", nargs="*", default=["default"], help="element/body lengths, m, or 'default'")
    ap.add_argument("--formulation", default="rigid_body")
    ap.add_argument("--friction", action="store_true", help="stabilise(friction=True)")
    ap.add_argument("--tolerance", type=float, default=1e-5)
    ap.add_argument("--max-steps", type=int, default=2_000_000)
    args = ap.parse_args()
    for length in args.lengths:
        kw = {} if length == "default" else {"element_length": float(length)}
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", beltrs.AccuracyWarning)  # lengths above the rule
            scene = conveyor_300(ramp=10.0, formulation=args.formulation, **kw).scene()
        sim = beltrs.Simulation(scene)
        t0 = time.perf_counter()
        rep = sim.stabilise(friction=args.friction, tolerance=args.tolerance, max_steps=args.max_steps,
                            progress=False)
        wall = time.perf_counter() - t0
        print(json.dumps(dict(length=length, formulation=args.formulation, friction=args.friction,
                              elements=sim.elements, dt=sim.dt, steps=rep["steps"], resets=rep["resets"],
                              residual=rep["residual"], wall=round(wall, 2))), flush=True)


if __name__ == "__main__":
    main()

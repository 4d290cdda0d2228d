"""Cost of wrap contact on the rolls (``belt.idler_contact = "wrap"``, issue 12) against the
segment contact: the 300 m conveyor of benches/ripple_drive.py (2877 nodes, 350 rolls; wrap
contact on the drums, spans placed in their sag, running start), 0.2 s of running per
repeat, the two contacts interleaved in one process. Prints the wall time per 0.2 s
(median, best) of each and their ratio. A script, not a test.

    python benches/roll_wrap_cost.py [--repeats 5]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import time

import numpy as np

import beltrs
from beltrs.conveyor import Conveyor, DriveSpec


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args(argv)
    sims = {}
    for kind in ("segment", "wrap"):
        curve = beltrs.StartCurve("harrison", speed=2.0, ramp=4.0)
        c = Conveyor(profile=[(0.0, 0.0), (300.0, 0.0)], belt="ST1250", capacity=500.0, speed=2.0, start="running",
                     drives=[DriveSpec("head", start_curve=curve)])
        s = c.scene()
        s = replace(s, belt=replace(s.belt, pulley_contact="wrap", idler_contact=kind),
                    initial=replace(s.initial, sag=True))
        sims[kind] = beltrs.Simulation(s)
        sims[kind].run(0.05, record_interval=0.01, tension=False, node_position=False, node_velocity=False)
    walls: dict = {k: [] for k in sims}
    for _ in range(args.repeats):
        for k, sim in sims.items():
            w = time.perf_counter()
            sim.run(0.2, record_interval=0.01, tension=False, node_position=False, node_velocity=False)
            walls[k].append(time.perf_counter() - w)
    for k, v in walls.items():
        print(f"{k}: {sims[k].nodes} nodes, step {sims[k].dt * 1e6:.2f} us, "
              f"wall per 0.2 s median {np.median(v):.3f} s, best {min(v):.3f} s")
    print(f"wrap / segment: median {np.median(walls['wrap']) / np.median(walls['segment']):.3f}, "
          f"best {min(walls['wrap']) / min(walls['segment']):.3f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

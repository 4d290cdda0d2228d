"""Does the design start's sag placement close on every builder conveyor? (issue 12, roll
wrap as the builders' default.) Builds level and 5 % inclined builder conveyors (ST1250)
of ``lo`` to ``hi`` m every ``step`` m, at rest and running, at four capacity/speed pairs,
with the given idler contact, and constructs each simulation (the placement runs there).
Prints each failure (length, start, capacity, speed, rise, the error) and the count. A
script, not a test (tests/test_roll_wrap.py keeps the layouts it found).

    python benches/placement_sweep.py wrap 20 320 0.5
    python benches/placement_sweep.py segment 20 320 0.5
"""

from __future__ import annotations

import argparse
from dataclasses import replace

import numpy as np

import beltrs
from beltrs.conveyor import Conveyor, DriveSpec

CASES = ((500.0, 2.0, 0.0), (1500.0, 3.0, 0.0), (300.0, 1.5, 0.05), (800.0, 4.0, 0.0))  # t/h, m/s, rise


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("idler_contact", choices=["segment", "wrap"])
    ap.add_argument("lo", type=float)
    ap.add_argument("hi", type=float)
    ap.add_argument("step", type=float)
    a = ap.parse_args(argv)
    fails = n = 0
    for length in np.arange(a.lo, a.hi, a.step):
        for start in ("rest", "running"):
            for capacity, speed, rise in CASES:
                curve = beltrs.StartCurve("harrison", speed=speed, ramp=4.0)
                c = Conveyor(profile=[(0.0, 0.0), (float(length), rise * float(length))], belt="ST1250",
                             capacity=capacity, speed=speed, start=start, drives=[DriveSpec("head", start_curve=curve)])
                s = c.scene()
                n += 1
                try:
                    beltrs.Simulation(replace(s, belt=replace(s.belt, idler_contact=a.idler_contact)))
                except beltrs.BeltrsError as e:
                    fails += 1
                    print(length, start, capacity, speed, rise, "FAIL", e, flush=True)
    print("fails", fails, "of", n, flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Roll wrap against the segment contact over a range of builder conveyors (issue 12: the
requirement before ``belt.idler_contact = "wrap"`` became the conveyor builders' default).
Each level conveyor (ST1250 1 m wide, 500 t/h at 2 m/s, head drive on a 4 s Harrison
curve, tail gravity takeup, every other setting the builder's) is placed from its design
start and run for ``--duration`` s, once at rest and once at speed, with either contact.
Prints one table row per length and contact:

- at rest: the largest roll force and the largest element tension over the run (a
  placement that put nodes inside a roll shows as a kick in the first);
- at speed: the drive torque's mean, its ripple above 2 Hz over the last ``--window`` s
  (max |tau - tau_2Hz| / |mean|, the figure of tests/test_ripple.py), the rms of the part
  above 2 Hz (N*m), and the median over the rolls of each one's normal-force standard
  deviation (N);
- the wall time of both runs.

A script, not a test (docs/wrap-contact.md, "Roll wrap as the builders' default").

    python benches/roll_wrap_sweep.py [--lengths 20,30,40,50,75,100,150,300] [--duration 2]
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import time

import numpy as np

import beltrs
from beltrs.analysis import low_pass
from beltrs.conveyor import Conveyor, DriveSpec


def scene(length: float, start: str, contact: str) -> beltrs.Scene:
    curve = beltrs.StartCurve("harrison", speed=2.0, ramp=4.0)
    c = Conveyor(profile=[(0.0, 0.0), (length, 0.0)], belt="ST1250", capacity=500.0, speed=2.0, start=start,
                 drives=[DriveSpec("head", start_curve=curve)])
    s = c.scene()
    return replace(s, belt=replace(s.belt, idler_contact=contact))


def run(s: beltrs.Scene, duration: float, interval: float):
    sim = beltrs.Simulation(s)
    res = sim.run(duration, record_interval=interval, tension=True, node_position=False, node_velocity=False,
                  progress=False)
    return sim, res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lengths", default="20,30,40,50,75,100,150,300", help="m, comma-separated")
    ap.add_argument("--duration", type=float, default=2.0, help="s of each run")
    ap.add_argument("--window", type=float, default=1.0, help="last s of the running start analysed")
    ap.add_argument("--interval", type=float, default=0.0005, help="sample interval, s")
    ap.add_argument("--contacts", default="segment,wrap")
    a = ap.parse_args(argv)
    print("| length, m | idler contact | nodes | at rest: max roll force, N | at rest: max tension, kN "
          "| at speed: torque mean, N*m | ripple | rms above 2 Hz, N*m | roll force std, N | wall, s |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for length in (float(x) for x in a.lengths.split(",")):
        for contact in a.contacts.split(","):
            wall = time.perf_counter()
            sim, rest = run(scene(length, "rest", contact), a.duration, a.interval)
            _, go = run(scene(length, "running", contact), a.duration, a.interval)
            wall = time.perf_counter() - wall
            j = go.pulley_names.index("head")
            tau = go.drive_torque[:, j]
            t = go.time
            low = low_pass(tau, float(np.median(np.diff(t))), 2.0)
            w = t >= t[-1] - a.window
            mean = float(tau[w].mean())
            ripple = float(np.abs(tau - low)[w].max() / abs(mean))
            rms = float(np.std((tau - low)[w]))
            roll_std = float(np.median(go.idler_force[w].std(axis=0)))
            print(f"| {length:g} | {contact} | {sim.nodes} | {rest.idler_force.max():.0f} | "
                  f"{rest.tension.max() / 1e3:.2f} | {mean:.0f} | {ripple:.3f} | {rms:.0f} | {roll_std:.0f} | "
                  f"{wall:.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

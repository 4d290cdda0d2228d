"""Chordal ripple on held drums (issue 12, "true peaks, smooth drives"): raw against
low-passed peak tight-side tension and the steady drive-torque ripple, on the builder-made
300 m conveyor of tests/conveyor_300.py and on case G (shortened or full length). Prints
the figures; a script, not a test (tests/test_ripple.py checks the targets).

    python benches/ripple.py conveyor300                 # 10 s Harrison start + 10 s running
    python benches/ripple.py caseg --length 200          # case G shortened to 200 m
    python benches/ripple.py caseg --steady 15           # case G, 972 m (minutes)
    python benches/ripple.py conveyor300 --contact nodes # the same with nodal contact

Definitions (docs/accuracy.md, "Raw peaks"):
- tight-side tension: of the element nearest a fixed point 10 m before the head drum on the
  carry strand, every ``--interval`` s; raw peak = its maximum; low-passed peak = the
  maximum of the same signal with everything above 2 Hz removed (beltrs.analysis.low_pass).
  Also the largest tension of any element at any sample (what res.tension.max() reads).
- drive-torque ripple: over the last ``--window`` s (steady running), max |tau - tau_2Hz| /
  |mean tau| (tau_2Hz: the torque below 2 Hz), and half the peak-to-peak over the mean.
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import os
import sys
import time

import beltrs

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
from conveyor_300 import conveyor_300, measure, ripple_figures  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", choices=["conveyor300", "caseg"])
    ap.add_argument("--length", type=float, default=None, help="m (default 300, or case G's 972)")
    ap.add_argument("--ramp", type=float, default=10.0, help="Harrison start, s")
    ap.add_argument("--steady", type=float, default=10.0, help="s at full speed after the ramp")
    ap.add_argument("--window", type=float, default=5.0, help="s of steady running for the torque ripple")
    ap.add_argument("--interval", type=float, default=0.002, help="sample interval, s")
    ap.add_argument("--element-length", type=float, default=None, help="m (default: the scene's)")
    ap.add_argument("--contact", choices=["nodes", "wrap"], default="wrap", help="belt.pulley_contact")
    args = ap.parse_args(argv)

    wall = time.perf_counter()
    kw = {} if args.element_length is None else {"element_length": args.element_length}
    if args.case == "conveyor300":
        length = args.length or 300.0
        c = conveyor_300(ramp=args.ramp, length=length, **kw)
        scene, probe = c.scene(), (length - 10.0, 0.0)
    else:
        from beltrs.scenes import GUO_WANG, guo_wang_conveyor

        length = args.length or GUO_WANG["length"]
        curve = beltrs.StartCurve(shape="harrison", speed=GUO_WANG["speed"], ramp=args.ramp)
        scene, probe = guo_wang_conveyor(curve, length=length, **kw), (length - 10.0, GUO_WANG["drum_radius"])
    scene = replace(scene, belt=replace(scene.belt, pulley_contact=args.contact))
    sim = beltrs.Simulation(scene)
    sim.stabilise(friction=scene.recording.stabilise_friction, tolerance=1e-5, max_steps=400_000)
    data = measure(sim, probe, "head", args.ramp + args.steady, args.interval)
    f = ripple_figures(data, args.window)
    wall = time.perf_counter() - wall
    print(f"beltrs {beltrs.__file__}")
    print(f"{args.case}, {args.contact} contact: {length} m, {sim.nodes} elements, dt {sim.dt * 1e6:.2f} us, "
          f"Harrison {args.ramp} s + "
          f"{args.steady} s, samples every {args.interval * 1e3:g} ms, wall {wall:.0f} s")
    print(f"  tight side 10 m before the head: raw peak {f['raw_peak'] / 1e3:.2f} kN "
          f"at {f['raw_peak_time']:.2f} s, "
          f"below 2 Hz {f['low_peak'] / 1e3:.2f} kN at {f['low_peak_time']:.2f} s: raw / low-passed - 1 = "
          f"{100 * (f['raw_peak'] / f['low_peak'] - 1):+.2f} %")
    print(f"  largest element tension (res.tension.max()): {f['max_tension'] / 1e3:.2f} kN = "
          f"{100 * (f['max_tension'] / f['low_peak'] - 1):+.2f} % against the low-passed probe peak")
    print(f"  drive torque, last {args.window} s: mean {f['torque_mean'] / 1e3:.3f} kN*m, "
          f"{f['torque_min'] / 1e3:.3f} .. {f['torque_max'] / 1e3:.3f} kN*m; ripple above 2 Hz "
          f"{100 * f['torque_ripple']:.2f} % of the mean, half swing {100 * f['torque_half_swing']:.2f} %")
    print(f"  drum speed {f['speed_mean']:.5f} rad/s; probe tension mean {f['tension_mean'] / 1e3:.2f} kN")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Case G: start Guo & Wang's 972 m cement-plant conveyor and read the peak tight-side tension.

    python examples/case_g.py                  # Harrison curve, 10 s start (about 5 minutes)
    python examples/case_g.py --ramp 30        # a 30 s start
    python examples/case_g.py --shape linear --prestart 3

The scene is examples/case_g.toml (= beltrs.scenes.guo_wang_conveyor()); the options change
its starting curve. The paper (Guo & Wang 2020, Table 1) gives: 972 m, 400 t/h at 2 m/s
(55.6 kg/m of material), belt 1 m wide, 24.5 kg/m, ST1250; drum 0.8 m, 800 kg; motor
150 kW at 1000 rpm. Everything else is assumed, with typical values:

- belt EA = 80 MN (steel cord ST1250), EI = 20 N*m^2, 5 % element damping, 0.196 m elements
  (at most 30 degrees on the 0.4 m drum, the engine's default limit, and off whole numbers
  per idler pitch: docs/wrap-contact.md, "Session 11: the element length off the pitches");
- tail pulley 0.4 m radius on a horizontal gravity takeup: 50 kN per strand (10.2 t);
- head drum inertia 100 kg*m^2; lagging mu_s 0.4, mu_k 0.35;
- carry idler sets every 1.2 m (20 kg rotating), return rolls every 3 m (15 kg), 133 mm
  rolls, inertia 0.8 m r^2, DIN 22101 f = 0.02 on every idler, belt-roll friction 0.5;
- material from 5 m after the tail centre to the head, constant kg per metre of belt;
- a variable-speed drive: PI speed controller (default gains) with a torque limit of 1.6 x
  rated (48 kN*m at the drum; gearbox ratio 20.9), motor inertia 4.88 kg*m^2 (assumed:
  session 10's catalogue law, docs/drives.md; 2139 kg*m^2 at the drum).

Prints the peak tension 10 m before the head on the carry strand (the paper's sensor
position), below 2 Hz as well (the raw value carries the node model's
chordal ripple at the node-passing frequency v/l; docs/case-g.md), and the steady running
tensions against DIN 22101.
"""

from __future__ import annotations

import argparse
import dataclasses
import pathlib

import numpy as np

import beltrs
from beltrs.analysis import low_pass, probe_run
from beltrs.scenes import guo_wang_din

HERE = pathlib.Path(__file__).resolve().parent


def main(argv: list[str] | None = None) -> dict[str, float]:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--shape", default="harrison", choices=["harrison", "nordell", "cubic", "linear"])
    ap.add_argument("--ramp", type=float, default=10.0, help="start time T, s (default 10)")
    ap.add_argument("--prestart", type=float, default=0.0, help="pre-start section, s (default 0)")
    ap.add_argument("--settle", type=float, default=10.0, help="s of running after the ramp (default 10)")
    ap.add_argument("--scene", default=str(HERE / "case_g.toml"))
    args = ap.parse_args(argv)

    scene = beltrs.load_scene(args.scene)
    head = scene.pulley_index("head")
    drive = scene.pulleys[head].drive
    curve = dataclasses.replace(drive.start_curve, shape=args.shape, ramp=args.ramp, prestart=args.prestart,
                                creep_speed=None)
    pulleys = list(scene.pulleys)
    pulleys[head] = dataclasses.replace(pulleys[head], drive=dataclasses.replace(drive, start_curve=curve))
    scene = dataclasses.replace(scene, pulleys=pulleys)

    sim = beltrs.Simulation(scene)
    print(f"{sim.nodes} nodes, {len(scene.idlers)} idlers, dt {sim.dt * 1e6:.1f} us; stages {sim.stages}")
    sim.stabilise(tolerance=1e-5, max_steps=400_000)
    length, r = scene.pulleys[head].center[0], scene.pulleys[head].radius
    duration = args.prestart + args.ramp + args.settle
    data = probe_run(sim, [(length - 10.0, r), (length - 10.0, -r)], duration, 0.005)
    t, t1, t2 = data["time"], data["tension"][:, 0], data["tension"][:, 1]
    smooth = low_pass(t1, 0.005, 2.0)  # the engineering figure of docs/case-g.md
    k = int(np.argmax(t1))
    steady = t >= t[-1] - 5.0
    din = guo_wang_din(length)
    out = {
        "peak": float(t1[k]), "peak_time": float(t[k]), "peak_smooth": float(smooth.max()),
        "T1_steady": float(t1[steady].mean()), "T2_steady": float(t2[steady].mean()),
        "din_T1": din.tensions.tight, "din_T2": din.tensions.slack, "din_F_U": din.resistances.total,
    }
    print(f"{args.shape} start in {args.ramp:g} s (pre-start {args.prestart:g} s): peak T1 {out['peak'] / 1e3:.1f} kN "
          f"at {out['peak_time']:.2f} s ({out['peak_smooth'] / 1e3:.1f} kN below 2 Hz)")
    print(f"steady (last 5 s): T1 {out['T1_steady'] / 1e3:.2f} kN, T2 {out['T2_steady'] / 1e3:.2f} kN; DIN 22101 at "
          f"the drum T1 {out['din_T1'] / 1e3:.2f}, T2 {out['din_T2'] / 1e3:.2f}, F_U {out['din_F_U'] / 1e3:.2f} kN "
          "(the probes sit 10 m from the drum)")
    return out


if __name__ == "__main__":
    main()

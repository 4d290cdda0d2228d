"""Start-up study on a builder-made conveyor: the four starting curves of Guo & Wang (2020)
(Harrison, Nordell, cubic, linear), each over two ramp times, with and without a pre-start
(creep) section, on a conveyor built with :mod:`beltrs.conveyor`. Prints a table of peak
belt tension, peak acceleration, takeup travel and drive power.

    python examples/startup_study.py            # 1 km, ST1250, 400 t/h at 2 m/s; 10 s and 30 s ramps,
                                                # 3 s pre-start: 16 runs, about 2 h on one core
    python examples/startup_study.py --quick    # 40 m EP630/4 belt, ramps 1 s and 3 s, 0.3 s pre-start:
                                                # the same study in seconds (a smoke test of the script)
    python examples/startup_study.py --control vfd  # the builder's default drive (PI speed loop with the
                                                # motor's rotor) instead of the ideal speed follower

examples/startup_study.toml is the full-size conveyor's scene with the first curve
(``--write-scene`` writes it; a test checks that it equals what this script builds).

Every case starts from the conveyor's static design state at rest (``Conveyor(start="rest")``,
docs/design-start.md): the belt placed along its profile stretched to the standstill
tensions, the takeup in place; no relaxation. The drive holds the belt for ``lead`` seconds
(2 s) while the spans sink into their sag between the rolls (the
placement puts the belt straight from roll to roll), then starts along its curve; times
and takeup travel are counted from the curve's start. Every case uses the same takeup tension and
motor (sized by the builder for the most demanding curve), so that the curves are compared
on one machine.

Columns:
- peak T: the largest element tension anywhere on the belt during the run, kN (raw), and
  the same series below 2 Hz (beltrs.analysis.low_pass: the node model's chordal ripple at
  the node-passing frequency removed, docs/case-g.md);
- T steady: the largest belt tension below 2 Hz averaged over the last second, kN (DIN
  22101's T1 from beltrs.statics is in the header: in the quick study the belt is still
  ringing from its start then);
- a drive / a tail: peak belt acceleration at the drive drum (from its recorded speed) and
  at the tail drum (its speed below 2 Hz: the free drum carries the chordal ripple), m/s^2;
  the tail's shows the start wave's overshoot;
- takeup: the largest takeup travel away from the conveyor (taking up the belt's stretch),
  m, from the curve's start;
- P peak / P end: drive power (torque x speed, positive when driving), kW.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace

import numpy as np

import beltrs
from beltrs.analysis import low_pass
from beltrs.conveyor import Conveyor, DriveSpec, TakeupSpec

SHAPES = ("harrison", "nordell", "cubic", "linear")

FULL = dict(length=1000.0, belt="ST1250", capacity=400.0, speed=2.0, ramps=(10.0, 30.0), prestart=3.0,
            settle=5.0, interval=0.05, lead=2.0)
QUICK = dict(length=40.0, belt="EP630/4", capacity=150.0, speed=1.5, ramps=(1.0, 3.0), prestart=0.3,
             settle=0.5, interval=0.01, lead=2.0)


def curves(cfg: dict) -> list[beltrs.StartCurve]:
    """The study's start curves: shapes x ramps x (no pre-start, pre-start)."""
    out = []
    for prestart in (0.0, cfg["prestart"]):
        for ramp in cfg["ramps"]:
            for shape in SHAPES:
                out.append(beltrs.StartCurve(shape=shape, speed=cfg["speed"], ramp=ramp, prestart=prestart))
    return out


def design(cfg: dict) -> tuple[float, float, beltrs.statics.TensionProfile]:
    """Takeup tension per strand (N) and motor power (W), sized by the builder for the
    study's steepest curve, and the DIN 22101 tensions, shared by every case."""
    steepest = max(curves(cfg), key=lambda c: float(np.max(c.acceleration_at(np.linspace(0, c.end, 2001)))))
    ref = Conveyor(profile=[(0.0, 0.0), (cfg["length"], 0.0)], belt=cfg["belt"], capacity=cfg["capacity"],
                   speed=cfg["speed"], drives=[DriveSpec("head", start_curve=steepest, control="ideal")])
    return ref.takeup_tension(), ref.motor_power("head"), ref.statics()


def build(cfg: dict, curve: beltrs.StartCurve, tension: float, power: float, control: str = "ideal") -> beltrs.Scene:
    """The study's conveyor started along ``curve`` (examples/startup_study.toml is the
    full-size one with the first curve). The drive is the ideal speed follower
    (``control="ideal"``, not the builder's default VFD): the study compares the curves
    themselves, each followed exactly within the torque limit. ``control="vfd"`` (the
    ``--control vfd`` option) runs the builder's default drive instead."""
    c = Conveyor(profile=[(0.0, 0.0), (cfg["length"], 0.0)], belt=cfg["belt"], capacity=cfg["capacity"],
                 speed=cfg["speed"], drives=[DriveSpec("head", start_curve=curve, power=power, control=control)],
                 takeup=TakeupSpec("tail", tension=tension))
    return c.scene()


def study(cfg: dict, out=sys.stdout, part: tuple[int, int] = (1, 1), control: str = "ideal") -> list[dict]:
    """Run the study's cases (``part`` = (k, n): only every n-th case from the k-th, to
    spread the full study over n processes; the table rows keep the study's order) with the
    drive ``control`` (:func:`build`)."""
    k, n = part
    cases = curves(cfg)[k - 1::n]
    tension, power, din = design(cfg)
    print(f"# Start-up study: {cfg['length']:g} m, {cfg['belt']}, {cfg['capacity']:g} t/h at {cfg['speed']:g} m/s; "
          f"takeup {tension / 1e3:g} kN per strand, motor {power / 1e3:g} kW; DIN 22101 T1 = "
          f"{din.drive('head').tight / 1e3:.1f} kN, T2 = {din.drive('head').slack / 1e3:.1f} kN"
          + ("" if control == "ideal" else f"; drive control = {control!r}") + "\n", file=out)

    rows = []
    lead = cfg["lead"]
    print(f"Start: the design state at rest (no relaxation), {lead:g} s of settling with the drive holding, then "
          "the curve (times from its start).\n", file=out)
    print("| curve | ramp, s | pre-start, s | peak T, kN | at, s | peak T < 2 Hz, kN | T steady, kN | "
          "a drive, m/s² | a tail, m/s² | takeup, m | P peak, kW | P end, kW | wall, s |", file=out)
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|", file=out, flush=True)
    for curve in cases:
        curve = replace(curve, start=lead)  # a short settle at rest first (the spans' sag)
        scene = build(cfg, curve, tension, power, control)
        head = scene.pulley_index("head")
        tail = scene.pulley_index("tail")
        r = scene.pulleys[head].radius
        t0 = time.perf_counter()
        s = beltrs.Simulation(scene)  # the design state: no relaxation
        res = s.run(curve.end + cfg["settle"], record_interval=cfg["interval"], tension=True,
                    node_position=False, node_velocity=False)
        wall = time.perf_counter() - t0
        dt = float(res.time[1] - res.time[0])
        k0 = int(np.searchsorted(res.time, lead - 1e-9))  # the curve's start
        res_time = res.time[k0:] - lead
        tmax = res.tension[k0:].max(axis=1)
        smooth = low_pass(tmax, dt, 2.0)
        last = res_time >= res_time[-1] - 1.0
        a_drive = np.gradient(-res.pulley_speed[k0:, head] * r, dt)  # held on its curve: no ripple
        a_tail = np.gradient(low_pass(-res.pulley_speed[k0:, tail] * r, dt, 2.0), dt)
        p = res.drive_torque[k0:, head] * res.pulley_speed[k0:, head]
        travel = res.takeup_travel[k0:, tail] - res.takeup_travel[k0, tail]
        rows.append(dict(
            shape=curve.shape, ramp=curve.ramp, prestart=curve.prestart,
            peak=tmax.max(), at=res_time[np.argmax(tmax)], peak2=smooth.max(),
            steady=smooth[last].mean(), a_drive=a_drive.max(), a_tail=a_tail.max(),
            takeup=travel.max(), p_peak=p.max(), p_end=p[last].mean(), wall=wall,
            t1_din=din.drive("head").tight))
        w = rows[-1]
        print(f"| {w['shape']} | {w['ramp']:g} | {w['prestart']:g} | {w['peak'] / 1e3:.1f} | {w['at']:.2f} | "
              f"{w['peak2'] / 1e3:.1f} | {w['steady'] / 1e3:.1f} | {w['a_drive']:.3f} | {w['a_tail']:.3f} | "
              f"{w['takeup']:.3f} | {w['p_peak'] / 1e3:.1f} | {w['p_end'] / 1e3:.1f} | {w['wall']:.1f} |", file=out,
              flush=True)
    print(f"\n{len(rows)} starts, {sum(w['wall'] for w in rows):.0f} s of wall in all.", file=out)
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="a 40 m conveyor with short ramps (seconds)")
    parser.add_argument("--write-scene", metavar="PATH", help="write the full study's first scene to PATH and stop")
    parser.add_argument("--part", metavar="K/N", default="1/1",
                        help="run every N-th case from the K-th (spread the study over N processes)")
    parser.add_argument("--control", choices=("ideal", "vfd"), default="ideal",
                        help="the drive: 'ideal' (the study's: the ideal speed follower) or 'vfd' (the builder's "
                        "default: PI speed loop with the motor's rotor)")
    args = parser.parse_args(argv)
    try:
        k, n = (int(v) for v in args.part.split("/"))
        if not 1 <= k <= n:
            raise ValueError
    except ValueError:
        parser.error(f"--part {args.part!r}: expected K/N with 1 <= K <= N, e.g. 1/2")
    if args.write_scene:
        tension, power, _ = design(FULL)
        build(FULL, curves(FULL)[0], tension, power).save(args.write_scene)
        return 0
    study(QUICK if args.quick else FULL, part=(k, n), control=args.control)
    return 0


if __name__ == "__main__":
    sys.exit(main())

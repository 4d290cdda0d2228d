"""Case K (Kubas 2014) with the paper's creep-rate friction: the steady answers, and what the
adaptive RKF45 costs at each transition speed (docs/kubas.md, "Case K with creep
friction"). An optional measurement, not in CI.

Run from the repository root with beltrs installed::

    python benches/case_k_creep.py steady [--integrator central_difference|rkf45]
        [--formulation rigid_body|node_kelvin_voigt] [--dv 1e-5] [--duration 0.5]
        [--window 0.15] [--ramp 0.3] [--rtol 1e-8] [--atol 1e-11]
    python benches/case_k_creep.py cost [--dv 1e-5 1e-3 ...] [--formulation ...]
        [--duration 2e-4] [--chunk 2e-5] [--rtol ...] [--atol ...]

``steady``: case K (``beltrs.scenes.kubas_case_k``) with creep friction mu_s 1.05,
mu_k 1.0, Delta_max 1e-4 m and the given Delta_v on both pulleys; relaxed, run for
``duration`` with the drive torque ramped over ``ramp``, averaged over the last ``window``
seconds. Prints T1, T2 (mean joint tension over the middle third of the tight and slack
span), T1 - T2 against M/r, T1 + T2 against twice the relaxed preload, the pulley speeds,
the slip 1 - w2/w1, the elastic creep (T1 - T2)/(EA + T1) and
``beltrs.analytic.two_pulley_creep`` at the measured drive speed; the steps and wall time.

``cost``: for each Delta_v, the same scene relaxed, the torque ramp started, and
``duration`` of RKF45 in chunks of ``chunk``: accepted and rejected steps, the mean
accepted step per chunk (smallest and largest over the chunks), derivative evaluations
(6 per accepted step, 5 per rejected one) and wall time, with the extrapolation to one
simulated second.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

import beltrs
from beltrs.analytic import two_pulley_creep

RADIUS, DISTANCE, EA, RHO = 0.027, 0.515, 1.52e5, 0.096
TORQUE = 15.0


def scene(dv: float, formulation: str, integrator: str, ramp: float, rtol: float, atol: float) -> beltrs.Scene:
    s = beltrs.scenes.kubas_case_k(ramp_time=ramp)
    s.belt.formulation = formulation
    for p in s.pulleys:
        p.friction = beltrs.Friction(model="creep", static=1.05, kinetic=1.0, transition_speed=dv, creep_limit=1e-4)
    s.solver.integrator = integrator
    if integrator == "rkf45":
        s.solver.relative_tolerance = rtol
        s.solver.absolute_tolerance = atol
    return s


def span_tensions(res: beltrs.Result) -> tuple[np.ndarray, np.ndarray]:
    """Mean joint tension over the middle third of the upper (tight) and lower span."""
    x = res.node_position
    mid = 0.5 * (x + np.roll(x, -1, axis=1))
    inner = (mid[..., 0] > DISTANCE / 3) & (mid[..., 0] < 2 * DISTANCE / 3)
    upper = np.where(inner & (mid[..., 1] > 0), res.tension, np.nan)
    lower = np.where(inner & (mid[..., 1] < 0), res.tension, np.nan)
    return np.nanmean(upper, axis=1), np.nanmean(lower, axis=1)


def steady(args: argparse.Namespace) -> None:
    sim = beltrs.Simulation(scene(args.dv[0], args.formulation, args.integrator, args.ramp, args.rtol, args.atol))
    assert sim.stabilise()["converged"]
    preload = float(np.mean(sim.tensions()))
    t0 = time.perf_counter()
    res = sim.run(args.duration, record_interval=1e-3, node_velocity=False)
    wall = time.perf_counter() - t0
    upper, lower = span_tensions(res)
    w = res.time >= args.duration - args.window
    t1, t2 = float(upper[w].mean()), float(lower[w].mean())
    speeds = res.pulley_speed[w].mean(axis=0)
    slip = 1 - speeds[1] / speeds[0]
    mr = TORQUE / RADIUS
    theory = two_pulley_creep(
        drive_radius=RADIUS, driven_radius=RADIUS, centre_distance=DISTANCE, axial_stiffness=EA,
        mass_per_length=RHO, pretension=preload, mu=1.0, drive_speed=float(speeds[0]), load_torque=TORQUE,
    )
    print(f"case K, {args.formulation}, {args.integrator}, creep friction dv = {args.dv[0]:g} m/s, "
          f"{args.duration} s (ramp {args.ramp} s), averages over the last {args.window} s")
    print(f"  preload (relaxed)   {preload:.1f} N")
    print(f"  T1, T2              {t1:.1f} N, {t2:.1f} N")
    print(f"  T1 - T2             {t1 - t2:.1f} N against M/r = {mr:.1f} N ({(t1 - t2) / mr - 1:+.2%})")
    print(f"  T1 + T2             {t1 + t2:.1f} N against 2 x preload {2 * preload:.1f} N "
          f"({(t1 + t2) / (2 * preload) - 1:+.2%}); "
          f"mean joint tension {res.tension[w].mean():.1f} N")
    print(f"  speeds              drive {speeds[0]:.4f}, driven {speeds[1]:.4f} rad/s (8 pi = {8 * math.pi:.4f})")
    print(f"  slip 1 - w2/w1      {slip:.3%}; elastic creep (T1 - T2)/(EA + T1) = {(t1 - t2) / (EA + t1):.3%}; "
          f"two_pulley_creep: slip {theory.creep:.3%}, "
          f"T1 {theory.tight_tension:.1f} N, T2 {theory.slack_tension:.1f} N")
    print(f"  steps               {res.steps_accepted} accepted, {res.steps_rejected} rejected; "
          f"wall {wall:.1f} s")


def cost(args: argparse.Namespace) -> None:
    print(f"case K, {args.formulation}, RKF45 rtol {args.rtol:g} atol {args.atol:g}, from the relaxed state "
          f"with the torque ramp starting; {args.duration:g} s in chunks of {args.chunk:g} s")
    print("  dv (m/s) | accepted | rejected | mean step (s): all, smallest..largest chunk "
          "| wall (s) | wall per simulated s")
    for dv in args.dv:
        sim = beltrs.Simulation(scene(dv, args.formulation, "rkf45", args.ramp, args.rtol, args.atol))
        assert sim.stabilise()["converged"]
        chunks = max(1, round(args.duration / args.chunk))
        acc = rej = 0
        means = []
        t0 = time.perf_counter()
        for _ in range(chunks):
            r = sim.run(args.chunk, record_interval=args.chunk)
            acc += r.steps_accepted
            rej += r.steps_rejected
            means.append(args.chunk / max(r.steps_accepted, 1))
        wall = time.perf_counter() - t0
        simulated = chunks * args.chunk
        print(f"  {dv:8.0e} | {acc:8d} | {rej:8d} | {simulated / acc:.2e}, {min(means):.2e}..{max(means):.2e} "
              f"| {wall:8.1f} | {wall / simulated:.3g}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("what", choices=["steady", "cost"])
    ap.add_argument("--dv", type=float, nargs="+", default=[1e-5], help="creep transition speed(s), m/s")
    ap.add_argument("--formulation", default="rigid_body", choices=["rigid_body", "node_kelvin_voigt"])
    ap.add_argument("--integrator", default="central_difference", choices=["central_difference", "rkf45"])
    ap.add_argument("--duration", type=float, default=None, help="simulated time, s")
    ap.add_argument("--window", type=float, default=0.15, help="averaging window (steady), s")
    ap.add_argument("--chunk", type=float, default=2e-5, help="chunk length (cost), s")
    ap.add_argument("--ramp", type=float, default=0.3, help="torque ramp time, s")
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--atol", type=float, default=1e-11)
    args = ap.parse_args()
    if args.duration is None:
        args.duration = 0.5 if args.what == "steady" else 2e-4
    steady(args) if args.what == "steady" else cost(args)


if __name__ == "__main__":
    main()

"""Command line: ``python -m beltrs demo`` runs case H on the built-in default scene."""

from __future__ import annotations

import argparse
import sys
import time
from typing import Optional, Sequence

import numpy as np


def demo(elements: int, out: str) -> int:
    """Stabilise case H, print static tensions, takeup position and wall times, run the
    thesis §6.4.2 torque pulse for 3.6 s, and write a PNG of tension around the belt."""
    import beltrs
    from beltrs.analysis import hustrulid_tangent_tensions
    from beltrs.analytic import two_pulley_takeup_statics
    from beltrs.plot import plot_tension_around_belt

    exact = two_pulley_takeup_statics()
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop(elements))
    print(f"beltrs {beltrs.__version__}: case H, Hustrulid's two-pulley loop, {sim.nodes} elements")
    print(f"  stages: {', '.join(sim.stages)}")
    print(f"  time step {sim.dt:.3e} s = {sim.dt / sim.dt_limit:.2f} x limit ({sim.dt_cause})")
    t0 = time.perf_counter()
    report = sim.stabilise()
    t_static = time.perf_counter() - t0
    x = sim.state()["node_position"]
    tension = sim.tensions()
    travel = float(sim.takeup_travel[1])
    yl = -travel
    ta, tb, tc, td = hustrulid_tangent_tensions(x, tension, yl)
    print(f"static equilibrium ({report['steps']} relaxation steps, {t_static * 1e3:.1f} ms wall):")
    print(f"  tension at lower tangent points A, B: {ta / 1e3:8.2f} {tb / 1e3:8.2f} kN"
          f"   (exact {exact.lower_tension / 1e3:.2f} kN)")
    print(f"  tension at upper tangent points C, D: {tc / 1e3:8.2f} {td / 1e3:8.2f} kN"
          f"   (exact {exact.upper_tension / 1e3:.2f} kN)")
    print(f"  takeup position: y = {yl:.4f} m, displacement {-travel:.4f} m"
          f"   (exact continuum {exact.takeup_displacement:.4f} m; the chord polygon error shrinks as 1/n²)")
    static_x, static_t = x.copy(), tension.copy()

    friction = beltrs.Friction(static=0.5, kinetic=0.4)
    sim.set_friction(0, friction)
    sim.set_friction(1, friction)
    sim.set_drive(0, beltrs.Drive.pulse(4e5, 0.07, start=sim.time))
    res = sim.run(3.6, record_interval=0.01, node_velocity=False)
    steps = int(round(3.6 / sim.dt))
    print(f"thesis §6.4.2: 400 kN·m for 0.07 s, then 3.6 s simulated: {steps} steps in {res.wall_time:.3f} s wall"
          f" ({sim.nodes * steps / res.wall_time:.3e} node-steps/s; the thesis took ~15 min)")
    assert res.tension is not None
    print(f"  peak tension {res.tension.max() / 1e3:.1f} kN, lowest {res.tension.min() / 1e3:.1f} kN")
    path = plot_tension_around_belt(
        static_x, static_t, out, title="Case H: static tension (kN)",
        takeup_time=res.time, takeup_travel=-res.takeup_travel[:, 1],
    )
    print(f"wrote {path}")
    return 0 if np.isfinite(res.tension).all() else 1


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="beltrs", description="belt conveyor dynamics")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("demo", help="case H: statics, a torque pulse, and a tension plot")
    p.add_argument("--elements", type=int, default=89, help="belt elements (default 89)")
    p.add_argument("--out", default="beltrs_case_h.png", help="PNG to write")
    args = parser.parse_args(argv)
    if args.command == "demo":
        return demo(args.elements, args.out)
    return 2


if __name__ == "__main__":
    sys.exit(main())

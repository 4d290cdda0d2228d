"""The two fixtures of tests/test_ripple.py (issue 12), exactly as the test builds them
(case G 150 m stabilised, then a 4 s Harrison start; the 300 m builder conveyor from its
sag-placed design start at rest), with the belt's idler contact and viscoelastic loss
factor set from the command line. Prints one JSON line: the test's figures
(``ripple_figures``: raw and low-passed probe-tension peaks, the drive torque's mean and
ripple above 2 Hz over the last 2 s of 4 s at speed, followed by 1 s more so that the
low-pass's ringing at the record's end stays outside the window), and the torque's rms above 2 Hz,
its band energies and strongest lines (``benches/ripple_drive.py``'s ``figures``), the
step and the wall time. A script, not a test (docs/wrap-contact.md, "Damping the strands'
modes").

    python benches/ripple_fixtures.py conveyor --idler-contact wrap --loss-factor 0.1
    python benches/ripple_fixtures.py case_g --idler-contact segment --loss-factor 0.2 --loss-frequency 3

Beyond the test: ``--steady`` s at speed (the figures then read over the last 2 s of it, 1 s more run after),
``--windows`` (the test figure in successive windows and the lines above 2 Hz over the last
``--spectrum`` s, benches/ripple_drive.py's ``window_figures`` and ``lines``), and the
element length and belt speed:

    python benches/ripple_fixtures.py case_g --steady 16 --windows 2 --spectrum 8
    python benches/ripple_fixtures.py case_g --element 0.19 --speed 1.5

Steady running without the start (``--start running``: the builder's running design start,
steady-running tensions and the belt at speed, no ramp; the figures over the last 2 s of
``--steady`` s): session 10 at the defaults, case G 0.146 (70 % of the energy above 2 Hz in
the 9.96 Hz cogging line) and 300 m 0.106 (drum stick-slip spikes above 80 Hz; 0.0094 once
the friction solve remembers sliding contacts, docs/wrap-contact.md "Session 10: the drums'
stick-slip"). Session 11 (that law on main, and case G's builder at 0.196 m elements, off
whole numbers per idler pitch): case G 0.018 motor, 0.032 gearbox shaft (0.2 m: 0.030, 0.052,
the 9.96 Hz cogging line), 300 m 0.011, 0.013; after the 4 s start case G 0.044:

    python benches/ripple_fixtures.py case_g --start running --steady 8 --windows 2 --spectrum 6

The 300 m conveyor's takeup tension (``--takeup`` N per strand; by default the builder's:
22 kN in session 11, with which the belt slides on the head drum through the 4 s start,
0.179; 28 kN from session 11's grip rule, 0.029; 31 kN since session 13's grip through the
start's dynamics, 0.0176; tests/test_takeup_swing.py, docs/stops-takeups.md), 0.018 at 30 kN:

    python benches/ripple_fixtures.py conveyor --takeup 30000
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import replace
from pathlib import Path

import beltrs
from beltrs.conveyor import Conveyor, DriveSpec
from beltrs.scenes import GUO_WANG, guo_wang_conveyor

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from conveyor_300 import LENGTH, conveyor_300, measure, ripple_figures, shaft_torque  # noqa: E402
from ripple_drive import figures, lines, window_figures  # noqa: E402

RAMP, STEADY, WINDOW, MARGIN = 4.0, 4.0, 2.0, 1.0  # tests/test_ripple.py


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("which", choices=["case_g", "conveyor"])
    ap.add_argument("--idler-contact", default="wrap", choices=["segment", "wrap"])
    ap.add_argument("--loss-factor", type=float, default=0.0)
    ap.add_argument("--loss-frequency", type=float, default=5.0, help="Hz")
    ap.add_argument("--steady", type=float, default=STEADY, help="s at speed after the start")
    ap.add_argument("--ramp", type=float, default=RAMP, help="s of the Harrison start")
    ap.add_argument("--element", type=float, default=None, help="element length, m (default: the builder's)")
    ap.add_argument("--speed", type=float, default=None,
                    help="belt speed, m/s (default 2; case G keeps its material per metre, the 300 m conveyor its "
                         "500 t/h)")
    ap.add_argument("--windows", type=float, default=None, help="also the figure in successive windows of this many s")
    ap.add_argument("--spectrum", type=float, default=8.0, help="s analysed for the lines (with --windows)")
    ap.add_argument("--drum-friction", default="default", choices=["default", "equal", "creep"],
                    help="the drums' friction: the builder's (stick-force, mu_s 0.4, mu_k 0.35), mu_s = mu_k = 0.35 "
                         "(no stick-slip), or the creep model with the builder's coefficients")
    ap.add_argument("--pi", action="store_true",
                    help="a PI speed controller (beltrs.SpeedController, default gains) on the head drive instead of "
                         "the ideal speed follower")
    ap.add_argument("--control", default="vfd", choices=["vfd", "ideal", "ideal0"],
                    help="the builders' drive: vfd (default since session 10: PI speed controller with the motor's "
                         "catalogue inertia), ideal (the ideal speed follower, same inertia) or ideal0 (the ideal "
                         "follower without motor inertia: the builders' drive of session 9, except case G's 3 kg*m^2)")
    ap.add_argument("--start", default="rest", choices=["rest", "running"],
                    help="rest: the test's start (case G stabilised at rest, the 300 m from its design state at "
                         "rest) then the ramp; running: the builder's running design start (steady-running "
                         "tensions, belt at speed, no ramp), the --steady s at speed measured")
    ap.add_argument("--takeup", type=float, default=None,
                    help="conveyor only: the takeup tension per strand, N (default: the builder's rule, 31 kN for "
                         "the 4 s start since session 13, 22 kN before session 11's grip rule); e.g. 30000 grips "
                         "the head drum through the whole 4 s start")
    ap.add_argument("--save", help="write the measured record (time, tension, torque, ...) to this .npz")
    a = ap.parse_args(argv)

    def belt(scene: beltrs.Scene) -> beltrs.Scene:
        scene = replace(scene, belt=replace(scene.belt, idler_contact=a.idler_contact, loss_factor=a.loss_factor,
                                            loss_frequency=a.loss_frequency))
        if a.drum_friction == "equal":
            scene = replace(scene, pulleys=[replace(p, friction=replace(p.friction, static=p.friction.kinetic))
                                            for p in scene.pulleys])
        elif a.drum_friction == "creep":
            scene = replace(scene, pulleys=[replace(p, friction=replace(p.friction, model="creep"))
                                            for p in scene.pulleys])
        if a.pi:
            scene = replace(scene, pulleys=[replace(p, drive=replace(p.drive, controller=beltrs.SpeedController()))
                                            if p.drive is not None else p for p in scene.pulleys])
        return scene

    t0 = time.perf_counter()
    ramp = 0.0 if a.start == "running" else a.ramp
    running = {"start": "running"} if a.start == "running" else {}
    if a.which == "case_g":
        length = 150.0
        curve = beltrs.StartCurve(shape="harrison", speed=a.speed or GUO_WANG["speed"], ramp=a.ramp)
        kw = {} if a.element is None else {"element_length": a.element}
        kw["control"] = "vfd" if a.control == "vfd" else "ideal"
        scene = belt(guo_wang_conveyor(curve, length=length, **running, **kw))
        if a.control == "ideal0":
            scene = replace(scene, pulleys=[replace(p, drive=replace(p.drive, inertia=0.0)) if p.drive is not None
                                            else p for p in scene.pulleys])
        sim = beltrs.Simulation(scene)
        if a.start != "running":
            sim.stabilise(tolerance=1e-5, max_steps=400_000)
        data = measure(sim, (length - 10.0, GUO_WANG["drum_radius"]), "head", ramp + a.steady + MARGIN)
    else:
        kw = {} if a.element is None else {"element_length": a.element}
        kw.update(running)
        if a.takeup is not None:
            from beltrs.conveyor import TakeupSpec

            kw["takeup"] = TakeupSpec(location="tail", tension=a.takeup)
        if a.speed is None:
            c = conveyor_300(ramp=a.ramp, **kw)
        else:
            c = Conveyor(profile=[(0.0, 0.0), (LENGTH, 0.0)], belt="ST1250", capacity=500.0, speed=a.speed,
                         drives=[DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=a.speed,
                                                                                 ramp=a.ramp))], **kw)
        c.drives = [replace(d, control="vfd" if a.control == "vfd" else "ideal",
                            inertia=0.0 if a.control == "ideal0" else d.inertia) for d in c.drives]
        scene = belt(c.scene())
        sim = beltrs.Simulation(scene)
        data = measure(sim, (290.0, 0.0), "head", ramp + a.steady + MARGIN)
    f = ripple_figures(data, WINDOW, margin=MARGIN)
    # the gearbox's output shaft: drive_torque - J i^2 domega/dt (docs/drives.md, "Which torque ...")
    inertia = next(p.drive.inertia for p in scene.pulleys if p.drive is not None)
    fs = ripple_figures(dict(data, torque=shaft_torque(data, scene)), WINDOW, margin=MARGIN)
    f.update(drive_inertia=inertia, shaft_ripple=fs["torque_ripple"], shaft_mean=fs["torque_mean"],
             shaft_min=fs["torque_min"], shaft_max=fs["torque_max"])
    if a.save:
        import numpy as np

        np.savez(a.save, **data)
    g = figures(data["time"], data["torque"], WINDOW)
    f.update(which=a.which, idler_contact=a.idler_contact, loss_factor=a.loss_factor,
             loss_frequency=a.loss_frequency, raw_over_low=f["raw_peak"] / f["low_peak"] - 1,
             rms_above_2hz=g["rms_abs"], bands=g["bands"], lines_hz=g["lines_hz"], dt_us=sim.dt * 1e6,
             wall_s=time.perf_counter() - t0, drum_friction=a.drum_friction, pi=a.pi, control=a.control,
             start=a.start, ramp=a.ramp, steady=a.steady,
             element=a.element, speed=a.speed, nodes=sim.nodes, takeup=a.takeup)
    if a.windows:
        f.update(windows=window_figures(data["time"], data["torque"], a.windows),
                 lines=lines(data["time"], data["torque"], a.spectrum))
    print(json.dumps(f), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Where the steady drive-torque ripple lives (issue 12, "smooth drives"): the 300 m builder
conveyor of tests/conveyor_300.py started from its running design state (no ramp), the head
drive's torque and the belt's friction torque on the head drum sampled every 0.5 ms, for one
model change at a time. Prints one JSON line per variant: mean torque, ripple above 2 Hz
(max |tau - tau_2Hz| / |mean|, the test's figure), its rms, and the share of the spectrum's
energy in bands (Hz) with the five strongest lines. A script, not a test.

    python benches/ripple_drive.py base mu_equal wrap tau1e4 no_idler_damp
    python benches/ripple_drive.py base --pi --motor-inertia 1.5   # PI speed loop, motor inertia
    python benches/ripple_drive.py base --element 0.1045           # half the element length

Variants: ``base`` (builder defaults: nodal contact, ideal speed-held head drum, lagging
0.4/0.35 stick-force, element damping 5 % of critical), ``mu_equal`` (lagging 0.35/0.35: no
stick-slip between mu_s and mu_k), ``creep`` (creep friction on the drums), ``wrap``
(``belt.pulley_contact = "wrap"``), ``tau1e4`` / ``tau3e4`` / ``tau1e3`` (Voigt
``damping_time`` instead of the element damping ratio), ``no_idler_damp`` / ``idler_damp4``
(roll contact damping 0 / 4x), ``no_gravity``, ``no_resistance`` (DIN f = 0 on the rolls),
``big_rolls`` (every roll 3x its radius, its top kept), ``no_roll_friction`` (no belt
friction on the rolls), ``zener`` / ``zener_wrap`` (a viscoelastic belt, ``belt.loss_factor`` = ``--loss-factor``
peaking at ``--loss-frequency`` Hz, on top of the builder's element damping; with nodal or
wrap contact).

    python benches/ripple_drive.py zener zener_wrap --loss-factor 0.1 --loss-frequency 5

Flags on top of any variant: ``--wrap`` (wrap contact on the drums), ``--roll-wrap`` (wrap
contact on the rolls, ``belt.idler_contact``), ``--sag`` (spans placed in their sag),
``--speed``. Also printed: the rolls' normal forces over the window (largest, and the
median over the rolls of each one's peak over its mean and of its standard deviation).

    python benches/ripple_drive.py base --wrap --sag --roll-wrap

``--windows 2`` prints the test figure in successive 2 s windows (does it decay?) and the
lines above 2 Hz over the last ``--window`` s with their share of the energy there:

    python benches/ripple_drive.py base --wrap --sag --roll-wrap --duration 16 --window 8 --windows 2
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import json
import time

import numpy as np

import beltrs
from beltrs.analysis import low_pass
from beltrs.conveyor import Conveyor, DriveSpec

BANDS = [(0, 2), (2, 8), (8, 15), (15, 30), (30, 80), (80, 200), (200, float("inf"))]


def figures(t: np.ndarray, x: np.ndarray, window: float) -> dict:
    """Ripple figures of the signal ``x`` over the last ``window`` s."""
    dt = float(np.median(np.diff(t)))
    low = low_pass(x, dt, 2.0)
    w = t >= t[-1] - window
    mean = float(x[w].mean())
    xs = x[w] - mean
    spec = np.abs(np.fft.rfft(xs * np.hanning(len(xs)))) ** 2
    f = np.fft.rfftfreq(len(xs), dt)
    total = spec.sum()
    return {
        "mean": round(mean, 1),
        "rms_abs": round(float(np.std((x - low)[w])), 1),
        "ripple": round(float(np.abs(x - low)[w].max() / abs(mean)), 3),
        "rms": round(float(np.std((x - low)[w]) / abs(mean)), 3),
        "bands": {f"{a:g}-{b:g}": round(float(spec[(f >= a) & (f < b)].sum() / total), 3) for a, b in BANDS},
        "lines_hz": [round(float(f[k]), 1) for k in np.argsort(spec)[-5:][::-1]],
    }


def window_figures(t: np.ndarray, x: np.ndarray, width: float, cutoff: float = 2.0) -> list:
    """The test's ripple figure (max |x - x_low| over |mean|, ``x_low`` the whole record
    below ``cutoff`` Hz, as ``tests/conveyor_300.py``'s ``ripple_figures`` takes it) in
    successive windows of ``width`` s, counted back from the record's end: a list of
    (window end, s; mean; ripple). A ripple that decays window by window is ringing (of
    the start or the initial state); one that holds is driven."""
    dt = float(np.median(np.diff(t)))
    dev = np.abs(x - low_pass(x, dt, cutoff))
    out = []
    end = t[-1]
    while end - width >= t[0] - 1e-9:
        w = (t > end - width + 1e-9) & (t <= end + 1e-9)
        mean = float(x[w].mean())
        out.append((round(float(end), 3), round(mean, 1), round(float(dev[w].max() / abs(mean)), 3)))
        end -= width
    return out[::-1]


def lines(t: np.ndarray, x: np.ndarray, window: float, above: float = 2.0, share: float = 0.03,
          half_width: int = 3, skip_end: float = 0.5) -> list:
    """The spectral lines of the part of ``x`` above ``above`` Hz (``x`` minus its low-pass,
    the part the test's ripple figure sees) over ``window`` s ending ``skip_end`` s before
    the record's end (away from the low-pass's end effect), Hann window: each local maximum
    of the power spectrum with the energy of the bins within ``half_width`` of it, as a
    share of all the energy there; those carrying at least ``share``, strongest first, as
    (frequency Hz, share, amplitude). The amplitude is that of the sinusoid with the line's
    energy (x's unit)."""
    dt = float(np.median(np.diff(t)))
    dev = x - low_pass(x, dt, above)
    w = (t >= t[-1] - skip_end - window) & (t <= t[-1] - skip_end)
    xs = dev[w] - dev[w].mean()
    spec = np.abs(np.fft.rfft(xs * np.hanning(len(xs)))) ** 2
    f = np.fft.rfftfreq(len(xs), dt)
    total = spec.sum()
    norm = len(xs) * float(np.sum(np.hanning(len(xs)) ** 2))  # A = sqrt(4 E / norm) for A cos(wt)
    peaks = [k for k in range(1, len(spec) - 1) if spec[k] >= spec[k - 1] and spec[k] > spec[k + 1]]
    out = []
    for k in peaks:
        e = spec[max(k - half_width, 0):k + half_width + 1].sum()
        out.append((round(float(f[k]), 2), round(float(e / total), 3), round(float(np.sqrt(4 * e / norm)), 1)))
    out.sort(key=lambda p: -p[1])
    # A line's neighbours within its own half width are its side lobes, not lines.
    kept: list = []
    df = f[1] - f[0]
    for fr, e, amp in out:
        if e >= share and all(abs(fr - g) > half_width * df for g, _, _ in kept):
            kept.append((fr, e, amp))
    return kept


def roll_figures(t: np.ndarray, force: np.ndarray, window: float) -> dict:
    """The rolls' normal forces over the last ``window`` s: the largest of all, N, and the
    median over the rolls of each roll's largest over its mean and of its standard
    deviation, N."""
    w = t >= t[-1] - window
    f = force[w]
    mean = np.maximum(f.mean(axis=0), 1e-9)
    return {"max": round(float(f.max()), 1), "median_peak_over_mean": round(float(np.median(f.max(axis=0) / mean)), 3),
            "median_std": round(float(np.median(f.std(axis=0))), 1)}


def belt(s, **kw):
    return replace(s, belt=replace(s.belt, **kw))


def drums(s, **kw):
    return replace(s, pulleys=[replace(p, **kw) for p in s.pulleys])


VARIANTS = {
    "base": lambda s: s,
    "wrap": lambda s: belt(s, pulley_contact="wrap"),
    "mu_equal": lambda s: drums(s, friction=beltrs.Friction(static=0.35, kinetic=0.35)),
    "creep": lambda s: drums(s, friction=beltrs.Friction(static=0.4, kinetic=0.35, model="creep")),
    "tau1e4": lambda s: belt(s, damping_ratio=0.0, damping_time=1e-4),
    "tau3e4": lambda s: belt(s, damping_ratio=0.0, damping_time=3e-4),
    "tau1e3": lambda s: belt(s, damping_ratio=0.0, damping_time=1e-3),
    "no_idler_damp": lambda s: replace(s, idlers=[replace(i, contact_damping=0.0) for i in s.idlers]),
    "idler_damp4": lambda s: replace(s, idlers=[replace(i, contact_damping=4 * i.contact_damping) for i in s.idlers]),
    "no_gravity": lambda s: replace(s, gravity=0.0),
    "no_resistance": lambda s: replace(s, idlers=[replace(i, resistance=0.0) for i in s.idlers]),
    "big_rolls": lambda s: replace(s, idlers=[
        replace(i, radius=3 * i.radius, center=(i.center[0], i.center[1] - 2 * i.radius)) for i in s.idlers]),
    "no_roll_friction": lambda s: replace(s, idlers=[replace(i, friction=None) for i in s.idlers]),
    "zener": lambda s: belt(s, loss_factor=LOSS[0], loss_frequency=LOSS[1]),
    "zener_wrap": lambda s: belt(s, loss_factor=LOSS[0], loss_frequency=LOSS[1], pulley_contact="wrap"),
}

#: (loss factor, its frequency in Hz) of the ``zener`` variants (``--loss-factor``,
#: ``--loss-frequency``).
LOSS = [0.1, 5.0]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("variants", nargs="+", choices=sorted(VARIANTS))
    ap.add_argument("--duration", type=float, default=2.0, help="s of running")
    ap.add_argument("--window", type=float, default=1.0, help="last s analysed")
    ap.add_argument("--interval", type=float, default=0.0005, help="sample interval, s")
    ap.add_argument("--length", type=float, default=300.0, help="m")
    ap.add_argument("--element", type=float, default=None, help="element length, m (default: the builder's)")
    ap.add_argument("--pi", action="store_true", help="PI speed controller (default gains) on the head drive")
    ap.add_argument("--motor-inertia", type=float, default=0.0, help="kg*m^2 at the motor shaft (1500 rpm)")
    ap.add_argument("--speed", type=float, default=2.0, help="belt speed, m/s")
    ap.add_argument("--sag", action="store_true", help="place the spans in their sag (initial.sag)")
    ap.add_argument("--wrap", action="store_true", help='wrap contact (belt.pulley_contact = "wrap") on top')
    ap.add_argument("--roll-wrap", action="store_true", help='wrap contact on the rolls (belt.idler_contact = "wrap")')
    ap.add_argument("--windows", type=float, default=None,
                    help="also print the test figure in successive windows of this many s, and the lines "
                         "above 2 Hz over the last --window s")
    ap.add_argument("--save", help="write time and drive torque of the (last) variant to this .npz")
    ap.add_argument("--loss-factor", type=float, default=0.1, help="belt.loss_factor of the zener variants")
    ap.add_argument("--loss-frequency", type=float, default=5.0, help="belt.loss_frequency, Hz")
    args = ap.parse_args(argv)
    LOSS[:] = [args.loss_factor, args.loss_frequency]
    kw = {} if args.element is None else {"element_length": args.element}
    drive = DriveSpec("head", start_curve=beltrs.StartCurve("harrison", speed=args.speed, ramp=4.0),
                      inertia=args.motor_inertia, controller=beltrs.SpeedController() if args.pi else None)
    for name in args.variants:
        c = Conveyor(profile=[(0.0, 0.0), (args.length, 0.0)], belt="ST1250", capacity=500.0, speed=args.speed,
                     start="running", drives=[drive], **kw)
        scene = VARIANTS[name](c.scene())
        if args.sag:
            scene = replace(scene, initial=replace(scene.initial, sag=True))
        if args.wrap:
            scene = belt(scene, pulley_contact="wrap")
        if args.roll_wrap:
            scene = belt(scene, idler_contact="wrap")
        sim = beltrs.Simulation(scene)
        wall = time.perf_counter()
        res = sim.run(args.duration, record_interval=args.interval, tension=False, node_position=False,
                      node_velocity=False, progress=False)
        wall = time.perf_counter() - wall
        j = res.pulley_names.index("head")
        out = {"variant": name, "loss": LOSS if name.startswith("zener") else None,
               "pi": args.pi, "motor_inertia": args.motor_inertia, "element": args.element,
               "speed": args.speed, "sag": args.sag, "wrap": args.wrap, "roll_wrap": args.roll_wrap,
               "nodes": sim.nodes, "dt_us": round(sim.dt * 1e6, 2), "wall_s": round(wall, 1),
               "drive_torque": figures(res.time, res.drive_torque[:, j], args.window),
               "friction_torque": figures(res.time, -res.friction_torque[:, j], args.window),
               "roll_force": roll_figures(res.time, res.idler_force, args.window)}
        if args.windows:
            out["windows"] = window_figures(res.time, res.drive_torque[:, j], args.windows)
            out["lines"] = lines(res.time, res.drive_torque[:, j], args.window)
        if args.save:
            np.savez(args.save, time=res.time, torque=res.drive_torque[:, j])
        print(json.dumps(out), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

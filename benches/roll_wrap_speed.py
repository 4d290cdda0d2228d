"""Roll wrap at conveyor speeds (issue 12, session 10): a level builder conveyor (ST1250 1 m
wide, ``--capacity`` t/h, head drive on a Harrison curve to the belt speed, tail gravity
takeup, every other setting the builder's, roll wrap the builder's default) started from
its running design state at each belt speed, run ``--duration`` s; over the last
``--window`` s it prints one table row per speed:

- the drive torque's mean, its ripple above 2 Hz (max |tau - tau_2Hz| / |mean|, the figure
  of tests/test_ripple.py) and the rms of its part above 2 Hz (N*m);
- the rolls: the median over the rolls of each one's normal-force standard deviation (N)
  and the share of (roll, sample) pairs with the roll unloaded (no normal force);
- the belt's flight over the rolls: at each sample and roll the clearance of the node chain
  over the circle the wrap contact measures the path over (the smallest distance from the
  circle's centre to an element near the roll, less the circle's radius; > 0: no element
  touches the circle, the belt has left the roll), its largest value (mm) and the share of
  (roll, sample) pairs with a clearance; and the height over the circle of the node nearest
  the roll's top (the median over the rolls of each one's largest, and the largest, mm: a node
  on the straight pieces beside the arc reads up to about (l/2)^2/(2 R_w) without flying);
- the circle's radius R_w (m): ``max(R, 3 l, min(k v^2/g, 20 l))``, ``k`` = ``--k`` (the
  engine's ``contact::roll_wrap::FLIGHT_MARGIN``; 0: session 9's ``max(R, 3 l)``), the
  circle the clearance is read over; the engine's own law decides the run;
- the answer against the statics (``Conveyor.statics()``, DIN 22101): the mean tension over
  the window 10 m before the head drum on the carry and return strands over DIN's tension
  there (T1, T2), also over DIN's plus m'_G v^2 (the belt's centrifugal tension: a gravity
  takeup balances 2 (T - m'_G v^2) on its drum, so a running belt's tension stands m'_G v^2
  above the statics', which leave it out; 10 % at 8 m/s here), and the drive's mean pull
  (torque / drum radius) over DIN's F_U (session 13 measured +0.4 % at 2 m/s, 100 m, over
  3 s); and the rolls unloaded on the loaded carry strand alone (loading point to head).

``--formulation rigid_body`` runs the rigid-body belt (segment contact on its rolls: the
engine refuses roll wrap there; no clearance figures).

A script, not a test (docs/wrap-contact.md, "Session 10: roll wrap at speed").

    python benches/roll_wrap_speed.py --length 50 --speeds 2,3,4,5,6
    python benches/roll_wrap_speed.py --length 300 --speeds 4 --duration 3 --window 1
    python benches/roll_wrap_speed.py --length 50 --speeds 8,10,12 --formulation rigid_body
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

import beltrs
from beltrs.analysis import low_pass, tension_at
from beltrs.conveyor import Conveyor, DriveSpec

#: The engine's margin k of the wrap radius's flight term (``contact::roll_wrap::FLIGHT_MARGIN``).
FLIGHT_MARGIN = 1.4
#: The cap of that term in element lengths (``contact::roll_wrap::ARC_SPREAD_MAX``).
ARC_SPREAD_MAX = 20.0


def conveyor(length: float, speed: float, capacity: float, element: float | None,
             formulation: str = "node_kelvin_voigt") -> Conveyor:
    curve = beltrs.StartCurve("harrison", speed=speed, ramp=4.0)
    kw = {} if element is None else {"element_length": element}
    return Conveyor(profile=[(0.0, 0.0), (length, 0.0)], belt="ST1250", capacity=capacity, speed=speed,
                    start="running", drives=[DriveSpec("head", start_curve=curve)], formulation=formulation, **kw)


def scene(length: float, speed: float, capacity: float, contact: str, element: float | None,
          formulation: str = "node_kelvin_voigt") -> beltrs.Scene:
    from dataclasses import replace

    s = conveyor(length, speed, capacity, element, formulation).scene()
    if formulation == "rigid_body":
        return s
    return replace(s, belt=replace(s.belt, idler_contact=contact))


def clearance(pos: np.ndarray, scene: beltrs.Scene, rw: np.ndarray, up: np.ndarray,
              span: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """(samples, rolls) clearance of the node chain over each roll's wrap circle, m (at each
    sample the elements within ``span`` of the node nearest the roll's top), and the height of
    that node over the circle, m."""
    out = np.empty((pos.shape[0], len(scene.idlers)))
    height = np.empty_like(out)
    n = pos.shape[1]
    rows = np.arange(pos.shape[0])[:, None]
    for r, idler in enumerate(scene.idlers):
        c = np.asarray(idler.center, float)
        top = c + up[r] * idler.radius
        cw = top - up[r] * rw[r]
        k = np.argmin(np.linalg.norm(pos - top, axis=2), axis=1)
        height[:, r] = np.linalg.norm(pos[np.arange(pos.shape[0]), k] - cw, axis=1) - rw[r]
        idx = (k[:, None] + np.arange(-span, span)[None, :]) % n
        a, b = pos[rows, idx], pos[rows, (idx + 1) % n]
        d = b - a
        u = np.clip(np.einsum("tnk,tnk->tn", cw - a, d) / np.maximum(np.einsum("tnk,tnk->tn", d, d), 1e-30), 0, 1)
        foot = a + d * u[..., None]
        out[:, r] = np.linalg.norm(foot - cw, axis=2).min(axis=1) - rw[r]
    return out, height


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--length", type=float, default=50.0, help="m")
    ap.add_argument("--speeds", default="2,3,4,5,6", help="belt speeds, m/s, comma-separated")
    ap.add_argument("--capacity", type=float, default=500.0, help="t/h")
    ap.add_argument("--duration", type=float, default=2.0, help="s of each run")
    ap.add_argument("--window", type=float, default=1.0, help="last s analysed")
    ap.add_argument("--interval", type=float, default=0.0005, help="sample interval, s")
    ap.add_argument("--element", type=float, default=None, help="element length, m (default: the builder's)")
    ap.add_argument("--contact", default="wrap", choices=["wrap", "segment"])
    ap.add_argument("--formulation", default="node_kelvin_voigt", choices=["node_kelvin_voigt", "rigid_body"])
    ap.add_argument("--k", type=float, default=FLIGHT_MARGIN,
                    help="k of R_w = max(R, 3 l, k v^2/g) for the clearance figure (the engine's margin; 0: session 9)")
    a = ap.parse_args(argv)
    # Above 8 m/s a roll-wrap scene warns (beltrs.diagnostics.check_roll_wrap_speed): measuring
    # that range is this script's purpose.
    warnings.simplefilter("ignore", beltrs.AccuracyWarning)
    print("| speed, m/s | R_w, m | nodes | torque mean, N*m | ripple | rms above 2 Hz, N*m | roll force std, N "
          "| rolls unloaded | largest clearance, mm | share with clearance "
          "| node over the circle: median of the rolls' largest, mm | largest, mm "
          "| T1 / DIN | T2 / DIN | T1 / (DIN + m'v^2) | T2 / (DIN + m'v^2) | pull / F_U "
          "| loaded carry rolls unloaded | wall, s |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for v in (float(x) for x in a.speeds.split(",")):
        c = conveyor(a.length, v, a.capacity, a.element, a.formulation)
        s = scene(a.length, v, a.capacity, a.contact, a.element, a.formulation)
        sim = beltrs.Simulation(s)
        wall = time.perf_counter()
        res = sim.run(a.duration - a.window, record_interval=a.interval, tension=False, node_position=False,
                      node_velocity=False, progress=False)
        win = sim.run(a.window, record_interval=a.interval, tension=True, node_position=True,
                      node_velocity=False, progress=False)
        wall = time.perf_counter() - wall
        # The answer against the statics: strand tensions 10 m before the head drum, the pull.
        p = c.statics()
        r = c.radius
        t1 = float(tension_at(win.node_position, win.tension, (a.length - 10.0, 0.0)).mean())
        t2 = float(tension_at(win.node_position, win.tension, (a.length - 10.0, -2 * r)).mean())
        d1, d2 = float(p.along(a.length - 10.0)), float(p.along(a.length + 10.0))
        cf = c.belt_mass * v * v  # the belt's centrifugal tension, N
        pull = -float(win.drive_torque[:, win.pulley_names.index("head")].mean()) / r / p.effective
        loaded = np.array([i.center[1] > -r and c.loading <= i.center[0] for i in s.idlers])
        loaded_unloaded = float(np.mean(win.idler_force[:, loaded] <= 0.0))
        statics_cols = (f"{t1 / d1:.4f} | {t2 / d2:.4f} | {t1 / (d1 + cf):.4f} | {t2 / (d2 + cf):.4f} | {pull:.4f} | "
                        f"{loaded_unloaded:.4f}")
        j = win.pulley_names.index("head")
        t = np.concatenate([res.time, win.time[1:]])
        tau = np.concatenate([res.drive_torque[:, j], win.drive_torque[1:, j]])
        low = low_pass(tau, float(np.median(np.diff(t))), 2.0)
        w = t >= t[-1] - a.window
        mean = float(tau[w].mean())
        ripple = float(np.abs(tau - low)[w].max() / abs(mean))
        rms = float(np.std((tau - low)[w]))
        force = win.idler_force
        roll_std = float(np.median(force.std(axis=0)))
        unloaded = float(np.mean(force <= 0.0))
        if a.formulation == "rigid_body":
            print(f"| {v:g} | - | {sim.nodes} | {mean:.0f} | {ripple:.3f} | {rms:.0f} | {roll_std:.0f} | "
                  f"{unloaded:.4f} | - | - | - | - | {statics_cols} | {wall:.1f} |", flush=True)
            continue
        l0 = float(np.mean(sim.rest_length))
        g = s.gravity
        rw = np.array([max(i.radius, 3 * l0, min(a.k * v * v / g, ARC_SPREAD_MAX * l0)) for i in s.idlers])
        pos = win.node_position
        up = []
        for i in s.idlers:
            c = np.asarray(i.center, float)
            k = np.argmin(np.linalg.norm(pos[0] - c, axis=1))
            up.append((0.0, 1.0 if pos[0, k, 1] > c[1] else -1.0))  # level conveyor: the belt above or below
        gap, height = clearance(pos, s, rw, np.array(up))
        print(f"| {v:g} | {rw.max():.3f} | {sim.nodes} | {mean:.0f} | {ripple:.3f} | {rms:.0f} | {roll_std:.0f} | "
              f"{unloaded:.4f} | {1e3 * max(gap.max(), 0.0):.2f} | {np.mean(gap > 0):.4f} | "
              f"{1e3 * np.median(height.max(axis=0)):.2f} | {1e3 * height.max():.2f} | {statics_cols} | {wall:.1f} |",
              flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

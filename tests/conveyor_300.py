"""A 300 m builder conveyor for the chordal-ripple tests and benches/ripple.py (issue 12,
"true peaks, smooth drives"): level, ST1250 1 m wide, 500 t/h at 2 m/s, head drive on a
Harrison start, tail gravity takeup, every numerical setting the builder's default
(elements of 30 deg of arc on the 0.4 m drums)."""

from __future__ import annotations

import beltrs
from beltrs.conveyor import Conveyor, DriveSpec

LENGTH = 300.0
SPEED = 2.0


def conveyor_300(ramp: float = 10.0, length: float = LENGTH, capacity: float = 500.0, **kw) -> Conveyor:
    """The conveyor; ``ramp`` s of Harrison start to 2 m/s. ``kw`` go to ``Conveyor``."""
    curve = beltrs.StartCurve("harrison", speed=SPEED, ramp=ramp)
    return Conveyor(profile=[(0.0, 0.0), (length, 0.0)], belt="ST1250", capacity=capacity, speed=SPEED,
                    drives=[DriveSpec("head", start_curve=curve)], **kw)


def measure(sim: beltrs.Simulation, probe, pulley: str, duration: float, interval: float = 0.002,
            chunk: float = 0.5) -> dict:
    """Run ``sim`` for ``duration`` s in chunks of ``chunk`` s, sampling every ``interval``
    s the tension at the fixed point ``probe`` (:func:`beltrs.analysis.tension_at`), the
    largest element tension anywhere, and the drive torque and speed of ``pulley``; the
    whole-belt arrays of a chunk are dropped once read. Returns arrays ``time``,
    ``tension`` (at the probe), ``max_tension``, ``torque``, ``speed``."""
    import numpy as np

    from beltrs.analysis import tension_at

    out: dict = {k: [] for k in ("time", "tension", "max_tension", "torque", "speed")}
    end = sim.time + duration
    j = None
    while sim.time < end - 1e-9:
        res = sim.run(min(chunk, end - sim.time), record_interval=interval, tension=True, node_position=True,
                      node_velocity=False)
        if j is None:
            j = res.pulley_names.index(pulley)
        s = slice(1, None) if out["time"] else slice(None)  # each chunk starts where the last ended
        out["time"].append(res.time[s])
        out["tension"].append(tension_at(res.node_position[s], res.tension[s], probe))
        out["max_tension"].append(res.tension[s].max(axis=1))
        out["torque"].append(res.drive_torque[s, j])
        out["speed"].append(res.pulley_speed[s, j])
    return {k: np.concatenate(v) for k, v in out.items()}


def ripple_figures(data: dict, window: float, cutoff: float = 2.0, margin: float = 0.0) -> dict:
    """The issue-12 figures of a :func:`measure` record: raw and low-passed (below
    ``cutoff`` Hz) peak of the probe tension, the largest element tension, and over the
    ``window`` s ending ``margin`` s before the record's end the drive torque's mean, its
    ripple above ``cutoff`` (max |tau - tau_low| / |mean|) and half its peak-to-peak over the
    mean.

    ``margin``: the low-pass (:func:`beltrs.analysis.low_pass`, a brick-wall cut of the
    mirrored record) rings near the record's ends, where the mirror breaks the signal's
    slope, and its error there decays only as 1/(2 pi cutoff t); a window that ends at the
    record's last sample measures that ringing, not the torque (case G with roll wrap: 0.83
    against 0.46 for the same window filtered inside a 20 s record; 0.52 with 1 s of margin,
    docs/wrap-contact.md "Session 9: what is left")."""
    import numpy as np

    from beltrs.analysis import low_pass

    t = data["time"]
    step = float(np.median(np.diff(t)))
    low = low_pass(data["tension"], step, cutoff)
    tau = data["torque"]
    tau_low = low_pass(tau, step, cutoff)
    end = t[-1] - margin
    w = (t >= end - window) & (t <= end + 1e-9)
    mean = float(tau[w].mean())
    return {
        "raw_peak": float(data["tension"].max()),
        "raw_peak_time": float(t[data["tension"].argmax()]),
        "low_peak": float(low.max()),
        "low_peak_time": float(t[low.argmax()]),
        "max_tension": float(data["max_tension"].max()),
        "torque_mean": mean,
        "torque_min": float(tau[w].min()),
        "torque_max": float(tau[w].max()),
        "torque_ripple": float(np.abs(tau - tau_low)[w].max() / abs(mean)),
        "torque_half_swing": float((tau[w].max() - tau[w].min()) / 2 / abs(mean)),
        "speed_mean": float(data["speed"][w].mean()),
        "tension_mean": float(data["tension"][w].mean()),
    }


def shaft_torque(data: dict, scene: beltrs.Scene, pulley: str = "head"):
    """The torque in the gearbox's output shaft of ``pulley``'s drive from a :func:`measure`
    record: the drive's torque (the motor's air-gap torque through a lossless gearbox) less
    what accelerates the rotor and coupling, J·i²·dω/dt with J·i² the drive's ``inertia``
    reflected to the drum (docs/drives.md, "Which torque ..."), dω/dt by central differences
    of the recorded drum speed. N·m, clockwise negative like ``drive_torque``."""
    import numpy as np

    inertia = scene.pulleys[scene.pulley_index(pulley)].drive.inertia
    return data["torque"] - inertia * np.gradient(data["speed"], data["time"])

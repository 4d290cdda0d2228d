"""The chordal ripple of the tight-side tension on a shortened case G running at full speed,
for either belt formulation and the settings that might change it (docs/case-g.md, "The raw
peak at today's defaults").

Builds :func:`beltrs.scenes.guo_wang_conveyor` from its running design state (belt at 2 m/s,
steady tensions, no ramp), reads T1 10 m before the head drum every ``--interval`` s for
``--duration`` s and prints one JSON line: the ripple (T1 less its part below 2 Hz, by
:func:`beltrs.analysis.low_pass`) over the last 1.5 s but 0.2 s (the start's transient before,
the filter's end effect after), its rms and largest value, N, and its five strongest lines
(Hz, N amplitude, Hann window). Run from the repository root with beltrs installed::

    python benches/chordal_ripple.py rigid_body                    # 100 m, 3 s, defaults
    python benches/chordal_ripple.py rigid_body --element 0.1      # shorter bodies
    python benches/chordal_ripple.py rigid_body --drums-alone      # no gravity, no material
    python benches/chordal_ripple.py node_kelvin_voigt --drums nodes --drums-alone
    python benches/chordal_ripple.py rigid_body --drums wrap       # the rigid belt's wrap joints

About 30-130 s of wall each at 100 m (one thread).
"""

from __future__ import annotations

import argparse
from dataclasses import replace
import json
import time

import numpy as np

import beltrs
from beltrs.analysis import low_pass, probe_run
from beltrs.scenes import GUO_WANG, guo_wang_conveyor

CUTOFF = 2.0  # Hz, as benches/case_g.py
PROBE = 10.0  # m before the head drum's centre


def scene_for(args: argparse.Namespace) -> beltrs.Scene:
    """The scene the options describe."""
    curve = beltrs.StartCurve(shape="harrison", speed=GUO_WANG["speed"], ramp=10.0)
    material = 0.0 if args.drums_alone else GUO_WANG["material"]
    scene = guo_wang_conveyor(curve, length=args.length, formulation=args.formulation, start="running",
                              element_length=args.element, material=material)
    belt = scene.belt
    if args.drums:
        belt = replace(belt, pulley_contact=args.drums)
    if args.rolls:
        belt = replace(belt, idler_contact=args.rolls)
    pulleys = scene.pulleys
    if args.drum_friction:
        pulleys = [replace(p, friction=replace(p.friction, model=args.drum_friction)) for p in pulleys]
    if args.drum_stiffness is not None:
        pulleys = [replace(p, contact_stiffness=args.drum_stiffness) for p in pulleys]
    if args.drum_damping is not None:
        pulleys = [replace(p, contact_damping_ratio=args.drum_damping) for p in pulleys]
    scene = replace(scene, belt=belt, pulleys=pulleys)
    if args.drums_alone:
        # No weight on the rolls: a winch holds the tail's 2 x 50 kN that the counterweight gave.
        winch = beltrs.Takeup(kind="winch", force=2 * GUO_WANG["takeup_tension"], direction=(-1.0, 0.0))
        scene = replace(scene, gravity=0.0, loads=[],
                        pulleys=[replace(scene.pulleys[0], takeup=winch)] + list(scene.pulleys[1:]))
    return scene


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("formulation", choices=("node_kelvin_voigt", "rigid_body"))
    ap.add_argument("--length", type=float, default=100.0, help="centre distance, m (default 100)")
    ap.add_argument("--duration", type=float, default=3.0, help="s run (default 3)")
    ap.add_argument("--interval", type=float, default=0.001, help="s between readings (default 0.001)")
    ap.add_argument("--element", type=float, default=0.2, help="element (body) length, m (default 0.2)")
    ap.add_argument("--drums", choices=("nodes", "wrap"),
                    help="drum contact (default: builder's); wrap with rigid_body: wrap joints")
    ap.add_argument("--rolls", choices=("segment", "wrap"), help="node belt's roll contact (default: builder's)")
    ap.add_argument("--drums-alone", action="store_true",
                    help="no gravity and no material (the rolls carry nothing), a winch takeup")
    ap.add_argument("--drum-damping", type=float, help="drums' contact damping ratio (default 0.2)")
    ap.add_argument("--drum-stiffness", type=float, help="drums' contact stiffness, N/m (default 1e8)")
    ap.add_argument("--drum-friction", choices=("stick_force", "creep"),
                    help="drums' friction model (default stick_force)")
    args = ap.parse_args(argv)
    scene = scene_for(args)
    t0 = time.perf_counter()
    sim = beltrs.Simulation(scene)
    r = GUO_WANG["drum_radius"]
    data = probe_run(sim, [(args.length - PROBE, r)], args.duration, args.interval)
    wall = time.perf_counter() - t0
    t, t1 = data["time"], data["tension"][:, 0]
    smooth = low_pass(t1, args.interval, CUTOFF)
    window = (t >= t[-1] - 1.5) & (t <= t[-1] - 0.2)
    ripple = (t1 - smooth)[window]
    freq = np.fft.rfftfreq(window.sum(), args.interval)
    amp = np.abs(np.fft.rfft(ripple * np.hanning(window.sum()))) * 4 / window.sum()
    top = np.argsort(amp)[::-1][:5]
    head = scene.pulley_index("head")
    out = {"formulation": args.formulation, "options": {k: v for k, v in vars(args).items() if k != "formulation"},
           "nodes": sim.nodes, "dt": sim.dt, "wall": round(wall, 1), "T1_mean": float(t1[window].mean()),
           "ripple_rms": float(ripple.std()), "ripple_max": float(np.abs(ripple).max()),
           "lines": [(round(float(freq[k]), 2), round(float(amp[k]))) for k in top],
           "drum_speed": float(np.mean(-data["pulley_speed"][window, head] * r))}
    print(json.dumps(out), flush=True)
    return out


if __name__ == "__main__":
    main()

"""Case H torque pulse (thesis §6.4.2): run the scene file and measure the wave speed.

    python examples/case_h_torque_pulse.py [examples/case_h_torque_pulse.toml]

Runs the scene as its [recording] table says (relax, then 3.6 s), then reads the arrival
of the tension front at two elements 10 elements (26 m of belt) apart on each vertical
strand and compares the speed with sqrt(EA / rho).
"""

import sys
from pathlib import Path

import numpy as np

import beltrs
from beltrs.analysis import arrival_time

path = sys.argv[1] if len(sys.argv) > 1 else Path(__file__).with_suffix(".toml")
scene = beltrs.load_scene(path)
sim = beltrs.Simulation(scene)
rec = scene.recording
if rec.stabilise:
    sim.stabilise(friction=rec.stabilise_friction)
res = sim.run(rec.duration, **rec.run_kwargs())
print(f"{path}: {sim.nodes} elements, {len(res)} samples, {res.wall_time:.3f} s wall")

x = res.node_position[0]
mid = 0.5 * (x + np.roll(x, -1, axis=0))  # element midpoints
c = np.sqrt(scene.belt.axial_stiffness / scene.belt.mass_per_length)
for side, name in ((-1, "left"), (1, "right")):
    strand = np.where((side * mid[:, 0] > 4) & (mid[:, 1] > 10) & (mid[:, 1] < 90))[0]
    a, b = strand[2], strand[12]
    ta = arrival_time(res.time, res.tension[:, a])
    tb = arrival_time(res.time, res.tension[:, b])
    speed = abs(b - a) * sim.rest_length[0] / abs(tb - ta)
    print(f"  {name} strand: front at elements {a} and {b} at {ta:.3f} s and {tb:.3f} s: "
          f"{speed:.1f} m/s (sqrt(EA/rho) = {c:.1f} m/s)")
print(f"  peak tension {res.tension.max() / 1e3:.1f} kN, lowest {res.tension.min() / 1e3:.1f} kN")

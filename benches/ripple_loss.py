"""The test figures of tests/test_ripple.py (issue 12) with a viscoelastic belt: case G
150 m or the 300 m builder conveyor, wrap contact, a 4 s Harrison start and 4 s at speed,
the drive torque over the last 2 s (mean, min, max, ripple above 2 Hz over the mean), with
``belt.loss_factor`` set (peak at the default 5 Hz). Prints one JSON line. A script, not a
test (docs/wrap-contact.md, "What is not fixed").

    python benches/ripple_loss.py case_g 0.1
    python benches/ripple_loss.py conveyor 0.3
"""

from __future__ import annotations

import json
import sys
import time
from dataclasses import replace
from pathlib import Path

import beltrs
from beltrs.scenes import GUO_WANG, guo_wang_conveyor

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from conveyor_300 import conveyor_300, measure, ripple_figures  # noqa: E402

RAMP, STEADY, WINDOW = 4.0, 4.0, 2.0


def main(argv: list[str]) -> int:
    which, eta = argv[0], float(argv[1])

    def lossy(scene: beltrs.Scene) -> beltrs.Scene:
        return replace(scene, belt=replace(scene.belt, pulley_contact="wrap", loss_factor=eta))

    t0 = time.perf_counter()
    if which == "case_g":
        length = 150.0
        curve = beltrs.StartCurve(shape="harrison", speed=GUO_WANG["speed"], ramp=RAMP)
        sim = beltrs.Simulation(lossy(guo_wang_conveyor(curve, length=length)))
        sim.stabilise(tolerance=1e-5, max_steps=400_000)
        data = measure(sim, (length - 10.0, GUO_WANG["drum_radius"]), "head", RAMP + STEADY)
    else:
        scene = lossy(conveyor_300(ramp=RAMP).scene())
        sim = beltrs.Simulation(scene)
        sim.stabilise(friction=scene.recording.stabilise_friction, tolerance=1e-5, max_steps=400_000)
        data = measure(sim, (290.0, 0.0), "head", RAMP + STEADY)
    f = ripple_figures(data, WINDOW)
    f.update(which=which, loss_factor=eta, dt_us=sim.dt * 1e6, wall_s=time.perf_counter() - t0)
    print(json.dumps(f), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))

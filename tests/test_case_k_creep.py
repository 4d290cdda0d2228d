"""Case K (Kubas 2014) with the paper's creep-rate friction: the steady answers under central
differences (docs/kubas.md, "Case K with creep friction").

Scene: ``beltrs.scenes.kubas_case_k`` (150 rigid bodies, Kubas's nonlinear contact, relaxed
preload), creep friction µs 1.05, µk 1.0, Δv = 1e-5 m/s, Δmax = 1e-4 m on both pulleys,
central differences at the default step. The torque is ramped to 15 N·m over 0.05 s (the
pulleys follow within I/c = 0.4 ms); 0.3 s, averages over the last 0.1 s.

Why 0.3 s: measured with ``python benches/case_k_creep.py steady --ramp 0.05 --window 0.1
--duration D``: T₁ − T₂ is −0.84 / −0.78 / −0.76 % of M/r at D = 0.15 / 0.3 / 0.45 s and
T₁ + T₂ −0.18 / +0.07 / +0.06 % of twice the preload (the 0.5 s run with the paper's 0.3 s
ramp: −0.80 %, +0.11 %), but the slip reads 0.311 % at 0.15 s (below the elastic creep: the
arcs have not settled) and 0.411 / 0.456 % at 0.3 / 0.45 s (0.441 % at 0.5 s). 0.3 s is
the shortest of these with every quantity in its steady band.
"""

from __future__ import annotations


import numpy as np
import pytest

import beltrs
from beltrs.analytic import two_pulley_creep

RADIUS, DISTANCE, EA, RHO, TORQUE = 0.027, 0.515, 1.52e5, 0.096, 15.0


@pytest.mark.slow
def test_case_k_paper_creep_steady_answers():
    scene = beltrs.scenes.kubas_case_k(ramp_time=0.05)
    for p in scene.pulleys:
        p.friction = beltrs.Friction(model="creep", static=1.05, kinetic=1.0, transition_speed=1e-5, creep_limit=1e-4)
    sim = beltrs.Simulation(scene)
    assert sim.stabilise(progress=False)["converged"]
    preload = float(np.mean(sim.tensions()))
    res = sim.run(0.3, record_interval=1e-3, node_velocity=False, progress=False)
    x = res.node_position
    mid = 0.5 * (x + np.roll(x, -1, axis=1))
    inner = (mid[..., 0] > DISTANCE / 3) & (mid[..., 0] < 2 * DISTANCE / 3)
    w = res.time >= 0.2
    t1 = float(np.nanmean(np.where(inner & (mid[..., 1] > 0), res.tension, np.nan)[w]))
    t2 = float(np.nanmean(np.where(inner & (mid[..., 1] < 0), res.tension, np.nan)[w]))
    speeds = np.abs(res.pulley_speed[w]).mean(axis=0)
    slip = 1 - speeds[1] / speeds[0]
    theory = two_pulley_creep(
        drive_radius=RADIUS, driven_radius=RADIUS, centre_distance=DISTANCE, axial_stiffness=EA,
        mass_per_length=RHO, pretension=preload, mu=1.0, drive_speed=float(speeds[0]), load_torque=TORQUE,
    )
    mr = TORQUE / RADIUS
    # The drive pulley's balance in steady running is exact, T1 - T2 = M/r (555.6 N); 2 % is
    # the target of the issue and covers the read-out in the spans (measured -0.78 %).
    assert abs((t1 - t2) / mr - 1) < 0.02, (t1, t2)
    # A closed belt keeps its length, so the span tensions straddle the preload: T1 + T2 =
    # 2 x preload up to the arcs' share of the stretch (measured +0.07 %); 0.5 % separates it
    # from the stick-force model, whose arcs hold the spacing they arrived with (-2.9 %).
    assert abs((t1 + t2) / (2 * preload) - 1) < 0.005, (t1, t2, preload)
    # Creep theory at the measured drive speed (measured -0.56 % on T1, -0.14 % on T2); 1.5 %:
    # the rigid bodies' polygon round the rims holds a^2/12 more belt (+3 N on both spans,
    # docs/kubas.md) and the creep law's mu lies between mu_k and mu_s on the slip arcs.
    assert abs(t1 / theory.tight_tension - 1) < 0.015, (t1, theory.tight_tension)
    assert abs(t2 / theory.slack_tension - 1) < 0.015, (t2, theory.slack_tension)
    # Slip: at least the elastic creep of creep theory (0.363 %; the soft contact's sink
    # only adds to it: the mass centres run at omega*(r - p), p deeper under T1), and at
    # most 0.25 points above it (measured 0.41-0.46 % over 0.1 s windows from 0.3 to 0.5 s):
    # a belt that slid on an arc, or the paper's 1.5 %, would fail.
    assert 0.98 * theory.creep <= slip <= theory.creep + 0.0025, (slip, theory.creep)

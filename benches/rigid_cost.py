"""The rigid-body belt's step against the node belt's: element-steps per second of both
formulations on the same scenes, in one process (a script that prints figures, not a test).

Run from the repository root, with beltrs installed::

    python benches/rigid_cost.py [--repeats N] [--steps N] [--scenes conveyor,case_k,case_k_ends]
                                 [--rkf45] [--checkpoints DIR]

Scenes (each with both belt formulations, ``belt.formulation``):

- ``conveyor``: ``beltrs.scenes.guo_wang_conveyor(length=200, start="running")``, case G's
  conveyor at 200 m (about 2000 elements of 0.2 m, 232 idlers, material, speed-controlled
  head drive, tail takeup; the rigid belt about 3400 bodies of 0.1185 m since session 13,
  the builders' l <= 0.3 R), from its running design start, 200 steps of warm-up.
- ``case_k``: ``beltrs.scenes.kubas_case_k()`` (150 elements, two pulleys with Kubas's
  nonlinear contact, stick-force friction, torque drive), relaxed, 20 000 steps of warm-up.
- ``case_k_ends``: the same with the linear penalty contact (the rigid bodies rest on the
  drums with their two ends, ``belt::rigid::contact``).

Each figure is the median over ``repeats`` timed calls of ``Simulation.step(steps)``, the
formulations interleaved (so both see the same machine); element-steps/s = elements ×
steps / wall. The ratio node/rigid per element-step is printed too: the rigid bodies' step
is also about half as long (their stable step), which this does not count.

``--rkf45``: also case K (both contacts, rigid bodies, the paper's creep friction: µs 1.05,
µk 1.0, Δv 1e-5 m/s, Δmax 1e-4 m) under RKF45 (default tolerances) against central
differences, per attempted RKF45 step and per force evaluation: the adaptive integrator's
overhead beyond its six evaluations.

``--checkpoints DIR``: write each warmed-up simulation to ``DIR/<scene>_<formulation>.ckpt``
(and, with ``--rkf45``, the creep-friction ones to ``DIR/<scene>_creep_rigid_body.ckpt``) for
``rust/examples/rigid_loop.rs`` (stepping without Python; callgrind; its ``rkf45`` argument
runs a checkpoint's state under RKF45).
"""

from __future__ import annotations

import argparse
import copy
import os
import statistics
import time

import beltrs
from beltrs.scenes import guo_wang_conveyor, kubas_case_k

FORMULATIONS = ("node_kelvin_voigt", "rigid_body")


def build(scene: str, formulation: str, creep: bool = False) -> beltrs.Simulation:
    """A warmed-up simulation of `scene` with `formulation` (case K with the paper's creep
    friction if `creep`)."""
    if scene == "conveyor":
        sim = beltrs.Simulation(guo_wang_conveyor(length=200.0, start="running", formulation=formulation))
        sim.step(200)
        return sim
    s = kubas_case_k()
    s.belt.formulation = formulation
    if scene == "case_k_ends":
        for p in s.pulleys:
            p.nonlinear_contact = None
    if creep:
        for p in s.pulleys:
            p.friction = beltrs.Friction(model="creep", static=1.05, kinetic=1.0,
                                         transition_speed=1e-5, creep_limit=1e-4)
    sim = beltrs.Simulation(s)
    if not sim.stabilise(progress=False)["converged"]:
        raise RuntimeError(f"{scene} {formulation}: relaxation did not converge")
    sim.step(20_000)
    return sim


def timed(sim: beltrs.Simulation, steps: int) -> float:
    t0 = time.perf_counter()
    sim.step(steps)
    return time.perf_counter() - t0


def measure(scene: str, steps: int, repeats: int, checkpoints: str | None) -> dict[str, float]:
    sims = {f: build(scene, f) for f in FORMULATIONS}
    if checkpoints:
        os.makedirs(checkpoints, exist_ok=True)
        for f, sim in sims.items():
            sim.save_checkpoint(os.path.join(checkpoints, f"{scene}_{f}.ckpt"))
    walls: dict[str, list[float]] = {f: [] for f in FORMULATIONS}
    for _ in range(repeats):
        for f, sim in sims.items():
            walls[f].append(timed(sim, steps))
    rates = {}
    for f, sim in sims.items():
        w = statistics.median(walls[f])
        rates[f] = sim.elements * steps / w
        print(f"  {scene:12s} {f:18s} {sim.elements:5d} elements  dt {sim.dt:.3e} s  "
              f"{w / steps * 1e6:9.2f} us/step  {rates[f]:.3e} element-steps/s "
              f"({1e9 / rates[f]:.1f} ns per element-step; "
              f"repeats {min(walls[f]) / w:.2f}-{max(walls[f]) / w:.2f} of the median)")
    ratio = rates["node_kelvin_voigt"] / rates["rigid_body"]
    print(f"  {scene:12s} rigid costs {ratio:.2f}x the node belt per element-step")
    return rates


def measure_rkf45(scene: str, steps: int, repeats: int, checkpoints: str | None) -> None:
    """RKF45 against central differences on the rigid-body belt of `scene`: wall per attempted
    step and per force evaluation."""
    cd = build(scene, "rigid_body", creep=True)
    if checkpoints:
        cd.save_checkpoint(os.path.join(checkpoints, f"{scene}_creep_rigid_body.ckpt"))
    rk_scene = copy.deepcopy(cd.scene)
    rk_scene.solver.integrator = "rkf45"
    rk = beltrs.Simulation(rk_scene)
    if not rk.stabilise(progress=False)["converged"]:
        raise RuntimeError(f"{scene} under RKF45: relaxation did not converge")
    rk.step(200)

    def attempted() -> int:
        return int(rk._core.accepted_steps) + int(rk._core.rejected_steps)

    walls: dict[str, list[float]] = {"cd": [], "rkf45": []}
    attempts: list[int] = []
    for _ in range(repeats):
        walls["cd"].append(timed(cd, steps))
        before = attempted()
        walls["rkf45"].append(timed(rk, steps))
        attempts.append(attempted() - before)
    cd_step = statistics.median(walls["cd"]) / steps
    per_attempt = statistics.median([w / a for w, a in zip(walls["rkf45"], attempts)])
    print(f"  {scene:12s} rigid_body: central differences {cd_step * 1e6:.2f} us/step; RKF45 "
          f"{per_attempt * 1e6:.2f} us per attempted step ({statistics.median(attempts)} attempts per "
          f"{steps} model steps of time) = {per_attempt / cd_step:.1f}x a central-difference step, "
          f"{per_attempt / 6 / cd_step:.2f}x per force evaluation (6 per attempt)")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--scenes", default="conveyor,case_k,case_k_ends")
    ap.add_argument("--rkf45", action="store_true")
    ap.add_argument("--checkpoints", default=None)
    a = ap.parse_args()
    print(f"beltrs {beltrs.__version__}; medians of {a.repeats} calls of step({a.steps}), formulations interleaved")
    for scene in a.scenes.split(","):
        measure(scene, a.steps, a.repeats, a.checkpoints)
    if a.rkf45:
        for scene in ("case_k", "case_k_ends"):
            measure_rkf45(scene, max(1, a.steps // 10), a.repeats, a.checkpoints)


if __name__ == "__main__":
    main()

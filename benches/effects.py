"""Cost per step of each effect, for case H and for a long idler conveyor.

For each effect the script times three scenes that differ only in that effect:

* ``ref``: the reference scene (the baseline plus the effect's prerequisites, e.g. idlers
  for idler friction);
* ``off``: the reference with the effect present in the scene but disabled by its own
  parameter (g = 0, EI = 0, damping ratio 0, contact stiffness 0, mu = 0; idlers, takeups
  and drives are simply absent, as that is how a scene has none);
* ``on``: the reference with the effect switched on.

It prints (a) ``off/ref``: a disabled effect adds nothing measurable (the ratio of the time
per step is 1 within noise, measured in the same run with the scenes interleaved); (b) the
increment ``on - ref`` next to the time the stage profile (``sim.set_profiling``) books to
the effect's stages, and their ratio. The baseline is axial springs and pulley contact on a
pretensioned belt (the belt is 0.1 % shorter than its path), without gravity; for "pulley
contact" itself the reference is the belt with no contact at all. "all" switches everything
on and compares with the baseline.

Each round times the three scenes in random order; ``off/ref`` and the increment are
taken within a round (neighbours in time, so slow drifts of a shared machine cancel) and
the table gives their medians over the rounds, with the interquartile range of ``off/ref``
as the noise it is judged against. Stage profiles are medians too, from separate copies of
the scenes with profiling on. Wall clock, single thread; steps run without recording
(``sim.step``). Run ``python benches/effects.py`` (about a minute);
``--quick`` for a short smoke run, ``--markdown`` to print the table for docs/effects.md.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import random
import statistics
import time
from dataclasses import replace
from typing import Callable

import beltrs
from beltrs import Belt, Brake, Drive, Friction, Idler, Load, Pulley, Scene, StartCurve, Takeup

EFFECTS = [
    "gravity",
    "bending",
    "damping",
    "pulley_contact",
    "pulley_friction",
    "idlers",
    "idler_friction",
    "takeup",
    "drives",
    "speed_drive",
    "loads",
    "running_resistance",
]
# Stages that an effect adds to the compiled list.
STAGES = {
    "gravity": [],  # folded into the axial pass: no stage of its own
    "bending": ["bending"],
    "damping": ["axial_damped"],  # replaces "axial"; the increment is axial_damped - axial
    "pulley_contact": ["pulley_contact"],
    "pulley_friction": ["pulley_friction"],
    "idlers": ["idler_contact"],
    "idler_friction": ["idler_friction"],
    "takeup": [],  # moved by the integrator: no stage of its own
    "drives": ["drives", "brakes"],
    "speed_drive": ["drives", "speed_drives"],
    "loads": ["loads"],
    "running_resistance": ["running_resistance"],
}
PREREQUISITES = {"idler_friction": {"idlers"}, "running_resistance": {"idlers"}}
BASELINE = frozenset({"pulley_contact"})
PRETENSION = 0.001  # the belt is this much shorter than its path


def case_h(on: frozenset, off: frozenset = frozenset()) -> Scene:
    """Case H (two 5 m pulleys 100 m apart, 89 elements) with the chosen effects; 20 idlers
    (10 per strand, touching from outside) when idlers are on."""
    e, w, t = 300e6, 1.0, 0.0254
    path = 2 * 100.0 + 2 * math.pi * 5.0
    belt = Belt(
        axial_stiffness=e * w * t,
        mass_per_length=100.0,
        bending_stiffness=e * w * t**3 / 12 if "bending" in on else 0.0,
        damping_ratio=0.05 if "damping" in on else 0.0,
        elements=89,
        length=path * (1 - PRETENSION),
    )
    k = 2e8 if "pulley_contact" in on else 0.0
    mu = Friction(0.5, 0.4) if "pulley_friction" in on else (Friction(0.0) if "pulley_friction" in off else None)
    upper = Pulley(
        name="upper", center=(0.0, 100.0), radius=5.0, mass=600.0, inertia=15_000.0, contact_stiffness=k, friction=mu
    )
    lower = replace(upper, name="lower", center=(0.0, 0.0))
    if "takeup" in on:
        lower.takeup = Takeup(counterweight=30_000.0)
    if "drives" in on:
        upper.drive = Drive.constant(1e4)
        lower.brake = Brake(capacity=[1e3])
    if "speed_drive" in on:  # replaces the torque drive when both are on
        upper.drive = Drive(start_curve=StartCurve(speed=1.0, ramp=1.0))
    idlers = []
    if "idlers" in on:
        imu = Friction(0.3) if "idler_friction" in on else (Friction(0.0) if "idler_friction" in off else None)
        f = 0.02 if "running_resistance" in on else 0.0
        r = 0.0635
        for y in range(10, 100, 9):
            idlers.append(Idler(center=(5.0 + r, float(y)), friction=imu, resistance=f))
            idlers.append(Idler(center=(-5.0 - r, float(y)), friction=imu, resistance=f))
    return Scene(
        belt=belt,
        pulleys=[upper, lower],
        idlers=idlers,
        gravity=9.81 if "gravity" in on else 0.0,
        loads=_loads(on, off, (5.0, 20.0), (5.0, 80.0)),
    )


def _loads(on: frozenset, off: frozenset, start: tuple, end: tuple) -> list[Load]:
    """50 kg/m from ``start`` to ``end`` when on; the same load of zero mass when off."""
    if "loads" in on:
        return [Load(mass_per_length=50.0, start=start, end=end)]
    return [Load(mass_per_length=0.0, start=start, end=end)] if "loads" in off else []


def conveyor(on: frozenset, off: frozenset = frozenset(), length: float = 860.0) -> Scene:
    """A horizontal conveyor: tail pulley at x = 0 (horizontal gravity takeup when on), head
    pulley at x = ``length`` (drive when on, and a brake on the tail), both 0.5 m radius;
    carry idlers every 1.2 m under the top strand, return idlers every 3 m under the
    bottom strand (715 + 286 = 1001 idlers for 860 m), 0.3 m elements (5744 nodes),
    30 kg/m, EA = 20 MN."""
    radius, r_idler = 0.5, 0.0635
    path = 2 * length + 2 * math.pi * radius
    elements = int(round(path / 0.3))
    belt = Belt(
        axial_stiffness=2e7,
        mass_per_length=30.0,
        bending_stiffness=50.0 if "bending" in on else 0.0,
        damping_ratio=0.05 if "damping" in on else 0.0,
        elements=elements,
        length=path * (1 - PRETENSION),
    )
    k = 1e8 if "pulley_contact" in on else 0.0
    mu = Friction(0.35, 0.3) if "pulley_friction" in on else (Friction(0.0) if "pulley_friction" in off else None)
    tail = Pulley(name="tail", center=(0.0, 0.0), radius=radius, mass=500.0, contact_stiffness=k, friction=mu)
    head = replace(tail, name="head", center=(length, 0.0))
    if "takeup" in on:
        tail.takeup = Takeup(counterweight=2000.0, direction=(-1.0, 0.0))
    if "drives" in on:
        head.drive = Drive.constant(2e3)
        tail.brake = Brake(capacity=[50.0])
    if "speed_drive" in on:  # replaces the torque drive when both are on
        head.drive = Drive(start_curve=StartCurve(speed=-1.0, ramp=5.0))
    idlers = []
    if "idlers" in on:
        imu = Friction(0.3) if "idler_friction" in on else (Friction(0.0) if "idler_friction" in off else None)
        f = 0.02 if "running_resistance" in on else 0.0
        # Node order runs counter-clockwise: the bottom strand goes tail -> head (return),
        # the top strand head -> tail (carry). Idlers touch the belt centre line from below.
        x = 1.2
        while x < length - 1.0:
            idlers.append(Idler(center=(x, radius - r_idler), radius=r_idler, friction=imu, resistance=f))
            x += 1.2
        x = 1.5
        while x < length - 1.0:
            idlers.append(Idler(center=(x, -radius - r_idler), radius=r_idler, friction=imu, resistance=f))
            x += 3.0
    return Scene(belt=belt, pulleys=[tail, head], idlers=idlers, gravity=9.81 if "gravity" in on else 0.0,
                 loads=_loads(on, off, (5.0, radius), (length - 5.0, radius)))


def per_step(sim: beltrs.Simulation, steps: int) -> float:
    t0 = time.perf_counter()
    sim.step(steps)
    return (time.perf_counter() - t0) / steps


def measure(builders: dict[str, Callable[[], Scene]], repeats: int, budget: float) -> tuple[dict, dict, dict]:
    """Time per step of each scene in each of ``repeats`` rounds (scenes in random order
    within a round, so that ratios can be taken between neighbours in time), the median
    profile per step of each stage, and the compiled stages. ``budget``: seconds per
    measurement."""
    sims = {name: beltrs.Simulation(b()) for name, b in builders.items()}
    profiled = {name: beltrs.Simulation(b()) for name, b in builders.items()}
    steps = {}
    for name, sim in sims.items():
        sim.step(200)  # warm up: caches, first contacts
        profiled[name].step(200)
        est = per_step(sim, 200)
        profiled[name].step(200)
        steps[name] = max(50, int(budget / est))
    samples: dict[str, list[float]] = {name: [] for name in sims}
    stage_samples: dict[str, dict[str, list[float]]] = {name: {} for name in sims}
    rng = random.Random(1)
    for _ in range(repeats):
        order = list(sims)
        rng.shuffle(order)  # no scene always runs first (or right after a given one)
        for name in order:
            samples[name].append(per_step(sims[name], steps[name]))
        for name in order:
            p = profiled[name]
            p.set_profiling(True)
            p.step(steps[name])
            for stage, t in p.profile().items():
                stage_samples[name].setdefault(stage, []).append(t / steps[name])
            p.set_profiling(False)
    profiles = {name: {s: statistics.median(v) for s, v in d.items()} for name, d in stage_samples.items()}
    stages = {name: sim.stages for name, sim in sims.items()}
    return samples, profiles, stages


def effect_table(case: str, build: Callable[..., Scene], repeats: int, budget: float) -> list[dict]:
    rows = []
    for effect in EFFECTS + ["all"]:
        if effect == "all":
            ref_on = BASELINE
            on = frozenset(EFFECTS)
            off_kw = frozenset(EFFECTS) - BASELINE
        elif effect == "pulley_contact":
            ref_on = frozenset()
            on = BASELINE
            off_kw = frozenset({effect})
        else:
            ref_on = BASELINE | PREREQUISITES.get(effect, set())
            on = ref_on | {effect}
            off_kw = frozenset({effect})
        builders = {
            "ref": lambda r=ref_on: build(r),
            "off": lambda r=ref_on, o=off_kw: build(r, o),
            "on": lambda o=on: build(o),
        }
        samples, prof, stages = measure(builders, repeats, budget)
        med = {name: statistics.median(v) for name, v in samples.items()}
        # Ratios within a round (neighbours in time), then their median and spread: the
        # spread is the noise a "nothing measurable" claim is judged against.
        ratios = sorted(o / r for o, r in zip(samples["off"], samples["ref"]))
        q1, q3 = statistics.quantiles(ratios, n=4)[0], statistics.quantiles(ratios, n=4)[2]
        increments = [o - r for o, r in zip(samples["on"], samples["ref"])]
        if effect == "all":
            booked = sum(prof["on"].values()) - sum(prof["ref"].values())
        else:
            booked = sum(prof["on"].get(s, 0.0) for s in STAGES[effect])
            if effect == "damping":
                booked -= prof["ref"].get("axial", 0.0)
        rows.append(
            {
                "case": case,
                "effect": effect,
                "stages_off_equal_ref": stages["off"] == stages["ref"],
                "ref": med["ref"],
                "off_ratio": statistics.median(ratios),
                "off_iqr": q3 - q1,
                "on": med["on"],
                "increment": statistics.median(increments),
                "profile": booked,
                "stages_on": stages["on"],
            }
        )
        r = rows[-1]
        print(
            f"{case:9s} {effect:16s} ref {1e6 * r['ref']:9.2f} us  "
            f"off/ref {r['off_ratio']:6.3f} (IQR {r['off_iqr']:.3f})  "
            f"on {1e6 * r['on']:9.2f} us  "
            f"+{1e6 * r['increment']:8.2f} us  profile {1e6 * r['profile']:8.2f} us",
            flush=True,
        )
    return rows


def markdown(rows: list[dict]) -> str:
    out = [
        "| case | effect | ref µs/step | off/ref (IQR) | on µs/step | increment µs "
        "| stage profile µs | increment/profile |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        ratio = r["increment"] / r["profile"] if r["profile"] > 0 else float("nan")
        out.append(
            f"| {r['case']} | {r['effect']} | {1e6 * r['ref']:.2f} "
            f"| {r['off_ratio']:.3f} ({r['off_iqr']:.3f}) | {1e6 * r['on']:.2f} | "
            f"{1e6 * r['increment']:+.2f} | {1e6 * r['profile']:.2f} | {ratio:.2f} |"
        )
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=15, help="interleaved repeats per scene (median)")
    ap.add_argument("--budget", type=float, default=0.03, help="seconds per timed measurement")
    ap.add_argument("--quick", action="store_true", help="3 repeats of 10 ms (smoke run)")
    ap.add_argument("--markdown", action="store_true", help="print a markdown table at the end")
    ap.add_argument("--case", choices=["h", "conveyor", "both"], default="both")
    args = ap.parse_args()
    if args.quick:
        args.repeats, args.budget = 3, 0.01
    print(
        f"beltrs {beltrs.__version__}, Python {platform.python_version()}, {platform.machine()}, "
        f"{os.cpu_count()} CPUs ({platform.processor() or platform.platform()}); "
        f"{args.repeats} repeats of {args.budget} s"
    )
    rows = []
    if args.case in ("h", "both"):
        sim = beltrs.Simulation(case_h(frozenset(EFFECTS)))
        print(f"case H: {sim.nodes} nodes, {len(sim.scene.idlers)} idlers, dt = {sim.dt:.3e} s")
        rows += effect_table("case H", case_h, args.repeats, args.budget)
    if args.case in ("conveyor", "both"):
        sim = beltrs.Simulation(conveyor(frozenset(EFFECTS)))
        print(f"conveyor: {sim.nodes} nodes, {len(sim.scene.idlers)} idlers, dt = {sim.dt:.3e} s")
        rows += effect_table("conveyor", conveyor, args.repeats, args.budget)
    bad = [r["effect"] for r in rows if not r["stages_off_equal_ref"]]
    print("disabled effects compile the same stages as absent ones:", "yes" if not bad else f"NO: {bad}")
    if args.markdown:
        print()
        print(markdown(rows))


if __name__ == "__main__":
    main()

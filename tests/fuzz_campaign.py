"""Adversarial fuzz of the public paths, each case in its own process.

A case is drawn from a seed (so every outcome can be replayed: ``--replay SEED``):

* a scene, valid or corrupted, reaching the engine through one of four paths: the
  dataclasses (``Scene`` objects whose fields are mutated), a dict (``Scene.from_dict``),
  the TOML text of a scene file (``loads_scene``, with the text mutated), or the raw
  binding (``_beltrs.Simulation(dict)``);
* then a few method calls with random, sometimes wrong, arguments: ``stabilise``, ``run``,
  ``step``, ``set_counterweight``, ``set_drive``, ``set_friction``, ``set_scene`` with a
  mutated scene between two runs (mid-run changes), and a checkpoint round trip.

Each case runs in a child forked from a parent that has imported beltrs (cheap), with an
address-space limit and a CPU-time limit, and a stall timeout enforced by the parent: a
child that uses no CPU for ``WALL_LIMIT`` seconds of wall time (blocked, e.g. on a FIFO) is
a hang; one that keeps computing is stopped by its CPU limit. So a campaign run under
``nice`` on a busy machine, where a child may wait minutes for a core, does not count the
waiting as hangs. A case is also stopped after ``ABSOLUTE_WALL_LIMIT`` seconds whatever it
does. Outcomes:

* ``ok``: every call returned, every returned array and the state are finite;
* ``beltrs_error``: a call raised a :class:`beltrs.BeltrsError` (a clear, expected error);
* ``internal``: a BeltrsError that reports an internal error (a caught panic);
* ``other_exception``: any other exception escaped (TypeError, IndexError, ...);
* ``non_finite``: calls returned normally but something returned is NaN or infinite;
* ``crash``: the child died of a signal (segfault, abort); ``hang``: CPU limit hit, or no
  CPU used for ``WALL_LIMIT`` s;
* ``memory``: the child ran out of its address space (MemoryError).

Usage: ``nice -n 19 python tests/fuzz_campaign.py --cases 10000 [--start 0] [--json out.json]``
(one case at a time; ``--json`` is rewritten every 100 cases, so an interrupted campaign
leaves the counts of the cases done). The pytest suite runs a fixed, small range of seeds
(tests/test_fuzz_scenes.py).
"""

from __future__ import annotations

import argparse
import copy
import dataclasses
import json
import math
import os
import random
import resource
import select
import signal
import sys
import tempfile
import time
import traceback
import warnings
from collections import Counter
from typing import Any, Callable, Optional

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import beltrs  # noqa: E402
from beltrs import _beltrs  # noqa: E402
from beltrs.scene_file import dumps_scene, loads_scene  # noqa: E402

PATHS = ("dataclass", "dict", "toml", "core")
WEIRD = [math.nan, math.inf, -math.inf, 0.0, -0.0, -1.0, 5e-324, 1e-300, 1e300, 1.7e308, -1e300, 1e160]
WRONG = ["text", None, True, [], [1.0, "a"], {"x": 1}, 10**40, -(10**40), 3 + 4j, b"bytes", object()]
#: Limits of one case: address space (bytes), CPU seconds, wall seconds without any CPU
#: progress (a blocked child), and wall seconds in all.
MEMORY_LIMIT = 3 * 2**30
CPU_LIMIT = 60
WALL_LIMIT = 120.0
ABSOLUTE_WALL_LIMIT = 3600.0
#: Bound on the work of one run call, steps (fewer on big belts), and its wall time, s.
MAX_STEPS = 3000
MAX_NODE_STEPS = 600_000


# --- scenes -------------------------------------------------------------------------------


def _friction(r: random.Random) -> Optional[dict]:
    kind = r.randrange(4)
    if kind == 0:
        return None
    if kind == 1:
        return {"model": "none"}
    mu = r.uniform(0, 1)
    d: dict[str, Any] = {"model": "stick_force", "static": mu}
    if r.random() < 0.5:
        d["kinetic"] = mu * r.uniform(0, 1)
    return d


def _table(r: random.Random, xkey: str, ykey: str, lo: float, hi: float) -> dict:
    n = r.randint(1, 4)
    xs = sorted(r.sample(range(0, 2000), n))
    return {xkey: [x / 1000 for x in xs], ykey: [r.uniform(lo, hi) for _ in range(n)]}


def random_scene(r: random.Random) -> dict:
    """A plausible scene in dict form: 2-4 pulleys (usually a convex ring), sometimes
    takeups, drives, brakes, idlers, friction."""
    n = r.randint(2, 4)
    if r.random() < 0.7:
        ring = r.uniform(3.0, 30.0)
        phase = r.uniform(0, 2 * math.pi)
        centres = [
            [ring * math.cos(phase + 2 * math.pi * k / n), ring * math.sin(phase + 2 * math.pi * k / n)]
            for k in range(n)
        ]
        max_r = ring * math.sin(math.pi / n) * 0.9
        radii = [r.uniform(0.2, max(0.21, max_r)) for _ in range(n)]
    else:
        centres = [[r.uniform(-30, 30), r.uniform(-30, 30)] for _ in range(n)]
        radii = [r.uniform(0.2, 3.0) for _ in range(n)]
    pulleys = []
    for k, (c, rad) in enumerate(zip(centres, radii)):
        p: dict[str, Any] = {
            "name": f"p{k}",
            "center": c,
            "radius": rad,
            "mass": r.uniform(1.0, 1e4),
            "wrap": r.choice(["ccw", "ccw", "ccw", "cw"]),
            "contact_stiffness": r.uniform(1e5, 1e9),
        }
        if r.random() < 0.5:
            p["inertia"] = r.uniform(0.1, 1e4)
        if r.random() < 0.5:
            p["contact_damping"] = r.uniform(0.0, 1e4)
        p["friction"] = _friction(r)
        if r.random() < 0.25:
            t: dict[str, Any] = {"counterweight": r.uniform(0, 1e4)}
            if r.random() < 0.5:
                t["direction"] = r.choice([[0.0, -1.0], [1.0, 0.0], [0.6, -0.8]])
            if r.random() < 0.5:
                t["travel_min"], t["travel_max"] = r.uniform(-5, 0), r.uniform(0, 5)
            p["takeup"] = t
        if r.random() < 0.25:
            d = _table(r, "time", "torque", -1e4, 1e4)
            d["viscous"] = r.uniform(0, 100)
            if r.random() < 0.5:
                d.update(_table(r, "speed", "speed_factor", 0, 2))
            p["drive"] = d
        if r.random() < 0.2:
            p["brake"] = _table(r, "time", "capacity", 0, 1e4)
        pulleys.append(p)
    belt: dict[str, Any] = {
        "axial_stiffness": r.uniform(1e4, 1e8),
        "mass_per_length": r.uniform(1.0, 200.0),
        "bending_stiffness": r.uniform(0.0, 1e3),
        "damping_ratio": r.uniform(0.0, 0.5),
        "max_element_angle": r.uniform(0.1, 1.0),
        "tension_only": r.random() < 0.5,
    }
    if r.random() < 0.5:
        belt["elements"] = r.randint(3, 400) if r.random() < 0.2 else r.randint(60, 400)
    if r.random() < 0.05:
        belt["length"] = r.uniform(1.0, 500.0)
    scene: dict[str, Any] = {
        "belt": belt,
        "pulleys": pulleys,
        "gravity": r.uniform(0.0, 20.0),
        "solver": {"time_step_fraction": r.uniform(0.05, 1.0)},
    }
    if r.random() < 0.1:
        scene["solver"]["time_step"] = 10 ** r.uniform(-7, -3)
    for _ in range(r.randint(0, 3)):
        idler = {
            "center": [r.uniform(-30, 30), r.uniform(-30, 30)],
            "radius": r.uniform(0.03, 0.2),
            "friction": _friction(r),
            "contact_stiffness": r.uniform(1e5, 1e9),
        }
        clear = all(
            math.dist(idler["center"], p["center"]) > p["radius"] + idler["radius"] + 0.1 for p in pulleys
        )
        if clear or r.random() < 0.1:  # overlapping rolls are refused; keep a few
            scene.setdefault("idlers", []).append(idler)
    return scene


def _slots(node: Any, out: list) -> list:
    if isinstance(node, dict):
        for k, v in node.items():
            out.append((node, k))
            _slots(v, out)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out.append((node, i))
            _slots(v, out)
    return out


def corrupt_dict(r: random.Random, scene: dict, times: int) -> dict:
    """One to three corruptions anywhere in the tree: a rule-breaking number, a removed
    key, an unknown key, or a value of the wrong type."""
    for _ in range(times):
        slots = _slots(scene, [])
        numbers = [(c, k) for c, k in slots if type(c[k]) in (int, float)]
        action = r.choice(["weird", "weird", "weird", "drop", "extra", "wrong"])
        if action == "weird" and numbers:
            c, k = r.choice(numbers)
            c[k] = r.choice(WEIRD)
            continue
        c, k = r.choice(slots)
        if k == "elements" and action == "wrong":
            c[k] = r.choice([-5, 0, 1, 2, 10**7, 10**12, 2**62, 2**64])
        elif action == "drop" and isinstance(c, dict):
            c.pop(k, None)
        elif action == "extra" and isinstance(c, dict):
            c[r.choice(["radius_", "speed_of_light", "Mass", "mu"])] = 1.0
        else:
            c[k] = r.choice(WRONG)
    return scene


def _dataclass_slots(obj: Any, out: list) -> list:
    if dataclasses.is_dataclass(obj):
        for f in dataclasses.fields(obj):
            out.append((obj, f.name))
            _dataclass_slots(getattr(obj, f.name), out)
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            out.append((obj, i))
            _dataclass_slots(v, out)
    return out


def corrupt_dataclass(r: random.Random, scene: beltrs.Scene, times: int) -> beltrs.Scene:
    """Mutate fields of the Scene objects in place: rule-breaking numbers, wrong types,
    None, a pulley dropped or duplicated."""
    for _ in range(times):
        slots = _dataclass_slots(scene, [])

        def get(c, k):
            return c[k] if isinstance(c, list) else getattr(c, k)

        def put(c, k, v):
            if isinstance(c, list):
                c[k] = v
            else:
                setattr(c, k, v)

        numbers = [(c, k) for c, k in slots if type(get(c, k)) in (int, float)]
        action = r.choice(["weird", "weird", "weird", "wrong", "none", "list"])
        if action == "weird" and numbers:
            c, k = r.choice(numbers)
            put(c, k, r.choice(WEIRD))
        elif action == "list" and scene.pulleys:
            if r.random() < 0.5:
                scene.pulleys.pop(r.randrange(len(scene.pulleys)))
            else:
                scene.pulleys.append(copy.deepcopy(r.choice(scene.pulleys)))
        else:
            c, k = r.choice(slots)
            put(c, k, None if action == "none" else r.choice(WRONG))
    return scene


def corrupt_toml(r: random.Random, text: str, times: int) -> str:
    """Edit the TOML text: a number replaced, a line dropped or duplicated, an unknown key,
    garbage, a deeply nested value, or a truncation."""
    for _ in range(times):
        lines = text.split("\n")
        action = r.choice(["number", "number", "drop", "dup", "extra", "garbage", "nest", "cut"])
        i = r.randrange(len(lines))
        if action == "number":
            nums = [k for k, ln in enumerate(lines) if "=" in ln and any(ch.isdigit() for ch in ln.split("=", 1)[1])]
            if nums:
                k = r.choice(nums)
                key = lines[k].split("=", 1)[0]
                lines[k] = key + "= " + r.choice(["nan", "inf", "-inf", "0", "-1", "5e-324", "1e308", "1e999", '"7"',
                                                  "true", "[]", "{}", "1979-05-27", "0x10", "1_000"])
        elif action == "drop":
            lines.pop(i)
        elif action == "dup":
            lines.insert(i, lines[i])
        elif action == "extra":
            lines.insert(i, r.choice(["speed_of_light = 3e8", "radius_ = 1.0", "[bogus]", "Mass = 2"]))
        elif action == "garbage":
            lines.insert(i, r.choice(["= = =", "[[", "\x00\x01", "é = 1", "key = 'unterminated"]))
        elif action == "nest":
            depth = r.choice([10, 100, 1000, 5000])
            lines.insert(i, "deep = " + "[" * depth + "]" * depth)
        else:
            return "\n".join(lines)[: r.randrange(max(1, len(text)))]
        text = "\n".join(lines)
    return text


# --- method arguments ----------------------------------------------------------------------


#: Chance that one method argument is drawn bad (rule-breaking or of the wrong type).
BAD_ARGUMENT = 0.08


def _arg(r: random.Random, good: Callable[[], Any]) -> Any:
    """Mostly a good value, sometimes a rule-breaking or wrongly typed one."""
    x = r.random()
    if x >= BAD_ARGUMENT:
        return good()
    if x < 0.5 * BAD_ARGUMENT:
        return r.choice(WEIRD)
    return r.choice(WRONG)


def actions(r: random.Random, scene: Optional[beltrs.Scene]) -> list[tuple[str, dict]]:
    """A few method calls (name, keyword arguments) for one case."""
    out: list[tuple[str, dict]] = []
    names = [p.name for p in scene.pulleys] if scene is not None else ["p0"]
    n_p = len(names)
    takeups = [k for k, p in enumerate(scene.pulleys) if p.takeup is not None] if scene is not None else []
    pulley = lambda: _arg(r, lambda: r.choice([r.randrange(max(1, n_p)), r.choice(names) if names else 0]))  # noqa: E731
    with_takeup = lambda: _arg(r, lambda: r.choice(takeups)) if takeups and r.random() < 0.9 else pulley()  # noqa: E731
    for _ in range(r.randint(1, 5)):
        what = r.choice(["stabilise", "run", "run", "step", "counterweight", "drive", "friction", "set_scene",
                         "checkpoint", "inspect"])
        if what == "stabilise":
            out.append((what, {"method": _arg(r, lambda: r.choice(["fire", "kinetic"])),
                               "tolerance": _arg(r, lambda: 10 ** r.uniform(-9, -3)),
                               "max_steps": _arg(r, lambda: r.randint(0, 400))}))
        elif what == "run":
            kw: dict[str, Any] = {"duration": _arg(r, lambda: r.uniform(0, 50) * 1e-4)}
            if r.random() < 0.5:
                kw["record_every"] = _arg(r, lambda: r.randint(1, 50))
            elif r.random() < 0.5:
                kw["record_interval"] = _arg(r, lambda: r.uniform(1e-5, 1e-3))
            if r.random() < 0.3:
                kw["max_samples"] = _arg(r, lambda: r.randint(2, 20))
            if r.random() < 0.2:
                kw["max_memory"] = _arg(r, lambda: r.uniform(1e3, 1e7))
            for ch in ("tension", "node_position", "node_velocity"):
                if r.random() < 0.15:
                    kw[ch] = _arg(r, lambda: r.random() < 0.5)
            if r.random() < 0.1:
                kw["max_wall_time"] = _arg(r, lambda: r.uniform(1e-3, 10))
            out.append((what, kw))
        elif what == "step":
            out.append((what, {"steps": _arg(r, lambda: r.randint(0, 200))}))
        elif what == "counterweight":
            out.append((what, {"pulley": with_takeup(), "mass": _arg(r, lambda: r.uniform(0, 1e4))}))
        elif what == "drive":
            out.append((what, {"pulley": pulley(), "drive": _arg(r, lambda: r.choice([
                None, beltrs.Drive(time=[0.0, 0.01], torque=[0.0, r.uniform(-1e4, 1e4)])]))}))
        elif what == "friction":
            out.append((what, {"pulley": pulley(), "friction": _arg(r, lambda: r.choice([
                None, beltrs.Friction(static=r.uniform(0, 1)), beltrs.Friction(model="none")]))}))
        elif what == "set_scene":
            out.append((what, {"seed": r.randrange(2**31), "corrupt": r.random() < 0.5}))
        elif what == "checkpoint":
            out.append((what, {"path": _arg(r, lambda: "ck"), "resume": r.random() < 0.7}))
        else:
            out.append((what, {}))
    return out


# --- one case -------------------------------------------------------------------------------


class NonFinite(Exception):
    """Something returned normally holds NaN or inf."""


def _check_finite(what: str, value: Any) -> None:
    if isinstance(value, dict):
        for k, v in value.items():
            if k == "motor_speed":  # NaN by design where a pulley has no motor: no infinities
                v = np.nan_to_num(np.asarray(v, dtype=float), nan=0.0, posinf=np.inf, neginf=-np.inf)
            _check_finite(f"{what}[{k}]", v)
        return
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        for f in dataclasses.fields(value):
            v = getattr(value, f.name)
            if isinstance(v, np.ndarray):
                # motor_speed is NaN by design where a pulley has no motor: no infinities.
                _check_finite(f"{what}.{f.name}", np.nan_to_num(v, nan=0.0, posinf=np.inf, neginf=-np.inf)
                              if f.name == "motor_speed" else v)
        return
    if isinstance(value, list) and not all(isinstance(v, (int, float)) for v in value):
        return
    if isinstance(value, (np.ndarray, float, int, list)) and not isinstance(value, bool):
        a = np.asarray(value, dtype=float)
        if not np.all(np.isfinite(a)):
            raise NonFinite(f"{what} is not finite")


def _mid_run_scene(r: random.Random, scene: beltrs.Scene, corrupt: bool) -> beltrs.Scene:
    """The running scene with parameters changed (counterweights, drives, friction,
    stiffness, gravity), sometimes to rule-breaking values."""
    s = copy.deepcopy(scene)
    s.gravity = r.uniform(0, 20)
    for p in s.pulleys:
        if p.takeup is not None and r.random() < 0.5:
            p.takeup.counterweight = r.uniform(0, 2e4)
        if r.random() < 0.3:
            p.friction = r.choice([None, beltrs.Friction(static=r.uniform(0, 1))])
    s.belt.damping_ratio = r.uniform(0, 0.5)
    if corrupt:
        s = corrupt_dataclass(r, s, r.randint(1, 2))
    return s


def run_case(seed: int, workdir: str) -> dict:
    """Build and exercise case ``seed``; return its record (raises on a non-finite result
    or any exception, which the caller classifies)."""
    r = random.Random(seed)
    path = PATHS[seed % len(PATHS)]
    scene_dict = random_scene(r)
    corrupt = r.random() < 0.5
    times = r.randint(1, 3)
    record = {"seed": seed, "path": path, "corrupted": corrupt}
    if path == "core":
        d = corrupt_dict(r, scene_dict, times) if corrupt else scene_dict
        core = _beltrs.Simulation(d)
        steps = max(1, min(MAX_STEPS, MAX_NODE_STEPS // core.nodes))
        core.stabilise("fire", False, 1e-7, 200)
        core.begin_recording(10, True, True, True, 100)
        core.advance(steps)
        core.end_recording()
        _check_finite("state", dict(core.state()))
        _check_finite("recording", dict(core.take_recording()))
        return record
    if path == "dict":
        d = corrupt_dict(r, scene_dict, times) if corrupt else scene_dict
        scene = beltrs.Scene.from_dict(d)
    elif path == "toml":
        text = dumps_scene(beltrs.Scene.from_dict(scene_dict))
        scene = loads_scene(corrupt_toml(r, text, times) if corrupt else text)
    else:
        scene = beltrs.Scene.from_dict(scene_dict)
        if corrupt:
            scene = corrupt_dataclass(r, scene, times)
    sim = beltrs.Simulation(scene)
    for name, kw in actions(r, sim.scene):
        record["last"] = name
        if name == "stabilise":
            try:
                _check_finite("stabilise", {k: v for k, v in sim.stabilise(**kw).items() if k != "residual"})
            except beltrs.BeltrsError as err:
                if "did not converge" not in str(err):
                    raise
        elif name == "run":
            duration = kw.pop("duration")
            if isinstance(duration, float) and math.isfinite(duration) and duration > 0:
                duration = min(duration, max(1, MAX_NODE_STEPS // sim.nodes) * sim.dt)
                duration = min(duration, MAX_STEPS * sim.dt)
            kw.setdefault("max_wall_time", 30.0)
            try:
                res = sim.run(duration, progress=False, **kw)
            except beltrs.DivergenceError as err:
                _check_finite("DivergenceError.result", err.result)
                raise
            _check_finite("run", res)
        elif name == "step":
            n = kw["steps"]
            if isinstance(n, int) and not isinstance(n, bool) and n > 0:
                kw["steps"] = min(n, max(1, MAX_NODE_STEPS // sim.nodes))
            sim.step(**kw)
        elif name == "counterweight":
            sim.set_counterweight(kw["pulley"], kw["mass"])
        elif name == "drive":
            sim.set_drive(kw["pulley"], kw["drive"])
        elif name == "friction":
            sim.set_friction(kw["pulley"], kw["friction"])
        elif name == "set_scene":
            sim.set_scene(_mid_run_scene(random.Random(kw["seed"]), sim.scene, kw["corrupt"]))
        elif name == "checkpoint":
            p = kw["path"]
            target = os.path.join(workdir, p) if isinstance(p, str) else p
            sim.save_checkpoint(target)
            if kw["resume"]:
                sim = beltrs.Simulation.load_checkpoint(target)
        else:
            _check_finite("state", sim.state())
        _check_finite("state", sim.state())
    return record


def classify(err: BaseException) -> str:
    if isinstance(err, NonFinite):
        return "non_finite"
    if isinstance(err, MemoryError):
        return "memory"
    if isinstance(err, beltrs.BeltrsError):
        return "internal" if "internal error" in str(err) else "beltrs_error"
    return "other_exception"


def _child(seed: int, wfd: int) -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
    resource.setrlimit(resource.RLIMIT_CPU, (CPU_LIMIT, CPU_LIMIT + 5))
    signal.signal(signal.SIGINT, signal.default_int_handler)
    # beltrs's own warnings (a run from the placement, an undamped contact, a checkpoint
    # that could not be written mid-run, ...) are a documented answer to a strange scene,
    # not an escape; any other warning (under pytest an error) still counts.
    warnings.simplefilter("ignore", beltrs.BeltrsWarning)
    warnings.simplefilter("ignore", beltrs.CheckpointWarning)
    with tempfile.TemporaryDirectory() as workdir:
        try:
            rec = run_case(seed, workdir)
            rec["outcome"] = "ok"
        except BaseException as err:  # noqa: BLE001 - classified, never re-raised
            rec = {"seed": seed, "path": PATHS[seed % len(PATHS)], "outcome": classify(err),
                   "error": f"{type(err).__name__}: {str(err)[:300]}"}
            if rec["outcome"] in ("other_exception", "internal"):
                rec["where"] = traceback.format_exc(limit=-3)[-600:]
    os.write(wfd, json.dumps(rec).encode())
    os.close(wfd)


def _cpu_seconds(pid: int) -> float:
    """User + system CPU time of a live child, s (from /proc; 0 where /proc is missing)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def run_in_child(seed: int) -> dict:
    """Fork, run case ``seed`` in the child under the limits, and classify how it ended."""
    rfd, wfd = os.pipe()
    pid = os.fork()
    if pid == 0:  # child
        os.close(rfd)
        code = 0
        try:
            _child(seed, wfd)
        except BaseException:  # noqa: BLE001
            code = 3
        os._exit(code)
    os.close(wfd)
    chunks = []
    start = time.monotonic()
    cpu, progressed = _cpu_seconds(pid), start
    timed_out = ""
    while True:
        now = time.monotonic()
        used = _cpu_seconds(pid)
        if used > cpu:
            cpu, progressed = used, now
        if now - progressed > WALL_LIMIT:
            timed_out = f"no CPU used for {WALL_LIMIT:g} s (blocked) after {cpu:.1f} CPU-s"
        elif now - start > ABSOLUTE_WALL_LIMIT:
            timed_out = f"no result within {ABSOLUTE_WALL_LIMIT:g} s of wall time"
        if timed_out:
            os.kill(pid, signal.SIGKILL)
            break
        ready, _, _ = select.select([rfd], [], [], 1.0)
        if ready:
            data = os.read(rfd, 1 << 16)
            if not data:
                break
            chunks.append(data)
    os.close(rfd)
    _, status = os.waitpid(pid, 0)
    base = {"seed": seed, "path": PATHS[seed % len(PATHS)]}
    if timed_out:
        return {**base, "outcome": "hang", "error": timed_out}
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        outcome = "hang" if sig in (signal.SIGXCPU, signal.SIGKILL) else "crash"
        return {**base, "outcome": outcome, "error": f"killed by signal {signal.Signals(sig).name}"}
    try:
        return json.loads(b"".join(chunks).decode())
    except ValueError:
        return {**base, "outcome": "crash", "error": f"no result (exit status {status})"}


def main(argv: Optional[list[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", type=int, default=1000)
    ap.add_argument("--start", type=int, default=0, help="first seed")
    ap.add_argument("--json", help="write every case's record here")
    ap.add_argument("--replay", type=int, help="run one seed in this process and show the traceback")
    args = ap.parse_args(argv)
    if args.replay is not None:
        with tempfile.TemporaryDirectory() as workdir:
            print(run_case(args.replay, workdir))
        return 0
    counts: Counter = Counter()
    by_path: Counter = Counter()
    records = []
    t0 = time.time()

    def summary() -> dict:
        return {
            "cases": len(records),
            "asked": args.cases,
            "start": args.start,
            "seconds": round(time.time() - t0, 1),
            "outcomes": dict(counts),
            "by_path": {f"{p}/{o}": n for (p, o), n in sorted(by_path.items())},
            "beltrs": beltrs.__version__,
        }

    def write_json() -> None:
        if args.json:
            tmp = f"{args.json}.{os.getpid()}.tmp"
            with open(tmp, "w") as f:
                json.dump({"summary": summary(), "cases": records}, f)
            os.replace(tmp, args.json)

    for seed in range(args.start, args.start + args.cases):
        rec = run_in_child(seed)
        records.append(rec)
        counts[rec["outcome"]] += 1
        by_path[(rec["path"], rec["outcome"])] += 1
        if rec["outcome"] not in ("ok", "beltrs_error"):
            print(json.dumps(rec), flush=True)
        done = seed - args.start + 1
        if done % 100 == 0:
            write_json()
        if done % 500 == 0:
            print(f"{done} cases, {time.time() - t0:.0f} s: {dict(counts)}", flush=True)
    print(json.dumps(summary(), indent=1))
    write_json()
    bad = sum(counts[k] for k in ("crash", "hang", "internal", "other_exception", "non_finite", "memory"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

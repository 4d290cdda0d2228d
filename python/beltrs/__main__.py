"""Command line (also installed as ``beltrs``).

- ``python -m beltrs demo`` runs case H on the built-in default scene.
- ``beltrs run SCENE.toml --out result.npz`` runs a scene file as its ``[recording]`` table
  says and writes every recorded array, the scene and metadata to an NPZ file.
- ``beltrs check SCENE.toml`` reads and compiles a scene file and prints what it compiled to.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import sys
import time
from pathlib import Path
from typing import Any, Optional, Sequence

import numpy as np


def demo(elements: int, out: str) -> int:
    """Stabilise case H, print static tensions, takeup position and wall times, run the
    thesis §6.4.2 torque pulse for 3.6 s, and write a PNG of tension around the belt."""
    import beltrs
    from beltrs.analysis import hustrulid_tangent_tensions
    from beltrs.analytic import two_pulley_takeup_statics
    from beltrs.plot import plot_tension_around_belt

    exact = two_pulley_takeup_statics()
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop(elements))
    print(f"beltrs {beltrs.__version__}: case H, Hustrulid's two-pulley loop, {sim.nodes} elements")
    print(f"  stages: {', '.join(sim.stages)}")
    print(f"  time step {sim.dt:.3e} s = {sim.dt / sim.dt_limit:.2f} x limit ({sim.dt_cause})")
    t0 = time.perf_counter()
    report = sim.stabilise()
    t_static = time.perf_counter() - t0
    x = sim.state()["node_position"]
    tension = sim.tensions()
    travel = float(sim.takeup_travel[1])
    yl = -travel
    ta, tb, tc, td = hustrulid_tangent_tensions(x, tension, yl)
    print(f"static equilibrium ({report['steps']} relaxation steps, {t_static * 1e3:.1f} ms wall):")
    print(f"  tension at lower tangent points A, B: {ta / 1e3:8.2f} {tb / 1e3:8.2f} kN"
          f"   (exact {exact.lower_tension / 1e3:.2f} kN)")
    print(f"  tension at upper tangent points C, D: {tc / 1e3:8.2f} {td / 1e3:8.2f} kN"
          f"   (exact {exact.upper_tension / 1e3:.2f} kN)")
    print(f"  takeup position: y = {yl:.4f} m, displacement {-travel:.4f} m"
          f"   (exact continuum {exact.takeup_displacement:.4f} m; the chord polygon error shrinks as 1/n²)")
    static_x, static_t = x.copy(), tension.copy()

    friction = beltrs.Friction(static=0.5, kinetic=0.4)
    sim.set_friction(0, friction)
    sim.set_friction(1, friction)
    sim.set_drive(0, beltrs.Drive.pulse(4e5, 0.07, start=sim.time))
    res = sim.run(3.6, record_interval=0.01, node_velocity=False)
    steps = int(round(3.6 / sim.dt))
    print(f"thesis §6.4.2: 400 kN·m for 0.07 s, then 3.6 s simulated: {steps} steps in {res.wall_time:.3f} s wall"
          f" ({sim.nodes * steps / res.wall_time:.3e} node-steps/s; the thesis took ~15 min)")
    assert res.tension is not None
    print(f"  peak tension {res.tension.max() / 1e3:.1f} kN, lowest {res.tension.min() / 1e3:.1f} kN")
    path = plot_tension_around_belt(
        static_x, static_t, out, title="Case H: static tension (kN)",
        takeup_time=res.time, takeup_travel=-res.takeup_travel[:, 1],
    )
    print(f"wrote {path}")
    return 0 if np.isfinite(res.tension).all() else 1


#: Exit codes of ``beltrs run`` and ``beltrs check``.
EXIT_OK, EXIT_RUN_FAILED, EXIT_BAD_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130


def result_arrays(res: Any) -> dict[str, np.ndarray]:
    """Every array of a :class:`beltrs.Result` (channels not recorded are absent), plus
    ``energy_columns`` and ``pulley_names`` as string arrays."""
    out: dict[str, np.ndarray] = {}
    for f in dataclasses.fields(res):
        value = getattr(res, f.name)
        if isinstance(value, np.ndarray):
            out[f.name] = value
    out["energy_columns"] = np.array(list(res.energy_columns), dtype=str)
    out["pulley_names"] = np.array(list(res.pulley_names), dtype=str)
    return out


def write_npz(path: Path, arrays: dict[str, Any]) -> None:
    """Write ``arrays`` to ``path`` (uncompressed NPZ, readable with
    ``np.load(path)`` and no pickle), atomically: a temporary file, then a rename."""
    from beltrs.scene_file import atomic_write

    atomic_write(path, lambda fh: np.savez(fh, **{k: np.asarray(v) for k, v in arrays.items()}), binary=True)


def run_scene(
    scene_path: str,
    out: str,
    *,
    stabilise: Optional[bool] = None,
    duration: Optional[float] = None,
    quiet: bool = False,
) -> int:
    """``beltrs run``: load, compile, stabilise (if asked), run, write the NPZ.

    Args:
        scene_path: TOML scene file.
        out: NPZ file to write (also written, with what was recorded, if the run diverges
            or is interrupted).
        stabilise: override ``recording.stabilise``. Default: the scene's setting.
        duration: override ``recording.duration``, s. Default: the scene's setting.
        quiet: print nothing but errors.

    Returns:
        0 on success, 1 if the relaxation or the run failed, 2 for a bad scene or bad
        arguments, 130 if interrupted by Ctrl-C. Errors go to stderr as one line.
    """
    import beltrs

    say = (lambda *a: None) if quiet else print
    scene = beltrs.load_scene(scene_path)
    rec = scene.recording
    if duration is not None:
        rec = dataclasses.replace(rec, duration=duration)
        scene = dataclasses.replace(scene, recording=rec)
    do_stabilise = rec.stabilise if stabilise is None else stabilise
    out_path = Path(out)
    if not out_path.parent.is_dir():
        raise beltrs.SceneError(f"--out {out}: the directory {out_path.parent} does not exist")

    sim = beltrs.Simulation(scene)
    say(f"beltrs {beltrs.__version__}: {scene_path}: {sim.nodes} nodes, {len(scene.pulleys)} pulleys, "
        f"{len(scene.idlers)} idlers")
    say(f"  stages: {', '.join(sim.stages)}")
    say(f"  time step {sim.dt:.4e} s = {sim.dt / sim.dt_limit:.3f} x limit {sim.dt_limit:.4e} s ({sim.dt_cause})")

    meta: dict[str, Any] = {
        "beltrs_version": beltrs.__version__,
        "scene": scene.to_toml(),
        "scene_path": str(scene_path),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "dt": sim.dt,
        "dt_limit": sim.dt_limit,
        "dt_cause": sim.dt_cause,
        "stages": np.array(sim.stages, dtype=str),
        "nodes": sim.nodes,
        "duration": rec.duration,
        "stabilised": do_stabilise,
        "stabilise_steps": 0,
        "stabilise_residual": np.nan,
        "stabilise_wall_time": 0.0,
    }
    if do_stabilise:
        t0 = time.perf_counter()
        report = sim.stabilise(friction=rec.stabilise_friction)
        meta["stabilise_wall_time"] = time.perf_counter() - t0
        meta["stabilise_steps"] = int(report["steps"])
        meta["stabilise_residual"] = float(report["residual"])
        say(f"  static equilibrium: {report['steps']} relaxation steps, residual {report['residual']:.2e}, "
            f"{meta['stabilise_wall_time']:.3f} s wall")

    step0 = int(sim.state()["step"])
    code, error = EXIT_OK, ""
    try:
        res = sim.run(rec.duration, **rec.run_kwargs())
    except beltrs.DivergenceError as err:
        res, code, error = err.result, EXIT_RUN_FAILED, str(err)  # type: ignore[attr-defined]
    meta["steps"] = int(sim.state()["step"]) - step0
    meta["wall_time"] = res.wall_time
    meta["interrupted"] = bool(res.interrupted)
    meta["error"] = error
    if res.interrupted:
        code = EXIT_INTERRUPTED
    write_npz(out_path, {**result_arrays(res), **meta})
    rate = sim.nodes * meta["steps"] / res.wall_time if res.wall_time > 0 else float("nan")
    say(f"  ran {meta['steps']} steps ({rec.duration} s simulated) in {res.wall_time:.3f} s wall "
        f"({rate:.3e} node-steps/s), {len(res)} samples")
    if error:
        print(f"beltrs: error: {error} (what was recorded before is in {out_path})", file=sys.stderr)
    elif res.interrupted:
        print(f"beltrs: interrupted; what was recorded so far is in {out_path}", file=sys.stderr)
    say(f"wrote {out_path}")
    return code


def check_scene(scene_path: str) -> int:
    """``beltrs check``: read and compile a scene file, print what it compiled to."""
    import beltrs

    scene = beltrs.load_scene(scene_path)
    sim = beltrs.Simulation(scene)
    print(f"{scene_path}: valid; {sim.nodes} nodes, {len(scene.pulleys)} pulleys, {len(scene.idlers)} idlers, "
          f"belt path {sim.path_length:.4f} m")
    print(f"  stages: {', '.join(sim.stages)}")
    print(f"  time step {sim.dt:.4e} s = {sim.dt / sim.dt_limit:.3f} x limit {sim.dt_limit:.4e} s ({sim.dt_cause})")
    return EXIT_OK


def _guarded(command: Any) -> int:
    """Run a command; a beltrs error, an unreadable file or Ctrl-C becomes one line on
    stderr and an exit code, never a traceback."""
    import beltrs

    try:
        return int(command())
    except beltrs.SceneError as err:
        print(f"beltrs: error: {err}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except beltrs.BeltrsError as err:
        print(f"beltrs: error: {err}", file=sys.stderr)
        return EXIT_RUN_FAILED
    except (OSError, ImportError) as err:
        print(f"beltrs: error: {err}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("beltrs: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED


def _duration(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected a number of seconds") from None
    if not (np.isfinite(value) and value >= 0):
        raise argparse.ArgumentTypeError(f"{text!r}: must be a finite number ≥ 0 (s)")
    return value


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="beltrs", description="belt conveyor dynamics")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("demo", help="case H: statics, a torque pulse, and a tension plot")
    p.add_argument("--elements", type=int, default=89, help="belt elements (default 89)")
    p.add_argument("--out", default="beltrs_case_h.png", help="PNG to write")
    r = sub.add_parser(
        "run",
        help="run a TOML scene file and write the results to an NPZ file",
        description="Run a scene file as its [recording] table says (docs/scene-format.md): "
        "stabilise, run the duration, and write every recorded array, the scene and metadata "
        "to an NPZ file.",
    )
    r.add_argument("scene", help="TOML scene file")
    r.add_argument("--out", required=True, help="NPZ file to write")
    r.add_argument(
        "--stabilise", action=argparse.BooleanOptionalAction, default=None,
        help="relax to static equilibrium first (default: recording.stabilise, itself true by default)",
    )
    r.add_argument("--duration", type=_duration, default=None, help="override recording.duration, s")
    r.add_argument("--quiet", action="store_true", help="print nothing but errors")
    c = sub.add_parser("check", help="read and compile a TOML scene file and print its stages")
    c.add_argument("scene", help="TOML scene file")
    args = parser.parse_args(argv)
    if args.command == "demo":
        return demo(args.elements, args.out)
    if args.command == "run":
        return _guarded(lambda: run_scene(
            args.scene, args.out, stabilise=args.stabilise, duration=args.duration, quiet=args.quiet
        ))
    if args.command == "check":
        return _guarded(lambda: check_scene(args.scene))
    return EXIT_BAD_INPUT


if __name__ == "__main__":
    sys.exit(main())

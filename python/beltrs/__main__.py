"""Command line (also installed as ``beltrs``; docs/cli.md).

- ``beltrs --version``
- ``python -m beltrs demo`` runs case H on the built-in default scene and draws it.
- ``beltrs run SCENE.toml [--out result.npz]`` runs a scene file as its ``[recording]``
  table says, prints a summary (peak tensions, takeup travel, drive torque and power, wall
  time) and writes the result (every recorded array, the scene and metadata) to NPZ or
  netCDF; the output is named after the scene by default.
- ``beltrs check SCENE.toml`` reads and compiles a scene file and prints what it compiled to.
- ``beltrs plot result.npz`` writes PNGs: tension waterfall, tension envelope, takeup
  travel, drive torque and power, slip margin (``beltrs.plot``).
- ``beltrs export result.npz --csv`` writes the time series as CSV files.

User errors (a bad scene, a missing file, a bad argument) are one line on stderr and a
nonzero exit code, never a traceback; warnings are one line each, ``beltrs: warning: ...``.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import sys
import time
import warnings
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
    scene = beltrs.scenes.hustrulid_loop(elements)
    sim = beltrs.Simulation(scene)
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
    travel_now = sim.takeup_travel
    static_centres = np.array([
        np.asarray(p.center) + (0.0 if p.takeup is None else travel_now[j]) * np.asarray(
            p.takeup.direction if p.takeup is not None else (0.0, 0.0))
        for j, p in enumerate(scene.pulleys)
    ])

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
        static_x, static_t, out, title="Case H: the belt, coloured by static tension",
        takeup_time=res.time, takeup_travel=-res.takeup_travel[:, 1],
        rest_length=sim.rest_length, pulleys=scene.pulleys, centres=static_centres,
        dynamic_time=res.time, dynamic_tension=res.tension, dynamic_title="400 kN·m pulse, 3.6 s",
    )
    print(f"wrote {path}")
    return 0 if np.isfinite(res.tension).all() else 1


#: Exit codes of the subcommands.
EXIT_OK, EXIT_RUN_FAILED, EXIT_BAD_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130


def result_arrays(res: Any) -> dict[str, np.ndarray]:
    """Every array of a :class:`beltrs.Result` (channels not recorded are absent), plus
    ``energy_columns`` and ``pulley_names`` as string arrays."""
    out: dict[str, np.ndarray] = dict(res.arrays())
    out["energy_columns"] = np.array(list(res.energy_columns), dtype=str)
    out["pulley_names"] = np.array(list(res.pulley_names), dtype=str)
    return out


def _where(res: Any, k_time: int, element: int) -> str:
    rest = res.metadata.get("rest_length")
    if rest is None:
        return f"element {element}"
    rl = np.asarray(rest)
    return f"{float(np.sum(rl[:element]) + rl[element] / 2):.1f} m along the belt (element {element})"


def summary_lines(res: Any, names: Sequence[str], nodes: int) -> list[str]:
    """The summary ``beltrs run`` prints: peak and lowest tension (where and when),
    takeup travel, drive torque and power, and wall time."""
    import beltrs

    lines = [f"summary: t = {res.time[0]:.4g} to {res.time[-1]:.4g} s, {len(res)} samples"]
    try:
        speed = res.belt_speed
        lines.append(f"  belt speed      {speed[0]:.3f} m/s at the start, {speed[-1]:.3f} m/s at the end "
                     f"(mean along the direction of travel)")
    except beltrs.BeltrsError:  # node velocities not recorded
        pass
    if res.tension is not None and res.tension.size:
        t = res.tension
        k = np.unravel_index(int(np.argmax(t)), t.shape)
        lo = np.unravel_index(int(np.argmin(t)), t.shape)
        lines.append(f"  peak tension    {t[k] / 1e3:10.2f} kN at t = {res.time[k[0]]:.3f} s, {_where(res, *k)}")
        lines.append(f"  lowest tension  {t[lo] / 1e3:10.2f} kN at t = {res.time[lo[0]]:.3f} s, {_where(res, *lo)}"
                     + ("  (compression)" if t[lo] < 0 else ""))
    for j, name in enumerate(names):
        travel = res.takeup_travel[:, j]
        if np.any(travel != travel[0]):
            moved = travel - travel[0]
            lines.append(f"  takeup {name!r}: travel since the start {moved.min() * 1e3:.1f} to "
                         f"{moved.max() * 1e3:.1f} mm, end {moved[-1] * 1e3:.1f} mm (+ towards the counterweight)")
    signed = _engineering(res)
    power = res.drive_power_kw
    for j, name in enumerate(names):
        torque = res.drive_torque[:, j] if signed is None else signed[0][:, j]
        if np.any(torque != 0):
            kt = int(np.argmax(np.abs(torque)))
            kp = int(np.argmax(np.abs(power[:, j])))
            unit = "kN·m" if signed is not None else "kN·m counter-clockwise"
            lines.append(f"  drive {name!r}: peak torque {torque[kt] / 1e3:.3f} {unit} at t = {res.time[kt]:.3f} s, "
                         f"peak power {power[kp, j]:.2f} kW at t = {res.time[kp]:.3f} s, "
                         f"end {torque[-1] / 1e3:.3f} {unit} / {power[-1, j]:.2f} kW (+ when driving)")
            util = None if signed is None or signed[1] is None else signed[1][:, j]
            if util is not None and np.any(np.isfinite(util)):
                ku = int(np.argmax(np.where(np.isnan(util), -np.inf, util)))
                lines.append(f"    capstan utilisation: peak {util[ku]:.2f} at t = {res.time[ku]:.3f} s "
                             f"(1 = slip limit T1/T2 = e^(µs·θ))")
    return lines


def _engineering(res: Any) -> Optional[tuple[np.ndarray, Optional[np.ndarray]]]:
    """Drive torque positive when driving, and the capstan utilisation (None where the
    result lacks what they need: an older file without the pulley constants, no tension)."""
    import beltrs

    try:
        torque = res.driving_torque
    except beltrs.BeltrsError:
        return None
    try:
        util = res.capstan().utilisation
    except beltrs.BeltrsError:
        util = None
    return torque, util


def default_output(scene_path: str, suffix: str = ".npz") -> Path:
    """``beltrs run``'s output when ``--out`` is not given: the scene file's name with
    ``suffix``, in the current directory."""
    return Path(Path(scene_path).stem + suffix)


def run_scene(
    scene_path: str,
    out: Optional[str] = None,
    *,
    stabilise: Optional[bool] = None,
    duration: Optional[float] = None,
    quiet: bool = False,
    progress: Optional[bool] = None,
) -> int:
    """``beltrs run``: load, compile, stabilise (if asked), run, print a summary, write
    the result.

    Args:
        scene_path: TOML scene file.
        out: result file to write: ``.npz`` (default) or ``.nc`` (netCDF). Also written,
            with what was recorded, if the run diverges or is interrupted. Default: the
            scene file's name with ``.npz``, in the current directory.
        stabilise: override ``recording.stabilise``. Default: the scene's setting.
        duration: override ``recording.duration``, s. Default: the scene's setting.
        quiet: print nothing but warnings and errors.
        progress: progress on stderr for the relaxation and the run. Default None: when
            stderr is a terminal (and not ``quiet``).

    Returns:
        0 on success, 1 if the relaxation or the run failed, 2 for a bad scene or bad
        arguments, 130 if interrupted by Ctrl-C. Errors go to stderr as one line.
    """
    import beltrs

    say = (lambda *a: None) if quiet else print
    if quiet and progress is None:
        progress = False
    scene = beltrs.load_scene(scene_path)
    rec = scene.recording
    if duration is not None:
        rec = dataclasses.replace(rec, duration=duration)
        scene = dataclasses.replace(scene, recording=rec)
    do_stabilise = rec.stabilise if stabilise is None else stabilise
    out_path = Path(out) if out is not None else default_output(scene_path)
    if not out_path.parent.is_dir():
        raise beltrs.SceneError(f"--out {out_path}: the directory {out_path.parent} does not exist")
    if out_path.suffix.lower() in (".nc", ".nc4", ".netcdf"):
        from beltrs.result import _netcdf_engine

        _netcdf_engine()  # refuse before running, not after, if netCDF cannot be written

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
        "dt_limit": sim.dt_limit,
        "dt_cause": sim.dt_cause,
        "nodes": sim.nodes,
        "duration": float(rec.duration),
        "stabilised": bool(do_stabilise),
        "stabilise_steps": 0,
        "stabilise_residual": float("nan"),
        "stabilise_wall_time": 0.0,
    }
    if do_stabilise:
        t0 = time.perf_counter()
        report = sim.stabilise(friction=rec.stabilise_friction, progress=progress)
        meta["stabilise_wall_time"] = time.perf_counter() - t0
        meta["stabilise_steps"] = int(report["steps"])
        meta["stabilise_residual"] = float(report["residual"])
        say(f"  static equilibrium: {report['steps']} relaxation steps, residual {report['residual']:.2e}, "
            f"{meta['stabilise_wall_time']:.3f} s wall")

    step0 = int(sim.state()["step"])
    code, error = EXIT_OK, ""
    try:
        # A run file keeps every array, the energies included (opt-in in the API).
        res = sim.run(rec.duration, progress=progress, energy=True, **rec.run_kwargs())
    except beltrs.DivergenceError as err:
        res, code, error = err.result, EXIT_RUN_FAILED, str(err)  # type: ignore[attr-defined]
    meta["steps"] = int(sim.state()["step"]) - step0
    meta["error"] = error
    if res.interrupted:
        code = EXIT_INTERRUPTED
    res.metadata.update(meta)
    res.save(out_path)
    rate = sim.nodes * meta["steps"] / res.wall_time if res.wall_time > 0 else float("nan")
    say(f"  ran {meta['steps']} steps ({rec.duration} s simulated) in {res.wall_time:.3f} s wall "
        f"({rate:.3e} node-steps/s), {len(res)} samples")
    if len(res):
        for line in summary_lines(res, [p.name for p in scene.pulleys], sim.nodes):
            say(line)
    say(f"  wall time: relaxation {meta['stabilise_wall_time']:.3f} s, run {res.wall_time:.3f} s")
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
    print(f"  default recording interval {sim.default_record_interval():.4g} s")
    return EXIT_OK


def _load(path: str) -> Any:
    import beltrs

    if not Path(path).is_file():
        raise FileNotFoundError(f"{path}: no such file")
    return beltrs.load_result(path)


def _out_dir(result_path: str, out_dir: Optional[str]) -> Path:
    import beltrs

    directory = Path(out_dir) if out_dir is not None else Path(result_path).parent
    if not directory.is_dir():
        raise beltrs.SceneError(f"--out-dir {directory}: the directory does not exist")
    return directory


def plot_command(result_path: str, out_dir: Optional[str] = None, cutoff: Optional[float] = None) -> int:
    """``beltrs plot``: the figures of :func:`beltrs.plot.plot_result`, beside the result
    file (or in ``out_dir``); ``cutoff`` (Hz) adds low-passed series."""
    from beltrs.plot import plot_result

    res = _load(result_path)
    paths = plot_result(res, _out_dir(result_path, out_dir), Path(result_path).stem, cutoff=cutoff)
    for path in paths:
        print(f"wrote {path}")
    if not paths:
        print("nothing to plot: no tension, takeup, drive or friction was recorded", file=sys.stderr)
    return EXIT_OK


def _write_csv(path: Path, header: list[str], columns: list[np.ndarray]) -> None:
    from beltrs.scene_file import atomic_write

    table = np.column_stack([np.asarray(c, dtype=float) if c.dtype.kind == "f" else c for c in columns])
    ints = [c.dtype.kind in "iub" for c in columns]
    fmt = ["%d" if i else "%.17g" for i in ints]

    def write(fh: Any) -> None:
        fh.write(",".join(header) + "\n")
        np.savetxt(fh, table, fmt=fmt, delimiter=",")

    atomic_write(path, write, binary=False)


def export_command(result_path: str, out_dir: Optional[str] = None) -> int:
    """``beltrs export --csv``: ``STEM_pulleys.csv`` (time and every per-pulley series,
    one column per quantity and pulley, unit in the header), ``STEM_energy.csv`` and, if
    recorded, ``STEM_tension.csv`` (time, then one column per element, headed by its
    distance along the belt in m). Floats are written with 17 significant digits (they
    read back exactly), counts as integers."""
    from beltrs.plot import belt_distance
    from beltrs.result import PULLEY_SERIES, UNITS

    res = _load(result_path)
    directory = _out_dir(result_path, out_dir)
    stem = Path(result_path).stem
    names = list(res.pulley_names)
    written = []
    header, cols = ["time (s)"], [res.time]
    for q in PULLEY_SERIES:
        values = getattr(res, q)
        if values is None:  # motor_speed in a result saved before beltrs recorded it
            continue
        for j, name in enumerate(names):
            header.append(f"{q}[{name}] ({UNITS[q]})")
            cols.append(values[:, j])
    path = directory / f"{stem}_pulleys.csv"
    _write_csv(path, header, cols)
    written.append(path)
    if res.energy is not None:  # energies are recorded only on request (energy=True)
        path = directory / f"{stem}_energy.csv"
        _write_csv(path, ["time (s)"] + [f"{c} (J)" for c in res.energy_columns],
                   [res.time] + [res.energy[:, k] for k in range(res.energy.shape[1])])
        written.append(path)
    if res.tension is not None:
        rest = res.metadata.get("rest_length")
        first = None if res.node_position is None else res.node_position[0]
        dist, _ = belt_distance(first, rest, res.tension.shape[1])
        path = directory / f"{stem}_tension.csv"
        _write_csv(path, ["time (s)"] + [f"T@{d:.6g}m (N)" for d in dist],
                   [res.time] + [res.tension[:, e] for e in range(res.tension.shape[1])])
        written.append(path)
    for path in written:
        print(f"wrote {path}")
    return EXIT_OK


def _guarded(command: Any) -> int:
    """Run a command; a beltrs error, an unreadable file or Ctrl-C becomes one line on
    stderr and an exit code, never a traceback. Warnings become one line each."""
    import beltrs

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        warnings.simplefilter("ignore", DeprecationWarning)
        try:
            code = int(command())
        except beltrs.SceneError as err:
            print(f"beltrs: error: {err}", file=sys.stderr)
            code = EXIT_BAD_INPUT
        except beltrs.BeltrsError as err:
            print(f"beltrs: error: {err}", file=sys.stderr)
            code = EXIT_RUN_FAILED
        except (OSError, ImportError) as err:
            print(f"beltrs: error: {err}", file=sys.stderr)
            code = EXIT_BAD_INPUT
        except KeyboardInterrupt:
            print("beltrs: interrupted", file=sys.stderr)
            code = EXIT_INTERRUPTED
    for w in caught:
        label = w.category.__name__ if issubclass(w.category, beltrs.BeltrsWarning) else "warning"
        print(f"beltrs: warning ({label}): {w.message}", file=sys.stderr)
    return code


def _duration(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected a number of seconds") from None
    if not (np.isfinite(value) and value >= 0):
        raise argparse.ArgumentTypeError(f"{text!r}: must be a finite number ≥ 0 (s)")
    return value


def _frequency(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected a frequency, Hz") from None
    if not (np.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"{text!r}: must be a finite frequency > 0 (Hz)")
    return value


def _elements(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected a whole number") from None
    if value < 8:
        raise argparse.ArgumentTypeError(f"{text!r}: must be ≥ 8")
    return value


def parser() -> argparse.ArgumentParser:
    """The argument parser (every subcommand has its own ``--help``)."""
    from beltrs import __version__

    top = argparse.ArgumentParser(
        prog="beltrs",
        description="Transient dynamics of belt conveyors and belt drives. SI units throughout.",
        epilog="Run 'beltrs COMMAND --help' for the options of a command; docs/cli.md has examples.",
    )
    top.add_argument("--version", action="version", version=f"beltrs {__version__}")
    sub = top.add_subparsers(dest="command", required=True, metavar="COMMAND")
    p = sub.add_parser(
        "demo", help="case H: statics, a torque pulse, and a tension plot",
        description="Case H (Hustrulid's two-pulley loop): relax it, print the static tensions and takeup "
        "position against the exact answers, run the thesis's 400 kN·m torque pulse for 3.6 s, and draw "
        "the tension along the belt (tangent points marked, the pulse's peak shown) as a PNG.",
    )
    p.add_argument("--elements", type=_elements, default=89, help="belt elements (default 89)")
    p.add_argument("--out", default="beltrs_case_h.png", help="PNG to write (default beltrs_case_h.png)")
    r = sub.add_parser(
        "run",
        help="run a TOML scene file, print a summary and save the result",
        description="Run a scene file as its [recording] table says (docs/scene-format.md): relax to static "
        "equilibrium, run the duration, print a summary (peak tensions, takeup travel, drive torque and "
        "power, wall time), and save every recorded array, the scene and metadata (NPZ, or netCDF for .nc).",
    )
    r.add_argument("scene", help="TOML scene file")
    r.add_argument("--out", default=None,
                   help="result file, .npz or .nc (default: the scene's name with .npz, in the current directory)")
    r.add_argument(
        "--stabilise", action=argparse.BooleanOptionalAction, default=None,
        help="relax to static equilibrium first (default: recording.stabilise, itself true by default)",
    )
    r.add_argument("--duration", type=_duration, default=None, help="override recording.duration, s")
    r.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress on stderr for the relaxation and the run (default: when stderr is a terminal)")
    r.add_argument("--quiet", action="store_true", help="print nothing but warnings and errors")
    c = sub.add_parser(
        "check", help="read and compile a TOML scene file and print its stages",
        description="Read a scene file, validate and compile it without running it, and print the node "
        "count, stages, time step and its limit, and the default recording interval.",
    )
    c.add_argument("scene", help="TOML scene file")
    pl = sub.add_parser(
        "plot", help="draw a result: tension waterfall and envelope, takeup travel, drives, slip margin",
        description="Write PNGs of a result saved by 'beltrs run' or Result.save: RESULT_waterfall.png "
        "(tension over distance along the belt and time), RESULT_envelope.png (max/min tension along the "
        "belt), RESULT_takeup.png (takeup travel since the start), RESULT_drives.png (drive torque and power, "
        "positive when driving), RESULT_slip.png (capstan utilisation of driven and braked pulleys). A "
        "figure whose data the result lacks is skipped.",
    )
    pl.add_argument("result", help="result file (.npz or .nc)")
    pl.add_argument("--out-dir", default=None, help="directory for the PNGs (default: beside the result)")
    pl.add_argument("--cutoff", type=_frequency, default=None, metavar="HZ",
                    help="also draw torque, power and slip margin low-passed below HZ, and the waterfall and "
                    "envelope from tensions low-passed below HZ (the band is named on the figure); default: raw only")
    ex = sub.add_parser(
        "export", help="export a result as CSV files",
        description="Write a result's time series as CSV: RESULT_pulleys.csv (every per-pulley series, unit "
        "in each header), RESULT_energy.csv and RESULT_tension.csv (one column per element).",
    )
    ex.add_argument("result", help="result file (.npz or .nc)")
    ex.add_argument("--csv", action="store_true", required=True, help="write CSV files (the one format so far)")
    ex.add_argument("--out-dir", default=None, help="directory for the CSV files (default: beside the result)")
    return top


def main(argv: Optional[Sequence[str]] = None) -> int:
    args = parser().parse_args(argv)
    if args.command == "demo":
        return _guarded(lambda: demo(args.elements, args.out))
    if args.command == "run":
        return _guarded(lambda: run_scene(
            args.scene, args.out, stabilise=args.stabilise, duration=args.duration, quiet=args.quiet,
            progress=args.progress,
        ))
    if args.command == "check":
        return _guarded(lambda: check_scene(args.scene))
    if args.command == "plot":
        return _guarded(lambda: plot_command(args.result, args.out_dir, args.cutoff))
    if args.command == "export":
        return _guarded(lambda: export_command(args.result, args.out_dir))
    return EXIT_BAD_INPUT


if __name__ == "__main__":
    sys.exit(main())

"""Sweeps: many independent runs (start-up studies: curves × loads × takeups × stops), on
local processes or on a Dask cluster, gathered into one xarray Dataset (docs/sweeps.md).

>>> from beltrs import study, scenes, StartCurve
>>> grid = {"start_curve": {s: StartCurve(shape=s, speed=2.0, ramp=10.0) for s in ("harrison", "linear")},
...         "material": [0.0, 55.6]}
>>> ds = study.sweep(grid, scene=scenes.guo_wang_conveyor)     # called as guo_wang_conveyor(**case)
>>> ds.peak_tension.sel(start_curve="linear")

``beltrs.study.sweep`` is this module's :func:`sweep`. Scheduling is Dask's or
:mod:`concurrent.futures`'s; beltrs only describes the cases and gathers the answers.
"""

from __future__ import annotations

import copy
import itertools
import math
import os
import re
import sys
import time as _time
import traceback
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Optional, Sequence, Union

import numpy as np

from . import _beltrs
from .scene import Scene

__all__ = ["SUMMARY_UNITS", "set_field", "summarise", "sweep"]

#: Outputs of :func:`summarise` and their units.
SUMMARY_UNITS = {
    "peak_tension": "N",
    "peak_tension_time": "s",
    "lowest_tension": "N",
    "takeup_travel_range": "m",
    "peak_drive_torque": "N*m",
    "peak_drive_power": "W",
    "end_time": "s",
    "run_wall_time": "s",
}

_TOKEN = re.compile(r"([A-Za-z_]\w*)|\[(-?\d+)\]|\.")


def _path_parts(path: str) -> list[Union[str, int]]:
    parts: list[Union[str, int]] = []
    pos = 0
    while pos < len(path):
        m = _TOKEN.match(path, pos)
        if m is None:
            raise _beltrs.SceneError(f"sweep parameter {path!r}: not a scene field path (e.g. 'pulleys[1].mass')")
        if m.group(1) is not None:
            parts.append(m.group(1))
        elif m.group(2) is not None:
            parts.append(int(m.group(2)))
        pos = m.end()
    if not parts or not isinstance(parts[0], str):
        raise _beltrs.SceneError(f"sweep parameter {path!r}: not a scene field path (e.g. 'pulleys[1].mass')")
    return parts


def set_field(scene: Scene, path: str, value: Any) -> Scene:
    """A copy of ``scene`` with the field at ``path`` (``"gravity"``,
    ``"pulleys[1].takeup.counterweight"``, ``"pulleys[0].drive.start_curve"``, ...) set to
    ``value``. The copy is validated when it is compiled.

    Raises:
        beltrs.SceneError: the path does not name a field of the scene.
    """
    out = copy.deepcopy(scene)
    parts = _path_parts(path)
    target: Any = out
    for k, part in enumerate(parts[:-1]):
        target = _step(target, part, path, parts[: k + 1])
    last = parts[-1]
    if isinstance(last, int):
        if not isinstance(target, list) or not -len(target) <= last < len(target):
            raise _beltrs.SceneError(f"sweep parameter {path!r}: index {last} out of range")
        target[last] = value
    else:
        if not hasattr(target, "__dataclass_fields__") or last not in target.__dataclass_fields__:
            raise _beltrs.SceneError(f"sweep parameter {path!r}: {type(target).__name__} has no field {last!r}")
        setattr(target, last, value)
    return out


def _step(target: Any, part: Union[str, int], path: str, done: Sequence[Union[str, int]]) -> Any:
    if isinstance(part, int):
        if not isinstance(target, list) or not -len(target) <= part < len(target):
            raise _beltrs.SceneError(f"sweep parameter {path!r}: index {part} out of range")
        return target[part]
    if not hasattr(target, "__dataclass_fields__") or part not in target.__dataclass_fields__:
        raise _beltrs.SceneError(f"sweep parameter {path!r}: {type(target).__name__} has no field {part!r}")
    value = getattr(target, part)
    if value is None:
        shown = "".join(f"[{d}]" if isinstance(d, int) else f".{d}" for d in done).lstrip(".")
        raise _beltrs.SceneError(f"sweep parameter {path!r}: {shown} is None in the base scene")
    return value


def summarise(scene: Scene) -> dict[str, float]:
    """The default per-case work of :func:`sweep`: compile ``scene``, relax it if its
    ``recording.stabilise`` says so, run ``recording.duration`` with its recording settings,
    and return the start-up figures an engineer compares (units in
    :data:`SUMMARY_UNITS`): peak and lowest tension, N (NaN if tension is not recorded), the
    time of the peak, s, the takeup's travel range, m, the largest drive torque, N*m, and
    power, W (absolute values over the drives), the end time and the run's wall time, s."""
    from .simulation import Simulation

    rec = scene.recording
    sim = Simulation(scene)
    if rec.stabilise:
        sim.stabilise(friction=rec.stabilise_friction, progress=False)
    res = sim.run(rec.duration, progress=False, **rec.run_kwargs())
    out = {k: math.nan for k in SUMMARY_UNITS}
    if res.tension is not None and res.tension.size:
        k = np.unravel_index(int(np.argmax(res.tension)), res.tension.shape)
        out["peak_tension"] = float(res.tension[k])
        out["peak_tension_time"] = float(res.time[k[0]])
        out["lowest_tension"] = float(res.tension.min())
    out["takeup_travel_range"] = float(np.ptp(res.takeup_travel, axis=0).max(initial=0.0))
    out["peak_drive_torque"] = float(np.abs(res.drive_torque).max(initial=0.0))
    out["peak_drive_power"] = float(np.abs(res.drive_power).max(initial=0.0))
    out["end_time"] = float(res.time[-1])
    out["run_wall_time"] = float(res.wall_time)
    return out


@dataclass
class _Case:
    index: tuple[int, ...]
    params: dict[str, Any]


def _build_scene(base: Any, params: Mapping[str, Any]) -> Scene:
    if base is None:
        raise _beltrs.SceneError("sweep: a grid needs scene= (a Scene or a function of the parameters)")
    if isinstance(base, Scene):
        scene = base
        for path, value in params.items():
            scene = set_field(scene, path, value)
        return scene
    scene = base(**params)
    if not isinstance(scene, Scene):
        raise _beltrs.SceneError(f"sweep: scene(**{params!r}) returned {type(scene).__name__}, not a beltrs.Scene")
    return scene


def _run_case(base: Any, scene: Optional[Scene], params: Mapping[str, Any], run: Callable[[Scene], Any]) -> dict:
    """One case, on a worker: never raises; errors come back as text."""
    import warnings

    t0 = _time.perf_counter()
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            case_scene = scene if scene is not None else _build_scene(base, params)
            values = dict(run(case_scene))
        out = {"values": values, "error": "", "warnings": [f"{w.category.__name__}: {w.message}" for w in caught]}
    except Exception as err:  # noqa: BLE001 - a failed case is data, not a crash of the sweep
        tb = traceback.extract_tb(err.__traceback__)
        # A beltrs error names field, value and rule; for anything else say where it came from.
        where = f" ({tb[-1].filename}:{tb[-1].lineno})" if tb and not isinstance(err, _beltrs.BeltrsError) else ""
        out = {"values": {}, "error": f"{type(err).__name__}: {err}{where}", "warnings": []}
    out["wall_time"] = _time.perf_counter() - t0
    return out


class _Progress:
    def __init__(self, total: int, enabled: Optional[bool]) -> None:
        if enabled is None:
            enabled = bool(getattr(sys.stderr, "isatty", lambda: False)())
        self.enabled, self.total, self.done, self.failed = enabled, total, 0, 0
        self.start = _time.perf_counter()

    def update(self, failed: bool) -> None:
        self.done += 1
        self.failed += int(failed)
        if self.enabled:
            elapsed = _time.perf_counter() - self.start
            eta = elapsed / self.done * (self.total - self.done)
            sys.stderr.write(f"\rbeltrs sweep: {self.done}/{self.total} cases, {self.failed} failed, "
                             f"{elapsed:.0f} s, ETA {eta:.0f} s ")
            sys.stderr.flush()

    def close(self) -> None:
        if self.enabled:
            sys.stderr.write("\n")
            sys.stderr.flush()


def _label(value: Any) -> Any:
    if isinstance(value, (bool, int, float, str, np.integer, np.floating)):
        return value
    return repr(value)


def sweep(
    scenes_or_grid: Union[Mapping[str, Any], Sequence[Scene]],
    run: Optional[Callable[[Scene], Mapping[str, Any]]] = None,
    client: Any = None,
    *,
    scene: Union[Scene, Callable[..., Scene], None] = None,
    max_workers: Optional[int] = None,
    progress: Optional[bool] = None,
) -> Any:
    """Run many independent cases and gather their answers in an ``xarray.Dataset``.

    Args:
        scenes_or_grid: either a grid, ``{parameter: values}`` (every combination is a
            case; values are a list, or a ``{label: value}`` dict when the values are
            objects such as starting curves), or a list of Scenes (``{name: Scene}`` names
            them).
        run: the work of one case, ``run(scene) -> {name: number or array}`` (picklable: a
            module-level function). Default :func:`summarise` (relax, run, peak tensions,
            takeup travel, drive torque and power).
        client: a ``dask.distributed.Client``: the cases run on its cluster (a
            ``LocalCluster`` or any Dask cluster; docs/sweeps.md shows a multi-machine
            one). Default None: local processes (:class:`concurrent.futures.ProcessPoolExecutor`,
            spawned, so ``run`` and ``scene`` must be importable).
        scene: for a grid, the base: a :class:`~beltrs.Scene` whose fields the parameters
            name by path (``"pulleys[1].takeup.counterweight"``, see :func:`set_field`), or
            a function called with the parameters as keywords that returns a Scene.
        max_workers: local processes. Default: the number of CPUs. 1 runs the cases in
            this process (no pool).
        progress: cases done, failed, elapsed and ETA on stderr. Default None: when stderr
            is a terminal.

    Returns:
        ``xarray.Dataset`` with one dimension per grid parameter (coordinates: the values
        or labels), or ``case`` for a list of scenes; one variable per output of ``run``
        (NaN where a case failed; array outputs get extra dimensions ``NAME_dim0``, ...),
        ``error`` (``""`` or the failure, type, message and place), ``warnings`` (the
        beltrs warnings the case raised, ``"; "``-joined) and ``wall_time`` (s, per
        case). A failed case never stops the sweep.

    Raises:
        beltrs.SceneError: an empty grid, a grid without ``scene``, a parameter path that is
            not a scene field.
        beltrs.BeltrsError: xarray is not installed.
    """
    from .result import _require

    xr = _require("xarray", "beltrs.study.sweep")
    run = summarise if run is None else run
    if isinstance(scenes_or_grid, Mapping) and not scenes_or_grid:
        raise _beltrs.SceneError("sweep: the grid is empty")
    if isinstance(scenes_or_grid, Mapping) and not all(isinstance(v, Scene) for v in scenes_or_grid.values()):
        grid = dict(scenes_or_grid)
        if scene is None:
            raise _beltrs.SceneError("sweep: a grid needs scene= (a Scene or a function of the parameters)")
        dims, axes = [], []
        for name, values in grid.items():
            if isinstance(values, Mapping):
                labels, vals = list(values.keys()), list(values.values())
            elif isinstance(values, (str, bytes)) or not isinstance(values, Sequence):
                raise _beltrs.SceneError(f"sweep: grid[{name!r}] = {values!r}: must be a list of values or a dict")
            else:
                vals = list(values)
                labels = [_label(v) for v in vals]
            if not vals:
                raise _beltrs.SceneError(f"sweep: grid[{name!r}] is empty")
            if isinstance(scene, Scene):
                _path_parts(name)  # refuse a bad path before anything runs
            dims.append(name)
            axes.append((labels, vals))
        cases = [
            _Case(tuple(idx), {d: axes[k][1][i] for k, (d, i) in enumerate(zip(dims, idx))})
            for idx in itertools.product(*(range(len(a[1])) for a in axes))
        ]
        base, scenes = scene, None
        coords = {d: list(axes[k][0]) for k, d in enumerate(dims)}
        shape = tuple(len(a[1]) for a in axes)
    else:
        if isinstance(scenes_or_grid, Mapping):
            names, scene_list = list(scenes_or_grid.keys()), list(scenes_or_grid.values())
        else:
            scene_list = list(scenes_or_grid)
            names = list(range(len(scene_list)))
        if not scene_list:
            raise _beltrs.SceneError("sweep: no scenes given")
        for k, s in enumerate(scene_list):
            if not isinstance(s, Scene):
                raise _beltrs.SceneError(f"sweep: scenes[{k}] is {type(s).__name__}, not a beltrs.Scene")
        dims, shape = ["case"], (len(scene_list),)
        cases = [_Case((k,), {}) for k in range(len(scene_list))]
        base, scenes = None, scene_list
        coords = {"case": names}

    bar = _Progress(len(cases), progress)
    outcomes: list[Optional[dict]] = [None] * len(cases)
    try:
        if client is not None:
            _on_dask(client, cases, base, scenes, run, outcomes, bar)
        elif max_workers == 1:
            for k, case in enumerate(cases):
                outcomes[k] = _run_case(base, None if scenes is None else scenes[k], case.params, run)
                bar.update(bool(outcomes[k]["error"]))
        else:
            _check_picklable(base, run)
            _on_processes(max_workers, cases, base, scenes, run, outcomes, bar)
    finally:
        bar.close()
    return _gather(xr, dims, shape, coords, cases, outcomes)


def _check_picklable(base: Any, run: Any) -> None:
    import pickle

    for name, value in (("scene", base), ("run", run)):
        try:
            pickle.dumps(value)
        except Exception as err:  # noqa: BLE001
            raise _beltrs.SceneError(
                f"sweep: {name} = {value!r} cannot be sent to a worker process ({type(err).__name__}: {err}); "
                f"use a module-level function (not a lambda or a local function), or max_workers=1 to run "
                f"here, or a Dask client (it pickles functions by value)"
            ) from None


def _on_processes(max_workers: Optional[int], cases: list, base: Any, scenes: Optional[list], run: Any,
                  outcomes: list, bar: _Progress) -> None:
    import concurrent.futures as cf
    import multiprocessing

    workers = max_workers or os.cpu_count() or 1
    with cf.ProcessPoolExecutor(max_workers=min(workers, len(cases)),
                                mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = {
            pool.submit(_run_case, base, None if scenes is None else scenes[k], case.params, run): k
            for k, case in enumerate(cases)
        }
        for future in cf.as_completed(futures):
            k = futures[future]
            err = future.exception()
            outcomes[k] = future.result() if err is None else _failed(err)
            bar.update(bool(outcomes[k]["error"]))


def _failed(error: BaseException) -> dict:
    """The failure of a worker itself (killed, lost, ...) as a failed case."""
    return {"values": {}, "error": f"{type(error).__name__}: {error}", "warnings": [], "wall_time": math.nan}


def _on_dask(client: Any, cases: list, base: Any, scenes: Optional[list], run: Any, outcomes: list,
             bar: _Progress) -> None:
    try:
        from distributed import as_completed
    except ImportError:  # pragma: no cover - a client implies distributed
        raise _beltrs.BeltrsError("sweep(client=...) needs the package 'distributed': pip install 'dask[distributed]'")
    futures = [
        client.submit(_run_case, base, None if scenes is None else scenes[k], case.params, run, pure=False)
        for k, case in enumerate(cases)
    ]
    index = {f.key: k for k, f in enumerate(futures)}
    for future in as_completed(futures):
        k = index[future.key]
        try:
            outcomes[k] = future.result()
        except Exception as err:  # noqa: BLE001 - a lost worker is a failed case
            outcomes[k] = _failed(err)
        bar.update(bool(outcomes[k]["error"]))


def _gather(xr: Any, dims: list, shape: tuple, coords: dict, cases: list, outcomes: list) -> Any:
    names: list[str] = []
    examples: dict[str, np.ndarray] = {}
    for out in outcomes:
        for key, value in out["values"].items():
            if key not in examples:
                names.append(key)
                examples[key] = np.asarray(value)
    data_vars: dict[str, Any] = {}
    for key in names:
        example = examples[key]
        kind = example.dtype.kind
        fill: Any = np.nan if kind in "fiub" else ""
        dtype = float if kind in "fiub" else object
        arr = np.full(shape + example.shape, fill, dtype=dtype)
        for case, out in zip(cases, outcomes):
            if key in out["values"]:
                value = np.asarray(out["values"][key])
                if value.shape != example.shape:
                    raise _beltrs.BeltrsError(
                        f"sweep: output {key!r} has shape {value.shape} in case {case.params or case.index}, "
                        f"{example.shape} in another; outputs must have one shape"
                    )
                arr[case.index] = value
        extra = tuple(f"{key}_dim{k}" for k in range(example.ndim))
        attrs = {"units": SUMMARY_UNITS[key]} if key in SUMMARY_UNITS else {}
        data_vars[key] = (tuple(dims) + extra, arr, attrs)
    error = np.full(shape, "", dtype=object)
    warned = np.full(shape, "", dtype=object)
    wall = np.full(shape, np.nan)
    for case, out in zip(cases, outcomes):
        error[case.index] = out["error"]
        warned[case.index] = "; ".join(out["warnings"])
        wall[case.index] = out["wall_time"]
    data_vars["error"] = (tuple(dims), error, {"long_name": "failure of the case ('' if it ran)"})
    data_vars["warnings"] = (tuple(dims), warned, {"long_name": "warnings the case raised"})
    data_vars["wall_time"] = (tuple(dims), wall, {"units": "s", "long_name": "wall time of the case"})
    failed = int(sum(bool(o["error"]) for o in outcomes))
    return xr.Dataset(data_vars, coords=coords,
                      attrs={"cases": len(cases), "failed": failed})

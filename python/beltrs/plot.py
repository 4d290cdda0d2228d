"""Plots (matplotlib, imported lazily and drawn off-screen): the demo figure and the
figures of a Result, each a function returning a matplotlib Figure (:func:`waterfall`,
:func:`envelope`, :func:`takeup`, :func:`drives`, :func:`slip_margin`), written together
by :func:`plot_result` and ``beltrs plot`` (docs/cli.md). Every panel has a title and axis
labels with units; tension is drawn against distance along the belt (m), not element
number; signs are those of an engineer (torque and power positive when driving, takeup
travel from the start of the run).

>>> fig = beltrs.plot.waterfall(res)
>>> fig.savefig("waterfall.png")
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Sequence, Union

import numpy as np

from . import _beltrs

if TYPE_CHECKING:  # pragma: no cover
    from .result import Result

__all__ = [
    "FIGURES",
    "along_route",
    "belt_distance",
    "contact_runs",
    "drives",
    "envelope",
    "plot_result",
    "plot_tension_around_belt",
    "slip_margin",
    "takeup",
    "waterfall",
]


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def belt_distance(node_position: Optional[np.ndarray] = None, rest_length: Optional[np.ndarray] = None,
                  elements: Optional[int] = None) -> tuple[np.ndarray, str]:
    """Distance along the belt of each element's midpoint, m, and an axis label.

    From the rest lengths (material coordinate from node 0) if given, else from the node
    positions (arc length along the polygon), else the element index (label says so)."""
    if rest_length is not None:
        rl = np.asarray(rest_length, dtype=float)
        return np.cumsum(rl) - rl / 2, "distance along the belt from node 0 (m, unstretched)"
    if node_position is not None:
        x = np.asarray(node_position, dtype=float)
        seg = np.hypot(*(np.roll(x, -1, axis=0) - x).T)
        return np.cumsum(seg) - seg / 2, "distance along the belt from node 0 (m)"
    n = int(elements or 0)
    return np.arange(n, dtype=float), "element"


def contact_runs(node_position: np.ndarray, centres: Sequence[Sequence[float]], radii: Sequence[float],
                 tolerance: float = 0.01) -> list[tuple[int, int, int]]:
    """The belt's contact arcs: ``(pulley, first node, last node)`` for each run of
    consecutive nodes (cyclic) inside a pulley or within ``tolerance`` × radius outside its
    surface. The first and last nodes of a run are the tangent points (the belt meets and
    leaves the pulley there).

    Inside counts however deep: the rigid-body belt's points are its bodies' mass centres,
    which sit on the chords, inside the radius (by 2.3 % of it on the builder's 0.4 m
    drums, measured), not on the surface as the node belt's nodes do."""
    x = np.asarray(node_position, dtype=float)
    n = len(x)
    runs = []
    for j, (c, r) in enumerate(zip(centres, radii)):
        on = np.hypot(*(x - np.asarray(c, dtype=float)).T) - r <= tolerance * r
        if not on.any() or on.all():
            continue
        start = int(np.flatnonzero(~on)[0])  # begin scanning just after a free node
        k = 0
        while k < n:
            i = (start + k) % n
            if on[i]:
                first = i
                while k < n and on[(start + k) % n]:
                    k += 1
                runs.append((j, first, (start + k - 1) % n))
            else:
                k += 1
    return runs


def plot_tension_around_belt(
    node_position: np.ndarray,
    tension: np.ndarray,
    path: Union[str, Path],
    *,
    title: str = "Belt tension",
    takeup_time: Optional[np.ndarray] = None,
    takeup_travel: Optional[np.ndarray] = None,
    rest_length: Optional[np.ndarray] = None,
    pulleys: Optional[Sequence[Any]] = None,
    centres: Optional[np.ndarray] = None,
    dynamic_time: Optional[np.ndarray] = None,
    dynamic_tension: Optional[np.ndarray] = None,
    dynamic_title: str = "dynamic",
) -> Path:
    """Write a PNG for an engineer: the belt coloured by tension (kN); tension against
    distance along the belt with the tangent points marked (static, and the dynamic
    envelope and peak if given); takeup position against time if given.

    Args:
        node_position: ``[E, 2]`` node positions of the state drawn, m.
        tension: ``[E]`` element tensions of that state, N.
        path: PNG file to write.
        title: title of the belt panel.
        takeup_time, takeup_travel: ``[n]`` s and m, the takeup panel.
        rest_length: ``[E]`` element rest lengths, m (distance along the belt); default:
            arc length of ``node_position``.
        pulleys: the scene's pulleys (``center``, ``radius``, ``name``), to mark the tangent
            points and name the contact arcs.
        centres: ``[P, 2]`` pulley centres of the state drawn, m (a takeup pulley moves);
            default: the scene's ``center``.
        dynamic_time, dynamic_tension: ``[n]`` s and ``[n, E]`` N of a run: its envelope
            (max and min over time of each element) is drawn with the static tension and
            its peak marked.
        dynamic_title: what the run was, for the legend.

    Returns:
        the path written.
    """
    plt = _pyplot()
    from matplotlib.collections import LineCollection

    x = np.asarray(node_position)
    t = np.asarray(tension) / 1e3
    dist, xlabel = belt_distance(x, rest_length)
    has_takeup = takeup_time is not None and takeup_travel is not None
    ncols = 3 if has_takeup else 2
    widths = [1.0, 2.0, 1.2][:ncols]
    fig, axes = plt.subplots(1, ncols, figsize=(5.2 * sum(widths) / 1.4, 5.5),
                             gridspec_kw={"width_ratios": widths})
    if pulleys is not None and centres is None:
        centres = np.array([p.center for p in pulleys], dtype=float)
    runs = [] if pulleys is None else contact_runs(x, centres, [p.radius for p in pulleys])

    # Panel 1: the belt coloured by tension.
    seg = np.stack([x, np.roll(x, -1, axis=0)], axis=1)
    lc = LineCollection(seg, array=t, cmap="viridis", linewidths=4)
    ax = axes[0]
    ax.add_collection(lc)
    ax.autoscale()
    ax.set_aspect("equal")
    ax.margins(0.15)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)
    fig.colorbar(lc, ax=ax, label="tension (kN)")
    for j, first, last in runs:
        for node in (first, last):
            ax.plot(*x[node], "o", color="crimson", ms=5, zorder=3)
    if pulleys is not None:
        for p, c in zip(pulleys, centres):
            ax.annotate(p.name, (c[0] + 1.6 * p.radius, c[1]), ha="left", va="center", fontsize=8)

    # Panel 2: tension against distance along the belt, tangent points marked.
    ax = axes[1]
    ax.plot(dist, t, ".-", color="C0", label="static")
    if dynamic_tension is not None:
        dyn = np.asarray(dynamic_tension) / 1e3
        hi, lo = dyn.max(axis=0), dyn.min(axis=0)
        ax.fill_between(dist, lo, hi, color="C1", alpha=0.3, label=f"{dynamic_title}: range over time")
        k = np.unravel_index(int(np.argmax(dyn)), dyn.shape)
        when = "" if dynamic_time is None else f" at t = {np.asarray(dynamic_time)[k[0]]:.2f} s"
        ax.plot(dist[k[1]], dyn[k], "v", color="C3", ms=9,
                label=f"dynamic peak {dyn[k]:.1f} kN{when}")
    ymax = ax.get_ylim()[1]
    for j, first, last in runs:
        name = pulleys[j].name if pulleys is not None else str(j)
        for node, side in ((first, "meets"), (last, "leaves")):
            # Tangent point: the node where the belt meets or leaves the pulley.
            ax.axvline(dist[node] if node < len(dist) else dist[-1], color="crimson", lw=0.8, ls="--")
        ax.annotate(name, ((dist[first] + dist[last]) / 2 if last >= first else dist[first], ymax),
                    ha="center", va="top", fontsize=8, color="crimson")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("tension (kN)")
    ax.set_title("Tension along the belt (dashed: tangent points)")
    ax.grid(True, alpha=0.4)
    ax.legend(loc="lower right", fontsize=8)

    if has_takeup:
        ax = axes[2]
        ax.plot(takeup_time, takeup_travel)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("takeup position y (m)")
        ax.set_title("Takeup position")
        ax.grid(True, alpha=0.4)
    fig.tight_layout()
    out = Path(path)
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out


def _distance_of(res: "Result") -> tuple[np.ndarray, str]:
    rest = res.metadata.get("rest_length") if res.metadata else None
    first = None if res.node_position is None else res.node_position[0]
    n = None if res.tension is None else res.tension.shape[1]
    return belt_distance(first, rest, n)


def _arc_lengths(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """Arc length along the closed polygon ``x`` to each node, each element's length, and
    the polygon's length."""
    chord = np.roll(x, -1, axis=0) - x
    length = np.hypot(chord[:, 0], chord[:, 1])
    start = np.concatenate([[0.0], np.cumsum(length)[:-1]])
    return start, length, float(start[-1] + length[-1])


def _route_frame(res: "Result") -> tuple[int, float, list[tuple[str, float, float]]]:
    """The route's frame at the first instant: the direction of travel (+1 node order), the
    origin (arc length in node order from node 0's start: where the belt leaves the first
    driven pulley, else node 0) and every pulley's contact arc as (name, meets, leaves) in
    route distance."""
    x = res.node_position[0]
    start, _, total = _arc_lengths(x)
    try:
        direction = res.travel_direction
    except _beltrs.BeltrsError:
        direction = 1
    radius = res.metadata.get("pulley_radius") if res.metadata else None
    runs = [] if radius is None else contact_runs(x, res.pulley_position[0], np.asarray(radius, dtype=float))
    leaves = {j: (last if direction > 0 else first) for j, first, last in runs}
    meets = {j: (first if direction > 0 else last) for j, first, last in runs}
    driven = [j for j in range(res.drive_torque.shape[1]) if np.any(res.drive_torque[:, j] != 0) and j in leaves]
    origin = float(start[leaves[driven[0]]]) if driven else 0.0
    names = _names(res)

    def route(place: float) -> float:
        return float((direction * (place - origin)) % total)

    arcs = [(names[j], route(start[meets[j]]), route(start[leaves[j]])) for j, _, _ in runs]
    return direction, origin, arcs


def along_route(res: "Result", cutoff: Optional[float] = None) -> tuple[np.ndarray, np.ndarray, str]:
    """Tension against distance along the belt's route, in a frame fixed in space.

    The belt moves, so an element's material coordinate is not a place on the conveyor.
    At every instant the tensions are placed at their element midpoints' arc length along
    the belt's polygon and interpolated (linearly, cyclically) onto the places of the
    first instant's midpoints. Distance runs in the belt's direction of travel
    (:attr:`beltrs.Result.travel_direction`) from where the belt leaves the first driven
    pulley at the first instant (so a drive's slack side is at 0 and its tight side at the
    end), or from node 0's first position without a drive. So column e is always the same
    place on the conveyor.

    Args:
        res: the result (tension and node positions recorded).
        cutoff: if given, each place's tension is low-passed in time below ``cutoff`` Hz
            (:func:`beltrs.analysis.low_pass`), e.g. to look through the node model's
            chordal ripple; the label says so.

    Returns:
        ``(distance, tension, label)``: ``[E]`` m ascending, ``[n, E]`` N, an axis label.
        Without recorded node positions, the material coordinate (rest lengths from node 0)
        and a label saying so.
    """
    if res.tension is None:
        raise _beltrs.BeltrsError("needs the tension channel")
    if res.node_position is None:
        dist, label = _distance_of(res)
        out, label = res.tension, label + ", material: moves with the belt"
    else:
        direction, origin, _ = _route_frame(res)
        x_all = res.node_position
        ref = x_all[0, 0]
        out = np.empty_like(res.tension)
        grid = None
        for k in range(len(res.time)):
            x = x_all[k]
            start, length, total = _arc_lengths(x)
            chord = np.roll(x, -1, axis=0) - x
            t = np.clip(np.einsum("ij,ij->i", ref - x, chord) / np.maximum(length**2, 1e-300), 0.0, 1.0)
            gap = np.hypot(*(x + t[:, None] * chord - ref).T)
            e = int(np.argmin(gap))
            place = start + 0.5 * length - (start[e] + t[e] * length[e])  # node order, from node 0's start
            place = (direction * (place - origin)) % total
            if grid is None:
                grid = place.copy()
            order = np.argsort(place)
            out[k] = np.interp(grid, place[order], res.tension[k, order], period=total)
        columns = np.argsort(grid)
        dist, out = grid[columns], out[:, columns]
        label = "distance along the route in the direction of travel (m)"
    if cutoff is not None:
        out = _low_pass(res, out, cutoff)
        label += f"; below {cutoff:g} Hz"
    return dist, out, label


def _low_pass(res: "Result", values: np.ndarray, cutoff: float) -> np.ndarray:
    """``values`` ([n, ...]) low-passed in time below ``cutoff`` Hz."""
    from .analysis import low_pass

    if not (isinstance(cutoff, (int, float)) and np.isfinite(cutoff) and cutoff > 0):
        raise _beltrs.BeltrsError(f"cutoff = {cutoff!r}: must be a frequency > 0, Hz")
    if len(res.time) < 3:
        return values
    interval = float(np.median(np.diff(res.time)))
    flat = np.asarray(values, dtype=float).reshape(len(res.time), -1)
    return np.stack([low_pass(flat[:, c], interval, cutoff) for c in range(flat.shape[1])], axis=1).reshape(
        np.shape(values))


def _pulley_arcs(res: "Result") -> list[tuple[str, float, float]]:
    """Each pulley's contact arc at the first instant as (name, meets, leaves) distance
    along the route (the frame of :func:`along_route`), for marking the plots."""
    if res.node_position is None or not res.metadata or res.metadata.get("pulley_radius") is None:
        return []
    return _route_frame(res)[2]


def _mark_pulleys(ax: Any, arcs: list[tuple[str, float, float]], total: float, shade: bool = True,
                  color: str = "grey") -> None:
    """Dashed lines where the belt meets and leaves each pulley, the arc shaded (split in
    two where it spans the start of the route), the pulley's name above the axes."""
    for name, a, b in arcs:
        spans = [(a, b)] if b >= a else [(a, total), (0.0, b)]
        if shade:
            for lo, hi in spans:
                ax.axvspan(lo, hi, color=color, alpha=0.15, lw=0)
        for edge in (a, b):
            ax.axvline(edge, color=color, lw=0.6, ls="--", alpha=0.8)
        lo, hi = max(spans, key=lambda span: span[1] - span[0])
        ax.annotate(name, ((lo + hi) / 2, 1.0), xycoords=("data", "axes fraction"), xytext=(0, 2),
                    textcoords="offset points", ha="center", va="bottom", fontsize=8)


def _route_length(res: "Result") -> float:
    if res.node_position is None:
        return 0.0
    x = res.node_position[0]
    return float(np.hypot(*(np.roll(x, -1, axis=0) - x).T).sum())


def _names(res: "Result") -> list[str]:
    names = list(res.pulley_names) or [str(j) for j in range(res.takeup_travel.shape[1])]
    return [name or f"pulley {j}" for j, name in enumerate(names)]


def _new(figsize: tuple[float, float], rows: int = 1) -> tuple[Any, Any]:
    plt = _pyplot()
    return plt.subplots(rows, 1, figsize=figsize, sharex=True)


def _peak(kn: np.ndarray) -> tuple[int, int]:
    k = np.unravel_index(int(np.argmax(kn)), kn.shape)
    return int(k[0]), int(k[1])


def waterfall(res: "Result", cutoff: Optional[float] = None) -> Any:
    """Tension waterfall: tension (colour, kN) over distance along the belt's route (x,
    :func:`along_route`: a frame fixed in space, in the direction of travel, pulleys'
    contact arcs dashed) and time (y), the peak marked. Stress waves are the slanted
    stripes. ``cutoff`` (Hz): low-pass each place's tension in time first (the band is in
    the axis label). Needs the tension channel. Returns the matplotlib Figure."""
    if res.tension is None or len(res.time) < 2:
        raise _beltrs.BeltrsError("waterfall: needs the tension channel and at least two instants")
    dist, tension, xlabel = along_route(res, cutoff)
    kn = tension / 1e3
    fig, ax = _new((9, 5.5))
    mesh = ax.pcolormesh(dist, res.time, kn, shading="nearest", cmap="viridis", rasterized=True)
    fig.colorbar(mesh, ax=ax, label="tension (kN)")
    _mark_pulleys(ax, _pulley_arcs(res), _route_length(res), shade=False, color="white")
    k = _peak(kn)
    ax.plot(dist[k[1]], res.time[k[0]], "v", color="crimson", mec="white", ms=10)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("time (s)")
    ax.set_title("Tension waterfall (dashed: where the belt meets and leaves each pulley)\n"
                 f"peak (red marker) {kn[k]:.1f} kN at t = {res.time[k[0]]:.2f} s, {dist[k[1]]:.1f} m", pad=14)
    fig.tight_layout()
    return fig


def envelope(res: "Result", cutoff: Optional[float] = None) -> Any:
    """Tension envelope along the belt's route (:func:`along_route`): the largest and
    smallest tension at each place over the run (kN), the first and last instants, the
    peak, and the pulleys' contact arcs shaded. ``cutoff`` (Hz): from tensions low-passed
    in time (named in the axis label). Returns the Figure."""
    if res.tension is None or len(res.time) < 1:
        raise _beltrs.BeltrsError("envelope: needs the tension channel")
    dist, tension, xlabel = along_route(res, cutoff)
    kn = tension / 1e3
    fig, ax = _new((9, 5))
    ax.fill_between(dist, kn.min(axis=0), kn.max(axis=0), color="C0", alpha=0.25, label="range over the run")
    ax.plot(dist, kn.max(axis=0), color="C3", lw=1.2, label="max")
    ax.plot(dist, kn.min(axis=0), color="C2", lw=1.2, label="min")
    ax.plot(dist, kn[0], color="k", lw=0.8, ls=":", label=f"start, t = {res.time[0]:.2f} s")
    ax.plot(dist, kn[-1], color="k", lw=0.8, label=f"end, t = {res.time[-1]:.2f} s")
    k = _peak(kn)
    ax.plot(dist[k[1]], kn[k], "v", color="crimson", ms=9,
            label=f"peak {kn[k]:.1f} kN at t = {res.time[k[0]]:.2f} s")
    low = np.unravel_index(int(np.argmin(kn)), kn.shape)
    if kn[low] < 0:
        ax.axhline(0, color="grey", lw=0.8)
        ax.plot(dist[low[1]], kn[low], "^", color="C2", ms=8, label=f"lowest {kn[low]:.1f} kN (compression)")
    _mark_pulleys(ax, _pulley_arcs(res), _route_length(res))
    ax.set_xlabel(xlabel)
    ax.set_ylabel("tension (kN)")
    ax.set_title("Tension envelope along the belt (max and min over the run; shaded: pulleys)", pad=14)
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    return fig


def _moving(res: "Result") -> list[int]:
    return [j for j in range(res.takeup_travel.shape[1]) if np.any(res.takeup_travel[:, j] != res.takeup_travel[0, j])]


def takeup(res: "Result") -> Any:
    """Takeup travel since the start of the run (m, positive towards the counterweight)
    of every pulley that moved. Returns the Figure."""
    moved = _moving(res)
    if not moved:
        raise _beltrs.BeltrsError("takeup: no pulley moved during the run")
    names = _names(res)
    travel = res.takeup_travel_from_start
    fig, ax = _new((8, 4.5))
    for j in moved:
        ax.plot(res.time, travel[:, j] * 1e3, label=f"{names[j]} (start at {res.takeup_travel[0, j]:.4f} m "
                "from its scene position)")
    ax.axhline(0, color="grey", lw=0.8)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("travel since the start (mm)")
    ax.set_title("Takeup travel (+ towards the counterweight)")
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def _driven(res: "Result") -> list[int]:
    return [j for j in range(res.drive_torque.shape[1]) if np.any(res.drive_torque[:, j] != 0)]


def _series(ax: Any, res: "Result", values: np.ndarray, label: str, cutoff: Optional[float], **kw: Any) -> Any:
    """Plot a time series: raw; with ``cutoff``, raw thin and light and the low-passed
    series over it, labelled with its band."""
    if cutoff is None or not np.all(np.isfinite(values)):
        return ax.plot(res.time, values, label=label, **kw)[0]
    raw = ax.plot(res.time, values, lw=0.6, alpha=0.35, **kw)[0]
    kw.setdefault("color", raw.get_color())
    return ax.plot(res.time, _low_pass(res, values, cutoff), lw=1.6, label=f"{label}, below {cutoff:g} Hz", **kw)[0]


def drives(res: "Result", cutoff: Optional[float] = None) -> Any:
    """Drive torque (kN·m, positive when it drives the belt along its direction of travel)
    and drive power (kW, positive when delivered) of every driven pulley against time.
    ``cutoff`` (Hz): also draw each series low-passed below it (raw kept, light).
    Returns the Figure."""
    driven = _driven(res)
    if not driven:
        raise _beltrs.BeltrsError("drives: no pulley has a drive torque")
    names = _names(res)
    torque = res.driving_torque
    power = res.drive_power_kw
    fig, (a1, a2) = _new((8, 6.5), rows=2)
    for j in driven:
        line = _series(a1, res, torque[:, j] / 1e3, names[j], cutoff)
        _series(a2, res, power[:, j], names[j], cutoff, color=line.get_color())
    a1.set_ylabel("torque (kN·m)")
    a1.set_title("Drive torque (+ driving the belt along its direction of travel)")
    a2.set_ylabel("power (kW)")
    a2.set_title("Drive power (+ delivered to the belt)")
    a2.set_xlabel("time (s)")
    for a in (a1, a2):
        a.axhline(0, color="grey", lw=0.8)
        a.grid(True, alpha=0.4)
        a.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return fig


def slip_margin(res: "Result", cutoff: Optional[float] = None) -> Any:
    """Capstan utilisation of every driven or braked pulley with friction against time:
    (T1 - T2)/(T2·(e^{µs·θ} - 1)), 1 at the Euler–Eytelwein slip limit
    (:meth:`beltrs.Result.capstan`), with the tension ratio T1/T2 against e^{µs·θ} below.
    ``cutoff`` (Hz): also draw each series low-passed below it. Returns the Figure."""
    cap = res.capstan()
    names = _names(res)
    loaded = [j for j in range(len(names)) if cap.friction[j] > 0 and (
        np.any(res.drive_torque[:, j] != 0) or np.any(res.brake_torque[:, j] != 0))]
    if not loaded:
        raise _beltrs.BeltrsError("slip_margin: no driven or braked pulley has friction")
    fig, (a1, a2) = _new((8, 6.5), rows=2)
    for j in loaded:
        line = _series(a1, res, cap.utilisation[:, j], names[j], cutoff)
        color = line.get_color()
        _series(a2, res, cap.tight[:, j] / cap.slack[:, j], f"{names[j]}: T1/T2", cutoff, color=color)
        a2.plot(res.time, np.exp(cap.friction[j] * cap.wrap[:, j]), color=color, ls="--", lw=1,
                label=f"{names[j]}: e^(µs·θ), µs = {cap.friction[j]:g}")
    a1.axhline(1.0, color="crimson", lw=1, ls="--", label="slip limit")
    a1.set_ylim(bottom=0)
    a1.set_ylabel("utilisation (1)")
    a1.set_title("Slip margin: capstan utilisation (T1 − T2) / (T2·(e^(µs·θ) − 1))")
    a2.set_ylim(bottom=1)
    a2.set_ylabel("tension ratio (1)")
    a2.set_title("Tension ratio T1/T2 against the capstan limit")
    a2.set_xlabel("time (s)")
    for a in (a1, a2):
        a.grid(True, alpha=0.4)
        a.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return fig


#: The figures of :func:`plot_result` (and ``beltrs plot``): file suffix and function.
FIGURES = {"waterfall": waterfall, "envelope": envelope, "takeup": takeup, "drives": drives, "slip": slip_margin}


def plot_result(res: "Result", out_dir: Union[str, Path], stem: str = "result",
                cutoff: Optional[float] = None) -> list[Path]:
    """Write the figures of ``beltrs plot`` for ``res`` into ``out_dir`` as PNGs and return
    their paths: ``STEM_waterfall.png`` (:func:`waterfall`), ``STEM_envelope.png``
    (:func:`envelope`), ``STEM_takeup.png`` (:func:`takeup`), ``STEM_drives.png``
    (:func:`drives`) and ``STEM_slip.png`` (:func:`slip_margin`). A figure whose data the
    result lacks (no tension recorded, no takeup, no drive, no friction) is skipped.
    ``cutoff`` (Hz) is passed to every figure but the takeup's (a low-passed series is
    drawn over the raw one, its band named)."""
    plt = _pyplot()
    out_dir = Path(out_dir)
    written: list[Path] = []
    for name, draw in FIGURES.items():
        try:
            fig = draw(res) if draw is takeup else draw(res, cutoff)
        except _beltrs.BeltrsError as err:
            if str(err).startswith("cutoff"):
                raise
            continue
        path = out_dir / f"{stem}_{name}.png"
        fig.savefig(path, dpi=100)
        plt.close(fig)
        written.append(path)
    return written

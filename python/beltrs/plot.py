"""Plots (matplotlib, imported lazily and drawn off-screen): the demo figure and the
figures of ``beltrs plot`` (docs/cli.md). Every panel has a title, axis labels with units,
and tension is drawn against distance along the belt (m), not element number."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Optional, Sequence, Union

import numpy as np

if TYPE_CHECKING:  # pragma: no cover
    from .result import Result

__all__ = [
    "belt_distance",
    "contact_runs",
    "plot_result",
    "plot_tension_around_belt",
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
    consecutive nodes (cyclic) within ``tolerance`` × radius of a pulley's surface. The
    first and last nodes of a run are the tangent points (the belt meets and leaves the
    pulley there)."""
    x = np.asarray(node_position, dtype=float)
    n = len(x)
    runs = []
    for j, (c, r) in enumerate(zip(centres, radii)):
        on = np.abs(np.hypot(*(x - np.asarray(c, dtype=float)).T) - r) <= tolerance * r
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


def plot_result(res: "Result", out_dir: Union[str, Path], stem: str = "result") -> list[Path]:
    """Write the figures of ``beltrs plot`` for ``res`` into ``out_dir`` and return their
    paths: ``STEM_waterfall.png`` (tension over distance along the belt and time),
    ``STEM_envelope.png`` (max, min and final tension along the belt), ``STEM_takeup.png``
    (takeup travel of each takeup pulley against time), ``STEM_drives.png`` (drive
    torque and power of each driven pulley against time). Figures whose data were not
    recorded (no tension, no takeup, no drive) are skipped."""
    plt = _pyplot()
    out_dir = Path(out_dir)
    written: list[Path] = []
    time = res.time
    names = list(res.pulley_names) or [str(j) for j in range(res.takeup_travel.shape[1])]

    def save(fig: Any, name: str) -> None:
        fig.tight_layout()
        path = out_dir / f"{stem}_{name}.png"
        fig.savefig(path, dpi=100)
        plt.close(fig)
        written.append(path)

    if res.tension is not None and len(time) >= 2:
        dist, xlabel = _distance_of(res)
        kn = res.tension / 1e3
        fig, ax = plt.subplots(figsize=(9, 5.5))
        mesh = ax.pcolormesh(dist, time, kn, shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label="tension (kN)")
        k = np.unravel_index(int(np.argmax(kn)), kn.shape)
        ax.plot(dist[k[1]], time[k[0]], "v", color="crimson", ms=9,
                label=f"peak {kn[k]:.1f} kN at t = {time[k[0]]:.2f} s")
        ax.legend(loc="upper right", fontsize=8)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("time (s)")
        ax.set_title("Tension waterfall: tension over the belt and time")
        save(fig, "waterfall")

        fig, ax = plt.subplots(figsize=(9, 5))
        ax.fill_between(dist, kn.min(axis=0), kn.max(axis=0), color="C0", alpha=0.3, label="range over the run")
        ax.plot(dist, kn.max(axis=0), color="C3", lw=1, label="max")
        ax.plot(dist, kn.min(axis=0), color="C2", lw=1, label="min")
        ax.plot(dist, kn[0], color="k", lw=0.8, ls=":", label=f"t = {time[0]:.2f} s")
        ax.plot(dist, kn[-1], color="k", lw=0.8, label=f"t = {time[-1]:.2f} s")
        ax.plot(dist[k[1]], kn[k], "v", color="crimson", ms=9, label=f"peak {kn[k]:.1f} kN")
        if kn.min() < 0:
            ax.axhline(0, color="grey", lw=0.8)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("tension (kN)")
        ax.set_title("Tension envelope along the belt")
        ax.grid(True, alpha=0.4)
        ax.legend(fontsize=8)
        save(fig, "envelope")

    takeups = [j for j in range(res.takeup_travel.shape[1]) if np.any(res.takeup_travel[:, j] != 0)]
    if takeups:
        fig, ax = plt.subplots(figsize=(8, 4.5))
        for j in takeups:
            ax.plot(time, res.takeup_travel[:, j], label=names[j])
        ax.set_xlabel("time (s)")
        ax.set_ylabel("takeup travel (m, + towards the counterweight)")
        ax.set_title("Takeup travel")
        ax.grid(True, alpha=0.4)
        ax.legend(fontsize=8)
        save(fig, "takeup")

    driven = [j for j in range(res.drive_torque.shape[1]) if np.any(res.drive_torque[:, j] != 0)]
    if driven:
        power = res.drive_power
        fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
        for j in driven:
            a1.plot(time, res.drive_torque[:, j] / 1e3, label=names[j])
            a2.plot(time, power[:, j] / 1e3, label=names[j])
        a1.set_ylabel("drive torque (kN·m, ccw +)")
        a1.set_title("Drive torque")
        a2.set_ylabel("drive power (kW)")
        a2.set_title("Drive power (torque × pulley speed)")
        a2.set_xlabel("time (s)")
        for a in (a1, a2):
            a.grid(True, alpha=0.4)
            a.legend(fontsize=8)
        save(fig, "drives")
    return written

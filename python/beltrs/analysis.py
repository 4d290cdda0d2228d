"""Post-processing helpers shared by the demo, the tests and the benchmarks."""

from __future__ import annotations

from typing import Sequence

import numpy as np

__all__ = ["arrival_time", "belt_coordinate", "hustrulid_tangent_tensions", "strand_tension"]


def strand_tension(
    node_position: np.ndarray,
    tension: np.ndarray,
    start: Sequence[float],
    end: Sequence[float],
    at: Sequence[float],
    tolerance: float = 0.05,
) -> float:
    """Tension (N) of a free straight strand at point ``at`` (m), from a least-squares line.

    The elements whose two nodes lie within ``tolerance`` (m) of the segment
    ``start``-``end`` (m) and whose midpoints lie strictly between its ends are fitted with
    T(s) = a + b*s along the strand, and the fit is evaluated at the projection of ``at``.
    This reads the tension at a tangent point without the local step that nodal contact
    puts in the first element on a pulley (thesis §6.3).
    """
    x = np.asarray(node_position, dtype=float)
    t = np.asarray(tension, dtype=float)
    p0, p1, q = (np.asarray(v, dtype=float) for v in (start, end, at))
    d = p1 - p0
    length = float(np.hypot(*d))
    u = d / length
    n = np.array([-u[1], u[0]])
    nxt = np.roll(x, -1, axis=0)
    s0, s1 = (x - p0) @ u, (nxt - p0) @ u
    off0, off1 = np.abs((x - p0) @ n), np.abs((nxt - p0) @ n)
    mid = 0.5 * (s0 + s1)
    keep = (off0 < tolerance) & (off1 < tolerance) & (mid > 0) & (mid < length)
    if keep.sum() < 2:
        raise ValueError(f"fewer than 2 elements lie on the strand {list(p0)} -> {list(p1)}")
    b, a = np.polyfit(mid[keep], t[keep], 1)
    return float(a + b * ((q - p0) @ u))


def belt_coordinate(rest_length: np.ndarray) -> np.ndarray:
    """Material coordinate of each element midpoint, m (0 at node 0)."""
    rest = np.asarray(rest_length, dtype=float)
    return np.cumsum(rest) - 0.5 * rest


def arrival_time(time: np.ndarray, signal: np.ndarray, fraction: float = 0.5) -> float:
    """First time (s) at which |signal - signal[0]| reaches ``fraction`` of its peak change,
    linearly interpolated between samples."""
    dev = np.abs(np.asarray(signal, dtype=float) - signal[0])
    level = fraction * dev.max()
    k = int(np.argmax(dev >= level))
    if k == 0:
        return float(time[0])
    t0, t1, d0, d1 = time[k - 1], time[k], dev[k - 1], dev[k]
    return float(t0 + (level - d0) * (t1 - t0) / (d1 - d0))


def hustrulid_tangent_tensions(
    node_position: np.ndarray, tension: np.ndarray, takeup_y: float, top_y: float = 100.0, half_width: float = 5.0
) -> tuple[float, float, float, float]:
    """Case H tensions (N) at the tangent points A, B (lower pulley at ``takeup_y``) and
    C, D (upper pulley at ``top_y``), from straight-line fits along the two strands at
    x = ±``half_width`` (m). Nodal contact puts the strands up to r(1 - cos(θ/2)) off the
    tangent line at coarse meshes (0.17 m at 89 elements), hence the 0.3 m tolerance."""
    w, yl, yt = half_width, takeup_y, top_y
    kw = dict(tolerance=0.3)
    a = strand_tension(node_position, tension, (w, yl), (w, yt), (w, yl), **kw)
    b = strand_tension(node_position, tension, (-w, yt), (-w, yl), (-w, yl), **kw)
    c = strand_tension(node_position, tension, (w, yl), (w, yt), (w, yt), **kw)
    d = strand_tension(node_position, tension, (-w, yt), (-w, yl), (-w, yt), **kw)
    return a, b, c, d

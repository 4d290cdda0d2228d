"""Post-processing helpers shared by the demo, the tests and the benchmarks."""

from __future__ import annotations

from typing import Sequence

import numpy as np

__all__ = [
    "arrival_time",
    "belt_coordinate",
    "hustrulid_tangent_tensions",
    "hustrulid_wave_speed",
    "low_pass",
    "oscillation",
    "probe_run",
    "strand_tension",
    "tension_at",
]


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


def tension_at(node_position: np.ndarray, tension: np.ndarray, point: Sequence[float]) -> np.ndarray:
    """Tension (N) of the element passing nearest a fixed point (m): a tension sensor at
    ``point`` that the belt runs past. Accepts one instant (positions ``[E, 2]``, tensions
    ``[E]``, returns a 0-d array) or a recording (``[S, E, 2]`` and ``[S, E]``, returns
    ``[S]``). The element's distance is measured from its midpoint."""
    x = np.asarray(node_position, dtype=float)
    t = np.asarray(tension, dtype=float)
    mid = 0.5 * (x + np.roll(x, -1, axis=-2))
    d2 = ((mid - np.asarray(point, dtype=float)) ** 2).sum(axis=-1)
    nearest = np.argmin(d2, axis=-1)
    return np.take_along_axis(t, np.expand_dims(nearest, -1), axis=-1)[..., 0]


def low_pass(signal: np.ndarray, interval: float, cutoff: float) -> np.ndarray:
    """Zero-phase low-pass filter of a uniformly sampled signal: Fourier components above
    ``cutoff`` (Hz) are removed; ``interval`` is the sample spacing, s. The signal is
    mirrored at both ends before the transform so that its ends do not ring.

    A measurement band chosen on purpose (e.g. a load cell's 2 Hz), or, with nodal pulley
    contact (``belt.pulley_contact = "nodes"``, the engine's default), a way to read start-up
    tensions without its chordal ripple: a belt of straight elements running onto a pulley
    moves at a speed that varies by 1 − cos(θ/2) (θ the element's angle on the pulley) at
    the node-passing frequency v/l, a discretisation artefact that fades as the elements
    shrink and that wrap contact (``"wrap"``) removes (docs/wrap-contact.md). For recorded
    channels, :meth:`beltrs.Result.lowpass` names its cut-off."""
    x = np.asarray(signal, dtype=float)
    if not (interval > 0 and cutoff > 0):
        raise ValueError(f"low_pass: interval = {interval!r} and cutoff = {cutoff!r}: both must be > 0")
    padded = np.concatenate([x[::-1], x, x[::-1]])
    spectrum = np.fft.rfft(padded)
    spectrum[np.fft.rfftfreq(len(padded), interval) > cutoff] = 0.0
    return np.fft.irfft(spectrum, len(padded))[len(x):2 * len(x)]


def probe_run(sim, points: Sequence[Sequence[float]], duration: float, interval: float) -> dict[str, np.ndarray]:
    """Run ``sim`` for ``duration`` s, reading the belt tension at fixed ``points`` (m)
    every ``interval`` s (rounded to whole steps) without recording whole-belt arrays:
    memory stays O(samples x points) however long the belt.

    Returns a dict of arrays: ``time`` [S] (s), ``tension`` [S, P] (N, see
    :func:`tension_at`), ``pulley_speed`` [S, pulleys] (rad/s) and ``takeup_travel``
    [S, pulleys] (m), sampled at the start and after each interval.
    """
    every = max(1, int(round(interval / sim.dt)))
    total = int(round(duration / sim.dt))
    times, tensions, speeds, travel = [], [], [], []

    def sample() -> None:
        state = sim.state()
        tension = sim.tensions()
        times.append(state["time"])
        tensions.append([float(tension_at(state["node_position"], tension, p)) for p in points])
        speeds.append(np.array(state["pulley_speed"]))
        travel.append(np.array(state["takeup_travel"]))

    sample()
    done = 0
    while done < total:
        n = min(every, total - done)
        sim.step(n)
        done += n
        sample()
    return {
        "time": np.array(times),
        "tension": np.array(tensions),
        "pulley_speed": np.array(speeds),
        "takeup_travel": np.array(travel),
    }


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


def hustrulid_wave_speed(
    time: np.ndarray,
    tension: np.ndarray,
    node_position: np.ndarray,
    rest_length: float,
    side: int = 1,
    gap: int = 10,
) -> float:
    """Case H axial wave speed, m/s of belt material, from a recorded pulse.

    On the strand at x = ``side`` × 5 m (``side`` = ±1), the elements whose midpoints lie
    between y = 10 m and 90 m are taken in belt order; the arrival (half the peak change,
    :func:`arrival_time`) is read at the third of them and at the one ``gap`` elements on
    (10 elements = 26 m at 89 elements, as the thesis's nodes 60 and 70). Speed = material
    distance ``gap`` × ``rest_length`` (m) over the arrival-time difference.

    Args:
        time: ``[n]`` recorded times, s.
        tension: ``[n, E]`` recorded tensions, N.
        node_position: ``[E, 2]`` node positions, m, at any recorded instant before the
            pulse has moved the belt much (the first is fine).
        rest_length: unstretched element length, m.
        side: strand at x = ``side`` x 5 m, +1 or -1. Default 1.
        gap: elements between the two read-outs. Default 10.
    """
    x = np.asarray(node_position, dtype=float)
    mid = 0.5 * (x + np.roll(x, -1, axis=0))
    strand = np.where((side * mid[:, 0] > 4) & (mid[:, 1] > 10) & (mid[:, 1] < 90))[0]
    if len(strand) < gap + 3:
        raise ValueError(f"only {len(strand)} elements on the strand at side {side}; need {gap + 3}")
    a, b = strand[2], strand[2 + gap]
    ta = arrival_time(time, tension[:, a])
    tb = arrival_time(time, tension[:, b])
    return float(abs(b - a) * rest_length / abs(tb - ta))


def oscillation(time: np.ndarray, signal: np.ndarray) -> tuple[float, float, float]:
    """Centre, amplitude and frequency of a steady oscillation (e.g. a step response).

    Centre = midpoint of the extremes, amplitude = half the peak-to-peak (units of
    ``signal``), frequency (Hz) from the upward crossings of the centre: (crossings − 1) /
    (last − first). Needs at least two upward crossings.
    """
    t = np.asarray(time, dtype=float)
    y0 = np.asarray(signal, dtype=float)
    centre = 0.5 * (y0.max() + y0.min())
    y = y0 - centre
    crossings = t[1:][(y[:-1] < 0) & (y[1:] >= 0)]
    if len(crossings) < 2:
        raise ValueError(f"{len(crossings)} upward crossings: run longer to measure a frequency")
    frequency = (len(crossings) - 1) / (crossings[-1] - crossings[0])
    return float(centre), float(0.5 * np.ptp(y0)), float(frequency)

"""Conveyor layout helpers: a profile of straights joined by circular curves, and idlers
placed along it. SI units (m, rad).

A profile is a polyline of vertices with an optional curve radius at each interior vertex
(the way a conveyor's vertical alignment is drawn): the straights are joined by circular
arcs tangent to both, like a fillet. :func:`idlers_along` puts idler rolls under (or over)
such a profile at a fixed pitch, e.g. carry idlers over a concave curve between two inclined
straights, where a fast start can lift the belt off.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional, Sequence

import numpy as np

from . import _beltrs
from .scene import Idler

__all__ = [
    "Profile",
    "RIGID_BODY_ANGLE",
    "belt_element_length",
    "check_rigid_body_length",
    "element_length_off_pitches",
    "idlers_along",
]


@dataclass(frozen=True)
class _Piece:
    """A straight (radius 0) or an arc of a profile, by arc length."""

    start: np.ndarray  # point, m
    direction: np.ndarray  # unit tangent at the start
    length: float  # m
    curvature: float  # 1/m, positive turning left (counter-clockwise)


def _error(field: str, value: Any, rule: str) -> _beltrs.SceneError:
    return _beltrs.SceneError(f"{field} = {value!r}: {rule}")


class Profile:
    """Straights through ``vertices`` joined by circular curves.

    Args:
        vertices: points (x, y), m, at least two; consecutive points distinct.
        curve_radii: radius of the curve at each interior vertex, m (0 = a sharp corner).
            Default all 0. A curve must fit: its tangent length R·tan(φ/2), φ the turn at
            the vertex, may not overrun the neighbouring straights (shared with the next
            curve).

    Raises:
        beltrs.SceneError: naming the offending vertex or radius and the rule.
    """

    def __init__(self, vertices: Sequence[Sequence[float]], curve_radii: Optional[Sequence[float]] = None):
        v = np.asarray(vertices, dtype=float)
        if v.ndim != 2 or v.shape[1] != 2 or len(v) < 2:
            raise _error("vertices", vertices, "need at least two (x, y) points")
        if not np.all(np.isfinite(v)):
            raise _error("vertices", vertices, "must be finite")
        n = len(v)
        radii = np.zeros(n - 2) if curve_radii is None else np.asarray(curve_radii, dtype=float)
        if radii.shape != (n - 2,):
            raise _error("curve_radii", curve_radii, f"need one radius per interior vertex ({n - 2})")
        for i, r in enumerate(radii):
            if not (math.isfinite(r) and r >= 0):
                raise _error(f"curve_radii[{i}]", float(r), "must be finite and >= 0 (m)")
        seg = np.diff(v, axis=0)
        lengths = np.hypot(seg[:, 0], seg[:, 1])
        for i, length in enumerate(lengths):
            if not length > 0:
                raise _error(f"vertices[{i + 1}]", tuple(v[i + 1]), "repeats the previous vertex")
        dirs = seg / lengths[:, None]
        # Tangent length of the curve at each interior vertex.
        tangent = np.zeros(n)
        turn = np.zeros(n)
        for i in range(1, n - 1):
            a, b = dirs[i - 1], dirs[i]
            phi = math.atan2(a[0] * b[1] - a[1] * b[0], float(a @ b))
            turn[i] = phi
            tangent[i] = radii[i - 1] * math.tan(abs(phi) / 2)
        for i in range(n - 1):
            if tangent[i] + tangent[i + 1] > lengths[i] * (1 + 1e-12):
                k = i if i + 1 <= n - 2 else i - 1  # the curve at vertex i + 1, else at i
                raise _error(
                    f"curve_radii[{k}]",
                    float(radii[k]),
                    f"the curves at vertices {i} and {i + 1} need {tangent[i] + tangent[i + 1]:.6g} m "
                    f"of the {lengths[i]:.6g} m straight between them",
                )
        pieces: list[_Piece] = []
        for i in range(n - 1):
            start = v[i] + dirs[i] * tangent[i]
            straight = lengths[i] - tangent[i] - tangent[i + 1]
            if straight > 0:
                pieces.append(_Piece(start, dirs[i], float(straight), 0.0))
            j = i + 1
            if j < n - 1 and tangent[j] > 0:
                r = radii[j - 1]
                pieces.append(
                    _Piece(v[j] - dirs[i] * tangent[j], dirs[i], float(r * abs(turn[j])), math.copysign(1 / r, turn[j]))
                )
        self.vertices = v
        self.curve_radii = radii
        self._pieces = pieces
        self.length = float(sum(p.length for p in pieces))
        """Arc length of the profile, m."""

    def point(self, s: float) -> tuple[np.ndarray, np.ndarray]:
        """Point and unit tangent at arc length ``s`` (m, clipped to [0, length])."""
        s = min(max(float(s), 0.0), self.length)
        for p in self._pieces:
            if s <= p.length or p is self._pieces[-1]:
                return _along(p, min(s, p.length))
            s -= p.length
        raise AssertionError("unreachable")

    def curvature(self, s: float) -> float:
        """Signed curvature at arc length ``s``, 1/m (positive: turning counter-clockwise)."""
        s = min(max(float(s), 0.0), self.length)
        for p in self._pieces:
            if s <= p.length:
                return p.curvature
            s -= p.length
        return self._pieces[-1].curvature


def _along(p: _Piece, s: float) -> tuple[np.ndarray, np.ndarray]:
    if p.curvature == 0.0:
        return p.start + p.direction * s, p.direction
    k = p.curvature
    left = np.array([-p.direction[1], p.direction[0]])
    theta = k * s
    centre = p.start + left / k
    rel = p.start - centre
    c, sn = math.cos(theta), math.sin(theta)
    point = centre + np.array([c * rel[0] - sn * rel[1], sn * rel[0] + c * rel[1]])
    d = np.array([c * p.direction[0] - sn * p.direction[1], sn * p.direction[0] + c * p.direction[1]])
    return point, d


def element_length_off_pitches(target: float, pitches: Sequence[float]) -> float:
    """The longest element length, m, not longer than ``target``, at which no idler pitch in
    ``pitches`` (m) is within an eighth of an element of a whole number of elements.

    Why (docs/wrap-contact.md, "Session 11: the element length off the pitches"): the node
    belt carries its weight at its nodes, and every roll's kink drives a force at v/l each
    time a node passes it (gravity cogging). Roll k of a row lies at k·p along the belt, so
    its force has the phase 2π·k·p/l; the N rolls of a row sum to
    |sin(N·π·φ)/sin(π·φ)| rolls' worth, φ the distance of p/l from the nearest whole number.
    With p a whole number of elements (φ = 0) every roll pushes in phase: N rolls' worth
    (case G's 0.2 m elements on its 1.2 m and 3 m pitches: a 9.96 Hz line in the drive
    torque, 0.05 of its mean). At φ ≥ 1/8 the sum is at most 1/sin(π/8) = 2.6 rolls' worth,
    whatever N; the length is searched upwards in p/l from ``target`` in steps of 1/1000 of
    an element of the first pitch.

    Args:
        target: the longest element length wanted, m, > 0.
        pitches: the idler pitches, m, each > 0 (e.g. carry and return).

    Returns:
        the element length, m (``target`` itself when it is already a quarter or more off
        every pitch).

    Raises:
        beltrs.SceneError: a bad target or pitch, named with its value.
    """
    if not (math.isfinite(target) and target > 0):
        raise _error("element_length", target, "must be a finite number > 0 (m)")
    for p in pitches:
        if not (math.isfinite(p) and p > 0):
            raise _error("pitch", p, "must be a finite number > 0 (m)")
    if not pitches:
        return float(target)

    def off(length: float) -> bool:
        return all(abs(p / length - round(p / length)) >= 0.125 - 1e-9 for p in pitches)

    first = pitches[0]
    x0 = first / target
    for step in range(4001):  # p/l from x0 to x0 + 4 elements
        length = target if step == 0 else first / (x0 + step / 1000)
        if off(length):
            return float(length)
    return float(target)  # pitches whose ratios allow none (not found for real rows): the target


#: The rigid-body belt's largest body angle on a drum, rad (0.3 rad, 17.2°): the builders
#: give its bodies at most ``RIGID_BODY_ANGLE`` × the smallest drum radius
#: (:func:`belt_element_length`). Measured on case G (60 m start of
#: tests/test_case_g_formulations.py, 0.4 m drums): the raw peak over the peak below 2 Hz is
#: +4.71 % at 0.196 m bodies (0.49 rad), +1.46 % at 0.1185 m (0.296 rad), +1.1 … +1.5 % at
#: 0.095 … 0.12 m; docs/kubas.md, "The bodies' length on the drums".
RIGID_BODY_ANGLE = 0.3


def belt_element_length(target: float, pitches: Sequence[float], *, formulation: str,
                        drum_radius: float) -> float:
    """The builders' element length, m: the longest not over ``target`` (the node belt's
    choice: each builder's own, documented there), shortened for the rigid-body belt to
    ``RIGID_BODY_ANGLE`` × ``drum_radius``, then taken off the idler ``pitches``
    (:func:`element_length_off_pitches`).

    Why the rigid belt's bodies are shorter (docs/kubas.md, "The bodies' length on the
    drums"): a chain of rigid bodies wraps a drum as a polygon of body angle a = l/R, and
    draws its strands at a speed that varies with a at the rate v/l (a chain on a sprocket;
    the wrap joints take most of that out, not all): the raw tension's chordal ripple
    falls as about a². On case G (0.4 m drums, 60 m start of
    tests/test_case_g_formulations.py) the raw peak tight-side tension is +4.71 % over its
    peak below 2 Hz at 0.196 m bodies (a = 0.49 rad), +3.51 % at 0.148 m, +2.49 % at
    0.130 m, **+1.46 % at 0.1185 m** (a = 0.296, this rule's choice), +1.11 … +1.54 % at
    the lengths from 0.095 to 0.115 m: issue 12's 3 % with margin from a ≈ 0.3 down (on
    case G at 150 m, Harrison 10 s: +4.32 % at 0.1185 m, a mid-ramp burst not traced,
    +1.6 … +2.4 % at 0.108–0.124 m; +6.17 % at 0.196 m). Cost:
    the bodies and the stable step both scale with l, so a run costs about (0.196 / l)²:
    measured 2.7× the 0.196 m bodies' (element-steps) on case G. The node belt (wrap
    contact on its drums, no chordal ripple) keeps ``target``.

    Args:
        target: the longest element length wanted, m, > 0.
        pitches: the idler pitches, m, each > 0 (e.g. carry and return).
        formulation: :attr:`beltrs.Belt.formulation` (``"node_kelvin_voigt"`` or
            ``"rigid_body"``).
        drum_radius: the smallest drum radius the belt wraps, m, > 0.

    Returns:
        the element length, m.

    Raises:
        beltrs.SceneError: a bad target, pitch or radius, named with its value.
    """
    if formulation == "rigid_body":
        if not (math.isfinite(drum_radius) and drum_radius > 0):
            raise _error("drum_radius", drum_radius, "must be a finite number > 0 (m)")
        target = min(target, RIGID_BODY_ANGLE * drum_radius)
    return element_length_off_pitches(target, pitches)


def check_rigid_body_length(length: float, drum_radius: float, *, field: str = "element_length",
                            leave: str = "element_length") -> None:
    """Warn (:class:`beltrs.AccuracyWarning`) when a rigid-body belt's explicit body length
    ``length`` (m, given as ``field``) is longer than :func:`belt_element_length`'s rule
    allows on drums of radius ``drum_radius`` (m, the smallest): its raw tension peaks then
    carry the bodies' chordal excess (case G: +4.71 % over the peak below 2 Hz at 0.196 m
    bodies on 0.4 m drums, against +1.46 % at the rule's 0.1185 m). The length is used as
    given. ``leave``: the setting to leave at None for the rule's length, named in the
    message."""
    limit = RIGID_BODY_ANGLE * drum_radius
    if not length > limit * (1 + 1e-9):
        return
    from .diagnostics import AccuracyWarning, _warn

    _warn(
        AccuracyWarning,
        f"{field} = {length!r}: rigid-body belt's bodies of {length:.4g} m are longer than the rule "
        f"l <= {RIGID_BODY_ANGLE:g} x the smallest drum radius ({RIGID_BODY_ANGLE:g} x {drum_radius:g} m = "
        f"{limit:.4g} m; body angle {length / drum_radius:.3f} rad on the drum). Their chordal action on the "
        f"drums raises raw tension peaks about as (l/R)^2: case G's raw peak tight-side tension is +4.71 % "
        f"over its peak below 2 Hz at 0.196 m bodies on 0.4 m drums, +1.46 % at the rule's 0.1185 m "
        f"(issue 12's target 3 %). The length is used as given; read peaks through beltrs.analysis.low_pass, "
        f"or leave {leave} at None for the rule's length (docs/kubas.md, \"The bodies' length on the drums\").",
    )


def idlers_along(
    profile: Profile,
    pitch: float,
    *,
    side: str = "right",
    offset: float = 0.0,
    start: Optional[float] = None,
    end: Optional[float] = None,
    **idler: Any,
) -> list[Idler]:
    """Idler rolls along ``profile`` every ``pitch`` metres of arc length.

    The belt centre line is meant to run along the profile shifted by ``offset`` to its
    left (m; negative shifts right, e.g. the return strand one pulley diameter below the
    carry strand's profile). Each roll touches that line from ``side``: ``"right"`` of the
    direction of travel along the vertices (under a strand running left to right) or
    ``"left"``; its centre is one roll radius off the line.

    Args:
        profile: the profile.
        pitch: idler pitch along the profile, m, > 0.
        side: ``"right"`` (default) or ``"left"``.
        offset: shift of the belt line to the left of the profile, m. Default 0.
        start: arc length of the first idler, m. Default pitch/2.
        end: no idler beyond this arc length, m. Default the profile length − pitch/2.
        **idler: further :class:`beltrs.Idler` fields (``radius`` m, default 0.0635;
            ``contact_stiffness``, ``contact_damping``, ``inertia``, ``friction``).

    Returns:
        list of :class:`beltrs.Idler`.

    Raises:
        beltrs.SceneError: a bad pitch, side or range, named with its value.
    """
    if not (math.isfinite(pitch) and pitch > 0):
        raise _error("pitch", pitch, "must be a finite number > 0 (m)")
    if side not in ("right", "left"):
        raise _error("side", side, 'must be "right" or "left"')
    if not math.isfinite(offset):
        raise _error("offset", offset, "must be finite (m)")
    s0 = 0.5 * pitch if start is None else float(start)
    s1 = profile.length - 0.5 * pitch if end is None else float(end)
    if not (0 <= s0 <= profile.length) or not (s0 <= s1 <= profile.length):
        raise _error("start, end", (s0, s1), f"must satisfy 0 <= start <= end <= {profile.length:.6g} (m)")
    roll = float(idler.get("radius", Idler().radius))
    sign = -1.0 if side == "right" else 1.0
    out = []
    count = int(math.floor((s1 - s0) / pitch + 1e-9)) + 1
    for k in range(count):
        p, d = profile.point(s0 + k * pitch)
        left = np.array([-d[1], d[0]])
        c = p + left * (offset + sign * roll)
        out.append(Idler(center=(round(float(c[0]), 9), round(float(c[1]), 9)), **idler))
    return out

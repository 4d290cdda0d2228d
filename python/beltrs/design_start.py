"""Start a run from the static design state (``docs/design-start.md``).

A conveyor's dynamic run should begin where its design calculation leaves it: the belt
stretched to the static tensions (DIN 22101 / ISO 5048 or CEMA, :mod:`beltrs.statics`),
the takeup in place, at rest or at running speed, not from an unstretched belt relaxed for
tens of seconds. The engine does this from a scene's ``initial`` table
(:class:`beltrs.Initial`): the tension along its path, the belt speed and, if the belt
does not simply run round the pulleys' tangents (vertical curves), the path itself. This
module turns a :class:`beltrs.statics.TensionProfile` into that table:

* :class:`Run` maps a stretch of the static loop (distances from its takeup, in the
  direction of travel) onto a stretch of the engine's path (arc length from node 0, in
  node order, either way round);
* :class:`Wrap` puts a pulley of the loop (a point, zero length in the statics) onto its
  wrap on the path; a drive's drop from T1 to T2 is spread over the wrap as the capstan
  law spreads it, T = T2·(T1/T2)^(θ/θ_wrap) (every node then needs the same friction
  ratio, ln(T1/T2)/θ_wrap ≤ µ: held by any design that meets Euler's grip rule);
* :func:`initial` builds the :class:`beltrs.Initial`.

The builder does all of this itself (:meth:`beltrs.conveyor.Conveyor.scene`, ``start=``);
so does case G (:func:`beltrs.scenes.guo_wang_conveyor`, ``start=``).

SI units: m, N, m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence, Union

import numpy as np

from . import statics
from ._beltrs import SceneError
from .scene import Initial

__all__ = ["FORCE_TAKEUPS", "START_KINDS", "TAKEUP_KINDS", "Run", "Wrap", "at_rest", "initial", "path_length",
           "running_tension", "tension_table"]

#: The design states a builder can start from: ``"rest"`` (standstill tensions: the
#: takeup and the lifts, no running resistance, belt at rest) and ``"running"`` (the
#: steady-running tensions, belt and pulleys at running speed).
START_KINDS = ("rest", "running")

#: Points of the table per wrap (the capstan curve across a drive drum), dimensionless.
WRAP_POINTS = 16


@dataclass(frozen=True)
class Run:
    """A stretch of the static loop laid on a stretch of the engine's path.

    Attributes:
        start, end: distances along the static loop (from its takeup, in the direction of
            travel, :attr:`beltrs.statics.TensionProfile.distance`), m, ``start < end``.
        path_start, path_end: arc lengths on the engine's path where ``start`` and ``end``
            lie, m (from node 0 in node order; ``path_end < path_start`` when the belt
            travels against node order). Distances in between map linearly.
    """

    start: float
    end: float
    path_start: float
    path_end: float


@dataclass(frozen=True)
class Wrap:
    """A point of the static loop (a pulley) laid on its wrap on the engine's path.

    Attributes:
        name: the point's name in the loop (its places are ``"<name>: in"`` and
            ``"<name>: out"``).
        path_in, path_out: arc lengths on the engine's path where the belt arrives on the
            pulley and leaves it, in the direction of travel, m.
    """

    name: str
    path_in: float
    path_out: float


def _check_piece(i: int, piece: Union[Run, Wrap], length: float) -> None:
    if isinstance(piece, Run):
        values = (("start", piece.start), ("end", piece.end), ("path_start", piece.path_start),
                  ("path_end", piece.path_end))
    elif isinstance(piece, Wrap):
        values = (("path_in", piece.path_in), ("path_out", piece.path_out))
    else:
        raise SceneError(f"pieces[{i}] = {piece!r}: expected a beltrs.design_start.Run or Wrap")
    for name, v in values:
        statics.check(f"pieces[{i}].{name}", v, low=-math.inf, unit="m")
    if isinstance(piece, Run) and not piece.end > piece.start:
        raise SceneError(f"pieces[{i}].end = {piece.end!r}: must exceed start = {piece.start!r} (m along the loop)")


def tension_table(profile: statics.TensionProfile, pieces: Sequence[Union[Run, Wrap]],
                  path_length: float) -> tuple[list[float], list[float]]:
    """The design tension along the engine's path, as ``(distance, tension)`` lists for
    :class:`beltrs.Initial` (distances sorted, in [0, ``path_length``)).

    Each :class:`Run` contributes the loop's tension at its ends and at every place of the
    loop inside it; each :class:`Wrap` the capstan curve from the pulley's "in" to its "out"
    tension. Between pieces the engine interpolates linearly (e.g. the short free spans
    between a drum and the first idler).

    Args:
        profile: the static tensions (:func:`beltrs.statics.tensions`,
            :meth:`beltrs.conveyor.Conveyor.statics`).
        pieces: :class:`Run` and :class:`Wrap` items, any order.
        path_length: length of the engine's path, m (``Simulation.path_length`` for the
            pulleys' path; the given path's length with ``Initial.path``).

    Raises:
        beltrs.SceneError: a bad piece, a wrap with no such point, a tension below 0.
    """
    if not isinstance(profile, statics.TensionProfile):
        raise SceneError(f"profile = {profile!r}: expected a beltrs.statics.TensionProfile")
    length = statics.check("path_length", path_length, positive=True, unit="m")
    if isinstance(pieces, (str, bytes)) or not hasattr(pieces, "__len__") or not len(pieces):
        raise SceneError(f"pieces = {pieces!r}: give a list of Run and Wrap items")
    s_out: list[float] = []
    t_out: list[float] = []
    for i, piece in enumerate(pieces):
        _check_piece(i, piece, length)
        if isinstance(piece, Run):
            d = profile.distance
            inside = sorted({float(x) for x in d if piece.start < x < piece.end})
            ds = [piece.start, *inside, piece.end]
            for j, x in enumerate(ds):
                w = (x - piece.start) / (piece.end - piece.start)
                s = piece.path_start + w * (piece.path_end - piece.path_start)
                # at a point inside the run (a loading point) the tension jumps: take the
                # value arriving just before it and leaving just after it
                arriving = float(profile.along(x - 1e-9)) if j > 0 else float(profile.along(x))
                leaving = float(profile.along(x))
                if 0 < j < len(ds) - 1 and abs(arriving - leaving) > 1e-9 * max(1.0, abs(leaving)):
                    step = 1e-3 * math.copysign(1.0, piece.path_end - piece.path_start)
                    s_out += [s - step, s + step]
                    t_out += [arriving, leaving]
                else:
                    s_out.append(s)
                    t_out.append(leaving if j < len(ds) - 1 else float(profile.along(x - 1e-9)))
        else:
            t_in = profile.at(f"{piece.name}: in")
            t_leave = profile.at(f"{piece.name}: out")
            for k in range(WRAP_POINTS + 1):
                w = k / WRAP_POINTS
                s_out.append(piece.path_in + w * (piece.path_out - piece.path_in))
                if t_in > 0 and t_leave > 0:
                    t_out.append(t_in * (t_leave / t_in) ** w)
                else:
                    t_out.append(t_in + w * (t_leave - t_in))
    s = np.mod(np.asarray(s_out, dtype=float), length)
    s[s > length * (1 - 1e-12)] = 0.0  # the end of the loop is its start
    t = np.asarray(t_out, dtype=float)
    order = np.argsort(s, kind="stable")
    s, t = s[order], t[order]
    keep = np.concatenate([[True], np.diff(s) > 1e-9 * length])  # duplicates: the first wins
    s, t = s[keep], t[keep]
    if np.any(t < 0):
        k = int(np.argmin(t))
        raise SceneError(f"design tension = {t[k]:.6g} N at {s[k]:.6g} m along the path: must be >= 0 (the static "
                         "calculation leaves the belt in compression there; raise the takeup tension)")
    return [float(x) for x in s], [float(x) for x in t]


#: The takeup kinds (:class:`beltrs.conveyor.Takeup` ``kind``): a counterweight, a winch, a
#: screw.
TAKEUP_KINDS = ("gravity", "winch", "fixed")

#: Takeup kinds that set the loop's tension by a force (:class:`beltrs.Takeup` ``kind``):
#: running, their carriage balances 2·(T − m'_G·v²), so the belt's tension is the static
#: one plus m'_G·v² (:func:`running_tension`). A ``"fixed"`` (screw) takeup fixes the belt's
#: length instead: its tension stays the static one.
FORCE_TAKEUPS = ("gravity", "winch")


def running_tension(belt_mass: float, speed: float, takeup: str = "gravity") -> float:
    """What a belt running at ``speed`` carries above its static (DIN 22101 / CEMA) tension
    at every point of the loop, N: m'_G·v² with a takeup that sets the tension by a force
    (``"gravity"``, ``"winch"``), 0 with a ``"fixed"`` one (docs/design-start.md, "Running at
    speed: the belt's m'·v²").

    The belt wrapping a drum at speed v presses on it with (T − m'_G·v²)/R, not T/R (the
    centripetal force of its own mass); so a takeup's carriage, pulled by the force F,
    balances 2·(T − m'_G·v²) = F, and the tension everywhere is the static one (where
    v = 0 gives 2·T = F) plus m'_G·v². A screw takeup fixes the belt's length and so its
    stretch: the tensions stay, the drums' contact unloads by m'_G·v²/R.

    Args:
        belt_mass: the belt's own mass per length m'_G, kg/m (without the material: the
            material leaves the belt at the discharge and never wraps the takeup drum).
        speed: belt speed, m/s (either sign).
        takeup: the takeup's kind, ``"gravity"`` (default), ``"winch"`` or ``"fixed"``.
    """
    m = statics.check("belt_mass", belt_mass, low=0.0, unit="kg/m")
    v = statics.check("speed", speed, low=-math.inf, unit="m/s")
    if takeup not in TAKEUP_KINDS:
        kinds = ", ".join(map(repr, TAKEUP_KINDS[:-1])) + f" or {TAKEUP_KINDS[-1]!r}"
        raise SceneError(f"takeup = {takeup!r}: must be {kinds} (the takeup's kind)")
    return m * v * v if takeup in FORCE_TAKEUPS else 0.0


def initial(profile: statics.TensionProfile, pieces: Sequence[Union[Run, Wrap]], path_length: float, *,
            speed: float = 0.0, path: Sequence[Sequence[float]] = (), sag: bool = False,
            belt_mass: float = 0.0, takeup: str = "gravity") -> Initial:
    """The :class:`beltrs.Initial` design state from static tensions.

    Running (``speed`` ≠ 0) with a takeup that sets the tension by a force, every tension of
    the table is raised by the belt's m'_G·v² (:func:`running_tension`): the static
    calculation leaves it out, the running belt carries it, and without it the takeup
    would move and the loop ring from t = 0.

    Args:
        profile, pieces, path_length: as :func:`tension_table`.
        speed: belt speed along the path in node order, m/s (negative: the belt travels
            against node order). Default 0 (at rest).
        path: corners (x, y, radius) of the path the belt is placed on, m
            (:class:`beltrs.Initial`). Default (): the pulleys' tangent path.
        sag: place the spans resting on idler rolls in their static sag
            (:attr:`beltrs.Initial.sag`). Default False (the builders pass True).
        belt_mass: the belt's own mass per length m'_G, kg/m (``Belt.mass_per_length``,
            without the material), for the m'_G·v² term. Default 0 (no term; the builders
            pass the belt's).
        takeup: the kind of the takeup that sets the loop's tension, ``"gravity"``
            (default), ``"winch"`` (both add m'_G·v²) or ``"fixed"`` (adds nothing).
    """
    statics.check("speed", speed, low=-math.inf, unit="m/s")
    extra = running_tension(belt_mass, speed, takeup)
    distance, tension = tension_table(profile, pieces, path_length)
    return Initial(tension=tuple(t + extra for t in tension), distance=tuple(distance), speed=float(speed),
                   path=tuple(tuple(float(v) for v in c) for c in path), sag=sag)


def at_rest(loop: Sequence[Union[statics.Section, statics.Point]]) -> list[Union[statics.Section, statics.Point]]:
    """The loop at standstill: every local resistance removed (no material accelerated at
    a loading point, nothing turning); with :class:`beltrs.statics.DIN22101` ``f = 0`` the
    tensions are then the takeup's and the lifts' alone, the state a conveyor relaxes to at
    rest with its drive holding."""
    out: list[Union[statics.Section, statics.Point]] = []
    for item in loop:
        if isinstance(item, statics.Point):
            from dataclasses import replace

            item = replace(item, resistance=0.0)
        out.append(item)
    return out


def path_length(corners: Sequence[Sequence[float]]) -> float:
    """Length of the closed path through ``corners`` (x, y, radius), m, as the engine builds
    it for :attr:`beltrs.Initial.path`: the spans between the corners less each corner's
    tangent lengths R·tan(|φ|/2), plus each corner's arc R·|φ| (φ its turn)."""
    pts = np.asarray(corners, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 3 or len(pts) < 2 or not np.all(np.isfinite(pts)):
        raise SceneError(f"corners = {corners!r}: expected at least two finite (x, y, radius) corners, m")
    m = len(pts)
    seg = np.roll(pts[:, :2], -1, axis=0) - pts[:, :2]
    lens = np.hypot(seg[:, 0], seg[:, 1])
    if np.any(lens == 0):
        raise SceneError(f"corners = {corners!r}: two consecutive corners coincide")
    dirs = seg / lens[:, None]
    total = float(lens.sum())
    for k in range(m):
        a, b = dirs[k - 1], dirs[k]
        phi = abs(math.atan2(a[0] * b[1] - a[1] * b[0], float(a @ b)))
        if phi > 1e-12:
            r = float(pts[k, 2])
            total += r * phi - 2 * r * math.tan(phi / 2)
    return total

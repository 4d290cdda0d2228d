"""Warnings for common mistakes (``docs/warnings.md``).

Every warning beltrs issues is a :class:`BeltrsWarning`, so one filter catches them all::

    import warnings, beltrs
    warnings.simplefilter("error", beltrs.BeltrsWarning)           # every one becomes an error
    warnings.simplefilter("ignore", beltrs.NotRelaxedWarning)      # or silence one kind

Categories (each a subclass of :class:`BeltrsWarning`, itself a ``UserWarning``):

- :class:`NotRelaxedWarning`: ``run`` starts from the initial placement of a scene that is
  far from static equilibrium, without :meth:`~beltrs.Simulation.stabilise`.
- :class:`DriveDirectionWarning`: a starting curve runs the belt against its path direction
  (the direction its loads carry material, loading point to discharge point).
- :class:`IdlerContactWarning`: an idler is so far from the belt that it never touches it.
- :class:`AccuracyWarning`: the scene relies on a default setting that is known to be
  inaccurate for a scene of its kind, a builder is given rigid bodies longer than its
  rule (0.3 × the drum radius), or the idler rolls' wrap contact runs above the speeds it
  is verified at (:data:`ROLL_WRAP_VERIFIED_SPEED`).

The checks are cheap (one force evaluation, or geometry of the compiled model); none of
them changes a result.
"""

from __future__ import annotations

import math
import os
import sys
import warnings
from typing import TYPE_CHECKING, Iterator, Optional

import numpy as np

from ._checks import BeltrsWarning

if TYPE_CHECKING:  # pragma: no cover
    from .simulation import Simulation

__all__ = [
    "AccuracyWarning",
    "BeltrsWarning",
    "DriveDirectionWarning",
    "IdlerContactWarning",
    "NotRelaxedWarning",
    "IDLER_GAP_LIMIT",
    "RELAXED_RESIDUAL_LIMIT",
    "ROLL_WRAP_VERIFIED_SPEED",
]


class NotRelaxedWarning(BeltrsWarning):
    """A run starts far from static equilibrium without a relaxation first."""


class DriveDirectionWarning(BeltrsWarning):
    """A drive's starting curve runs the belt against its path direction."""


class IdlerContactWarning(BeltrsWarning):
    """An idler is too far from the belt ever to touch it."""


class AccuracyWarning(BeltrsWarning):
    """A default setting is known to be inaccurate for this scene, (from the builders) a
    rigid-body belt's explicit body length is longer than their rule
    (:func:`beltrs.layout.check_rigid_body_length`), or the rolls' wrap contact runs above
    its verified speed (:func:`check_roll_wrap_speed`)."""


#: Largest out-of-balance nodal force, as a fraction of the largest of (belt tension,
#: node weight), above which a run from the initial placement warns. A relaxed scene sits
#: at ≤ 1e-5 (the relaxation's own tolerance is 1e-7); the initial placement of every
#: built-in scene sits at 0.28–0.78 (unsupported weight and the takeup's unbalanced pull).
#: 1e-2 separates the two by decades on both sides.
RELAXED_RESIDUAL_LIMIT = 1e-2

#: Gap between an idler's surface and the initial belt centre line above which the idler
#: is taken never to touch the belt, m. Conveyor design keeps the belt's sag between idlers
#: to 0.5–3 % of the idler pitch (DIN 22101), a few centimetres at the usual 1–3 m pitches,
#: and the belt sags onto idlers placed just below its initial straight line; 0.1 m is
#: several times that, so an idler this far away is a placement mistake (a sign or a radius
#: in a coordinate), not sag.
IDLER_GAP_LIMIT = 0.1

#: Largest belt speed, m/s, at which the idler rolls' wrap contact (``belt.idler_contact =
#: "wrap"``, the builders' default for the node belt) is verified: no roll unloads as the
#: nodes pass, on the level 50 m builder conveyor at 2, 3, 4, 5, 6 and 8 m/s
#: (tests/test_roll_wrap.py; docs/wrap-contact.md, "Session 14: roll wrap above 8 m/s").
#: Above it the lightest rolls unload at the node-passing rate
#: (``python benches/roll_wrap_speed.py --length 50 --speeds 8,9,10,12,15``): 0.02 % of the
#: (roll, sample) pairs at 9 m/s, 0.25 % at 10, 0.9 % at 12, 2.1 % at 15 (the first roll past
#: the tail drum in up to 44 % of its samples at 12 m/s).
ROLL_WRAP_VERIFIED_SPEED = 8.0

#: Element arc on a pulley (rad) below which raw tension peaks of a running belt are within
#: about 5 % of their low-passed value (case G, docs/accuracy.md: 7 degrees).
RIPPLE_FREE_ANGLE = math.radians(7.0)


_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


def _warn(category: type, message: str) -> None:
    """Issue the warning at the first caller outside the beltrs package (the user's line)."""
    frame, level = sys._getframe(1), 2
    while frame is not None and os.path.dirname(os.path.abspath(frame.f_code.co_filename)) == _PACKAGE_DIR:
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)


def equilibrium_residual(sim: "Simulation") -> float:
    """Largest out-of-balance force on a belt node at the current state, as a fraction of
    the largest of the element tensions and the node weights (dimensionless). One force
    evaluation; the state does not change."""
    forces = np.asarray(sim.forces())
    scale = float(np.abs(sim.tensions()).max(initial=0.0))
    g = float(sim.scene.gravity)
    if g > 0:
        scale = max(scale, float(np.max(sim.node_masses(), initial=0.0)) * g)
    worst = float(np.hypot(forces[:, 0], forces[:, 1]).max(initial=0.0))
    if scale <= 0:
        return 0.0 if worst == 0 else math.inf
    return worst / scale


def check_relaxed(sim: "Simulation") -> None:
    """Warn (:class:`NotRelaxedWarning`) if the simulation is still at its initial
    placement, was never relaxed, and is far from equilibrium."""
    residual = equilibrium_residual(sim)
    if residual > RELAXED_RESIDUAL_LIMIT:
        _warn(
            NotRelaxedWarning,
            f"run() starts from the initial placement, which is far from static equilibrium: the largest "
            f"out-of-balance nodal force is {residual:.2g} of the largest tension or node weight "
            f"(> {RELAXED_RESIDUAL_LIMIT:g}). The run will show the belt falling into place (start-up peaks "
            f"several times too high, compression) rather than your scenario. Call sim.stabilise() first, "
            f"or silence this with warnings.simplefilter('ignore', beltrs.NotRelaxedWarning) if the "
            f"transient from the placement is what you want.",
        )


def _belt_direction(sim: "Simulation") -> Iterator[tuple[int, int]]:
    """For each load: (index, +1 if its material travels in node order, -1 against)."""
    zones = np.asarray(sim.load_zones())
    total = float(np.sum(sim.rest_length))
    for k, (start, end, length) in enumerate(zones):
        forward = (end - start) % total
        backward = (start - end) % total
        if abs(forward - length) <= abs(backward - length):
            yield k, 1
        else:
            yield k, -1


def check_drive_directions(sim: "Simulation") -> None:
    """Warn (:class:`DriveDirectionWarning`) for each speed-controlled drive whose starting
    curve (or DOL motor whose rotation) turns its pulley so that the belt moves against its
    path direction: the
    direction in which the scene's loads carry material from loading to discharge point.
    Scenes without loads have no path direction and are not checked."""
    if not sim.scene.loads:
        return
    directions = dict(_belt_direction(sim))
    if not directions or len(set(directions.values())) != 1:
        return  # no loads compiled (zero mass), or loads disagree: no single path direction
    along = next(iter(directions.values()))
    for j, p in enumerate(sim.scene.pulleys):
        motor = None if p.drive is None else p.drive.motor
        if motor is not None:
            wrap = 1 if p.wrap == "ccw" else -1
            wanted = along * wrap
            if (1 if motor.rotation == "ccw" else -1) != wanted:
                _warn(
                    DriveDirectionWarning,
                    f"pulleys[{j}].drive.motor.rotation = {motor.rotation!r}: runs the belt backwards. The "
                    f"loads carry material {'in' if along > 0 else 'against'} node order, and the belt wraps "
                    f"pulley {p.name!r} {p.wrap}: give rotation {'ccw' if wanted > 0 else 'cw'!r} "
                    "(docs/drives.md).",
                )
            continue
        curve = None if p.drive is None else p.drive.start_curve
        if curve is None or not curve.speed:
            continue
        wrap = 1 if p.wrap == "ccw" else -1
        wanted = along * wrap  # pulley turning sign that moves the belt along its path
        if np.sign(curve.speed) != wanted:
            sense = "counter-clockwise (+)" if wanted > 0 else "clockwise (-)"
            _warn(
                DriveDirectionWarning,
                f"pulleys[{j}].drive.start_curve.speed = {curve.speed!r}: runs the belt backwards. The loads "
                f"carry material {'in' if along > 0 else 'against'} node order (loading point to discharge "
                f"point), and the belt wraps pulley {p.name!r} {p.wrap}, so the belt moves that way when the "
                f"pulley turns {sense}: give speed the sign {'+' if wanted > 0 else '-'} (speeds are "
                f"counter-clockwise positive, docs/drives.md).",
            )


def _distance_to_path(points: np.ndarray, path: np.ndarray) -> np.ndarray:
    """Distance from each point to the closed polyline ``path``, m."""
    a = path
    b = np.roll(path, -1, axis=0)
    ab = b - a
    len2 = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    out = np.empty(len(points))
    for k, p in enumerate(points):
        with np.errstate(over="ignore"):  # a very short element far from p: t clips to 0 or 1
            t = np.clip(np.einsum("ij,ij->i", p - a, ab) / len2, 0.0, 1.0)
        nearest = a + t[:, None] * ab
        out[k] = float(np.min(np.hypot(*(p - nearest).T)))
    return out


def check_idlers(sim: "Simulation") -> None:
    """Warn (:class:`IdlerContactWarning`) once, naming every idler whose surface is more
    than :data:`IDLER_GAP_LIMIT` from the belt centre line now. Run on the state a run
    starts from: after :meth:`~beltrs.Simulation.stabilise` (static equilibrium, where the
    belt has sagged onto idlers placed along a curved profile below its initial straight
    line), or at a run from the initial placement."""
    idlers = sim.scene.idlers
    if not idlers:
        return
    centres = np.array([d.center for d in idlers], dtype=float)
    radii = np.array([d.radius for d in idlers], dtype=float)
    state = sim.state()
    path = np.asarray(state["node_position"])
    # The distance to the element each idler tracks (and its neighbours) bounds the distance
    # to the belt from above: only idlers beyond the limit by that measure need the exact
    # distance to the whole polygon.
    n = len(path)
    tracked = np.asarray(state["idler_element"], dtype=np.int64) % n
    a = np.concatenate([path[(tracked + d) % n] for d in (-1, 0, 1)])
    b = np.concatenate([path[(tracked + d + 1) % n] for d in (-1, 0, 1)])
    p = np.tile(centres, (3, 1))
    ab = b - a
    with np.errstate(over="ignore"):  # a very short element far from p: t clips to 0 or 1
        t = np.clip(np.einsum("ij,ij->i", p - a, ab) / np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300), 0.0, 1.0)
    near = np.hypot(*(p - (a + t[:, None] * ab)).T).reshape(3, -1).min(axis=0)
    gap = near - radii
    candidates = np.flatnonzero(gap > IDLER_GAP_LIMIT)
    if candidates.size:
        gap[candidates] = _distance_to_path(centres[candidates], path) - radii[candidates]
    far = np.flatnonzero(gap > IDLER_GAP_LIMIT)
    key = tuple(far.tolist())
    if key == getattr(sim, "_idlers_warned", None):
        return
    sim._idlers_warned = key  # type: ignore[attr-defined]
    if far.size == 0:
        return
    shown = ", ".join(f"idlers[{k}] at {tuple(float(c) for c in centres[k])} ({gap[k]:.3g} m)" for k in far[:5])
    more = f" and {far.size - 5} more" if far.size > 5 else ""
    _warn(
        IdlerContactWarning,
        f"{far.size} idler(s) will never touch the belt: {shown}{more} away from the belt centre line, more "
        f"than {IDLER_GAP_LIMIT} m (the belt's sag between idlers is a few cm). Check the idler centres "
        f"(an idler touches the belt when its centre is one radius from the belt centre line).",
    )


def check_defaults(sim: "Simulation") -> None:
    """Warn (:class:`AccuracyWarning`) for default settings known to be inaccurate for
    this scene: the default mesh (30 degrees of arc per element on the smallest pulley)
    under a belt that a speed-controlled drive runs over its pulleys (not an open belt with
    an anchored end: it cannot run over them). Each element passing
    onto a pulley kinks the tension (the chordal ripple at the node-passing frequency):
    case G's raw peak start-up tension is 20 % above its low-passed value at 30 degrees
    and within 5 % only at about 7 degrees (docs/accuracy.md)."""
    from .scene import Belt

    belt = sim.scene.belt
    if belt.elements is not None or belt.max_element_angle != Belt.max_element_angle:
        return
    if belt.start is not None and "anchor" in (belt.start.hold, getattr(belt.end, "hold", None)):
        return  # an anchored open belt cannot run over its pulleys: no node passing
    if belt.pulley_contact == "wrap":  # no chord polygon on the pulleys: no chordal ripple
        return
    drives = [
        j for j, p in enumerate(sim.scene.pulleys)
        if p.drive is not None and p.drive.start_curve is not None and p.drive.start_curve.speed
    ]
    if not drives:
        return
    j = drives[0]
    _warn(
        AccuracyWarning,
        f"belt.elements = None: the default mesh puts up to {math.degrees(belt.max_element_angle):.0f} degrees "
        f"of arc on an element, and pulleys[{j}].drive.start_curve runs the belt over its pulleys. Raw tension "
        f"peaks then carry a chordal ripple at the node-passing frequency (case G: 20 % above the low-passed "
        f"peak at 30 degrees, docs/accuracy.md). Read peaks through beltrs.analysis.low_pass, or set "
        f"belt.max_element_angle = {RIPPLE_FREE_ANGLE:.3f} (7 degrees: raw peaks within about 5 %) or "
        f"belt.elements explicitly, or use belt.pulley_contact = \"wrap\" (raw peaks within 3 %, "
        f"docs/wrap-contact.md).",
    )


def check_roll_wrap_speed(sim: "Simulation", scene_dict: Optional[dict] = None) -> None:
    """Warn (:class:`AccuracyWarning`) when the idler rolls' wrap contact runs above
    :data:`ROLL_WRAP_VERIFIED_SPEED`: the scene's belt speed (the one the contact sizes its
    circles for: the design start's speed, the speed-controlled drives' curve and creep
    speeds, the direct-on-line motors' no-load belt speeds) is above the speeds at which no
    roll unloads as the nodes pass. Warns once per speed (a ``set_scene`` to another speed
    warns again). ``scene_dict``: ``sim.scene.to_dict()`` if the caller has it at hand (it
    costs about a tenth of building a 1 km conveyor's Simulation)."""
    scene = sim.scene
    if scene.belt.idler_contact != "wrap" or not scene.idlers or not scene.gravity > 0:
        return
    from . import _beltrs

    speed = float(_beltrs.roll_wrap_speed(scene.to_dict() if scene_dict is None else scene_dict))
    if not speed > ROLL_WRAP_VERIFIED_SPEED * (1 + 1e-9):
        return
    if getattr(sim, "_roll_wrap_speed_warned", None) == speed:
        return
    sim._roll_wrap_speed_warned = speed  # type: ignore[attr-defined]
    _warn(
        AccuracyWarning,
        f"belt.idler_contact = \"wrap\" at a belt speed of {speed:.3g} m/s: the rolls' wrap contact is verified "
        f"at 2-{ROLL_WRAP_VERIFIED_SPEED:g} m/s only. Above it the lumped belt's nodes unload the lightest rolls "
        f"as they pass (the 50 m builder conveyor: 0.02 % of the roll samples at 9 m/s, 0.25 % at 10, 0.9 % at "
        f"12, 2.1 % at 15; the first roll past the tail drum up to 44 % of its samples at 12 m/s), so the roll "
        f"forces are not to be trusted there; the tensions, the mean drive pull and the drive torque above 2 Hz "
        f"still read as at 8 m/s (docs/wrap-contact.md, \"Session 14: roll wrap above 8 m/s\"). The segment "
        f"contact (belt.idler_contact = \"segment\") is worse at speed.",
    )


def check_scene(sim: "Simulation", scene_dict: Optional[dict] = None) -> None:
    """The checks that need only the compiled scene (run when a Simulation is built;
    ``scene_dict``: the scene's ``to_dict()``, if at hand)."""
    check_drive_directions(sim)
    check_defaults(sim)
    check_roll_wrap_speed(sim, scene_dict)

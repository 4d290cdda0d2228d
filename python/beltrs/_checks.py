"""Warnings for scenes that run but are known to give wrong answers (``docs/belt-drives.md``).

Every warning here is a :class:`BeltrsWarning`, so users can filter all of them at once or
turn them into errors (``warnings.simplefilter("error", beltrs.BeltrsWarning)``).
"""

from __future__ import annotations

import warnings
from typing import Any

__all__ = ["BeltrsWarning", "UndampedContactWarning", "warn_scene"]


class BeltrsWarning(UserWarning):
    """Base class of the warnings beltrs gives about a scene or a run."""


class UndampedContactWarning(BeltrsWarning):
    """Undamped penalty contact together with friction (``docs/belt-drives.md``).

    An undamped contact spring never loses the energy a node brings when it meets the
    pulley: the wrapped belt rings on the contact springs, and friction (which couples the
    normal and the tangential motion) feeds that ringing from the belt's motion over the
    pulley (mode-coupling flutter). The belt then bounces off the pulley: on a small
    two-pulley drive only about one node in 25 of the wrap touches at a time and the driven
    pulley turns at under half the creep-theory speed, while the span tensions still look
    plausible. Any contact damping from 1 % of critical removes it; the default is 20 %.
    """


def _undamped(body: Any) -> bool:
    if body.contact_damping is not None:
        return body.contact_damping == 0.0
    return body.contact_damping_ratio is not None and body.contact_damping_ratio == 0.0


def _has_friction(body: Any) -> bool:
    f = body.friction
    return f is not None and f.model != "none" and f.static > 0.0


def warn_scene(scene: Any, stacklevel: int = 3) -> None:
    """Warn about each pulley and idler of ``scene`` with friction on undamped contact.

    Call it on a scene the engine has accepted (its fields then have their types)."""
    bodies = [
        (f"pulleys[{j}]" + (f" ({p.name})" if p.name else ""), p)
        for j, p in enumerate(scene.pulleys)
        if p.contact_stiffness > 0.0
    ]
    bodies += [(f"idlers[{k}]", d) for k, d in enumerate(scene.idlers)]
    bad = [name for name, body in bodies if _has_friction(body) and _undamped(body)]
    if bad:
        shown = ", ".join(bad[:5]) + (f" and {len(bad) - 5} more" if len(bad) > 5 else "")
        warnings.warn(
            f"{shown}: friction on undamped contact (contact damping 0). The belt bounces off "
            "the pulley (the contact springs ring, and friction couples that ringing to the "
            "belt's motion: mode-coupling flutter), so wrap, slip and driven speeds come out "
            "wrong while the tensions still look plausible. Leave contact_damping and "
            "contact_damping_ratio at their defaults (20 % of critical), or give a ratio "
            "> 0 (docs/belt-drives.md).",
            UndampedContactWarning,
            stacklevel=stacklevel,
        )

"""Static drive calculation of a straight, head-driven belt conveyor after DIN 22101 (CEMA
uses the same structure): the independent reference that the steady running of a simulated
conveyor is checked against (reference-cases.md, case G). Its section formula is
:func:`beltrs.statics.din_main_resistance`, the one that :mod:`beltrs.statics` uses for the
tensions at every point of any loop (several sections, drives, inclines, CEMA); this module
keeps the lumped, two-strand form of the standard's hand calculation.

Pure Python, SI units (m, kg, s, N). Only the resistances that the engine models are
included, so that engine and hand calculation describe the same conveyor:

* **main resistance** (DIN 22101 eq. for F_H), idler running resistance with the artificial
  friction coefficient f on the weight resting on the idlers, strand by strand:

  F_H = f · g · [L_c · (m'_R,c + (m'_G + m'_L) · cos δ) + L_r · (m'_R,r + m'_G · cos δ)]

  (m'_G belt, m'_L material and m'_R rotating idler mass per metre; L_c, L_r the carry and
  return lengths resting on idlers; δ the slope). The engine applies f at every idler
  contact to the contact's normal force plus the roll's own weight, which sums to exactly
  this on a straight strand.
* **acceleration of the material at the loading point**, F_bA = Q · v = m'_L · v²
  (material arrives with no speed along the belt; Q = m'_L · v is the mass flow of a
  belt carrying m'_L per metre at speed v);
* **slope resistance** of the material, F_St = m'_L · g · H (H the lift of the loaded
  length; the belt's own weight cancels between the strands).

DIN's coefficient C for the remaining secondary resistances (skirt boards, pulley
bending, bearings of the pulleys, belt cleaners) is *not* applied: the engine does not
model those. A designer adds them as DIN prescribes; a comparison with the engine must
leave them out.

Tensions of a conveyor with a head drive and a gravity takeup at the tail pulley
(:func:`head_drive_tensions`): the takeup fixes the tension at the tail, T_tail = pull/2
(a horizontal takeup whose counterweight rope pull is shared by the two strands); the
return strand, moving from the head towards the tail, gains its resistance along its
travel, so the slack-side tension at the head is T2 = T_tail − F_H,return − (return strand
lift); the tight side is T1 = T2 + F_U.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ._beltrs import SceneError
from .statics import check as _check_value
from .statics import din_main_resistance

__all__ = ["Resistances", "HeadDriveTensions", "resistances", "head_drive_tensions", "rigid_start_force"]

G = 9.81


@dataclass(frozen=True)
class Resistances:
    """Steady-running resistances of a conveyor, N (DIN 22101 symbols).

    Attributes:
        main_carry: F_H of the carry strand, N.
        main_return: F_H of the return strand, N.
        loading: F_bA, acceleration of the material at the loading point, N.
        slope: F_St, lifting the material, N.
    """

    main_carry: float
    main_return: float
    loading: float
    slope: float

    @property
    def main(self) -> float:
        """F_H = main_carry + main_return, N."""
        return self.main_carry + self.main_return

    @property
    def total(self) -> float:
        """F_U, the steady peripheral force the drive must supply, N."""
        return self.main + self.loading + self.slope


def _check(name: str, value: float, *, positive: bool = False) -> float:
    """``value`` as a float; a :class:`beltrs.SceneError` naming it and the rule if it is
    not finite and >= 0 (> 0 with ``positive``)."""
    return _check_value(name, value, positive=positive)


def resistances(
    *,
    carry_length: float,
    return_length: float,
    belt_mass: float,
    material_mass: float,
    speed: float,
    f: float = 0.02,
    carry_rotating_mass: float = 0.0,
    return_rotating_mass: float = 0.0,
    slope: float = 0.0,
    loaded_length: float | None = None,
    lift: float = 0.0,
    gravity: float = G,
) -> Resistances:
    """DIN 22101 steady-running resistances of a straight conveyor.

    Args:
        carry_length: L_c, carry strand resting on idlers, m.
        return_length: L_r, return strand resting on idlers, m.
        belt_mass: m'_G, belt mass per metre, kg/m.
        material_mass: m'_L, material per metre of belt on the loaded length, kg/m.
        speed: belt speed v, m/s.
        f: artificial friction coefficient (DIN 22101 f; 0.02 is the standard value for
            a well-aligned conveyor at normal temperature). Default 0.02.
        carry_rotating_mass: m'_R,c, rotating mass of the carry idlers per metre, kg/m.
            Default 0.
        return_rotating_mass: m'_R,r, per metre of return strand, kg/m. Default 0.
        slope: δ, rad. Default 0 (horizontal).
        loaded_length: length of carry strand carrying material, m. Default carry_length.
        lift: H, height the material is lifted, m. Default 0.
        gravity: g, m/s². Default 9.81.

    Raises:
        beltrs.SceneError: a value out of range, naming it and the rule.
    """
    lc = _check("carry_length", carry_length)
    lr = _check("return_length", return_length)
    mg = _check("belt_mass", belt_mass)
    ml = _check("material_mass", material_mass)
    v = _check("speed", speed)
    f = _check("f", f)
    mrc = _check("carry_rotating_mass", carry_rotating_mass)
    mrr = _check("return_rotating_mass", return_rotating_mass)
    ll = lc if loaded_length is None else _check("loaded_length", loaded_length)
    g = _check("gravity", gravity)
    slope = _check_value("slope", slope, low=-math.pi / 2, unit="rad")
    if abs(slope) >= math.pi / 2:
        raise SceneError(f"slope = {slope!r}: must be finite with |slope| < pi/2 (rad)")
    lift = _check_value("lift", lift, low=-math.inf, unit="m")
    cos = math.cos(slope)
    return Resistances(
        # belt and rolls on the whole carry strand, material on its loaded length
        main_carry=din_main_resistance(lc, f, mg, 0.0, mrc, cos, g) + din_main_resistance(ll, f, 0.0, ml, 0.0, cos, g),
        main_return=din_main_resistance(lr, f, mg, 0.0, mrr, cos, g),
        loading=ml * v * v,
        slope=ml * g * lift,
    )


@dataclass(frozen=True)
class HeadDriveTensions:
    """Steady tensions of a head-driven conveyor with a gravity takeup at the tail, N.

    Attributes:
        tail: T_tail, each strand at the tail pulley, N.
        slack: T2, slack side at the drive pulley (return strand leaving it), N.
        tight: T1, tight side at the drive pulley (carry strand arriving), N.
    """

    tail: float
    slack: float
    tight: float


def head_drive_tensions(r: Resistances, takeup_pull: float, return_lift: float = 0.0,
                        belt_mass: float = 0.0, gravity: float = G) -> HeadDriveTensions:
    """Tensions of a head drive / tail takeup conveyor in steady running.

    Args:
        r: the resistances (:func:`resistances`).
        takeup_pull: total pull of the takeup on the tail pulley, N (counterweight × g for
            a rope over a sheave: each strand carries half).
        return_lift: height the return strand rises from head to tail, m (negative when
            the tail is lower). Default 0.
        belt_mass: m'_G, kg/m (only needed with a return lift). Default 0.
        gravity: m/s². Default 9.81.
    """
    pull = _check("takeup_pull", takeup_pull, positive=True)
    tail = 0.5 * pull
    slack = tail - r.main_return - belt_mass * gravity * return_lift
    return HeadDriveTensions(tail=tail, slack=slack, tight=slack + r.total)


def rigid_start_force(moving_mass: float, acceleration: float, running: float = 0.0) -> float:
    """CEMA's rigid-belt start: the peripheral force F = M_eq · a + F_running, N.

    Args:
        moving_mass: M_eq, every moving mass reduced to the belt line (belt, material,
            idler rotating masses, pulley and drive inertias / r²), kg.
        acceleration: belt acceleration, m/s².
        running: steady resistances, N. Default 0.
    """
    return _check("moving_mass", moving_mass) * float(acceleration) + float(running)

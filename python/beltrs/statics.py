"""Steady-running ("static") belt tensions at every point of a conveyor, after DIN 22101 /
ISO 5048 and after CEMA (7th edition's method as the Hustrulid 1993 thesis, chapter 2,
presents it). Pure Python, SI units (m, kg, s, N). ``docs/statics.md`` has the formulas,
their symbols and units, and the worked examples the tests check.

A conveyor is described as a closed **loop** in the direction of belt travel: a list of
:class:`Section` (runs of belt on idlers, with their length, lift and loads) and
:class:`Point` (pulleys, drives, the takeup, a loading point: anything that sits at one
place and adds a local resistance, takes tension out as a drive, or fixes the tension as a
takeup). :func:`tensions` walks the loop once:

1. each section's tension rise ΔT (its running resistance plus its lift) by the chosen
   method (:class:`DIN22101` or :class:`CEMA`);
2. the peripheral force F_U = Σ ΔT + Σ local resistances, the force the drives supply
   together; each drive takes its share of F_U out of the belt (T2 = T1 − share · F_U);
3. the takeup fixes the absolute level: the tension where it sits is its tension per
   strand (a gravity takeup's pull over two strands: pull / 2); on a drum that also drives
   (or has a local resistance) it holds the mean of the tensions arriving and leaving;
4. from the takeup, in the direction of travel, T grows by each section's ΔT and each
   point's local resistance and falls at each drive, back to the takeup (the loop closes
   exactly because the drives' shares add up to 1).

CEMA's K_y depends on the section's average tension, so under CEMA steps 1-4 repeat until
the tensions settle (a fixed point; in practice 3-6 passes).

The section formulas (:func:`din_section_rise`, :func:`cema_section_rise`) are the one
implementation: :mod:`beltrs.din22101` (the straight head-drive conveyor of case G) calls
them, and :mod:`beltrs.conveyor` builds its loop from a conveyor description.

Bad input raises :class:`beltrs.SceneError` naming the field, the value and the rule.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional, Sequence, Union

import numpy as np

from ._beltrs import SceneError

__all__ = [
    "CEMA",
    "CEMA_IDLER_RESISTANCE",
    "DIN22101",
    "Point",
    "Section",
    "TensionProfile",
    "cema_kx",
    "cema_ky",
    "cema_section_rise",
    "din_main_resistance",
    "din_secondary_coefficient",
    "din_section_rise",
    "tensions",
]

G = 9.81  #: m/s², standard gravity as the standards and the thesis use it

LB_PER_FT = 0.45359237 / 0.3048  #: kg/m in one lb/ft (1.48816)
LBF = 4.4482216152605  #: N in one pound-force
FT = 0.3048  #: m in one foot


# --- validation -------------------------------------------------------------------------
def _error(name: str, value: Any, rule: str) -> SceneError:
    return SceneError(f"{name} = {value!r}: {rule}")


def check_flag(name: str, value: Any, *, none: bool = False) -> Optional[bool]:
    """``value`` as a bool (a Python or NumPy bool; or None if ``none``), or a SceneError
    naming ``name``, the value and the rule."""
    if value is None and none:
        return None
    if not isinstance(value, (bool, np.bool_)):
        raise _error(name, value, "must be True, False or None" if none else "must be True or False")
    return bool(value)


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise _error(name, value, "expected a number")
    return float(value)


def check(name: str, value: Any, *, positive: bool = False, finite: bool = True,
          low: Optional[float] = None, high: Optional[float] = None, unit: str = "") -> float:
    """``value`` as a float, or a SceneError naming ``name``, the value and the rule.

    By default the value must be finite and >= 0; ``positive`` asks > 0; ``low``/``high``
    replace the lower bound / add an upper bound (inclusive); ``finite=False`` admits inf.
    """
    v = _number(name, value)
    suffix = f" ({unit})" if unit else ""
    if math.isnan(v) or (finite and math.isinf(v)):
        raise _error(name, value, f"must be finite{suffix}")
    if low is None:
        if positive and not v > 0:
            raise _error(name, value, f"must be > 0{suffix}")
        if not positive and v < 0:
            raise _error(name, value, f"must be >= 0{suffix}")
    elif v < low:
        raise _error(name, value, f"must be >= {low:g}{suffix}")
    if high is not None and v > high:
        raise _error(name, value, f"must be <= {high:g}{suffix}")
    return v


# --- DIN 22101 / ISO 5048 ---------------------------------------------------------------
def din_main_resistance(length: float, f: float, belt_mass: float, material_mass: float,
                        rotating_mass: float, cos_slope: float = 1.0, gravity: float = G) -> float:
    """DIN 22101 main resistance of one section (thesis eq. 2.10), N:

    F_H,i = f · g · [m'_R + (m'_G + m'_L) · cos δ] · l

    Args:
        length: l, belt length of the section, m.
        f: artificial friction coefficient, dimensionless.
        belt_mass: m'_G, kg/m. material_mass: m'_L, kg/m. rotating_mass: m'_R, kg/m.
        cos_slope: cos δ of the section's slope. Default 1.
        gravity: g, m/s². Default 9.81.
    """
    return f * gravity * (rotating_mass + (belt_mass + material_mass) * cos_slope) * length


#: DIN 22101 Table 2.3 of the thesis: coefficient C for the secondary resistances against
#: the conveyor length L (m), for filling ratios of 70-110 %.
DIN_C_TABLE = (
    (80, 1.92), (100, 1.78), (150, 1.58), (200, 1.45), (300, 1.31), (400, 1.25), (500, 1.20),
    (600, 1.17), (700, 1.14), (800, 1.12), (900, 1.10), (1000, 1.09), (1500, 1.06), (2000, 1.05),
)


def din_secondary_coefficient(length: float) -> float:
    """DIN 22101's C = 1 + F_N/F_H (thesis Table 2.3, eq. 2.7), linear between the table's
    lengths, 1.05 from 2000 m on.

    Args:
        length: conveyor length L, m, >= 80 (DIN: below 80 m, or with several loading
            points, compute each secondary resistance instead).
    """
    L = check("length", length, low=80.0, unit="m; DIN 22101 gives C from 80 m on, compute F_N "
              "item by item below")
    xs, cs = zip(*DIN_C_TABLE)
    return float(np.interp(L, xs, cs))


@dataclass(frozen=True)
class DIN22101:
    """DIN 22101 / ISO 5048 section resistances (thesis §2.3.2, eq. 2.9-2.11):

    ΔT_i = f · g · [m'_R + (m'_G + m'_L) · cos δ] · l + g · (m'_G + m'_L) · ΔY

    Attributes:
        f: artificial friction coefficient f, dimensionless, >= 0 (thesis Table 2.2:
            0.017 favourable, 0.020 normal, 0.023-0.027 adverse, up to 0.035 extreme cold;
            0.012-0.016 for steep regenerative declines). Default 0.02.
        gravity: g, m/s². Default 9.81.
    """

    f: float = 0.02
    gravity: float = G

    def validate(self) -> None:
        check("DIN22101.f", self.f, unit="dimensionless")
        check("DIN22101.gravity", self.gravity, positive=True, unit="m/s^2")


def din_section_rise(s: "Section", belt_mass: float, method: DIN22101 = DIN22101()) -> float:
    """Tension rise over a section in the direction of travel, DIN 22101 (thesis eq.
    2.9-2.11): main resistance plus the lift of belt and material, N."""
    cos = math.sqrt(max(0.0, 1.0 - (s.lift / s.length) ** 2))
    main = din_main_resistance(s.length, method.f, belt_mass, s.material, s.rotating_mass, cos, method.gravity)
    return main + method.gravity * (belt_mass + s.material) * s.lift


# --- CEMA -------------------------------------------------------------------------------
#: A_i of thesis eq. 2.2 by CEMA idler class, N (force to turn the rolls of one idler set).
CEMA_IDLER_RESISTANCE = {
    "C6": 6.67, "D6": 6.67,  # 6 in (152 mm) rolls
    "A5": 8.01, "B5": 8.01, "C5": 8.01, "D5": 8.01,  # 5 in (127 mm)
    "A4": 10.23, "B4": 10.23, "C4": 10.23,  # 4 in (102 mm)
    "E7": 10.68,  # 7 in (178 mm)
    "E6": 12.45,  # 6 in, class E
}

# Thesis Table 2.1 (CEMA's K_y table): rows = average belt tension, 1000-16000 lbf;
# columns = idler spacing 3.0, 3.5, 4.0, 4.5, 5.0 ft; each entry (A, B).
_KY_TENSION = np.arange(1, 17) * 1000.0 * LBF  # N (4.45 ... 71.17 kN)
_KY_SPACING = np.array([3.0, 3.5, 4.0, 4.5, 5.0]) * FT  # m (0.914 ... 1.524)
_KY_A = np.array([
    [1.4447, 1.4753, 1.4783, 1.4825, 1.4615],
    [1.2412, 1.1186, 1.0856, 1.0511, 1.0368],
    [1.0943, 0.9856, 0.9626, 0.9538, 0.9890],
    [0.9827, 0.9085, 0.8934, 0.8903, 0.9307],
    [0.8620, 0.8014, 0.7934, 0.7937, 0.8254],
    [0.7646, 0.7217, 0.7139, 0.7164, 0.7366],
    [0.6766, 0.6349, 0.6420, 0.6576, 0.6984],
    [0.6163, 0.5747, 0.5808, 0.5964, 0.6443],
    [0.5515, 0.5376, 0.5304, 0.5603, 0.5988],
    [0.4866, 0.4947, 0.4835, 0.5255, 0.5556],
    [0.4356, 0.4460, 0.4464, 0.4956, 0.5220],
    [0.3916, 0.3916, 0.4188, 0.4536, 0.4980],
    [0.3499, 0.3522, 0.3852, 0.4152, 0.4583],
    [0.3151, 0.3232, 0.3504, 0.3743, 0.4092],
    [0.2803, 0.2977, 0.3180, 0.3480, 0.3768],
    [0.2502, 0.2665, 0.2851, 0.3084, 0.3396],
])
_KY_B = np.array([
    [1.565, 1.925, 2.250, 2.584, 2.910],
    [1.345, 1.744, 1.982, 2.197, 2.331],
    [1.237, 1.593, 1.799, 1.991, 2.091],
    [1.164, 1.465, 1.659, 1.825, 1.938],
    [1.122, 1.381, 1.559, 1.714, 1.839],
    [1.076, 1.318, 1.472, 1.627, 1.761],
    [1.039, 1.256, 1.404, 1.549, 1.657],
    [0.998, 1.194, 1.337, 1.472, 1.583],
    [0.958, 1.120, 1.272, 1.388, 1.507],
    [0.918, 1.066, 1.216, 1.314, 1.430],
    [0.885, 1.024, 1.167, 1.238, 1.340],
    [0.842, 0.992, 1.100, 1.180, 1.242],
    [0.798, 0.938, 1.040, 1.116, 1.169],
    [0.763, 0.897, 0.996, 1.069, 1.123],
    [0.718, 0.841, 0.935, 1.006, 1.063],
    [0.663, 0.780, 0.875, 0.958, 1.009],
])

#: K_y above the table's last row (16 000 lbf = 71.17 kN), thesis §2.2.1.
KY_ABOVE_TABLE = 0.016
#: K_y of return sections, thesis §2.2.1.
KY_RETURN = 0.015


def _bilinear(table: np.ndarray, tension: float, spacing: float) -> float:
    i = int(np.clip(np.searchsorted(_KY_TENSION, tension) - 1, 0, len(_KY_TENSION) - 2))
    j = int(np.clip(np.searchsorted(_KY_SPACING, spacing) - 1, 0, len(_KY_SPACING) - 2))
    u = (tension - _KY_TENSION[i]) / (_KY_TENSION[i + 1] - _KY_TENSION[i])
    w = (spacing - _KY_SPACING[j]) / (_KY_SPACING[j + 1] - _KY_SPACING[j])
    return float((1 - u) * (1 - w) * table[i, j] + u * (1 - w) * table[i + 1, j]
                 + (1 - u) * w * table[i, j + 1] + u * w * table[i + 1, j + 1])


def cema_ky(belt_mass: float, material_mass: float, tension: float, idler_spacing: float) -> float:
    """CEMA's K_y from thesis eq. 2.3 and Table 2.1, dimensionless:

    K_y = (W_m + W_b) · A · 10⁻⁴ + B · 10⁻²

    A and B are interpolated bilinearly in the average belt tension and the idler spacing.
    The table is CEMA's imperial table (rows 1000-16 000 lbf, columns 3.0-5.0 ft; the
    thesis prints rounded kN and m beside them), so W_m + W_b enters in **lb/ft**: the
    masses given in kg/m are divided by 1.48816. (Read with kg/m the formula would give a
    different K_y from the same table; the A term is per lb/ft.)

    Range: tensions below the first row (4.45 kN) use the first row (the largest K_y,
    conservative); above the last row (71.17 kN) K_y = 0.016 (thesis §2.2.1; note the
    step there: the table's last row gives a smaller K_y for light belts). Spacings outside
    3.0-5.0 ft (0.914-1.524 m) are refused: the table does not cover them.

    Args:
        belt_mass: W_b, kg/m. material_mass: W_m, kg/m.
        tension: average belt tension over the section, N.
        idler_spacing: carry idler spacing S_i, m.

    Raises:
        beltrs.SceneError: a value out of range, named with the rule.
    """
    wb = check("belt_mass", belt_mass, unit="kg/m")
    wm = check("material_mass", material_mass, unit="kg/m")
    t = _number("tension", tension)
    if not math.isfinite(t):
        raise _error("tension", tension, "must be finite (N)")
    lo, hi = float(_KY_SPACING[0]), float(_KY_SPACING[-1])
    s = _number("idler_spacing", idler_spacing)
    if not (lo * (1 - 1e-9) <= s <= hi * (1 + 1e-9)):
        raise _error("idler_spacing", idler_spacing,
                     f"CEMA's K_y table covers carry idler spacings {lo:.4f}-{hi:.4f} m (3.0-5.0 ft); "
                     "give K_y explicitly (CEMA(ky=...)) outside it")
    if t > _KY_TENSION[-1]:
        return KY_ABOVE_TABLE
    t = max(t, float(_KY_TENSION[0]))
    w_lbft = (wb + wm) / LB_PER_FT
    return w_lbft * _bilinear(_KY_A, t, s) * 1e-4 + _bilinear(_KY_B, t, s) * 1e-2


def cema_kx(belt_mass: float, material_mass: float, idler_resistance: float, idler_spacing: float,
            gravity: float = G) -> float:
    """CEMA's idler friction factor K_x, thesis eq. 2.2, N/m:

    K_x = 0.00068 · (W_b + W_m) · g + A_i / S_i

    Args:
        belt_mass: W_b, kg/m. material_mass: W_m, kg/m.
        idler_resistance: A_i, N per idler set (:data:`CEMA_IDLER_RESISTANCE`; 0 for
            regenerative declines; +5 % for two-roll vee return idlers).
        idler_spacing: carry idler spacing S_i, m, > 0.
        gravity: g, m/s². Default 9.81.
    """
    return 0.00068 * (belt_mass + material_mass) * gravity + idler_resistance / idler_spacing


@dataclass(frozen=True)
class CEMA:
    """CEMA section resistances (thesis §2.2.2, eq. 2.4):

    carry: ΔT = l · K_t · (K_x + C₁ · K_y · W_b · g) + W_m · g · (C₁ · l · K_y + ΔY) + W_b · g · ΔY
    return: the same with K_x = 0, C₁ = 1, K_y = 0.015 (and W_m = 0 unless material rides on it)

    K_x (eq. 2.2) lumps the idler friction of both strands into the carry strand, as CEMA
    does: exact for the effective tension, approximate for the split between the strands
    (thesis §2.2.1).

    Attributes:
        kt: ambient temperature correction factor K_t, dimensionless, >= 1 (CEMA Figure
            6-1, thesis Figure 2.1: 1.0 at or above about 0 °C, rising below freezing;
            read it from that figure for cold sites). Default 1.0.
        idler_resistance: A_i, N per carry idler set (eq. 2.2, :data:`CEMA_IDLER_RESISTANCE`,
            or a class name such as ``"C6"``). Default 6.67 N (CEMA C6/D6, 6 in rolls).
        c1: friction modification factor C₁ of the carry strand, in (0, 1] (0.5-0.7 for
            regenerative conveyors, 1 otherwise). Default 1.
        ky: carry K_y, dimensionless, or None to take it from Table 2.1 at each section's
            average tension (iterated, :func:`cema_ky`). Default None.
        ky_return: K_y of the return strand. Default 0.015.
        gravity: g, m/s². Default 9.81.
    """

    kt: float = 1.0
    idler_resistance: Union[float, str] = 6.67
    c1: float = 1.0
    ky: Optional[float] = None
    ky_return: float = KY_RETURN
    gravity: float = G

    @property
    def ai(self) -> float:
        """A_i, N (the class name resolved)."""
        if isinstance(self.idler_resistance, str):
            return CEMA_IDLER_RESISTANCE[self.idler_resistance]
        return float(self.idler_resistance)

    def validate(self) -> None:
        check("CEMA.kt", self.kt, low=1.0, unit="dimensionless, CEMA's K_t is 1 or more")
        if isinstance(self.idler_resistance, str):
            if self.idler_resistance not in CEMA_IDLER_RESISTANCE:
                raise _error("CEMA.idler_resistance", self.idler_resistance,
                             f"unknown CEMA idler class (known: {', '.join(CEMA_IDLER_RESISTANCE)}), "
                             "or give A_i in N")
        else:
            check("CEMA.idler_resistance", self.idler_resistance, unit="N per idler set")
        check("CEMA.c1", self.c1, positive=True, high=1.0, unit="dimensionless")
        if self.ky is not None:
            check("CEMA.ky", self.ky, unit="dimensionless")
        check("CEMA.ky_return", self.ky_return, unit="dimensionless")
        check("CEMA.gravity", self.gravity, positive=True, unit="m/s^2")


def cema_section_rise(s: "Section", belt_mass: float, method: CEMA, average_tension: float) -> float:
    """Tension rise over a section in the direction of travel, CEMA (thesis eq. 2.4), N.

    ``average_tension`` (N) picks K_y from Table 2.1 for a carry section when
    ``method.ky`` is None."""
    g, wb, wm, dy, length = method.gravity, belt_mass, s.material, s.lift, s.length
    if s.strand == "return":
        return length * method.kt * method.ky_return * wb * g + wm * g * (length * method.ky_return + dy) + wb * g * dy
    if s.idler_pitch is None:
        raise _error(f"sections[{s.name or '?'}].idler_pitch", None,
                     "CEMA needs the carry idler spacing S_i of every carry section (m)")
    ky = method.ky if method.ky is not None else cema_ky(wb, wm, average_tension, s.idler_pitch)
    kx = cema_kx(wb, wm, method.ai, s.idler_pitch, g)
    c1 = method.c1
    return length * method.kt * (kx + c1 * ky * wb * g) + wm * g * (c1 * length * ky + dy) + wb * g * dy


# --- the loop ---------------------------------------------------------------------------
STRANDS = ("carry", "return")


@dataclass(frozen=True)
class Section:
    """A run of belt on idlers between two points of the loop, in the direction of travel.

    Attributes:
        length: belt length l, m, > 0.
        lift: rise ΔY over the section in the direction of travel, m, |lift| < length
            (negative going down). Default 0.
        strand: ``"carry"`` or ``"return"`` (CEMA treats them differently). Default carry.
        material: m'_L (W_m), material on this section per metre of belt, kg/m. Default 0.
        rotating_mass: m'_R, rotating mass of the idler rolls per metre of belt, kg/m (DIN;
            CEMA uses A_i instead). Default 0.
        idler_pitch: idler spacing, m (CEMA's S_i on carry sections). Default None.
        name: label in the results. Default "".
    """

    length: float
    lift: float = 0.0
    strand: str = "carry"
    material: float = 0.0
    rotating_mass: float = 0.0
    idler_pitch: Optional[float] = None
    name: str = ""

    def validate(self, where: str) -> None:
        length = check(f"{where}.length", self.length, positive=True, unit="m")
        lift = _number(f"{where}.lift", self.lift)
        if not (math.isfinite(lift) and abs(lift) < length):
            raise _error(f"{where}.lift", self.lift, f"must be finite with |lift| < length = {length:g} (m)")
        if self.strand not in STRANDS:
            raise _error(f"{where}.strand", self.strand, 'must be "carry" or "return"')
        check(f"{where}.material", self.material, unit="kg/m")
        check(f"{where}.rotating_mass", self.rotating_mass, unit="kg/m")
        if self.idler_pitch is not None:
            check(f"{where}.idler_pitch", self.idler_pitch, positive=True, unit="m")


@dataclass(frozen=True)
class Point:
    """A place on the loop: a pulley, a drive, the takeup, a loading point.

    Attributes:
        name: label (e.g. ``"head"``), unique among the points that drive. Default "".
        drive: share of the peripheral force F_U this drive supplies, in [0, 1]; the shares
            of all points add up to 1 (a single drive: 1). Default 0 (not a drive).
        takeup: tension the takeup holds at this point, N (a gravity takeup with pull P on
            a pulley holds P/2 in each strand; on a drive drum, the mean of T1 and T2).
            Exactly one point has it. Default None.
        resistance: local resistance the belt meets here, N (pulley bearings and belt
            bending at the pulley, belt cleaners, skirt boards, the acceleration of the
            material at a loading point Q·v = m'_L·v²). Default 0.
    """

    name: str = ""
    drive: float = 0.0
    takeup: Optional[float] = None
    resistance: float = 0.0

    def validate(self, where: str) -> None:
        check(f"{where}.drive", self.drive, high=1.0, unit="share of F_U")
        if self.takeup is not None:
            check(f"{where}.takeup", self.takeup, positive=True, unit="N")
        check(f"{where}.resistance", self.resistance, unit="N")


@dataclass(frozen=True)
class DriveTensions:
    """Tensions at one drive, N.

    Attributes:
        name: the drive point's name.
        tight: T1, arriving at the drive. slack: T2, leaving it.
        force: T1 − T2, N: its share of F_U less any local resistance at the point.
    """

    name: str
    tight: float
    slack: float

    @property
    def force(self) -> float:
        return self.tight - self.slack


@dataclass(frozen=True)
class TensionProfile:
    """Tensions around the loop (:func:`tensions`).

    Attributes:
        distance: belt distance of each listed place from the takeup, m, in the direction
            of travel ([K]; each point appears twice, before and after it, at one distance).
        tension: tension there, N ([K]).
        label: what each place is (``"head: in"``, ``"head: out"``, ``"carry 2: end"``).
        effective: F_U, the peripheral force the drives supply together, N.
        drives: :class:`DriveTensions` per drive, in loop order.
        section_rise: ΔT of each section, N, in loop order.
        ky: K_y used on each section (CEMA; NaN for DIN), in loop order.
        iterations: passes of the CEMA fixed point (1 for DIN).
        method: the method used.
    """

    distance: np.ndarray
    tension: np.ndarray
    label: list[str]
    effective: float
    drives: list[DriveTensions]
    section_rise: np.ndarray
    ky: np.ndarray
    iterations: int
    method: Any
    length: float = field(default=0.0)

    @property
    def max(self) -> float:
        """Largest tension, N."""
        return float(self.tension.max())

    @property
    def min(self) -> float:
        """Smallest tension, N."""
        return float(self.tension.min())

    def drive(self, name: str) -> DriveTensions:
        """The :class:`DriveTensions` of the drive called ``name``."""
        for d in self.drives:
            if d.name == name:
                return d
        raise _error("drive", name, f"no drive of that name (drives: {[d.name for d in self.drives]})")

    def at(self, label: str) -> float:
        """Tension at the place labelled ``label`` (see :attr:`label`), N."""
        try:
            return float(self.tension[self.label.index(label)])
        except ValueError:
            raise _error("label", label, f"no such place (labels: {self.label})") from None

    def along(self, distance: Union[float, Sequence[float]]) -> Any:
        """Tension at belt distance(s) from the takeup, m (linear within each section;
        at a point, the tension leaving it). Distances wrap around the loop."""
        d = np.mod(np.asarray(distance, dtype=float), self.length)
        # keep the value leaving a point: search among places after equal distances
        idx = np.searchsorted(self.distance, d, side="right") - 1
        idx = np.clip(idx, 0, len(self.distance) - 2)
        d0, d1 = self.distance[idx], self.distance[idx + 1]
        t0, t1 = self.tension[idx], self.tension[idx + 1]
        span = np.where(d1 > d0, d1 - d0, 1.0)
        out = t0 + (t1 - t0) * np.clip((d - d0) / span, 0.0, 1.0)
        return float(out) if np.ndim(distance) == 0 else out


Method = Union[DIN22101, CEMA]


def tensions(loop: Sequence[Union[Section, Point]], belt_mass: float, method: Optional[Method] = None,
             *, tolerance: float = 1e-9, max_iterations: int = 200) -> TensionProfile:
    """Steady-running tensions at every point of a closed belt loop.

    Args:
        loop: sections and points in the direction of belt travel, closing on itself
            (the last item is followed by the first). One point has the ``takeup``; the
            points with ``drive`` > 0 share F_U.
        belt_mass: m'_G (W_b), belt mass per metre, kg/m.
        method: :class:`DIN22101` (default) or :class:`CEMA`.
        tolerance: CEMA fixed point: stop when no tension moves by more than this
            fraction of F_U. Default 1e-9.
        max_iterations: CEMA fixed point: at most this many passes. Default 200.

    Returns:
        :class:`TensionProfile`.

    Raises:
        beltrs.SceneError: bad input, naming the item (``loop[3].length``), the value and
            the rule; no takeup or several; drive shares that do not add up to 1; a
            resistance sum that leaves nothing for the drives to do is fine (F_U may be
            negative on a regenerative decline: the drives brake).
    """
    method = DIN22101() if method is None else method
    if not isinstance(method, (DIN22101, CEMA)):
        raise _error("method", method, "must be beltrs.statics.DIN22101(...) or beltrs.statics.CEMA(...)")
    method.validate()
    mg = check("belt_mass", belt_mass, unit="kg/m")
    items = list(loop)
    if not items:
        raise _error("loop", loop, "needs at least one section and one point")
    for i, it in enumerate(items):
        if isinstance(it, Section):
            it.validate(f"loop[{i}]")
        elif isinstance(it, Point):
            it.validate(f"loop[{i}]")
        else:
            raise _error(f"loop[{i}]", it, "must be a beltrs.statics.Section or Point")
    takeups = [i for i, it in enumerate(items) if isinstance(it, Point) and it.takeup is not None]
    if len(takeups) != 1:
        raise _error("loop", [items[i].name for i in takeups],
                     f"needs exactly one point with a takeup tension (found {len(takeups)}): it fixes the "
                     "tension level; with two the tensions are statically indeterminate")
    drives = [i for i, it in enumerate(items) if isinstance(it, Point) and it.drive > 0]
    if not drives:
        named = [i for i, it in enumerate(items) if isinstance(it, Point) and it.name]
        raise _error("loop", [items[i].name for i in named],
                     "needs a drive: give one point drive = 1 (or shares adding up to 1)")
    shares = sum(items[i].drive for i in drives)
    if abs(shares - 1.0) > 1e-9:
        raise _error("loop drive shares", [items[i].drive for i in drives],
                     f"must add up to 1 (they add up to {shares:.6g})")
    if not any(isinstance(it, Section) for it in items):
        raise _error("loop", loop, "needs at least one section")

    # Rotate so that the walk starts at the takeup point.
    k = takeups[0]
    items = items[k:] + items[:k]
    t_takeup = float(items[0].takeup)  # type: ignore[union-attr]
    sections = [it for it in items if isinstance(it, Section)]
    average = np.full(len(sections), t_takeup)
    ky = np.full(len(sections), math.nan)
    rise = np.zeros(len(sections))
    previous: Optional[np.ndarray] = None
    iterations = 0
    for iterations in range(1, max_iterations + 1):
        for j, s in enumerate(sections):
            if isinstance(method, DIN22101):
                rise[j] = din_section_rise(s, mg, method)
            else:
                rise[j] = cema_section_rise(s, mg, method, average[j])
                if s.strand == "carry":
                    ky[j] = method.ky if method.ky is not None else cema_ky(mg, s.material, average[j], s.idler_pitch)
        effective = float(rise.sum() + sum(it.resistance for it in items if isinstance(it, Point)))
        dist, ten, lab = [], [], []
        # The takeup holds the mean of the tensions arriving and leaving (a gravity takeup's
        # pull is their sum): the same thing on a plain pulley, half the drop on a drive drum.
        first = items[0]
        t = t_takeup - 0.5 * (first.resistance - first.drive * effective)  # type: ignore[union-attr]
        d, j = 0.0, 0
        starts = np.zeros(len(sections))
        arrive: dict[int, int] = {}  # item position -> index of its "in" place
        for n, it in enumerate(items):
            if isinstance(it, Point):
                arrive[n] = len(ten)
                dist.append(d), ten.append(t), lab.append(f"{it.name}: in")
                t = t + it.resistance - it.drive * effective
                dist.append(d), ten.append(t), lab.append(f"{it.name}: out")
            else:
                starts[j] = t
                t += rise[j]
                d += it.length
                dist.append(d), ten.append(t), lab.append(f"{it.name or f'section {j}'}: end")
                j += 1
        tension = np.array(ten)
        if isinstance(method, DIN22101) or method.ky is not None:
            break
        average = starts + 0.5 * rise
        if previous is not None and np.max(np.abs(tension - previous)) <= tolerance * max(abs(effective), 1.0):
            break
        previous = tension
    else:
        raise SceneError(f"statics: CEMA's K_y iteration did not settle in {max_iterations} passes "
                         "(the average tension sits at a step of Table 2.1); give CEMA(ky=...)")
    drive_list = [DriveTensions(it.name, tight=float(tension[arrive[n]]), slack=float(tension[arrive[n] + 1]))
                  for n, it in enumerate(items) if isinstance(it, Point) and it.drive > 0]
    return TensionProfile(
        distance=np.array(dist), tension=tension, label=lab, effective=effective, drives=drive_list,
        section_rise=rise.copy(), ky=ky, iterations=iterations, method=method, length=float(d),
    )

"""Closed-form and semi-analytic reference solutions for belt-conveyor checks.

Everything here is pure Python + numpy and uses SI units throughout
(m, kg, s, N). The functions are meant as independent references for the
numerical engine, so they avoid any shared state and any third-party solver.

Two-pulley gravity take-up (case H)
-----------------------------------
A vertical closed belt loop runs around an upper pulley (fixed, centre at
height ``centre_distance`` above the initial centre of the lower pulley) and
a lower pulley that hangs freely in the loop as a gravity take-up (moving
mass ``takeup_mass`` = pulley + counterweight). Both pulleys have radius
``r``; the belt makes a half wrap around each and forms two vertical strands.
The belt is unstretched on the initial path (length ``2 H + 2 pi r``).

With frictionless pulleys and a linear elastic belt ``T = EA * strain``
(strain measured against the material/unstretched length, so a material
element ``dl0`` occupies ``dl = (1 + T/EA) dl0``), the equilibrium is exact
(continuum, no small-strain assumption):

* along the belt the tension only changes with height,
  ``dT/ds = rho g / (1 + T/EA) * dy/ds``
  (``rho`` = mass per *material* length, so ``rho / (1 + T/EA)`` is the mass
  per geometric length);
* take-up equilibrium (pulley + belt on its arc as free body):
  ``2 T_A = (M + m_arc) g``;
* compatibility: the material lengths of the lower arc, the two strands and
  the upper arc add up to the belt length.

The defaults give ``T_A = 157.64 kN``, ``T_C = 256.15 kN`` and a take-up
displacement of ``-3.1410 m``. The small-strain hand estimate (rigid-belt
tensions, strain ``T/EA`` integrated over the *initial* path, i.e. the
additional stretch of the strands that have become ``d`` longer is not taken
into account) gives ``-0.5 (H + pi r)(T_A0 + T_C0)/EA = -3.1410 m`` as well
(``-3.14094 m`` vs. the exact ``-3.14096 m``); the two agree to about
6e-6 relative because the extra stretch of the strands that became ``d``
longer and the ``1/(1 + T/EA)`` reductions of strain and of the mass per
geometric length nearly cancel. The value ``-3.128 m`` quoted in the project
reference document is about 0.4 % (13 mm) smaller than both; it is not
reproduced by the exact continuum model nor by the hand formula.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np

try:  # the engine's error, when the extension is built (as part of the beltrs package)
    from ._beltrs import SceneError
except ImportError:  # loaded on its own (by file path), or without the extension
    try:
        from beltrs._beltrs import SceneError
    except ImportError:

        class SceneError(Exception):  # type: ignore[no-redef]
            """Bad input to a reference solution (stands in for ``beltrs.SceneError`` when
            this module runs without the compiled extension)."""


__all__ = [
    "Capstan",
    "CreepDrive",
    "HangingRope",
    "capstan",
    "discrete_capstan_ratio",
    "hanging_rope",
    "TakeupStatics",
    "TakeupStepResponse",
    "axial_wave_speed",
    "two_pulley_takeup_statics",
    "takeup_step_response",
    "two_pulley_creep",
    "pulley_torsion_frequency",
]


# --------------------------------------------------------------------------
# Data containers
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class TakeupStatics:
    """Exact static equilibrium of the two-pulley gravity take-up loop.

    Attributes:
        lower_tension: belt tension at the lower tangent points A, B [N].
        upper_tension: belt tension at the upper tangent points C, D [N].
        takeup_displacement: signed vertical take-up displacement from the
            initial (unstretched) position [m]; negative = moved down.
        strand_length: geometric length of each vertical strand at
            equilibrium, ``centre_distance - takeup_displacement`` [m].
        belt_mass_on_lower_arc: mass of the belt lying on the lower pulley
            (half wrap) at equilibrium [kg].
    """

    lower_tension: float
    upper_tension: float
    takeup_displacement: float
    strand_length: float
    belt_mass_on_lower_arc: float


@dataclass(frozen=True)
class TakeupStepResponse:
    """Reference numbers for a step increase of the take-up mass.

    Attributes:
        static_shift: change of the exact static take-up displacement when
            the take-up mass goes from ``M`` to ``M (1 + step)`` [m];
            negative = the take-up moves further down.
        frequency_thesis: natural frequency from Hustrulid's eq. 6.2 [Hz]
            (one strand spring, half of the take-up, see
            :func:`takeup_step_response`).
        frequency_loop: natural frequency from the whole-loop compliance
            estimate [Hz] (see :func:`takeup_step_response`).
    """

    static_shift: float
    frequency_thesis: float
    frequency_loop: float


# --------------------------------------------------------------------------
# Numerical helpers (RK4, Brent)
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class _SegmentResult:
    """Result of integrating the tension ODE along one belt segment.

    Attributes:
        end_tension: tension at the end of the segment [N].
        stretch: geometric minus material length of the segment [m],
            ``integral of (T/EA) / (1 + T/EA) dl``.
    """

    end_tension: float
    stretch: float


def _integrate_segment(
    start_tension: float,
    x_start: float,
    x_end: float,
    n: int,
    height_rate: Callable[[np.ndarray], np.ndarray],
    length_rate: float,
    weight_per_material_length: float,
    axial_stiffness: float,
) -> _SegmentResult:
    """Integrate tension and stretch along a segment with classical RK4.

    The segment is parametrised by ``x`` (an angle [rad] on an arc, the
    height [m] on a strand) with ``dy/dx = height_rate(x)`` [m per unit x]
    and ``dl/dx = length_rate`` [m per unit x]. The system integrated is::

        dT/dx = w * dy/dx / (1 + T/EA)
        dS/dx = dl/dx * (T/EA) / (1 + T/EA)

    with ``w = rho g`` [N/m] and ``S`` the stretch (geometric - material
    length) [m]. Integrating the small quantity ``S`` instead of the material
    length keeps full relative precision even for very stiff belts.

    Args:
        start_tension: tension at ``x_start`` [N].
        x_start: start of the parameter interval.
        x_end: end of the parameter interval.
        n: number of fixed RK4 steps.
        height_rate: vectorised ``dy/dx`` [m per unit x].
        length_rate: ``dl/dx`` [m per unit x] (constant).
        weight_per_material_length: ``rho g`` [N/m].
        axial_stiffness: ``EA`` [N].

    Returns:
        End tension [N] and stretch of the segment [m].
    """
    if n < 1:
        raise RuntimeError(f"internal: n = {n!r} RK4 steps")
    h = (x_end - x_start) / n
    nodes = x_start + h * np.arange(n + 1, dtype=float)
    rate_nodes = weight_per_material_length * np.asarray(height_rate(nodes), dtype=float)
    rate_mid = weight_per_material_length * np.asarray(height_rate(nodes[:-1] + 0.5 * h), dtype=float)
    a0: Sequence[float] = rate_nodes[:-1].tolist()
    a1: Sequence[float] = rate_nodes[1:].tolist()
    am: Sequence[float] = rate_mid.tolist()

    inv_ea = 1.0 / axial_stiffness
    half_h = 0.5 * h
    sixth_h = h / 6.0
    tension = float(start_tension)
    stretch_sum = 0.0
    for r0, rm, r1 in zip(a0, am, a1):
        e1 = tension * inv_ea
        q1 = 1.0 / (1.0 + e1)
        k1 = r0 * q1
        e2 = (tension + half_h * k1) * inv_ea
        q2 = 1.0 / (1.0 + e2)
        k2 = rm * q2
        e3 = (tension + half_h * k2) * inv_ea
        q3 = 1.0 / (1.0 + e3)
        k3 = rm * q3
        e4 = (tension + h * k3) * inv_ea
        q4 = 1.0 / (1.0 + e4)
        k4 = r1 * q4
        tension += sixth_h * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        stretch_sum += e1 * q1 + 2.0 * e2 * q2 + 2.0 * e3 * q3 + e4 * q4
    return _SegmentResult(end_tension=tension, stretch=sixth_h * length_rate * stretch_sum)


def _brent(
    func: Callable[[float], float],
    a: float,
    b: float,
    fa: float,
    fb: float,
    xtol: float,
    max_iter: int = 200,
) -> float:
    """Find a root of ``func`` in the bracket ``[a, b]`` with Brent's method.

    Args:
        func: continuous scalar function with ``fa * fb <= 0``.
        a, b: bracket ends.
        fa, fb: function values at ``a`` and ``b``.
        xtol: absolute tolerance on the root.
        max_iter: iteration limit.

    Returns:
        The root estimate.
    """
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if fa * fb > 0.0:
        raise RuntimeError("internal: Brent's method called without a bracketed root")
    if abs(fa) < abs(fb):
        a, b, fa, fb = b, a, fb, fa
    c, fc = a, fa
    d = e = b - a
    for _ in range(max_iter):
        if fb == 0.0:
            return b
        if fa * fb > 0.0:
            a, fa = c, fc
            d = e = b - a
        if abs(fa) < abs(fb):
            c, fc = b, fb
            b, fb = a, fa
            a, fa = c, fc
        tol = 2.0 * np.finfo(float).eps * abs(b) + 0.5 * xtol
        m = 0.5 * (a - b)
        if abs(m) <= tol:
            return b
        if abs(e) >= tol and abs(fc) > abs(fb):
            s = fb / fc
            if a == c:
                # secant
                p = 2.0 * m * s
                q = 1.0 - s
            else:
                # inverse quadratic interpolation
                qq = fc / fa
                rr = fb / fa
                p = s * (2.0 * m * qq * (qq - rr) - (b - c) * (rr - 1.0))
                q = (qq - 1.0) * (rr - 1.0) * (s - 1.0)
            if p > 0.0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * m * q - abs(tol * q), abs(e * q)):
                e, d = d, p / q
            else:
                d = e = m
        else:
            d = e = m
        c, fc = b, fb
        b += d if abs(d) > tol else math.copysign(tol, m)
        fb = func(b)
    raise RuntimeError("Brent's method did not converge")


# --------------------------------------------------------------------------
# Public API
# --------------------------------------------------------------------------


def axial_wave_speed(axial_stiffness: float, mass_per_length: float) -> float:
    """Longitudinal (axial) wave speed of the belt, ``c = sqrt(EA / rho)``.

    The speed is in material coordinates (material length per second), as
    follows from the linear wave equation ``rho u_tt = EA u_xx``.

    Args:
        axial_stiffness: axial stiffness ``EA`` [N].
        mass_per_length: belt mass per unstretched length ``rho`` [kg/m].

    Returns:
        Wave speed [m/s].
    """
    _check_positive("axial_stiffness", axial_stiffness)
    _check_positive("mass_per_length", mass_per_length)
    return math.sqrt(axial_stiffness / mass_per_length)


def two_pulley_takeup_statics(
    *,
    axial_stiffness: float = 7.62e6,
    mass_per_length: float = 100.0,
    radius: float = 5.0,
    centre_distance: float = 100.0,
    takeup_mass: float = 30600.0,
    g: float = 9.81,
    belt_length: float | None = None,
    n: int = 20000,
) -> TakeupStatics:
    """Exact static equilibrium of a vertical loop with a gravity take-up.

    Geometry: the upper pulley is fixed with its centre ``centre_distance``
    above the initial centre of the lower (take-up) pulley; both have radius
    ``radius`` and carry a half wrap; the two strands are vertical. The lower
    pulley hangs in the loop and, together with its counterweight, has the
    moving mass ``takeup_mass``. Pulleys are frictionless, so along the belt
    (arc length ``s``, height ``y``)::

        dT/ds = rho g / (1 + T/EA) * dy/ds,    dl0/ds = 1 / (1 + T/EA)

    with ``l0`` the material (unstretched) length and ``rho`` the mass per
    material length; ``rho / (1 + T/EA)`` is the mass per geometric length.

    Solution procedure:

    1. Take-up equilibrium ``2 T_A = (M + rho * l0_arc(T_A)) g`` — the lower
       arc's tension profile depends only on ``T_A`` — is solved by fixed
       point iteration (contraction factor ~ ``rho g pi r / (2 EA)``).
    2. For a trial drop ``d`` the strand (height ``H + d``) and the upper arc
       are integrated with RK4 (``n`` steps per segment: lower arc, strand,
       upper arc). Compatibility ``sum(l0) = belt_length`` is then solved for
       ``d`` with Brent's method. Stretch (geometric minus material length)
       is integrated instead of material length so that the result keeps
       its relative precision for very stiff belts.

    With the defaults (case H) the result is ``T_A = 157.64 kN``,
    ``T_C = 256.15 kN`` and ``takeup_displacement = -3.1410 m``.

    Args:
        axial_stiffness: belt axial stiffness ``EA`` [N].
        mass_per_length: belt mass per unstretched length ``rho`` [kg/m].
        radius: radius of both pulleys ``r`` [m].
        centre_distance: initial vertical centre distance ``H`` [m].
        takeup_mass: moving take-up mass ``M`` (pulley + counterweight) [kg].
        g: gravitational acceleration [m/s^2].
        belt_length: unstretched belt length [m]; defaults to the initial
            path length ``2 H + 2 pi r`` (belt unstretched on that path).
        n: number of RK4 steps per segment.

    Returns:
        :class:`TakeupStatics` with tensions [N], take-up displacement [m]
        (negative = down), strand length [m] and lower-arc belt mass [kg].
    """
    ea = _number("axial_stiffness", axial_stiffness)
    rho = _number("mass_per_length", mass_per_length)
    r = _number("radius", radius)
    h_c = _number("centre_distance", centre_distance)
    mass = _number("takeup_mass", takeup_mass)
    g = _number("g", g)
    for name, value in (
        ("axial_stiffness", ea),
        ("mass_per_length", rho),
        ("radius", r),
        ("centre_distance", h_c),
        ("g", g),
    ):
        _check_positive(name, value)
    _check_non_negative("takeup_mass", mass)
    if belt_length is not None:
        _check_positive("belt_length", float(belt_length))
    if not (isinstance(n, int) and n >= 1):
        raise SceneError(f"n = {n!r}: must be a positive integer (RK4 steps per segment)")
    path_length = 2.0 * h_c + 2.0 * math.pi * r
    material_length = path_length if belt_length is None else float(belt_length)
    w = rho * g
    half_pi = 0.5 * math.pi

    # Lower arc: angle phi from -pi/2 (A) via the bottom (0) to pi/2 (B);
    # height relative to A is -r cos(phi), so dy/dphi = r sin(phi).
    def lower_arc(t_a: float) -> _SegmentResult:
        return _integrate_segment(t_a, -half_pi, half_pi, n, lambda x: r * np.sin(x), r, w, ea)

    # Upper arc: phi from -pi/2 (C) over the top (0) to pi/2 (D);
    # height relative to C is r cos(phi), so dy/dphi = -r sin(phi).
    def upper_arc(t_c: float) -> _SegmentResult:
        return _integrate_segment(t_c, -half_pi, half_pi, n, lambda x: -r * np.sin(x), r, w, ea)

    # Strand from A (height -d) up to C (height H): parameter = height.
    def strand(t_a: float, drop: float) -> _SegmentResult:
        return _integrate_segment(t_a, 0.0, h_c + drop, n, np.ones_like, 1.0, w, ea)

    # 1. take-up force balance (independent of the drop d).
    t_a = 0.5 * (mass + rho * math.pi * r) * g
    for _ in range(100):
        arc = lower_arc(t_a)
        t_new = 0.5 * (mass + rho * (math.pi * r - arc.stretch)) * g
        converged = abs(t_new - t_a) <= 1e-14 * abs(t_new)
        t_a = t_new
        if converged:
            break
    else:  # pragma: no cover - contraction factor is ~1e-4 for real belts
        raise RuntimeError("take-up force balance did not converge")
    lower = lower_arc(t_a)
    if abs(lower.end_tension - t_a) > 1e-9 * t_a:  # symmetry sanity check
        raise RuntimeError("lower arc integration is not symmetric; increase n")

    # 2. compatibility: path length - stretch = material length.
    def residual(drop: float) -> float:
        s = strand(t_a, drop)
        up = upper_arc(s.end_tension)
        geometric = path_length + 2.0 * drop
        return geometric - (lower.stretch + 2.0 * s.stretch + up.stretch) - material_length

    # Fixed-point start (stretch evaluated on the initial path), then bracket.
    strand0 = strand(t_a, 0.0)
    stretch0 = lower.stretch + 2.0 * strand0.stretch + upper_arc(strand0.end_tension).stretch
    drop0 = 0.5 * (material_length - path_length + stretch0)
    lower_limit = -h_c  # strands cannot have negative length
    f0 = residual(drop0)
    step = max(abs(drop0) * 0.05, 1e-12 * path_length)
    a, fa = drop0, f0
    b, fb = drop0, f0
    direction = 1.0 if f0 < 0.0 else -1.0  # residual increases with the drop
    for _ in range(200):
        if fa * fb <= 0.0 and a != b:
            break
        b = a + direction * step
        if b <= lower_limit:
            b = 0.5 * (a + lower_limit)
        fb = residual(b)
        if fa * fb > 0.0:
            a, fa = b, fb
            step *= 2.0
    else:
        raise RuntimeError("could not bracket the take-up displacement")
    xtol = max(1e-13 * abs(drop0), 1e-15 * path_length)
    drop = _brent(residual, a, b, fa, fb, xtol=xtol)

    s = strand(t_a, drop)
    return TakeupStatics(
        lower_tension=t_a,
        upper_tension=s.end_tension,
        takeup_displacement=-drop,
        strand_length=h_c + drop,
        belt_mass_on_lower_arc=rho * (math.pi * r - lower.stretch),
    )


def takeup_step_response(
    *,
    axial_stiffness: float = 7.62e6,
    mass_per_length: float = 100.0,
    radius: float = 5.0,
    centre_distance: float = 100.0,
    takeup_mass: float = 30600.0,
    step: float = 0.1,
    g: float = 9.81,
) -> TakeupStepResponse:
    """Reference numbers for a step in the take-up mass (``M -> M (1+step)``).

    ``static_shift`` [m] is exact: the difference of the take-up
    displacement of :func:`two_pulley_takeup_statics` with mass
    ``M (1 + step)`` and with mass ``M`` (negative = further down). For the
    defaults (``step`` applied to the whole take-up mass, +3060 kg) it is
-0.2279 m. The "-0.2235 m" of the project reference corresponds to a 10 %
step of the *counterweight only* (30000 kg -> 33000 kg, pulley 600 kg
unchanged, i.e. ``step = 3000/30600``), which gives -0.2234 m exactly and
-0.5 (H + pi r) (3000 kg) g / EA = -0.2234 m in the small-strain estimate.

    The two frequencies are the linear small-oscillation estimates quoted in
    the project reference; both use the take-up mass *before* the step
    (that is what reproduces the quoted 0.315 Hz and 0.295 Hz; with the
    stepped mass they would be 0.304 Hz and 0.284 Hz):

    ``frequency_thesis`` [Hz] — Hustrulid eq. 6.2, half-model of the loop:
    ONE strand as a spring ``k = EA / H`` carrying HALF the take-up::

        m = M/2 + rho pi r / 2 + rho H / 3
        f = sqrt(k / m) / (2 pi)

    i.e. half the counterweight plus half the pulley (``M/2``; 15000 + 300 kg
    in the thesis), half of the nominal belt mass on the lower arc
    (``rho pi r / 2`` = 5 pi/2 * 100 kg) and one third of the mass of one
    strand (``rho H / 3`` = 100*100/3 kg). Defaults: 0.3153 Hz. (This is the
    same as two strands ``2 EA/H`` in parallel with the full masses.)

    ``frequency_loop`` [Hz] — whole-loop compliance: a take-up drop ``d``
    lengthens the loop (unstretched length ``L = 2 H + 2 pi r``) by ``2 d``,
    i.e. a uniform extra strain ``2 d / L`` and a tension change
    ``EA 2 d / L`` in both strands, so the restoring force on the take-up is
    ``2 EA 2 d / L`` and ``k = 4 EA / L``; effective mass
    ``M + rho L / 3`` (counterweight + pulley + a third of the belt).
    Defaults: 0.2951 Hz.

    Args:
        axial_stiffness: belt axial stiffness ``EA`` [N].
        mass_per_length: belt mass per unstretched length ``rho`` [kg/m].
        radius: pulley radius ``r`` [m].
        centre_distance: initial centre distance ``H`` [m].
        takeup_mass: take-up mass ``M`` before the step [kg].
        step: relative increase of the take-up mass [-].
        g: gravitational acceleration [m/s^2].

    Returns:
        :class:`TakeupStepResponse` with the static shift [m] and the two
        frequency estimates [Hz].
    """
    _check_positive("takeup_mass", takeup_mass)
    step = _number("step", step)
    if not (math.isfinite(step) and step > -1.0):
        raise SceneError(f"step = {step!r}: must be finite and > -1 (the stepped mass M (1 + step) must stay > 0)")
    common = dict(
        axial_stiffness=axial_stiffness,
        mass_per_length=mass_per_length,
        radius=radius,
        centre_distance=centre_distance,
        g=g,
    )
    before = two_pulley_takeup_statics(takeup_mass=takeup_mass, **common)
    after = two_pulley_takeup_statics(takeup_mass=takeup_mass * (1.0 + step), **common)
    static_shift = after.takeup_displacement - before.takeup_displacement

    ea = float(axial_stiffness)
    rho = float(mass_per_length)
    k_strand = ea / centre_distance
    m_half = 0.5 * takeup_mass + 0.5 * rho * math.pi * radius + rho * centre_distance / 3.0
    frequency_thesis = math.sqrt(k_strand / m_half) / (2.0 * math.pi)

    loop_length = 2.0 * centre_distance + 2.0 * math.pi * radius
    k_loop = 4.0 * ea / loop_length
    m_loop = takeup_mass + rho * loop_length / 3.0
    frequency_loop = math.sqrt(k_loop / m_loop) / (2.0 * math.pi)

    return TakeupStepResponse(
        static_shift=static_shift,
        frequency_thesis=frequency_thesis,
        frequency_loop=frequency_loop,
    )


# --------------------------------------------------------------------------
# Two-pulley belt drive: Euler-Eytelwein + Grashof creep (docs/belt-drives.md)
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class CreepDrive:
    """Exact steady state of a two-pulley belt drive by creep theory (``docs/belt-drives.md``).

    Attributes:
        tight_tension: T1, tension of the tight span (entering the drive pulley) [N].
        slack_tension: T2, tension of the slack span (leaving the drive pulley) [N].
        drive_speed: angular speed of the drive pulley, as given [rad/s].
        driven_speed: angular speed of the driven pulley [rad/s].
        creep: speed loss ``1 - (omega2 r2)/(omega1 r1) = (T1 - T2)/(EA + T1)`` [-].
        slip_angle: angle of the slip arc on each pulley (the same on both) [rad].
        slip_arc: length of the slip arc on the drive and on the driven pulley,
            ``(r1 phi, r2 phi)`` [m].
        wrap_angles: wrap angles of the drive and the driven pulley [rad].
        adhesion_angles: wrap minus slip angle on each pulley [rad].
        tight_speed: belt speed in the tight span [m/s].
        slack_speed: belt speed in the slack span [m/s].
        mass_flow: belt mass passing any section per second, ``rho v/(1 + T/EA)`` [kg/s].
        centrifugal: centrifugal tension ``Q v`` in the tight and the slack span [N].
    """

    tight_tension: float
    slack_tension: float
    drive_speed: float
    driven_speed: float
    creep: float
    slip_angle: float
    slip_arc: tuple[float, float]
    wrap_angles: tuple[float, float]
    adhesion_angles: tuple[float, float]
    tight_speed: float
    slack_speed: float
    mass_flow: float
    centrifugal: tuple[float, float]


def _number(name: str, value: object) -> float:
    """``value`` as a float, or a :class:`SceneError` naming ``name``."""
    if isinstance(value, bool):
        raise SceneError(f"{name} = {value!r}: expected a number")
    try:
        return float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise SceneError(f"{name} = {value!r}: expected a number") from None


def _check_positive(name: str, value: float) -> None:
    v = _number(name, value)
    if not (math.isfinite(v) and v > 0.0):
        raise SceneError(f"{name} = {value!r}: must be finite and > 0")


def _check_non_negative(name: str, value: float) -> None:
    v = _number(name, value)
    if not (math.isfinite(v) and v >= 0.0):
        raise SceneError(f"{name} = {value!r}: must be finite and >= 0")


def two_pulley_creep(
    *,
    drive_radius: float,
    driven_radius: float,
    centre_distance: float,
    axial_stiffness: float,
    mass_per_length: float,
    pretension: float,
    mu: float,
    drive_speed: float,
    load_torque: float,
    quadrature: int = 64,
) -> CreepDrive:
    """Steady running of an open two-pulley belt drive by creep theory (exact for the model).

    The belt is a perfectly flexible, linear elastic string (``T = EA * strain``, strain on
    the unstretched length), without bending stiffness or gravity, on rigid pulleys with
    Coulomb friction ``mu``. The drive pulley turns at ``drive_speed``; a constant
    ``load_torque`` brakes the driven pulley. In steady running (``docs/belt-drives.md``
    derives every line):

    * each pulley carries the belt over an adhesion arc (entering, no tension change, the
      belt moving with the pulley surface) and then a slip arc where, with the centrifugal
      tension ``c(T) = Q v = Q^2 (1 + T/EA)/rho`` (Q the mass flow), ``T - c(T)`` changes
      as ``exp(mu psi)`` (Euler-Eytelwein): ``(T1 - c1)/(T2 - c2) = exp(mu phi)``;
    * the driven pulley's torque balance, with the momentum flux, is
      ``(T1 - c1) - (T2 - c2) = M/r2``;
    * mass flow is the same everywhere: the drive's adhesion arc sets ``v1 = omega1 r1``
      at strain ``T1/EA``, the driven pulley's adhesion arc moves at ``v2 = v1 (EA + T2)/(EA
      + T1)`` (Grashof creep), so ``omega2 = v2/r2``;
    * the unstretched belt length is conserved: the spans, the adhesion arcs and the slip
      arcs (integrated over the exponential tension) hold the length ``L0 = L_path/(1 +
      T0/EA)`` of the belt placed on the pulleys at rest with uniform tension ``T0``
      (``pretension``). This fixes ``T1 + T2``.

    Args:
        drive_radius: r1, radius to the belt centre line of the drive pulley [m].
        driven_radius: r2, of the driven pulley [m].
        centre_distance: distance between the pulley centres [m] (> ``|r2 - r1|``).
        axial_stiffness: EA [N].
        mass_per_length: rho, mass per unstretched length [kg/m] (> 0).
        pretension: T0, the belt's tension at rest on the pulleys [N] (> 0).
        mu: friction coefficient (kinetic, on the slip arcs) [-] (> 0).
        drive_speed: omega1 [rad/s], > 0 (counter-clockwise for a counter-clockwise wrap).
        load_torque: M, torque braking the driven pulley [N*m], >= 0.
        quadrature: Gauss-Legendre points for the slip-arc length integral. Default 64
            (the integrand is smooth: exact to rounding).

    Returns:
        :class:`CreepDrive`.

    Raises:
        beltrs.SceneError: a non-physical argument (naming it, its value and the rule), or a
            load beyond the capstan limit (the slip arc would exceed the smaller wrap: the
            belt slides).
    """
    for name, value in (
        ("drive_radius", drive_radius),
        ("driven_radius", driven_radius),
        ("centre_distance", centre_distance),
        ("axial_stiffness", axial_stiffness),
        ("mass_per_length", mass_per_length),
        ("pretension", pretension),
        ("mu", mu),
        ("drive_speed", drive_speed),
    ):
        _check_positive(name, value)
    _check_non_negative("load_torque", load_torque)
    if not (isinstance(quadrature, int) and quadrature >= 2):
        raise SceneError(f"quadrature = {quadrature!r}: must be an integer >= 2 (Gauss-Legendre points)")
    r1, r2, d, ea, rho = drive_radius, driven_radius, centre_distance, axial_stiffness, mass_per_length
    if d <= abs(r2 - r1):
        raise SceneError(f"centre_distance = {d!r}: must exceed |driven_radius - drive_radius| (here {abs(r2 - r1)!r})")
    beta = math.asin((r2 - r1) / d)
    span = math.sqrt(d * d - (r2 - r1) ** 2)
    wrap1, wrap2 = math.pi - 2.0 * beta, math.pi + 2.0 * beta
    path = 2.0 * span + r1 * wrap1 + r2 * wrap2
    length0 = path / (1.0 + pretension / ea)
    x, w = np.polynomial.legendre.leggauss(quadrature)
    dstar = load_torque / r2  # (T1 - c1) - (T2 - c2)

    def solve(kappa: float) -> tuple[float, float, float]:
        """T1, T2 and phi for a centrifugal coefficient kappa = Q^2/rho (c = kappa (1 + T/EA))."""
        scale = 1.0 - kappa / ea  # T* = T scale - kappa

        def tension(tstar: float | np.ndarray) -> float | np.ndarray:
            return (tstar + kappa) / scale

        def length(t2star: float) -> float:
            t1star = t2star + dstar
            t1, t2 = tension(t1star), tension(t2star)
            phi = math.log(t1star / t2star) / mu
            psi = 0.5 * phi * (x + 1.0)
            slip = 0.5 * phi * float(np.sum(w / (1.0 + tension(t2star * np.exp(mu * psi)) / ea)))
            return (
                span / (1.0 + t1 / ea)
                + span / (1.0 + t2 / ea)
                + r1 * ((wrap1 - phi) / (1.0 + t1 / ea) + slip)
                + r2 * ((wrap2 - phi) / (1.0 + t2 / ea) + slip)
                - length0
            )

        lo = 1e-12 * max(pretension, dstar)
        hi = 2.0 * pretension + dstar
        # The material the path holds falls as the tension rises: > L0 at lo, < L0 at hi.
        while length(hi) > 0.0:
            hi *= 2.0
        t2star = _brent(length, lo, hi, length(lo), length(hi), 1e-12 * hi)
        t1star = t2star + dstar
        return float(tension(t1star)), float(tension(t2star)), math.log(t1star / t2star) / mu

    kappa = 0.0
    for _ in range(50):
        t1, t2, phi = solve(kappa)
        q = rho * drive_speed * r1 / (1.0 + t1 / ea)
        new = q * q / rho
        if abs(new - kappa) <= 1e-14 * (1.0 + new):
            kappa = new
            break
        kappa = new
    t1, t2, phi = solve(kappa)
    if phi > min(wrap1, wrap2):
        raise SceneError(
            f"load_torque = {load_torque!r}: the slip arc ({phi:.4f} rad) would exceed the wrap "
            f"({min(wrap1, wrap2):.4f} rad): the belt slides (capstan limit)"
        )
    v1 = drive_speed * r1
    v2 = v1 * (1.0 + t2 / ea) / (1.0 + t1 / ea)
    q = rho * v1 / (1.0 + t1 / ea)
    return CreepDrive(
        tight_tension=t1,
        slack_tension=t2,
        drive_speed=drive_speed,
        driven_speed=v2 / r2,
        creep=1.0 - v2 / v1,
        slip_angle=phi,
        slip_arc=(r1 * phi, r2 * phi),
        wrap_angles=(wrap1, wrap2),
        adhesion_angles=(wrap1 - phi, wrap2 - phi),
        tight_speed=v1,
        slack_speed=v2,
        mass_flow=q,
        centrifugal=(q * v1, q * v2),
    )


# --------------------------------------------------------------------------
# Capstan (Euler-Eytelwein) and the hanging rope of a hoist
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Capstan:
    """Tension ratios of a belt over a pulley by the capstan (Euler-Eytelwein) law.

    Attributes:
        wrap: wrap angle theta [rad].
        onset_ratio: T_tight/T_slack at which sliding starts, ``exp(mu_s theta)`` [-]: a belt
            at rest on the pulley can hold any ratio up to it.
        sliding_ratio: T_tight/T_slack while the belt slides over the whole wrap,
            ``exp(mu_k theta)`` [-].
    """

    wrap: float
    onset_ratio: float
    sliding_ratio: float


def capstan(*, static: float, wrap: float, kinetic: float | None = None) -> Capstan:
    """The capstan law (Euler 1762, Eytelwein 1808) for a perfectly flexible belt on a rigid
    pulley with Coulomb friction, without centrifugal tension or belt weight (exact for that
    model).

    Along a wrap where the belt slides, dT/dpsi = mu T (the normal pressure per unit length
    is T/r and the friction mu T/r), so T_tight/T_slack = exp(mu theta). A belt that does
    not slide can carry any ratio up to ``exp(mu_s theta)`` (the onset of sliding); once it
    slides over the whole wrap the ratio is ``exp(mu_k theta)``.

    Args:
        static: mu_s [-], > 0.
        wrap: theta [rad], > 0 (may exceed 2 pi: a rope turned several times round a
            bollard).
        kinetic: mu_k [-], in [0, mu_s]. Default: equal to ``static``.

    Returns:
        :class:`Capstan`.

    Raises:
        beltrs.SceneError: a bad argument (named, with its value and the rule).
    """
    _check_positive("static", static)
    _check_positive("wrap", wrap)
    mu_k = static if kinetic is None else kinetic
    _check_non_negative("kinetic", mu_k)
    if mu_k > static:
        raise SceneError(f"kinetic = {kinetic!r}: must not exceed static ({static!r})")
    return Capstan(wrap=float(wrap), onset_ratio=math.exp(static * wrap), sliding_ratio=math.exp(mu_k * wrap))


def discrete_capstan_ratio(*, mu: float, wrap: float, element_angle: float) -> float:
    """The tension ratio over a wrap ``wrap`` (rad) of a belt of nodes, each turning it by
    ``element_angle`` (rad) and sliding with ``mu``: per node
    (1 + mu tan(a/2))/(1 - mu tan(a/2)) (its normal force is (T_a + T_b) sin(a/2), its
    friction (T_b - T_a) cos(a/2)), over ``wrap/element_angle`` nodes. It exceeds
    ``exp(mu wrap)`` by about ``exp(mu wrap (1 + mu^2) a^2/12)``; the engine's default
    element count keeps that within 0.5 % (docs/belt-drives.md).

    Raises:
        beltrs.SceneError: a bad argument, or ``mu tan(a/2) >= 1`` (no finite ratio).
    """
    _check_positive("mu", mu)
    _check_positive("wrap", wrap)
    _check_positive("element_angle", element_angle)
    x = mu * math.tan(0.5 * element_angle)
    if not (element_angle < math.pi and x < 1.0):
        raise SceneError(f"element_angle = {element_angle!r}: mu*tan(a/2) = {x!r} must be < 1 (a < pi)")
    return ((1.0 + x) / (1.0 - x)) ** (wrap / element_angle)


@dataclass(frozen=True)
class HangingRope:
    """A vertical rope (or belt) of unstretched length L hanging a mass m: the hoist.

    Attributes:
        bottom_tension: tension at the mass, ``m g`` [N].
        top_tension: tension at the top, ``(m + rho L) g`` [N].
        stretch: elongation under its own weight and the mass,
            ``(m g L + rho g L^2/2)/EA`` [m].
        frequency: fundamental frequency of the mass bouncing on the rope, fixed at the top
            [Hz], exact for the continuum: ``beta tan(beta) = rho L/m``,
            ``f = beta c/(2 pi L)``, ``c = sqrt(EA/rho)``.
        frequency_rayleigh: Rayleigh's estimate with a third of the rope's mass,
            ``sqrt(EA/(L (m + rho L/3)))/(2 pi)`` [Hz].
    """

    bottom_tension: float
    top_tension: float
    stretch: float
    frequency: float
    frequency_rayleigh: float

    def tension(self, s0: float | np.ndarray, *, mass: float, mass_per_length: float, g: float = 9.81):
        """Tension at unstretched distance ``s0`` (m) above the mass: ``(m + rho s0) g`` [N]."""
        return (mass + mass_per_length * np.asarray(s0, dtype=float)) * g


def hanging_rope(
    *, axial_stiffness: float, mass_per_length: float, length: float, mass: float, g: float = 9.81
) -> HangingRope:
    """Statics and the bounce frequency of a mass hanging on an elastic rope (a hoist).

    The rope is linear elastic (``T = EA strain``, strain on the unstretched length), with
    mass ``rho`` per unstretched length, fixed at its top, vertical, under gravity ``g``.

    * Statics (exact): at unstretched distance s0 above the mass the rope carries the mass
      and the rope below, ``T = (m + rho s0) g``; the stretch is the integral of T/EA.
    * Axial vibration: in material coordinates rho u_tt = EA u_ss (linear, whatever the
      pre-stress), u = 0 at the top and m u_tt = -EA u_s at the mass. Its modes are
      u = sin(beta s/L) with ``beta tan(beta) = rho L / m``; the fundamental is the root
      in (0, pi/2), ``omega = beta c / L``. For a light rope this tends to Rayleigh's
      ``sqrt(EA/(L (m + rho L/3)))`` (the rope's mass counts a third).

    Args:
        axial_stiffness: EA [N], > 0.
        mass_per_length: rho [kg/m], > 0.
        length: unstretched rope length L from the fixed point to the mass [m], > 0.
        mass: m [kg], > 0.
        g: gravitational acceleration [m/s^2], >= 0.

    Returns:
        :class:`HangingRope`.

    Raises:
        beltrs.SceneError: a bad argument (named, with its value and the rule).
    """
    for name, value in (
        ("axial_stiffness", axial_stiffness),
        ("mass_per_length", mass_per_length),
        ("length", length),
        ("mass", mass),
    ):
        _check_positive(name, value)
    _check_non_negative("g", g)
    ea, rho, big_l, m = float(axial_stiffness), float(mass_per_length), float(length), float(mass)
    ratio = rho * big_l / m
    # beta tan(beta) rises from 0 to +inf over (0, pi/2): one root there.
    hi = 0.5 * math.pi * (1.0 - 1e-12)

    def excess(b: float) -> float:
        return b * math.tan(b) - ratio

    beta = _brent(excess, 0.0, hi, -ratio, excess(hi), 1e-15)
    c = math.sqrt(ea / rho)
    return HangingRope(
        bottom_tension=m * g,
        top_tension=(m + rho * big_l) * g,
        stretch=(m * g * big_l + 0.5 * rho * g * big_l**2) / ea,
        frequency=beta * c / (2.0 * math.pi * big_l),
        frequency_rayleigh=math.sqrt(ea / (big_l * (m + rho * big_l / 3.0))) / (2.0 * math.pi),
    )


def pulley_torsion_frequency(
    *,
    inertia: float,
    radius: float,
    axial_stiffness: float,
    spans: "list[float] | tuple[float, ...]",
    mass_per_length: float = 0.0,
    wrap: float = 0.0,
) -> float:
    """Lowest torsional frequency of a pulley held by the belt spans leaving it, each span
    fixed at its far end (the other pulley's speed prescribed), Hz.

    The pulley (polar inertia J) turns by theta; each span's end on its rim moves by r*theta
    along the span, stretching one span and relaxing the other, and both pull it back. Each
    span is an elastic rod of length L_s, axial stiffness EA and mass rho per length, fixed
    at the far end: for a harmonic motion at omega its end force per unit end displacement
    is EA*beta*cot(beta*L_s), beta = omega/sqrt(EA/rho) (exact for the continuous rod). The
    belt on the pulley's ``wrap`` turns with it (inertia rho*r^3*wrap). The frequency is
    the lowest root of

        (J + rho r^3 wrap) omega^2 = r^2 EA beta sum_s cot(beta L_s).

    Without belt mass (``mass_per_length = 0``) that is omega^2 = k_theta/J with
    k_theta = r^2 sum_s EA/L_s, the pulley on the spans' stiffness; to first order in the
    belt mass each span adds rho L_s r^2/3 to the inertia (Rayleigh). Neglected: the
    compliance of the slip arcs (the belt creeps over part of each wrap, lengthening the
    spans' effective lengths), the belt's transport speed (wave speeds c +- v,
    (v/c)^2 ~ 1e-4 in belt drives) and its transverse motion.

    Args:
        inertia: J, kg*m^2, > 0.
        radius: r, m, > 0.
        axial_stiffness: EA, N, > 0.
        spans: span lengths L_s, m, each > 0 (two for a two-pulley drive).
        mass_per_length: rho, kg/m, >= 0. Default 0.
        wrap: belt wrap on the pulley that turns with it, rad, >= 0. Default 0.

    Returns:
        f = omega/(2 pi), Hz.

    Raises:
        beltrs.SceneError: a bad argument (named, with its value and the rule).
    """
    _check_positive("inertia", inertia)
    _check_positive("radius", radius)
    _check_positive("axial_stiffness", axial_stiffness)
    _check_non_negative("mass_per_length", mass_per_length)
    _check_non_negative("wrap", wrap)
    if isinstance(spans, (str, bytes)) or not hasattr(spans, "__len__") or len(spans) == 0:
        raise SceneError(f"spans = {spans!r}: must be a non-empty list of span lengths (m)")
    lengths = []
    for k, length in enumerate(spans):
        _check_positive(f"spans[{k}]", length)
        lengths.append(float(length))
    j, r, ea, rho = float(inertia), float(radius), float(axial_stiffness), float(mass_per_length)
    stiffness = r * r * ea * sum(1.0 / s for s in lengths)
    if rho == 0.0:
        return math.sqrt(stiffness / j) / (2 * math.pi)
    inertia_on = j + rho * r**3 * float(wrap)
    c = math.sqrt(ea / rho)

    def residual(omega: float) -> float:
        beta = omega / c
        return r * r * ea * beta * sum(1.0 / math.tan(beta * s) for s in lengths) - inertia_on * omega**2

    # The residual falls from k_theta > 0 at omega -> 0 and reaches -inf at the first pole
    # beta L_max = pi of the cotangents: the lowest root lies below it.
    hi = math.pi * c / max(lengths) * (1 - 1e-12)
    lo = 1e-9 * hi
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if residual(mid) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi) / (2 * math.pi)

"""The drive's grip through a start: a lumped model of a two-pulley conveyor's belt loop,
the belt held on the drive drum, and the largest tension ratio T₁/T₂ it asks of the drum
(issue 12, "Does the drive pulley slip?"; docs/conveyor-builder.md "Takeup tension",
docs/stops-takeups.md "The takeup's swing after a start").

DIN 22101's grip rule T₂ ≥ F_A / (e^{µθ} − 1) takes the start force of a rigid belt. An
elastic belt on a gravity takeup overshoots it: the strands and the takeup's mass swing
while the drive accelerates, and the ratio at the drum runs above the rigid belt's. This
module integrates that swing, linearly and cheaply (milliseconds), so that
:meth:`beltrs.conveyor.Conveyor.takeup_tension` can choose a takeup that keeps the belt on
the drum through the builder's start.

The model (:class:`Loop`): the carry and the return strand, each ``n`` elements of the
belt's EA in series with their spans' sag between idlers (a parabolic span of pitch p,
weight w per metre, at tension T shortens its chord by w²p³/(24T²), a compliance
w²p²/(12T³) per metre, linearised at the element's tension at rest), with their moving
mass per metre lumped at the nodes (belt, material, the rolls' I/r² per pitch); the two
drums' surfaces (their inertia over r², the belt on their wraps, the drive's rotor through
the gearbox); the takeup's carriage (a gravity takeup's counterweight and pulley; a winch
pulls with a constant force, its pulley's mass only; a fixed takeup is locked). The drive
drum follows the start curve through a PI speed loop (a spring K_i/r² and a dashpot
K_p/r² to the reference, as the engine's :class:`beltrs.SpeedController` acts) or exactly
(the ideal follower). The idlers' running resistance f·g·(m'_G + m'_L + rolls) per metre is
a constant force while the belt runs forward, switched on with the reference speed over
its first mm/s. Gravity along the strands and the takeup's pull are in the state at rest and
drop out of the increments; the model is linear about that state, so it is integrated
exactly for inputs linear over each step (a first-order hold, one matrix exponential).
Being linear, it cannot cap the drive at the motor's torque limit, so where the drive sits at
its limit in the start it asks more of the drum, and so more takeup tension, than the engine
does (conservative): the 300 m conveyor of the tests in the builder's 10 s start at 18 kN,
model T₁/T₂ 2.96 at the drum, the engine 2.62 10 m from it (its 30 kW motor at its limit).

The same model, written independently with its sag nonlinear and its resistance
regularised node by node, is tests/takeup_swing.py's ``Lumped``. On the 300 m conveyor of
the tests in a 4 s start at 28 kN it reads T₁/T₂ = 3.108 in its end element, this model 3.16
there (the sag's stiffness linearised, the secant to the rigid start state) and 3.30 at the
drum (the half element lumped there), the engine with the belt held on the drum (lagging
µ = 1) 3.17 10 m from it (tests/test_start_grip.py, docs/stops-takeups.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ._beltrs import SceneError

__all__ = ["Loop", "StartRatio", "expm", "start_ratio"]

#: The reference speed, m/s, over which the idlers' running resistance is switched on
#: (the static friction of a belt at rest carries what the moving belt's resistance does).
RESISTANCE_SPEED = 1e-3


@dataclass(frozen=True)
class Loop:
    """A two-pulley conveyor's belt loop for :func:`start_ratio`. SI units.

    Attributes:
        length: each strand's length, m (the carry profile's length), > 0.
        ea: belt axial stiffness, N.
        carry_mass, return_mass: moving mass per metre of each strand, kg/m (belt,
            material on the carry, the rolls' I/r² per pitch).
        carry_weight, return_weight: weight per metre hanging in a span between idlers,
            N/m (belt and material on the carry, belt on the return).
        carry_pitch, return_pitch: idler pitch, m (0: no sag).
        carry_resistance, return_resistance: running resistance per metre, N/m.
        carry_rest, return_rest: ``[n]`` each element's tension at rest, N, in the
            direction of travel (carry tail to head, return head to tail).
        drive: ``"head"`` or ``"tail"``: the driven drum.
        drive_mass: the drive drum's surface mass, kg: (drum + rotor·i² + flywheel·i²)
            inertia / r², and the belt on its wrap.
        pulley_mass: the other drum's surface mass, kg.
        takeup: ``"head"`` or ``"tail"``: the drum on the takeup's carriage.
        takeup_mass: the carriage's mass, kg (counterweight and pulley); None: a fixed
            takeup, locked.
        kp, ki: the speed loop's gains at the drum's surface, N·s/m and N/m (K_p/r²,
            K_i/r²); None: the ideal follower (the drum on the curve exactly).
    """

    length: float
    ea: float
    carry_mass: float
    return_mass: float
    carry_weight: float
    return_weight: float
    carry_pitch: float
    return_pitch: float
    carry_resistance: float
    return_resistance: float
    carry_rest: np.ndarray
    return_rest: np.ndarray
    drive: str
    drive_mass: float
    pulley_mass: float
    takeup: str
    takeup_mass: Optional[float]
    kp: Optional[float]
    ki: Optional[float]

    @property
    def n(self) -> int:
        """Elements per strand."""
        return len(self.carry_rest)

    def element_stiffness(self, tension: Optional[np.ndarray] = None) -> np.ndarray:
        """``[2n]`` axial stiffness of each element, N/m (carry then return): EA in series
        with its spans' sag, the secant from the tension at rest T_r to ``tension`` T
        (``[2n]``, N; default the tension at rest: the tangent there), chord stretch
        (T − T_r)/EA + w²p²/24 · (1/T_r² − 1/T²) per metre."""
        le = self.length / self.n
        rest = np.maximum(np.concatenate([self.carry_rest, self.return_rest]), 1.0)
        t = rest if tension is None else np.maximum(np.asarray(tension, dtype=float), 1.0)
        sag = np.concatenate([np.full(self.n, (self.carry_weight * self.carry_pitch) ** 2 / 24),
                              np.full(self.n, (self.return_weight * self.return_pitch) ** 2 / 24)])
        return 1.0 / (le / self.ea + le * sag * (t + rest) / (rest**2 * t**2))


@dataclass(frozen=True)
class StartRatio:
    """:func:`start_ratio`'s answer.

    Attributes:
        time: ``[k]`` s, from the curve's time 0.
        tight, slack: ``[k]`` the tension increments over the state at rest where the
            belt arrives at the drive drum (tight side) and leaves it (slack side), N: the
            end elements' tension and the force on the half element lumped at the drum
            (its inertia at the drum's acceleration, its resistance).
        tight_rest, slack_rest: the end elements' tensions at rest, N.
        frequency: the lowest natural frequency of the loop with the drive's speed loop,
            Hz (the takeup's swing on a gravity takeup).
    """

    time: np.ndarray
    tight: np.ndarray
    slack: np.ndarray
    tight_rest: float
    slack_rest: float
    frequency: float

    @property
    def ratio(self) -> np.ndarray:
        """``[k]`` T₁/T₂ at the drive drum, the belt held on it."""
        return (self.tight_rest + self.tight) / (self.slack_rest + self.slack)

    def takeup_for(self, grip: float) -> float:
        """The smallest uniform rise of the tensions at rest, N (negative: a fall), that
        keeps T₁/T₂ ≤ ``grip`` throughout: max over time of (T₁ − grip·T₂)/(grip − 1). A
        takeup tension raised by it keeps the ratio at ``grip`` at most, the increments
        unchanged (they are, to first order: a heavier counterweight and stiffer spans
        move them a little, hence the fixed point in
        :meth:`beltrs.conveyor.Conveyor.takeup_tension`)."""
        t1 = self.tight_rest + self.tight
        t2 = self.slack_rest + self.slack
        return float(np.max((t1 - grip * t2) / (grip - 1.0)))


def expm(a: np.ndarray) -> np.ndarray:
    """Matrix exponential (scaling and squaring of the [6/6] Padé approximant; the argument
    scaled to a norm under 0.5, where the approximant's error is below 1e-15)."""
    norm = float(np.linalg.norm(a, 1))
    s = max(0, int(math.ceil(math.log2(norm / 0.5)))) if norm > 0.5 else 0
    x = a / 2.0**s
    c = [1.0, 1 / 2, 5 / 44, 1 / 66, 1 / 792, 1 / 15840, 1 / 665280]
    eye = np.eye(len(a))
    p, q, xk = c[0] * eye, c[0] * eye, eye
    for k in range(1, 7):
        xk = xk @ x
        p = p + c[k] * xk
        q = q + (-1) ** k * c[k] * xk
    e = np.linalg.solve(q, p)
    for _ in range(s):
        e = e @ e
    return e


def start_ratio(loop: Loop, speed, duration: float, periods: float = 0.0, step: float = 5e-3,
                acceleration: Optional[float] = None) -> StartRatio:
    """The drive drum's T₁ and T₂ through a start, the belt held on the drum (:class:`Loop`).

    Args:
        loop: the conveyor's loop.
        speed: the start curve, a function of time (s, array) giving the reference belt
            speed, m/s, positive (``beltrs.StartCurve.speed_at`` of the builder's curve).
        duration: s from time 0 (the builder: the curve's end).
        periods: periods of :attr:`StartRatio.frequency` run after ``duration`` (the
            builder: 1, the swing's first peaks after the ramp). Default 0.
        step: s between samples; the inputs are linear over each step (first-order hold),
            the response exact for them. Default 5 ms.
        acceleration: m/s², the rigid belt's start acceleration whose quasi-static tensions
            the strands' stiffness is taken at (the secant from rest, :meth:`Loop.element_stiffness`:
            the sag stiffens the tight side and softens the slack side as the drive pulls).
            Default None: the tangent at rest. The builder gives its curve's peak.
    """
    n = loop.n
    le = loop.length / n
    ends = ("head", "tail")
    if loop.drive not in ends or loop.takeup not in ends:
        raise SceneError(f"Loop.drive = {loop.drive!r}, Loop.takeup = {loop.takeup!r}: each must be "
                         "\"head\" or \"tail\"")
    # Coordinates: tail surface, head surface, carriage (unless fixed), inner nodes of each strand.
    names = ["tail", "head"] + (["x"] if loop.takeup_mass is not None else [])
    dof = len(names) + 2 * (n - 1)
    col = {k: i for i, k in enumerate(names)}
    nodes = 2 * (n + 1)  # carry 0..n tail to head, return 0..n head to tail
    tr = np.zeros((nodes, dof))
    tr[0, col["tail"]] = 1.0  # carry's tail end leaves the tail
    tr[n, col["head"]] = 1.0  # carry's head end arrives at the head
    tr[n + 1, col["head"]] = 1.0  # return's head end leaves the head
    tr[2 * n + 1, col["tail"]] = 1.0  # return's tail end arrives at the tail
    if "x" in col:  # the carriage moves away from the conveyor by x: arriving end +x, leaving end -x
        arrive, leave = (2 * n + 1, 0) if loop.takeup == "tail" else (n, n + 1)
        tr[arrive, col["x"]] = 1.0
        tr[leave, col["x"]] = -1.0
    for i in range(1, n):
        tr[i, len(names) + i - 1] = 1.0
        tr[n + 1 + i, len(names) + n - 1 + i - 1] = 1.0
    mb = np.concatenate([np.full(n + 1, loop.carry_mass * le), np.full(n + 1, loop.return_mass * le)])
    wb = np.concatenate([np.full(n + 1, loop.carry_resistance * le), np.full(n + 1, loop.return_resistance * le)])
    for e in (0, n, n + 1, 2 * n + 1):
        mb[e] /= 2
        wb[e] /= 2
    first = np.concatenate([np.arange(n), n + 1 + np.arange(n)])  # each element's first node

    def stiffness(ke: np.ndarray) -> np.ndarray:
        kb = np.zeros((nodes, nodes))
        for i, a in enumerate(first):
            kb[np.ix_([a, a + 1], [a, a + 1])] += ke[i] * np.array([[1.0, -1.0], [-1.0, 1.0]])
        return tr.T @ kb @ tr

    m = tr.T @ np.diag(mb) @ tr
    d = col[loop.drive]
    other = col["tail" if loop.drive == "head" else "head"]
    m[d, d] += loop.drive_mass
    m[other, other] += loop.pulley_mass
    if "x" in col:
        m[col["x"], col["x"]] += loop.takeup_mass
    rest = np.concatenate([loop.carry_rest, loop.return_rest])
    ke = loop.element_stiffness()
    if acceleration is not None:
        # The rigid belt's start state: every drum and belt node at ``acceleration``, the
        # carriage still, the resistance on; quasi-statically, the drive drum's coordinate
        # held (it carries the drive's force). The strands' stiffness is the secant to it.
        k = stiffness(ke)
        rigid = np.ones(dof)
        if "x" in col:
            rigid[col["x"]] = 0.0
        force = -m @ rigid * acceleration - tr.T @ wb
        free = [i for i in range(dof) if i != d]
        q = np.zeros(dof)
        q[free] = np.linalg.solve(k[np.ix_(free, free)], force[free])
        x = tr @ q
        ke = loop.element_stiffness(rest + ke * (x[first + 1] - x[first]))
    k = stiffness(ke)
    c = np.zeros_like(k)
    # Relative to the rigid motion along the curve: q = s_ref(t) r + q_rel, r = 1 for the
    # drums and the belt, 0 for the carriage (a rigid belt does not move it). K r = 0, and
    # the PI's force on the drum is -K_i q_rel - K_p q_rel' there, so
    #     M q_rel'' + C q_rel' + K q_rel = -M r a_ref(t) - w on(t),
    # inputs u = (a_ref, on) (on: the resistance switched on with the reference speed).
    rigid = np.ones(dof)
    if "x" in col:
        rigid[col["x"]] = 0.0
    b = np.column_stack([-m @ rigid, -tr.T @ wb])
    ideal = loop.kp is None or loop.ki is None
    if ideal:  # the drum is on the curve: no relative motion there
        keep = [i for i in range(dof) if i != d]
    else:
        k[d, d] += loop.ki
        c[d, d] += loop.kp
        keep = list(range(dof))
    m, k, c, b = m[np.ix_(keep, keep)], k[np.ix_(keep, keep)], c[np.ix_(keep, keep)], b[keep]
    f = len(keep)
    mi = np.linalg.inv(m)
    a = np.block([[np.zeros((f, f)), np.eye(f)], [-mi @ k, -mi @ c]])
    bu = np.vstack([np.zeros((f, 2)), mi @ b])
    w2 = np.linalg.eigvals(mi @ k).real
    w2 = w2[w2 > 1e-9 * max(w2.max(), 1e-30)]
    frequency = float(np.sqrt(w2.min()) / (2 * np.pi)) if w2.size else 0.0
    # First-order hold: expm of [[A, B, 0], [0, 0, I], [0, 0, 0]] * step, balanced: positions
    # scaled by the highest natural frequency, so that every block is of the order of
    # omega_max * step (unscaled, a stiff belt's blocks differ by omega_max^2).
    z = np.zeros((2 * f + 4, 2 * f + 4))
    z[: 2 * f, : 2 * f] = a
    z[: 2 * f, 2 * f: 2 * f + 2] = bu
    z[2 * f: 2 * f + 2, 2 * f + 2:] = np.eye(2)
    omega = math.sqrt(max(float(np.max(w2)) if w2.size else 1.0, 1.0))
    scale = np.concatenate([np.full(f, 1.0 / omega), np.ones(f + 4)])
    ez = expm(z * step * scale[None, :] / scale[:, None]) * scale[:, None] / scale[None, :]
    phi, g0, g1 = ez[: 2 * f, : 2 * f], ez[: 2 * f, 2 * f: 2 * f + 2], ez[: 2 * f, 2 * f + 2:] / step
    if frequency > 0:
        duration += periods / frequency
    steps = int(math.ceil(duration / step))
    t = np.arange(steps + 1) * step
    v = np.maximum(np.asarray(speed(t), dtype=float), 0.0)
    acc_ref = np.gradient(v, step)
    on = np.clip(v / RESISTANCE_SPEED, 0.0, 1.0)
    u = np.column_stack([acc_ref, on])
    y = np.zeros((steps + 1, 2 * f))
    for j in range(steps):
        y[j + 1] = phi @ y[j] + g0 @ u[j] + g1 @ (u[j + 1] - u[j])
    q = np.zeros((steps + 1, dof))
    q[:, keep] = y[:, :f]
    x = q @ tr.T  # belt node displacements along travel, relative to the rigid motion
    tension = (x[:, first + 1] - x[:, first]) * ke
    # Tight side: the element arriving at the drive; slack: the one leaving it. At the drum
    # itself the tension differs from the element's by the half element lumped on the drum
    # (its inertia at the drum's acceleration and its resistance).
    i_tight, i_slack = (n - 1, n) if loop.drive == "head" else (2 * n - 1, 0)
    acc = acc_ref if ideal else acc_ref + np.gradient(y[:, f + keep.index(d)], step)
    half_in, half_out = (first[i_tight] + 1, first[i_slack])
    tight = tension[:, i_tight] + mb[half_in] * acc + wb[half_in] * on
    slack = tension[:, i_slack] - mb[half_out] * acc - wb[half_out] * on
    return StartRatio(time=t, tight=tight, slack=slack,
                      tight_rest=float(rest[i_tight]), slack_rest=float(rest[i_slack]), frequency=frequency)

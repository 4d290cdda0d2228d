"""A lumped model of a conveyor's takeup swing after a start, independent of the engine
(issue 12; docs/stops-takeups.md, "The takeup's swing after a start").

A level two-pulley conveyor: head drive, tail gravity takeup. Each strand (carry, return) is
a chain of ``n`` linear spring-dashpot elements (EA, Kelvin-Voigt) with its mass per metre
(belt, material on the carry, the rolls' rotational inertia as I/r^2 per pitch) lumped at
the nodes. Generalised coordinates, displacements along the belt's motion:

- ``s``: the head drum's surface (mass (J_rotor + J_drum)/r^2), driven by the VFD's PI
  loop as a force K_p (v_ref - v) + K_i (s_ref - s) (gains per metre of surface,
  K/r^2; K_p = 2 zeta omega_c J, K_i = omega_c^2 J as in docs/drives.md);
- ``u``: the tail pulley's surface (mass J_tail/r^2);
- ``x``: the takeup's travel away from the head (mass: counterweight + tail pulley);
- the inner nodes of each strand.

The carry's end at the tail moves u - x along the carry (tail to head), the return's end at
the tail u + x along the return (head to tail); both strands' head ends move s. With n = 1
and the drum held this is a 2-DOF model (u, x): the strands' masses lumped at their ends,
takeup mass M + (m_c + m_r) L/2, tail mass J/r^2 + (m_c + m_r) L/2, coupled through
(m_r - m_c) L/2 (the loaded carry is heavier than the return, so the belt's motion drives
the takeup), stiffness 2 k each with k the strand's stiffness; more elements converge to the
strands' distributed mass (n = 10 is within 0.1 % of n = 30 in frequency).

Each element's stiffness is the belt's EA in series with its spans' sag between the idlers
(a parabolic span of pitch p, weight w per metre, tension T shortens its chord by
w^2 p^3 / (24 T^2), a compliance w^2 p^2 / (12 T^3) per metre): at 22 kN on 1.2 m carry
pitches this is 0.7 of the elastic compliance L/EA, which takes the takeup mode of the 300 m
conveyor from 0.69 Hz (elastic only) to 0.58 Hz. In a start it is integrated as it is (the
tension of each element from its stretch, Newton).

The running resistance (DIN 22101's f on the weight of belt, material and rolls) is a
Coulomb force opposing the motion, regularised below 1 mm/s; while the belt runs forward it
is a constant load, which shifts the takeup but damps nothing. Gravity and the
counterweight balance the initial tension T0 in both strands and drop out (the belt starts
at rest at T0 everywhere, as the builder's design start at rest does).

The belt on the head drum is held there (``mu`` None) or slides on it (``mu`` the kinetic
coefficient: a node of its own, the friction between it and the drum a dashpot of
``slip_damping`` clipped at the capstan limit (e^(mu pi) - 1) T2, T2 the return's tension
at the drum).

Everything is numpy (eigenvalues and a fixed-step RK4), nothing from beltrs."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np


@dataclass
class Lumped:
    length: float  # m, centre to centre
    ea: float  # N, belt axial stiffness
    belt: float  # kg/m
    material: float  # kg/m on the carry
    carry_rolls: float  # kg/m, carry rolls' I/r^2 per pitch
    return_rolls: float  # kg/m
    takeup_mass: float  # kg, counterweight + tail pulley
    tail_inertia: float  # kg (J/r^2 of the tail pulley)
    drum_inertia: float  # kg ((J_rotor + J_drum)/r^2 of the head)
    kp: float  # N*s/m, the PI's proportional gain per metre of surface
    ki: float  # N/m
    f: float  # DIN 22101's f
    carry_roll_mass: float  # kg/m, the carry rolls' rotating mass (their weight loads the bearings)
    return_roll_mass: float  # kg/m
    tau: float = 0.0  # s, the belt's Kelvin-Voigt retardation time
    t0: float = 0.0  # N, the tension at rest (both strands)
    carry_pitch: float = 0.0  # m, the carry idlers' pitch (0: no sag)
    return_pitch: float = 0.0  # m
    # The belt on the head drum: None holds it there (no slip); a kinetic coefficient mu lets
    # it slide (capstan: |T1 - T2| <= (e^(mu pi) - 1) T2, a stick regularised by a dashpot
    # of slip_damping N*s/m between drum and belt).
    mu: float | None = None
    slip_damping: float = 5e6
    gravity: float = 9.81
    n: int = 30

    def _parts(self):
        """Transformation T (belt nodes from the coordinates), lumped belt masses, the element
        incidence (first node, second node, sag constant w^2 p^2/24 in N^2), resistances."""
        n, L = self.n, self.length
        le = L / n
        mc = self.belt + self.material + self.carry_rolls
        mr = self.belt + self.return_rolls
        dof = 3 + 2 * (n - 1) + (self.mu is not None)
        b = dof - 1 if self.mu is not None else 0  # the belt on the head drum
        # belt nodes: carry 0..n (tail to head), return 0..n (head to tail)
        T = np.zeros((2 * (n + 1), dof))
        T[0, 1], T[0, 2] = 1.0, -1.0  # carry's tail end: u - x
        T[n, b] = 1.0  # carry's head end: s (or the belt on the drum)
        T[n + 1, b] = 1.0  # return's head end
        T[2 * n + 1, 1], T[2 * n + 1, 2] = 1.0, 1.0  # return's tail end: u + x
        for i in range(1, n):
            T[i, 2 + i] = 1.0
            T[n + 1 + i, 2 + n - 1 + i] = 1.0
        mb = np.zeros(2 * (n + 1))
        mb[: n + 1] = mc * le
        mb[[0, n]] = mc * le / 2
        mb[n + 1:] = mr * le
        mb[[n + 1, 2 * n + 1]] = mr * le / 2
        g = self.gravity
        # the weight per metre hanging in a span between idlers: belt and material (carry)
        sag_c = ((self.belt + self.material) * g * self.carry_pitch) ** 2 / 24
        sag_r = (self.belt * g * self.return_pitch) ** 2 / 24
        a = np.array([i for i in range(n)] + [n + 1 + i for i in range(n)])
        sag = np.array([sag_c] * n + [sag_r] * n)
        wc = self.f * g * (self.belt + self.material + self.carry_roll_mass)
        wr = self.f * g * (self.belt + self.return_roll_mass)
        w = np.zeros(2 * (n + 1))
        w[: n + 1] = wc * le
        w[[0, n]] = wc * le / 2
        w[n + 1:] = wr * le
        w[[n + 1, 2 * n + 1]] = wr * le / 2
        return T, mb, a, sag, w

    def element_stiffness(self, tension):
        """Tangent axial stiffness (N/m) of an element of length L/n at ``tension``: the belt's
        EA in series with its spans' sag, chord shortening per metre w^2 p^2 / (24 T^2)
        (a parabolic span of pitch p under weight w per metre at tension T; d/dT gives the
        compliance w^2 p^2 / (12 T^3) per metre)."""
        _, _, _, sag, _ = self._parts()
        le = self.length / self.n
        return 1.0 / (le / self.ea + le * 2 * sag / np.asarray(tension) ** 3)

    def matrices(self, tension=None):
        """M, C, K (linearised about the element tensions ``tension``, default T0), T, w."""
        n = self.n
        T, mb, a, sag, w = self._parts()
        tension = np.full(2 * n, self.t0) if tension is None else np.asarray(tension)
        ke = self.element_stiffness(tension) if self.t0 > 0 else np.full(2 * n, self.ea * n / self.length)
        kb = np.zeros((2 * (n + 1), 2 * (n + 1)))
        cb = np.zeros_like(kb)
        for i, j in enumerate(a):
            kb[np.ix_([j, j + 1], [j, j + 1])] += ke[i] * np.array([[1, -1], [-1, 1]])
            cb[np.ix_([j, j + 1], [j, j + 1])] += self.tau * self.ea * n / self.length * np.array([[1, -1], [-1, 1]])
        M = T.T @ np.diag(mb) @ T
        M[0, 0] += self.drum_inertia
        M[1, 1] += self.tail_inertia
        M[2, 2] += self.takeup_mass
        K = T.T @ kb @ T
        C = T.T @ cb @ T
        K[0, 0] += self.ki
        C[0, 0] += self.kp
        return M, C, K, T, w

    def running_tensions(self):
        """The element tensions in steady running, quasi-statically: T0 at the tail on both
        strands (the gravity takeup), rising along the carry and falling back along the
        return towards the head by the running resistance."""
        n, le = self.n, self.length / self.n
        _, _, _, _, w = self._parts()
        g = self.gravity
        wc = self.f * g * (self.belt + self.material + self.carry_roll_mass)
        wr = self.f * g * (self.belt + self.return_roll_mass)
        x = (np.arange(n) + 0.5) * le
        return np.concatenate([self.t0 + wc * x, self.t0 - wr * (self.length - x)])

    def modes(self, tension=None):
        """(frequency Hz, damping ratio) of the modes below 3 Hz, lowest first, the drive's PI
        loop included (a spring K_i and a dashpot K_p to the reference), linearised about
        ``tension`` (default: :meth:`running_tensions`)."""
        held = replace(self, mu=None)
        M, C, K, _, _ = held.matrices(held.running_tensions() if tension is None else tension)
        d = M.shape[0]
        Mi = np.linalg.inv(M)
        A = np.block([[np.zeros((d, d)), np.eye(d)], [-Mi @ K, -Mi @ C]])
        lam = np.linalg.eigvals(A)
        lam = lam[lam.imag > 1e-6]
        out = sorted((abs(v) / (2 * np.pi), -v.real / abs(v)) for v in lam)
        return [m for m in out if m[0] < 3.0]

    def start(self, speed: float, ramp: float, duration: float, dt: float = 5e-4, every: int = 4):
        """Integrate a Harrison start (v = V/2 (1 - cos(pi t/ramp))) from rest at T0, the
        elements' tension from their stretch through the sag law (Newton per step). Returns
        a dict of arrays: time, travel (x, m), T1 and T2 (the strands' tensions at their
        head ends, N), drive (the PI's force on the drum, N; times the radius it is the drive
        torque's magnitude) and speed (the drum's surface speed)."""
        M, C, K, T, w = self.matrices()
        n, le = self.n, self.length / self.n
        _, _, a, sag, _ = self._parts()
        Mi = np.linalg.inv(M)
        d = M.shape[0]
        v_eps = 1e-3
        t0 = self.t0
        b = self.tau * self.ea / le
        state = {"T": np.full(2 * n, t0)}

        def tension(stretch):
            # stretch/le = (T - T0)/EA + 2 sag/le... : chord stretch = le [(T-T0)/EA + sag (1/T0^2 - 1/T^2)]
            tt = state["T"]
            for _ in range(30):
                g = le * ((tt - t0) / self.ea + sag * (1 / t0 ** 2 - 1 / tt ** 2)) - stretch
                dg = le * (1 / self.ea + 2 * sag / tt ** 3)
                step = g / dg
                tt = np.maximum(tt - step, 0.05 * t0)
                if np.max(np.abs(step)) < 1e-6:
                    break
            state["T"] = tt
            return tt

        def ref(t):
            if t >= ramp:
                return speed * (t - ramp / 2), speed
            return speed / 2 * (t - ramp / np.pi * np.sin(np.pi * t / ramp)), speed / 2 * (1 - np.cos(np.pi * t / ramp))

        def forces(t, y):
            q, v = y[:d], y[d:]
            xb, vb = T @ q, T @ v
            te = tension(xb[a + 1] - xb[a]) - t0 + b * (vb[a + 1] - vb[a])
            fb = -w * np.clip(vb / v_eps, -1.0, 1.0)
            np.add.at(fb, a, te)
            np.add.at(fb, a + 1, -te)
            f = T.T @ fb
            sr, vr = ref(t)
            drive = self.ki * (sr - q[0]) + self.kp * (vr - v[0])
            f[0] += drive
            if self.mu is not None:
                limit = (np.exp(self.mu * np.pi) - 1) * max(t0 + te[n], 0.0)
                ff = float(np.clip(self.slip_damping * (v[0] - v[-1]), -limit, limit))
                f[0] -= ff
                f[-1] += ff
            return f, te, drive

        def rhs(t, y):
            f, _, _ = forces(t, y)
            return np.concatenate([y[d:], Mi @ f])

        y = np.zeros(2 * d)
        steps = int(round(duration / dt))
        rec = {k: [] for k in ("time", "travel", "T1", "T2", "drive", "speed", "slip")}
        for k in range(steps + 1):
            t = k * dt
            if k % every == 0:
                _, te, drive = forces(t, y)
                rec["time"].append(t)
                rec["travel"].append(y[2])
                rec["T1"].append(t0 + te[n - 1])
                rec["T2"].append(t0 + te[n])
                rec["drive"].append(drive)
                rec["speed"].append(y[d])
                rec["slip"].append(y[-1] - y[d] if self.mu is not None else 0.0)
            k1 = rhs(t, y)
            k2 = rhs(t + dt / 2, y + dt / 2 * k1)
            k3 = rhs(t + dt / 2, y + dt / 2 * k2)
            k4 = rhs(t + dt, y + dt * k3)
            y = y + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        return {k: np.array(v) for k, v in rec.items()}


def from_scene(scene, length: float, speed_loop_inertia: float | None = None, n: int = 30,
               sag: bool = True, carry_pitch: float = 1.2, return_pitch: float = 3.0) -> Lumped:
    """The lumped model of a level two-pulley builder conveyor's ``scene`` (head drive with a
    PI controller, tail gravity takeup), ``length`` m centre to centre. The PI's gains are
    computed as the engine computes them (docs/drives.md, "Gains from physics": K_p =
    2 zeta omega_c J, K_i = omega_c^2 J) on ``speed_loop_inertia`` (kg*m^2), by default the
    rigid conveyor reflected to the drum: belt, material, rolls' I (r/r_k)^2, both pulleys
    and the drive's rotor."""
    tail = next(p for p in scene.pulleys if p.takeup is not None)
    head = next(p for p in scene.pulleys if p.drive is not None)
    r = head.radius
    carry = [i for i in scene.idlers if i.center[1] > -tail.radius]
    ret = [i for i in scene.idlers if i.center[1] <= -tail.radius]
    load = scene.loads[0]
    material = load.mass_per_length * (load.end[0] - load.start[0]) / length
    carry_rolls = sum(i.inertia / i.radius ** 2 for i in carry) / length
    return_rolls = sum(i.inertia / i.radius ** 2 for i in ret) / length
    loop = 2 * length + 2 * np.pi * r
    drum = (head.drive.inertia + head.inertia) / r ** 2
    if speed_loop_inertia is None:
        rigid = (scene.belt.mass_per_length * loop + material * length + (carry_rolls + return_rolls) * length
                 + tail.inertia / tail.radius ** 2 + drum)
        speed_loop_inertia = rigid * r ** 2
    c = head.drive.controller
    kp = 2 * c.damping_ratio * c.bandwidth * speed_loop_inertia / r ** 2
    ki = c.bandwidth ** 2 * speed_loop_inertia / r ** 2
    le = loop / scene.belt.elements
    tau = 2 * scene.belt.damping_ratio * np.sqrt(scene.belt.axial_stiffness / le * scene.belt.mass_per_length * le) \
        * le / scene.belt.axial_stiffness
    return Lumped(length=length, ea=scene.belt.axial_stiffness, belt=scene.belt.mass_per_length, material=material,
                  carry_rolls=carry_rolls, return_rolls=return_rolls,
                  takeup_mass=tail.takeup.counterweight + tail.mass, tail_inertia=tail.inertia / tail.radius ** 2,
                  drum_inertia=drum, kp=kp, ki=ki, f=carry[0].resistance,
                  carry_roll_mass=sum(i.rotating_mass for i in carry) / length,
                  return_roll_mass=sum(i.rotating_mass for i in ret) / length, tau=tau, n=n,
                  t0=scene.initial.tension[0] if sag and scene.initial.tension else 0.0,
                  carry_pitch=carry_pitch if sag else 0.0, return_pitch=return_pitch if sag else 0.0)


def fit_swing(t, y, lo: float, hi: float):
    """Frequency (Hz) and amplitude of the strongest sinusoid between 0.3 and 1.2 Hz in ``y``
    over ``lo``..``hi`` s (a linear trend removed; least squares on a 0.5 mHz grid)."""
    w = (t >= lo) & (t <= hi)
    tt, yy = t[w], y[w]
    yy = yy - np.polyval(np.polyfit(tt, yy, 1), tt)
    best = None
    for f in np.arange(0.3, 1.2, 0.0005):
        X = np.column_stack([np.sin(2 * np.pi * f * tt), np.cos(2 * np.pi * f * tt)])
        c = np.linalg.lstsq(X, yy, rcond=None)[0]
        r = float(((yy - X @ c) ** 2).sum())
        if best is None or r < best[0]:
            best = (r, f, float(np.hypot(*c)))
    return best[1], best[2]

"""A plain NumPy implementation of beltrs' node model, for comparison (not part of the package).

Hustrulid's node model as a Python user would write it with NumPy: whole-array
operations, no loops over nodes. Kelvin-Voigt axial elements (thesis eq. 4.40, 4.56),
rotational bending springs ½k_θθ² (eq. 4.11), gravity (eq. 4.49), nodal penalty contact
with pulleys (eq. 4.70-4.75, every node tested against every pulley), gravity takeups, and
central differences (eq. 4.59-4.60), in the same order of operations as beltrs' stepper.
Frictionless: there is no stick-force friction, drive or idler here.

    python benches/numpy_ref.py      # speed against beltrs on case H and a 1e4-node loop

:meth:`NumpyBelt.from_simulation` copies a beltrs simulation's model and state, so both can
be stepped from the same point and compared (``tests/test_numpy_ref.py``).
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, field

import numpy as np

import beltrs


@dataclass
class NumpyPulley:
    """A pulley: ``center0`` m (initial centre), ``radius`` m, ``stiffness`` N/m,
    ``damping`` N*s/m; with ``direction`` (unit vector) it is a takeup of ``moving_mass``
    kg pulled along it by ``pull`` N."""

    center0: np.ndarray
    radius: float
    stiffness: float
    damping: float = 0.0
    direction: np.ndarray | None = None
    moving_mass: float = np.inf
    pull: float = 0.0
    travel: float = 0.0
    speed: float = 0.0

    def center(self) -> np.ndarray:
        return self.center0 if self.direction is None else self.center0 + self.travel * self.direction

    def center_velocity(self) -> np.ndarray:
        return np.zeros(2) if self.direction is None else self.speed * self.direction


@dataclass
class NumpyBelt:
    """State and parameters of a closed belt of n nodes (element e joins e and e+1).

    Arrays: ``x``, ``v`` [n, 2] m, m/s (v at the half step); ``mass`` [n] kg; ``k`` [n] N/m;
    ``c`` [n] N*s/m; ``l0`` [n] m; ``kb`` [n] N*m/rad; ``gravity`` m/s^2; ``dt`` s."""

    x: np.ndarray
    v: np.ndarray
    mass: np.ndarray
    k: np.ndarray
    c: np.ndarray
    l0: np.ndarray
    kb: np.ndarray
    gravity: float
    dt: float
    pulleys: list[NumpyPulley] = field(default_factory=list)

    @classmethod
    def from_simulation(cls, sim) -> "NumpyBelt":
        """Copy a :class:`beltrs.Simulation` (node model, frictionless) and its state."""
        scene = sim.scene
        belt = scene.belt
        st = sim.state()
        l0 = np.asarray(sim.rest_length, dtype=float)
        m = np.asarray(sim.node_mass, dtype=float)
        k = belt.axial_stiffness / l0
        m_el = belt.mass_per_length * l0
        c = 2.0 * m_el * belt.damping_ratio * np.sqrt(k / m_el)
        pulleys = []
        for j, p in enumerate(scene.pulleys):
            if p.friction is not None or p.drive is not None or p.brake is not None:
                raise ValueError(f"pulleys[{j}]: the NumPy reference has no friction, drive or brake")
            # The engine's rule (docs/belt-drives.md): absolute if given, else 2 zeta sqrt(k m).
            if p.contact_damping is not None:
                damping = p.contact_damping
            else:
                zeta = p.contact_damping_ratio
                if zeta is None:
                    zeta = beltrs.DEFAULT_CONTACT_DAMPING_RATIO
                damping = 2.0 * zeta * math.sqrt(p.contact_stiffness * m_el[0])
            q = NumpyPulley(np.array(p.center, dtype=float), p.radius, p.contact_stiffness, damping)
            if p.takeup is not None:
                d = np.array(p.takeup.direction, dtype=float)
                d /= np.hypot(*d)
                q.direction = d
                q.moving_mass = p.mass + p.takeup.counterweight
                q.pull = p.takeup.counterweight * scene.gravity - p.mass * scene.gravity * d[1]
                q.travel = float(st["takeup_travel"][j])
                q.speed = float(st["takeup_speed"][j])
            pulleys.append(q)
        if scene.idlers:
            raise ValueError("the NumPy reference has no idlers")
        return cls(
            x=np.array(st["node_position"], dtype=float),
            v=np.array(st["node_velocity_half_step"], dtype=float),
            mass=m,
            k=k,
            c=c,
            l0=l0,
            kb=np.full(len(l0), belt.bending_stiffness) / l0,
            gravity=scene.gravity,
            dt=sim.dt,
            pulleys=pulleys,
        )

    def forces(self) -> tuple[np.ndarray, list[np.ndarray]]:
        """Net node forces [n, 2] N and the resultant belt force on each pulley."""
        x, v = self.x, self.v
        f = np.zeros_like(x)
        f[:, 1] -= self.mass * self.gravity
        # Axial: T = k (l - l0) + c dl/dt along each element.
        d = np.roll(x, -1, axis=0) - x
        length = np.hypot(d[:, 0], d[:, 1])
        t = self.k * (length - self.l0)
        if np.any(self.c):
            rate = np.einsum("ij,ij->i", np.roll(v, -1, axis=0) - v, d) / length
            t = t + self.c * rate
        fe = d * (t / length)[:, None]
        f += fe - np.roll(fe, 1, axis=0)
        # Bending: theta_j = angle from element j-1 to element j.
        if np.any(self.kb):
            a = np.roll(d, 1, axis=0)
            b = d
            cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
            dot = np.einsum("ij,ij->i", a, b)
            moment = self.kb * np.arctan2(cross, dot)
            ga = np.stack([-a[:, 1], a[:, 0]], axis=1) * (moment / np.einsum("ij,ij->i", a, a))[:, None]
            gb = np.stack([-b[:, 1], b[:, 0]], axis=1) * (moment / np.einsum("ij,ij->i", b, b))[:, None]
            f += ga + gb - np.roll(gb, 1, axis=0) - np.roll(ga, -1, axis=0)
        # Nodal penalty contact: every node against every pulley.
        on_pulley = []
        for p in self.pulleys:
            rel = x - p.center()
            dist = np.hypot(rel[:, 0], rel[:, 1])
            inside = dist < p.radius
            normal = rel[inside] / dist[inside, None]
            approach = -np.einsum("ij,ij->i", v[inside] - p.center_velocity(), normal)
            fn = np.maximum(p.stiffness * (p.radius - dist[inside]) + p.damping * approach, 0.0)
            fc = normal * fn[:, None]
            f[inside] += fc
            on_pulley.append(-fc.sum(axis=0))
        return f, on_pulley

    def step(self, steps: int = 1) -> None:
        """Central differences: v(n+1/2) = v(n-1/2) + dt f/m, x(n+1) = x(n) + dt v(n+1/2)."""
        dt = self.dt
        inv_m = (dt / self.mass)[:, None]
        for _ in range(steps):
            f, on_pulley = self.forces()
            self.v += f * inv_m
            self.x += self.v * dt
            for p, fp in zip(self.pulleys, on_pulley):
                if p.direction is not None:
                    p.speed += dt * (p.direction @ fp + p.pull) / p.moving_mass
                    p.travel += dt * p.speed


def compare_speed(sim, steps: int) -> dict[str, float]:
    """node-steps/s of beltrs and of the NumPy reference stepping the same state."""
    ref = NumpyBelt.from_simulation(sim)
    ref.step(10)  # warm-up
    t0 = time.perf_counter()
    ref.step(steps)
    numpy_wall = time.perf_counter() - t0
    beltrs_steps = steps * 20
    sim.step(100)
    t0 = time.perf_counter()
    sim.step(beltrs_steps)
    beltrs_wall = time.perf_counter() - t0
    n = sim.nodes
    out = {
        "nodes": n,
        "numpy_node_steps_per_s": n * steps / numpy_wall,
        "beltrs_node_steps_per_s": n * beltrs_steps / beltrs_wall,
    }
    out["ratio"] = out["beltrs_node_steps_per_s"] / out["numpy_node_steps_per_s"]
    return out


def main() -> int:
    import beltrs

    sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parent))
    from bench_scenes import conveyor

    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop(89))
    sim.stabilise()
    r = compare_speed(sim, 2000)
    print(f"case H, 89 nodes: beltrs {r['beltrs_node_steps_per_s']:.3g}, NumPy {r['numpy_node_steps_per_s']:.3g} "
          f"node-steps/s: {r['ratio']:.0f}x")
    scene = conveyor(1000.0, 10_000, friction=None, drive_torque=0.0)
    scene.idlers = []
    sim = beltrs.Simulation(scene)
    r = compare_speed(sim, 200)
    print(f"frictionless loop, 1e4 nodes: beltrs {r['beltrs_node_steps_per_s']:.3g}, NumPy "
          f"{r['numpy_node_steps_per_s']:.3g} node-steps/s: {r['ratio']:.0f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""The compiled model of a scene, read-only: the stages it runs and its time step.

Compiling a scene (validating it, placing the belt on its path, estimating the stable time
step and choosing the stages it needs) is done by the engine once, in
``rust/src/model/``. :func:`compile` and :attr:`beltrs.Simulation.model` give a snapshot
of the result; nothing here recomputes it.

>>> model = beltrs.compile(beltrs.scenes.hustrulid_loop())
>>> model.stages
('axial', 'bending', 'pulley_contact')
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from . import _beltrs
from .scene import Scene

__all__ = ["Model", "compile"]


def _read_only(values: Any) -> np.ndarray:
    a = np.array(values, dtype=float)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class Model:
    """A compiled scene (a snapshot: it does not change when the simulation goes on).

    Attributes:
        scene: the scene it was compiled from.
        stages: the stages one step runs, in order (``"loads"``, ``"axial"`` or
            ``"axial_damped"``, ``"bending"``, ``"pulley_contact"``, ``"idler_contact"``,
            ``"running_resistance"``, ``"drives"``, ``"bearing_drag"``,
            ``"motors"``, ``"speed_control"``, ``"pulley_friction"``, ``"idler_friction"``,
            ``"speed_drives"``, ``"brakes"``).
            An effect the scene does not use is absent and costs nothing: ``axial``
            instead of ``axial_damped`` when the damping ratio is 0, no ``bending`` when
            EI = 0, no ``pulley_contact`` when every pulley's contact stiffness is 0, no
            ``idler_contact`` without idlers, no friction stage when every µs is 0, no
            ``drives``, ``bearing_drag`` or ``brakes`` without them (``docs/effects.md``).
            The node weights (gravity) are part of the axial pass, and takeups move with
            the integrator: neither is a stage.
        dt: time step in use, s.
        dt_limit: estimated explicit stability limit of the time step, s.
        dt_cause: the stiffest term, which sets ``dt_limit``.
        nodes: number of belt nodes (= elements; the belt is a closed loop).
        path_length: length of the initial belt path, m.
        wrap_angles: wrap angle on each pulley on the initial path, rad.
        rest_length: element rest lengths, m, shape ``[E]`` (read-only).
        node_mass: node masses, kg, shape ``[E]`` (read-only).
        controllers: per pulley, its compiled PI speed controller as a dict (``inertia``
            kg*m^2 the gains are tuned on, ``proportional_gain`` N*m*s/rad,
            ``integral_gain`` N*m/rad, ``droop`` rad/s per N*m), or None
            (``docs/drives.md``).
    """

    scene: Scene
    stages: tuple[str, ...]
    dt: float
    dt_limit: float
    dt_cause: str
    nodes: int
    path_length: float
    wrap_angles: tuple[float, ...]
    rest_length: np.ndarray
    node_mass: np.ndarray
    controllers: tuple[Any, ...] = ()

    @classmethod
    def _from_core(cls, core: Any, scene: Scene) -> "Model":
        return cls(
            scene=scene,
            stages=tuple(core.stages),
            dt=float(core.dt),
            dt_limit=float(core.dt_limit),
            dt_cause=str(core.dt_cause),
            nodes=int(core.nodes),
            path_length=float(core.path_length),
            wrap_angles=tuple(float(w) for w in core.wrap_angles),
            rest_length=_read_only(core.rest_length),
            node_mass=_read_only(core.node_mass),
            controllers=tuple(
                None if c is None else dict(zip(("inertia", "proportional_gain", "integral_gain", "droop"), c))
                for c in core.controllers
            ),
        )

    def has_stage(self, name: str) -> bool:
        """True if one step runs the stage ``name``."""
        return name in self.stages


def compile(scene: Scene) -> Model:  # noqa: A001 - the issue's name; not in beltrs.__all__
    """Validate and compile ``scene`` without keeping a simulation.

    The same compilation as :class:`beltrs.Simulation` (``sim.model`` gives the same
    snapshot for a running simulation).

    Raises:
        beltrs.SceneError: an invalid scene (the message names the field, the value and the
            rule).
        beltrs.TimeStepError: ``solver.time_step`` above the stability limit.
    """
    return Model._from_core(_beltrs.Simulation(scene.to_dict()), scene)

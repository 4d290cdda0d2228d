"""Results of a run: NumPy arrays with documented shapes and SI units."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

__all__ = ["Result"]


@dataclass
class Result:
    """Arrays recorded by :meth:`beltrs.Simulation.run`.

    ``n`` = recorded instants, ``E`` = elements (= nodes), ``P`` = pulleys, ``I`` = idlers.
    Element ``e`` joins node ``e`` to node ``e + 1`` (the last closes the loop).

    Attributes:
        time: ``[n]`` simulated time, s.
        tension: ``[n, E]`` element force (Kelvin-Voigt: spring + dashpot), N; None if not
            recorded.
        node_position: ``[n, E, 2]`` node positions, m; None if not recorded.
        node_velocity: ``[n, E, 2]`` node velocities (centred on ``time``), m/s; None if not
            recorded.
        pulley_position: ``[n, P, 2]`` pulley centres, m.
        takeup_travel: ``[n, P]`` takeup travel along its pull direction from the initial
            centre, m (0 for fixed pulleys; positive = towards the counterweight).
        pulley_speed: ``[n, P]`` angular speed, rad/s, counter-clockwise positive.
        friction_torque: ``[n, P]`` torque of belt friction on the pulley, N*m.
        drive_torque: ``[n, P]`` drive torque, N*m.
        brake_torque: ``[n, P]`` brake torque, N*m.
        pulley_force: ``[n, P, 2]`` resultant belt force (contact + friction) on the pulley, N.
        normal_force: ``[n, P]`` sum of nodal normal contact forces, N.
        friction_force: ``[n, P]`` sum of tangential friction forces on the pulley, N.
        contact_nodes: ``[n, P]`` nodes touching each pulley.
        slipping_nodes: ``[n, P]`` of those, nodes slipping.
        idler_force: ``[n, I]`` idler normal force, N.
        idler_speed: ``[n, I]`` idler angular speed, rad/s.
        energy: ``[n, 7]`` J; columns in ``energy_columns``: kinetic, strain, bending,
            gravity, contact, total (sum of the first five), drive_work.
        dt: time step, s.
        stages: compiled stages.
        wall_time: wall-clock seconds of the run.
        interrupted: True if stopped by Ctrl-C (the arrays hold everything recorded until then).
        pulley_names: names of the pulleys.
        record_every: steps between recorded instants at the end of the run: the requested
            interval, doubled each time the recording reached its bound (``max_samples``)
            and dropped every other instant.
        checkpoint_error: the last :class:`beltrs.CheckpointError` of a periodic or final
            checkpoint that could not be written (the run went on), else None.
    """

    time: np.ndarray
    tension: Optional[np.ndarray]
    node_position: Optional[np.ndarray]
    node_velocity: Optional[np.ndarray]
    pulley_position: np.ndarray
    takeup_travel: np.ndarray
    pulley_speed: np.ndarray
    friction_torque: np.ndarray
    drive_torque: np.ndarray
    brake_torque: np.ndarray
    pulley_force: np.ndarray
    normal_force: np.ndarray
    friction_force: np.ndarray
    contact_nodes: np.ndarray
    slipping_nodes: np.ndarray
    idler_force: np.ndarray
    idler_speed: np.ndarray
    energy: np.ndarray
    energy_columns: list[str]
    dt: float = 0.0
    stages: list[str] = field(default_factory=list)
    wall_time: float = 0.0
    interrupted: bool = False
    pulley_names: list[str] = field(default_factory=list)
    record_every: int = 1
    checkpoint_error: Optional[BaseException] = None

    @classmethod
    def _from_core(cls, rec: dict[str, Any], **meta: Any) -> "Result":
        return cls(
            time=rec["time"],
            tension=rec.get("tension"),
            node_position=rec.get("node_position"),
            node_velocity=rec.get("node_velocity"),
            pulley_position=rec["pulley_position"],
            takeup_travel=rec["takeup_travel"],
            pulley_speed=rec["pulley_speed"],
            friction_torque=rec["friction_torque"],
            drive_torque=rec["drive_torque"],
            brake_torque=rec["brake_torque"],
            pulley_force=rec["pulley_force"],
            normal_force=rec["normal_force"],
            friction_force=rec["friction_force"],
            contact_nodes=rec["contact_nodes"],
            slipping_nodes=rec["slipping_nodes"],
            idler_force=rec["idler_force"],
            idler_speed=rec["idler_speed"],
            energy=rec["energy"],
            energy_columns=list(rec["energy_columns"]),
            **meta,
        )

    def energy_of(self, name: str) -> np.ndarray:
        """One energy column by name (``"kinetic"``, ``"total"``, ...), J, shape ``[n]``."""
        return self.energy[:, self.energy_columns.index(name)]

    def __len__(self) -> int:
        return int(self.time.shape[0])

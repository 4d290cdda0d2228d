"""Results of a run: NumPy arrays with documented shapes and SI units, that travel.

A :class:`Result` saves to NPZ (``Result.save("run.npz")``, readable with plain
``numpy.load`` and no pickle) or netCDF (``.nc``, through xarray), loads back with
:func:`load_result` bit for bit, and gives labelled views: :meth:`Result.to_xarray` (named
dimensions ``time``, ``element``, ``node``, ``pulley``, ``idler``, ``axis``, ``energy_term``,
units as attributes) and :meth:`Result.to_pandas` (the per-pulley time series). xarray and
pandas are optional; without them those two methods raise :class:`beltrs.BeltrsError`
saying what to install. File format: ``docs/results.md``.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any, Optional, Union

import numpy as np

from . import _beltrs

__all__ = ["FORMAT", "UNITS", "DIMS", "Capstan", "ContactProfile", "Result", "load_result"]

#: Format tag written into every saved result (NPZ key / netCDF attribute ``beltrs_format``).
FORMAT = "beltrs-result/1"

#: Unit of every array channel (UDUNITS spelling; ``"1"`` = a count or a pure number).
UNITS: dict[str, str] = {
    "time": "s",
    "tension": "N",
    "node_position": "m",
    "node_velocity": "m/s",
    "pulley_position": "m",
    "takeup_travel": "m",
    "pulley_speed": "rad/s",
    "friction_torque": "N*m",
    "drive_torque": "N*m",
    "brake_torque": "N*m",
    "pulley_force": "N",
    "normal_force": "N",
    "friction_force": "N",
    "contact_nodes": "1",
    "slipping_nodes": "1",
    "motor_speed": "rad/s",
    "idler_force": "N",
    "idler_speed": "rad/s",
    "energy": "J",
    "contact_normal": "N",
    "contact_friction": "N",
    "contact_angle": "rad",
    "drive_power": "W",
}

#: Named dimensions of every array channel.
DIMS: dict[str, tuple[str, ...]] = {
    "time": ("time",),
    "tension": ("time", "element"),
    "node_position": ("time", "node", "axis"),
    "node_velocity": ("time", "node", "axis"),
    "pulley_position": ("time", "pulley", "axis"),
    "takeup_travel": ("time", "pulley"),
    "pulley_speed": ("time", "pulley"),
    "friction_torque": ("time", "pulley"),
    "drive_torque": ("time", "pulley"),
    "brake_torque": ("time", "pulley"),
    "pulley_force": ("time", "pulley", "axis"),
    "normal_force": ("time", "pulley"),
    "friction_force": ("time", "pulley"),
    "contact_nodes": ("time", "pulley"),
    "slipping_nodes": ("time", "pulley"),
    "motor_speed": ("time", "pulley"),
    "idler_force": ("time", "idler"),
    "idler_speed": ("time", "idler"),
    "energy": ("time", "energy_term"),
    "contact_normal": ("time", "pulley", "node"),
    "contact_friction": ("time", "pulley", "node"),
    "contact_angle": ("time", "pulley", "node"),
}

_DESCRIPTION: dict[str, str] = {
    "time": "simulated time",
    "tension": "element force (Kelvin-Voigt: spring + dashpot); element e joins node e to node e+1",
    "node_position": "node position",
    "node_velocity": "node velocity (centred on time)",
    "pulley_position": "pulley centre",
    "takeup_travel": "takeup travel along its pull direction from the initial centre (+ = towards the counterweight)",
    "pulley_speed": "pulley angular speed, counter-clockwise positive",
    "friction_torque": "torque of belt friction on the pulley",
    "drive_torque": "drive torque on the pulley",
    "brake_torque": "brake torque on the pulley",
    "pulley_force": "resultant belt force (contact + friction) on the pulley",
    "normal_force": "sum of nodal normal contact forces on the pulley",
    "friction_force": "sum of tangential friction forces on the pulley",
    "contact_nodes": "belt nodes touching the pulley",
    "slipping_nodes": "belt nodes slipping on the pulley",
    "motor_speed": "DOL motor speed at its shaft, in the motor's sense of rotation (NaN: no motor)",
    "idler_force": "idler normal force",
    "idler_speed": "idler angular speed",
    "energy": "energies (terms: coordinate energy_term)",
    "contact_normal": "normal contact force of the pulley on the belt point (0 off the pulley)",
    "contact_friction": (
        "friction force of the belt point on the pulley along its counter-clockwise tangent (0 off the pulley)"
    ),
    "contact_angle": (
        "angle of the belt point about the pulley centre, counter-clockwise from +x (NaN off the pulley)"
    ),
    "drive_power": "drive power = drive_torque * pulley_speed",
}

#: Channels holding counts: integers in memory and on disk.
_COUNTS = ("contact_nodes", "slipping_nodes")
#: The per-pulley time series of :meth:`Result.to_pandas`, in column order.
PULLEY_SERIES = (
    "takeup_travel",
    "pulley_speed",
    "drive_torque",
    "drive_power",
    "brake_torque",
    "friction_torque",
    "normal_force",
    "friction_force",
    "contact_nodes",
    "slipping_nodes",
    "motor_speed",
)
#: Scalar attributes of a Result and their types, saved beside the arrays.
_SCALARS = {
    "dt": float,
    "wall_time": float,
    "interrupted": bool,
    "record_every": int,
    "steps_accepted": int,
    "steps_rejected": int,
}
_LISTS = ("energy_columns", "stages", "pulley_names")
_DESCRIPTORS = ("beltrs_format", "units", "dims", "metadata_types")
#: Fields that ``Result.__eq__`` leaves out: how the run went, not what it computed.
_NOT_COMPARED = ("wall_time", "checkpoint_error")


def _require(module: str, what: str) -> Any:
    """Import an optional dependency or raise a BeltrsError saying how to get it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError:
        raise _beltrs.BeltrsError(
            f"{what} needs the optional package {module!r}: pip install {module} "
            f"(or pip install 'beltrs[test]', which brings xarray and pandas)"
        ) from None


@dataclass
class Result:
    """Arrays recorded by :meth:`beltrs.Simulation.run`.

    ``n`` = recorded instants, ``E`` = elements (= nodes), ``P`` = pulleys, ``I`` = idlers.
    Element ``e`` joins node ``e`` to node ``e + 1`` (the last closes the loop).

    Attributes:
        time: ``[n]`` simulated time, s. The last instant is the end of the run.
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
        contact_nodes: ``[n, P]`` nodes touching each pulley (int64 count).
        slipping_nodes: ``[n, P]`` of those, nodes slipping (int64 count).
        motor_speed: ``[n, P]`` speed of each pulley's DOL motor (:class:`beltrs.Motor`)
            at the motor shaft, rad/s, positive in the motor's sense of rotation
            (``rotation``): the pulley speed times ``gear_ratio`` when geared rigidly, the
            rotor's own speed behind a :class:`beltrs.FluidCoupling` (their difference is
            the coupling's slip). NaN for pulleys without a motor; None in results saved
            before beltrs recorded it.
        idler_force: ``[n, I]`` idler normal force, N.
        idler_speed: ``[n, I]`` idler angular speed, rad/s.
        energy: ``[n, 7]`` J, or None unless the run asked for it (``energy=True``);
            columns in ``energy_columns``: kinetic, strain, bending, gravity, contact, total
            (sum of the first five), drive_work.
        contact_normal: ``[n, P, E]`` normal contact force of pulley j on belt point i (a
            node, or a rigid body's mass centre), N, >= 0; 0 where the point does not touch
            the pulley. ``contact_normal.sum(axis=2)`` is ``normal_force``. None unless the
            run asked for it (``contact_forces=True``).
        contact_friction: ``[n, P, E]`` friction force of belt point i on pulley j, N, along
            the pulley's counter-clockwise tangent at the point (the belt feels the
            opposite); 0 where the point does not touch the pulley or no friction acts.
            ``contact_friction.sum(axis=2)`` is ``friction_force``. None unless recorded.
        contact_angle: ``[n, P, E]`` angle of belt point i about the centre of pulley j,
            rad, counter-clockwise from +x, in (-pi, pi]; NaN where the point does not
            touch the pulley. None unless recorded. :meth:`contact_profile` turns the three
            into forces by wrap angle along the direction of travel.
        dt: time step, s.
        stages: compiled stages.
        wall_time: wall-clock seconds of the run.
        interrupted: True if stopped by Ctrl-C (the arrays hold everything recorded until then).
        pulley_names: names of the pulleys.
        record_every: steps between recorded instants at the end of the run: the requested
            interval, doubled each time the recording reached its bound (``max_samples``)
            and dropped every other instant. The last instant (the end of the run) may
            follow the one before it after fewer steps.
        metadata: free-form facts saved with the result (``beltrs run`` stores the scene
            as TOML, the beltrs version, the date, relaxation figures, ...): str, bool,
            int, float, lists of str, or NumPy arrays. Default empty.
        checkpoint_error: the last :class:`beltrs.CheckpointError` of a periodic or final
            checkpoint that could not be written (the run went on), else None.
        steps_accepted, steps_rejected: steps the adaptive integrator
            (``Solver(integrator="rkf45")``) accepted and rejected during the run (each
            rejected step was retried smaller); 0 with central differences.
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
    energy: Optional[np.ndarray]
    energy_columns: list[str]
    motor_speed: Optional[np.ndarray] = None
    dt: float = 0.0
    stages: list[str] = field(default_factory=list)
    wall_time: float = 0.0
    interrupted: bool = False
    pulley_names: list[str] = field(default_factory=list)
    record_every: int = 1
    metadata: dict[str, Any] = field(default_factory=dict)
    checkpoint_error: Optional[BaseException] = None
    steps_accepted: int = 0
    steps_rejected: int = 0
    contact_normal: Optional[np.ndarray] = None
    contact_friction: Optional[np.ndarray] = None
    contact_angle: Optional[np.ndarray] = None

    @classmethod
    def _from_core(cls, rec: dict[str, Any], **meta: Any) -> "Result":
        arrays = {name: rec.get(name) for name in DIMS}
        for name in _COUNTS:
            # Counts are whole numbers by construction; the engine hands them over as f64.
            arrays[name] = np.asarray(arrays[name]).astype(np.int64)
        return cls(**arrays, energy_columns=list(rec["energy_columns"]), **meta)

    # --- access ------------------------------------------------------------------------
    def energy_of(self, name: str) -> np.ndarray:
        """One energy column by name (``"kinetic"``, ``"total"``, ...), J, shape ``[n]``.

        Raises:
            beltrs.BeltrsError: the run did not record energies (``run(..., energy=True)``),
                or ``name`` is not one of ``energy_columns``.
        """
        from . import _beltrs

        if self.energy is None:
            raise _beltrs.BeltrsError("energy: not recorded; run with energy=True to record the energies")
        if name not in self.energy_columns:
            raise _beltrs.BeltrsError(f"energy column {name!r}: unknown (known: {', '.join(self.energy_columns)})")
        return self.energy[:, self.energy_columns.index(name)]

    @property
    def drive_power(self) -> np.ndarray:
        """``[n, P]`` power the drives deliver to the pulleys, W: ``drive_torque *
        pulley_speed`` (positive when the drive drives, negative when it holds back)."""
        return self.drive_torque * self.pulley_speed

    # --- engineering views: signs along the belt's direction of travel ------------------
    # The engine's pulley quantities are counter-clockwise positive. These views turn them
    # into what a conveyor engineer reads: speeds along the belt's direction of travel,
    # drive torque positive when it drives the belt that way, power in kW positive when the
    # drive delivers it, takeup travel from the start of the run, and the capstan
    # utilisation of each pulley. Each is computed from the recorded arrays and constants
    # that every Result of Simulation.run carries in its metadata: ``pulley_radius`` (m),
    # ``pulley_wrap_sign`` (+1 where the belt wraps counter-clockwise in node order, -1
    # clockwise), ``pulley_friction_static`` (mu_s, 0 without friction) and
    # ``travel_direction`` (+1: the belt travels in node order, -1: against it, 0: not
    # known from the scene, then taken from the run).

    def _pulley_constant(self, key: str, what: str) -> np.ndarray:
        value = self.metadata.get(key)
        if value is None:
            raise _beltrs.BeltrsError(
                f"{what}: this Result has no metadata[{key!r}] (a result saved by an older beltrs, or "
                f"built by hand); run the scene again, or set metadata[{key!r}] to one value per pulley"
            )
        value = np.asarray(value, dtype=float)
        if value.shape != (self.pulley_speed.shape[1],):
            raise _beltrs.BeltrsError(
                f"{what}: metadata[{key!r}] has shape {value.shape}, expected one value per pulley "
                f"({self.pulley_speed.shape[1]})"
            )
        return value

    def _node_order_speed(self) -> Optional[np.ndarray]:
        """``[n]`` mean belt speed in node order, m/s (None without node velocities)."""
        if self.node_position is None or self.node_velocity is None:
            return None
        x, v = self.node_position, self.node_velocity
        chord = np.roll(x, -1, axis=1) - x
        length = np.linalg.norm(chord, axis=2)
        along = np.einsum("tek,tek->te", 0.5 * (v + np.roll(v, -1, axis=1)), chord) / np.where(length > 0, length, 1)
        rest = self.metadata.get("rest_length")
        weight = np.asarray(rest, dtype=float) if rest is not None and np.shape(rest) == (x.shape[1],) else length
        return (along * weight).sum(axis=-1) / weight.sum(axis=-1)

    @property
    def travel_direction(self) -> int:
        """+1 if the belt's direction of travel is node order, -1 if against it.

        From the scene when it says (``metadata["travel_direction"]``, set by
        :meth:`beltrs.Simulation.run`: the direction the loads carry material, loading
        point to discharge point, else the direction the speed-controlled drives' starting
        curves run the belt); otherwise the direction the belt ran fastest in this run (its
        mean speed in node order, or the pulleys' surface speeds without node velocities);
        +1 if it never moved."""
        given = self.metadata.get("travel_direction")
        if given in (1, -1):
            return int(given)
        speed = self._node_order_speed()
        if speed is None:
            wrap = self._pulley_constant("pulley_wrap_sign", "travel_direction")
            radius = self._pulley_constant("pulley_radius", "travel_direction")
            surface = self.pulley_speed * (wrap * radius)
            speed = surface.ravel()
        if speed.size == 0 or not np.any(speed != 0):
            return 1
        return 1 if speed.ravel()[int(np.argmax(np.abs(speed.ravel())))] > 0 else -1

    def _travel_sign(self, what: str) -> np.ndarray:
        """``[P]`` the sign that turns a counter-clockwise-positive pulley quantity into one
        along the belt's direction of travel."""
        return self._pulley_constant("pulley_wrap_sign", what) * self.travel_direction

    @property
    def surface_speed(self) -> np.ndarray:
        """``[n, P]`` surface speed of each pulley along the belt's direction of travel, m/s
        (counter-clockwise ``pulley_speed`` times radius, signed by the wrap and
        :attr:`travel_direction`). At a drive it is the belt speed there (plus creep,
        docs/belt-drives.md)."""
        return self.pulley_speed * (self._travel_sign("surface_speed") * self._pulley_constant(
            "pulley_radius", "surface_speed"))

    @property
    def belt_speed(self) -> np.ndarray:
        """``[n]`` mean speed of the belt along its direction of travel, m/s: each element's
        mean node velocity projected on the element, averaged over the belt weighted by the
        rest lengths. Needs ``node_position`` and ``node_velocity``.

        Raises:
            beltrs.BeltrsError: node positions or velocities were not recorded.
        """
        speed = self._node_order_speed()
        if speed is None:
            raise _beltrs.BeltrsError(
                "belt_speed: needs node_position and node_velocity (recorded by default; use "
                "surface_speed for the speed at each pulley)"
            )
        return speed * self.travel_direction

    @property
    def driving_torque(self) -> np.ndarray:
        """``[n, P]`` drive torque, N*m, positive when it drives the belt along its direction
        of travel (negative when it holds the belt back, e.g. regenerating on a decline)."""
        return self.drive_torque * self._travel_sign("driving_torque")

    @property
    def drive_power_kw(self) -> np.ndarray:
        """``[n, P]`` drive power, kW, positive when the drive delivers power (drives),
        negative when it absorbs it (regenerates): ``drive_torque * pulley_speed / 1000``."""
        return self.drive_power / 1e3

    @property
    def takeup_travel_from_start(self) -> np.ndarray:
        """``[n, P]`` takeup travel since the start of the run (the first recorded instant),
        m, positive towards the counterweight (``takeup_travel`` counts from the scene's
        initial centre, so after ``stabilise()`` it does not start at 0)."""
        return self.takeup_travel - self.takeup_travel[:1]

    def capstan(self, friction: Optional[Union[float, np.ndarray]] = None) -> "Capstan":
        """The capstan (Euler–Eytelwein) state of every pulley at every recorded instant.

        At each instant and pulley, the belt's contact arc is the longest run of nodes inside
        the pulley (closer to its centre than its radius, as the contact force counts them,
        or on its surface within :data:`ARC_TOLERANCE` of the radius, where the wrap contact
        holds them; a single node off the surface inside an arc does not split it). The strands
        are the elements one beyond those joining the arc's end nodes to the first free
        nodes (those are chords across the tangent points, partly on the pulley); their
        tensions give ``tight`` (the larger) and ``slack`` (the smaller), and the wrap angle
        ``wrap`` is the turn from the incoming to the outgoing strand's direction. Then

            utilisation = (tight - slack) / (slack * (exp(mu * wrap) - 1)),

        the friction the pulley needs, T1 - T2, over the most the arc can transmit with that
        slack side, T2·(e^{µθ} - 1). Below 1 the belt grips; 1 is the Euler–Eytelwein limit
        T1/T2 = e^{µθ}, where gross slip starts (an elastic belt creeps before: slip starts
        between the kinetic and the static limit, docs/stability.md). The margin against
        slip is 1 - utilisation (or the safety factor 1/utilisation).

        Args:
            friction: the coefficient µ, one for all pulleys or one per pulley. Default
                None: each pulley's static coefficient ``metadata["pulley_friction_static"]``
                (µs at the end of the run); pass the kinetic one to check a sliding belt.

        Returns:
            a :class:`Capstan` of ``[n, P]`` arrays. NaN where a pulley has no contact arc,
            no friction, or no tension recorded; ``utilisation`` is inf where the slack side
            is not in tension (no capstan capacity) but the tight side is.

        Raises:
            beltrs.BeltrsError: tension or node positions were not recorded, or the
                metadata lacks the pulley constants.
        """
        if self.tension is None or self.node_position is None:
            raise _beltrs.BeltrsError("capstan: needs the tension and node_position channels (recorded by default)")
        radius = self._pulley_constant("pulley_radius", "capstan")
        sign = self._pulley_constant("pulley_wrap_sign", "capstan")
        count = len(radius)
        if friction is None:
            mu = self._pulley_constant("pulley_friction_static", "capstan")
        else:
            try:
                mu = np.broadcast_to(np.asarray(friction, dtype=float), (count,)).copy()
            except (TypeError, ValueError):
                raise _beltrs.BeltrsError(
                    f"friction = {friction!r}: must be a number or one number per pulley ({count})"
                ) from None
            if not np.all(np.isfinite(mu) & (mu >= 0)):
                raise _beltrs.BeltrsError(f"friction = {friction!r}: must be finite and ≥ 0")
        n, elements = self.tension.shape
        tight, slack, wrap = (np.full((n, count), np.nan) for _ in range(3))
        x = self.node_position
        for j in range(count):
            for k in range(n):  # one instant at a time: [n, E] temporaries would not fit a long run
                dist = np.hypot(*(x[k] - self.pulley_position[k, j]).T)
                arc = _longest_arc(dist < radius[j] * (1 + ARC_TOLERANCE))
                if arc is None:
                    continue
                first, last = arc
                # The strands: the elements just beyond the ones that join the arc to the
                # first free node (those are chords across the tangent point, partly on the
                # pulley: their tension and direction are neither strand's nor the arc's).
                enter, leave = (first - 2) % elements, (last + 1) % elements
                t_in, t_out = self.tension[k, enter], self.tension[k, leave]
                d_in = x[k, (enter + 1) % elements] - x[k, enter]
                d_out = x[k, (leave + 1) % elements] - x[k, leave]
                turn = np.arctan2(d_in[0] * d_out[1] - d_in[1] * d_out[0], d_in @ d_out)
                tight[k, j], slack[k, j] = max(t_in, t_out), min(t_in, t_out)
                wrap[k, j] = (sign[j] * turn) % (2 * np.pi)
        capacity = np.exp(mu * wrap) - 1
        with np.errstate(divide="ignore", invalid="ignore"):
            util = np.where(slack > 0, (tight - slack) / (slack * capacity), np.where(tight > slack, np.inf, 0.0))
        util[np.isnan(wrap) | (mu == 0)[None, :]] = np.nan
        return Capstan(tight=tight, slack=slack, wrap=wrap, friction=mu, utilisation=util)

    def contact_profile(
        self,
        pulley: Union[int, str],
        start: Optional[float] = None,
        end: Optional[float] = None,
        bins: int = 24,
    ) -> "ContactProfile":
        """The normal and friction force on the belt round one pulley, by wrap angle along
        the direction of travel, averaged over the instants from ``start`` to ``end``.

        Each recorded contact (instant, belt point) in the window is placed at its wrap
        angle psi = s * (angle - origin) mod 2*pi, with s = +1 when the belt travels
        counter-clockwise round the pulley (``pulley_wrap_sign * travel_direction``) and
        -1 otherwise, so psi grows along the direction of travel from where the belt
        meets the pulley. The origin is the mean over the window of the angle of the first
        point of the arc in the direction of travel (the arc's entry): a fixed place, as
        the field of a steadily running drive is; it lies within one point spacing after
        the tangent point where the incoming strand meets the pulley. The wrap angles are
        then cut into ``bins`` equal bins from 0 to the largest, and each bin gives the
        mean force per belt point. Points that enter before the mean origin have small
        negative wrap angles.

        Args:
            pulley: index or name.
            start, end: the window, s (inclusive). Default: the whole run.
            bins: number of bins, an integer >= 1. Default 24.

        Returns:
            a :class:`ContactProfile`.

        Raises:
            beltrs.SceneError: contact forces were not recorded (``run(...,
                contact_forces=True)``), an unknown pulley, a bad window or bin count, or
                no contact with the pulley in the window.
        """
        if self.contact_normal is None or self.contact_friction is None or self.contact_angle is None:
            raise _beltrs.SceneError(
                "contact_profile: contact forces were not recorded; run with contact_forces=True "
                "(or list \"contact_forces\" in the scene file's recording.channels)"
            )
        count = self.contact_normal.shape[1]
        names = list(self.pulley_names)
        if isinstance(pulley, str):
            if pulley not in names:
                raise _beltrs.SceneError(f"pulley = {pulley!r}: no pulley of that name (names: {names})")
            j = names.index(pulley)
        elif isinstance(pulley, (int, np.integer)) and not isinstance(pulley, bool) and 0 <= pulley < count:
            j = int(pulley)
        else:
            raise _beltrs.SceneError(
                f"pulley = {pulley!r}: must be a pulley name or an index from 0 to {count - 1}"
            )
        if isinstance(bins, bool) or not isinstance(bins, (int, np.integer)) or bins < 1:
            raise _beltrs.SceneError(f"bins = {bins!r}: must be an integer >= 1")
        t = np.asarray(self.time, dtype=float)
        lo = t[0] if start is None else start
        hi = t[-1] if end is None else end
        for name, value in (("start", lo), ("end", hi)):
            if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) \
                    or not np.isfinite(value):
                raise _beltrs.SceneError(f"{name} = {value!r}: must be a finite time, s")
        if hi < lo:
            raise _beltrs.SceneError(f"end = {hi!r}: must not be before start = {lo!r}")
        rows = np.flatnonzero((t >= lo) & (t <= hi))
        direction = int(self._travel_sign("contact_profile")[j])
        angle = self.contact_angle[rows, j]
        on = ~np.isnan(angle)
        if not on.any():
            raise _beltrs.SceneError(
                f"contact_profile: no belt point touches pulley {names[j] if names else j!r} "
                f"between {lo:g} s and {hi:g} s"
            )
        # The arc's entry at each instant: the point after the widest gap between the
        # contact angles round the circle, in the direction of travel.
        entries, free = [], []
        for k in range(len(rows)):
            a = np.sort(np.mod(direction * angle[k][on[k]], 2 * np.pi))
            if a.size == 0:
                continue
            gaps = np.diff(np.append(a, a[0] + 2 * np.pi))
            entries.append(a[(int(np.argmax(gaps)) + 1) % a.size])
            free.append(float(gaps.max()))
        origin = float(np.angle(np.mean(np.exp(1j * np.asarray(entries)))))
        # A point that entered a little before the mean entry has a small negative psi,
        # not one near 2*pi: cut the circle in the middle of the free (untouched) part.
        half = 0.5 * float(np.mean(free))
        psi = np.mod(direction * angle[on] - origin + half, 2 * np.pi) - half
        normal = self.contact_normal[rows, j][on]
        # On the belt, along the direction of travel: the opposite of the force on the
        # pulley along its counter-clockwise tangent, times the sense of travel.
        friction = -direction * self.contact_friction[rows, j][on]
        low, high = min(0.0, float(psi.min())), float(psi.max())
        edges = np.linspace(low, high + 1e-12 * max(1.0, abs(high)), int(bins) + 1)
        which = np.clip(np.searchsorted(edges, psi, side="right") - 1, 0, int(bins) - 1)
        hits = np.bincount(which, minlength=int(bins))
        with np.errstate(invalid="ignore", divide="ignore"):
            mean_normal = np.bincount(which, normal, minlength=int(bins)) / hits
            mean_friction = np.bincount(which, friction, minlength=int(bins)) / hits
        return ContactProfile(
            angle=0.5 * (edges[:-1] + edges[1:]),
            normal=mean_normal,
            friction=mean_friction,
            count=hits.astype(np.int64),
            origin=float(np.mod(direction * origin, 2 * np.pi)),
            direction=direction,
        )

    def lowpass(self, channel: str, cutoff: float) -> np.ndarray:
        """A recorded channel with everything above ``cutoff`` Hz removed (zero phase, along
        ``time``; :func:`beltrs.analysis.low_pass` on a uniform grid of the run's sample
        spacing, then back onto ``time``), same shape and unit as the channel.

        The raw channels are the model's answer and carry no filter. A low-pass is a
        measurement band chosen on purpose: e.g. the tension a load cell of 2 Hz bandwidth
        reads (``res.lowpass("tension", 2.0)``), or the slow dynamics of a start without
        the belt's higher modes. Tensions follow the belt's elements (material points);
        for a fixed point use :func:`beltrs.analysis.tension_at` first.

        Args:
            channel: a recorded array channel with a ``time`` axis first (``"tension"``,
                ``"drive_torque"``, ``"pulley_speed"``, ...).
            cutoff: highest frequency kept, Hz, > 0 and below the Nyquist frequency of the
                recording.

        Raises:
            beltrs.SceneError: unknown or unrecorded channel, a bad cutoff, or fewer than 3
                samples.
        """
        from .analysis import low_pass

        if channel not in DIMS or channel == "time" or DIMS[channel][0] != "time":
            raise _beltrs.SceneError(f"channel = {channel!r}: not a recorded time series "
                                     f"(known: {', '.join(n for n in DIMS if n != 'time')})")
        data = getattr(self, channel)
        if data is None:
            raise _beltrs.SceneError(f"channel = {channel!r}: not recorded in this run")
        t = np.asarray(self.time, dtype=float)
        if len(t) < 3:
            raise _beltrs.SceneError(f"lowpass: {len(t)} samples; need at least 3")
        step = float(np.median(np.diff(t)))
        if not (isinstance(cutoff, (int, float)) and not isinstance(cutoff, bool) and 0 < cutoff < 0.5 / step):
            raise _beltrs.SceneError(f"cutoff = {cutoff!r}: must be a number of Hz > 0 and below the "
                                     f"recording's Nyquist frequency {0.5 / step:g} Hz")
        x = np.asarray(data, dtype=float)
        flat = x.reshape(len(t), -1)
        grid = np.linspace(t[0], t[-1], max(3, int(round((t[-1] - t[0]) / step)) + 1))
        out = np.empty_like(flat)
        for k in range(flat.shape[1]):
            filtered = low_pass(np.interp(grid, t, flat[:, k]), float(grid[1] - grid[0]), float(cutoff))
            out[:, k] = np.interp(t, grid, filtered)
        return out.reshape(x.shape)

    def tension_lowpass(self, cutoff: float) -> np.ndarray:
        """``[n, E]`` element tensions below ``cutoff`` Hz, N (:meth:`lowpass` of
        ``"tension"``)."""
        return self.lowpass("tension", cutoff)

    def drive_torque_lowpass(self, cutoff: float) -> np.ndarray:
        """``[n, P]`` drive torques below ``cutoff`` Hz, N*m (:meth:`lowpass` of
        ``"drive_torque"``)."""
        return self.lowpass("drive_torque", cutoff)

    def arrays(self) -> dict[str, np.ndarray]:
        """Every recorded array channel by name (channels not recorded are absent)."""
        return {name: getattr(self, name) for name in DIMS if getattr(self, name) is not None}

    def __len__(self) -> int:
        return int(self.time.shape[0])

    def __eq__(self, other: object) -> bool:
        """Equal when the recorded data are: every array bit for bit (NaNs in the same
        places), the time step, ``record_every``, ``interrupted``, the stage, pulley and
        energy-column names and :attr:`metadata`. ``wall_time`` and ``checkpoint_error``
        are not compared: they say how the run went on this machine (a saved and reloaded
        Result does not carry ``checkpoint_error``; two identical runs take different wall
        times), not what it computed."""
        if not isinstance(other, Result):
            return NotImplemented
        for f in fields(self):
            if f.name in _NOT_COMPARED:
                continue
            a, b = getattr(self, f.name), getattr(other, f.name)
            if f.name == "metadata":
                if a.keys() != b.keys() or not all(_same(a[k], b[k]) for k in a):
                    return False
            elif not _same(a, b):
                return False
        return True

    # --- saving ------------------------------------------------------------------------
    def save(self, path: Union[str, os.PathLike], format: Optional[str] = None) -> Path:  # noqa: A002
        """Save to ``path``, atomically (a temporary file, then a rename).

        Args:
            path: file to write. ``.nc`` writes netCDF-4 (needs xarray and the h5netcdf or
                netCDF4 package); anything else writes NPZ (uncompressed, readable with
                ``numpy.load`` without pickle).
            format: ``"npz"`` or ``"netcdf"`` to override the choice by suffix.

        Every array keeps its dtype (counts stay int64), every float its bits; units,
        dimension names, the scalar fields and :attr:`metadata` are stored beside them.
        :func:`load_result` reads both formats back into an equal Result.

        Returns:
            the path written.

        Raises:
            beltrs.BeltrsError: unknown ``format``, metadata of a type that cannot be
                stored, or netCDF without xarray/h5netcdf.
        """
        path = Path(path)
        fmt = format or ("netcdf" if path.suffix.lower() in (".nc", ".nc4", ".netcdf") else "npz")
        if fmt not in ("npz", "netcdf"):
            raise _beltrs.BeltrsError(f"format = {format!r}: must be 'npz' or 'netcdf'")
        if not path.parent.is_dir():
            raise _beltrs.BeltrsError(f"{path}: the directory {path.parent} does not exist")
        meta_types = _metadata_types(self.metadata)
        from .scene_file import atomic_write

        if fmt == "npz":
            payload = self._npz_payload(meta_types)
            atomic_write(path, lambda fh: np.savez(fh, **payload), binary=True)
        else:
            ds = self.to_xarray()
            engine = _netcdf_engine()
            tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
            try:
                ds.to_netcdf(tmp, engine=engine, format="NETCDF4" if engine == "netcdf4" else None)
                os.replace(tmp, path)
            finally:
                if tmp.exists():
                    tmp.unlink()
        return path

    def _npz_payload(self, meta_types: dict[str, str]) -> dict[str, np.ndarray]:
        out: dict[str, np.ndarray] = dict(self.arrays())
        for name in _LISTS:
            out[name] = np.array(list(getattr(self, name)), dtype=str)
        for name, kind in _SCALARS.items():
            out[name] = np.array(kind(getattr(self, name)))
        for key, value in self.metadata.items():
            if key in out or key in _DESCRIPTORS:
                raise _beltrs.BeltrsError(f"metadata[{key!r}]: the name of a Result field; choose another key")
            out[key] = np.array(value if meta_types[key] != "list" else list(value), dtype=_npz_dtype(value))
        out["beltrs_format"] = np.array(FORMAT)
        out["units"] = np.array(json.dumps({k: UNITS[k] for k in DIMS}))
        out["dims"] = np.array(json.dumps({k: list(v) for k, v in DIMS.items()}))
        out["metadata_types"] = np.array(json.dumps(meta_types))
        return out

    # --- labelled views ----------------------------------------------------------------
    def to_xarray(self) -> Any:
        """An ``xarray.Dataset`` with named dimensions and units.

        Dimensions: ``time`` (s, the coordinate), ``element`` (element e joins node e to
        e + 1), ``node``, ``pulley`` (coordinate: pulley names), ``idler``, ``axis``
        (``"x"``, ``"y"``), ``energy_term`` (coordinate: energy column names); ``element`` has
        the coordinate ``distance`` (m along the unstretched belt from node 0, element
        midpoints) when the Result carries ``metadata["rest_length"]``. Every variable has
        ``units`` and ``long_name`` attributes; ``drive_power`` (W) is added. Dataset
        attributes: ``dt``, ``wall_time``, ``interrupted`` (0/1), ``record_every``,
        ``stages``, ``beltrs_format`` and :attr:`metadata` (lists and bools stored so that
        netCDF can hold them; :func:`load_result` restores the types).

        >>> ds = res.to_xarray()
        >>> ds.tension.sel(time=2.0, method="nearest").max()
        >>> ds.drive_torque.sel(pulley="head").plot()

        Raises:
            beltrs.BeltrsError: xarray is not installed.
        """
        xr = _require("xarray", "Result.to_xarray")
        data_vars: dict[str, Any] = {}
        for name, value in self.arrays().items():
            if name == "time":
                continue
            data_vars[name] = (DIMS[name], value, {"units": UNITS[name], "long_name": _DESCRIPTION[name]})
        data_vars["drive_power"] = (
            ("time", "pulley"), self.drive_power, {"units": "W", "long_name": _DESCRIPTION["drive_power"]}
        )
        coords = {
            "time": ("time", self.time, {"units": "s", "long_name": "simulated time"}),
            "pulley": ("pulley", np.array(list(self.pulley_names), dtype=str)),
            "axis": ("axis", np.array(["x", "y"])),
            "energy_term": ("energy_term", np.array(list(self.energy_columns), dtype=str)),
        }
        rest = self.metadata.get("rest_length")
        if self.tension is not None and isinstance(rest, np.ndarray) and rest.shape == self.tension.shape[1:]:
            coords["distance"] = (
                "element", np.cumsum(rest) - rest / 2,
                {"units": "m", "long_name": "element midpoint: distance along the unstretched belt from node 0"},
            )
        meta_types = _metadata_types(self.metadata)
        attrs: dict[str, Any] = {
            "beltrs_format": FORMAT,
            "dt": float(self.dt),
            "wall_time": float(self.wall_time),
            "interrupted": int(bool(self.interrupted)),
            "record_every": int(self.record_every),
            "steps_accepted": int(self.steps_accepted),
            "steps_rejected": int(self.steps_rejected),
            "stages": json.dumps(list(self.stages)),
            "metadata_types": json.dumps(meta_types),
        }
        for key, value in self.metadata.items():
            if key in attrs or key in data_vars or key in coords or key in _DESCRIPTORS:
                raise _beltrs.BeltrsError(f"metadata[{key!r}]: the name of a Result field; choose another key")
            kind = meta_types[key]
            attrs[key] = (
                int(value) if kind == "bool" else json.dumps(list(value)) if kind == "list" else value
            )
        return xr.Dataset(data_vars, coords=coords, attrs=attrs)

    def to_pandas(self) -> Any:
        """The per-pulley time series as a ``pandas.DataFrame``.

        Index: ``time`` (s). Columns: a two-level index (quantity, pulley name) over
        takeup_travel (m), pulley_speed (rad/s), drive_torque (N*m), drive_power (W),
        brake_torque (N*m), friction_torque (N*m), normal_force (N), friction_force (N),
        contact_nodes and slipping_nodes (int64 counts), motor_speed (rad/s; NaN without a
        motor; absent from results saved before beltrs recorded it). ``df.attrs["units"]``
        maps each quantity to its unit.

        >>> df = res.to_pandas()
        >>> df[("drive_torque", "head")].max()
        >>> df.xs("takeup", axis=1, level="pulley")     # every series of one pulley

        Raises:
            beltrs.BeltrsError: pandas is not installed.
        """
        pd = _require("pandas", "Result.to_pandas")
        names = list(self.pulley_names) or [str(j) for j in range(self.takeup_travel.shape[1])]
        series = [q for q in PULLEY_SERIES if q == "drive_power" or getattr(self, q) is not None]
        columns = pd.MultiIndex.from_product([series, names], names=["quantity", "pulley"])
        frame = pd.DataFrame(
            {(q, p): getattr(self, q)[:, j] for q in series for j, p in enumerate(names)},
            index=pd.Index(self.time, name="time"),
            columns=columns,
        )
        frame.attrs["units"] = {q: UNITS[q] for q in series} | {"time": "s"}
        return frame


@dataclass
class ContactProfile:
    """Forces on the belt round one pulley by wrap angle (:meth:`Result.contact_profile`).

    Attributes:
        angle: ``[B]`` bin centres: wrap angle along the direction of travel from where the
            belt meets the pulley, rad.
        normal: ``[B]`` mean normal force on a belt point in the bin, N (NaN in an empty bin).
        friction: ``[B]`` mean friction force on a belt point, N, along the direction of
            travel: positive where the pulley pushes the belt forward (a drive), negative
            where the belt drags the pulley (a driven pulley); NaN in an empty bin.
        count: ``[B]`` contacts (instant, point) in each bin.
        origin: polar angle of the origin, rad, counter-clockwise from +x, in [0, 2*pi).
        direction: +1 if the belt travels counter-clockwise round the pulley, -1 if
            clockwise.
    """

    angle: np.ndarray
    normal: np.ndarray
    friction: np.ndarray
    count: np.ndarray
    origin: float
    direction: int


@dataclass
class Capstan:
    """The capstan state of each pulley (:meth:`Result.capstan`); ``[n, P]`` arrays.

    Attributes:
        tight: tight-side tension T1 (the larger strand tension at the contact arc's ends), N.
        slack: slack-side tension T2, N.
        wrap: wrap angle θ (turn from the incoming to the outgoing strand), rad.
        friction: ``[P]`` the coefficient µ used, dimensionless.
        utilisation: (T1 - T2) / (T2·(e^{µθ} - 1)), dimensionless: 1 at the
            Euler–Eytelwein slip limit.
    """

    tight: np.ndarray
    slack: np.ndarray
    wrap: np.ndarray
    friction: np.ndarray
    utilisation: np.ndarray


#: A node counts as on a pulley's arc within this fraction of the radius outside it: the wrap
#: contact (``pulley_contact = "wrap"``, the builder's) holds the nodes on the surface within
#: micrometres either side, alternating (measured ±1 µm on the 300 m builder conveyor's
#: 0.4 m drums); 1e-4 of the radius (40 µm there) keeps them in the arc, and a free strand's
#: first node, s²/(2r) off the surface a length s from the tangent point, out for any element
#: longer than a fortieth of the radius.
ARC_TOLERANCE = 1e-4


def _longest_arc(inside: np.ndarray) -> Optional[tuple[int, int]]:
    """First and last node of the longest cyclic run of True in ``inside``, after filling
    single-node gaps (a node that bounces off the surface inside an arc); None if there
    is no run or every node is inside."""
    on = inside | (np.roll(inside, 1) & np.roll(inside, -1))
    if not on.any() or on.all():
        return None
    starts = np.flatnonzero(on & ~np.roll(on, 1))
    ends = np.flatnonzero(on & ~np.roll(on, -1))
    ends = ends[np.searchsorted(ends, starts) % len(ends)]  # each run's end, cyclically
    size = (ends - starts) % len(on) + 1
    best = int(np.argmax(size))
    return int(starts[best]), int(ends[best])


def load_result(path: Union[str, os.PathLike]) -> Result:
    """Read a result written by :meth:`Result.save` (or by ``beltrs run``): NPZ, or netCDF
    for ``.nc`` files. The Result equals the one saved (arrays bit for bit, counts int64,
    metadata with their types).

    Raises:
        beltrs.BeltrsError: the file is missing, not a beltrs result, or of another
            format version (the message names the file and the problem).
    """
    path = Path(path)
    if not path.is_file():
        raise _beltrs.BeltrsError(f"{path}: no such file")
    with open(path, "rb") as fh:
        magic = fh.read(8)
    if magic.startswith(b"PK"):
        return _load_npz(path)
    if magic.startswith(b"\x89HDF") or magic.startswith(b"CDF"):
        return _load_netcdf(path)
    raise _beltrs.BeltrsError(f"{path}: not a beltrs result (neither NPZ nor netCDF)")


def _load_npz(path: Path) -> Result:
    try:
        f = np.load(path, allow_pickle=False)
    except (OSError, ValueError) as err:
        raise _beltrs.BeltrsError(f"{path}: cannot be read as NPZ: {err}") from None
    with f:
        files = set(f.files)
        fmt = str(f["beltrs_format"]) if "beltrs_format" in files else None
        if fmt is not None and fmt != FORMAT:
            raise _beltrs.BeltrsError(f"{path}: format {fmt!r}, this beltrs reads {FORMAT!r}")
        missing = [k for k in ("time", "takeup_travel", "energy_columns") if k not in files]
        if missing:
            raise _beltrs.BeltrsError(f"{path}: not a beltrs result (missing {', '.join(missing)})")
        kw: dict[str, Any] = {name: (f[name] if name in files else None) for name in DIMS}
        for name in _LISTS:
            kw[name] = [str(s) for s in f[name]] if name in files else []
        for name, kind in _SCALARS.items():
            if name in files:
                kw[name] = kind(f[name].item())
        meta_types = json.loads(str(f["metadata_types"])) if "metadata_types" in files else {}
        known = set(DIMS) | set(_LISTS) | set(_SCALARS) | set(_DESCRIPTORS)
        metadata: dict[str, Any] = {}
        for key in f.files:
            if key in known:
                continue
            metadata[key] = _from_npz(f[key], meta_types.get(key))
    for name in _COUNTS:
        if kw[name] is not None:
            kw[name] = kw[name].astype(np.int64)  # files of beltrs ≤ 0.1 stored counts as floats
    return Result(**kw, metadata=metadata)


def _load_netcdf(path: Path) -> Result:
    xr = _require("xarray", f"reading the netCDF file {path}")
    try:
        ds = xr.load_dataset(path, engine=_netcdf_engine())
    except (OSError, ValueError) as err:
        raise _beltrs.BeltrsError(f"{path}: cannot be read as netCDF: {err}") from None
    fmt = ds.attrs.get("beltrs_format")
    if fmt != FORMAT:
        raise _beltrs.BeltrsError(f"{path}: format {fmt!r}, this beltrs reads {FORMAT!r}")
    kw: dict[str, Any] = {name: (ds[name].values if name in ds.variables else None) for name in DIMS}
    kw["pulley_names"] = [str(s) for s in ds["pulley"].values]
    kw["energy_columns"] = [str(s) for s in ds["energy_term"].values]
    kw["stages"] = list(json.loads(ds.attrs["stages"]))
    for name, kind in _SCALARS.items():
        kw[name] = kind(ds.attrs[name])
    meta_types = json.loads(ds.attrs.get("metadata_types", "{}"))
    metadata: dict[str, Any] = {}
    for key, kind in meta_types.items():
        value = ds.attrs[key]
        if kind == "bool":
            value = bool(value)
        elif kind == "list":
            value = list(json.loads(value))
        elif kind == "array":
            value = np.asarray(value)
        elif kind == "int":
            value = int(value)
        elif kind == "float":
            value = float(value)
        else:
            value = str(value)
        metadata[key] = value
    return Result(**kw, metadata=metadata)


def _netcdf_engine() -> str:
    import importlib.util

    _require("xarray", "netCDF files")
    if importlib.util.find_spec("h5netcdf") is not None and importlib.util.find_spec("h5py") is not None:
        return "h5netcdf"
    if importlib.util.find_spec("netCDF4") is not None:
        return "netcdf4"
    raise _beltrs.BeltrsError(
        "netCDF files need the optional packages 'h5netcdf' and 'h5py' (or 'netCDF4'): "
        "pip install h5netcdf h5py; or save to .npz"
    )


def _metadata_types(metadata: dict[str, Any]) -> dict[str, str]:
    """The storable type of each metadata value, else a BeltrsError naming the key."""
    out = {}
    for key, value in metadata.items():
        if not isinstance(key, str) or not key.isidentifier():
            raise _beltrs.BeltrsError(f"metadata key {key!r}: must be a name (letters, digits, _)")
        if isinstance(value, bool) or isinstance(value, np.bool_):
            out[key] = "bool"
        elif isinstance(value, (int, np.integer)):
            out[key] = "int"
        elif isinstance(value, (float, np.floating)):
            out[key] = "float"
        elif isinstance(value, str):
            out[key] = "str"
        elif isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
            out[key] = "list"
        elif isinstance(value, np.ndarray) and value.dtype.kind in "biufU":
            out[key] = "array"
        else:
            raise _beltrs.BeltrsError(
                f"metadata[{key!r}] = {value!r:.60}: must be str, bool, int, float, a list of str "
                f"or a NumPy array of numbers or str"
            )
    return out


def _npz_dtype(value: Any) -> Any:
    if isinstance(value, (list, tuple)):
        return str
    return None


def _from_npz(value: np.ndarray, kind: Optional[str]) -> Any:
    if kind == "array":
        return value
    if kind == "list":
        return [str(s) for s in value]
    if kind is None:  # a file written by another tool or an older beltrs: scalars as Python values
        return value.item() if value.ndim == 0 else value
    item = value.item()
    return {"bool": bool, "int": int, "float": float, "str": str}[kind](item)


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        if a is None or b is None:
            return False
        a, b = np.asarray(a), np.asarray(b)
        return a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a, b, equal_nan=a.dtype.kind in "fc")
    if isinstance(a, float) and isinstance(b, float) and np.isnan(a) and np.isnan(b):
        return True
    return type(a) is type(b) and a == b

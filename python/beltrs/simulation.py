"""The Python face of the engine: build, stabilise, run, change and continue."""

from __future__ import annotations

import math
import numbers
import os
import time as _time
from dataclasses import replace
from typing import Any, Optional, Union

import numpy as np

from . import _beltrs, diagnostics
from ._checks import warn_scene
from ._progress import make_bar, make_ticker
from .model import Model
from .result import Result
from .scene import Drive, Friction, Scene

__all__ = ["DEFAULT_MAX_MEMORY", "MAX_RECORD_INTERVAL", "Simulation"]

#: Default bound on the memory of a run's recording, bytes (256 MiB); see :meth:`Simulation.run`.
DEFAULT_MAX_MEMORY = 256 * 2**20
#: Longest default recording interval, s (100 samples per second): see
#: :meth:`Simulation.default_record_interval`.
MAX_RECORD_INTERVAL = 0.01
#: Samples per period of the shortest strand's fundamental longitudinal mode in the default
#: recording interval (:meth:`Simulation.default_record_interval`).
SAMPLES_PER_STRAND_PERIOD = 20
_MAX_STEPS = 2**63 - 1
_CHUNK_SECONDS = 0.1


def _whole(name: str, value: Any) -> int:
    """``value`` as an int in [0, 2^63 - 1], else a SceneError naming the argument."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or not 0 <= value <= _MAX_STEPS:
        raise _beltrs.SceneError(f"{name} = {value!r}: must be a whole number in [0, 2^63 - 1]")
    return int(value)


def _next_chunk(chunk: int, seconds: float) -> int:
    """Steps for the next chunk so that it takes about ``_CHUNK_SECONDS`` of wall time
    (growing or shrinking at most fourfold per chunk)."""
    if seconds <= 0:
        return min(chunk * 4, 1 << 40)
    wanted = int(chunk * _CHUNK_SECONDS / seconds)
    return max(1, chunk // 4, min(wanted, 4 * chunk, 1 << 40))


class Simulation:
    """A compiled scene and its state.

    >>> sim = Simulation(beltrs.scenes.hustrulid_loop())
    >>> sim.stabilise()
    >>> res = sim.run(1.0, record_interval=0.01)

    Raises :class:`beltrs.SceneError` (naming field, value and rule) for invalid scenes and
    :class:`beltrs.TimeStepError` for a time step above the stability limit.
    """

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        self._core = _beltrs.Simulation(scene.to_dict())
        self.last_result: Optional[Result] = None
        self._placed = True  # still at the initial placement: never relaxed nor run
        warn_scene(scene)
        diagnostics.check_scene(self)

    # --- model facts -------------------------------------------------------------------
    @property
    def model(self) -> Model:
        """The compiled model (stages, time step and its limit, nodes, ...), a read-only
        snapshot of the one in use; :meth:`set_scene` compiles a new one."""
        return Model._from_core(self._core, self.scene)

    @property
    def dt(self) -> float:
        """Time step in use, s."""
        return float(self._core.dt)

    @property
    def dt_limit(self) -> float:
        """Estimated explicit stability limit, s."""
        return float(self._core.dt_limit)

    @property
    def dt_cause(self) -> str:
        """Which stiffness sets the stability limit."""
        return str(self._core.dt_cause)

    @property
    def stages(self) -> list[str]:
        """Compiled stages, in the order they run; effects the scene does not use are absent."""
        return list(self._core.stages)

    @property
    def nodes(self) -> int:
        """Number of belt nodes (= elements)."""
        return int(self._core.nodes)

    @property
    def time(self) -> float:
        """Simulated time, s."""
        return float(self._core.time)

    @property
    def path_length(self) -> float:
        """Length of the initial belt path, m."""
        return float(self._core.path_length)

    @property
    def wrap_angles(self) -> list[float]:
        """Wrap angle on each pulley on the initial path, rad."""
        return list(self._core.wrap_angles)

    @property
    def rest_length(self) -> np.ndarray:
        """Element rest lengths, m, shape ``[E]``."""
        return np.asarray(self._core.rest_length)

    @property
    def node_mass(self) -> np.ndarray:
        """Node masses of the belt alone, kg, shape ``[E]`` (with loads, the current masses
        are :meth:`node_masses`)."""
        return np.asarray(self._core.node_mass)

    def default_record_interval(self) -> float:
        """Recording interval :meth:`run` uses when given neither ``record_every`` nor
        ``record_interval``, s: the smaller of :data:`MAX_RECORD_INTERVAL` (0.01 s) and
        1/20 of the period of the shortest free strand's fundamental longitudinal mode,
        ``2 L / c`` with ``c = sqrt(EA / m')`` the belt's axial wave speed (m' its own mass
        per metre, the fastest case) and ``L`` the tangent-to-tangent length of the
        shortest strand between consecutive pulleys. 20 samples a period resolve a wave
        front crossing the strand and its reflections at the pulleys, which are the fastest
        events a conveyor start or stop produces; the 0.01 s cap keeps drive and brake
        events (torque pulses of 0.05 s and more) on ≥ 5 samples. :meth:`run` rounds it to
        whole steps (at least one).

        Examples: case H (100 m strands, c = 276 m/s) → 0.01 s; a belt drive with 0.5 m
        strands and c ≈ 1 km/s → 25 µs (then every step, if the step is larger).
        """
        belt = self.scene.belt
        c = math.sqrt(belt.axial_stiffness / belt.mass_per_length)
        pulleys = self.scene.pulleys
        strands = []
        for a, b in zip(pulleys, pulleys[1:] + pulleys[:1]):
            if a is b:
                continue
            d = math.dist(a.center, b.center)
            offset = abs(a.radius - b.radius) if a.wrap == b.wrap else a.radius + b.radius
            strands.append(math.sqrt(d * d - offset * offset) if d > offset else d)
        length = min(strands) if strands else self.path_length / 2
        return min(MAX_RECORD_INTERVAL, 2.0 * length / c / SAMPLES_PER_STRAND_PERIOD)

    # --- state -------------------------------------------------------------------------
    def node_masses(self) -> np.ndarray:
        """Node masses now, kg, shape ``[E]``: the belt's (:attr:`node_mass`) plus the
        material of the scene's loads on each node's tributary length, which changes as the
        belt moves (docs/loads.md)."""
        return np.asarray(self._core.node_masses())

    def load_zones(self) -> np.ndarray:
        """Each load's zone now, shape ``[loads, 3]`` (loads of zero mass are dropped when
        the scene is compiled): the material coordinates (m of unstretched belt from node 0)
        of the belt points at the loading and at the discharge point, and the zone's length
        between them, m (its material is
        ``mass_per_length`` times that)."""
        return np.asarray(self._core.load_zones())

    def state(self) -> dict[str, Any]:
        """Current state as NumPy arrays (positions m, half-step velocities m/s, ...)."""
        return dict(self._core.state())

    def tensions(self) -> np.ndarray:
        """Element tensions at the current state, N, shape ``[E]``."""
        return np.asarray(self._core.tensions())

    def forces(self) -> np.ndarray:
        """Net force on each node at the current state, N, shape ``[E, 2]``."""
        return np.asarray(self._core.forces())

    def energies(self) -> dict[str, float]:
        """Energies of the current state, J."""
        return dict(self._core.energies())

    @property
    def takeup_travel(self) -> np.ndarray:
        """Travel of each takeup from its initial position along its pull direction, m."""
        return np.asarray(self.state()["takeup_travel"])

    # --- actions -----------------------------------------------------------------------
    def stabilise(
        self,
        method: str = "fire",
        *,
        friction: bool = False,
        tolerance: float = 1e-7,
        max_steps: int = 5_000_000,
        progress: Optional[bool] = None,
    ) -> dict[str, Any]:
        """Relax to static equilibrium (thesis §6.2); simulated time does not advance.

        Args:
            method: ``"fire"`` (default, fast inertial relaxation) or ``"kinetic"``
                (kinetic-energy damping of the thesis, applied per degree of freedom).
            friction: keep belt friction on while relaxing (locks in lower tensions around
                the pulleys, thesis fig. 6.6). Default False (thesis §6.2).
            tolerance: converged when the largest out-of-balance force is below this
                fraction of the largest tension. Default 1e-7.
            max_steps: give up after this many relaxation steps.
            progress: show the elapsed wall time on stderr while relaxing (one Rust call,
                so no fraction done), then steps and residual. Default None: only when
                stderr is a terminal.

        Returns:
            dict with ``steps``, ``residual``, ``converged``, ``resets``.

        Raises:
            beltrs.BeltrsError: if the relaxation does not converge.
        """
        max_steps = _whole("max_steps", max_steps)
        ticker = make_ticker(progress, "beltrs: relaxing to static equilibrium")
        try:
            report = dict(self._core.stabilise(method, friction, tolerance, max_steps))
        except BaseException:
            ticker.close("failed")
            raise
        ticker.close(f"{report['steps']} steps, residual {report['residual']:.2e}")
        self._placed = False
        if not report["converged"]:
            raise _beltrs.BeltrsError(
                f"stabilise did not converge in {report['steps']} steps: residual {report['residual']:.3e} "
                f"> tolerance {tolerance:.3e}"
            )
        diagnostics.check_idlers(self)
        return report

    def run(
        self,
        duration: float,
        *,
        record_every: Optional[int] = None,
        record_interval: Optional[float] = None,
        tension: bool = True,
        node_position: bool = True,
        node_velocity: bool = True,
        max_samples: Optional[int] = None,
        max_memory: float = DEFAULT_MAX_MEMORY,
        progress: Optional[bool] = None,
        checkpoint: Optional[Union[str, os.PathLike]] = None,
        checkpoint_interval: float = 600.0,
    ) -> Result:
        """Run for ``duration`` seconds and return what was recorded.

        Args:
            duration: simulated time, s (rounded to whole steps).
            record_every: sample every this many steps. Give this or
                ``record_interval``, not both.
            record_interval: sample about every this many seconds (rounded to whole steps).
                Default (neither given): :meth:`default_record_interval`, from the scene's
                wave physics, at most 0.01 s. The final state is always recorded: the last
                instant of the Result is the end of the run (it may follow the one before
                after fewer steps than the others).
            tension, node_position, node_velocity: record these large arrays. Default True.
            max_samples: most recorded instants kept (>= 2). When the buffer is full, every
                other instant is dropped and the interval doubles, so the result always
                spans the whole run on a uniform grid (``Result.record_every`` gives the
                final interval in steps). Default None: as many as fit in ``max_memory``.
            max_memory: bound on the recording's memory when ``max_samples`` is None, bytes.
                One instant takes ``8 * (8 + 5*E + 13*P + 2*I)`` bytes with every channel on
                (E nodes, P pulleys, I idlers; tension, node_position and node_velocity
                switched off save 8*E, 16*E and 16*E); see :meth:`sample_bytes`.
                Default 256 MiB.
            progress: show a progress bar on stderr (tqdm if installed, else a built-in
                one). Default None: only when stderr is a terminal.
            checkpoint: if given, save a checkpoint to this path (atomically) every
                ``checkpoint_interval`` seconds of wall time, at the end, and on Ctrl-C.
            checkpoint_interval: wall-clock seconds between checkpoints. Default 600.

        Returns:
            :class:`Result`. Ctrl-C stops the run cleanly: the Result holds everything
            recorded so far and ``interrupted`` is True; the state stays consistent, so the
            run can go on with another ``run``.

        Raises:
            beltrs.DivergenceError: the state became non-finite; the message names time,
                node and quantity, and ``err.result`` holds what was recorded before.
        """
        duration = float(duration)
        if not np.isfinite(duration) or duration < 0:
            raise _beltrs.SceneError(f"duration = {duration}: must be a finite number ≥ 0 (s)")
        if record_every is not None and record_interval is not None:
            raise _beltrs.SceneError("give record_every or record_interval, not both")
        every = max(1, int(round(self.default_record_interval() / self.dt)))
        if record_every is not None:
            if int(record_every) < 1:
                raise _beltrs.SceneError(f"record_every = {record_every}: must be ≥ 1")
            every = min(int(record_every), _MAX_STEPS)
        elif record_interval is not None:
            if not (np.isfinite(record_interval) and record_interval > 0):
                raise _beltrs.SceneError(f"record_interval = {record_interval}: must be > 0 (s)")
            every = max(1, min(int(round(record_interval / self.dt)), _MAX_STEPS))
        steps = int(round(duration / self.dt))
        if steps > _MAX_STEPS:
            raise _beltrs.SceneError(
                f"duration = {duration}: {steps:.3e} steps of {self.dt:.3e} s, more than {_MAX_STEPS:.3e}"
            )
        per_sample = self.sample_bytes(tension, node_position, node_velocity)
        if max_samples is None:
            if not (np.isfinite(max_memory) and max_memory > 0):
                raise _beltrs.SceneError(f"max_memory = {max_memory}: must be a finite number > 0 (bytes)")
            max_samples = int(max_memory // per_sample)
            if max_samples < 2:
                raise _beltrs.SceneError(
                    f"max_memory = {max_memory}: must hold at least 2 samples of {per_sample} bytes"
                )
        elif int(max_samples) < 2:
            raise _beltrs.SceneError(f"max_samples = {max_samples}: must be ≥ 2")
        max_samples = min(int(max_samples), _MAX_STEPS)
        if checkpoint is not None and not (np.isfinite(checkpoint_interval) and checkpoint_interval >= 0):
            raise _beltrs.SceneError(f"checkpoint_interval = {checkpoint_interval}: must be ≥ 0 (s)")

        if self._placed:
            diagnostics.check_relaxed(self)
            diagnostics.check_idlers(self)
            self._placed = False

        core = self._core
        target = int(core.step_count) + steps
        t0 = _time.perf_counter()
        last_checkpoint = t0
        interrupted = False
        bar = make_bar(progress, steps, self.time + steps * self.dt)
        try:
            core.begin_recording(every, tension, node_position, node_velocity, max_samples)
            try:
                # Short chunks (about 0.1 s of wall time each) keep the bar live and let
                # Ctrl-C in between them; each chunk runs in Rust without the GIL, and a
                # chunk always completes, so the state is consistent when Ctrl-C lands.
                chunk = 64
                while int(core.step_count) < target:
                    n = min(chunk, target - int(core.step_count))
                    c0 = _time.perf_counter()
                    core.advance(n)
                    now = _time.perf_counter()
                    chunk = _next_chunk(chunk, now - c0)
                    bar.update(n, self.time)
                    if checkpoint is not None and now - last_checkpoint >= checkpoint_interval:
                        self.save_checkpoint(checkpoint)
                        last_checkpoint = _time.perf_counter()
            except KeyboardInterrupt:
                interrupted = True
            core.end_recording(interrupted)
            rec, record_every = self._with_final_sample(tension, node_position, node_velocity, interrupted)
        except _beltrs.DivergenceError as err:
            err.result = self._result(_time.perf_counter() - t0)  # type: ignore[attr-defined]
            self.last_result = err.result  # type: ignore[attr-defined]
            raise
        finally:
            bar.close()
        if checkpoint is not None:
            self.save_checkpoint(checkpoint)
        self.last_result = self._result(_time.perf_counter() - t0, rec, record_every)
        return self.last_result

    def _with_final_sample(
        self, tension: bool, node_position: bool, node_velocity: bool, interrupted: bool
    ) -> tuple[dict[str, Any], int]:
        """The recording just closed, with the final state appended when it fell between
        two instants of the recording grid, so that the last instant is the end of the
        run; and the grid's interval in steps."""
        core = self._core
        rec = dict(core.recording())
        every = int(core.record_every)
        times = np.asarray(rec["time"])
        if len(times) and times[-1] == self.time:
            return rec, every
        # Sample the final state through a fresh one-instant recording and append it.
        core.begin_recording(1, tension, node_position, node_velocity, 2)
        core.end_recording(interrupted)
        last = dict(core.recording())
        for key, value in rec.items():
            if isinstance(value, np.ndarray) and key in last:
                rec[key] = np.concatenate([value, np.asarray(last[key])], axis=0)
        return rec, every

    def sample_bytes(self, tension: bool = True, node_position: bool = True, node_velocity: bool = True) -> int:
        """Bytes one recorded instant takes with these channels:
        ``8 * (8 + E*(tension + 2*node_position + 2*node_velocity) + 13*P + 2*I)``."""
        return int(self._core.sample_bytes(tension, node_position, node_velocity))

    def _result(self, wall: float, rec: Optional[dict[str, Any]] = None, record_every: Optional[int] = None) -> Result:
        return Result._from_core(
            dict(self._core.recording()) if rec is None else rec,
            dt=self.dt,
            stages=self.stages,
            wall_time=wall,
            interrupted=bool(self._core.interrupted),
            pulley_names=[p.name for p in self.scene.pulleys],
            record_every=int(self._core.record_every) if record_every is None else record_every,
            metadata={"rest_length": self.rest_length},
        )

    # --- checkpoints -------------------------------------------------------------------
    def save_checkpoint(self, path: Union[str, os.PathLike]) -> None:
        """Save the scene and the full state to ``path``, atomically (a temporary file in
        the same directory, flushed to disk, then renamed over ``path``: a crash leaves the
        old file). The recording is not saved. Format: ``docs/runtime.md``.

        Raises:
            beltrs.CheckpointError: the file cannot be written (the message names the file
                and the cause).
        """
        self._core.save_checkpoint(os.fspath(path))

    @classmethod
    def load_checkpoint(cls, path: Union[str, os.PathLike], scene: Optional[Scene] = None) -> "Simulation":
        """A simulation resumed from the checkpoint at ``path``; it continues bit-for-bit as
        the saved one would have.

        Args:
            path: checkpoint file written by :meth:`save_checkpoint`.
            scene: if given, the checkpoint must hold exactly this scene (e.g. the scene
                file the run started from), else :class:`beltrs.CheckpointError` names the
                first part that differs. Default None: the scene stored in the checkpoint
                (including parameters changed during the run) is used.

        Raises:
            beltrs.CheckpointError: missing, truncated or corrupt file, another format
                version, or another scene; the message names the file and the problem.
        """
        core = _beltrs.Simulation.load_checkpoint(os.fspath(path), None if scene is None else scene.to_dict())
        sim = cls.__new__(cls)
        sim._core = core
        sim.scene = scene if scene is not None else Scene.from_dict(dict(core.scene_dict()))
        sim.last_result = None
        sim._placed = False
        return sim

    def step(self, steps: int = 1) -> None:
        """Advance ``steps`` steps (a whole number ≥ 0) without recording."""
        self._core.step(_whole("steps", steps))
        self._placed = False

    # --- change a parameter and continue ----------------------------------------------
    def set_scene(self, scene: Scene) -> None:
        """Swap in changed parameters and keep the state. The belt discretisation, the
        pulley centres and takeup lines must stay the same."""
        self._core.set_scene(scene.to_dict())
        self.scene = scene
        warn_scene(scene)
        diagnostics.check_drive_directions(self)  # e.g. set_drive with a starting curve

    def _pulley(self, pulley: Union[int, str]) -> int:
        return self.scene.pulley_index(pulley) if isinstance(pulley, str) else int(pulley)

    def _with_pulley(self, pulley: Union[int, str], **changes: Any) -> None:
        j = self._pulley(pulley)
        pulleys = list(self.scene.pulleys)
        pulleys[j] = replace(pulleys[j], **changes)
        self.set_scene(replace(self.scene, pulleys=pulleys))

    def set_counterweight(self, pulley: Union[int, str], mass: float) -> None:
        """Set the takeup counterweight of ``pulley`` to ``mass`` kg (e.g. a 10 % step)."""
        j = self._pulley(pulley)
        takeup = self.scene.pulleys[j].takeup
        if takeup is None:
            raise _beltrs.SceneError(f"pulleys[{j}].takeup = None: this pulley has no takeup")
        self._with_pulley(j, takeup=replace(takeup, counterweight=mass))

    def set_drive(self, pulley: Union[int, str], drive: Optional[Drive]) -> None:
        """Set (or remove, with None) the drive of ``pulley``. Drive tables and starting
        curves use absolute simulated time (see :attr:`time`): a speed-controlled drive
        started now is ``Drive(start_curve=StartCurve(..., start=sim.time))``
        (``docs/drives.md``)."""
        self._with_pulley(pulley, drive=drive)

    def set_friction(self, pulley: Union[int, str], friction: Optional[Friction]) -> None:
        """Set (or remove) belt friction on ``pulley``."""
        self._with_pulley(pulley, friction=friction)

    # --- profiling ---------------------------------------------------------------------
    def set_profiling(self, on: bool) -> None:
        """Per-stage timing on (zeroed) or off. Off costs nothing."""
        self._core.set_profiling(bool(on))

    def profile(self) -> dict[str, float]:
        """Seconds spent in each stage since profiling was turned on."""
        return dict(self._core.profile())

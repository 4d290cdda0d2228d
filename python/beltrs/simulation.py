"""The Python face of the engine: build, stabilise, run, change and continue."""

from __future__ import annotations

import contextlib
import math
import numbers
import os
import signal
import sys
import threading
import time as _time
import warnings
from dataclasses import replace
from typing import Any, Iterator, Optional, Union

import numpy as np

from . import _beltrs, diagnostics
from ._checks import warn_scene
from ._progress import make_bar
from .model import Model
from .result import Result
from .scene import Brake, Drive, Friction, Holdback, Scene
from .statics import check_flag

__all__ = ["DEFAULT_MAX_MEMORY", "DEFAULT_MAX_WALL_TIME", "MAX_RECORD_INTERVAL", "CheckpointWarning", "Simulation"]

#: Default bound on the memory of a run's recording, bytes (256 MiB); see :meth:`Simulation.run`.
DEFAULT_MAX_MEMORY = 256 * 2**20
#: Default bound on a run's estimated wall time, s (one day); see :meth:`Simulation.run`.
DEFAULT_MAX_WALL_TIME = 86_400.0
#: A run estimated to take longer than this (s of wall time) shows its progress bar by
#: default, also when stderr is not a terminal.
PROGRESS_AFTER = 30.0
#: Longest default recording interval, s (100 samples per second): see
#: :meth:`Simulation.default_record_interval`.
MAX_RECORD_INTERVAL = 0.01
#: Samples per period of the shortest strand's fundamental longitudinal mode in the default
#: recording interval (:meth:`Simulation.default_record_interval`).
SAMPLES_PER_STRAND_PERIOD = 20
_MAX_STEPS = 2**63 - 1
_CHUNK_SECONDS = 0.1


class CheckpointWarning(UserWarning):
    """A checkpoint could not be written during or at the end of a run; the run itself is
    kept (``Result.checkpoint_error`` holds the error)."""


def _whole(name: str, value: Any, low: int = 0) -> int:
    """``value`` as an int in [low, 2^63 - 1], else a SceneError naming the argument."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or not low <= value <= _MAX_STEPS:
        raise _beltrs.SceneError(f"{name} = {value!r}: must be a whole number in [{low}, 2^63 - 1]")
    return int(value)


def _real(name: str, value: Any, rule: str, ok: Any = lambda v: True) -> float:
    """``value`` as a finite float for which ``ok`` holds, else a SceneError naming the
    argument, its value and ``rule``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise _beltrs.SceneError(f"{name} = {value!r}: must be a number; {rule}")
    try:
        v = float(value)
    except (OverflowError, ValueError):
        raise _beltrs.SceneError(f"{name} = {value!r}: {rule}") from None
    if not (np.isfinite(v) and ok(v)):
        raise _beltrs.SceneError(f"{name} = {value!r}: {rule}")
    return v


def _flag(name: str, value: Any, none: bool = False) -> Any:
    """``value`` as a bool (or None if ``none``), else a SceneError naming the argument
    (:func:`beltrs.statics.check_flag`)."""
    return check_flag(name, value, none=none)


def _path(name: str, value: Any) -> str:
    """``value`` as a file system path, else a SceneError naming the argument."""
    if not isinstance(value, (str, os.PathLike)):
        raise _beltrs.SceneError(f"{name} = {value!r}: must be a path (str or os.PathLike)")
    path = os.fspath(value)
    if not isinstance(path, str) or not path or "\0" in path:
        raise _beltrs.SceneError(f"{name} = {value!r}: must be a non-empty text path")
    return path


class _DeferSignals:
    """While a run finishes (closing the recording, handing it to the Result, the final
    checkpoint), a Ctrl-C must not throw away what was simulated. In the main thread this
    replaces Python's default SIGINT handler by one that raises KeyboardInterrupt once (the
    first Ctrl-C stops the run) and only counts any later one; the old handler is restored
    on exit. A user's own handler is left alone."""

    def __init__(self) -> None:
        self.installed = False
        self.fired = 0

    def _handler(self, signum: int, frame: Any) -> None:
        self.fired += 1
        if self.fired == 1:
            raise KeyboardInterrupt

    def __enter__(self) -> "_DeferSignals":
        if threading.current_thread() is threading.main_thread():
            try:
                if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
                    signal.signal(signal.SIGINT, self._handler)
                    self.installed = True
            except (ValueError, OSError):  # not allowed here (e.g. a sub-interpreter)
                pass
        return self

    def __exit__(self, *exc: Any) -> None:
        if self.installed:
            signal.signal(signal.SIGINT, signal.default_int_handler)


def _estimate_step_seconds(core: Any) -> float:
    """Wall time of one step, s, estimated from force evaluations (which do not change the
    state): the median of three."""
    times = []
    for _ in range(3):
        t0 = _time.perf_counter()
        core.forces()
        times.append(_time.perf_counter() - t0)
    return sorted(times)[1]


def _human(seconds: float) -> str:
    """A wall time in s, min, h or days."""
    for unit, size in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"


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
        if not isinstance(scene, Scene):
            raise _beltrs.SceneError(f"scene = {scene!r}: must be a beltrs.Scene")
        self.scene = scene
        scene_dict = scene.to_dict()
        self._core = _beltrs.Simulation(scene_dict)
        self.last_result: Optional[Result] = None
        # Still at the initial placement (never relaxed nor run): the first run warns if it is
        # far from equilibrium. Not so a design state (scene.initial, docs/design-start.md): it
        # is held by the drums' and idlers' friction, which that frictionless check omits.
        self._placed = scene.initial is None
        warn_scene(scene)
        diagnostics.check_scene(self, scene_dict)
        self._busy = threading.Lock()

    @contextlib.contextmanager
    def _exclusive(self, what: str) -> Iterator[None]:
        """Keeps run, stabilise and step from overlapping (from different threads): a
        second one raises a BeltrsError at once and changes nothing."""
        busy = self.__dict__.setdefault("_busy", threading.Lock())
        if not busy.acquire(blocking=False):
            raise _beltrs.BeltrsError(
                f"Simulation.{what}: another run, stabilise or step is in progress on this simulation "
                "(in another thread); wait for it to return. Reading the state, saving a checkpoint "
                "or changing parameters from another thread is allowed"
            )
        try:
            yield
        finally:
            busy.release()

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
        """Number of belt nodes (= elements for a closed loop; elements + 1 for an open belt)."""
        return int(self._core.nodes)

    @property
    def elements(self) -> int:
        """Number of belt elements (the nodes of a closed loop; nodes - 1 for an open belt)."""
        return int(self._core.elements)

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
        if not c > 0:
            # EA/m' underflows (e.g. EA = 5e-324): no stress wave to resolve, the cap holds.
            return MAX_RECORD_INTERVAL
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
        """Current state as NumPy arrays (positions m, half-step velocities m/s, ...;
        ``body_angle`` (rad) and ``body_spin`` (rad/s) of the rigid-body belt's points,
        empty for the node belt)."""
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
                the pulleys, thesis fig. 6.6). Default False (thesis §6.2). With friction the
                pulleys with a drive or a brake are held at rest and a holdback stops its
                pulley turning backwards, as on a stopped conveyor, so a loaded incline or
                decline relaxes on its held drums (docs/engine.md, "Relaxing with
                friction").
            tolerance: converged when the largest out-of-balance force is below this
                fraction of the largest tension. Default 1e-7.
            max_steps: give up after this many relaxation steps.
            progress: show a progress bar of the relaxation steps (out of ``max_steps``) on
                stderr, then a line with the steps and the residual. Default None: when
                stderr is a terminal, or when ``max_steps`` steps would take more than
                ``PROGRESS_AFTER`` (30 s) of wall time.

        Returns:
            dict with ``steps``, ``residual``, ``converged``, ``resets``,
            ``interrupted`` and ``holding_torque`` (N*m per pulley, counter-clockwise
            positive: what the holder of each held pulley takes at the end; 0 for a free
            pulley and without friction; empty if interrupted inside a stage change).
            Ctrl-C stops the relaxation within about 0.1 s and returns its report with
            ``interrupted`` True and ``converged`` False (the belt at rest where the
            relaxation had brought it; call again to continue).

        Raises:
            beltrs.BeltrsError: if the relaxation does not converge.
        """
        if not (isinstance(method, str) and method in ("fire", "kinetic")):
            raise _beltrs.SceneError(f'method = {method!r}: unknown relaxation (known: "fire", "kinetic")')
        friction = _flag("friction", friction)
        tolerance = _real("tolerance", tolerance, "must be a finite number > 0", lambda v: v > 0)
        max_steps = _whole("max_steps", max_steps)
        progress = _flag("progress", progress, none=True)
        with self._exclusive("stabilise"):
            if progress is None and max_steps * _estimate_step_seconds(self._core) > PROGRESS_AFTER:
                progress = True
            if progress is None:
                progress = bool(getattr(sys.stderr, "isatty", lambda: False)())
            bar = make_bar(progress, max_steps, None)
            now = self.time  # the callback runs inside the engine's call: no calls back into it
            shown = [0]

            def tick(done: int) -> None:
                if done < shown[0]:  # a new stage of the contact-stiffness continuation
                    shown[0] = 0
                bar.update(done - shown[0], now)
                shown[0] = done

            try:
                report = dict(self._core.stabilise(method, friction, tolerance, max_steps, tick))
            finally:
                bar.close()
            if progress:
                sys.stderr.write(
                    f"beltrs: relaxing to static equilibrium: {report['steps']} steps, "
                    f"residual {report['residual']:.2e}{' (interrupted)' if report['interrupted'] else ''}\n"
                )
        self._placed = False
        if report["interrupted"]:
            return report
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
        energy: bool = False,
        contact_forces: bool = False,
        max_samples: Optional[int] = None,
        max_memory: float = DEFAULT_MAX_MEMORY,
        progress: Optional[bool] = None,
        checkpoint: Optional[Union[str, os.PathLike]] = None,
        checkpoint_interval: float = 600.0,
        max_wall_time: Optional[float] = DEFAULT_MAX_WALL_TIME,
    ) -> Result:
        """Run for ``duration`` seconds and return what was recorded.

        Args:
            duration: simulated time, s. The run ends at ``time + duration`` exactly: the
                integrator takes whole steps and then one shortened step, and the last
                sample is taken there.
            record_every: sample every this many steps. Give this or
                ``record_interval``, not both.
            record_interval: sample about every this many seconds (rounded to whole steps).
                Default (neither given): :meth:`default_record_interval`, from the scene's
                wave physics, at most 0.01 s. The final state is always recorded: the last
                instant of the Result is the end of the run (it may follow the one before
                after fewer steps than the others).
            tension, node_position, node_velocity: record these large arrays. Default True.
            energy: record the energies (``Result.energy``), computed at each sample from
                every node and element. Default False (opt-in: they cost a pass over the
                belt per sample).
            contact_forces: record the normal and friction force of every belt point on
                every pulley, with the point's angle about the pulley centre
                (``Result.contact_normal``, ``contact_friction``, ``contact_angle``, each
                ``[n, P, E]``; ``docs/results.md``). Default False (opt-in: ``24*P*E``
                bytes per instant; off, the friction stages keep no per-point forces).
            max_samples: most recorded instants kept (>= 2). When the buffer is full, every
                other instant is dropped and the interval doubles, so the result always
                spans the whole run on a uniform grid (``Result.record_every`` gives the
                final interval in steps). Default None: as many as fit in ``max_memory``.
            max_memory: bound on the recording's memory when ``max_samples`` is None, bytes.
                One instant takes ``8 * (8 + 5*E + 14*P + 2*I + 3*P*E)`` bytes with every
                channel on (E nodes, P pulleys, I idlers; tension, node_position,
                node_velocity, energy and contact_forces switched off save 8*E, 16*E, 16*E,
                56 and 24*P*E); see :meth:`sample_bytes`.
                Default 256 MiB.
            progress: show a progress bar on stderr (tqdm if installed, else a built-in
                one). Default None: when stderr is a terminal, or when the run is estimated
                to take more than ``PROGRESS_AFTER`` (30 s) of wall time.
            checkpoint: if given, save a checkpoint to this path (atomically) before the
                first step (so a bad path fails at once, before anything is simulated),
                every ``checkpoint_interval`` seconds of wall time, at the end, and on
                Ctrl-C. A failure after the first save never costs the run: it gives a
                :class:`CheckpointWarning`, the run goes on, and the returned Result holds
                the last error in ``checkpoint_error``.
            checkpoint_interval: wall-clock seconds between checkpoints. Default 600.
            max_wall_time: refuse the run if its wall time, estimated before the first
                step from the cost of a force evaluation, exceeds this many seconds (the
                error gives the estimate). Default one day; None: no bound.

        Returns:
            :class:`Result`. Ctrl-C stops the run within about 0.1 s at a whole step: the
            Result holds everything recorded so far and ``interrupted`` is True; the state
            stays consistent, so the run can go on with another ``run``. A second Ctrl-C
            while the Result is being assembled is ignored (nothing is lost).

        Raises:
            beltrs.SceneError: an argument of the wrong type or out of range, or a run
                estimated to take longer than ``max_wall_time``.
            beltrs.CheckpointError: the checkpoint cannot be written before the first step.
            beltrs.DivergenceError: the state (or a recorded value) became non-finite; the
                message names time, node and quantity, and ``err.result`` holds what was
                recorded before (finite rows only).
            beltrs.BeltrsError: another run, stabilise or step of this simulation is in
                progress in another thread.
        """
        duration = _real("duration", duration, "must be a finite number ≥ 0 (s)", lambda v: v >= 0)
        if record_every is not None and record_interval is not None:
            raise _beltrs.SceneError("give record_every or record_interval, not both")
        tension = _flag("tension", tension)
        node_position = _flag("node_position", node_position)
        node_velocity = _flag("node_velocity", node_velocity)
        energy = _flag("energy", energy)
        contact_forces = _flag("contact_forces", contact_forces)
        progress = _flag("progress", progress, none=True)
        dt = self.dt
        every = max(1, int(round(self.default_record_interval() / dt)))
        if record_every is not None:
            every = _whole("record_every", record_every, low=1)
        elif record_interval is not None:
            record_interval = _real("record_interval", record_interval, "must be > 0 (s)", lambda v: v > 0)
            ratio = record_interval / dt  # may overflow to inf: compare before converting
            every = _MAX_STEPS if not ratio < _MAX_STEPS else max(1, int(round(ratio)))
        # Whole steps and at most one shortened step (for the bar and the bounds).
        ratio = duration / dt
        steps = math.ceil(ratio - 1e-9) if ratio < _MAX_STEPS else ratio
        if steps > _MAX_STEPS:
            raise _beltrs.SceneError(
                f"duration = {duration}: {steps:.3e} steps of {dt:.3e} s, more than {_MAX_STEPS:.3e}"
            )
        per_sample = self.sample_bytes(tension, node_position, node_velocity, energy, contact_forces)
        if max_samples is None:
            max_memory = _real("max_memory", max_memory, "must be a finite number > 0 (bytes)", lambda v: v > 0)
            max_samples = int(min(max_memory // per_sample, _MAX_STEPS))
            if max_samples < 2:
                raise _beltrs.SceneError(
                    f"max_memory = {max_memory:g}: must hold at least 2 samples of {per_sample} bytes"
                )
        elif isinstance(max_samples, numbers.Integral) and not isinstance(max_samples, bool) and max_samples < 2:
            raise _beltrs.SceneError(f"max_samples = {max_samples}: must be ≥ 2")
        else:
            max_samples = _whole("max_samples", max_samples, low=2)
        if checkpoint is not None:
            checkpoint = _path("checkpoint", checkpoint)
            checkpoint_interval = _real("checkpoint_interval", checkpoint_interval, "must be ≥ 0 (s)", lambda v: v >= 0)
        if max_wall_time is not None:
            max_wall_time = _real("max_wall_time", max_wall_time, "must be > 0 (s) or None", lambda v: v > 0)

        with self._exclusive("run"):
            return self._run(
                duration, steps, every, (tension, node_position, node_velocity, energy, contact_forces),
                max_samples, progress,
                checkpoint, checkpoint_interval, max_wall_time,
            )

    def _run(
        self,
        duration: float,
        steps: int,
        every: int,
        channels: tuple[bool, bool, bool, bool, bool],
        max_samples: int,
        progress: Optional[bool],
        checkpoint: Optional[str],
        checkpoint_interval: float,
        max_wall_time: Optional[float],
    ) -> Result:
        core = self._core
        self._adaptive_start = (int(core.accepted_steps), int(core.rejected_steps))
        estimate = steps * _estimate_step_seconds(core) if steps > 0 else 0.0
        if max_wall_time is not None and estimate > max_wall_time:
            raise _beltrs.SceneError(
                f"duration = {duration:.6g} s: {steps:.3e} steps of {self.dt:.3e} s would take about "
                f"{_human(estimate)} of wall time here, more than max_wall_time = {_human(max_wall_time)}; "
                "shorten the run, coarsen the scene, or pass max_wall_time=None to run it anyway"
            )
        if progress is None and estimate > PROGRESS_AFTER:
            progress = True
        checkpoint_error: Optional[BaseException] = None

        def save(first: bool = False) -> None:
            nonlocal checkpoint_error
            if checkpoint is None:
                return
            try:
                self.save_checkpoint(checkpoint)
            except _beltrs.CheckpointError as err:
                if first:
                    raise
                checkpoint_error = err
                warnings.warn(f"{err}; the run goes on (Result.checkpoint_error)", CheckpointWarning, stacklevel=4)

        save(first=True)
        if self._placed:
            diagnostics.check_relaxed(self)
            diagnostics.check_idlers(self)
            self._placed = False

        end = self.time + duration
        t0 = _time.perf_counter()
        last_checkpoint = t0
        interrupted = False
        bar = make_bar(progress, steps, end)
        with _DeferSignals():
            try:
                core.begin_recording(every, *channels[:3], max_samples, *channels[3:])
                try:
                    # Short chunks (about 0.1 s of wall time each) keep the bar live and let
                    # other threads in between them (a checkpoint, a parameter change); each
                    # chunk runs in Rust without the GIL and polls Ctrl-C every ~20 ms,
                    # stopping at a whole step, so the state is consistent when it lands.
                    chunk = 64
                    done = False
                    while not done:
                        before = int(core.step_count)
                        c0 = _time.perf_counter()
                        done = core.advance_to(end, chunk)
                        now = _time.perf_counter()
                        chunk = _next_chunk(chunk, now - c0)
                        bar.update(int(core.step_count) - before, self.time)
                        if checkpoint is not None and now - last_checkpoint >= checkpoint_interval:
                            save()
                            last_checkpoint = _time.perf_counter()
                except KeyboardInterrupt:
                    interrupted = True
                core.end_recording(interrupted)
                rec, record_every = self._with_final_sample(channels, interrupted)
            except _beltrs.DivergenceError as err:
                err.result = self._result(  # type: ignore[attr-defined]
                    _time.perf_counter() - t0, checkpoint_error=checkpoint_error
                )
                self.last_result = err.result  # type: ignore[attr-defined]
                raise
            finally:
                bar.close()
            save()
            self.last_result = self._result(_time.perf_counter() - t0, rec, record_every, checkpoint_error)
        return self.last_result

    def _with_final_sample(
        self, channels: tuple[bool, bool, bool, bool, bool], interrupted: bool
    ) -> tuple[dict[str, Any], int]:
        """The recording just closed (taken over from the engine without a copy), with the
        final state appended when it fell between two instants of the recording grid, so
        that the last instant is the end of the run; and the grid's interval in steps."""
        core = self._core
        every = int(core.record_every)
        rec = dict(core.take_recording())
        times = np.asarray(rec["time"])
        if len(times) and times[-1] == self.time:
            return rec, every
        # Sample the final state through a fresh one-instant recording and append it.
        core.begin_recording(1, *channels[:3], 2, *channels[3:])
        core.end_recording(interrupted)
        last = dict(core.take_recording())
        for key, value in rec.items():
            if isinstance(value, np.ndarray) and key in last:
                rec[key] = np.concatenate([value, np.asarray(last[key])], axis=0)
        return rec, every

    def sample_bytes(
        self,
        tension: bool = True,
        node_position: bool = True,
        node_velocity: bool = True,
        energy: bool = False,
        contact_forces: bool = False,
    ) -> int:
        """Bytes one recorded instant takes with these channels:
        ``8 * (1 + 7*energy + E*(tension + 2*node_position + 2*node_velocity) + 14*P + 2*I
        + 3*P*E*contact_forces)``."""
        return int(
            self._core.sample_bytes(
                _flag("tension", tension),
                _flag("node_position", node_position),
                _flag("node_velocity", node_velocity),
                _flag("energy", energy),
                _flag("contact_forces", contact_forces),
            )
        )

    def _result(
        self,
        wall: float,
        rec: Optional[dict[str, Any]] = None,
        record_every: Optional[int] = None,
        checkpoint_error: Optional[BaseException] = None,
    ) -> Result:
        # The recording's buffers are handed over to NumPy (no copy) and the recorder is
        # left empty, so the memory of a run is held once.
        return Result._from_core(
            dict(self._core.take_recording()) if rec is None else rec,
            checkpoint_error=checkpoint_error,
            dt=self.dt,
            stages=self.stages,
            wall_time=wall,
            interrupted=bool(self._core.interrupted),
            pulley_names=[p.name for p in self.scene.pulleys],
            record_every=int(self._core.record_every) if record_every is None else record_every,
            steps_accepted=int(self._core.accepted_steps) - getattr(self, "_adaptive_start", (0, 0))[0],
            steps_rejected=int(self._core.rejected_steps) - getattr(self, "_adaptive_start", (0, 0))[1],
            metadata={"rest_length": self.rest_length, **self._pulley_constants()},
        )

    def _pulley_constants(self) -> dict[str, Any]:
        """Constants a Result needs for its engineering views (signs along the direction of
        travel, surface speed, capstan): each pulley's radius, m; +1/-1 for a belt wrapping
        it counter-clockwise/clockwise in node order; its static friction coefficient (0
        without); and the belt's direction of travel (+1 node order, -1 against, 0 unknown):
        the direction the loads carry material, else the one the speed-controlled drives'
        starting curves run the belt, if they agree."""
        pulleys = self.scene.pulleys
        direction = 0
        loads = {d for _, d in diagnostics._belt_direction(self)} if self.scene.loads else set()
        if len(loads) == 1:
            direction = loads.pop()
        else:
            drives = {
                int(np.sign(p.drive.start_curve.speed)) * (1 if p.wrap == "ccw" else -1)
                for p in pulleys
                if p.drive is not None and p.drive.start_curve is not None and p.drive.start_curve.speed
            }
            if len(drives) == 1:
                direction = drives.pop()
        return {
            "pulley_radius": np.array([float(p.radius) for p in pulleys]),
            "pulley_wrap_sign": np.array([1.0 if p.wrap == "ccw" else -1.0 for p in pulleys]),
            "pulley_friction_static": np.array(
                [float(p.friction.static) if p.friction is not None else 0.0 for p in pulleys]
            ),
            "travel_direction": int(direction),
        }

    # --- checkpoints -------------------------------------------------------------------
    def save_checkpoint(self, path: Union[str, os.PathLike]) -> None:
        """Save the scene and the full state to ``path``, atomically (a temporary file in
        the same directory, flushed to disk, then renamed over ``path``: a crash leaves the
        old file). The recording is not saved. Format: ``docs/runtime.md``.

        Raises:
            beltrs.CheckpointError: the file cannot be written (the message names the file
                and the cause).
        """
        self._core.save_checkpoint(_path("path", path))

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
        if scene is not None and not isinstance(scene, Scene):
            raise _beltrs.SceneError(f"scene = {scene!r}: must be a beltrs.Scene or None")
        core = _beltrs.Simulation.load_checkpoint(_path("path", path), None if scene is None else scene.to_dict())
        sim = cls.__new__(cls)
        sim._core = core
        sim._busy = threading.Lock()
        sim.scene = scene if scene is not None else Scene.from_dict(dict(core.scene_dict()))
        sim.last_result = None
        sim._placed = False
        return sim

    def step(self, steps: int = 1) -> None:
        """Advance ``steps`` steps (a whole number ≥ 0) without recording.

        Raises:
            KeyboardInterrupt: on Ctrl-C, within about 0.1 s, at a whole step (the state is
                consistent and :attr:`time` tells how far it got).
            beltrs.DivergenceError: the state became non-finite.
        """
        steps = _whole("steps", steps)
        with self._exclusive("step"):
            self._core.step(steps)
        self._placed = False

    # --- change a parameter and continue ----------------------------------------------
    def set_scene(self, scene: Scene) -> None:
        """Swap in changed parameters and keep the state. The belt discretisation, the
        pulley centres and takeup lines must stay the same."""
        if not isinstance(scene, Scene):
            raise _beltrs.SceneError(f"scene = {scene!r}: must be a beltrs.Scene")
        scene_dict = scene.to_dict()
        self._core.set_scene(scene_dict)
        self.scene = scene
        warn_scene(scene)
        diagnostics.check_drive_directions(self)  # e.g. set_drive with a starting curve
        diagnostics.check_roll_wrap_speed(self, scene_dict)  # e.g. a faster starting curve

    def _pulley(self, pulley: Union[int, str]) -> int:
        """The index of ``pulley`` (an index in [0, P) or a name), else a SceneError. A
        negative index is refused (it would silently pick a pulley from the end)."""
        names = [p.name for p in self.scene.pulleys]
        if isinstance(pulley, str):
            if pulley not in names:
                raise _beltrs.SceneError(
                    f"pulley = {pulley!r}: no pulley of that name (names: {names})"
                )
            return names.index(pulley)
        if isinstance(pulley, bool) or not isinstance(pulley, numbers.Integral):
            raise _beltrs.SceneError(f"pulley = {pulley!r}: must be a pulley index (int) or name (str)")
        if not 0 <= pulley < len(names):
            raise _beltrs.SceneError(
                f"pulley = {pulley}: no such pulley; the scene has {len(names)} (indices 0 to {len(names) - 1})"
            )
        return int(pulley)

    def _with_pulley(self, pulley: Union[int, str], **changes: Any) -> None:
        j = self._pulley(pulley)
        pulleys = list(self.scene.pulleys)
        pulleys[j] = replace(pulleys[j], **changes)
        self.set_scene(replace(self.scene, pulleys=pulleys))

    def set_counterweight(self, pulley: Union[int, str], mass: float) -> None:
        """Set the takeup counterweight of ``pulley`` to ``mass`` kg (e.g. a 10 % step)."""
        j = self._pulley(pulley)
        mass = _real("mass", mass, "must be a finite number ≥ 0 (kg)", lambda v: v >= 0)
        takeup = self.scene.pulleys[j].takeup
        if takeup is None:
            raise _beltrs.SceneError(f"pulleys[{j}].takeup = None: this pulley has no takeup")
        self._with_pulley(j, takeup=replace(takeup, counterweight=mass))

    def set_drive(self, pulley: Union[int, str], drive: Optional[Drive]) -> None:
        """Set (or remove, with None) the drive of ``pulley``. Drive tables and starting
        curves use absolute simulated time (see :attr:`time`): a speed-controlled drive
        started now is ``Drive(start_curve=StartCurve(..., start=sim.time))``
        (``docs/drives.md``)."""
        if drive is not None and not isinstance(drive, Drive):
            raise _beltrs.SceneError(f"drive = {drive!r}: must be a beltrs.Drive or None")
        self._with_pulley(pulley, drive=drive)

    def set_friction(self, pulley: Union[int, str], friction: Optional[Friction]) -> None:
        """Set (or remove) belt friction on ``pulley``."""
        if friction is not None and not isinstance(friction, Friction):
            raise _beltrs.SceneError(f"friction = {friction!r}: must be a beltrs.Friction or None")
        self._with_pulley(pulley, friction=friction)

    def set_brake(self, pulley: Union[int, str], brake: Optional[Brake]) -> None:
        """Set (or remove, with None) the brake of ``pulley``; its ``applied`` time is
        absolute simulated time (a brake applied now: ``Brake(torque=..., applied=sim.time)``;
        ``docs/stops-takeups.md``)."""
        if brake is not None and not isinstance(brake, Brake):
            raise _beltrs.SceneError(f"brake = {brake!r}: must be a beltrs.Brake or None")
        self._with_pulley(pulley, brake=brake)

    def set_holdback(self, pulley: Union[int, str], holdback: Optional[Holdback]) -> None:
        """Set (or remove, with None) the holdback of ``pulley``."""
        if holdback is not None and not isinstance(holdback, Holdback):
            raise _beltrs.SceneError(f"holdback = {holdback!r}: must be a beltrs.Holdback or None")
        self._with_pulley(pulley, holdback=holdback)

    def power_off(self, pulley: Union[int, str, None] = None, at: Optional[float] = None) -> None:
        """Cut the power of the drive of ``pulley`` (every drive if None) at time ``at`` (s,
        absolute simulated time; default now, :attr:`time`): from then on the motor
        supplies no torque and the belt coasts (``Drive.power_off``)."""
        at = self.time if at is None else _real("at", at, "must be a finite number (s)")
        if pulley is None:
            targets = [j for j, p in enumerate(self.scene.pulleys) if p.drive is not None]
            if not targets:
                raise _beltrs.SceneError("pulley = None: the scene has no drive to switch off")
        else:
            j = self._pulley(pulley)
            if self.scene.pulleys[j].drive is None:
                raise _beltrs.SceneError(f"pulleys[{j}].drive = None: this pulley has no drive to switch off")
            targets = [j]
        pulleys = list(self.scene.pulleys)
        for j in targets:
            pulleys[j] = replace(pulleys[j], drive=replace(pulleys[j].drive, power_off=at))
        self.set_scene(replace(self.scene, pulleys=pulleys))

    # --- profiling ---------------------------------------------------------------------
    def set_profiling(self, on: bool) -> None:
        """Per-stage timing on (zeroed) or off. Off costs nothing."""
        self._core.set_profiling(_flag("on", on))

    def profile(self) -> dict[str, float]:
        """Seconds spent in each stage since profiling was turned on."""
        return dict(self._core.profile())

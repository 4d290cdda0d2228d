"""Studies. :func:`sweep` runs many independent cases (start-up studies: curves × loads ×
takeups × stops) on local processes or a Dask cluster into one xarray Dataset
(``beltrs.sweep``, docs/sweeps.md). The rest of this module is about what accuracy costs in
time: run a scene at a ladder of settings and tabulate the answer, its error, the observed
order of convergence, the wall time and the node-steps.

>>> import beltrs
>>> from beltrs import study
>>> table = study.accuracy_cost(
...     beltrs.scenes.hustrulid_loop,           # a factory (called with the setting) or a Scene
...     study.takeup_displacement("takeup"),    # what to measure (a Quantity or any callable)
...     refine="elements", values=[89, 178, 356],
... )
>>> print(table.to_markdown())

Settings that can be refined (``refine=``), with the step size ``h`` used for the orders:

=======================  ===========================================  ===================
``refine``               what changes                                 ``h``
=======================  ===========================================  ===================
``"elements"``           ``belt.elements`` (factory: ``elements=``)   1 / elements
``"element_length"``     elements = round(belt length / value), m     value (m)
``"time_step_fraction"`` fraction of the stability limit              value
``"contact_stiffness"``  every pulley and idler, N/m                  1 / value (m/N)
``"rkf_tolerance"``      ``solver.integrator = "rkf45"`` with this    value
                         ``relative_tolerance`` (absolute tolerance
                         as the scene's)
=======================  ===========================================  ===================

Under ``"rkf_tolerance"`` a factory is called without arguments and its scene's solver is
replaced; the scene must suit RKF45 (creep-rate friction, not stick-force: the engine
refuses the rest with a ``SceneError`` naming the key). The order is then the exponent of
the error in the tolerance (about 0.8 for a 4(5) pair with error-per-step control), the
``dt`` column the mean accepted step over the dynamic run, and node-steps count accepted
steps (each costs six force evaluations, central differences one).

A factory is called with the setting as a keyword (``elements=``, ``time_step_fraction=``,
``contact_stiffness=``; ``element_length`` is turned into ``elements=``), so
:func:`beltrs.scenes.hustrulid_loop` works as it is. A :class:`~beltrs.Scene` is changed with
:func:`dataclasses.replace`.

Each setting: a fresh :class:`~beltrs.Simulation` is built, stabilised (if the quantity asks
for it), the quantity's scenario is run, and the quantity measured. Wall time covers all
of that (it is the price of the answer); node-steps = nodes × (relaxation + dynamic steps).

Errors are against ``exact`` when it is known (an argument, or the quantity's own); else
against a Richardson-extrapolated reference built from the three finest settings,
q* = q₃ + (q₃ − q₂)/(r^p − 1), with p the order those three settings show.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field, replace
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np

from . import _beltrs
from .analysis import arrival_time, hustrulid_tangent_tensions, hustrulid_wave_speed, oscillation
from .analytic import axial_wave_speed, two_pulley_takeup_statics
from .scene import Drive, Friction, Scene
from .simulation import Simulation
from .sweep import set_field, summarise, sweep

__all__ = [
    "Quantity",
    "StudyRow",
    "StudyTable",
    "SETTINGS",
    "accuracy_cost",
    "accuracy_costs",
    "counterweight_step_frequency",
    "hustrulid_tension",
    "hustrulid_wave_speed_quantity",
    "pareto_front",
    "peak_tension",
    "set_field",
    "slip",
    "summarise",
    "sweep",
    "takeup_displacement",
    "tension_difference",
    "wave_arrival_time",
]

#: Settings ``accuracy_cost`` can refine, with their default ladders (coarse to fine).
SETTINGS: dict[str, Optional[tuple[float, ...]]] = {
    "elements": None,  # default: base, 2x, 4x the scene's element count
    "element_length": None,  # default: base, 1/2, 1/4 of the scene's element length
    "time_step_fraction": (0.8, 0.4, 0.2, 0.1),
    "contact_stiffness": (1e7, 1e8, 1e9, 1e10),
    "rkf_tolerance": (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9),
}

SceneSource = Union[Scene, Callable[..., Scene]]


# --- quantities ---------------------------------------------------------------------------
@dataclass
class Quantity:
    """Something to measure, with the scenario that produces it.

    Attributes:
        name: label for tables and plots.
        unit: SI unit of the value.
        measure: ``measure(sim) -> float``, called after the scenario.
        run: ``run(sim)``: the dynamic scenario after stabilisation (set drives, call
            ``sim.run``...). Default None (a static quantity).
        stabilise: relax to static equilibrium first. Default True.
        exact: the exact answer, if known (same unit). Default None (Richardson).
    """

    name: str
    unit: str
    measure: Callable[[Simulation], float]
    run: Optional[Callable[[Simulation], Any]] = None
    stabilise: bool = True
    exact: Optional[float] = None

    def __call__(self, sim: Simulation) -> float:
        return float(self.measure(sim))


def _pulley_index(sim: Simulation, pulley: Union[int, str]) -> int:
    return sim.scene.pulley_index(pulley) if isinstance(pulley, str) else int(pulley)


def takeup_displacement(pulley: Union[int, str] = 1, component: int = 1, exact: Optional[float] = None) -> Quantity:
    """Static displacement of a takeup pulley's centre, m, along axis ``component``
    (0 = x, 1 = y; default y, negative = down, the sign of
    :func:`beltrs.analytic.two_pulley_takeup_statics`). ``exact`` defaults to the case H
    continuum answer (−3.1410 m) when ``pulley`` is ``"takeup"`` or 1 and ``component`` is
    y; pass ``exact=math.nan`` to force a Richardson reference."""

    def measure(sim: Simulation) -> float:
        j = _pulley_index(sim, pulley)
        takeup = sim.scene.pulleys[j].takeup
        if takeup is None:
            raise _beltrs.SceneError(f"pulleys[{j}].takeup = None: takeup_displacement needs a takeup pulley")
        return float(sim.takeup_travel[j] * takeup.direction[component])

    if exact is None and pulley in (1, "takeup") and component == 1:
        exact = two_pulley_takeup_statics().takeup_displacement
    if exact is not None and math.isnan(exact):
        exact = None
    return Quantity("takeup displacement", "m", measure, exact=exact)


def hustrulid_tension(point: str = "A") -> Quantity:
    """Case H static tension at tangent point ``point`` (A, B lower; C, D upper), N, from
    straight-line fits along the strands (:func:`beltrs.analysis.hustrulid_tangent_tensions`).
    Exact: the continuum answer of :func:`beltrs.analytic.two_pulley_takeup_statics`."""
    k = "ABCD".index(point.upper())
    ex = two_pulley_takeup_statics()

    def measure(sim: Simulation) -> float:
        values = hustrulid_tangent_tensions(sim.state()["node_position"], sim.tensions(), -sim.takeup_travel[1])
        return float(values[k])

    exact = ex.lower_tension if k < 2 else ex.upper_tension
    return Quantity(f"tension at {point.upper()}", "N", measure, exact=exact)


Setup = Optional[Callable[[Simulation], Any]]


def _scenario(setup: Setup, duration: float, **record: Any) -> Callable[[Simulation], Any]:
    def run(sim: Simulation) -> Any:
        if setup is not None:
            setup(sim)
        return sim.run(duration, **record)

    return run


def _result(sim: Simulation) -> Any:
    if sim.last_result is None:
        raise _beltrs.BeltrsError("the quantity needs a run: give it a scenario (run=...)")
    return sim.last_result


def peak_tension(duration: float, setup: Setup = None, exact: Optional[float] = None) -> Quantity:
    """Largest element tension over a run of ``duration`` s (recorded every step), N.
    ``setup(sim)`` prepares the run after stabilisation (e.g. sets a drive)."""

    def measure(sim: Simulation) -> float:
        return float(np.max(_result(sim).tension))

    run = _scenario(setup, duration, record_every=1, node_position=False, node_velocity=False)
    return Quantity("peak tension", "N", measure, run=run, exact=exact)


def wave_arrival_time(
    element: int, duration: float, setup: Optional[Callable[[Simulation], Any]] = None, fraction: float = 0.5
) -> Quantity:
    """Time (s, from the start of the run) at which element ``element``'s tension first
    changes by ``fraction`` of its peak change (:func:`beltrs.analysis.arrival_time`).
    Use it with a fixed element count (time-step or contact refinements); under element
    refinement the element index moves along the belt."""

    def measure(sim: Simulation) -> float:
        res = _result(sim)
        return arrival_time(res.time, res.tension[:, element], fraction) - float(res.time[0])

    run = _scenario(setup, duration, record_every=1, node_position=False, node_velocity=False)
    return Quantity("wave arrival time", "s", measure, run=run)


def hustrulid_wave_speed_quantity(
    side: int = 1,
    torque: float = 4e5,
    pulse: float = 0.07,
    duration: float = 0.6,
    gap_m: float = 26.0,
    friction: Friction = Friction(static=0.5, kinetic=0.4),
) -> Quantity:
    """Case H axial wave speed, m/s of material, from a ``torque`` N·m pulse of ``pulse`` s
    on the upper pulley (thesis §6.4.1), with ``friction`` on both pulleys to carry the
    torque into the belt, measured over ``gap_m`` m of strand
    (:func:`beltrs.analysis.hustrulid_wave_speed`, 10 elements at 89). Exact: √(EA/ρ)."""

    def setup(sim: Simulation) -> None:
        # Friction carries the pulley torque into the belt (as in tests/test_case_h.py).
        sim.set_friction(0, friction)
        sim.set_friction(1, friction)
        sim.set_drive(0, Drive.pulse(torque, pulse, start=sim.time))

    def measure(sim: Simulation) -> float:
        res = _result(sim)
        gap = max(1, int(round(gap_m / sim.rest_length[0])))
        return hustrulid_wave_speed(res.time, res.tension, res.node_position[0], sim.rest_length[0], side, gap)

    belt = Scene().belt  # case H defaults: EA 7.62 MN, 100 kg/m
    run = _scenario(setup, duration, record_every=1, node_velocity=False)
    return Quantity(
        "wave speed", "m/s", measure, run=run, exact=axial_wave_speed(belt.axial_stiffness, belt.mass_per_length)
    )


def counterweight_step_frequency(
    pulley: Union[int, str] = 1, counterweight: float = 33_000.0, duration: float = 12.0, record_interval: float = 0.005
) -> Quantity:
    """Frequency (Hz) of the takeup oscillation after the counterweight of ``pulley`` is set
    to ``counterweight`` kg at rest in equilibrium (case H: +10 %), over ``duration`` s
    (:func:`beltrs.analysis.oscillation`). No exact answer (the Rayleigh estimates are
    approximations): Richardson."""

    def setup(sim: Simulation) -> None:
        sim.set_counterweight(pulley, counterweight)

    def measure(sim: Simulation) -> float:
        res = _result(sim)
        j = _pulley_index(sim, pulley)
        return oscillation(res.time, res.takeup_travel[:, j])[2]

    run = _scenario(
        setup, duration, record_interval=record_interval, tension=False, node_position=False, node_velocity=False
    )
    return Quantity("counterweight-step frequency", "Hz", measure, run=run)


def _steady_window(time: np.ndarray, window: float) -> np.ndarray:
    return time >= time[-1] - window


def slip(
    drive: Union[int, str],
    driven: Union[int, str],
    duration: float,
    setup: Optional[Callable[[Simulation], Any]] = None,
    window: float = 0.1,
    stabilise: bool = True,
    record_interval: Optional[float] = None,
) -> Quantity:
    """Speed loss of a belt drive, 1 − ω₂r₂/(ω₁r₁) (drive 1, driven 2), averaged over the
    last ``window`` s of a ``duration`` s run (dimensionless). Sampled every
    ``record_interval`` s (default None: every 10 steps)."""

    def measure(sim: Simulation) -> float:
        res = _result(sim)
        i, j = _pulley_index(sim, drive), _pulley_index(sim, driven)
        keep = _steady_window(res.time, window)
        r1, r2 = sim.scene.pulleys[i].radius, sim.scene.pulleys[j].radius
        w1 = float(np.mean(res.pulley_speed[keep, i]))
        w2 = float(np.mean(res.pulley_speed[keep, j]))
        return 1.0 - (w2 * r2) / (w1 * r1)

    run = _scenario(setup, duration, **_every(record_interval), tension=False, node_position=False, node_velocity=False)
    return Quantity("slip", "-", measure, run=run, stabilise=stabilise)


def _every(record_interval: Optional[float]) -> dict[str, Any]:
    return {"record_every": 10} if record_interval is None else {"record_interval": record_interval}


def tension_difference(
    drive: Union[int, str],
    driven: Union[int, str],
    duration: float,
    setup: Optional[Callable[[Simulation], Any]] = None,
    window: float = 0.1,
    exact: Optional[float] = None,
    stabilise: bool = True,
    record_interval: Optional[float] = None,
) -> Quantity:
    """T₁ − T₂ (N) of a two-pulley belt drive: the median tension of the elements in the
    middle 60 % of each free span (between the pulley centres, one span on each side of the
    line joining them), over the last ``window`` s of a ``duration`` s run; tight minus
    slack. In steady running it must equal M/r of the drive pulley (force balance).
    Sampled every ``record_interval`` s (default None: every 10 steps)."""

    def measure(sim: Simulation) -> float:
        res = _result(sim)
        c1 = np.asarray(sim.scene.pulleys[_pulley_index(sim, drive)].center, dtype=float)
        c2 = np.asarray(sim.scene.pulleys[_pulley_index(sim, driven)].center, dtype=float)
        keep = _steady_window(res.time, window)
        u = c2 - c1
        x = res.node_position[keep]
        mid = 0.5 * (x + np.roll(x, -1, axis=1)) - c1
        along = (mid @ u) / (u @ u)
        side = mid[..., 0] * u[1] - mid[..., 1] * u[0]
        span = (along > 0.2) & (along < 0.8)
        t = res.tension[keep]
        a = float(np.median(t[span & (side > 0)]))
        b = float(np.median(t[span & (side < 0)]))
        return abs(a - b)

    run = _scenario(setup, duration, **_every(record_interval), node_velocity=False)
    return Quantity("T1 - T2", "N", measure, run=run, exact=exact, stabilise=stabilise)


# --- the table ----------------------------------------------------------------------------
@dataclass
class StudyRow:
    """One setting of a study.

    Attributes:
        setting: the refined setting's value (unit of the setting).
        h: step size used for the orders (see the module docstring).
        nodes: belt nodes.
        time_step: s (under RKF45 the mean accepted step).
        value: the quantity (its unit).
        error: |value − reference| (the quantity's unit).
        order: observed order of convergence reaching this row (NaN for the first rows).
        wall_time: s, build + stabilise + run + measure.
        node_steps: nodes × (relaxation steps + dynamic steps).
    """

    setting: float
    h: float
    nodes: int
    time_step: float
    value: float
    error: float
    order: float
    wall_time: float
    node_steps: int


@dataclass
class StudyTable:
    """Result of :func:`accuracy_cost`.

    Attributes:
        refine: the setting refined.
        quantity: the quantity's name.
        unit: its unit.
        reference: the value errors are measured against.
        reference_kind: ``"exact"``, ``"richardson"`` or ``"finest"`` (Richardson refused
            because the three finest values are not monotone; errors are then against
            the finest value and say little about it).
        richardson_order: the order shown by the three finest settings (NaN if exact).
        rows: coarse to fine.
    """

    refine: str
    quantity: str
    unit: str
    reference: float
    reference_kind: str
    richardson_order: float
    rows: list[StudyRow] = field(default_factory=list)

    def _col(self, name: str) -> np.ndarray:
        return np.array([getattr(r, name) for r in self.rows], dtype=float)

    @property
    def setting(self) -> np.ndarray:
        """``[n]`` setting values."""
        return self._col("setting")

    @property
    def value(self) -> np.ndarray:
        """``[n]`` quantity values."""
        return self._col("value")

    @property
    def error(self) -> np.ndarray:
        """``[n]`` errors."""
        return self._col("error")

    @property
    def order(self) -> np.ndarray:
        """``[n]`` observed orders (NaN where not defined)."""
        return self._col("order")

    @property
    def wall_time(self) -> np.ndarray:
        """``[n]`` wall times, s."""
        return self._col("wall_time")

    @property
    def node_steps(self) -> np.ndarray:
        """``[n]`` node-steps."""
        return self._col("node_steps")

    def to_dict(self) -> dict[str, Any]:
        """Plain data (JSON-ready)."""
        return {
            "refine": self.refine,
            "quantity": self.quantity,
            "unit": self.unit,
            "reference": self.reference,
            "reference_kind": self.reference_kind,
            "richardson_order": self.richardson_order,
            "rows": [dict(r.__dict__) for r in self.rows],
        }

    def to_markdown(self, scale: float = 1.0, unit: Optional[str] = None, digits: int = 6) -> str:
        """A Markdown table; values and errors multiplied by ``scale`` and labelled ``unit``."""
        u = unit if unit is not None else self.unit
        head = (
            f"| {self.refine} | nodes | dt (ms) | {self.quantity} ({u}) | error ({u}) | order | wall (s) "
            "| node-steps |"
        )
        rule = "|---:|---:|---:|---:|---:|---:|---:|---:|"
        lines = [head, rule]
        for r in self.rows:
            order = "" if math.isnan(r.order) else f"{r.order:.2f}"
            lines.append(
                f"| {r.setting:.4g} | {r.nodes} | {r.time_step * 1e3:.4g} | {r.value * scale:.{digits}g} | "
                f"{r.error * scale:.3g} | {order} | {r.wall_time:.3g} | {r.node_steps:.3g} |"
            )
        ref = f"reference {self.reference * scale:.{digits + 1}g} {u} ({self.reference_kind}"
        if self.reference_kind == "richardson":
            ref += f", order {self.richardson_order:.2f} from the three finest"
        lines.append("")
        lines.append(ref + ")")
        return "\n".join(lines)

    def against(self, reference: float, kind: str) -> "StudyTable":
        """The same runs with errors and orders against another ``reference`` (the
        quantity's unit), labelled ``kind`` (e.g. ``"RKF45 at 1e-9"``): to compare ladders
        of different settings against one common reference."""
        rows = [replace(r, error=abs(r.value - reference), order=math.nan) for r in self.rows]
        for i in range(1, len(rows)):
            e0, e1, h0, h1 = rows[i - 1].error, rows[i].error, rows[i - 1].h, rows[i].h
            if e0 > 0 and e1 > 0 and h0 != h1:
                rows[i].order = math.log(e0 / e1) / math.log(h0 / h1)
        return StudyTable(self.refine, self.quantity, self.unit, float(reference), kind, math.nan, rows)

    def pareto(self) -> list[int]:
        """Indices of the rows on the error-versus-wall-time Pareto front."""
        return pareto_front(self.wall_time, self.error)


def pareto_front(cost: Sequence[float], error: Sequence[float]) -> list[int]:
    """Indices of the points no other point beats in both cost and error, by cost."""
    c = np.asarray(cost, dtype=float)
    e = np.asarray(error, dtype=float)
    order = np.lexsort((e, c))
    front, best = [], math.inf
    for i in order:
        if e[i] < best:
            front.append(int(i))
            best = e[i]
    return front


# --- orders ---------------------------------------------------------------------------------
def _three_point_order(h: Sequence[float], q: Sequence[float]) -> float:
    """Order p for q(h) = q* + C h^p through three points (h decreasing); NaN if the
    differences change sign or vanish."""
    d1, d2 = q[0] - q[1], q[1] - q[2]
    if d1 == 0.0 or d2 == 0.0 or (d1 > 0) != (d2 > 0):
        return math.nan
    ratio = d1 / d2
    r1, r2 = h[0] / h[1], h[1] / h[2]
    if abs(r1 - r2) < 1e-9 * r1:
        return math.log(ratio) / math.log(r1)

    # d1/d2 = r2^p (r1^p - 1)/(r2^p - 1): increasing in p; bisect on [1e-3, 20].
    def f(p: float) -> float:
        return math.log(r2**p * (r1**p - 1) / (r2**p - 1)) - math.log(ratio)

    lo, hi = 1e-3, 20.0
    if f(lo) > 0 or f(hi) < 0:
        return math.nan
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)


def _reference(h: np.ndarray, q: np.ndarray) -> tuple[float, str, float]:
    p = _three_point_order(h[-3:], q[-3:])
    if math.isnan(p) or p <= 0:
        return float(q[-1]), "finest", p
    r = h[-2] / h[-1]
    return float(q[-1] + (q[-1] - q[-2]) / (r**p - 1.0)), "richardson", p


# --- the study ------------------------------------------------------------------------------
def _check_setting(refine: str, scene: SceneSource) -> None:
    if refine not in SETTINGS:
        raise _beltrs.SceneError(f"refine = {refine!r}: must be one of {sorted(SETTINGS)}")


def _base_scene(scene: SceneSource) -> Scene:
    return scene if isinstance(scene, Scene) else scene()


def _belt_length(scene: Scene) -> float:
    if scene.belt.length is not None:
        return float(scene.belt.length)
    return Simulation(scene).path_length


def _default_values(refine: str, scene: SceneSource) -> list[float]:
    if refine in ("elements", "element_length"):
        sim = Simulation(_base_scene(scene))
        if refine == "elements":
            return [sim.nodes, 2 * sim.nodes, 4 * sim.nodes]
        length = _belt_length(_base_scene(scene)) / sim.nodes
        return [length, length / 2, length / 4]
    default = SETTINGS[refine]
    assert default is not None
    return list(default)


def _scene_at(scene: SceneSource, refine: str, value: float) -> Scene:
    if refine == "element_length":
        if not value > 0:
            raise _beltrs.SceneError(f"element_length = {value}: must be > 0 (m)")
        n = max(3, int(round(_belt_length(_base_scene(scene)) / value)))
        refine, value = "elements", n
    if refine == "rkf_tolerance":
        base = _base_scene(scene)
        solver = replace(base.solver, integrator="rkf45", time_step=None, relative_tolerance=float(value))
        return replace(base, solver=solver)
    if not isinstance(scene, Scene):
        kw = {refine: int(value) if refine == "elements" else float(value)}
        return scene(**kw)
    if refine == "elements":
        return replace(scene, belt=replace(scene.belt, elements=int(value)))
    if refine == "time_step_fraction":
        return replace(scene, solver=replace(scene.solver, time_step=None, time_step_fraction=float(value)))
    if refine == "contact_stiffness":
        return replace(
            scene,
            pulleys=[replace(p, contact_stiffness=float(value)) for p in scene.pulleys],
            idlers=[replace(d, contact_stiffness=float(value)) for d in scene.idlers],
        )
    raise AssertionError(refine)


def _h(refine: str, value: float) -> float:
    if refine == "elements":
        return 1.0 / value
    if refine == "contact_stiffness":
        return 1.0 / value
    return float(value)


def _mean_step(sim: Simulation) -> float:
    """The central-difference step, or under RKF45 the mean accepted step of the run(s), s."""
    accepted = int(sim._core.accepted_steps)
    if sim.scene.solver.integrator == "rkf45" and accepted > 0:
        return float(sim.time) / accepted
    return float(sim.dt)


def _as_quantity(quantity: Union[Quantity, Callable[[Simulation], float]]) -> Quantity:
    if isinstance(quantity, Quantity):
        return quantity
    return Quantity(getattr(quantity, "__name__", "quantity"), "", quantity)


def run_setting(
    scene: Scene, quantity: Union[Quantity, Callable[[Simulation], float]], stabilise_options: Optional[dict] = None
) -> tuple[float, Simulation, float, int]:
    """Build, stabilise (if asked), run the scenario and measure once.

    Returns (value, simulation, wall time s, node-steps)."""
    values, sim, wall, node_steps = _run_setting(scene, [_as_quantity(quantity)], stabilise_options)
    return values[0], sim, wall, node_steps


def _run_setting(
    scene: Scene, quantities: Sequence[Quantity], stabilise_options: Optional[dict]
) -> tuple[list[float], Simulation, float, int]:
    q = quantities[0]
    t0 = _time.perf_counter()
    sim = Simulation(scene)
    relax = 0
    if q.stabilise:
        relax = int(sim.stabilise(**(stabilise_options or {}))["steps"])
    step0 = int(sim.state()["step"])
    if q.run is not None:
        q.run(sim)
    values = [qq(sim) for qq in quantities]
    wall = _time.perf_counter() - t0
    steps = relax + int(sim.state()["step"]) - step0
    return values, sim, wall, sim.nodes * steps


def accuracy_cost(
    scene: SceneSource,
    quantity: Union[Quantity, Callable[[Simulation], float]],
    refine: str = "elements",
    values: Optional[Sequence[float]] = None,
    *,
    exact: Optional[float] = None,
    stabilise_options: Optional[dict] = None,
    repeats: int = 1,
) -> StudyTable:
    """Run ``scene`` at a ladder of settings and tabulate value, error, order and cost.

    Args:
        scene: a :class:`~beltrs.Scene`, or a factory called with the setting as keyword
            (``beltrs.scenes.hustrulid_loop``).
        quantity: a :class:`Quantity` (scenario + measurement, e.g.
            :func:`takeup_displacement`) or a callable ``f(sim) -> float`` measured after
            ``sim.stabilise()``.
        refine: ``"elements"``, ``"element_length"`` (m), ``"time_step_fraction"``,
            ``"contact_stiffness"`` (N/m) or ``"rkf_tolerance"`` (RKF45's relative
            tolerance; the scene must suit RKF45). Default ``"elements"``.
        values: the ladder, any order (sorted coarse to fine). Default: 1x, 2x, 4x the
            scene's element count / 1, 1/2, 1/4 of its element length / fractions 0.8,
            0.4, 0.2, 0.1 / stiffness 1e7 to 1e10 N/m / tolerances 1e-4 to 1e-9.
        exact: exact answer (the quantity's unit); overrides the quantity's. Default None:
            the quantity's, else a Richardson reference (needs at least three settings).
        stabilise_options: keyword arguments for :meth:`Simulation.stabilise`.
        repeats: runs per setting; the fastest wall time is kept (the value must not
            change between repeats). Default 1.

    Returns:
        :class:`StudyTable`, rows coarse to fine.

    Raises:
        beltrs.SceneError: unknown or refused setting, bad ladder.
    """
    q = _as_quantity(quantity)
    if exact is not None:
        q = replace(q, exact=exact)
    return accuracy_costs(scene, [q], refine, values, stabilise_options=stabilise_options, repeats=repeats)[0]


def accuracy_costs(
    scene: SceneSource,
    quantities: Sequence[Union[Quantity, Callable[[Simulation], float]]],
    refine: str = "elements",
    values: Optional[Sequence[float]] = None,
    *,
    stabilise_options: Optional[dict] = None,
    repeats: int = 1,
) -> list[StudyTable]:
    """:func:`accuracy_cost` for several quantities measured on the same runs: the first
    quantity's scenario is run (and its ``stabilise`` obeyed), then every quantity is
    measured (the others' ``run`` is not called). One table per quantity, in order, with
    the same wall times and node-steps; each against its own ``exact`` or a Richardson
    reference.

    Raises:
        beltrs.SceneError: as :func:`accuracy_cost`; an empty list of quantities.
    """
    if len(quantities) == 0:
        raise _beltrs.SceneError("quantities = []: give at least one quantity")
    _check_setting(refine, scene)
    if repeats < 1:
        raise _beltrs.SceneError(f"repeats = {repeats}: must be >= 1")
    ladder = list(values) if values is not None else _default_values(refine, scene)
    if len(ladder) < 2:
        raise _beltrs.SceneError(f"values = {ladder}: need at least two settings")
    for v in ladder:
        if not (isinstance(v, (int, float, np.floating, np.integer)) and math.isfinite(v) and v > 0):
            raise _beltrs.SceneError(f"values: {v!r} must be a finite number > 0")
    if refine == "rkf_tolerance" and max(ladder) >= 1:
        raise _beltrs.SceneError(f"values: rkf_tolerance {max(ladder)} must be < 1 (a relative tolerance)")
    if refine == "time_step_fraction" and max(ladder) > 1:
        raise _beltrs.SceneError(f"values: time_step_fraction {max(ladder)} must be <= 1")
    ladder.sort(key=lambda v: -_h(refine, v))
    qs = [_as_quantity(q) for q in quantities]
    if any(q.exact is None for q in qs) and len(ladder) < 3:
        raise _beltrs.SceneError(f"values = {ladder}: a Richardson reference needs at least three settings")

    raw = []
    for v in ladder:
        s = _scene_at(scene, refine, v)
        best = None
        for _ in range(repeats):
            try:
                value, sim, wall, node_steps = _run_setting(s, qs, stabilise_options)
            except _beltrs.BeltrsError as err:
                raise type(err)(f"{refine} = {v}: {err}") from err
            if best is None or wall < best[2]:
                best = (value, sim, wall, node_steps)
        assert best is not None
        raw.append((v, *best))

    h = np.array([_h(refine, r[0]) for r in raw])
    return [_table(refine, q, h, [(r[0], r[1][k], *r[2:]) for r in raw]) for k, q in enumerate(qs)]


def _table(refine: str, q: Quantity, h: np.ndarray, raw: list) -> StudyTable:
    qv = np.array([r[1] for r in raw])
    if q.exact is not None:
        reference, kind, p_ref = float(q.exact), "exact", math.nan
    else:
        reference, kind, p_ref = _reference(h, qv)
    err = np.abs(qv - reference)
    orders = np.full(len(raw), math.nan)
    for i in range(1, len(raw)):
        if kind == "exact":
            if err[i] > 0 and err[i - 1] > 0:
                orders[i] = math.log(err[i - 1] / err[i]) / math.log(h[i - 1] / h[i])
        elif i >= 2:
            orders[i] = _three_point_order(h[i - 2 : i + 1], qv[i - 2 : i + 1])
    rows = [
        StudyRow(
            setting=float(v),
            h=float(h[i]),
            nodes=sim.nodes,
            time_step=_mean_step(sim),
            value=float(value),
            error=float(err[i]),
            order=float(orders[i]),
            wall_time=float(wall),
            node_steps=int(node_steps),
        )
        for i, (v, value, sim, wall, node_steps) in enumerate(raw)
    ]
    return StudyTable(refine, q.name, q.unit, reference, kind, float(p_ref), rows)

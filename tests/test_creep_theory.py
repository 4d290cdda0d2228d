"""A two-pulley belt drive at DEFAULT settings against exact creep theory (issue 11).

The drive is of our own design, given only physical data: pulleys R = 0.1 m, centres
0.5 m apart, a flat belt EA = 15 kN and 0.1 kg/m, pretension 400 N, mu = 0.5, the drive
pulley's speed held at 20 rad/s (2 m/s belt) by a speed-controlled drive, a load torque of
30 N*m on the driven pulley, no gravity, 200 elements. Contact stiffness, contact damping
and the time step are the engine's defaults. The exact answer is
:func:`beltrs.analytic.two_pulley_creep` (Euler-Eytelwein over the slip arc, adhesion arc,
Grashof creep; docs/belt-drives.md): T1 = 554.97 N, T2 = 254.96 N, driven speed
19.614 rad/s (creep 1.93 %), slip arc 1.557 rad on each pulley.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import beltrs
from beltrs import Belt, Drive, Friction, Pulley, Scene, Simulation, StartCurve
from beltrs.analytic import two_pulley_creep

R, D, EA, RHO, T0, MU = 0.1, 0.5, 1.5e4, 0.1, 400.0, 0.5
SPEED, LOAD, ELEMENTS = 2.0, 30.0, 200
SETTLE, WINDOW = 0.25, 0.1  # s: start-up (ramps end at 0.1 s), then the averaging window


def drive_scene(**pulley: object) -> Scene:
    """The drive: physical data only (``pulley`` adds keyword arguments to both pulleys)."""
    path = 2 * D + 2 * math.pi * R
    common: dict = dict(radius=R, mass=1.0, inertia=1e-3, friction=Friction(static=MU, kinetic=MU))
    common.update(pulley)
    return Scene(
        belt=Belt(axial_stiffness=EA, mass_per_length=RHO, length=path / (1 + T0 / EA), elements=ELEMENTS),
        pulleys=[
            # Speed-controlled: 0 to 2 m/s over 0.1 s, then held.
            Pulley(
                name="drive", center=(0.0, 0.0), drive=Drive(start_curve=StartCurve(speed=SPEED, ramp=0.1)), **common
            ),
            # The load torque (clockwise, against the counter-clockwise run), ramped in with the speed.
            Pulley(name="driven", center=(D, 0.0), drive=Drive(time=[0.0, 0.1], torque=[0.0, -LOAD]), **common),
        ],
        gravity=0.0,
    )


@pytest.fixture(scope="module")
def theory() -> beltrs.analytic.CreepDrive:
    return two_pulley_creep(
        drive_radius=R,
        driven_radius=R,
        centre_distance=D,
        axial_stiffness=EA,
        mass_per_length=RHO,
        pretension=T0,
        mu=MU,
        drive_speed=SPEED / R,
        load_torque=LOAD,
    )


@pytest.fixture(
    scope="module",
    params=["node_kelvin_voigt", pytest.param("rigid_body", marks=pytest.mark.slow)],
    ids=["node", "rigid"],
)
def steady(request: pytest.FixtureRequest) -> beltrs.Result:
    """The drive in steady running, with either belt formulation. The rigid-body belt
    (200 bodies resting on the pulleys with their ends at rho = (l/2) cot(l/2R), whose
    polygon holds the arcs' length: docs/kubas.md; 50-75 s of wall) measured 2026-11-23:
    driven speed -0.017 %, T1 +0.04 %, T2 -0.02 %, slip arcs +0.55 % (drive) and +0.59 %
    (driven), utilisation at most 0.015 on the adhesion arcs and 0.996 (median) on the
    slip arcs."""
    scene = drive_scene()
    scene.belt.formulation = request.param
    sim = Simulation(scene)
    # From the placement on purpose: the drive runs up and settles into steady creep.
    with pytest.warns(beltrs.NotRelaxedWarning):
        sim.run(SETTLE)
    return sim.run(WINDOW, record_interval=2e-4)


def span_tensions(res: beltrs.Result) -> tuple[float, float]:
    """Mean tension of the elements in the middle 40 % of the upper (tight) and lower
    (slack) spans over the window."""
    x = res.node_position
    mid = 0.5 * (x + np.roll(x, -1, axis=1))
    middle = (mid[..., 0] > 0.3 * D) & (mid[..., 0] < 0.7 * D)
    upper = middle & (mid[..., 1] > 0.0)
    lower = middle & (mid[..., 1] < 0.0)
    return float(res.tension[upper].mean()), float(res.tension[lower].mean())


def utilisation(res: beltrs.Result, pulley: int, bins: int = 36) -> tuple[np.ndarray, np.ndarray]:
    """Friction utilisation u(psi) = |d ln T / d psi| / mu along the wrap, psi from the
    entry tangent point, from the window-averaged tension of the elements on the pulley
    binned by angle: 0 on an adhesion arc (no tension change), 1 where the belt slides
    (|f| = mu N, the normal force per radian being T)."""
    x = res.node_position
    mid = 0.5 * (x + np.roll(x, -1, axis=1))
    if pulley == 0:  # drive: the belt enters at the top and runs down the left side
        on = mid[..., 0] < 0.0
        psi = np.mod(np.arctan2(mid[..., 1], mid[..., 0]) - math.pi / 2, 2 * math.pi)
    else:  # driven: enters at the bottom and runs up the right side
        on = mid[..., 0] > D
        psi = np.arctan2(mid[..., 1], mid[..., 0] - D) + math.pi / 2
    edges = np.linspace(0.0, math.pi, bins + 1)
    which = np.clip(np.digitize(psi[on], edges) - 1, 0, bins - 1)
    tension = np.bincount(which, weights=res.tension[on], minlength=bins) / np.bincount(which, minlength=bins)
    centres = 0.5 * (edges[1:] + edges[:-1])
    return centres, np.abs(np.gradient(np.log(tension), centres)) / MU


def slip_arc(psi: np.ndarray, u: np.ndarray) -> float:
    """Wrap (pi) minus the angle where the utilisation first crosses 1/2 (linear
    interpolation between bin centres): the arc over which the belt slides."""
    k = int(np.argmax(u > 0.5))
    assert k > 0, "the belt slides from the entry on: no adhesion arc"
    onset = psi[k - 1] + (0.5 - u[k - 1]) * (psi[k] - psi[k - 1]) / (u[k] - u[k - 1])
    return math.pi - onset


def test_creep_theory_exact_answer(theory: beltrs.analytic.CreepDrive) -> None:
    """The exact answer is self-consistent: torque balance, Euler-Eytelwein and Grashof."""
    t1, t2 = theory.tight_tension, theory.slack_tension
    c1, c2 = theory.centrifugal
    assert (t1 - c1) - (t2 - c2) == pytest.approx(LOAD / R, rel=1e-12)
    assert (t1 - c1) / (t2 - c2) == pytest.approx(math.exp(MU * theory.slip_angle), rel=1e-12)
    assert theory.creep == pytest.approx((t1 - t2) / (EA + t1), rel=1e-12)
    assert theory.driven_speed == pytest.approx(SPEED / R * (1 - theory.creep), rel=1e-12)
    # Numbers quoted in the module docstring and docs/belt-drives.md.
    assert (t1, t2) == pytest.approx((554.97, 254.96), abs=0.01)
    assert theory.slip_angle == pytest.approx(1.5572, abs=1e-4)


def test_driven_speed_within_half_a_percent(steady: beltrs.Result, theory: beltrs.analytic.CreepDrive) -> None:
    """Driven pulley speed within 0.5 % of creep theory. The creep is 1.93 %, so a model
    without creep fails this test by four times its tolerance (undamped contact, which
    lets the belt bounce, fails it by 50 %). The discretisation error is far smaller: the
    chord polygon on the wraps changes the belt's strain there by about (l/R)^2/24 = 3e-4
    of the speed (measured error about 0.1 %)."""
    drive, driven = res_speeds = steady.pulley_speed.mean(axis=0)
    assert drive == pytest.approx(SPEED / R, rel=1e-9)  # held by the speed-controlled drive
    assert driven == pytest.approx(theory.driven_speed, rel=5e-3), res_speeds


def test_span_tensions_within_one_percent(steady: beltrs.Result, theory: beltrs.analytic.CreepDrive) -> None:
    """Tight and slack span tensions within 1 % of creep theory. Their difference is set by
    the driven pulley's torque balance alone and is checked to 0.3 %. Their sum comes from
    the conserved belt length: the chord polygon on the 2 x pi wrap holds about
    (l/R)^2/24 = 2.9e-4 less belt than the arcs, which lowers both tensions by about
    EA * 2.9e-4 * 2 pi R / L = 1.7 N (0.7 % of T2; it shrinks as the element angle
    squared). 1 % leaves room for that bias and nothing else."""
    tight, slack = span_tensions(steady)
    assert tight == pytest.approx(theory.tight_tension, rel=1e-2)
    assert slack == pytest.approx(theory.slack_tension, rel=1e-2)
    assert tight - slack == pytest.approx(LOAD / R, rel=3e-3)


@pytest.mark.parametrize("pulley", [0, 1], ids=["drive", "driven"])
def test_slip_arc_within_five_percent(
    steady: beltrs.Result, theory: beltrs.analytic.CreepDrive, pulley: int
) -> None:
    """The slip arc on each pulley within 5 % of creep theory, and Euler-Eytelwein on it:
    the friction is fully used (u = 1) over the slip arc and unused (u = 0) over the
    adhesion arc. The arc is read from the tension profile (one 5 degree bin is 5.6 % of
    the arc; the crossing is interpolated within it, so the reading is good to a fraction
    of a bin, as is the model's transition, which spreads over about one element of 4.8
    degrees). Counting the nodes flagged as slipping reads about 14 % short: at the onset
    of the slip arc the nodes alternate between sticking at the limit and slipping."""
    psi, u = utilisation(steady, pulley)
    arc = slip_arc(psi, u)
    assert arc == pytest.approx(theory.slip_angle, rel=5e-2)
    adhesion = psi < math.pi - arc - 0.15
    sliding = (psi > math.pi - arc + 0.15) & (psi < math.pi - 0.1)
    assert np.all(u[adhesion] < 0.05), u[adhesion]
    assert np.median(u[sliding]) == pytest.approx(1.0, abs=0.02), u[sliding]


def test_undamped_contact_with_friction_warns() -> None:
    """Friction on undamped contact is the bouncing belt: the engine says so."""
    with pytest.warns(beltrs.UndampedContactWarning, match="flutter"):
        Simulation(drive_scene(contact_damping_ratio=0.0))
    with pytest.warns(beltrs.UndampedContactWarning, match=r"pulleys\[0\] \(drive\), pulleys\[1\]"):
        Simulation(drive_scene(contact_damping=0.0))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Simulation(drive_scene(contact_damping=50.0))  # absolute damping: fine
        Simulation(drive_scene(contact_damping_ratio=0.0, friction=None))  # no friction: fine


def test_creep_theory_limits_and_unequal_pulleys() -> None:
    """Unequal pulleys: the wraps add to 2 pi, the speed ratio carries r1/r2, the slip angle
    is the same on both; no load: no creep and no slip arc, T1 = T2 = T0; beyond the
    capstan limit of the smaller wrap the belt slides and the theory refuses."""
    kw = dict(
        centre_distance=0.6, axial_stiffness=EA, mass_per_length=RHO, pretension=T0, mu=MU, drive_speed=20.0
    )
    r = two_pulley_creep(drive_radius=0.08, driven_radius=0.16, load_torque=20.0, **kw)
    assert sum(r.wrap_angles) == pytest.approx(2 * math.pi, rel=1e-12)
    assert r.wrap_angles[0] < math.pi < r.wrap_angles[1]
    speed_ratio = 0.08 / 0.16 * (EA + r.slack_tension) / (EA + r.tight_tension)
    assert r.driven_speed == pytest.approx(20.0 * speed_ratio, rel=1e-12)
    assert r.slip_arc == pytest.approx((0.08 * r.slip_angle, 0.16 * r.slip_angle), rel=1e-12)
    idle = two_pulley_creep(drive_radius=R, driven_radius=R, load_torque=0.0, **kw)
    assert idle.creep == 0.0 and idle.slip_angle == 0.0
    # A belt of fixed length keeps its tension when it spins: the centrifugal term Q*v
    # lowers the contact pressure (T - Q*v)/r instead.
    assert idle.tight_tension == pytest.approx(T0, rel=1e-12)
    assert idle.slack_tension == pytest.approx(T0, rel=1e-12)
    with pytest.raises(beltrs.SceneError, match="capstan limit"):
        two_pulley_creep(drive_radius=R, driven_radius=R, load_torque=80.0, **kw)
    with pytest.raises(beltrs.SceneError, match="mu = -0.5: must be finite and > 0"):
        two_pulley_creep(drive_radius=R, driven_radius=R, load_torque=1.0, **{**kw, "mu": -0.5})


def test_breakaway_friction_above_sliding_runs_as_creep_theory_with_mu_k(theory: beltrs.analytic.CreepDrive) -> None:
    """The same drive with breakaway friction above sliding friction, mu_s = 0.6 > mu_k =
    MU = 0.5, runs as creep theory with mu_k (Grashof: the slip arc slides, at mu_k; the
    adhesion arc carries no friction, so mu_s never acts in steady running): the slip arcs
    within 5 % of the fixture's theory, the slip arcs' nodes sliding, and the drive torque
    steady (issue 12; docs/wrap-contact.md, "Session 10: the drums' stick-slip").

    It can fail. Without Coulomb's kinetic state and the slip front (friction::static_limits:
    a contact that slid, or whose neighbour slid, in the last step has mu_k * N, not mu_s * N)
    the slip arcs' nodes stick up to mu_s * N, break away, slide a few steps and stick
    again; measured then: 5.5 and 3.9 nodes sliding on average (0.29 and 0.20 of the
    theory's 19.1), drive torque ripple 0.080; with them 16.4 and 16.1 (0.86, 0.84) and
    0.024, and 0.023 with mu_s = mu_k. Bounds: the count reads short by the arc's onset,
    which spreads over about two elements (the slip-arc test above: about 14 % short), so
    0.75 of the theory's count; the ripple with mu_s = mu_k is the spans' standing waves
    (0.023), so 0.04."""
    sim = Simulation(drive_scene(friction=Friction(static=0.6, kinetic=MU)))
    with pytest.warns(beltrs.NotRelaxedWarning):
        sim.run(SETTLE)
    res = sim.run(WINDOW, record_interval=2e-4)
    element_angle = 2 * D / ELEMENTS / R + 2 * math.pi / ELEMENTS  # the rest path's share, rad of wrap per element
    nodes_on_arc = theory.slip_angle / element_angle
    for pulley in (0, 1):
        psi, u = utilisation(res, pulley)
        assert slip_arc(psi, u) == pytest.approx(theory.slip_angle, rel=5e-2)
        sliding = res.slipping_nodes[:, pulley].mean()
        assert sliding >= 0.75 * nodes_on_arc, f"pulley {pulley}: {sliding:.1f} of {nodes_on_arc:.1f} nodes slide"
    tau = res.drive_torque[:, 0]
    ripple = float(np.max(np.abs(tau - tau.mean())) / abs(tau.mean()))
    assert ripple < 0.04, f"drive torque ripple {ripple:.4f}"

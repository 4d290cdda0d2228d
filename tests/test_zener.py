"""The viscoelastic (Zener) belt, ``Belt.loss_factor`` / ``Belt.loss_frequency``
(rust/src/belt/node/zener.rs, docs/wrap-contact.md "A viscoelastic belt"): a free
longitudinal vibration decays at the logarithmic decrement of the law, the state resumes
bit for bit from a checkpoint, the law is off (no stage) unless asked for, and bad input is
a SceneError naming the field."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import beltrs
from beltrs import Simulation
from beltrs.analytic import hanging_rope
from test_open_belts import hoist

ETA = 0.1  # the loss factor given; its frequency is the default (5 Hz)


def zener_arm(eta: float, frequency: float) -> tuple[float, float]:
    """(r, tau) of the arm whose loss factor peaks at ``eta`` at ``frequency`` Hz."""
    r = 2 * eta * eta + 2 * eta * math.sqrt(1 + eta * eta)
    return r, 1.0 / (2 * math.pi * frequency * math.sqrt(1 + r))


def test_free_vibration_decays_at_the_decrement_of_the_loss_factor() -> None:
    """The hoist of tests/test_open_belts.py (a 200 kg load on 4.75 m of 2 MN rope over a
    frictionless sheave) with ``loss_factor`` = 0.1 and every other setting the default:
    released 10 % lighter, the load bounces on the rope at about 8 Hz. With the rope's
    mass (0.6 kg/m, 0.5 % of the load) lumped into the load (Rayleigh's rho L/3), the load
    on the Zener rope is one degree of freedom, m s^2 + k (1 + r tau s/(1 + tau s)) = 0:
    its oscillating root gives the decrement exactly, and to first order in the loss factor
    delta = pi tan(delta) at the bounce frequency. The decrement is read from the ratio of
    successive swings (peak to trough, free of the equilibrium's offset) over 8 periods,
    sampled at 1/80 period (0.1 % in a swing). Tolerance 2 % on the exact root (the rope
    mass lumped: its first-mode error is 0.01 %, 0.5 % on the frequency at most) and 5 % on
    pi tan(delta) (the first-order relation's error is O(tan^2 delta) and the loss factor
    varies over the decay's bandwidth). Without the law the rope has no damping and the
    decrement is under 1 % of these."""
    r, tau = zener_arm(ETA, 5.0)
    decrements = {}
    for eta in (ETA, 0.0):
        sim = Simulation(hoist(loss_factor=eta))
        assert sim.stabilise()["converged"]
        sim.set_scene(hoist(mass=180.0, loss_factor=eta))
        rope = sim.path_length
        period = 1.0 / hanging_rope(axial_stiffness=2e6, mass_per_length=0.6, length=rope, mass=180.0).frequency
        res = sim.run(8.0 * period, record_interval=period / 80.0)
        y = res.node_position[:, -1, 1]
        turns = [k for k in range(1, len(y) - 1) if (y[k] - y[k - 1]) * (y[k + 1] - y[k]) < 0]
        swings = np.abs(np.diff(y[turns]))
        decrements[eta] = float(np.mean(2.0 * np.log(swings[:-1] / swings[1:])))
        if eta > 0:
            times = res.time[turns]
            omega = math.pi / float(np.mean(np.diff(times)))
    m = 180.0 + 0.6 * rope / 3.0
    k = 2e6 / rope
    roots = np.roots([m * tau, m, k * (1 + r) * tau, k])
    s = next(z for z in roots if abs(z.imag) > 0)
    exact = -2 * math.pi * s.real / abs(s.imag)
    wt = omega * tau
    tan_delta = r * wt / (1 + (1 + r) * wt * wt)
    assert decrements[ETA] == pytest.approx(exact, rel=0.02), (decrements, exact)
    assert decrements[ETA] == pytest.approx(math.pi * tan_delta, rel=0.05), (decrements, tan_delta)
    assert abs(decrements[0.0]) < 0.01 * exact


def test_the_instantaneous_stiffness_sets_the_step_and_an_unused_law_costs_nothing() -> None:
    """The explicit step's bound takes the arm's instantaneous stiffness (1 + r) EA: the
    lossy rope's step is that of an elastic rope of (1 + r) EA, to the last bit (the same
    bound on the same numbers; the rope's relaxed EA and the arm's r are independent of the
    sheave's contact term in it). Off, the law compiles no stage and carries no state."""
    plain = Simulation(hoist())
    lossy = Simulation(hoist(loss_factor=0.3))
    assert "belt_arms" not in plain.stages and "belt_arms" in lossy.stages
    r, _ = zener_arm(0.3, 5.0)
    stiff = Simulation(hoist(axial_stiffness=2e6 * (1 + r)))
    assert lossy.dt == pytest.approx(stiff.dt, rel=1e-12)
    assert lossy.dt < plain.dt


def test_a_viscoelastic_belt_resumes_bit_for_bit_from_a_checkpoint(tmp_path) -> None:
    a = Simulation(hoist(loss_factor=ETA))
    a.stabilise()
    a.set_scene(hoist(mass=180.0, loss_factor=ETA))
    a.run(0.05)
    a.save_checkpoint(tmp_path / "z.ck")
    b = Simulation.load_checkpoint(tmp_path / "z.ck")
    ra, rb = a.run(0.05, record_interval=2e-3), b.run(0.05, record_interval=2e-3)
    assert np.array_equal(ra.tension, rb.tension)
    assert np.array_equal(ra.node_position, rb.node_position)


def test_loss_factor_round_trips_through_a_scene_file(tmp_path) -> None:
    scene = hoist(loss_factor=0.15, loss_frequency=8.0)
    scene.save(tmp_path / "z.toml")
    back = beltrs.load_scene(tmp_path / "z.toml")
    assert (back.belt.loss_factor, back.belt.loss_frequency) == (0.15, 8.0)
    assert beltrs.Scene().belt.loss_factor == 0.0 and beltrs.Scene().belt.loss_frequency == 5.0


@pytest.mark.parametrize("change, message", [
    (dict(loss_factor=-0.1), r"belt\.loss_factor.*\[0, 1\]"),
    (dict(loss_factor=1.5), r"belt\.loss_factor.*\[0, 1\]"),
    (dict(loss_factor=float("nan")), r"belt\.loss_factor"),
    (dict(loss_frequency=0.0), r"belt\.loss_frequency.*> 0"),
    (dict(loss_frequency=float("inf")), r"belt\.loss_frequency"),
    (dict(loss_factor=0.1, formulation="rigid_body"), r"belt\.loss_factor.*node formulation"),
])
def test_bad_loss_settings_name_the_field(change: dict, message: str) -> None:
    with pytest.raises(beltrs.SceneError, match=message):
        Simulation(hoist(**change))


def test_rkf45_is_refused_with_a_viscoelastic_belt() -> None:
    scene = hoist(loss_factor=0.1)
    scene = replace(scene, solver=replace(scene.solver, integrator="rkf45"))
    with pytest.raises(beltrs.SceneError, match=r"belt\.loss_factor.*rkf45"):
        Simulation(scene)


def test_bad_loss_factor_from_a_scene_file_names_the_field(tmp_path) -> None:
    scene = hoist()
    scene.save(tmp_path / "z.toml")
    text = (tmp_path / "z.toml").read_text()
    assert "loss_factor = 0.0" in text
    text = text.replace("loss_factor = 0.0", "loss_factor = 3.0", 1)
    (tmp_path / "bad.toml").write_text(text)
    with pytest.raises(beltrs.SceneError, match=r"belt\.loss_factor"):
        Simulation(beltrs.load_scene(tmp_path / "bad.toml"))

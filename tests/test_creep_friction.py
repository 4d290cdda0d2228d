"""Creep friction (Kubas 2014 eq. 12-19) as a pulley friction model: scene paths,
defaults, bad input, the memory in checkpoints, and the creep-theory drive at default
settings (docs/belt-drives.md, "Creep friction")."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from test_creep_theory import LOAD, MU, SETTLE, SPEED, WINDOW, drive_scene, span_tensions

import beltrs
from beltrs import Friction, Scene, Simulation
from beltrs.analytic import two_pulley_creep

CREEP = Friction(model="creep", static=MU)


def test_defaults_come_from_the_engine_and_are_documented(tmp_path) -> None:
    f = Friction(model="creep", static=0.5)
    assert f.transition_speed is None and f.creep_limit is None
    sim = Simulation(drive_scene(friction=f))
    sim.save_checkpoint(tmp_path / "c.ck")
    stored = Simulation.load_checkpoint(tmp_path / "c.ck").scene.pulleys[0].friction
    # The engine fills in its documented defaults (1 mm/s, 0.1 mm) and mu_k = mu_s.
    assert stored == Friction(model="creep", static=0.5, kinetic=0.5, transition_speed=1e-3, creep_limit=1e-4)
    assert "pulley_friction" in sim.stages


def test_the_three_scene_paths_agree(tmp_path) -> None:
    f = Friction(model="creep", static=0.4, kinetic=0.3, transition_speed=2e-3, creep_limit=5e-5)
    scene = drive_scene(friction=f)
    as_dict = Scene.from_dict(scene.to_dict())
    assert as_dict == scene
    path = tmp_path / "creep.toml"
    scene.save(path)
    text = path.read_text()
    assert 'model = "creep"' in text and "transition_speed = 0.002" in text
    assert beltrs.load_scene(path) == scene
    sims = [Simulation(s) for s in (scene, as_dict, beltrs.load_scene(path))]
    for s in sims:
        s.step(50)
    positions = [s.state()["node_position"] for s in sims]
    assert all(np.array_equal(p, positions[0]) for p in positions)


@pytest.mark.parametrize(
    ("friction", "message"),
    [
        (
            {"model": "stick_force", "static": 0.5, "transition_speed": 1e-3},
            r'pulleys\[0\]\.friction\.transition_speed = 0\.001: belongs to the creep friction model only',
        ),
        (
            {"model": "stick_force", "static": 0.5, "creep_limit": 1e-4},
            r"pulleys\[0\]\.friction\.creep_limit = 0\.0001: belongs to the creep friction model only",
        ),
        ({"model": "creep", "static": 0.5, "transition_speed": 0.0}, r"friction\.transition_speed = 0: must be > 0"),
        ({"model": "creep", "static": 0.5, "creep_limit": -1e-4}, r"friction\.creep_limit = -0\.0001: must be > 0"),
        ({"model": "creep", "static": 0.5, "creep_limit": math.nan}, r"friction\.creep_limit = NaN: must be a finite"),
        ({"model": "creep", "static": 0.3, "kinetic": 0.4}, r"friction\.kinetic = 0\.4: must not exceed the static"),
        ({"model": "creep", "static": 0.5, "transition_speed": "fast"}, r"transition_speed = 'fast': expected"),
        ({"model": "creap", "static": 0.5}, r'friction\.model = "creap": unknown friction model, did you mean "creep"'),
    ],
)
def test_bad_creep_friction_is_a_scene_error(friction: dict, message: str) -> None:
    data = drive_scene().to_dict()
    data["pulleys"][0]["friction"] = friction
    with pytest.raises(beltrs.SceneError, match=message):
        Simulation(Scene.from_dict(data))


def test_creep_friction_on_an_idler_is_refused() -> None:
    scene = beltrs.scenes.hustrulid_loop(elements=89)
    scene.idlers.append(beltrs.Idler(center=(5.0 + 0.0635, 50.0), friction=Friction(model="creep", static=0.3)))
    with pytest.raises(beltrs.SceneError, match=r"idlers\[0\]\.friction\.model = \"creep\": .*pulleys only"):
        Simulation(scene)


def test_the_memory_resumes_from_a_checkpoint_bit_for_bit(tmp_path) -> None:
    scene = drive_scene(friction=CREEP)
    a = Simulation(scene)
    with pytest.warns(beltrs.NotRelaxedWarning):
        a.run(0.05)
    memory = a.state()["creep_displacement"]
    assert memory.shape == (a.nodes, 2)
    assert np.count_nonzero(memory) > 10  # the contacts on both pulleys carry creep
    assert np.abs(memory).max() <= 1e-4 * (1 + 1e-6) + 1e-6  # held at Delta_max (Euler overshoot < v dt)
    path = tmp_path / "creep.ck"
    a.save_checkpoint(path)
    b = Simulation.load_checkpoint(path)
    ra, rb = a.run(0.01, record_interval=1e-3), b.run(0.01, record_interval=1e-3)
    assert np.array_equal(ra.tension, rb.tension)
    assert np.array_equal(ra.pulley_speed, rb.pulley_speed)
    # A run that had no memory in its checkpoint would differ: the creep matters.
    c = Simulation.load_checkpoint(path)
    c.set_friction("drive", Friction(static=MU))
    c.set_friction("driven", Friction(static=MU))
    rc = c.run(0.01, record_interval=1e-3)
    assert not np.array_equal(ra.tension, rc.tension)


@pytest.fixture(scope="module")
def steady_creep() -> beltrs.Result:
    sim = Simulation(drive_scene(friction=CREEP))
    with pytest.warns(beltrs.NotRelaxedWarning):
        sim.run(SETTLE)
    return sim.run(WINDOW, record_interval=2e-4)


def test_the_creep_theory_drive_at_default_settings(steady_creep: beltrs.Result) -> None:
    """The drive of test_creep_theory with creep friction at its defaults: the slip arcs
    slide at 1.9 % of 2 m/s = 39 mm/s, far above 1.5 * Delta_v = 1.5 mm/s, so they carry
    mu_k N as creep theory assumes; the adhesion arcs hold with mu below mu_s. The same
    tolerances as the stick-force model there: driven speed 0.5 % (creep is 1.93 %),
    tensions 1 % (the chord polygon lowers both by about 0.7 % of T2)."""
    theory = two_pulley_creep(
        drive_radius=0.1,
        driven_radius=0.1,
        centre_distance=0.5,
        axial_stiffness=1.5e4,
        mass_per_length=0.1,
        pretension=400.0,
        mu=MU,
        drive_speed=SPEED / 0.1,
        load_torque=LOAD,
    )
    driven = float(steady_creep.pulley_speed[:, 1].mean())
    assert driven == pytest.approx(theory.driven_speed, rel=5e-3)
    t1, t2 = span_tensions(steady_creep)
    assert t1 == pytest.approx(theory.tight_tension, rel=1e-2)
    assert t2 == pytest.approx(theory.slack_tension, rel=1e-2)


def test_stick_force_and_creep_agree_on_the_drive(steady_creep: beltrs.Result) -> None:
    sim = Simulation(drive_scene())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", beltrs.NotRelaxedWarning)
        sim.run(SETTLE)
    stick = sim.run(WINDOW, record_interval=2e-4)
    for a, b in zip(span_tensions(stick), span_tensions(steady_creep)):
        assert a == pytest.approx(b, rel=5e-3)
    assert float(stick.pulley_speed[:, 1].mean()) == pytest.approx(
        float(steady_creep.pulley_speed[:, 1].mean()), rel=1e-3
    )

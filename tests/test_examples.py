"""Every example is a scene file that loads, compiles and runs; the named ones equal the
scenes the Python builders make."""

import runpy
import sys
from pathlib import Path

import numpy as np
import pytest

import beltrs
from beltrs import scenes

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
FILES = sorted(EXAMPLES.glob("*.toml"))


def test_examples_exist():
    names = {p.stem for p in FILES}
    assert {"case_h", "case_h_torque_pulse", "idler_conveyor"} <= names


def test_every_example_is_a_scene_file_or_the_script_of_one():
    """examples/ holds scene files, plus a script only where analysis is needed, next to the
    scene file it analyses (same name), or naming the example scene files it reads."""
    others = [p for p in EXAMPLES.iterdir() if p.is_file() and p.suffix != ".toml" and not p.name.startswith(".")]
    for p in others:
        assert p.suffix == ".py", p.name
        named = [f for f in FILES if f.name in p.read_text()]
        assert (EXAMPLES / f"{p.stem}.toml").is_file() or named, p.name


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_every_example_loads_compiles_and_runs(path):
    sim = beltrs.Simulation(beltrs.load_scene(path))
    sim.step(300)
    state = sim.state()
    assert state["step"] == 300
    for key, value in state.items():
        assert np.all(np.isfinite(value)), key
    # Gravity has moved the belt in 300 steps: the run did something.
    assert np.any(state["node_velocity_half_step"] != 0.0)


@pytest.mark.parametrize(
    ("name", "builder"),
    [("case_h", lambda: scenes.hustrulid_loop(89)),
     ("case_h_torque_pulse", lambda: scenes.hustrulid_torque_pulse(89)),
     ("idler_conveyor", scenes.idler_conveyor),
     ("case_g", scenes.guo_wang_conveyor),
     ("case_k", scenes.kubas_case_k),
     ("cepon_boltezar", scenes.cepon_boltezar)],
)
def test_example_equals_its_builder(name, builder):
    assert beltrs.load_scene(EXAMPLES / f"{name}.toml") == builder()


def test_torque_pulse_file_reproduces_the_demo_run():
    """The file's run (friction and drive in the scene from the start, relaxed without
    friction) and the demo's (relaxed frictionless, then friction and drive set) agree."""
    scene = beltrs.load_scene(EXAMPLES / "case_h_torque_pulse.toml")
    a = beltrs.Simulation(scene)
    a.stabilise()
    ra = a.run(0.5, record_interval=0.01, node_velocity=False)
    b = beltrs.Simulation(scenes.hustrulid_loop(89))
    b.stabilise()
    friction = beltrs.Friction(static=0.5, kinetic=0.4)
    b.set_friction(0, friction)
    b.set_friction(1, friction)
    b.set_drive(0, beltrs.Drive.pulse(4e5, 0.07, start=b.time))
    rb = b.run(0.5, record_interval=0.01, node_velocity=False)
    assert a.stages == b.stages
    np.testing.assert_array_equal(ra.tension, rb.tension)
    np.testing.assert_array_equal(ra.pulley_speed, rb.pulley_speed)


def test_idler_conveyor_starts_up_stably():
    """Relax, then 3 s of the drive ramp: the belt moves towards the head on the carry
    side, stays on the idlers, does not slip on the head pulley and stays finite."""
    scene = scenes.idler_conveyor()
    sim = beltrs.Simulation(scene)
    assert "idler_contact" in sim.stages and "idler_friction" in sim.stages
    sim.stabilise()
    res = sim.run(3.0, record_interval=0.05, node_velocity=False)
    assert np.all(np.isfinite(res.tension)) and np.all(np.isfinite(res.node_position))
    # Statics: each strand carries half the counterweight's pull, 9.81 kN, within the
    # sag and weight effects (a few per cent at these tensions).
    assert np.median(res.tension[0]) == pytest.approx(2000 * 9.81 / 2, rel=0.05)
    # The head pulley turns clockwise, faster and faster during the ramp (torque = ramp x
    # motor line: still far from the 2 rad/s no-load speed at 3 s).
    head = res.pulley_speed[:, 1]
    assert head[-1] < -0.5 and np.all(np.diff(head[::10]) < 0)
    # The belt stays on the idlers (every carry idler bears some weight, on average).
    assert np.all(res.idler_force[-20:].mean(axis=0) > 0)
    # Tensions stay in a sane band around the static 9.8 kN.
    assert 5e3 < res.tension.min() and res.tension.max() < 2e4


def test_torque_pulse_script_prints_the_wave_speed(capsys, monkeypatch):
    monkeypatch.setattr(sys, "argv", ["case_h_torque_pulse.py"])
    runpy.run_path(str(EXAMPLES / "case_h_torque_pulse.py"), run_name="__main__")
    out = capsys.readouterr().out
    speeds = [float(line.split(": ")[-1].split(" m/s")[0]) for line in out.splitlines() if "strand" in line]
    # sqrt(EA/rho) = 276.0 m/s; sampled every 0.01 s the half-amplitude reading is within 3 %.
    assert len(speeds) == 2 and all(abs(s / 276.0 - 1) < 0.03 for s in speeds), out


def test_plot_belt_drive_writes_its_pictures(tmp_path, capsys):
    """examples/plot_belt_drive.py runs headless (Agg) on a belt drive scene and writes its
    four PNGs; the Čepon & Boltežar drive, past its load step, is quick."""
    import matplotlib

    backend = matplotlib.get_backend()
    try:
        script = runpy.run_path(str(EXAMPLES / "plot_belt_drive.py"), run_name="plot_belt_drive")
        out = script["main"]([str(EXAMPLES / "cepon_boltezar.toml"), "--out", str(tmp_path), "--duration", "0.35"])
    finally:
        matplotlib.use(backend)
    assert out == tmp_path
    for name in ("speeds", "tensions", "contact_forces", "belt_point"):
        png = tmp_path / f"{name}.png"
        assert png.is_file() and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", name
    printed = capsys.readouterr().out
    assert "slip" in printed and "tight span" in printed

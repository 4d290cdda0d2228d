"""Long runs: checkpoints, the recorder's memory bound, progress bar, Ctrl-C, divergence."""

from __future__ import annotations

import _thread
import signal
import subprocess
import sys
import textwrap
import threading
import time
from dataclasses import fields

import numpy as np
import pytest

import beltrs
from tiny_scene import tiny_scene
from beltrs import Drive, Friction, Idler, Scene
from beltrs.scenes import hustrulid_loop


def busy_case_h() -> Scene:
    """Case H with friction, a drive, a brake, damping and a frictional idler: every part of
    the state changes during a run."""
    scene = hustrulid_loop(89, friction=Friction(static=0.5, kinetic=0.4), damping_ratio=0.02)
    scene.pulleys[0].drive = Drive(time=[0.0, 0.2, 10.0], torque=[0.0, 2e5, 2e5], viscous=10.0)
    scene.pulleys[1].brake = beltrs.Brake(capacity=[1e3])
    scene.idlers = [Idler(center=(5.0 + 0.0635, 50.0), friction=Friction(static=0.5, kinetic=0.4))]
    return scene


def result_arrays(res: beltrs.Result) -> dict[str, np.ndarray]:
    return {f.name: getattr(res, f.name) for f in fields(res) if isinstance(getattr(res, f.name), np.ndarray)}


# --- checkpoints ----------------------------------------------------------------------


def test_resume_from_checkpoint_is_bit_for_bit(tmp_path):
    path = tmp_path / "run.ck"
    a = beltrs.Simulation(busy_case_h())
    with pytest.warns(beltrs.NotRelaxedWarning):  # from the placement, on purpose
        a.run(400 * a.dt, record_every=50, progress=False)
    a.set_counterweight("takeup", 33_000.0)  # a parameter changed mid-run travels along
    a.step(100)
    a.save_checkpoint(path)

    b = beltrs.Simulation.load_checkpoint(path)
    assert b.scene.to_dict() == a.scene.to_dict()
    assert b.scene.pulleys[1].takeup.counterweight == 33_000.0
    ra = a.run(700 * a.dt, record_every=3, progress=False)
    rb = b.run(700 * b.dt, record_every=3, progress=False)
    arrays_a, arrays_b = result_arrays(ra), result_arrays(rb)
    assert arrays_a.keys() == arrays_b.keys() and len(arrays_a) >= 17
    for name, value in arrays_a.items():
        assert np.array_equal(value, arrays_b[name], equal_nan=True), name
    # The run exercised what a checkpoint must carry: turning pulleys and idler, friction.
    assert np.abs(ra.pulley_speed).max() > 1e-3
    assert np.abs(ra.idler_speed).max() > 1e-6
    assert np.abs(ra.friction_torque).max() > 0
    sa, sb = a.state(), b.state()
    for key in sa:
        assert np.array_equal(sa[key], sb[key], equal_nan=True), key


def test_checkpoint_validated_against_given_scene(tmp_path):
    path = tmp_path / "h.ck"
    scene = hustrulid_loop(89)
    beltrs.Simulation(scene).save_checkpoint(path)
    assert beltrs.Simulation.load_checkpoint(path, scene=scene).scene is scene
    other = hustrulid_loop(89, counterweight=31_000.0)
    with pytest.raises(beltrs.CheckpointError, match=r"h\.ck: it holds a different scene .*pulleys\[1\]"):
        beltrs.Simulation.load_checkpoint(path, scene=other)


@pytest.mark.parametrize(
    "damage, message",
    [
        (lambda b: b[: len(b) // 2], "truncated"),
        (lambda b: b[:5], "truncated"),
        (lambda b: b[:100] + bytes([b[100] ^ 1]) + b[101:], "checksum mismatch"),
        (lambda b: b"PK\x03\x04" + b[4:], "not a beltrs checkpoint"),
    ],
)
def test_damaged_checkpoint_names_file_and_problem(tmp_path, damage, message):
    good = tmp_path / "good.ck"
    beltrs.Simulation(tiny_scene()).save_checkpoint(good)
    bad = tmp_path / "bad.ck"
    bad.write_bytes(damage(good.read_bytes()))
    with pytest.raises(beltrs.CheckpointError, match=rf"checkpoint .*bad\.ck: .*{message}"):
        beltrs.Simulation.load_checkpoint(bad)


def test_missing_checkpoint(tmp_path):
    with pytest.raises(beltrs.CheckpointError, match=r"nothing\.ck: cannot read"):
        beltrs.Simulation.load_checkpoint(tmp_path / "nothing.ck")


def test_failed_write_leaves_no_partial_file(tmp_path):
    # The target is a directory: the final rename fails after the temporary file is
    # complete. The error names the target and no temporary file is left behind.
    target = tmp_path / "run.ck"
    target.mkdir()
    (target / "keep").write_text("x")
    sim = beltrs.Simulation(tiny_scene())
    with pytest.raises(beltrs.CheckpointError, match=r"run\.ck: cannot write"):
        sim.save_checkpoint(target)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.ck"]
    assert (target / "keep").read_text() == "x"


def test_killed_writer_never_leaves_a_corrupt_checkpoint(tmp_path):
    # A child saves checkpoints of a 4000-node belt in a loop and is killed with SIGKILL
    # at an arbitrary moment; the checkpoint file must still load (old or new version).
    path = tmp_path / "run.ck"
    code = textwrap.dedent(
        f"""
        import sys, beltrs
        from beltrs import Belt, Pulley, Scene
        s = Scene(belt=Belt(elements=4000), gravity=0.0,
                  pulleys=[Pulley(center=(0.0, 0.0), radius=5.0), Pulley(center=(100.0, 0.0), radius=5.0)])
        sim = beltrs.Simulation(s)
        sim.save_checkpoint({str(path)!r})
        print("ready", flush=True)
        while True:
            sim.step(1)
            sim.save_checkpoint({str(path)!r})
        """
    )
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "ready"
        time.sleep(0.7)
    finally:
        child.kill()
        child.wait()
        child.stdout.close()
    sim = beltrs.Simulation.load_checkpoint(path)
    # It loads, and it is one of the rewritten versions (the child got past the first).
    assert sim.nodes == 4000 and sim.state()["step"] >= 1


# --- memory bound ---------------------------------------------------------------------


def test_million_steps_recorded_every_step_stay_within_bound():
    sim = beltrs.Simulation(tiny_scene())
    bound = 1000
    with pytest.warns(beltrs.NotRelaxedWarning):  # from the placement, on purpose
        # 977 x 1024 steps: the final state lands on the final grid, so the recording
        # measured below is the run's own (no final instant appended).
        res = sim.run(1_000_448 * sim.dt, record_every=1, max_samples=bound, progress=False)
    assert sim.state()["step"] == 1_000_448
    assert bound // 2 <= len(res) <= bound
    # 10^6 steps into at most 1000 samples: the interval doubled to 1024 steps.
    assert res.record_every == 1024
    assert np.allclose(np.diff(res.time), 1024 * sim.dt, rtol=1e-9)
    assert res.time[0] == 0.0 and res.time[-1] == sim.time
    assert np.all(np.isfinite(res.node_position))
    # Memory: the buffers never hold more than the bound (capacity, not just length).
    per_sample = sim.sample_bytes()
    assert per_sample == 8 * (1 + 5 * 16 + 14 * 2)  # energies are opt-in: off here
    assert sim._core.recording_allocated_bytes() <= bound * per_sample


def test_default_bound_comes_from_max_memory():
    sim = beltrs.Simulation(tiny_scene())
    per_sample = sim.sample_bytes(tension=False, node_position=False, node_velocity=False)
    with pytest.warns(beltrs.NotRelaxedWarning):  # from the placement, on purpose
        res = sim.run(
            5000 * sim.dt,
            record_every=1,
            tension=False,
            node_position=False,
            node_velocity=False,
            max_memory=100 * per_sample,
            progress=False,
        )
    assert 50 <= len(res) <= 100
    with pytest.raises(beltrs.SceneError, match=r"max_samples = 1: must be ≥ 2"):
        sim.run(sim.dt, max_samples=1)
    with pytest.raises(beltrs.SceneError, match=r"max_memory = 10: must hold at least 2 samples"):
        sim.run(sim.dt, max_memory=10)


# --- progress bar ---------------------------------------------------------------------


def test_builtin_progress_bar_and_switch(capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)  # force the built-in bar
    sim = beltrs.Simulation(tiny_scene())
    with pytest.warns(beltrs.NotRelaxedWarning):  # from the placement, on purpose
        sim.run(2000 * sim.dt, record_every=100, progress=True)
    err = capsys.readouterr().err
    assert "100.0%" in err and "steps/s" in err
    sim.run(2000 * sim.dt, record_every=100, progress=False)
    assert capsys.readouterr().err == ""
    # Default: on only for a terminal; pytest's captured stderr is not one.
    sim.run(2000 * sim.dt, record_every=100)
    assert capsys.readouterr().err == ""


# --- Ctrl-C ---------------------------------------------------------------------------


def test_ctrl_c_in_process_returns_partial_result(tmp_path):
    sim = beltrs.Simulation(tiny_scene())
    steps = 50_000_000  # about a minute: Ctrl-C must stop it long before
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    t0 = time.perf_counter()
    try:
        with pytest.warns(beltrs.NotRelaxedWarning):  # from the placement, on purpose
            res = sim.run(steps * sim.dt, record_every=100, progress=False, checkpoint=tmp_path / "run.ck")
    finally:
        timer.cancel()
    wall = time.perf_counter() - t0
    assert res.interrupted and sim.last_result is res
    assert wall < 5.0
    done = sim.state()["step"]
    assert 0 < done < steps
    # The interrupted state was checkpointed.
    assert beltrs.Simulation.load_checkpoint(tmp_path / "run.ck").state()["step"] == done
    # Everything up to the interruption is there, on the grid, finite.
    # Samples at steps 0, 100, ... <= done, plus the final state when it is off the grid.
    assert len(res) == done // 100 + 1 + (done % 100 != 0)
    assert res.time[-1] == sim.time
    assert np.all(np.isfinite(res.tension))
    # The state is consistent: the run goes on.
    more = sim.run(100 * sim.dt, record_every=10, progress=False)
    assert not more.interrupted and len(more) == 11


def test_sigint_to_a_subprocess_returns_partial_result():
    code = textwrap.dedent(
        """
        import math, sys
        import beltrs
        from beltrs import Belt, Pulley, Scene
        path = 4.0 + math.pi
        s = Scene(belt=Belt(axial_stiffness=1e6, mass_per_length=10.0, elements=16, length=0.998 * path,
                            damping_ratio=0.05),
                  pulleys=[Pulley(center=(0.0, 0.0), radius=0.5, contact_stiffness=1e7),
                           Pulley(center=(2.0, 0.0), radius=0.5, contact_stiffness=1e7)])
        sim = beltrs.Simulation(s)
        print("start", flush=True)
        res = sim.run(5e7 * sim.dt, record_every=1000, progress=False)
        print(len(res), res.interrupted, sim.state()["step"], flush=True)
        """
    )
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "start"
    time.sleep(0.7)
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=20)
    assert child.returncode == 0, err
    samples, interrupted, steps = out.split()
    assert interrupted == "True"
    assert 0 < int(steps) < 50_000_000
    # The grid's instants, and the final state when it falls between two of them.
    assert int(samples) == int(steps) // 1000 + 1 + (int(steps) % 1000 != 0)


# --- divergence with chunking ---------------------------------------------------------


def test_divergence_after_many_chunks_keeps_everything_before():
    scene = tiny_scene()
    sim = beltrs.Simulation(scene)
    t_blow = 2000 * sim.dt
    # A drive switched on at t_blow on a pulley of (valid but absurd) inertia 1e-300 kg*m^2:
    # its speed overflows to infinity in the first step after t_blow.
    scene.pulleys[1].inertia = 1e-300
    scene.pulleys[1].drive = Drive(time=[0.0, t_blow, t_blow + 1e-9], torque=[0.0, 0.0, 1e20])
    sim.set_scene(scene)
    with pytest.raises(
        beltrs.DivergenceError, match=r"non-finite at t = [0-9.e-]+ s \(step 20\d\d\): angular speed of pulley head"
    ) as err:
        with pytest.warns(beltrs.NotRelaxedWarning):  # from the placement, on purpose
            sim.run(10_000 * sim.dt, record_every=10, progress=False)
    partial = err.value.result
    # Samples every 10 steps up to the blow-up at step ~2000, which falls in the fourth
    # chunk (chunks start at 64 steps and grow fourfold while they take < 0.1 s).
    assert 199 <= len(partial) <= 202
    assert np.array_equal(partial.time, np.arange(len(partial)) * 10 * sim.dt) or np.allclose(
        partial.time, np.arange(len(partial)) * 10 * sim.dt, rtol=1e-12
    )
    assert np.all(np.isfinite(partial.node_position))
    assert not partial.interrupted


def test_periodic_checkpoints_during_a_run(tmp_path):
    path = tmp_path / "run.ck"
    sim = beltrs.Simulation(tiny_scene())
    with pytest.warns(beltrs.NotRelaxedWarning):  # from the placement, on purpose
        sim.run(20_000 * sim.dt, record_every=1000, progress=False, checkpoint=path, checkpoint_interval=0.0)
    resumed = beltrs.Simulation.load_checkpoint(path)
    assert resumed.state()["step"] == 20_000
    a = sim.run(500 * sim.dt, record_every=7, progress=False, energy=True)
    b = resumed.run(500 * sim.dt, record_every=7, progress=False, energy=True)
    assert np.array_equal(a.node_velocity, b.node_velocity) and np.array_equal(a.energy, b.energy)

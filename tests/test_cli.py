"""``beltrs run SCENE.toml --out result.npz``: the NPZ holds every recorded array, the
scene and metadata; bad input is one clear line on stderr and a nonzero exit."""

import dataclasses
import datetime
import os
import stat
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import beltrs
from beltrs.__main__ import main
from beltrs.scenes import hustrulid_loop

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def scene_file(tmp_path, scene=None, name="scene.toml"):
    path = tmp_path / name
    (scene or hustrulid_loop()).save(path)
    return path


def test_run_writes_every_array_the_scene_and_metadata(tmp_path, capsys):
    scene = hustrulid_loop()
    scene.recording = beltrs.Recording(duration=0.2, every=3, channels=("tension", "node_position"))
    path, out = scene_file(tmp_path, scene), tmp_path / "r.npz"
    assert main(["run", str(path), "--out", str(out)]) == 0
    assert f"wrote {out}" in capsys.readouterr().out

    # The same run through the Python API, for comparison bit for bit.
    sim = beltrs.Simulation(scene)
    report = sim.stabilise()
    res = sim.run(0.2, record_every=3, tension=True, node_position=True, node_velocity=False)

    with np.load(out) as f:  # no pickle needed
        for field in dataclasses.fields(res):
            value = getattr(res, field.name)
            if isinstance(value, np.ndarray):
                assert np.array_equal(f[field.name], value, equal_nan=True), field.name
        assert "node_velocity" not in f.files  # a channel not asked for
        assert list(f["energy_columns"]) == res.energy_columns
        assert list(f["pulley_names"]) == ["upper", "takeup"]
        assert beltrs.Scene.from_toml(str(f["scene"])) == scene
        assert str(f["beltrs_version"]) == beltrs.__version__
        assert float(f["dt"]) == sim.dt and float(f["dt_limit"]) == sim.dt_limit
        assert list(f["stages"]) == sim.stages
        assert int(f["nodes"]) == 89
        # Whole steps and one shortened step: the run ends, and is sampled, at 0.2 s exactly.
        assert int(f["steps"]) == int(np.ceil(0.2 / sim.dt))
        assert float(f["time"][-1]) == 0.2
        assert int(f["stabilise_steps"]) == report["steps"]
        assert bool(f["stabilised"]) and not bool(f["interrupted"]) and str(f["error"]) == ""
        assert float(f["wall_time"]) > 0 and float(f["duration"]) == 0.2
        stamp = datetime.datetime.fromisoformat(str(f["date"]))
        assert abs((datetime.datetime.now(datetime.timezone.utc) - stamp).total_seconds()) < 600


def test_run_options_override_the_scene(tmp_path, capsys):
    path, out = scene_file(tmp_path), tmp_path / "r.npz"
    assert main(["run", str(path), "--out", str(out), "--no-stabilise", "--duration", "0.05", "--quiet"]) == 0
    assert capsys.readouterr().out == ""
    with np.load(out) as f:
        assert not bool(f["stabilised"]) and int(f["stabilise_steps"]) == 0
        assert float(f["time"][-1]) == pytest.approx(0.05, abs=float(f["dt"]))
        # Not relaxed: the belt starts near unstretched, far from the static 157-257 kN.
        assert np.abs(f["tension"][0]).max() < 50e3


def test_bad_scene_file_is_one_line_on_stderr(tmp_path, capsys):
    path = tmp_path / "typo.toml"
    path.write_text(hustrulid_loop().to_toml().replace("radius = 5.0", "radious = 5.0", 1))
    assert main(["run", str(path), "--out", str(tmp_path / "r.npz")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"beltrs: error: {path}: pulleys[0].radious = 'radious': unknown key, did you mean 'radius'?")
    assert err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "r.npz").exists()
    # A value that breaks a rule is reported the same way, by the engine.
    scene = hustrulid_loop()
    scene.pulleys[1].mass = -600.0
    assert main(["check", str(scene_file(tmp_path, scene))]) == 2
    assert "pulleys[1].mass = -600: must be > 0" in capsys.readouterr().err
    assert main(["run", str(tmp_path / "missing.toml"), "--out", str(tmp_path / "r.npz")]) == 2
    assert "No such file" in capsys.readouterr().err


def test_divergence_keeps_what_was_recorded(tmp_path, capsys):
    scene = hustrulid_loop()
    scene.gravity = 1e140  # finite, but drives the state to infinity within a few steps
    scene.recording = beltrs.Recording(duration=1.0, every=1, stabilise=False)
    out = tmp_path / "r.npz"
    assert main(["run", str(scene_file(tmp_path, scene)), "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "non-finite at t = " in err and "Traceback" not in err
    with np.load(out) as f:
        assert "non-finite" in str(f["error"])
        assert len(f["time"]) >= 1 and np.all(np.isfinite(f["time"]))


def test_check_prints_the_stages(tmp_path, capsys):
    assert main(["check", str(scene_file(tmp_path))]) == 0
    assert "stages: axial, bending, pulley_contact" in capsys.readouterr().out


def run_process(*args, cwd):
    return subprocess.run(
        [sys.executable, "-m", "beltrs", *args], cwd=cwd, capture_output=True, text=True, timeout=120, check=False
    )


def test_python_m_beltrs_run_in_a_subprocess(tmp_path):
    out = tmp_path / "h.npz"
    # --no-progress: the relaxation shows progress on its own when max_steps times the
    # estimated step time exceeds 30 s; that estimate times a Python force call (about 6 us
    # here, more on a loaded machine) against 5e6 steps, so on a slow machine case H's 40 ms
    # relaxation crosses it. Progress has its own tests; this one checks a quiet, clean run.
    proc = run_process("run", str(EXAMPLES / "case_h.toml"), "--out", str(out), "--duration", "0.1", "--no-progress",
                       cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    with np.load(out) as f:
        assert f["tension"].shape[1] == 89 and np.all(np.isfinite(f["tension"]))
        # Relaxed before the run: the takeup has moved down by about 3.3 m (case H).
        assert -3.5 < float(f["takeup_travel"][0, 1]) * -1 < -3.1


def test_bad_input_in_a_subprocess_has_no_traceback(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text((EXAMPLES / "case_h.toml").read_text().replace("[solver]", "[solver]\ntime_stepp = 1e-4"))
    proc = run_process("run", str(path), "--out", str(tmp_path / "r.npz"), cwd=tmp_path)
    assert proc.returncode == 2
    assert "solver.time_stepp = 'time_stepp': unknown key, did you mean 'time_step'?" in proc.stderr
    assert "Traceback" not in proc.stderr and proc.stdout == ""


def test_console_script(tmp_path):
    script = Path(sys.executable).with_name("beltrs")
    if not script.exists():
        pytest.skip("the beltrs console script is not installed next to this Python")
    proc = subprocess.run(
        [str(script), "check", str(EXAMPLES / "case_h.toml")], capture_output=True, text=True, timeout=120, check=False
    )
    assert proc.returncode == 0 and "valid; 89 nodes" in proc.stdout


def test_output_files_get_the_usual_permissions(tmp_path):
    """Written through a temporary file, but readable like any other file (not 0600)."""
    mask = os.umask(0o022)
    try:
        path, out = scene_file(tmp_path), tmp_path / "r.npz"
        assert main(["run", str(path), "--out", str(out), "--duration", "0.01", "--quiet"]) == 0
        assert stat.S_IMODE(out.stat().st_mode) == 0o644
        assert stat.S_IMODE(path.stat().st_mode) == 0o644
        assert sorted(p.name for p in tmp_path.iterdir()) == ["r.npz", "scene.toml"]
    finally:
        os.umask(mask)

"""The fuller command line: --version, help on every subcommand, run's summary and default
output name, plot (PNGs) and export --csv; user errors are one line, never a traceback."""

import csv
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import beltrs
from beltrs.__main__ import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
COMMANDS = ["demo", "run", "check", "plot", "export"]


def test_version(capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0 and capsys.readouterr().out == f"beltrs {beltrs.__version__}\n"


@pytest.mark.parametrize("command", COMMANDS)
def test_every_subcommand_has_help(command, capsys):
    with pytest.raises(SystemExit) as exit_:
        main([command, "--help"])
    out = capsys.readouterr().out
    assert exit_.value.code == 0 and out.startswith(f"usage: beltrs {command}")
    assert len(out.splitlines()) >= 5  # a description, not just the usage line


def test_top_level_help_lists_every_command(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    out = capsys.readouterr().out
    assert all(c in out for c in COMMANDS)


@pytest.fixture(scope="module")
def pulse_npz(tmp_path_factory):
    """`beltrs run` on the torque-pulse example, 0.5 s, with the default output name."""
    d = tmp_path_factory.mktemp("run")
    scene = beltrs.load_scene(EXAMPLES / "case_h_torque_pulse.toml")
    scene.recording = beltrs.Recording(duration=0.5, interval=0.01, stabilise=True)
    scene.save(d / "pulse.toml")
    proc = subprocess.run([sys.executable, "-m", "beltrs", "run", "pulse.toml"], cwd=d, capture_output=True,
                          text=True, timeout=300, check=False)
    assert proc.returncode == 0, proc.stderr
    return d / "pulse.npz", proc.stdout


def test_run_prints_a_summary_and_names_the_output_after_the_scene(pulse_npz):
    path, out = pulse_npz
    assert path.exists() and f"wrote {path.name}" in out
    res = beltrs.load_result(path)
    peak = res.tension.max()
    assert f"peak tension    {peak / 1e3:10.2f} kN" in out
    assert "takeup 'takeup': travel" in out
    torque = res.driving_torque[:, 0]  # positive when driving (ccw wrap: the engine's sign)
    assert f"drive 'upper': peak torque {torque[np.argmax(np.abs(torque))] / 1e3:.3f} kN·m" in out
    assert "capstan utilisation: peak" in out
    assert "peak power" in out and "wall time: relaxation" in out
    # The CLI's metadata travel with the result.
    assert res.metadata["stabilised"] is True and res.metadata["nodes"] == 89
    assert beltrs.Scene.from_toml(res.metadata["scene"]).pulleys[0].name == "upper"


def test_plot_writes_the_five_figures(pulse_npz, tmp_path, capsys):
    path, _ = pulse_npz
    assert main(["plot", str(path), "--out-dir", str(tmp_path)]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == [f"pulse_{n}.png" for n in ("drives", "envelope", "slip", "takeup", "waterfall")]
    for p in tmp_path.iterdir():
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and p.stat().st_size > 10_000
    assert capsys.readouterr().out.count("wrote") == 5


def test_export_csv_reads_back_exactly(pulse_npz, tmp_path):
    path, _ = pulse_npz
    assert main(["export", str(path), "--csv", "--out-dir", str(tmp_path)]) == 0
    res = beltrs.load_result(path)
    with open(tmp_path / "pulse_pulleys.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    header, body = rows[0], rows[1:]
    assert header[0] == "time (s)" and "drive_torque[upper] (N*m)" in header and "contact_nodes[takeup] (1)" in header
    assert len(body) == len(res)
    col = header.index("drive_torque[upper] (N*m)")
    assert [float(r[col]) for r in body] == res.drive_torque[:, 0].tolist()  # 17 digits: exact
    col = header.index("contact_nodes[takeup] (1)")
    assert [int(r[col]) for r in body] == res.contact_nodes[:, 1].tolist()
    tension = np.loadtxt(tmp_path / "pulse_tension.csv", delimiter=",", skiprows=1)
    assert np.array_equal(tension[:, 1:], res.tension) and np.array_equal(tension[:, 0], res.time)
    assert (tmp_path / "pulse_energy.csv").exists()


@pytest.mark.parametrize("command", [["plot"], ["export", "--csv"]])
def test_missing_or_foreign_result_files_are_one_line(command, tmp_path, capsys):
    assert main([command[0], str(tmp_path / "none.npz"), *command[1:]]) == 2
    err = capsys.readouterr().err
    assert err == f"beltrs: error: {tmp_path / 'none.npz'}: no such file\n"
    (tmp_path / "x.npz").write_bytes(b"not a zip")
    assert main([command[0], str(tmp_path / "x.npz"), *command[1:]]) == 1
    err = capsys.readouterr().err
    assert "not a beltrs result" in err and err.count("\n") == 1 and "Traceback" not in err


def test_export_needs_a_format(tmp_path, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(["export", str(tmp_path / "r.npz")])
    assert exit_.value.code == 2 and "--csv" in capsys.readouterr().err


def test_warnings_are_one_line_on_stderr(tmp_path, capsys):
    scene = beltrs.scenes.hustrulid_loop()
    scene.recording = beltrs.Recording(duration=0.02, stabilise=False)
    scene.save(tmp_path / "s.toml")
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "s.npz"), "--quiet"]) == 0
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err.startswith("beltrs: warning (NotRelaxedWarning): run() starts from the initial placement")
    assert captured.err.count("\n") == 1


def test_run_to_netcdf(tmp_path, capsys):
    scene = beltrs.scenes.hustrulid_loop()
    scene.recording = beltrs.Recording(duration=0.05)
    scene.save(tmp_path / "s.toml")
    assert main(["run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "s.nc"), "--quiet"]) == 0
    res = beltrs.load_result(tmp_path / "s.nc")
    assert res.metadata["nodes"] == 89 and res.contact_nodes.dtype == np.int64

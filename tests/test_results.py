"""Results that travel: Result.save / beltrs.load_result (NPZ and netCDF), to_xarray,
to_pandas; the default recording interval and the final instant at the end of the run."""

import dataclasses
import json
import math
import sys

import numpy as np
import pytest

import beltrs
from beltrs import Friction
from beltrs.result import DIMS, UNITS

from conftest import stabilised


@pytest.fixture(scope="module")
def pulse_result():
    """Case H with friction, the §6.4.2 pulse and a brake-free run: every channel moves."""
    sim = stabilised(89)
    sim.set_friction(0, Friction(static=0.5, kinetic=0.4))
    sim.set_friction(1, Friction(static=0.5, kinetic=0.4))
    sim.set_drive(0, beltrs.Drive.pulse(4e5, 0.07, start=sim.time))
    res = sim.run(0.5, record_interval=0.01)
    res.metadata.update(
        text="case H", flag=True, count=7, value=math.pi, missing=float("nan"), names=["a", "b"],
        table=np.arange(6, dtype=np.int32).reshape(2, 3),
    )
    return res


def test_counts_are_integers_and_arrays_have_units(pulse_result):
    res = pulse_result
    assert res.contact_nodes.dtype == np.int64 and res.slipping_nodes.dtype == np.int64
    assert res.contact_nodes.max() > 0  # the belt wraps both pulleys
    assert set(res.arrays()) <= set(UNITS) and set(DIMS) <= set(UNITS)
    assert res.drive_power.shape == res.drive_torque.shape
    np.testing.assert_array_equal(res.drive_power, res.drive_torque * res.pulley_speed)
    assert res.metadata["rest_length"].shape == (89,)  # every Result carries its rest lengths


@pytest.mark.parametrize("suffix", [".npz", ".nc"])
def test_save_load_round_trip_is_lossless(tmp_path, pulse_result, suffix):
    path = pulse_result.save(tmp_path / f"r{suffix}")
    back = beltrs.load_result(path)
    assert back == pulse_result  # every array bit for bit, dtypes, scalars, metadata and types
    assert back.contact_nodes.dtype == np.int64
    assert type(back.metadata["flag"]) is bool and type(back.metadata["count"]) is int
    assert math.isnan(back.metadata["missing"]) and back.metadata["names"] == ["a", "b"]
    assert back.metadata["table"].dtype == np.int32
    # Equality is strict: one flipped bit is a difference.
    back.tension[3, 4] = np.nextafter(back.tension[3, 4], np.inf)
    assert back != pulse_result


def test_equality_compares_the_data_not_how_the_run_went(tmp_path, pulse_result):
    # A reloaded result does not carry the run's checkpoint error, and a rerun takes another
    # wall time: neither is part of what the run computed.
    run = dataclasses.replace(pulse_result, checkpoint_error=beltrs.CheckpointError("disk full"), wall_time=9.0)
    back = beltrs.load_result(run.save(tmp_path / "r.npz"))
    assert back.checkpoint_error is None and back == run
    assert dataclasses.replace(back, dt=back.dt * 2) != run  # the data still count
    assert dataclasses.replace(back, record_every=back.record_every + 1) != run


def test_npz_is_plain_numpy_with_units(tmp_path, pulse_result):
    path = pulse_result.save(tmp_path / "r.npz")
    with np.load(path, allow_pickle=False) as f:
        assert str(f["beltrs_format"]) == "beltrs-result/1"
        assert json.loads(str(f["units"]))["tension"] == "N"
        assert json.loads(str(f["dims"]))["node_position"] == ["time", "node", "axis"]
        assert f["contact_nodes"].dtype == np.int64
        assert f["time"][-1] == pulse_result.time[-1]


def test_unstorable_metadata_and_foreign_files_are_clear_errors(tmp_path, pulse_result):
    res = beltrs.load_result(pulse_result.save(tmp_path / "r.npz"))
    res.metadata["bad"] = {"a": 1}
    with pytest.raises(beltrs.BeltrsError, match=r"metadata\['bad'\] = .*must be str, bool, int, float"):
        res.save(tmp_path / "s.npz")
    assert not (tmp_path / "s.npz").exists()
    for key in ("tension", "units", "dt"):
        res.metadata = {key: "x"}
        with pytest.raises(beltrs.BeltrsError, match=rf"metadata\['{key}'\]: the name of a Result field"):
            res.save(tmp_path / "s.npz")
    with pytest.raises(beltrs.BeltrsError, match="must be 'npz' or 'netcdf'"):
        pulse_result.save(tmp_path / "s.npz", format="hdf")
    with pytest.raises(beltrs.BeltrsError, match="does not exist"):
        pulse_result.save(tmp_path / "nowhere" / "s.npz")
    (tmp_path / "x.txt").write_text("hello")
    with pytest.raises(beltrs.BeltrsError, match="not a beltrs result"):
        beltrs.load_result(tmp_path / "x.txt")
    np.savez(tmp_path / "other.npz", a=np.zeros(3))
    with pytest.raises(beltrs.BeltrsError, match=r"not a beltrs result \(missing time"):
        beltrs.load_result(tmp_path / "other.npz")
    with pytest.raises(beltrs.BeltrsError, match="no such file"):
        beltrs.load_result(tmp_path / "missing.npz")


def test_to_xarray_has_named_dimensions_and_units(pulse_result):
    ds = pulse_result.to_xarray()
    assert ds.tension.dims == ("time", "element") and ds.tension.attrs["units"] == "N"
    assert ds.node_position.dims == ("time", "node", "axis")
    assert ds.drive_torque.dims == ("time", "pulley") and ds.drive_power.attrs["units"] == "W"
    assert list(ds.pulley.values) == ["upper", "takeup"]
    assert list(ds.energy_term.values) == pulse_result.energy_columns
    assert ds.time.attrs["units"] == "s"
    # Index by name and by the end time.
    end = ds.takeup_travel.sel(pulley="takeup", time=pulse_result.time[-1])
    assert float(end) == pulse_result.takeup_travel[-1, 1]
    assert ds.attrs["dt"] == pulse_result.dt and ds.contact_nodes.dtype == np.int64
    # Tension against distance along the belt: element midpoints, unstretched metres.
    rest = pulse_result.metadata["rest_length"]
    assert ds.distance.dims == ("element",) and ds.distance.values[-1] == pytest.approx(rest.sum() - rest[-1] / 2)


def test_to_pandas_per_pulley_series(pulse_result):
    df = pulse_result.to_pandas()
    assert df.index.name == "time" and len(df) == len(pulse_result)
    np.testing.assert_array_equal(df["drive_torque"]["upper"].to_numpy(), pulse_result.drive_torque[:, 0])
    np.testing.assert_array_equal(df[("takeup_travel", "takeup")].to_numpy(), pulse_result.takeup_travel[:, 1])
    assert df["contact_nodes"]["upper"].dtype == np.int64
    assert df.attrs["units"]["drive_power"] == "W"
    assert set(df.columns.get_level_values("pulley")) == {"upper", "takeup"}


def test_missing_optional_package_is_a_beltrs_error(monkeypatch, pulse_result):
    monkeypatch.setitem(sys.modules, "xarray", None)
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(beltrs.BeltrsError, match=r"Result.to_xarray needs the optional package 'xarray'"):
        pulse_result.to_xarray()
    with pytest.raises(beltrs.BeltrsError, match=r"Result.to_pandas needs the optional package 'pandas'"):
        pulse_result.to_pandas()


# --- recording defaults --------------------------------------------------------------------


def test_default_interval_comes_from_the_strands_and_is_capped(case_h):
    # Case H: 100 m strands, c = sqrt(7.62e6 / 100) = 276 m/s: 2 L / c / 20 = 36 ms > the cap.
    assert case_h.default_record_interval() == 0.01
    res = case_h.run(2.0)
    assert res.record_every == round(0.01 / case_h.dt)
    assert len(res) == pytest.approx(2.0 / 0.01, abs=2)  # ~200 instants, not ~1800 steps
    # A short, stiff strand: 0.5 m, c = sqrt(1e6 / 0.1) = 3162 m/s: 2 * 0.5 / 3162 / 20 = 15.8 µs.
    scene = beltrs.Scene(
        belt=beltrs.Belt(axial_stiffness=1e6, mass_per_length=0.1, elements=100),
        pulleys=[beltrs.Pulley(center=(0.0, 0.0), radius=0.1), beltrs.Pulley(center=(0.5, 0.0), radius=0.1)],
        gravity=0.0,
    )
    drive = beltrs.Simulation(scene)
    assert drive.default_record_interval() == pytest.approx(2 * 0.5 / math.sqrt(1e7) / 20, rel=1e-12)


def test_last_instant_is_the_end_of_the_run(case_h):
    # 20 s is not a whole number of grid intervals (case H: 21893 steps of 0.91 ms, 22-step grid).
    t0 = case_h.time
    res = case_h.run(20.0, record_interval=0.02, tension=False, node_position=False, node_velocity=False)
    assert res.time[-1] == case_h.time  # the final state is recorded
    assert abs(res.time[-1] - (t0 + 20.0)) <= case_h.dt / 2  # whole steps: within half a step
    steps = np.diff(res.time) / case_h.dt
    assert np.allclose(steps[:-1], res.record_every) and 0 < steps[-1] <= res.record_every
    # On the grid already: nothing is appended twice.
    res = case_h.run(res.record_every * case_h.dt * 3, record_every=res.record_every)
    assert len(res) == 4 and res.time[-1] == case_h.time


def test_run_ends_exactly_at_the_end_time(case_h):
    t0 = case_h.time
    res = case_h.run(20.0, record_interval=0.02, tension=False, node_position=False, node_velocity=False)
    assert res.time[-1] == t0 + 20.0


def test_npz_of_an_older_beltrs_run_still_loads(tmp_path, pulse_result):
    """`beltrs run` NPZ files from before the result format: counts as floats, metadata as
    plain keys, no descriptors."""
    old = {k: v for k, v in pulse_result.arrays().items()}
    old["contact_nodes"] = old["contact_nodes"].astype(float)
    old["slipping_nodes"] = old["slipping_nodes"].astype(float)
    old.update(energy_columns=np.array(pulse_result.energy_columns), pulley_names=np.array(["upper", "takeup"]),
               stages=np.array(pulse_result.stages), dt=pulse_result.dt, wall_time=0.5, interrupted=False,
               record_every=9, scene="gravity = 9.81", nodes=89)
    np.savez(tmp_path / "old.npz", **old)
    res = beltrs.load_result(tmp_path / "old.npz")
    assert res.contact_nodes.dtype == np.int64
    np.testing.assert_array_equal(res.contact_nodes, pulse_result.contact_nodes)
    assert res.metadata == {"scene": "gravity = 9.81", "nodes": 89} and res.record_every == 9


def test_relaxation_shows_progress_when_asked(capsys):
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop())
    report = sim.stabilise(progress=True)
    err = capsys.readouterr().err
    assert f"beltrs: relaxing to static equilibrium: {report['steps']} steps, residual" in err
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop())
    sim.stabilise(progress=False)
    assert capsys.readouterr().err == ""

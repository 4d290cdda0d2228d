"""beltrs.study.sweep: many independent runs on local processes or a Dask cluster, gathered
into an xarray Dataset indexed by the sweep parameters; a failed case is data."""

import warnings

import numpy as np
import pytest

import beltrs
from beltrs import study
from beltrs.scenes import hustrulid_loop

COUNTERWEIGHT = "pulleys[1].takeup.counterweight"


def base_scene():
    scene = hustrulid_loop(elements=60)
    scene.recording = beltrs.Recording(duration=0.3, channels=("tension",))
    return scene


def test_set_field_by_path():
    scene = base_scene()
    changed = study.set_field(scene, COUNTERWEIGHT, 33_000.0)
    assert changed.pulleys[1].takeup.counterweight == 33_000.0 and scene.pulleys[1].takeup.counterweight == 30_000.0
    with pytest.raises(beltrs.SceneError, match=r"'pulleys\[1\]\.takeup\.weight': Takeup has no field 'weight'"):
        study.set_field(scene, "pulleys[1].takeup.weight", 1.0)
    with pytest.raises(beltrs.SceneError, match=r"index 5 out of range"):
        study.set_field(scene, "pulleys[5].mass", 1.0)
    with pytest.raises(beltrs.SceneError, match=r"pulleys\[0\]\.takeup is None in the base scene"):
        study.set_field(scene, "pulleys[0].takeup.counterweight", 1.0)


def test_sweep_here_matches_single_runs_and_keeps_failures():
    grid = {COUNTERWEIGHT: [30_000.0, 33_000.0, -1.0], "recording.duration": [0.2, 0.3]}
    ds = study.sweep(grid, scene=base_scene(), max_workers=1, progress=False)
    assert ds.peak_tension.dims == (COUNTERWEIGHT, "recording.duration")
    assert ds.peak_tension.attrs["units"] == "N"
    assert list(ds[COUNTERWEIGHT].values) == [30_000.0, 33_000.0, -1.0]
    # The bad counterweight failed with its error, NaN outputs, and did not stop the others.
    bad = ds.sel({COUNTERWEIGHT: -1.0})
    assert all("counterweight = -1" in str(e) and "SceneError" in str(e) for e in bad.error.values)
    assert np.all(np.isnan(bad.peak_tension.values)) and ds.attrs["failed"] == 2
    good = ds.sel({COUNTERWEIGHT: 33_000.0, "recording.duration": 0.3})
    assert good.error.item() == ""
    # The same case run by hand gives the same figures, bit for bit.
    scene = study.set_field(base_scene(), COUNTERWEIGHT, 33_000.0)
    assert study.summarise(scene)["peak_tension"] == good.peak_tension.item()
    # A heavier counterweight pulls harder: the peak tension grows.
    peaks = ds.peak_tension.sel({"recording.duration": 0.3})
    assert peaks.sel({COUNTERWEIGHT: 33_000.0}) > peaks.sel({COUNTERWEIGHT: 30_000.0})
    assert np.all(ds.end_time.sel({COUNTERWEIGHT: 30_000.0}).values == pytest.approx([0.2, 0.3], abs=0.002))


def test_bad_sweeps_are_refused_before_running():
    with pytest.raises(beltrs.SceneError, match="the grid is empty"):
        study.sweep({}, scene=base_scene())
    with pytest.raises(beltrs.SceneError, match=r"grid\['gravity'\] is empty"):
        study.sweep({"gravity": []}, scene=base_scene())
    with pytest.raises(beltrs.SceneError, match="a grid needs scene="):
        study.sweep({"gravity": [9.81]}, max_workers=1, progress=False)
    with pytest.raises(beltrs.SceneError, match=r"scene = .*cannot be sent to a worker process"):
        study.sweep({"elements": [60]}, scene=lambda elements: hustrulid_loop(elements), progress=False)
    with pytest.raises(beltrs.SceneError, match=r"scenes\[1\] is int, not a beltrs.Scene"):
        study.sweep([base_scene(), 3])


def test_sweep_on_local_processes_with_a_factory():
    ds = study.sweep({"elements": [50, 60]}, scene=hustrulid_loop, max_workers=2, progress=False)
    assert list(ds.elements.values) == [50, 60] and np.all(ds.error.values == ""), ds.error.values
    # hustrulid_loop's own recording: relaxed, then 1 s of the static loop: tensions near 157-257 kN.
    assert np.all((ds.peak_tension.values > 200e3) & (ds.peak_tension.values < 300e3))


def test_sweep_on_a_dask_local_cluster():
    distributed = pytest.importorskip("distributed")
    with warnings.catch_warnings():
        # Dask's own start-up chatter (ports, deprecations) is not ours to test.
        warnings.simplefilter("ignore")
        cluster = distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        )
        client = distributed.Client(cluster)
    try:
        scenes = {"light": base_scene(), "heavy": study.set_field(base_scene(), COUNTERWEIGHT, 33_000.0),
                  "broken": study.set_field(base_scene(), "belt.axial_stiffness", -1.0)}
        ds = study.sweep(scenes, client=client, progress=False)
        assert list(ds.case.values) == ["light", "heavy", "broken"]
        assert ds.error.sel(case="light").item() == "" and ds.error.sel(case="heavy").item() == ""
        assert "belt.axial_stiffness = -1" in ds.error.sel(case="broken").item()
        here = study.summarise(scenes["heavy"])
        assert ds.peak_tension.sel(case="heavy").item() == here["peak_tension"]  # bit for bit
        # A custom run (a lambda is fine on Dask: it pickles by value) with an array output.
        ds = study.sweep(
            {COUNTERWEIGHT: [30_000.0, 33_000.0]}, scene=base_scene(), client=client, progress=False,
            run=lambda scene: {"takeup": np.array([scene.pulleys[1].takeup.counterweight, 1.0])},
        )
        assert ds.takeup.dims == (COUNTERWEIGHT, "takeup_dim0")
        assert ds.takeup.values[:, 0].tolist() == [30_000.0, 33_000.0]
    finally:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            client.close()
            cluster.close()


def test_progress_counts_cases(capsys):
    study.sweep({"recording.duration": [0.05, 0.1]}, scene=base_scene(), max_workers=1, progress=True)
    err = capsys.readouterr().err
    assert "beltrs sweep: 1/2 cases, 0 failed" in err and "beltrs sweep: 2/2 cases, 0 failed" in err

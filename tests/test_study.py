"""beltrs.study: the accuracy-versus-cost API (smoke test of benches/accuracy_study.py --quick)."""

import importlib.util
import math
import pathlib

import numpy as np
import pytest

import beltrs
from beltrs import study

ROOT = pathlib.Path(__file__).resolve().parents[1]


def load_study_script():
    spec = importlib.util.spec_from_file_location("accuracy_study", ROOT / "benches" / "accuracy_study.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_quick_study_shows_second_order_takeup_displacement(tmp_path):
    script = load_study_script()
    tables = script.main(["--quick", "--out", str(tmp_path)])
    table = tables["takeup_elements"]
    assert table.reference_kind == "exact"
    assert list(table.setting) == [100, 200, 400]
    # Errors must fall and node-steps grow with refinement.
    assert np.all(np.diff(table.error) < 0)
    assert np.all(np.diff(table.node_steps) > 0)
    # The chord polygon shortens each half wrap by π r θ²/24: an O(h²) error in the takeup
    # displacement. Measured orders 2.11 and 1.96 at 100/200/400 elements; the window
    # [1.7, 2.3] allows the odd/even node-pattern asymmetry (±0.15 seen) with margin, and
    # would fail for a first-order (1.0) or a third-order (3.0) error.
    orders = table.order[1:]
    assert np.all((orders > 1.7) & (orders < 2.3)), orders
    assert (tmp_path / "accuracy.md").exists()


def test_richardson_reference_without_exact_answer():
    quantity = study.takeup_displacement(exact=math.nan)
    table = study.accuracy_cost(beltrs.scenes.hustrulid_loop, quantity, values=[100, 200, 400])
    assert table.reference_kind == "richardson"
    # The extrapolated reference must land near the exact continuum answer (-3.1410 m):
    # second-order error 0.0102 m at 400 elements extrapolates to within ~1 mm.
    exact = beltrs.analytic.two_pulley_takeup_statics().takeup_displacement
    assert table.reference == pytest.approx(exact, abs=3e-3)
    assert table.richardson_order == pytest.approx(2.0, abs=0.3)


def test_scene_and_factory_give_the_same_table_values():
    scene = beltrs.scenes.hustrulid_loop()
    a = study.accuracy_cost(scene, study.takeup_displacement(), values=[100, 200])
    b = study.accuracy_cost(beltrs.scenes.hustrulid_loop, study.takeup_displacement(), values=[200, 100])
    np.testing.assert_allclose(a.value, b.value, rtol=0, atol=1e-9)
    assert "| 100 | 100 |" in a.to_markdown()
    assert a.to_dict()["rows"][1]["nodes"] == 200


def test_bad_settings_are_refused_with_the_rule():
    q = study.takeup_displacement()
    with pytest.raises(beltrs.SceneError, match="must be < 1"):
        study.accuracy_cost(beltrs.scenes.hustrulid_loop, q, refine="rkf_tolerance", values=[2.0, 1e-4])
    # Stick-force friction is refused under RKF45 by the engine, with the setting named.
    scene = tiny_rigid_drive()
    scene.pulleys[0].friction = beltrs.Friction(static=0.5)
    with pytest.raises(beltrs.SceneError, match=r"rkf_tolerance = 0.001: .*creep-rate friction"):
        study.accuracy_cost(scene, q, refine="rkf_tolerance", values=[1e-3, 1e-4])
    with pytest.raises(beltrs.SceneError, match="refine = 'dt'"):
        study.accuracy_cost(beltrs.scenes.hustrulid_loop, q, refine="dt")
    with pytest.raises(beltrs.SceneError, match="must be <= 1"):
        study.accuracy_cost(beltrs.scenes.hustrulid_loop, q, refine="time_step_fraction", values=[2.0, 0.5])
    with pytest.raises(beltrs.SceneError, match="at least three"):
        study.accuracy_cost(beltrs.scenes.hustrulid_loop, study.takeup_displacement(exact=math.nan), values=[100, 200])


def test_pareto_front():
    # (cost, error): the third point is beaten by the second in both.
    assert study.pareto_front([1, 2, 3, 4], [0.5, 0.1, 0.2, 0.05]) == [0, 1, 3]


def tiny_rigid_drive() -> beltrs.Scene:
    """Two pulleys R = 0.05 m, 0.3 m apart, a rigid-body belt of 24 bodies 1 % short of its
    path (EA 2e4 N, 0.1 kg/m), no friction, no gravity: placed, not relaxed, it rings."""
    path = 2 * 0.3 + 2 * math.pi * 0.05
    pulleys = [
        beltrs.Pulley(name=n, center=(x, 0.0), radius=0.05, mass=1.0, inertia=1e-3) for n, x in (("a", 0.0), ("b", 0.3))
    ]
    belt = beltrs.Belt(formulation="rigid_body", axial_stiffness=2e4, mass_per_length=0.1, damping_ratio=0.1,
                       length=path / 1.01, elements=24)
    return beltrs.Scene(belt=belt, pulleys=pulleys, gravity=0.0)


def test_rkf_tolerance_ladder_error_falls_with_the_tolerance():
    """The RKF45 tolerance ladder: the belt placed 1 % short rings for 2 ms from its
    placement; the tension of joint 3 at the end, against a run at 1e-11. A 4(5) pair with
    error-per-step control has a global error of about tol^0.8, so each two decades of
    tolerance must cut the error (by ~40 expected; asserted: by at least 5) and the accepted
    steps must grow. A ladder that ignored the tolerance (or ran central differences) would
    give equal errors and equal steps, and fail."""

    def ring(sim):
        with pytest.warns(beltrs.NotRelaxedWarning):  # the transient from the placement is the test
            sim.run(2e-3, record_interval=1e-3, node_position=False, node_velocity=False)

    quantity = study.Quantity("joint tension", "N", lambda sim: sim.tensions()[3], run=ring, stabilise=False)
    exact = study.run_setting(replace_solver(tiny_rigid_drive(), 1e-11), quantity)[0]
    table = study.accuracy_cost(tiny_rigid_drive, quantity, "rkf_tolerance", [1e-8, 1e-4, 1e-6], exact=exact)
    assert list(table.setting) == [1e-4, 1e-6, 1e-8]
    assert table.reference_kind == "exact"
    assert np.all(table.error[:-1] > 5 * table.error[1:]), table.error
    assert np.all(np.diff(table.node_steps) > 0), table.node_steps
    # The dt column holds the mean accepted step, well under 2 ms and shrinking.
    assert np.all(np.diff(table._col("time_step")) < 0) and table.rows[0].time_step < 2e-4
    assert "| 0.0001 | 24 |" in table.to_markdown()


def replace_solver(scene: beltrs.Scene, tolerance: float) -> beltrs.Scene:
    from dataclasses import replace

    return replace(scene, solver=replace(scene.solver, integrator="rkf45", relative_tolerance=tolerance))

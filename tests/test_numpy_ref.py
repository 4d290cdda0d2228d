"""benches/numpy_ref.py (the NumPy comparison implementation) steps the same model as beltrs."""

import importlib.util
import pathlib
import sys

import numpy as np
import pytest

import beltrs

BENCHES = pathlib.Path(__file__).resolve().parents[1] / "benches"


@pytest.fixture(scope="module")
def numpy_ref():
    sys.path.insert(0, str(BENCHES))
    spec = importlib.util.spec_from_file_location("numpy_ref", BENCHES / "numpy_ref.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["numpy_ref"] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("damping_ratio", [0.0, 0.05])
def test_numpy_reference_matches_beltrs_over_300_steps(numpy_ref, damping_ratio):
    # Case H (axial, bending, gravity, pulley contact, takeup), stabilised, then a 10 %
    # counterweight step so that every node and the takeup move (3.5 cm in 360 steps).
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop(89, damping_ratio=damping_ratio))
    sim.stabilise()
    sim.set_counterweight(1, 33_000.0)
    ref = numpy_ref.NumpyBelt.from_simulation(sim)
    s0 = sim.takeup_travel[1]
    sim.step(360)
    ref.step(360)
    st = sim.state()
    assert st["takeup_travel"][1] - s0 > 0.03  # the run is not trivial
    # Same equations in the same order; only the order of floating-point sums differs
    # (NumPy rolls, beltrs loops), i.e. ~1e-16 relative on coordinates of ~100 m, and this
    # non-chaotic run does not amplify it much: measured 1.3e-13 m after 300 steps. 1e-9 m
    # is far above rounding yet a million times below any modelling difference (a wrong
    # term moves nodes by millimetres in 300 steps).
    assert np.abs(st["node_position"] - ref.x).max() < 1e-9
    assert abs(st["takeup_travel"][1] - ref.pulleys[1].travel) < 1e-9
    # Velocities ~0.2 m/s; measured differences ~1e-10 m/s.
    assert np.abs(st["node_velocity_half_step"] - ref.v).max() < 1e-7

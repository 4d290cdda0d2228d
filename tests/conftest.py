"""Shared fixtures: case H stabilised once per session (each test copies what it changes)."""

import pytest

import beltrs


def stabilised(elements: int = 89, tolerance: float = 1e-7, **kw):
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop(elements, **kw))
    sim.stabilise(tolerance=tolerance)
    return sim


@pytest.fixture
def case_h():
    return stabilised(89)

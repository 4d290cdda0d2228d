"""Shared fixtures: case H stabilised once per session (each test copies what it changes).

Hypothesis runs derandomized by default (profile "ci"), so that the suite, CI included,
draws the same examples every time and a red run can be reproduced. For fresh random
examples when hunting bugs: HYPOTHESIS_PROFILE=explore python -m pytest tests/test_fuzz_scenes.py
"""

import os
import signal

import pytest
from hypothesis import settings

import beltrs

settings.register_profile("ci", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

# The Ctrl-C tests need Python's SIGINT handler. A shell starts a background job (`bash .ci/run &`)
# with SIGINT ignored, and Python then leaves it ignored, so those tests would see no Ctrl-C.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


def stabilised(elements: int = 89, tolerance: float = 1e-7, **kw):
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop(elements, **kw))
    sim.stabilise(tolerance=tolerance)
    return sim


@pytest.fixture
def case_h():
    return stabilised(89)


@pytest.fixture(scope="session")
def case_k_run():
    """Case K as built in, at default settings: relaxed, then 0.5 s (the torque ramps over
    0.3 s), recorded every 1 ms with the contact forces; (simulation, static preload N,
    Result). Shared by tests/test_rigid_body.py and tests/test_kubas_figures.py."""
    import numpy as np

    sim = beltrs.Simulation(beltrs.scenes.kubas_case_k())
    assert sim.stabilise()["converged"]
    preload = float(np.mean(sim.tensions()))
    res = sim.run(0.5, record_interval=1e-3, node_velocity=False, contact_forces=True)
    return sim, preload, res

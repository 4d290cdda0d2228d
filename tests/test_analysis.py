"""beltrs.analysis helpers used by case G: tension probes and the zero-phase low-pass."""

import numpy as np
import pytest

import beltrs
from beltrs.analysis import low_pass, probe_run, tension_at


def test_tension_at_picks_the_element_passing_the_point():
    # A square loop of 4 elements; element k runs from node k to node k+1.
    x = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    t = np.array([10.0, 20.0, 30.0, 40.0])
    assert tension_at(x, t, (0.5, -0.1)) == 10.0
    assert tension_at(x, t, (1.1, 0.5)) == 20.0
    assert tension_at(x, t, (-0.2, 0.4)) == 40.0
    # A recording: [S, E, 2] and [S, E] give [S].
    xs = np.stack([x, x[[1, 2, 3, 0]]])
    ts = np.stack([t, t])
    np.testing.assert_array_equal(tension_at(xs, ts, (0.5, -0.1)), [10.0, 40.0])


def test_low_pass_keeps_slow_content_and_removes_fast():
    dt = 0.005
    t = np.arange(0, 10, dt)
    slow = np.sin(2 * np.pi * 0.5 * t) + 0.3 * t
    x = slow + 0.5 * np.sin(2 * np.pi * 10 * t)
    y = low_pass(x, dt, 2.0)
    inner = slice(200, -200)  # 1 s from the ends (the ideal filter rings near them)
    # The 10 Hz ripple (amplitude 0.5) is gone to under 1 % of its amplitude.
    assert np.max(np.abs(y[inner] - slow[inner])) < 0.005
    with pytest.raises(ValueError, match="cutoff = 0"):
        low_pass(x, dt, 0)


def test_probe_run_reads_the_same_tension_as_the_state():
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop(89))
    sim.stabilise()
    data = probe_run(sim, [(0.0, 10.0)], 0.05, 0.01)
    assert data["time"].shape == (6,) and data["tension"].shape == (6, 1)
    state = sim.state()
    assert data["tension"][-1, 0] == tension_at(state["node_position"], sim.tensions(), (0.0, 10.0))
    assert data["time"][-1] == pytest.approx(0.05, abs=sim.dt)

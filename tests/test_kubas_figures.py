"""Case K (Kubas 2014, section 4) at default settings: the contact forces round the pulleys
of the paper's figures 16 and 17, and the span tensions of its figure 15
(docs/kubas.md, "Figures 15-17").

The paper follows one body round the drive; in steady running the field is stationary, so
the same pattern is read here, better averaged, from every body on each pulley over
0.35-0.5 s, binned by wrap angle along the direction of travel
(:meth:`beltrs.Result.contact_profile`, 12 bins of 15.6 degrees over the ~180 degree wrap,
about 140 body-instants per bin). The first two and the last bin hold the bodies entering
and leaving the arc (the impact of a 0.3 rad body meeting the rim, and the one leaving):
the pattern is asserted on the bins between.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_rigid_body import CASE_K_TORQUE, span_tensions

MU_K, MU_S = 1.0, 1.05
BINS = 12


@pytest.fixture(scope="module")
def profiles(case_k_run):
    _, _, res = case_k_run
    return {name: res.contact_profile(name, start=0.35, bins=BINS) for name in ("drive", "driven")}


def test_normal_force_falls_on_the_drive_and_rises_on_the_driven_pulley(profiles):
    """Figure 16: viewed in the direction of travel the normal force falls round the drive
    pulley (tight side in, slack side out) and rises round the driven one. Measured per
    body: drive 333 N on the adhesion arc falling to 122 N (ratio 0.37), driven 97 N rising
    to 248 N (ratio 2.5); the span tensions' ratio is T2/T1 = 0.32. Asserted: monotone
    along travel within 3 % bin to bin (the adhesion arc is flat, its bins scatter by
    0.7 %), and exit over entry below 0.5 (drive) and above 2 (driven)."""
    drive = profiles["drive"].normal[2:-1]
    driven = profiles["driven"].normal[2:-1]
    assert np.all(drive[1:] <= 1.03 * drive[:-1]), drive
    assert np.all(driven[1:] >= 0.97 * driven[:-1]), driven
    assert drive[-1] / drive[0] < 0.5, drive
    assert driven[-1] / driven[0] > 2.0, driven


def test_friction_is_full_on_the_slip_arcs_and_follows_the_normal_force(profiles):
    """Figure 17: the friction force. Kubas's bodies slide over the whole wrap (his figure
    18), so his friction is mu*N everywhere and figure 17 looks like figure 16. Here the
    drive runs as creep theory says: an adhesion arc at the entry with almost no friction
    (|f| < 0.1 N measured 0.002-0.09 N on the drive, 0.007-0.05 on the driven pulley), then
    a slip arc where |f| = mu*N and friction follows the normal force: it falls round the
    drive pulley (pushing the belt forward, f > 0) and rises round the driven one (holding
    it back, f < 0). Measured |f|/N on the drive's slip arc 0.99-1.01 (mu_k = 1.0, mu_s =
    1.05: asserted within [0.95, 1.06]); on the driven one it reaches 0.94 within the wrap
    (the bodies there still creep towards the exit), asserted > 0.85 at its largest."""
    drive, driven = profiles["drive"], profiles["driven"]
    # Adhesion arcs: the three bins after the entry.
    assert np.all(np.abs(drive.friction[2:5]) < 0.1 * drive.normal[2:5]), drive.friction
    assert np.all(np.abs(driven.friction[3:6]) < 0.1 * driven.normal[3:6]), driven.friction
    # Slip arcs: the last four bins before the exit bin.
    ratio = drive.friction[-5:-1] / drive.normal[-5:-1]
    assert np.all((ratio > 0.95) & (ratio < 1.06)), ratio
    assert np.all(np.diff(drive.friction[-5:-1]) < 0), drive.friction
    f = driven.friction[-6:-2]
    assert np.all(f < 0) and np.all(np.diff(np.abs(f)) > 0), driven.friction
    assert np.max(np.abs(f) / driven.normal[-6:-2]) > 0.85


def test_span_tensions_swing_as_in_figure_15(case_k_run):
    """Figure 15: an SDE's force swings between about 250 N on the slack (upper in the
    paper's view, lower here) span and about 780 N on the tight one. Measured at default
    settings: 264 N and 815 N (+5.6 %, +4.5 %). The paper's figures are read off a plot
    ("about") and do not fit its own data exactly: 780 - 250 = 530 N is 4.6 % below the
    M/r = 555.6 N that the drive pulley's balance requires in steady running, and
    780 + 250 = 1030 N is 7 % below twice its "slightly above 550 N" preload, which a
    closed belt of fixed length keeps within a few per cent. A 10 % tolerance therefore
    allows for the reading and asserts the level; the difference is held to M/r within
    2 % by tests/test_rigid_body.py."""
    _, _, res = case_k_run
    upper, lower = span_tensions(res)
    window = res.time >= 0.35
    tight, slack = upper[window].mean(), lower[window].mean()
    assert tight == pytest.approx(780.0, rel=0.10)
    assert slack == pytest.approx(250.0, rel=0.10)
    assert tight - slack == pytest.approx(CASE_K_TORQUE, rel=0.02)
    # A body is followed round: the joint tension of one body swings between the two
    # levels as it passes from one span to the other (its largest and smallest values
    # over the run after the ramp bracket both span means).
    joint = res.tension[window]
    assert np.all(joint.max(axis=0) >= slack) and joint.max() > tight and joint.min() < slack

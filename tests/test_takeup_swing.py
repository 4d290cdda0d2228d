"""The 300 m builder conveyor's takeup swing after a 4 s start (issue 12), against a lumped
model written independently of the engine (tests/takeup_swing.py; docs/stops-takeups.md,
"The takeup's swing after a start").

What the comparison found (session 11, `python benches/ripple_fixtures.py conveyor`, and
the engine's record of takeup travel, T1 and T2 10 m from the head over 16 s):

- The frequency is physics: the takeup (5285 kg) on the two strands' axial stiffness in
  series with their spans' sag between idlers, the strands' mass distributed (the loaded
  carry's 104 kg/m against the return's 26 kg/m couples the belt's motion to the takeup's),
  the VFD's PI loop stiff at the drum (K_i 4.5 MN/m against 2 EA/L = 0.56 MN/m): 0.578 Hz
  in the lumped model (0.69 Hz without the sag), 0.554-0.598 Hz in the engine (the sag's
  stiffness rises with tension, so the frequency rises as the swing decays: 0.554 Hz at
  31 mm, 0.598 Hz at 15 mm).
- The decay is the drive's: the belt's Kelvin-Voigt damping (zeta 0.05 of an element, a
  retardation time of 11 us) gives the mode 2e-5, the idlers' resistance f is a constant
  force while the belt runs forward and damps nothing; the PI loop's K_p gives the lumped
  mode zeta = 1.7 %, the engine's swing decays at about 2.4 % (31, 23, 18, 15 mm in
  successive 3 s windows).
- The amplitude is the lumped model's once the belt may slide on the head drum: 31 mm of
  takeup travel and 6.0 kN*m of torque in the engine after the start, 32 mm and 5.8 kN*m
  in the lumped model with the capstan limit, against 3.8 mm and 0.9 kN*m with the belt
  held on the drum (3.8 to 14 mm for ramps of 3.6-4.4 s: the residual of a smooth start
  depends on where it ends in the mode's cycle). Held there, the lumped model's T1/T2
  reaches 3.88, beyond e^(mu_k pi) = 3.00 at the lagging's 0.35. The engine's belt slides
  on the head drum through the whole ramp (T1/T2 10 m from the drum 2.92-2.98 from 0.5 s
  to 4 s), the drive's torque held at the friction limit (-12 to -16 kN*m), and at the end
  of the ramp the belt catches up with the drum: the torque falls from -14.6 to -2 kN*m
  within 0.4 s, a step that starts the 31 mm swing. That slip is what the physics of this
  conveyor does with a 22 kN takeup: the builder's grip rule (Conveyor.takeup_tension, DIN
  22101's T2 >= F_A/(e^(mu theta) - 1)) takes the static slack-side tension at the drum,
  the takeup tension less the return's running resistance, and leaves out the return
  strand's own acceleration force in the start (26.4 kg/m x 300 m x 0.785 m/s^2 = 6.2 kN),
  which the takeup at the tail cannot supply to the drum: in the start T2 at the drum
  falls to 13 kN. This was a design-rule gap of the builder, not an error of the engine:
  since session 11 the rule counts that force (``Conveyor._mass_to_takeup``) and chose
  28 kN; the engine's belt still slid there for 0.6 s of the ramp (session 13), and since
  session 13 the rule also takes the start's dynamic overshoot (``Conveyor.start_grip``)
  and chooses 31 kN, which holds the belt on the drum (the last test here). The tests of
  the sliding swing keep the 22 kN takeup (``sliding_scene``).
"""

from dataclasses import replace

import numpy as np
import pytest

import beltrs
from conveyor_300 import conveyor_300
from takeup_swing import Lumped, fit_swing, from_scene

RAMP = 4.0
MU_K = 0.35  # the builder's default lagging, kinetic


SLIDING = 22e3  # N per strand: the takeup the builder chose before session 11's grip rule


def takeup_scene(tension: float) -> beltrs.Scene:
    from beltrs.conveyor import TakeupSpec

    return conveyor_300(ramp=RAMP, takeup=TakeupSpec(location="tail", tension=tension)).scene()


def gripping_scene():
    return takeup_scene(30e3)


def sliding_scene():
    return takeup_scene(SLIDING)


@pytest.fixture(scope="module")
def lumped():
    return from_scene(sliding_scene(), 300.0, n=10)


def test_two_element_lumped_model_matches_its_closed_form():
    """n = 1, no sag, the drum held (K_i huge, K_p 0): the 2-DOF model of the module's
    docstring, whose eigenvalues are those of M = [[m_u, m_ux], [m_ux, m_x]], K = 2k I."""
    m = Lumped(length=300.0, ea=83.3e6, belt=22.4, material=69.4, carry_rolls=13.3, return_rolls=4.0,
               takeup_mass=5285.0, tail_inertia=640.0, drum_inertia=5644.0, kp=0.0, ki=1e15, f=0.0,
               carry_roll_mass=0.0, return_roll_mass=0.0, n=1)
    mc, mr, L, k = 22.4 + 69.4 + 13.3, 22.4 + 4.0, 300.0, 83.3e6 / 300.0
    M = np.array([[640.0 + (mc + mr) * L / 2, (mr - mc) * L / 2], [(mr - mc) * L / 2, 5285.0 + (mc + mr) * L / 2]])
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, 2 * k * np.eye(2))).real)
    got = [f for f, _ in m.modes()][:2]
    assert got == pytest.approx(np.sqrt(w2) / (2 * np.pi), rel=1e-6)


def test_lumped_takeup_mode_converges_and_the_spans_sag_sets_its_frequency(lumped):
    f10, z10 = lumped.modes()[0]
    f30, _ = replace(lumped, n=30).modes()[0]
    assert f30 == pytest.approx(f10, rel=2e-3)  # measured 0.5782 / 0.5777
    assert f10 == pytest.approx(0.578, abs=0.002)
    assert 0.01 < z10 < 0.03  # the PI's K_p: measured 1.7 %
    # Without the spans' sag (the elastic strands only): 0.69 Hz, well above the engine's.
    elastic = replace(lumped, carry_pitch=0.0, return_pitch=0.0).modes()[0][0]
    assert elastic == pytest.approx(0.690, abs=0.003)
    # The belt's own damping alone (the PI's K_p removed) is negligible at this frequency.
    assert replace(lumped, kp=0.0).modes()[0][1] < 1e-3


def test_the_builders_takeup_cannot_hold_the_belt_on_the_drum_in_a_four_second_start(lumped):
    """Held on the drum (the lumped model cannot slip) the belt needs T1/T2 above e^(mu pi)
    at a 22 kN takeup (the builder's choice before session 11): the drum must slide. 30 kN
    holds it."""
    grip = np.exp(MU_K * np.pi)
    r = lumped.start(2.0, RAMP, RAMP + 0.5)
    assert (r["T1"] / r["T2"]).max() > 1.2 * grip  # measured 3.88 against 3.00
    r = from_scene(gripping_scene(), 300.0, n=10).start(2.0, RAMP, RAMP + 0.5)
    assert (r["T1"] / r["T2"]).max() < grip  # measured 2.91


@pytest.fixture(scope="module")
def engine():
    """The test_ripple ``conveyor`` fixture's run as it was before session 11's grip rule
    (builder's defaults but the 22 kN takeup, design start at rest, 4 s Harrison start),
    recording the takeup's travel and T1, T2 10 m from the head."""
    from beltrs.analysis import tension_at

    scene = sliding_scene()
    sim = beltrs.Simulation(scene)
    out = {k: [] for k in ("time", "T1", "T2", "torque", "travel")}
    while sim.time < 9.0 - 1e-9:
        res = sim.run(min(0.5, 9.0 - sim.time), record_interval=0.002, tension=True, node_position=True,
                      node_velocity=False)
        s = slice(1, None) if out["time"] else slice(None)
        out["time"].append(res.time[s])
        out["T1"].append(tension_at(res.node_position[s], res.tension[s], (290.0, 0.0)))
        out["T2"].append(tension_at(res.node_position[s], res.tension[s], (290.0, -0.8)))
        out["torque"].append(res.drive_torque[s, res.pulley_names.index("head")])
        out["travel"].append(res.takeup_travel[s, res.pulley_names.index("tail")])
    return {k: np.concatenate(v) for k, v in out.items()}


@pytest.mark.slow
def test_engine_takeup_swing_after_the_start_has_the_lumped_models_frequency(engine, lumped):
    """Frequency of the takeup's travel and of the drive torque over 4.5-8.5 s, against the
    lumped model's mode at the running tensions. Tolerance 8 %: the sag's stiffness grows as
    T^3, so the mode's frequency depends on the swing's amplitude, and the engine's own
    frequency moves by 8 % (0.554 -> 0.598 Hz) as the swing decays from 31 to 15 mm
    (measured over 16 s); the lumped model is linearised about the steady tensions."""
    f0 = lumped.modes()[0][0]
    t = engine["time"]
    ft, at = fit_swing(t, engine["travel"], 4.5, 8.5)
    fq, aq = fit_swing(t, engine["torque"], 4.5, 8.5)
    assert ft == pytest.approx(f0, rel=0.08)
    assert fq == pytest.approx(f0, rel=0.08)
    # The swing is the takeup's: tens of mm of travel, kN*m of torque (measured over 4.5-8.5 s:
    # 0.571 Hz, 31 mm; 0.575 Hz, 6.0 kN*m; the lumped model 0.578 Hz).
    assert at > 0.01 and aq > 2e3


@pytest.mark.slow
def test_engine_belt_slides_on_the_head_drum_through_the_start(engine):
    """What sets the amplitude: through the ramp T1/T2 10 m from the drum stays at the
    kinetic limit e^(mu_k pi) = 3.00 (within 3 %: the 10 m of carry and return between the
    probes and the drum, their resistance and inertia, measured 2.92-2.98), and at the end
    of the ramp the torque falls off that limit within 0.5 s."""
    t, r = engine["time"], engine["T1"] / engine["T2"]
    grip = np.exp(MU_K * np.pi)
    for a in np.arange(0.5, 4.0, 0.5):
        w = (t >= a) & (t < a + 0.5)
        assert r[w].max() == pytest.approx(grip, rel=0.03), a
    tq = engine["torque"]
    at_end = tq[np.argmin(abs(t - RAMP))]
    after = tq[np.argmin(abs(t - RAMP - 0.5))]
    # measured -14.6 and -2 kN*m (session 11); -14.7 and +0.3 with session 12's motor law
    # (63 kW and 0.99 kg*m^2 instead of 61 kW and 0.81: the swing's phase at 0.5 s moves)
    assert at_end < -12e3 and after > -6e3


@pytest.mark.slow
def test_a_takeup_that_grips_the_start_leaves_the_lumped_models_swing_and_a_smooth_torque():
    """The same conveyor and start with a 30 kN takeup (``TakeupSpec(tension=30e3)``), with
    which the lumped model keeps T1/T2 under e^(mu_k pi) (2.91): the belt stays on the drum,
    and the engine's swing after the start is the lumped model's. Measured (session 11,
    `python benches/ripple_fixtures.py conveyor --takeup 30000`): torque swing 0.642 Hz and
    1.12 kN*m over 4.5-8.5 s against the lumped model's 0.629 Hz and 1.08 kN*m (its mode at
    the running tensions 0.623 Hz; the 30 kN takeup's counterweight is 6116 kg);
    the torque stays between -4.5 and -2.3 kN*m (mean -3.17) and
    the figure above 2 Hz after the start reads 0.018 (0.179 at the builder's 22 kN, where
    the drum slides through the start). Session 12's motor law (63 kW, 0.99 kg*m^2): engine
    0.642 Hz and 1.14 kN*m, lumped 0.629 Hz and 1.10 kN*m (mode 0.624 Hz), torque -4.57 to
    -2.27 kN*m (mean -3.17), figure 0.0185.

    Tolerances: frequency 5 % (the engine's own frequency moves by 8 % as a 31 -> 15 mm
    swing decays, at this 5 mm swing less); amplitude 30 % (the residual of a smooth start
    depends on the phase at which the ramp ends in the mode's cycle: in the lumped model
    ramps of 3.8, 4.0 and 4.2 s leave 6.3, 3.8 and 7.3 mm, so a 2 % frequency difference
    moves it by tens of %); the after-start figure is the issue's 5 %."""
    from conveyor_300 import measure, ripple_figures

    scene = gripping_scene()
    model = from_scene(scene, 300.0, n=10)
    r = model.start(2.0, RAMP, 9.0)
    f_model, a_model = fit_swing(r["time"], r["drive"] * scene.pulleys[1].radius, 4.5, 8.5)
    assert model.modes()[0][0] == pytest.approx(0.623, abs=0.003)
    data = measure(beltrs.Simulation(scene), (290.0, 0.0), "head", 9.0)
    f_eng, a_eng = fit_swing(data["time"], data["torque"], 4.5, 8.5)
    assert f_eng == pytest.approx(model.modes()[0][0], rel=0.05)
    assert a_eng == pytest.approx(a_model, rel=0.30)
    fig = ripple_figures(data, 2.0, margin=1.0)
    assert fig["torque_max"] < 0, fig  # no reversal
    assert fig["torque_ripple"] < 0.05, fig


@pytest.mark.slow
def test_after_the_start_the_engines_swing_is_the_lumped_models_with_the_belt_sliding_on_the_drum(engine):
    """The after-start case of tests/test_ripple.py at the builder's defaults with the 22 kN
    takeup it chose before session 11,
    as a test of its physics: the lumped model with the belt free to slide on the head drum
    (capstan limit at the lagging's mu_k = 0.35, ``Lumped.mu``) against the engine, over
    4.5-8.5 s. The drive torque's figure above 2 Hz there is 0.179 (`python
    benches/ripple_fixtures.py conveyor`; 0.189 reported before the session's last merges),
    the issue's 5 % not met: that is this swing, which reverses the torque (-10.4 to
    +1.9 kN*m about -3.3 kN*m); a takeup that grips (30 kN, below) reads 0.018.

    Measured: lumped 0.551 Hz, 32.3 mm of travel, 5.83 kN*m of torque, the torque falling
    from 13.0 to 0.1 kN*m within 0.5 s of the ramp's end; engine 0.571 Hz, 31.2 mm, 0.575 Hz,
    5.97 kN*m, -14.6 to -2.0 kN*m. Session 12's motor law (the builder's motor 63 kW and
    0.99 kg*m^2 instead of 61 kW and 0.81): lumped 0.552 Hz, 32.4 mm, 5.85 kN*m; engine
    0.571 Hz, 31.3 mm, 0.575 Hz, 5.99 kN*m, -14.7 to +0.3 kN*m. Tolerances: frequency 8 % (the engine's own moves by 8 %
    as the swing decays, above); amplitudes 25 %: the swing starts with the re-grip, whose
    timing the lumped model's regularised stick (a 5 MN*s/m dashpot, creep up to 1 cm/s at
    30 kN) and its ten elements per strand place only approximately; with a 3.6 s ramp the
    two read 33.1 and 25.5 mm (30 % apart), at 4 s within 4 %."""
    model = replace(from_scene(sliding_scene(), 300.0, n=10), mu=MU_K)
    r = model.start(2.0, RAMP, 9.0)
    fm, am = fit_swing(r["time"], r["travel"], 4.5, 8.5)
    _, qm = fit_swing(r["time"], 0.4 * r["drive"], 4.5, 8.5)
    t = engine["time"]
    fe, ae = fit_swing(t, engine["travel"], 4.5, 8.5)
    _, qe = fit_swing(t, engine["torque"], 4.5, 8.5)
    assert fe == pytest.approx(fm, rel=0.08)
    assert ae == pytest.approx(am, rel=0.25)
    assert qe == pytest.approx(qm, rel=0.25)
    # Without the slip the lumped model's swing is 8x smaller: the slip is the mechanism.
    held = replace(model, mu=None).start(2.0, RAMP, 9.0)
    assert fit_swing(held["time"], held["travel"], 4.5, 8.5)[1] < ae / 4


def test_the_builders_takeup_counts_the_return_strands_start_force_and_the_starts_overshoot():
    """Since session 11 the builder's grip rule counts the return strand's acceleration force
    between the head drum and the tail takeup (DIN 22101's start tension distribution,
    ``Conveyor._mass_to_takeup``): DIN's two rules choose 28 kN for this conveyor and start
    (22 kN before). The lumped model held on the drum then still needs T1/T2 of 3.11 through
    the start against the grip e^(mu_k pi) = 3.00 (3.88 at 22 kN, 2.91 at 30 kN; measured,
    session 11): the start's dynamic overshoot over the rigid belt's force. The engine at
    28 kN slid on the drum for 0.60 s between 1.44 and 2.79 s, at up to 17.4 mm/s (session
    13; held there by a lagging of mu = 1, its T1/T2 10 m from the drum reads 3.17).
    Since session 13 the rule takes that overshoot from a lumped model of its own
    (``Conveyor.start_grip``, beltrs.start_grip) and chooses 31 kN; there this model reads
    2.830 and the engine grips (no instant with the whole arc slipping, the belt behind the
    drum by 0.86 mm/s at most, T1/T2 10 m from the drum 2.88; session 13)."""
    c = conveyor_300(ramp=RAMP)
    assert c.takeup_tension(start_dynamics=False) == 28e3
    assert c.takeup_tension() == 31e3
    grip = np.exp(MU_K * np.pi)
    din = conveyor_300(ramp=RAMP, takeup=beltrs.conveyor.TakeupSpec(location="tail", tension=28e3))
    r = from_scene(din.scene(), 300.0, n=10).start(2.0, RAMP, RAMP + 0.5)
    assert (r["T1"] / r["T2"]).max() > 1.03 * grip  # measured 3.108
    r = from_scene(c.scene(), 300.0, n=10).start(2.0, RAMP, RAMP + 0.5)
    assert (r["T1"] / r["T2"]).max() < 0.96 * grip  # measured 2.830

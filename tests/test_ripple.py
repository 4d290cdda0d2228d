"""True peaks and smooth drives (issue 12): the raw tight-side tension peak within 3 % of
the peak below 2 Hz, and the steady drive torque free of ripple (under 5 % of its mean), on
case G (shortened) and on a 300 m builder conveyor, at the builders' default settings: wrap
contact on the drums and on the rolls (``belt.pulley_contact = "wrap"``,
``belt.idler_contact = "wrap"``) and, from a design start, the spans placed in their sag
(``initial.sag``), the conveyor builders' defaults (docs/wrap-contact.md).

The mechanism (docs/case-g.md, "The chordal ripple"): with nodal contact the belt round a
held drum was a chain of straight links on a sprocket; its strand left from the last node
on the drum along a chord, at a speed varying as 1 - cos(theta/2) at the node-passing
frequency, and each node landing on the drum was brought to its surface speed within one
step. Wrap contact (rust/src/contact/wrap.rs) measures the elements on a pulley along the
belt's path round it, so the strand leaves on the tangent at the drum's speed.

Tolerance: 3 % is the issue's target. The low-passed peak is the converged engineering
figure (within 1 % from 0.2 m to 0.05 m elements, docs/accuracy.md), so it is read from the
same run. With nodal contact these runs read +7.2 % (case G, 150 m) and +9.4 % (300 m);
with wrap contact on the drums and the segment contact on the rolls +1.62 % and +0.98 %;
at today's defaults (roll wrap too) +1.08 % and +0.06 % (``python benches/ripple_fixtures.py
{case_g|conveyor}``, session 9; docs/wrap-contact.md).

The second target, a steady drive torque within 5 % of its mean, is not met (strict xfail,
so the day it is met the test says so). At today's defaults these fixtures read 0.46
(case G) and 0.29 (300 m) of the mean above 2 Hz (the same command; with the segment
contact on the rolls, the builders' defaults until session 9, 3.26 and 1.68). The torque's
window ends MARGIN s before the record does: the low-pass rings at the record's end (case G
with roll wrap: 0.83 with the window at the end, 0.46 inside a 20 s record). Measured
(docs/wrap-contact.md, "The rolls' chordal action", "Roll wrap as the builders' default",
"Roll wrap with a viscoelastic belt" and "Session 9: what is left"; benches/ripple_drive.py):
the largest part was the idler rolls' chordal action, a straight element over a roll lifting
its nodes off the belt's curve at the node-passing frequency v/l (lines at its harmonics, in
phase over all rolls when the pitch is a whole number of elements), which roll wrap removes.
What is left (benches/ripple_fixtures.py ``--steady 16 --windows 2``): the figure does not
fall over 16 s at speed, but it holds mostly the start's ringing of the strands'
longitudinal modes, damped at zeta ~ 1e-3 (case G: the loop's 2.02 Hz mode, just above the
2 Hz cut-off, 0.30 of the mean; 300 m: the takeup's 0.59 Hz swing of 1.7x the mean, which
reverses the torque, and lines at 2.4-4.4 Hz); the lumped weight riding the rolls' kinks at
v/l, in phase on case G whose pitches are whole numbers of elements (10 Hz, 0.13); drum
stick-slip spikes above 80 Hz (0.06-0.20). A viscoelastic belt (``belt.loss_factor`` 0.2)
brought them to 0.14 and 0.12 in session 8, and no published loss factor for a conveyor belt
in tension was found to make it a default. Case G reaches 0.037 with a PI speed controller
on the drive and 0.19 m elements, neither of them a builder default.

Steady running (session 10). The figure after a 4 s start measures mostly that start's
physical ringing, which the model damps only as much as its drive and belt do. The issue's
target is the steady-running ripple, so it is also measured where nothing rings: from the
builders' running design start (steady-running tensions, belt at speed, no ramp; the window
the same 2 s, ending MARGIN s before the record). With the ideal speed follower what is left
there is the model's own ripple: the lumped weight's cogging over the rolls (case G 0.084)
and the drums' stick-slip (300 m 0.069). The builders drive with a VFD since session 10 (PI
speed loop, the motor's rotor through the gearbox: docs/drives.md): its motor torque is
within 5 % on both (0.030, 0.011), the gearbox shaft's on the 300 m (0.013) but not quite on
case G (0.051: cogging and stick-slip, strict xfail). Session 11: the drums' stick-slip law
(a sliding contact and the slip front at mu_k, docs/wrap-contact.md) and case G's element
length off its idler pitches (0.196 m; the cogging line 40.6 -> 12.1 N*m): case G's shaft
0.032, motor 0.018, 300 m unchanged (0.013, 0.011); after the 4 s start case G's motor
torque reads 0.044 (under 5 %; it was 0.057) and the 300 m's 0.189
(the 300 m: 0.079 with the 24 kN takeup the builder chose before its grip rule left the rotor
out; at 22 kN the takeup's swing reverses the torque, -10.4 to +1.9 kN*m). Why
(tests/test_takeup_swing.py): at 22 kN the belt slides on the head drum through the whole
start, the builder's grip rule leaving out the return strand's acceleration force; a 30 kN
takeup grips and reads 0.018 after the start. The rule now counts that force (lead, session
11): the builder chooses 28 kN, and the 300 m reads 0.029 after the start (torque -4.39 ...
-2.06 kN*m, no reversal), 0.0093 motor and 0.0107 shaft in steady running. Every ripple
target of the issue is then met at the defaults on both conveyors. Session 12's motor-inertia
law (docs/drives.md; the 300 m's motor 63 kW and 0.99 kg*m^2 instead of 61 kW and 0.81):
0.029 after the start (-4.40 ... -2.04 kN*m), 0.0095 motor and 0.0105 shaft in steady running.
Session 13's grip through the start's dynamics (Conveyor.start_grip: at 28 kN the belt still
slid on the head drum for 0.6 s of the 4 s start) chooses 31 kN: 0.0176 after the start
(-4.61 ... -2.23 kN*m about -3.15 kN*m), 0.0097 motor and 0.0112 shaft in steady running.
"""

from dataclasses import replace

import numpy as np

import pytest

import beltrs
from beltrs.scenes import GUO_WANG, guo_wang_conveyor
from conveyor_300 import conveyor_300, measure, ripple_figures, shaft_torque

RAMP = 4.0  # s, Harrison to 2 m/s
STEADY = 4.0  # s at full speed
WINDOW = 2.0  # s of steady running for the torque
# s run after the torque's window, so that the low-pass's ringing at the record's end stays
# outside it (ripple_figures; measured on case G with roll wrap: window at the record's end
# 0.83, 1 s inside it 0.52, inside a 20 s record 0.46).
MARGIN = 1.0


def wrapped(scene: beltrs.Scene) -> beltrs.Scene:
    return replace(scene, belt=replace(scene.belt, pulley_contact="wrap"))


@pytest.fixture(scope="module")
def case_g():
    length = 150.0
    curve = beltrs.StartCurve(shape="harrison", speed=GUO_WANG["speed"], ramp=RAMP)
    scene = guo_wang_conveyor(curve, length=length)
    assert scene.belt.pulley_contact == "wrap"  # the builder's default
    sim = beltrs.Simulation(scene)
    sim.stabilise(tolerance=1e-5, max_steps=400_000)
    data = measure(sim, (length - 10.0, GUO_WANG["drum_radius"]), "head", RAMP + STEADY + MARGIN)
    return ripple_figures(data, WINDOW, margin=MARGIN)


@pytest.fixture(scope="module")
def conveyor():
    # The builder's design start (at rest, no relaxation), its spans placed in their sag
    # (initial.sag, the builders' default: docs/design-start.md). From the straight design
    # placement this read +4.9 %: the spans sinking into their sag during the first second
    # rang the strands (raw 57.8 kN at 4.0 s against 55.1 kN below 2 Hz at 1.2 s).
    scene = conveyor_300(ramp=RAMP).scene()
    assert scene.belt.pulley_contact == "wrap" and scene.initial.sag  # the builder's defaults
    sim = beltrs.Simulation(scene)
    data = measure(sim, (290.0, 0.0), "head", RAMP + STEADY + MARGIN)
    return ripple_figures(data, WINDOW, margin=MARGIN)


def with_shaft(data: dict, scene: beltrs.Scene) -> dict:
    """The figures of ``data`` and, as ``shaft_*``, those of the gearbox shaft's torque."""
    f = ripple_figures(data, WINDOW, margin=MARGIN)
    s = ripple_figures(dict(data, torque=shaft_torque(data, scene)), WINDOW, margin=MARGIN)
    f.update({"shaft_" + k: s[k] for k in ("torque_mean", "torque_ripple")})
    return f


@pytest.fixture(scope="module")
def case_g_running():
    # Steady running without the start: the builder's running design start (DIN 22101's
    # steady-running tensions, belt and drums at speed; docs/design-start.md), measured over
    # the window ending MARGIN s before the record's end.
    length = 150.0
    curve = beltrs.StartCurve(shape="harrison", speed=GUO_WANG["speed"], ramp=RAMP)
    scene = guo_wang_conveyor(curve, length=length, start="running")
    data = measure(beltrs.Simulation(scene), (length - 10.0, GUO_WANG["drum_radius"]), "head", STEADY + MARGIN)
    return with_shaft(data, scene)


@pytest.fixture(scope="module")
def conveyor_running():
    scene = conveyor_300(ramp=RAMP, start="running").scene()
    data = measure(beltrs.Simulation(scene), (290.0, 0.0), "head", STEADY + MARGIN)
    return with_shaft(data, scene)


@pytest.mark.slow
@pytest.mark.parametrize("which", [
    "case_g",
    # Measured +0.06 % at the defaults since session 9 (roll wrap; the segment contact on
    # the rolls +0.98 %, and +1.10 % before the 1 s MARGIN: raw 56.14 kN at 4.0 s, 55.53 kN
    # below 2 Hz at 1.2 s); the same start with nodal contact reads +5.98 %. At session 13's
    # 31 kN takeup -0.06 % (raw 66.92 kN at 2.62 s, 66.96 kN below 2 Hz at 2.61 s).
    "conveyor",
])
def test_raw_peak_within_three_percent_of_the_low_passed_peak(which, request):
    f = request.getfixturevalue(which)
    assert f["raw_peak"] == pytest.approx(f["low_peak"], rel=0.03), f


@pytest.mark.slow
@pytest.mark.parametrize("which", ["case_g_running", "conveyor_running"])
def test_steady_running_drive_torque_ripple_under_five_percent(which, request):
    """The issue's target as it reads: the drive torque in steady running within 5 % of its
    mean above 2 Hz, at the builders' defaults (since session 10 a VFD: PI speed loop and the
    motor's rotor, docs/drives.md). ``drive_torque`` is the motor's air-gap torque; the rotor's
    inertia keeps the drums' stick-slip spikes off it. Measured (session 10, `python
    benches/ripple_fixtures.py {case_g|conveyor} --start running`): 0.030 (case G) and 0.011
    (300 m); with the ideal speed follower (``--control ideal``) 0.084 and 0.069 (the 9.96 Hz
    cogging line on case G, the drums' stick-slip spikes on 300 m). Session 11 (the drums'
    stick-slip law, case G's element length off its pitches): 0.018 and 0.011; ideal
    follower 0.075 (case G: its head drum's last node breaking away from mu_s, a slip arc
    shorter than a node, docs/wrap-contact.md) and 0.020. The 300 m at the 28 kN takeup of
    the builder's grip rule since session 11: 0.0093; with session 12's motor law 0.0095; at
    the 31 kN of session 13's rule (the start's dynamics) 0.0097."""
    f = request.getfixturevalue(which)
    assert f["torque_mean"] < 0, f
    assert f["torque_ripple"] < 0.05, f


@pytest.mark.slow
@pytest.mark.parametrize("which", ["case_g_running", "conveyor_running"])
def test_steady_running_gearbox_shaft_torque_ripple_under_five_percent(which, request):
    """The same target on the torque a gearbox designer reads: the shaft between gearbox and
    drum, the motor's torque less what accelerates the rotor (tests/conveyor_300.py
    ``shaft_torque``). Measured (session 11, `python benches/ripple_fixtures.py
    {case_g|conveyor} --start running`, its ``shaft_ripple``): case G 0.032, 300 m 0.013
    (0.0107 at the 28 kN takeup of the builder's grip rule since session 11; 0.0105 with
    session 12's motor law; 0.0112 at session 13's 31 kN).
    Case G read 0.051 (a strict xfail) with 0.2 m elements, its 1.2 m and 3 m idler pitches
    whole numbers of them: the rolls' gravity cogging added up in phase, a 9.96 Hz line of
    40.6 N*m. Its builder now takes 0.196 m (6.125 and 15.3125 per pitch,
    ``beltrs.layout.element_length_off_pitches``): the line at 9.98 Hz is 12.1 N*m."""
    f = request.getfixturevalue(which)
    assert f["shaft_torque_mean"] < 0, f
    assert f["shaft_torque_ripple"] < 0.05, f


@pytest.mark.slow
@pytest.mark.parametrize("which", [
    # Measured 0.044 (session 11, `python benches/ripple_fixtures.py case_g`): 0.057 with
    # 0.2 m elements, whose whole numbers per idler pitch put the rolls' gravity cogging in
    # phase; the builder's 0.196 m keeps the pitches off them (docs/wrap-contact.md,
    # "Session 11: the element length off the pitches").
    "case_g",
    # Measured 0.029 (session 11, lead: `python benches/ripple_fixtures.py conveyor`; torque
    # -4.39 ... -2.06 kN*m about -3.12 kN*m) at the 28 kN takeup the builder's grip rule
    # chooses since it counts the return strand's start force (session 12's motor law, 63 kW
    # and 0.99 kg*m^2: 0.029, -4.40 ... -2.04 kN*m). With the 22 kN it chose
    # before: 0.179 (0.189 earlier in session 11), the belt sliding on the head drum through
    # the start and re-gripping at its end, the takeup swinging at 0.57 Hz by +-31 mm and
    # reversing the torque (tests/test_takeup_swing.py, docs/stops-takeups.md, "The takeup's
    # swing after a start"); with a 30 kN takeup 0.018. Session 13: the rule takes the
    # start's overshoot (at 28 kN the belt still slid for 0.6 s) and chooses 31 kN: 0.0176
    # (-4.61 ... -2.23 kN*m about -3.15 kN*m).
    "conveyor",
])
def test_drive_torque_ripple_after_a_four_second_start_under_five_percent(which, request):
    f = request.getfixturevalue(which)
    # A normal head drive: the belt runs clockwise over the drum, the torque is negative.
    assert f["torque_mean"] < 0, f
    assert f["torque_ripple"] < 0.05, f


def test_element_length_keeps_the_idler_pitches_off_whole_numbers_of_elements():
    """Gravity cogging (docs/wrap-contact.md, "Session 11: the element length off the
    pitches"): roll k of a row drives a force at v/l with phase 2*pi*k*p/l, so the N rolls
    of a row add to |sin(N*pi*phi)/sin(pi*phi)| rolls' worth, phi the distance of p/l from
    a whole number. The chosen length keeps phi >= 1/8 on every pitch: at most 2.6 rolls'
    worth however many rolls, against all N of them at a whole number."""
    from beltrs.conveyor import Conveyor
    from beltrs.layout import element_length_off_pitches

    def rolls_worth(pitch, length, n=125):
        k = np.arange(n)
        return abs(np.exp(2j * np.pi * k * pitch / length).sum())

    # Case G: 0.2 m is a whole 6 and 15 per 1.2 m and 3 m pitch: 125 carry rolls in phase.
    assert rolls_worth(1.2, 0.2) == pytest.approx(125)
    le = element_length_off_pitches(0.2, [1.2, 3.0])
    assert le == pytest.approx(1.2 / 6.125) and le <= 0.2  # 15.3125 per return pitch
    assert all(rolls_worth(p, le) <= 1 / np.sin(np.pi / 8) + 1e-9 for p in (1.2, 3.0))
    # The builder uses it; an explicit element_length is used as given.
    path = 2 * 150.0 + 2 * np.pi * GUO_WANG["drum_radius"]
    assert guo_wang_conveyor(length=150.0).belt.elements == int(np.ceil(path / le))
    assert guo_wang_conveyor(length=150.0, element_length=0.2).belt.elements == int(np.ceil(path / 0.2))
    # Already off the pitches (the 300 m builder conveyor's 0.2094 m: 5.73 and 14.3): kept.
    assert element_length_off_pitches(0.4 * np.pi / 6, [1.2, 3.0]) == 0.4 * np.pi / 6
    # The builder's other choice, a quarter of the carry pitch, is a whole 4 per pitch (and
    # 10 per 3 m return pitch): drums above 1.146 m took it until session 11.
    assert element_length_off_pitches(0.3, [1.2, 3.0]) == pytest.approx(1.2 / 4.125)
    assert Conveyor(pulley_radius=1.0).chosen_element_length == pytest.approx(1.2 / 4.125)
    assert Conveyor().chosen_element_length == 0.4 * np.pi / 6
    # A return pitch twice the carry pitch: half an element off on the carry would put the
    # return on a whole number, so both are kept an eighth off.
    le = element_length_off_pitches(0.3, [1.2, 2.4])
    assert all(abs(p / le - round(p / le)) >= 0.125 - 1e-9 for p in (1.2, 2.4)) and le <= 0.3
    for bad, field in ((0.0, "element_length"), (float("nan"), "element_length")):
        with pytest.raises(beltrs.SceneError, match=field):
            element_length_off_pitches(bad, [1.2])
    with pytest.raises(beltrs.SceneError, match="pitch"):
        element_length_off_pitches(0.2, [1.2, -3.0])


def test_wrap_contact_removes_the_chord_polygon_error_of_case_h():
    """Case H's takeup displacement: the chord polygon (nodal contact) frees pi*r*theta^2/24
    of belt per half wrap, 0.17 m at 89 elements (docs/accuracy.md); wrap contact holds the
    arc's length, so what is left is the contact compliance and the strands (under 1 mm)."""
    exact = beltrs.analytic.two_pulley_takeup_statics().takeup_displacement
    scene = beltrs.scenes.hustrulid_loop(89)
    nodes = beltrs.Simulation(scene)
    nodes.stabilise()
    wrap = beltrs.Simulation(wrapped(scene))
    wrap.stabilise()
    assert -nodes.takeup_travel[1] - exact < -0.1  # the chord polygon's overshoot
    assert -wrap.takeup_travel[1] == pytest.approx(exact, abs=1e-3)


def test_pulley_contact_key_round_trips_and_bad_values_name_the_field(tmp_path):
    scene = wrapped(beltrs.scenes.hustrulid_loop(89))
    path = tmp_path / "s.toml"
    scene.save(path)
    assert beltrs.load_scene(path).belt.pulley_contact == "wrap"
    assert beltrs.Scene().belt.pulley_contact == "nodes"
    with pytest.raises(beltrs.SceneError, match=r"pulley_contact.*\"nodes\" or \"wrap\""):
        beltrs.Simulation(replace(scene, belt=replace(scene.belt, pulley_contact="wrapped")))


def test_lowpass_names_its_cutoff_and_checks_it():
    sim = beltrs.Simulation(beltrs.scenes.hustrulid_loop(89))
    sim.stabilise()
    res = sim.run(0.5, record_interval=0.005)
    low = res.tension_lowpass(5.0)
    assert low.shape == res.tension.shape
    # A slow component passes, a fast one goes (away from the ends, where the mirrored
    # padding leaks: a few % of the removed amplitude on 100 samples).
    t = res.time
    slow = 3.0 + 0.5 * np.sin(2 * np.pi * 2.0 * t)
    res.drive_torque[:, 0] = slow + np.sin(2 * np.pi * 40.0 * t)
    assert np.allclose(res.drive_torque_lowpass(5.0)[10:-10, 0], slow[10:-10], atol=0.1)
    assert not np.allclose(res.drive_torque[10:-10, 0], slow[10:-10], atol=0.5)
    for bad in (0.0, -1.0, 1e6, "2"):
        with pytest.raises(beltrs.SceneError, match="cutoff"):
            res.lowpass("tension", bad)
    with pytest.raises(beltrs.SceneError, match="channel"):
        res.lowpass("tensions", 2.0)

"""Case G with both belt formulations (issue 12), shortened to 100 m as tests/test_case_g.py
shortens it, here to 60 m: a loaded rigid-body belt runs the same start as the node belt.
Steady running against DIN 22101 and the node model; the start's peak against the node
model. The side-by-side study is benches/case_g.py --formulations (docs/case-g.md).

Cost: four starts (each formulation loaded and bare), 5 s each; the rigid bodies take half
the node belt's step at about three times its cost per step, so they dominate (about a
minute quiet): the smallest run that holds a loaded strand, a start and a steady window.
Since session 13 the builder's rigid bodies are 0.1185 m (at most 0.3 x the drum radius)
instead of 0.196 m: 2.7x their element-steps; this file and tests/test_design_start.py
together measured 120 s of CPU against 80 s."""

from dataclasses import replace

import numpy as np
import pytest

import beltrs
from beltrs.analysis import low_pass, probe_run
from beltrs.scene_file import dumps_scene, loads_scene
from beltrs.scenes import GUO_WANG, guo_wang_conveyor, guo_wang_din

LENGTH = 60.0
R = GUO_WANG["drum_radius"]
RAMP = 2.0  # s, Harrison
SETTLE = 3.0  # s at full speed
INTERVAL = 0.005  # s
PROBES = [(LENGTH - 10.0, R), (LENGTH - 10.0, -R)]  # 10 m before / after the head drum


def start(formulation, **kw):
    curve = beltrs.StartCurve(shape="harrison", speed=GUO_WANG["speed"], ramp=RAMP)
    sim = beltrs.Simulation(guo_wang_conveyor(curve, length=LENGTH, formulation=formulation, **kw))
    sim.stabilise(tolerance=1e-5, max_steps=400_000)
    return sim, probe_run(sim, PROBES, RAMP + SETTLE, INTERVAL)


FORMULATIONS = ("node_kelvin_voigt", "rigid_body")


@pytest.fixture(scope="module")
def runs():
    return {f: start(f) for f in FORMULATIONS}


@pytest.fixture(scope="module")
def bare():
    """No material, f = 0: what each model loses on its own (the belt points landing on
    and leaving the drums, docs/case-g.md)."""
    return {f: start(f, f=0.0, material=0.0) for f in FORMULATIONS}


def steady(data):
    """Mean tension at the probes over the last 2.5 s, Hann-weighted. The chordal ripple
    (about ±5 kN at the rate the belt points leave the head drum: 9.9 Hz for the nodes, an
    inscribed polygon, 10.2 Hz for the rigid bodies, a circumscribed one) and the strand's
    2.1 Hz mode (±0.5 kN) do not fit a whole number of periods into the window: a plain
    mean keeps up to A/(pi f T) of each, 65 N and 36 N (measured: window means of one run
    spread by ±100 N as the window end moves, issue 12). The Hann weight's leakage falls
    as (f T)^-3: below 2 N for both."""
    t = data["time"]
    window = t >= t[-1] - 2.5
    weight = np.hanning(window.sum())
    return weight @ data["tension"][window] / weight.sum()


def test_loaded_rigid_belt_carries_the_material(runs):
    sim, _ = runs["rigid_body"]
    # The material rides on the bodies: 55.6 kg/m on the carry strand from 5 m to the head.
    extra = sim.node_masses().sum() - sim.node_mass.sum()
    expected = GUO_WANG["material"] * (LENGTH - 5.0)
    # 1 %: the zone's edges sit on the bodies nearest the loading point and the head drum's
    # top (within a body, 0.2 m of 95 m).
    assert extra == pytest.approx(expected, rel=0.01)


def net_force(runs, bare, f):
    """Steady T1 − T2 at the probes over the bare conveyor's, and the absolute T1, T2."""
    t1, t2 = steady(runs[f][1])
    b1, b2 = steady(bare[f][1])
    return (t1 - t2) - (b1 - b2), t1, t2


# Measured (session 8, builders' defaults; the rigid bodies resting on their ends,
# rust/src/belt/rigid/contact.rs): the node belt +0.76 %, the rigid bodies -4.95 % of DIN's
# 1395 N; T1, T2 within +0.41 % and +0.02 %. The rigid figure sits at the edge of the 5 %:
# before that contact (bodies touching at their mass centres, dragged by the contact damping
# of turning bodies) it was +13 % (docs/case-g.md, the term-by-term audit). With the
# builder's wrap joints (session 11, 0.2 m, the old drum friction law): rigid +1.96 % (1422.8 N;
# T1 +0.45 %, T2 -0.02 %); at today's 0.196 m bodies and the drums' stick-slip law +3.90 %
# (node belt -0.71 %; lead, merge of session 11); with the drums taking back the moment of
# the bodies' contact (session 12) -1.46 % (1375.0 N; T1 51 302 N, T2 49 754 N; bare
# T1 - T2 172.8 N); at the 0.1185 m bodies the builders give since session 13 (at most
# 0.3 x the drum radius) -0.84 % (1383.7 N; T1 51 300 N +0.37 %, T2 49 730 N +0.03 %).
# With plain joints:
# main 5179f03, 0.2 m: rigid -0.36 % (old drum friction law) and -2.57 % (the
# drums' stick-slip law); 0.192 m elements +2.04 %. The rigid figure is one window of a
# wandering quantity: the same Hann mean in windows ending 5, 6, ... 15 s reads -12.0 to
# +4.6 % (either law; the loaded belt's T1 - T2 swings by 100-150 N below 1 Hz), so it can
# move by several points with anything that shifts that swing's phase (docs/wrap-contact.md,
# "The four tests it moved"). Session 13, stick-force friction with each body's arm
# (docs/kubas.md): rigid -1.84 % (1369.8 N; bare T1 - T2 214.1 N), main edfc824 -1.63 %.
@pytest.mark.parametrize("formulation", ["node_kelvin_voigt", "rigid_body"])
def test_steady_running_matches_din_22101(runs, bare, formulation):
    d1, d2 = guo_wang_din(LENGTH).at_probes(10.0)
    net, t1, t2 = net_force(runs, bare, formulation)
    # The takeup fixes the tail tension: absolute tensions within 1.5 %, as
    # tests/test_case_g.py holds them (the window mean of the ripple).
    assert t1 == pytest.approx(d1, rel=0.015)
    assert t2 == pytest.approx(d2, rel=0.015)
    # What resistances and loading add over the bare conveyor is DIN's F_U less the
    # 2 x 10 m outside the probes (1.4 kN here). 5 %: tests/test_case_g.py's 3 % at 150 m,
    # with a F_U 2.5 times smaller here against the same ±10 kN ripple.
    assert net == pytest.approx(d1 - d2, rel=0.05)


def test_start_peak_agrees_between_formulations(runs):
    peaks = {}
    for f, (_, data) in runs.items():
        peaks[f] = low_pass(data["tension"][:, 0], INTERVAL, 2.0).max()
    # Below 2 Hz the start's own dynamics (the strand's modes, rigid-body acceleration of
    # belt, material and rolls) are the same physics in both models; what differs is each
    # model's loss on the drums and the chordal ripple above 2 Hz. 3 %.
    assert peaks["rigid_body"] == pytest.approx(peaks["node_kelvin_voigt"], rel=0.03)


# Issue 12's raw-peak target: at default settings the raw peak tight-side tension within 3 %
# of the peak below 2 Hz. Measured (session 10) on this 2 s start: node belt +1.20 % (wrap
# contact on drums and rolls, the builder's), rigid bodies with plain joints +35.1 %: their
# raw peak came at full speed (4.26 s, against 1.15 s below 2 Hz), the chordal action of
# 0.2 m bodies on the 0.4 m drums at v/l = 10 Hz (a chain on a sprocket: the strand is drawn
# at R_e*omega*cos(theta), theta from -a/2 to a/2, a = l/R). The builder now gives the rigid
# belt wrap joints (session 11, docs/kubas.md "Wrap joints": the strand drawn at R*omega):
# +9.1 % (63.68 / 58.36 kN, both near 1.2 s, 0.2 m bodies); +7.43 % at today's 0.196 m bodies
# with the drums' stick-slip law (lead, merge of session 11; node belt +0.44 %). That raw peak
# came at 4.73 s, the crest of a 10.2 Hz (v/l) ripple growing through the settle (a loop mode
# sits on v/l here): the drums' contact moment, which no body took back, swung the tail drum
# (session 12, docs/kubas.md "The contact's moment on the drum"). With the pulley taking it
# back: +4.71 % (61.25 / 58.50 kN, raw at 1.22 s in the ramp; no growth). Still above 3 %,
# hence the strict xfail then. Shorter wrap-joint fades read +2.29 % at 1.5 % of the bend (1 %:
# +2.54 %, 0.75 %: +3.46 %; docs/kubas.md "The fades' share"), but there the undamped wrap
# loop drifts by 3.4 % of its energy (rust/tests/rigid_wrap.rs holds 3 %). Session 13, two
# changes. (1) C² fades of 1 % (energy kept: 14.0 J of the test's 20.2 J) with the design
# landing kept out of the fades (design_rigid::landings): at 0.196 m +2.39 %, but one crest
# of a ~0.9 kN rms ripple: 0.19 / 0.195 / 0.198 / 0.2 m read +2.91 / +3.91 / +2.32 / +3.31 %.
# (2) The builders give the rigid belt bodies of at most 0.3 x the drum radius
# (beltrs.layout.belt_element_length; docs/kubas.md "The bodies' length on the drums"):
# 0.1185 m here. With the 4 % C¹ fades alone: +1.46 %, and at the lengths around it, off the
# pitches, 0.095-0.115 m +1.11 … +1.54 %, 0.124 m +1.75 %, +2.5 % at 0.13-0.14 m,
# +3.3 … +3.8 % at 0.148-0.168 m: the chord's a², not one crest's luck. Both together (lead,
# merge): 0.1148 / 0.1185 / 0.1244 / 0.1297 m +1.76 / +1.71 / +1.45 / +1.33 %. Cost: about
# 2.7x the 0.196 m bodies' element-steps. The node belt: +0.44 % (unchanged). With
# stick-force friction's arms (session 13, docs/kubas.md), at 0.196 m: +2.31 % (59.76 / 58.41
# kN, raw at 1.40 s); 0.195 m +3.88 % (main edfc824 +3.91 %).
@pytest.mark.parametrize("formulation", FORMULATIONS)
def test_raw_peak_within_3_percent_of_the_peak_below_2_hz(runs, formulation):
    t1 = runs[formulation][1]["tension"][:, 0]
    smooth = low_pass(t1, INTERVAL, 2.0)
    assert t1.max() / smooth.max() - 1 < 0.03


@pytest.mark.parametrize("formulation", FORMULATIONS)
def test_the_tail_drum_is_not_swung_at_the_body_rate(runs, formulation):
    """The tail drum (free, 64 kg m^2) turns with the belt: its surface speed above 2 Hz over
    the steady window. Measured: node belt 0.006 m/s; rigid bodies 0.0147 m/s since the
    drums take back the moment of the bodies' contact (session 12; 0.0124 m/s at the
    0.1185 m bodies of session 13, 0.0147 at 0.196 m), 0.0716 m/s before
    (swung at v/l = 10.2 Hz by the moment (l/2)(N_a - N_b) that acted on the belt alone,
    docs/kubas.md "The contact's moment on the drum"). 0.03 m/s: twice the rigid figure,
    under half the old one. Session 13 (main edfc824): node 0.0082, rigid 0.0130 m/s; with
    stick-force friction's arms 0.0134."""
    _, data = runs[formulation]
    t = data["time"]
    surface = data["pulley_speed"][:, 0] * R
    ripple = surface - low_pass(surface, INTERVAL, 2.0)
    assert ripple[t >= t[-1] - 2.5].std() < 0.03


def test_bad_formulation_input_is_refused_by_name():
    with pytest.raises(beltrs.SceneError, match="formulation = 'rigid'"):
        guo_wang_conveyor(length=LENGTH, formulation="rigid")
    # The rigid-body belt has its own design start (docs/design-start.md), its spans placed
    # in their sag as the node belt's (initial.sag, the builders' default); bad input named.
    scene = guo_wang_conveyor(length=LENGTH, formulation="rigid_body", start="rest")
    assert scene.initial is not None and scene.initial.sag
    assert scene.belt.pulley_contact == "wrap"  # the rigid belt's wrap joints (docs/kubas.md)
    assert loads_scene(dumps_scene(scene)).belt.pulley_contact == "wrap"
    with pytest.raises(beltrs.SceneError, match=r"initial\.sag"):
        beltrs.Simulation(replace(scene, initial=replace(scene.initial, sag="yes")))
    # The node belt's scene switched to rigid bodies by hand: its roll wrap is refused by name
    # (its drums' wrap contact means wrap joints for rigid bodies).
    node = guo_wang_conveyor(length=LENGTH, start="rest")
    with pytest.raises(beltrs.SceneError, match="idler_contact"):
        beltrs.Simulation(replace(node, belt=replace(node.belt, formulation="rigid_body")))
    # The builder: a known formulation; rigid bodies start from the design state too.
    from beltrs.conveyor import Conveyor

    with pytest.raises(beltrs.SceneError, match="formulation = 'rigid'"):
        Conveyor(formulation="rigid").validate()
    scene = Conveyor(formulation="rigid_body", capacity=400.0).scene()
    assert scene.belt.formulation == "rigid_body" and scene.initial is not None and scene.initial.sag
    assert not scene.recording.stabilise and scene.belt.pulley_contact == "wrap"
    assert scene.loads and scene.loads[0].mass_per_length > 0
    # From TOML: the builder's field, and a scene file's loads on a rigid-body belt.
    assert beltrs.conveyor.loads('[conveyor]\nformulation = "rigid_body"\n').formulation == "rigid_body"
    with pytest.raises(beltrs.SceneError, match="formulation = 'rigid'"):
        beltrs.conveyor.loads('[conveyor]\nformulation = "rigid"\n').scene()
    text = dumps_scene(guo_wang_conveyor(length=LENGTH, formulation="rigid_body"))
    back = loads_scene(text)
    assert back.belt.formulation == "rigid_body" and back.loads


def test_rigid_bodies_are_chosen_from_the_drum_and_longer_ones_warn():
    """The builders give the rigid-body belt bodies of at most 0.3 x the smallest drum radius,
    then off the idler pitches (``beltrs.layout.belt_element_length``, docs/kubas.md, "The
    bodies' length on the drums"): 0.1185 m on case G's 0.4 m drums; the node belt keeps
    0.196 m (guo_wang_conveyor) and 0.209 m (Conveyor). A longer rigid body length given
    explicitly is used as given and warns (AccuracyWarning) naming the field, the value,
    the rule and the raw peak's measured chordal excess, at the user's line; a length
    within the rule, or any node belt's, does not."""
    import math
    import warnings

    from beltrs.conveyor import Conveyor
    from beltrs.layout import RIGID_BODY_ANGLE, belt_element_length

    path = 2 * LENGTH + 2 * math.pi * R
    rigid = guo_wang_conveyor(length=LENGTH, formulation="rigid_body")
    assert path / rigid.belt.elements == pytest.approx(0.11852, rel=1e-3)
    assert path / rigid.belt.elements <= RIGID_BODY_ANGLE * R
    assert guo_wang_conveyor(length=LENGTH).belt.elements == math.ceil(path / 0.1959183673469388)
    assert Conveyor(formulation="rigid_body").chosen_element_length == pytest.approx(0.11852, rel=1e-4)
    assert Conveyor().chosen_element_length == pytest.approx(math.pi / 15, rel=1e-12)  # 30 deg on 0.4 m
    # the rule's cap applies before the pitches: 1.2 / 0.12 = 10 is a whole number of bodies
    assert belt_element_length(0.2, [1.2, 3.0], formulation="rigid_body", drum_radius=0.4) < 0.12
    assert belt_element_length(0.2, [1.2, 3.0], formulation="node_kelvin_voigt", drum_radius=0.4) > 0.19
    with pytest.raises(beltrs.SceneError, match=r"drum_radius = -0\.4"):
        belt_element_length(0.2, [1.2], formulation="rigid_body", drum_radius=-0.4)

    rule = r"l <= 0\.3 x the smallest drum radius \(0\.3 x 0\.4 m = 0\.12 m"
    with pytest.warns(beltrs.AccuracyWarning, match=r"element_length = 0\.196: .*" + rule + r".*\+4\.71 %") as w:
        guo_wang_conveyor(length=LENGTH, formulation="rigid_body", element_length=0.196)
    assert w[0].filename == __file__  # at the user's line
    with pytest.warns(beltrs.AccuracyWarning, match=r"elements = 600, so the body length = 0\.204.*" + rule):
        guo_wang_conveyor(length=LENGTH, formulation="rigid_body", elements=600)
    with pytest.warns(beltrs.AccuracyWarning, match=r"element_length = 0\.2: .*" + rule) as w:
        Conveyor(formulation="rigid_body", element_length=0.2).scene()
    assert w[0].filename == __file__
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        guo_wang_conveyor(length=LENGTH, formulation="rigid_body", element_length=0.12)  # the limit itself
        guo_wang_conveyor(length=LENGTH, formulation="rigid_body", elements=1100)
        guo_wang_conveyor(length=LENGTH, element_length=0.3)  # node belt: no rule
        Conveyor(element_length=0.3).scene()
        Conveyor(formulation="rigid_body", element_length=0.1).scene()


def test_bench_section_names_each_runs_contact(tmp_path):
    """benches/case_g.py --formulations: a run at the builder's contact (--pulley-contact
    builder) or with other elements is named so in the page's table; the old runs (no
    contact recorded) and the nodal pinning read as before."""
    import argparse
    import importlib.util
    import pathlib

    path = pathlib.Path(__file__).resolve().parents[1] / "benches" / "case_g.py"
    spec = importlib.util.spec_from_file_location("case_g_bench", path)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    run = dict(shape="harrison", ramp=30.0, prestart=0.0, formulation="node_kelvin_voigt", peak=86e3,
               peak_time=18.0, peak_filtered=85e3, peak_filtered_time=18.5, takeup_max=0.7, nodes=9733,
               dt=3.7e-5, stabilise_steps=1, steps=2, stabilise_wall=1.0, run_wall=1.0)
    old = bench.formulations_section([run], 972.0, 60.0, "test")
    assert "unless the belt column" not in old and "| node |" in old
    wrap = dict(run, pulley_contact="wrap", idler_contact="wrap")
    rigid = dict(run, formulation="rigid_body", pulley_contact="nodes", idler_contact="segment",
                 element_length=0.1)
    text = bench.formulations_section([run, wrap, rigid], 972.0, 60.0, "test")
    assert "unless the belt column" in text
    assert "| node (drums wrap, rolls wrap) |" in text
    # --element-length builder (None): the builder's rule, and the run records the length it
    # gave (the node belt's 0.196 m, moved off the idler pitches by at most a few %)
    assert bench.element_length_arg("builder") is None and bench.element_length_arg("0.1185") == 0.1185
    for bad in ("x", "0", "-1", "nan"):
        with pytest.raises(argparse.ArgumentTypeError, match="length"):
            bench.element_length_arg(bad)
    run = bench.start("harrison", 0.5, 0.5, LENGTH, 0.0, contact="builder", control="vfd",
                      loss=(0.1, 0.5), creep_ramp=0.5, element_length=None)
    assert run["element_length"] == pytest.approx(0.196, rel=0.03)
    assert (run["loss_factor"], run["loss_frequency"], run["creep_ramp"]) == (0.1, 0.5, 0.5)
    assert "| rigid body (0.1 m elements) |" in text
    # --loss-factor and --creep-ramp (session 12): a viscoelastic belt and a pre-start with a
    # creep ramp other than its default half are named too; the default creep ramp is not.
    zener = dict(wrap, loss_factor=0.1, loss_frequency=0.5, prestart=3.0, creep_ramp=3.0)
    plain = dict(wrap, loss_factor=0.0, loss_frequency=5.0, prestart=3.0, creep_ramp=1.5)
    text = bench.formulations_section([zener, plain], 972.0, 60.0, "test")
    assert "| node (drums wrap, rolls wrap; tan δ 0.1 at 0.5 Hz; creep ramp 3 s) |" in text
    assert "| node (drums wrap, rolls wrap) |" in text
    with pytest.raises(ValueError, match="contact must be"):
        bench.start("harrison", 1.0, 0.0, LENGTH, 0.0, contact="wrap")
    # an --out without a case-g.md of its own starts from the repository's page
    page = tmp_path / "case-g.md"
    bench.write_section(page, text)
    written = page.read_text(encoding="utf-8")
    assert written.startswith("# ") and written.count(bench.BEGIN) == 1 and "tan δ 0.1 at 0.5 Hz" in written

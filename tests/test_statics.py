"""beltrs.statics: DIN 22101 and CEMA tensions at every point of the belt, checked against
worked examples computed by hand (each step written out; docs/statics.md repeats them)."""

import math

import numpy as np
import pytest

import beltrs
from beltrs import din22101, statics
from beltrs.statics import CEMA, DIN22101, Point, Section


def din_example_loop():
    """Worked example 1: a 200 m inclined conveyor, head drive, tail gravity takeup."""
    return [
        Point("tail", takeup=20e3),
        Point("loading", resistance=50.0 * 2.0**2),  # F_bA = m'_L v^2, 50 kg/m at 2 m/s
        Section(200.0, lift=10.0, strand="carry", material=50.0, rotating_mass=15.0, name="carry"),
        Point("head", drive=1.0),
        Section(200.0, lift=-10.0, strand="return", rotating_mass=5.0, name="return"),
    ]


def test_din_worked_example():
    # Belt m'_G = 20 kg/m; f = 0.02; g = 9.81.
    # cos(delta) = sqrt(1 - (10/200)^2) = sqrt(0.9975) = 0.99874922
    # Carry: F_H = 0.02 * 9.81 * [15 + (20 + 50) * 0.99874922] * 200
    #            = 0.1962 * [15 + 69.912445] * 200 = 0.1962 * 84.912445 * 200 = 3331.964 N
    #        lift: 9.81 * (20 + 50) * 10 = 6867.000 N            -> dT_carry = 10198.964 N
    # Return: F_H = 0.1962 * [5 + 20 * 0.99874922] * 200 = 0.1962 * 24.974984 * 200 = 980.018 N
    #        lift: 9.81 * 20 * (-10) = -1962.000 N               -> dT_return = -981.982 N
    # Loading: 50 * 2^2 = 200 N.  F_U = 10198.964 - 981.982 + 200 = 9416.982 N
    # Walk from the takeup: tail 20000; after loading 20200; head in T1 = 20200 + 10198.964
    # = 30398.964 N; head out T2 = 30398.964 - 9416.982 = 20981.982 N; back at the tail
    # 20981.982 - 981.982 = 20000.000 N (the loop closes).
    p = statics.tensions(din_example_loop(), belt_mass=20.0)
    np.testing.assert_allclose(p.section_rise, [10198.964, -981.982], rtol=1e-6)
    assert p.effective == pytest.approx(9416.982, rel=1e-6)
    head = p.drive("head")
    assert head.tight == pytest.approx(30398.964, rel=1e-6)
    assert head.slack == pytest.approx(20981.982, rel=1e-6)
    assert p.at("return: end") == pytest.approx(20000.0, rel=1e-9)
    assert p.at("loading: out") == pytest.approx(20200.0, rel=1e-12)
    assert p.max == pytest.approx(30398.964, rel=1e-6) and p.min == pytest.approx(20000.0, rel=1e-9)
    # Along the belt, linear in each section: halfway up the carry strand.
    assert p.along(100.0) == pytest.approx(20200.0 + 10198.964 / 2, rel=1e-6)
    assert p.along(300.0) == pytest.approx(20981.982 - 981.982 / 2, rel=1e-6)
    assert p.length == 400.0 and p.iterations == 1


def test_din22101_module_uses_the_same_section_formula():
    # The straight conveyor of test_din22101 (100 m, f 0.02, belt 10, material 20, rolls 6/2,
    # 2 m/s, takeup pull 20 kN) as a loop gives din22101's tensions.
    r = din22101.resistances(carry_length=100, return_length=100, belt_mass=10, material_mass=20, speed=2,
                             carry_rotating_mass=6, return_rotating_mass=2)
    t = din22101.head_drive_tensions(r, takeup_pull=20e3)
    loop = [Point("tail", takeup=10e3), Point("loading", resistance=20 * 2.0**2),
            Section(100, material=20, rotating_mass=6), Point("head", drive=1.0),
            Section(100, strand="return", rotating_mass=2)]
    p = statics.tensions(loop, belt_mass=10)
    assert p.drive("head").tight == pytest.approx(t.tight, rel=1e-12)
    assert p.drive("head").slack == pytest.approx(t.slack, rel=1e-12)
    assert p.effective == pytest.approx(r.total, rel=1e-12)


def test_cema_worked_example():
    # 300 m level, W_b = 30 kg/m, W_m = 100 kg/m, carry idlers every 4 ft = 1.2192 m, C6 rolls
    # (A_i = 6.67 N), K_t = 1, C1 = 1, tail takeup 30 kN.
    # K_x = 0.00068 * 130 * 9.81 + 6.67 / 1.2192 = 0.867204 + 5.470801 = 6.338005 N/m
    # Carry dT = 300 * (K_x + K_y * 30 * 9.81) + 100 * 9.81 * 300 * K_y
    #          = 1901.401 + K_y * (88290 + 294300) = 1901.401 + 382590 * K_y
    # Return dT = 300 * 0.015 * 30 * 9.81 = 1324.350 N
    # K_y (eq. 2.3): W = 130 kg/m = 130 / 1.48816 = 87.3560 lb/ft. Average carry tension
    # T = 30000 + dT/2 lands between the 7000 and 8000 lbf rows (31137.55, 35585.77 N), in
    # the 4 ft column: A = 0.6420 - 0.0612 u, B = 1.404 - 0.067 u, u = (T - 31137.55)/4448.22
    #   K_y = 87.3560e-4 * A + 1e-2 * B = 0.0196483 - 0.00120462 u
    #   T = 30000 + 950.700 + 191295 K_y = 34709.32 - 230.44 u
    #   and T = 31137.55 + 4448.22 u  ->  u = 3571.77 / 4678.66 = 0.76342, T = 34533.4 N
    #   K_y = 0.0196483 - 0.00120462 * 0.76342 = 0.018729
    # Carry dT = 1901.401 + 382590 * 0.018729 = 9067.03 N; T1 = 39067.03 N
    # F_U = 9067.03 + 1324.35 = 10391.38 N; T2 = T1 - F_U = 28675.65 N = 30000 - 1324.35.
    # Tolerance 5e-5: K_y carried to 5 digits by hand moves dT by up to 382590 * 5e-7 = 0.2 N.
    loop = [Point("tail", takeup=30e3), Section(300.0, material=100.0, idler_pitch=1.2192, name="carry"),
            Point("head", drive=1.0), Section(300.0, strand="return", name="return")]
    p = statics.tensions(loop, belt_mass=30.0, method=CEMA(idler_resistance="C6"))
    assert statics.cema_kx(30, 100, 6.67, 1.2192) == pytest.approx(6.338005, rel=1e-6)
    assert p.ky[0] == pytest.approx(0.018729, rel=2e-4)
    assert p.section_rise[1] == pytest.approx(1324.35, rel=1e-9)
    assert p.drive("head").tight == pytest.approx(39067.03, rel=5e-5)
    assert p.drive("head").slack == pytest.approx(28675.65, rel=1e-9)
    assert p.effective == pytest.approx(10391.38, rel=5e-5)
    assert 2 <= p.iterations < 50


def test_cema_loop_sums_to_the_effective_tension_formula():
    # Eq. 2.1 (no pulleys, accessories or material acceleration) against the loop's F_U for
    # the same straight conveyor lifting H = 12 m, at a fixed K_y (the carry strand's one
    # value, as eq. 2.1 has): the belt's own lift cancels between the strands.
    L, H, wb, wm, ky, kt, si = 400.0, 12.0, 25.0, 60.0, 0.022, 1.2, 1.0
    method = CEMA(kt=kt, ky=ky, idler_resistance=8.01)
    loop = [Point("tail", takeup=25e3), Section(L, H, material=wm, idler_pitch=si), Point("head", drive=1.0),
            Section(L, -H, strand="return")]
    p = statics.tensions(loop, belt_mass=wb, method=method)
    g = 9.81
    kx = 0.00068 * (wb + wm) * g + 8.01 / si
    te = L * kt * (kx + ky * wb * g + 0.015 * wb * g) + wm * g * (L * ky + H)  # eq. 2.1
    assert p.effective == pytest.approx(te, rel=1e-12)


def test_cema_ky_table():
    # At a grid point: 5000 lbf, 3.5 ft -> A = 0.8014, B = 1.381; W = 100 lb/ft.
    w = 100 * statics.LB_PER_FT
    ky = statics.cema_ky(w, 0.0, 5000 * statics.LBF, 3.5 * statics.FT)
    assert ky == pytest.approx(100 * 0.8014e-4 + 1.381e-2, rel=1e-12)
    # Halfway between rows and columns: the mean of four corners (bilinear).
    t = 5500 * statics.LBF
    s = 3.75 * statics.FT
    a = (0.8014 + 0.7217 + 0.7934 + 0.7139) / 4
    b = (1.381 + 1.318 + 1.559 + 1.472) / 4
    assert statics.cema_ky(w, 0.0, t, s) == pytest.approx(100 * a * 1e-4 + b * 1e-2, rel=1e-12)
    # Below the first row: the first row; above the last: 0.016.
    assert statics.cema_ky(w, 0, 1000.0, 0.9144) == pytest.approx(100 * 1.4447e-4 + 1.565e-2, rel=1e-12)
    assert statics.cema_ky(w, 0, 80e3, 0.9144) == 0.016
    with pytest.raises(beltrs.SceneError, match=r"idler_spacing = 2\.0: CEMA's K_y table covers"):
        statics.cema_ky(w, 0, 20e3, 2.0)


def test_din_secondary_coefficient():
    assert statics.din_secondary_coefficient(80) == 1.92
    assert statics.din_secondary_coefficient(250) == pytest.approx((1.45 + 1.31) / 2, rel=1e-12)
    assert statics.din_secondary_coefficient(5000) == 1.05
    with pytest.raises(beltrs.SceneError, match=r"length = 50: must be >= 80"):
        statics.din_secondary_coefficient(50)


def test_two_drives_share_and_the_loop_closes():
    # Head drive 2/3, tail drive 1/3, takeup after the head (slack side): each drive takes
    # its share of F_U out; walking round returns to the takeup tension.
    loop = [Point("takeup", takeup=15e3), Section(100, strand="return", rotating_mass=4),
            Point("tail", drive=1 / 3), Section(500, 5, material=40, rotating_mass=12),
            Point("head", drive=2 / 3), Section(400, -5, strand="return", rotating_mass=4)]
    p = statics.tensions(loop, belt_mass=18)
    assert p.drive("head").force == pytest.approx(2 / 3 * p.effective, rel=1e-12)
    assert p.drive("tail").force == pytest.approx(1 / 3 * p.effective, rel=1e-12)
    assert p.tension[-1] == pytest.approx(15e3, rel=1e-12)
    assert p.drive("head").tight == p.max


@pytest.mark.parametrize(
    "loop,method,match",
    [
        ([Point("t", takeup=1e4), Section(-5.0), Point("h", drive=1)], None, r"loop\[1\]\.length = -5\.0: must be > 0"),
        ([Point("t", takeup=1e4), Section(5.0, lift=6.0), Point("h", drive=1)], None, r"loop\[1\]\.lift = 6\.0"),
        ([Point("t", takeup=1e4), Section(5.0, strand="top"), Point("h", drive=1)], None, r"strand = 'top'"),
        ([Point("t"), Section(5.0), Point("h", drive=1)], None, r"exactly one point with a takeup"),
        ([Point("t", takeup=1e4), Section(5.0), Point("h", drive=0.5)], None, r"must add up to 1"),
        ([Point("t", takeup=1e4), Section(5.0), Point("h")], None, r"needs a drive"),
        ([Point("t", takeup=-1.0), Section(5.0), Point("h", drive=1)], None, r"loop\[0\]\.takeup = -1\.0: must be > 0"),
        ([Point("t", takeup=1e4), Section(5.0, material=math.nan), Point("h", drive=1)], None,
         r"material = nan: must be finite"),
        ([Point("t", takeup=1e4), "belt", Point("h", drive=1)], None, r"loop\[1\] = 'belt': must be"),
        ([Point("t", takeup=1e4), Section(5.0), Point("h", drive=1)], CEMA(kt=0.8), r"CEMA\.kt = 0\.8: must be >= 1"),
        ([Point("t", takeup=1e4), Section(5.0), Point("h", drive=1)], CEMA(idler_resistance="Z9"),
         r"idler_resistance = 'Z9': unknown CEMA idler class"),
        ([Point("t", takeup=1e4), Section(5.0), Point("h", drive=1)], CEMA(), r"idler_pitch = None: CEMA needs"),
        ([Point("t", takeup=1e4), Section(5.0), Point("h", drive=1)], DIN22101(f=-0.1), r"DIN22101\.f = -0\.1"),
        ([Point("t", takeup=1e4), Section(5.0), Point("h", drive=1)], "din", r"method = 'din'"),
    ],
)
def test_bad_input_names_field_value_and_rule(loop, method, match):
    with pytest.raises(beltrs.SceneError, match=match):
        statics.tensions(loop, belt_mass=10.0, method=method)


def test_bad_belt_mass_and_lookup():
    with pytest.raises(beltrs.SceneError, match=r"belt_mass = 'heavy': expected a number"):
        statics.tensions(din_example_loop(), belt_mass="heavy")
    p = statics.tensions(din_example_loop(), belt_mass=20.0)
    with pytest.raises(beltrs.SceneError, match=r"drive = 'tail': no drive of that name"):
        p.drive("tail")
    with pytest.raises(beltrs.SceneError, match=r"label = 'nowhere': no such place"):
        p.at("nowhere")

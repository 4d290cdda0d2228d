"""beltrs.din22101: the static reference for case G, checked against hand arithmetic."""

import math

import pytest

import beltrs
from beltrs import din22101


def test_resistances_match_hand_arithmetic():
    # 100 m horizontal, f = 0.02, belt 10 kg/m, material 20 kg/m, rolls 6 + 2 kg/m, 2 m/s:
    # F_H,c = 0.02*9.81*100*(6+10+20) = 706.32 N; F_H,r = 0.02*9.81*100*(2+10) = 235.44 N;
    # F_bA = 20*2^2 = 80 N; no lift.
    r = din22101.resistances(carry_length=100, return_length=100, belt_mass=10, material_mass=20, speed=2,
                             carry_rotating_mass=6, return_rotating_mass=2)
    assert r.main_carry == pytest.approx(706.32, rel=1e-12)
    assert r.main_return == pytest.approx(235.44, rel=1e-12)
    assert r.loading == pytest.approx(80.0, rel=1e-12)
    assert r.slope == 0.0
    assert r.total == pytest.approx(706.32 + 235.44 + 80.0, rel=1e-12)


def test_slope_and_partial_loading():
    # 5 degrees, material on 60 of 100 m, lifted 5 m.
    d = math.radians(5)
    r = din22101.resistances(carry_length=100, return_length=100, belt_mass=10, material_mass=20, speed=1,
                             slope=d, loaded_length=60, lift=5.0)
    assert r.main_carry == pytest.approx(0.02 * 9.81 * (100 * 10 + 60 * 20) * math.cos(d), rel=1e-12)
    assert r.slope == pytest.approx(20 * 9.81 * 5.0, rel=1e-12)


def test_head_drive_tensions():
    r = din22101.resistances(carry_length=100, return_length=100, belt_mass=10, material_mass=20, speed=2)
    t = din22101.head_drive_tensions(r, takeup_pull=20e3)
    assert t.tail == 10e3
    assert t.slack == pytest.approx(10e3 - r.main_return, rel=1e-12)
    assert t.tight - t.slack == pytest.approx(r.total, rel=1e-12)
    assert din22101.rigid_start_force(1000.0, 0.5, running=100.0) == 600.0


@pytest.mark.parametrize("field,value", [("belt_mass", -1.0), ("speed", math.nan), ("f", math.inf)])
def test_bad_input_names_field_and_value(field, value):
    kw = dict(carry_length=100, return_length=100, belt_mass=10, material_mass=20, speed=2)
    kw[field] = value
    with pytest.raises(beltrs.SceneError, match=rf"{field} = {value!r}"):
        din22101.resistances(**kw)

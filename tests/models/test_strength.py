"""Pin pressure and tube fatigue (``pumplink.models.strength``), against numbers worked by hand."""

import math

import numpy as np
import pytest

from pumplink.models import strength as S


def test_bearing_pressure_is_force_over_projected_area():
    # 600 N on a 12 mm pin through both 2.6 mm walls of a tube: 600 / (12 * 5.2) N/mm^2
    assert S.bearing_pressure(-600.0, 0.012, 2 * 0.0026) == pytest.approx(600 / (12 * 5.2) * 1e6, rel=1e-14)


def test_tube_section_by_hand():
    # 26.9 x 2.6 mm: d = 21.7 mm; A = pi/4 (26.9^2 - 21.7^2) mm^2, Z = pi (26.9^4 - 21.7^4) / (32 * 26.9) mm^3
    sec = S.tube_section(0.0269, 0.0026)
    assert sec.area == pytest.approx(math.pi / 4 * (26.9**2 - 21.7**2) * 1e-6, rel=1e-12)
    assert sec.modulus == pytest.approx(math.pi * (26.9**4 - 21.7**4) / (32 * 26.9) * 1e-9, rel=1e-12)
    solid = S.tube_section(0.0127, 0.0127 / 2)  # a 1/2" bar: Z = pi D^3 / 32
    assert solid.modulus == pytest.approx(math.pi * 0.0127**3 / 32, rel=1e-12)


def test_endurance_limit_by_hand():
    # S235 (360 MPa), hot-rolled: ka = 57.7 * 360^-0.718; de = 0.37 * 26.9 mm, kb = 1.24 de^-0.107; ke = 0.814
    ka = 57.7 * 360.0**-0.718
    kb = 1.24 * (0.37 * 26.9) ** -0.107
    want = ka * kb * 0.814 * 180.0e6
    assert S.endurance_limit(360e6, 0.0269) == pytest.approx(want, rel=1e-12)
    assert S.endurance_limit(360e6, 0.0269, notch_factor=2.5) == pytest.approx(want / 2.5, rel=1e-12)
    assert 110e6 < want < 130e6  # about a third of the tensile strength, as the textbooks say


def test_goodman_on_fully_reversed_and_pulsating_bending():
    sec = S.tube_section(0.0269, 0.0026)
    z = float(sec.modulus)
    t = np.linspace(0, 2 * np.pi, 1001)
    se, su = 100e6, 360e6
    # fully reversed +-50 N m, no axial force: sigma_a = 50/Z, sigma_m = 0, n = Se / sigma_a
    rev = S.fatigue(50 * np.sin(t), 0 * t, sec, se, su)
    assert rev.amplitude == pytest.approx(50 / z, rel=1e-6)
    assert rev.safety == pytest.approx(se / (50 / z), rel=1e-6)
    # pulsating 0..40 N m: on the tension fibre sigma_a = sigma_m = 20/Z, 1/n = sigma_a/Se + sigma_m/Su
    pul = S.fatigue(20 + 20 * np.cos(t), 0 * t, sec, se, su)
    assert pul.safety == pytest.approx(1 / ((20 / z) / se + (20 / z) / su), rel=1e-6)
    assert pul.largest == pytest.approx(40 / z, rel=1e-9)
    # an axial tension adds to the mean of the fibre it loads: the worse fibre decides
    ax = S.fatigue(20 + 20 * np.cos(t), 1000 + 0 * t, sec, se, su)
    s_a, s_m = 20 / z, 20 / z + 1000 / float(sec.area)
    assert ax.safety == pytest.approx(1 / (s_a / se + s_m / su), rel=1e-6)

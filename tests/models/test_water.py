"""Water delivered by a design (``pumplink.models.water``, docs/water.md).

Expected values come from hand arithmetic written out in each test (checked to 30 digits with
mpmath when the test was written), from a second route that shares no formula with the code (the
volume swept per wheel turn times turns per minute), from the rope and piston load forces of
``pumplink.inputs.pump.rope_force`` and ``pumplink.models.piston.load_force`` (which the water module does
not use), and from the field's published discharges (docs/water.md §6).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from mpmath import mp, mpf

from pumplink.constants import (
    DEFAULT_EFFICIENCY,
    DEFAULT_VOLUMETRIC_EFFICIENCY,
    HOUR_POWER_W,
    SUSTAINED_POWER_W,
)
from pumplink.models import water
from pumplink.models.load import piston_load_force, rope_force

RPM = 2.0 * math.pi / 60.0  # rad/s per rpm
L_PER_MIN = 60_000.0  # (l/min) per (m^3/s)


def test_rope_pump_flow_by_hand():
    """23 mm rising main, 0.25 m wheel radius, 60 rpm, eta_v = 0.87.

    pipe area      pi 0.023^2 / 4          = 4.15476e-4 m^2
    rope per turn  2 pi 0.25               = 1.570796 m
    swept per turn 4.15476e-4 x 1.570796   = 6.52628e-4 m^3 = 0.652628 l
    swept per min  0.652628 l x 60         = 39.1577 l/min
    delivered      39.1577 x 0.87          = 34.0672 l/min
    """
    q = water.rope_pump_flow(0.023, 60 * RPM, 0.25, 0.87)
    assert float(q) * L_PER_MIN == pytest.approx(34.0672, rel=2e-6)  # hand value, 6 digits


def test_rope_pump_flow_is_the_volume_swept_per_turn_times_turns():
    """Second route, in 30-digit arithmetic: the pistons sweep the pipe area over the wheel's
    circumference each turn; the flow is that volume x turns per second x eta_v."""
    mp.dps = 30
    for d, r, rpm, eta in [(0.023, 0.25, 60, 0.87), (0.016, 0.20, 40, 0.8), (0.032, 0.30, 25, 0.95)]:
        per_turn = mp.pi * mpf(d) ** 2 / 4 * 2 * mp.pi * mpf(r)
        expected = per_turn * mpf(rpm) / 60 * mpf(eta)
        got = water.rope_pump_flow(d, rpm * RPM, r, eta)
        assert float(got) == pytest.approx(float(expected), rel=1e-14)


def test_rope_pump_flow_defaults_to_the_documented_volumetric_efficiency():
    assert DEFAULT_VOLUMETRIC_EFFICIENCY == 0.87
    assert float(water.rope_pump_flow(0.023, 60 * RPM, 0.25)) == float(
        water.rope_pump_flow(0.023, 60 * RPM, 0.25, 0.87)
    )


def test_piston_pump_flow_by_hand():
    """The piston-pump example of docs/piston-pump.md: 50 mm bore, 50 mm crank without offset
    (stroke 2 x 50 mm = 0.100 m), 40 rpm, single-acting, eta_v = 0.9.

    bore area     pi 0.050^2 / 4       = 1.963495e-3 m^2
    per stroke    1.963495e-3 x 0.100  = 1.963495e-4 m^3 = 0.1963495 l
    per minute    0.1963495 l x 40     = 7.853982 l/min   (one working stroke per turn)
    delivered     7.853982 x 0.9       = 7.068583 l/min
    """
    q = water.piston_pump_flow(0.050, 0.100, 40 * RPM, 0.9)
    assert float(q) * L_PER_MIN == pytest.approx(7.068583, rel=1e-7)


def test_water_power_by_hand():
    """34.0672 l/min = 5.67786e-4 m^3/s lifted 10 m: 1000 x 9.81 x 10 x 5.67786e-4 = 55.6998 W."""
    q = 34.0672 / L_PER_MIN
    assert float(water.water_power(q, 10.0)) == pytest.approx(55.6998, rel=2e-6)


def test_overall_efficiency_is_force_times_volumetric_efficiency_by_hand():
    """The village well (10 m, 23 mm, wheel radius 0.25 m, 60 rpm) at the defaults.

    rope force   1000 x 9.81 x 10 x 4.15476e-4 / 0.75 = 54.3442 N   (spec.rope_force)
    operator     54.3442 N x 1.570796 m/s              = 85.3637 W
    water        55.6998 W                              (test_water_power_by_hand)
    efficiency   55.6998 / 85.3637                      = 0.6525 = 0.87 x 0.75
    """
    omega, r = 60 * RPM, 0.25
    fw = rope_force(head=10.0, pipe_diameter=0.023)
    assert fw == pytest.approx(54.3442, rel=2e-6)
    p_op = fw * r * omega
    assert p_op == pytest.approx(85.3637, rel=2e-6)
    p_w = water.water_power(water.rope_pump_flow(0.023, omega, r), 10.0)
    eta = water.overall_efficiency(p_w, p_op)
    assert float(eta) == pytest.approx(0.6525, rel=1e-12)
    assert float(eta) == pytest.approx(DEFAULT_EFFICIENCY * DEFAULT_VOLUMETRIC_EFFICIENCY, rel=1e-12)


def test_power_limited_flow_and_share_by_hand():
    """Q* for the men's sustained 75 W at 10 m, eta = 0.75 x 0.87 = 0.6525:

    Q*     0.6525 x 75 / (1000 x 9.81 x 10) = 4.98853e-4 m^3/s = 29.9312 l/min
    share  34.0672 / 29.9312                 = 1.13818  (= 85.3637 W / 75 W)
    """
    q_star = water.power_limited_flow(75.0, 10.0)
    assert float(q_star) * L_PER_MIN == pytest.approx(29.9312, rel=2e-6)
    q = water.rope_pump_flow(0.023, 60 * RPM, 0.25)
    share = water.flow_share(q, q_star)
    assert float(share) == pytest.approx(1.13818, rel=5e-6)
    assert float(share) == pytest.approx(85.3637 / 75.0, rel=2e-6)


def test_lossless_bound_is_the_pump_limit_over_its_efficiency():
    """With force and volumetric efficiency 1, Q* is the thermodynamic bound P / (rho g H):
    75 W at 10 m is 75 / 98100 = 7.64526e-4 m^3/s = 45.8716 l/min, 1/0.6525 times the pump's Q*."""
    ideal = water.power_limited_flow(75.0, 10.0, 1.0, 1.0)
    assert float(ideal) * L_PER_MIN == pytest.approx(45.8716, rel=2e-6)
    assert float(ideal / water.power_limited_flow(75.0, 10.0)) == pytest.approx(1 / 0.6525, rel=1e-12)


def test_people_served_by_hand():
    """34.0672 l/min for 8 h a day = 34.0672 x 480 = 16352.3 l; at 20 l/person/day: 817.61
    people; at 50 l and 6 h: 34.0672 x 360 / 50 = 245.28 people."""
    q = 34.0672 / L_PER_MIN
    assert float(water.people_served(q)) == pytest.approx(817.61, rel=1e-5)
    assert float(water.people_served(q, daily_hours=6.0, litres_per_person_day=50.0)) == pytest.approx(
        245.28, rel=2e-5
    )


# (head [m], published discharge [l/min], source) -- docs/water.md §6
FIELD = [
    (10.0, 35.0, "Akvopedia, 'Rope pump': 35 l/min from 10 m"),
    (20.0, 17.5, "Akvopedia, 'Rope pump': half of that from 20 m"),
    (10.0, 40.0, "Practical Action, 'Hand pumps for water lifting': 40 l/min up to 10 m"),
    (35.0, 10.0, "Practical Action, 'Hand pumps for water lifting': 10 l/min at 35 m"),
]


@pytest.mark.parametrize("head, litres_per_minute, source", FIELD, ids=[f[2] for f in FIELD])
def test_field_discharges_need_more_than_sustained_and_less_than_hour_power(head, litres_per_minute, source):
    """At the default efficiencies (overall 0.6525), each published discharge of a hand rope pump
    needs an operator power between the sustained 75 W and the hour power 150 W (docs/water.md §6):
    35 l/min at 10 m is 57.2 W of water, 87.7 W at the handle.  Too optimistic efficiencies (say
    both 1) would put the field below 75 W; too pessimistic ones above 150 W."""
    q = litres_per_minute / L_PER_MIN
    p_op = float(water.water_power(q, head)) / (DEFAULT_EFFICIENCY * DEFAULT_VOLUMETRIC_EFFICIENCY)
    assert SUSTAINED_POWER_W < p_op < HOUR_POWER_W, source


@settings(max_examples=300, deadline=None)  # pure arithmetic on scalars: 300 draws cost ~0.1 s
@given(
    d=st.floats(0.008, 0.06),
    head=st.floats(0.5, 80.0),
    radius=st.floats(0.05, 0.6),
    omega=st.floats(0.2, 12.0),
    eta_f=st.floats(0.2, 1.0),
    eta_v=st.floats(0.2, 1.0),
    p_s=st.floats(10.0, 200.0),
)
def test_rope_share_is_operator_power_over_sustained_power(d, head, radius, omega, eta_f, eta_v, p_s):
    """With the design's own efficiencies in Q*, Q/Q* = P_operator / P_sustained exactly, the
    operator power taken from the rope force of spec.rope_force (docs/water.md §4); hence the
    share is at most 1 whenever the operator works at or below the sustained power."""
    p_op = rope_force(head=head, pipe_diameter=d, efficiency=eta_f) * radius * omega
    q = water.rope_pump_flow(d, omega, radius, eta_v)
    share = float(water.flow_share(q, water.power_limited_flow(p_s, head, eta_f, eta_v)))
    assert share == pytest.approx(p_op / p_s, rel=1e-12)
    if p_op <= p_s:
        assert share <= 1.0 + 1e-12


@settings(max_examples=200, deadline=None)  # pure arithmetic on scalars: cheap
@given(
    bore=st.floats(0.02, 0.1),
    stroke=st.floats(0.02, 0.4),
    head=st.floats(0.5, 80.0),
    omega=st.floats(0.2, 12.0),
    eta_f=st.floats(0.2, 1.0),
    eta_v=st.floats(0.2, 1.0),
    p_s=st.floats(10.0, 200.0),
)
def test_piston_share_is_operator_power_over_sustained_power(bore, stroke, head, omega, eta_f, eta_v, p_s):
    """The same for the piston pump, its mean operator power F_load x stroke x w / (2 pi) from the
    load force of models.load.piston_load_force (Eq. P.1, P.3 of docs/piston-pump.md)."""
    p_op = float(piston_load_force(bore, head, eta_f)) * stroke * omega / (2 * math.pi)
    q = water.piston_pump_flow(bore, stroke, omega, eta_v)
    share = float(water.flow_share(q, water.power_limited_flow(p_s, head, eta_f, eta_v)))
    assert share == pytest.approx(p_op / p_s, rel=1e-12)
    if p_op <= p_s:
        assert share <= 1.0 + 1e-12


def test_functions_broadcast_over_designs_like_a_loop_of_scalars():
    d = np.array([0.016, 0.023, 0.032])[:, None]
    omega = np.array([2.0, 4.0, 6.0, 8.0])[None, :]
    grid = water.rope_pump_flow(d, omega, 0.25)
    assert grid.shape == (3, 4)
    for i in range(3):
        for j in range(4):
            assert grid[i, j] == float(water.rope_pump_flow(float(d[i, 0]), float(omega[0, j]), 0.25))
    heads = np.array([5.0, 10.0, 20.0, 35.0])
    q_star = water.power_limited_flow(75.0, heads)
    assert q_star.shape == (4,)
    assert q_star * heads == pytest.approx(np.full(4, float(q_star[0] * heads[0])), rel=1e-14)


def test_invalid_inputs_give_nan_and_the_edges_are_explicit():
    assert math.isnan(float(water.rope_pump_flow(-0.02, 6.0, 0.25)))
    assert math.isnan(float(water.piston_pump_flow(0.05, -0.1, 4.0)))
    assert math.isnan(float(water.water_power(1e-3, -1.0)))
    assert math.isnan(float(water.overall_efficiency(50.0, 0.0)))  # no work, no efficiency
    assert math.isnan(float(water.power_limited_flow(75.0, -5.0)))
    assert math.isinf(float(water.power_limited_flow(75.0, 0.0)))  # no head: no power limit
    assert float(water.flow_share(1e-3, np.inf)) == 0.0
    assert math.isnan(float(water.flow_share(1e-3, 0.0)))
    assert math.isnan(float(water.people_served(1e-3, litres_per_person_day=0.0)))

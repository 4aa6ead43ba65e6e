"""Operator profiles (``pumplink.profiles``, docs/operators.md): every value has a source, lies in
the range its source gives, and the derived ones follow from their stated arithmetic.

The expected numbers are the published figures themselves (HSE, ADA/ABA, Practical Action, CDC
growth charts, Pheasant's stature table, the MTDC accessible-handpump tech tip) written out here,
and the derivations of docs/operators.md redone from them.
"""

import ast
import dataclasses
import math
from pathlib import Path

import pytest

import pumplink.profiles as profiles_module
from pumplink import constants
from pumplink.profiles import DEFAULT_PROFILE, FIELDS, PROFILES, Source

G = 9.81
LBF = 4.4482216152605  # N per pound-force (exact definition)
INCH = 0.0254  # m

# Published figures (docs/operators.md, each read as stated there)
HSE_KEEP_MOVING_KG = {"men": 10.0, "women": 7.0}  # HSE push/pull guideline figures
HSE_KEEP_MOVING_N = {"men": 100.0, "women": 70.0}  # "about 100 / 70 Newtons"
PA_HUMAN_POWER_W = (60.0, 75.0)  # Practical Action: 0.06-0.075 kW
HOUR_POWER_RANGE_W = (50.0, 150.0)  # 50-150 W for an hour
STATURE_M = {"men": (1.625, 1.855), "women": (1.505, 1.710)}  # Pheasant, British 19-65, 5th/95th
CHILD_STATURE_M = (1.275, 1.770)  # CDC 2000: girls 10 y 5th percentile, boys 14 y 95th
CDC_MASS_KG = {"boys_10": 32.1, "girls_20": 58.2}  # CDC 2000 weight-for-age medians
ADULT_MASS_KG = 60.0  # pumplink.constants.ARM_BODY_MASS_KG, basis of the men's 4 m/s
SHOULDER, WRIST = 0.818, 0.485  # Drillis-Contini proportions of stature


def floor_to(x, step):
    return math.floor(x / step + 1e-9) * step


def test_every_field_of_every_profile_has_a_source_with_a_basis():
    for p in (*PROFILES.values(), DEFAULT_PROFILE):
        assert set(p.sources) == set(FIELDS), p.name
        for name in FIELDS:
            s = p.sources[name]
            assert isinstance(s, Source)
            assert s.basis in ("source", "secondary", "derived"), (p.name, name)
            assert len(s.text) > 20, (p.name, name)
        assert {f.name for f in dataclasses.fields(p)} == {"name", "sources", *FIELDS}


def test_profiles_are_the_four_the_docs_name():
    assert list(PROFILES) == ["men", "women", "children", "accessible"]
    for name, p in PROFILES.items():
        assert p.name == name


@pytest.mark.parametrize("name", ["men", "women"])
def test_force_limits_are_the_hse_guideline_figures(name):
    p = PROFILES[name]
    assert p.force_limit == HSE_KEEP_MOVING_N[name]
    assert p.force_limit == pytest.approx(HSE_KEEP_MOVING_KG[name] * G, rel=0.03)  # "about"
    assert p.sources["force_limit"].basis == "source"


def test_accessible_force_is_the_ada_five_pounds():
    p = PROFILES["accessible"]
    assert p.force_limit <= 5 * LBF
    assert p.force_limit == pytest.approx(5 * LBF, abs=0.05)


def test_children_force_is_the_womens_scaled_by_body_mass_rounded_down():
    scaled = HSE_KEEP_MOVING_N["women"] * CDC_MASS_KG["boys_10"] / CDC_MASS_KG["girls_20"]  # 38.6 N
    assert PROFILES["children"].force_limit == math.floor(scaled)
    assert PROFILES["children"].sources["force_limit"].basis == "derived"


def test_sustained_powers_lie_in_the_published_human_range_or_follow_from_it():
    lo, hi = PA_HUMAN_POWER_W
    assert PROFILES["men"].sustained_power == hi
    assert PROFILES["women"].sustained_power == lo
    assert PROFILES["women"].sustained_power == pytest.approx(hi / 1.2, rel=0.05)  # men ~20 % more
    ratio = CDC_MASS_KG["boys_10"] / CDC_MASS_KG["girls_20"]
    assert PROFILES["children"].sustained_power == round(lo * ratio)
    acc = PROFILES["accessible"]
    assert acc.sustained_power >= acc.force_limit * acc.grip_speed_warn  # the force decides


def test_hour_powers_follow_from_the_published_range():
    assert PROFILES["men"].hour_power == HOUR_POWER_RANGE_W[1]
    assert PROFILES["women"].hour_power == pytest.approx(HOUR_POWER_RANGE_W[1] / 1.2)
    ratio = CDC_MASS_KG["boys_10"] / CDC_MASS_KG["girls_20"]
    assert PROFILES["children"].hour_power == round(PROFILES["women"].hour_power * ratio)
    for p in PROFILES.values():
        assert p.sustained_power < p.hour_power <= HOUR_POWER_RANGE_W[1], p.name


@pytest.mark.parametrize("name", ["men", "women"])
def test_adult_grip_band_runs_from_the_tall_users_wrist_to_the_short_users_shoulder(name):
    short, tall = STATURE_M[name]
    lo, hi = PROFILES[name].grip_height_range
    assert lo == pytest.approx(WRIST * tall, abs=0.005)
    assert hi == pytest.approx(SHOULDER * short, abs=0.005)


def test_children_grip_band_uses_the_10_to_14_year_statures():
    short, tall = CHILD_STATURE_M
    lo, hi = PROFILES["children"].grip_height_range
    assert lo == pytest.approx(WRIST * tall, abs=0.005)
    assert hi == pytest.approx(SHOULDER * short, abs=0.005)


def test_accessible_grip_band_is_28_to_40_inches_inside_the_aba_reach_range():
    lo, hi = PROFILES["accessible"].grip_height_range
    assert lo == pytest.approx(28 * INCH, abs=0.005)
    assert hi == pytest.approx(40 * INCH, abs=0.005)
    assert 15 * INCH <= lo < hi <= 48 * INCH


def test_grip_bands_are_ordered_and_on_the_ground():
    for p in (*PROFILES.values(), DEFAULT_PROFILE):
        lo, hi = p.grip_height_range
        assert 0.0 < lo < hi < 2.0, p.name


@pytest.mark.parametrize(
    "name, mass",
    [("women", CDC_MASS_KG["girls_20"]), ("children", CDC_MASS_KG["boys_10"]), ("accessible", ADULT_MASS_KG)],
)
def test_grip_speeds_scale_as_the_root_of_force_over_arm_mass(name, mass):
    """The arms' inertia force 2 m_arm v^2 / stroke reaches the force limit at v_fail, so v scales
    as sqrt(F / m_arm), m_arm proportional to body mass; the men's 2.5 / 4.0 m/s at 100 N and
    60 kg are the reference; rounded down to 0.1 m/s (docs/operators.md §5)."""
    p = PROFILES[name]
    factor = math.sqrt((p.force_limit / mass) / (100.0 / ADULT_MASS_KG))
    assert p.grip_speed_warn == pytest.approx(floor_to(2.5 * factor, 0.1))
    assert p.grip_speed_fail == pytest.approx(floor_to(4.0 * factor, 0.1))


def test_warn_speed_is_below_fail_speed():
    for p in (*PROFILES.values(), DEFAULT_PROFILE):
        assert 0.0 < p.grip_speed_warn < p.grip_speed_fail, p.name


def test_limits_fall_from_men_to_accessible():
    order = [PROFILES[n] for n in ("men", "women", "children", "accessible")]
    for a, b in zip(order, order[1:]):
        assert a.force_limit > b.force_limit
        assert a.sustained_power > b.sustained_power
        assert a.grip_speed_fail >= b.grip_speed_fail


def test_default_profile_is_todays_constants():
    d = DEFAULT_PROFILE
    assert d.force_limit == constants.FORCE_LIMIT_N
    assert d.sustained_power == constants.SUSTAINED_POWER_W
    assert d.hour_power == constants.HOUR_POWER_W
    assert d.grip_height_range == tuple(constants.GRIP_HEIGHT_RANGE_M)
    assert d.grip_speed_warn == constants.GRIP_SPEED_WARN_M_S
    assert d.grip_speed_fail == constants.GRIP_SPEED_FAIL_M_S


def test_the_default_profile_is_the_mens_and_the_verdicts_defaults_are_its_limits():
    """A spec without a profile is judged by the men's limits, each sourced; the verdict's defaults in
    pumplink.constants are the same numbers (the unsourced 0.5-0.9 m grip band is gone,
    docs/operators.md §8)."""
    from pumplink import constants as C

    men = PROFILES["men"]
    assert DEFAULT_PROFILE is men
    assert (men.force_limit, men.sustained_power, men.hour_power) == (
        C.FORCE_LIMIT_N,
        C.SUSTAINED_POWER_W,
        C.HOUR_POWER_W,
    )
    assert (men.grip_speed_warn, men.grip_speed_fail) == (C.GRIP_SPEED_WARN_M_S, C.GRIP_SPEED_FAIL_M_S)
    assert tuple(men.grip_height_range) == tuple(C.GRIP_HEIGHT_RANGE_M)


def test_profiles_are_frozen():
    p = PROFILES["women"]
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.force_limit = 1.0  # type: ignore[misc]
    with pytest.raises(TypeError):
        p.sources["force_limit"] = Source("x", "derived")  # type: ignore[index]
    with pytest.raises(TypeError):
        PROFILES["men"] = p  # type: ignore[index]


def test_profiles_module_imports_only_pumplink_constants():
    """Data only: besides the standard library it may import pumplink.constants and nothing else."""
    tree = ast.parse(Path(profiles_module.__file__).read_text())
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            names.add(node.module)
    assert {n for n in names if n.startswith("pumplink")} <= {"pumplink.constants"}
    assert names <= {"__future__", "dataclasses", "types", "typing", "pumplink.constants"}


# ----------------------------------------------------------------------------- through the verdict
#: docs/operators.md §1, each profile's limits as that table prints them: force [N], sustained and
#: hour power [W], grip heights [m], grip speed warn and fail [m/s].
TABLE = {
    "men": (100.0, 75.0, 150.0, (0.90, 1.33), 2.5, 4.0),
    "women": (70.0, 60.0, 125.0, (0.83, 1.23), 2.1, 3.3),
    "children": (38.0, 33.0, 69.0, (0.86, 1.04), 2.1, 3.3),
    "accessible": (22.2, 25.0, 50.0, (0.71, 1.02), 1.1, 1.8),
}

#: A quasi-static rope pump (no wheel mass): 10 m through a 23 mm main, 0.25 m wheel, a 1 m handle
#: swung 60 deg (grip stroke 2 x 1.0 x sin 30 deg = 1.0 m).  By hand (docs/physics.md §5): rope
#: force rho g H (pi d^2/4) / eta_f = 1000 x 9.81 x 10 x 4.15476e-4 / 0.75 = 54.344 N, wheel torque
#: M = 0.25 x 54.344 = 13.586 N m, operator power M w, mean grip force over a turn 2 pi M / (2 x
#: 1.0 m) = 42.68 N (the work of a turn over the grip's travel out and back).
HAND_SPEC = {
    "name": "profile check",
    "wheel": {"radius": 0.25, "axle_height": 0.55},
    "linkage": {"L1": 0.40, "D1": 0.20, "b": 0.10, "rocker": 0.20, "handle": 1.00, "swing": 60.0},
    # the efficiency given: the constant at every speed, so the hand formula holds (the loss
    # model, docs/water.md §2a, would decide at some of the speeds below)
    "load": {"head": 10.0, "pipe_diameter": 0.023, "efficiency": 0.75},
    "operator": {"speed": 270.0},
}
TORQUE = 0.25 * 1000.0 * 9.81 * 10.0 * (math.pi * 0.023**2 / 4) / 0.75  # [N m]
MEAN_FORCE = 2 * math.pi * TORQUE / (2 * 1.0)  # [N]


def _judged(profile: str, speed_deg_s: float) -> dict:
    import pumplink

    spec = {**HAND_SPEC, "operator": {"speed": speed_deg_s, "profile": profile}}
    row = pumplink.to_dict(pumplink.analyse(pumplink.load(spec)))
    assert row["model"].startswith("quasi-static") and row["operator_profile"] == profile
    return {c["key"]: c for c in row["checks"]}


@pytest.mark.parametrize("profile", list(TABLE))
def test_each_profiles_limits_are_the_ones_the_verdict_judges_by(profile):
    """Every limit of docs/operators.md's table reaches the verdict of a design judged for that
    profile: the check's own limits, and its result on either side of each power and grip-speed
    limit (the speed put 3 % below and above each).  The power is the hand formula M w; the grip
    speed is the product's (H times the rocker's peak rate times w: linear in the speed, checked),
    judged here against the table's limits; the mean force is the hand formula against the force
    limit (42.7 N: men and women pass, children and accessible fail)."""
    force, sustained, hour, (low, high), warn, fail = TABLE[profile]
    base = _judged(profile, 270.0)
    rate = base["grip_speed"]["value"] / math.radians(270.0)  # grip speed per wheel speed [m/rad]
    assert (base["mean_force"]["fail_limit"], base["peak_force"]["fail_limit"]) == (force, force)
    assert base["mean_force"]["value"] == pytest.approx(MEAN_FORCE, rel=1e-9)
    assert base["mean_force"]["result"] == ("pass" if MEAN_FORCE <= force else "fail")
    assert (base["power"]["warn_limit"], base["power"]["fail_limit"]) == (sustained, hour)
    assert (base["grip_speed"]["warn_limit"], base["grip_speed"]["fail_limit"]) == (warn, fail)
    assert base["grip_height"]["warn_limit"] == high  # the grip rises to 1.35 m, above every band
    assert base["grip_height"]["result"] == "warn" and low < high
    speeds = [
        *(v / rate * k for v in (warn, fail) for k in (0.97, 1.03)),  # [rad/s]
        *(p / TORQUE * k for p in (sustained, hour) for k in (0.97, 1.03)),
    ]
    for w in speeds:
        checks = _judged(profile, math.degrees(w))
        power, grip = TORQUE * w, rate * w
        assert checks["power"]["value"] == pytest.approx(power, rel=1e-9)
        assert checks["grip_speed"]["value"] == pytest.approx(grip, rel=1e-9)
        expected_power = "fail" if power > hour else "warn" if power > sustained else "pass"
        expected_grip = "fail" if grip > fail else "warn" if grip > warn else "pass"
        assert (checks["power"]["result"], checks["grip_speed"]["result"]) == (
            expected_power,
            expected_grip,
        ), (
            profile,
            math.degrees(w),
            power,
            grip,
        )

"""Operator profiles: the limits a design is held to for one kind of operator, each with its source.

Data only (docs/operators.md gives the reasoning and the sources in full).  Each profile sets the
largest push/pull force, the power sustained for hours and for about an hour, the grip-height
range over the swing, the grip speeds at which the verdict warns and fails, the cadence (wheel
turns a minute) outside which it warns, and the power the field's published discharges imply
while filling containers (the filling duty, docs/water.md §6).  Every value
carries a :class:`Source`: the text a reader can check and its basis, one of

* ``"source"``: read at the source named;
* ``"secondary"``: read only in a secondary citation of the source named;
* ``"derived"``: computed from other values by the reasoning given (docs/operators.md).

:data:`DEFAULT_PROFILE` is the men's: every limit of the verdict has a source.  The grip-height
range 0.5-0.9 m used before profiles existed had none and is gone (docs/operators.md §8).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Literal

Basis = Literal["source", "secondary", "derived"]

#: The numeric fields of a profile, each of which needs a :class:`Source`.
FIELDS = (
    "force_limit",
    "sustained_power",
    "hour_power",
    "grip_height_range",
    "grip_speed_warn",
    "grip_speed_fail",
    "cadence_range",
    "filling_power",
)


@dataclass(frozen=True)
class Source:
    """Where a value comes from: ``text`` names the source (title, publisher, section) or the
    derivation; ``basis`` says how it was checked (module docstring)."""

    text: str
    basis: Basis


@dataclass(frozen=True)
class OperatorProfile:
    """The limits for one kind of operator (SI units).

    force_limit [N]: largest push/pull force at the grip;  sustained_power [W]: power kept up for
    hours (above it the verdict warns);  hour_power [W]: power for about an hour (above it the
    design fails);  grip_height_range [m]: lowest and highest grip height above the ground over the
    swing;  grip_speed_warn, grip_speed_fail [m/s]: peak grip speeds;  cadence_range [turns/min]:
    the wheel turns (push-pull cycles) a minute outside which the verdict warns;  filling_power [W]:
    the operator's power while filling containers, the duty the published discharges are for;
    sources: a :class:`Source` per field of :data:`FIELDS`.
    """

    name: str
    force_limit: float
    sustained_power: float
    hour_power: float
    grip_height_range: tuple[float, float]
    grip_speed_warn: float
    grip_speed_fail: float
    cadence_range: tuple[float, float]
    filling_power: float
    sources: MappingProxyType = field(repr=False, compare=False)


def _profile(name: str, **limits: tuple) -> OperatorProfile:
    """A profile from its limits, each given as (value, :class:`Source`)."""
    return OperatorProfile(
        name=name,
        **{key: value for key, (value, _) in limits.items()},
        sources=MappingProxyType({key: source for key, (_, source) in limits.items()}),
    )


# ------------------------------------------------------------------------------------- sources
_HSE = (
    "UK HSE, 'Doing a push/pull risk assessment' (hse.gov.uk/msd/pushpull), table of guideline "
    "figures from L23 'Manual handling', Appendix: keeping a load in motion, men 10 kg (about "
    "100 N), women 7 kg (about 70 N); starting or stopping it 20 kg / 15 kg"
)
_ADA = (
    "2010 ADA Standards for Accessible Design §309.4 and ABA Standards §1011.6 (US Access Board, "
    "'Chapter 10: Outdoor Developed Areas' guide, water hydrants, which include hand pumps): "
    "operable parts need 5 lbf (22.2 N) at most"
)
_POWER = (
    "Practical Action, 'Human and animal powered water-lifting devices for irrigation' "
    "(technical brief), Introduction: human physical power output 0.06-0.075 kW"
)
_HOUR = (
    "Human-power figures as summarised in Wikipedia, 'Human power' (not its primary source): adults "
    "of good fitness average 50-150 W for an hour; a labourer sustains about 75 W over 8 hours"
)
_SEX_RATIO = (
    "Abbott & Wilson, 'Human-Powered Vehicles' (Human Kinetics 1995), as quoted by Princeton "
    "MAE 'Human power' pages: steady-state power capability about 20 % larger for adult men than "
    "adult women"
)
_ZONE = (
    "HSE push/pull guideline figures apply with the hands between knuckle and shoulder height "
    "(same page as the force figures); grip band = [wrist height 0.485 H of the tallest user, "
    "shoulder height 0.818 H of the shortest] with the Drillis-Contini body proportions (Winter, "
    "'Biomechanics and Motor Control of Human Movement', Fig. 4.1; not re-read here); wrist height "
    "stands in for knuckle height, which makes the band narrower, on the safe side"
)
_PHEASANT = (
    "stature of British adults 19-65, Pheasant, 'Bodyspace' Table 10.1, via City University of Hong "
    "Kong 'Online Anthropometry' Ch. 2-1: men 5th/95th percentile 1625/1855 mm, women 1505/1710 mm"
)
_SPEED = (
    "scaled from the men's limits (pumplink.constants: 2.5 and 4.0 m/s) as v ~ sqrt(F_limit / "
    "m_arm): the arms' inertia force 2 m_arm v^2 / stroke grows as v^2, and the fail limit is where "
    "it reaches the force limit; m_arm = 0.072 x body mass (Winter's segment fractions, as "
    "pumplink.constants.ARM_MASS_FRACTION); rounded down to 0.1 m/s"
)


_CADENCE = (
    "wheel turns (push-pull cycles) a minute: 30, the lower end of the 'strong preference for a "
    "narrow operating speed range, 30 to 50 rev/min' for hand and foot operation found in Harare "
    "tests of the rope-washer, Rower, Bumi and treadle pumps ('The efficient use of human energy for "
    "micro-scale irrigation', J. Agric. Eng. Res. 48(3) 171-183, 1991; abstract read); 60, the "
    "fastest rate of the AIT laboratory tests of hand pumps (IDRC report RP-01638, Table 2: 20-60 "
    "strokes/min) and the pump paper's 60 rpm; no source for one kind of operator was found, so "
    "every profile has the same range (docs/operators.md §6)"
)
_FILLING = (
    "the operator's power while filling containers, fitted (one value) so that the published "
    "one-person discharges for this operator are reproduced through the evaluation "
    "(pumplink validate, docs/water.md §6)"
)


def _zone(derivation: str) -> Source:
    """A grip-height range derived from the push/pull zone (:data:`_ZONE`) and a stature."""
    return Source(_ZONE + "; " + derivation, "derived")


def _speed(derivation: str) -> Source:
    """A grip-speed limit scaled from the men's (:data:`_SPEED`) with the profile's numbers."""
    return Source(_SPEED + "; " + derivation, "derived")


# ------------------------------------------------------------------------------------- profiles
MEN = _profile(
    "men",
    force_limit=(100.0, Source(_HSE + "; men, keeping a load in motion: 100 N", "source")),
    sustained_power=(75.0, Source(_POWER + ", upper end 75 W", "source")),
    hour_power=(150.0, Source(_HOUR + ", upper end 150 W", "secondary")),
    grip_height_range=((0.90, 1.33), _zone(_PHEASANT + ": 0.485 x 1.855 = 0.90 m to 0.818 x 1.625 = 1.33 m")),
    grip_speed_warn=(
        2.5,
        Source(
            "V. Kleshnev, 'Rowing Biomechanics' (2006): trained rowers' handle speed peaks at about "
            "2-3 m/s in the drive (docs/references.md [rowing biomechanics]; not re-read here)",
            "secondary",
        ),
    ),
    grip_speed_fail=(
        4.0,
        Source(
            "docs/models.md §4: on a 1.4 m stroke the grip accelerates at 2 v^2 / stroke = 23 m/s^2 "
            "at 4 m/s, and 4.32 kg of arms (0.072 x 60 kg) then need about 100 N, the force limit",
            "derived",
        ),
    ),
    cadence_range=((30.0, 60.0), Source(_CADENCE, "derived")),
    filling_power=(
        81.0,
        Source(
            _FILLING + ": Akvopedia 'Rope pump' (35 l/min at 10 m, half that at 20 m) and the "
            "University of Twente demonstration site (an adult, 25 l/min at 12 m); minimax fit "
            "80.95 W, residuals at 81 W -7.6 %, -7.6 %, +7.8 % (scripts/field_fit.py)",
            "derived",
        ),
    ),
)

WOMEN = _profile(
    "women",
    force_limit=(70.0, Source(_HSE + "; women, keeping a load in motion: 70 N", "source")),
    sustained_power=(
        60.0,
        Source(
            _POWER
            + ": its lower end, 60 W, taken for women; agrees with 75 W / 1.2 = 62.5 W from "
            + _SEX_RATIO,
            "derived",
        ),
    ),
    hour_power=(125.0, Source("150 W / 1.2 = 125 W: the men's hour power over " + _SEX_RATIO, "derived")),
    grip_height_range=((0.83, 1.23), _zone(_PHEASANT + ": 0.485 x 1.710 = 0.83 m to 0.818 x 1.505 = 1.23 m")),
    grip_speed_warn=(
        2.1,
        _speed(
            "70 N, 58.2 kg (CDC 2000 growth charts, weight-for-age median at 20 years, girls): "
            "2.5 x sqrt((70/58.2)/(100/60)) = 2.12"
        ),
    ),
    grip_speed_fail=(3.3, _speed("as the warn limit: 4.0 x 0.850 = 3.40")),
    cadence_range=((30.0, 60.0), Source(_CADENCE, "derived")),
    filling_power=(
        75.0,
        Source(
            _FILLING + ": Arrakis 'Hand rope pumps (continued)', women and children, 30 l/min at "
            "10 m and 15 l/min at 20 m; minimax fit 75.17 W, residuals at 75 W -0.2 %, -0.2 % "
            "(scripts/field_fit.py)",
            "derived",
        ),
    ),
)

CHILDREN = _profile(
    "children",
    force_limit=(
        38.0,
        Source(
            "no published push/pull guideline for children was found; the HSE women's 70 N scaled by "
            "body mass, 70 x 32.1 / 58.2 = 38.6 N, rounded down (CDC 2000 weight-for-age medians: "
            "boys 10 years 32.1 kg, girls 20 years 58.2 kg); de Winter et al., 'Pushing and pulling "
            "forces exerted by children' (1994, abstract) support body mass as the force indicator "
            "and find the force per body mass lower in younger children, so this is an upper "
            "estimate for children under 10",
            "derived",
        ),
    ),
    sustained_power=(
        33.0,
        Source(
            "the women's 60 W scaled by the same body-mass ratio 32.1/58.2 = 33 W; Shephard et al., "
            "'Sex differences of physical working capacity' (Ergonomics 31, 1988, abstract): "
            "working capacity follows fat-free body mass",
            "derived",
        ),
    ),
    hour_power=(69.0, Source("the women's 125 W x 32.1/58.2 = 69 W", "derived")),
    grip_height_range=(
        (0.86, 1.04),
        _zone(
            "stature 10-14 years, CDC 2000 stature-for-age: girls 10 years 5th percentile "
            "127.5 cm, boys 14 years 95th percentile 177.0 cm: 0.485 x 1.770 = 0.86 m to 0.818 x "
            "1.275 = 1.04 m (adult proportions applied to children: approximate)"
        ),
    ),
    grip_speed_warn=(2.1, _speed("38 N, 32.1 kg: 2.5 x sqrt((38/32.1)/(100/60)) = 2.11")),
    grip_speed_fail=(3.3, _speed("as the warn limit: 4.0 x 0.843 = 3.37")),
    cadence_range=((30.0, 60.0), Source(_CADENCE, "derived")),
    filling_power=(
        41.0,
        Source(
            "no discharge published for children alone; the women's filling power (which Arrakis's "
            "figure for women and children fits) scaled by the body-mass ratio 32.1/58.2, as the "
            "children's other powers: 75 x 32.1 / 58.2 = 41.4 W, rounded down",
            "derived",
        ),
    ),
)

ACCESSIBLE = _profile(
    "accessible",
    force_limit=(22.2, Source(_ADA, "source")),
    sustained_power=(
        25.0,
        Source(
            "no source found for seated arm work; 25 W is about the mean power a design can demand "
            "at this profile's force and warn-speed limits (22.2 N x 1.1 m/s = 24 W), so the force "
            "limit, not the power, decides",
            "derived",
        ),
    ),
    hour_power=(50.0, Source("twice the sustained power, the men's ratio 150 W / 75 W", "derived")),
    grip_height_range=(
        (0.71, 1.02),
        Source(
            "USDA Forest Service MTDC Tech Tip 0571-2311 'New Accessible Handpump for Campgrounds' "
            "(Kuhn & Beckley 2005): control heights between 28 and 40 inches (0.71-1.02 m), citing "
            "ADA Accessibility Guidelines 14.15.4; inside the current ABA §1011.6 range for operable "
            "parts of water hydrants, 15-48 inches (0.38-1.22 m)",
            "source",
        ),
    ),
    grip_speed_warn=(1.1, _speed("22.2 N, 60 kg adult: 2.5 x sqrt(22.2/100) = 1.18")),
    grip_speed_fail=(1.8, _speed("as the warn limit: 4.0 x 0.471 = 1.88")),
    cadence_range=((30.0, 60.0), Source(_CADENCE, "derived")),
    filling_power=(
        27.0,
        Source(
            "no discharge published for seated operators; the sustained 25 W times the men's ratio "
            "of filling to sustained power: 25 x 81 / 75 = 27.0 W",
            "derived",
        ),
    ),
)

#: The profiles by name (docs/operators.md).
PROFILES = MappingProxyType({p.name: p for p in (MEN, WOMEN, CHILDREN, ACCESSIBLE)})

#: The profile of a spec that names none: the men's, the operator the 100 N force limit was
#: always meant for (UK HSE); every one of its limits has a source (docs/operators.md).
DEFAULT_PROFILE = MEN


def operator_limits(value) -> OperatorProfile:
    """The operator's limits from spec values: ``value("operator.profile")`` names the profile
    (None: the default, the men's), and each of its limits a ``value("operator.<key>")`` that is
    not None replaces (a float, or an array over designs); ``operator.cadence_min`` and
    ``operator.cadence_max`` the ends of the cadence range."""
    name = value("operator.profile")
    base = DEFAULT_PROFILE if name is None else PROFILES[name]
    lo, hi = base.grip_height_range
    lo, hi = (
        base if v is None else v
        for base, v in ((lo, value("operator.grip_height_min")), (hi, value("operator.grip_height_max")))
    )
    given = {
        k: value(f"operator.{k}")
        for k in (
            "force_limit", "sustained_power", "hour_power", "grip_speed_warn", "grip_speed_fail",
            "filling_power",
        )
    }  # fmt: skip
    slow, fast = base.cadence_range
    slow, fast = (
        base if v is None else v
        for base, v in ((slow, value("operator.cadence_min")), (fast, value("operator.cadence_max")))
    )
    return replace(
        base,
        grip_height_range=(lo, hi),
        cadence_range=(slow, fast),
        **{k: v for k, v in given.items() if v is not None},
    )

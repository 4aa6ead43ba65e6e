"""The rope-pump spec: a TOML file validated by pydantic (SI units; angles in degrees).

The keys and units are the contract other tools write against.  Every bad value is
reported as one sentence naming the key, the value and what is allowed.
"""

from __future__ import annotations

import math
from pathlib import Path
from types import MappingProxyType
from typing import Any, Literal

from pydantic import Field, model_validator

from pumplink.constants import (
    DEFAULT_ARM_MASS,
    DEFAULT_DAILY_PUMPING_HOURS,
    DEFAULT_LITRES_PER_PERSON_DAY,
    DEFAULT_SPEED_FLUCTUATION,
)
from pumplink.inputs.toml import MAX_NAME_CHARS, Section, optional, read_spec, validate_spec
from pumplink.models import load as _load
from pumplink.profiles import DEFAULT_PROFILE, PROFILES, OperatorProfile, operator_limits


class Wheel(Section):
    radius: float = Field(ge=0.001, le=5, description="upper wheel radius rw [m]")
    axle_height: float | None = optional(
        "height of the wheel axle above the ground [m] (optional; the paper uses 0.40-0.70 m)", gt=0, le=5
    )
    inertia: float | None = optional(
        ("moment of inertia of the wheel about its axle [kg m^2] (optional; turns on the flywheel model)"),
        gt=0,
        le=1000,
    )
    mass: float | None = optional(
        "wheel mass [kg], taken as a rim: J = mass * radius^2 (optional, instead of inertia)", gt=0, le=1000
    )

    @model_validator(mode="after")
    def _one_inertia(self) -> Wheel:
        if self.inertia is not None and self.mass is not None:
            raise ValueError(
                f"give either wheel.inertia [kg m^2] or wheel.mass [kg], not both "
                f"(inertia = {self.inertia!r}, mass = {self.mass!r})"
            )
        return self


class Linkage(Section):
    L1: float = Field(
        ge=0, le=10, description="horizontal placement of the rocker pivot beyond the stand [m]"
    )
    D1: float = Field(
        ge=-10, le=10, description="depth of the rocker pivot below the axle [m] (negative = above)"
    )
    b: float = Field(ge=0, le=10, description="width of the pump stand [m]")
    rocker: float = Field(ge=0.001, le=10, description="rocker length l4 [m]")
    handle: float = Field(ge=0.001, le=20, description="handle length H, rocker pivot to hand grip [m]")
    swing: float = Field(
        ge=2 * math.pi,  # below: radians, said by _swing_in_degrees
        lt=180,
        description="total handle swing [deg], symmetric about vertical",
    )
    mass_per_length: float | None = optional(
        (
            "mass per metre of the handle and coupler [kg/m] for the link-energy estimate "
            "(default 1.56: 3/4-inch steel tube)"
        ),
        gt=0,
        le=100,
    )
    coupler_mass: float | None = optional(
        "coupler mass [kg] (full dynamics; default mass_per_length * coupler length)", ge=0, le=1000
    )
    handle_mass: float | None = optional(
        (
            "handle mass [kg], a uniform bar from the rocker pivot to the grip (full dynamics; "
            "default mass_per_length * max(handle, rocker))"
        ),
        ge=0,
        le=1000,
    )
    hole_diameter: float | None = optional(
        (
            "diameter of the pins and of their holes on the workshop template [m], in a spec "
            "without [parts] (an older name of parts.pin_diameter; default 0.012)"
        ),
        ge=0.001,
        le=0.1,
    )

    @model_validator(mode="before")
    @classmethod
    def _swing_in_degrees(cls, data: Any) -> Any:
        # A swing below 2 pi is almost surely radians (1.047 for 60 deg): a 1.8 mm crank that
        # fails with no hint otherwise.  Said before the range check, with the fix, when the fix
        # is itself a valid swing (6.143 rad is 352 deg: the range error says what is allowed).
        swing = data.get("swing") if isinstance(data, dict) else None
        if (
            isinstance(swing, (int, float))
            and not isinstance(swing, bool)
            and 0 < swing < 2 * math.pi
            and 2 * math.pi <= round(math.degrees(swing), 1) < 180
        ):
            deg = f"{round(math.degrees(swing), 1):g}"
            raise ValueError(
                f"linkage.swing = {swing!r} looks like radians: did you mean {deg}°? The swing is in "
                f"degrees, {2 * math.pi:g} <= swing < 180 (write swing = {deg})"
            )
        return data


class Load(Section):
    rope_force: float | None = optional(
        "rope force Fw at the wheel rim [N] (or give head and pipe_diameter)", ge=0.001, le=10_000
    )
    head: float | None = optional("pumping head [m]", ge=0.001, le=200)
    pipe_diameter: float | None = optional("rising-main bore [m]", ge=0.001, le=0.5)
    efficiency: float | None = optional(
        (
            "force (mechanical) efficiency with head/pipe_diameter [-]: the rope force is the "
            "water column's weight over it (default 0.75)"
        ),
        ge=0.05,
        le=1,
    )
    volumetric_efficiency: float | None = optional(
        (
            "delivered over swept flow with head/pipe_diameter [-] (leakage past the pistons; "
            "default 0.87, docs/water.md)"
        ),
        ge=0.05,
        le=1,
    )
    moving_mass: float | None = optional(
        (
            "rope, pistons and water moving with the wheel rim [kg] (default with head and "
            "pipe_diameter: the water in the rising main)"
        ),
        ge=0,
        le=10_000,
    )
    piston_clearance: float | None = optional(
        (
            "bore minus piston diameter [m], for the loss model's leakage (default 0.00035: the "
            "middle of 0.2-0.5 mm, docs/water.md §2a)"
        ),
        gt=0,
        le=0.01,
    )
    piston_spacing: float | None = optional(
        "distance between the pistons on the rope [m], for the loss model (default 1.0, docs/water.md §2a)",
        gt=0,
        le=100,
    )

    @property
    def rope_force_N(self) -> float:
        """Rope force at the rim [N] (:func:`pumplink.models.load.rope_force`)."""
        return _load.rope_force(self.rope_force, self.head, self.pipe_diameter, self.efficiency)

    @property
    def moving_mass_kg(self) -> float:
        """Mass moving at rim speed [kg] (:func:`pumplink.models.load.moving_mass`)."""
        return _load.moving_mass(self.moving_mass, self.head, self.pipe_diameter)

    @model_validator(mode="after")
    def _one_load(self) -> Load:
        by_head = self.head is not None or self.pipe_diameter is not None
        if self.rope_force is not None and by_head:
            raise ValueError("give either load.rope_force or load.head with load.pipe_diameter, not both")
        if self.rope_force is None and not (self.head is not None and self.pipe_diameter is not None):
            raise ValueError(
                "give load.rope_force [N], or load.head [m] together with load.pipe_diameter [m]"
            )
        if self.efficiency is not None and not by_head:
            raise ValueError("load.efficiency only applies with load.head and load.pipe_diameter")
        for key in ("piston_clearance", "piston_spacing"):
            if getattr(self, key) is not None and not by_head:
                raise ValueError(f"load.{key} only applies with load.head and load.pipe_diameter")
        if self.volumetric_efficiency is not None and not by_head:
            raise ValueError(
                "load.volumetric_efficiency only applies with load.head and load.pipe_diameter (the flow "
                "needs the pipe)"
            )
        return self


#: The operator's power keys, the same in the rope-pump spec and the piston-pump spec.
SUSTAINED_POWER = optional("power the operator sustains for hours [W] (profile's)", ge=1, le=1000)
HOUR_POWER = optional("power the operator gives for about an hour [W] (profile's)", ge=1, le=2000)


class Operator(Section):
    profile: Literal["men", "women", "children", "accessible"] | None = optional(
        "who pumps: sets force_limit, sustained_power, hour_power, the grip-height range and "
        "the grip-speed limits (docs/operators.md); any of those keys given here overrides it "
        "(default: men)"
    )
    force_limit: float | None = optional(
        "largest acceptable operator force [N] (default: the profile's; men 100, women 70)", ge=1, le=10_000
    )
    sustained_power: float | None = SUSTAINED_POWER
    hour_power: float | None = HOUR_POWER
    grip_height_min: float | None = optional("lowest comfortable grip height [m] (profile's)", ge=0, le=3)
    grip_height_max: float | None = optional("highest comfortable grip height [m] (profile's)", ge=0, le=3)
    grip_speed_warn: float | None = optional(
        "grip speed above which the verdict warns [m/s] (profile's)", gt=0, le=20
    )
    grip_speed_fail: float | None = optional(
        "grip speed above which the design fails [m/s] (profile's)", gt=0, le=20
    )
    cadence_min: float | None = optional(
        "fewest wheel turns a minute before the verdict warns [1/min] (profile's: 30)", gt=0, le=600
    )
    cadence_max: float | None = optional(
        "most wheel turns a minute before the verdict warns [1/min] (profile's: 60)", gt=0, le=600
    )
    filling_power: float | None = optional(
        "the operator's power while filling containers [W] (profile's; docs/water.md §6)", ge=1, le=2000
    )
    speed: float = Field(default=360.0, gt=0, le=7200, description="wheel speed [deg/s]")
    dead_band: float = Field(
        default=20.0,
        ge=0,
        lt=90,
        description="crank angle each side of a dead centre left to the wheel's inertia [deg] "
        "(quasi-static model only)",
    )
    speed_fluctuation: float = Field(
        default=DEFAULT_SPEED_FLUCTUATION,
        gt=0,
        le=1,
        description="largest coefficient of speed fluctuation (w_max - w_min) / w_mean [-] (flywheel model)",
    )
    arm_mass: float | None = optional(
        (
            "operator's hands and forearms moving with the grip [kg] (full dynamics: the "
            "muscular effort and the best cadence; default 4.32)"
        ),
        ge=0,
        le=100,
    )
    arms_in_verdict: bool | None = optional(
        "true to judge the muscular effort (arm_mass at the grip) against force_limit "
        "instead of the hand force"
    )

    @property
    def arm_mass_kg(self) -> float:
        """operator.arm_mass, or the anthropometric default (pumplink.constants.DEFAULT_ARM_MASS) [kg]."""
        return DEFAULT_ARM_MASS if self.arm_mass is None else self.arm_mass

    @property
    def limits(self) -> OperatorProfile:
        """The operator's limits: the profile's (:mod:`pumplink.profiles`; the men's without one),
        with every key the spec gives instead."""
        return operator_limits(lambda key: getattr(self, key.split(".")[1], None))

    @model_validator(mode="after")
    def _limits_in_order(self) -> Operator:
        limits_in_order(self.limits)
        return self


def limits_in_order(limits: OperatorProfile, grip: bool = True) -> None:
    """Raise ValueError naming the spec keys of the first pair of the operator's ``limits`` in the
    wrong order: the grip heights and speeds (``grip``: a piston pump's operator has no grip),
    and the powers."""
    speeds = (limits.grip_speed_warn, limits.grip_speed_fail)
    pairs = [
        ("operator.grip_height_min must be below operator.grip_height_max", *limits.grip_height_range),
        ("operator.grip_speed_warn must be below operator.grip_speed_fail", *speeds),
    ]
    pairs.append(("operator.cadence_min must be below operator.cadence_max", *limits.cadence_range))
    pairs = pairs if grip else []
    powers = (limits.sustained_power, limits.hour_power)
    pairs.append(("operator.sustained_power must be at most operator.hour_power", *powers))
    for what, a, b in pairs:
        if not a <= b:
            raise ValueError(f"{what} (with the {limits.name} profile: {a:g} and {b:g})")


#: The fatigue notch factor each way of joining a part gives when ``[parts]`` states none
#: (docs/workshop.md §2): a hole drilled through the tube or bar about 3 (Peterson's transverse
#: hole, Kf close to Kt for mild steel), the toe of a weld about 2.
JOINT_NOTCH = MappingProxyType({"hole": 3.0, "lug": 2.0, "welded": 2.0})
#: How the handle and the crank are joined when ``[parts]`` does not say: the coupler's pin
#: through a hole drilled in the handle tube (as the default pin_width, both walls of the tube),
#: the crank welded to the axle.
DEFAULT_JOINTS = MappingProxyType({"handle": "hole", "crank": "welded"})


class Parts(Section):
    pin_diameter: float = Field(
        default=0.012,
        ge=0.001,  # as linkage.hole_diameter, its older name
        le=0.1,
        description="diameter of the joint pins [m], and of the holes the workshop template drills for them",
    )
    pin_width: float = Field(
        default=0.0052,
        ge=0.0005,
        le=0.2,
        description="length of bore each pin bears on [m] (a bushing's length, or both walls of the tube "
        "it passes through: 2 x 2.6 mm by default)",
    )
    handle_diameter: float = Field(
        default=0.0269, ge=0.005, le=0.2, description="handle tube's outer diameter [m]"
    )
    handle_wall: float = Field(default=0.0026, ge=0.0005, le=0.1, description="handle tube's wall [m]")
    handle_joint: Literal["hole", "lug"] = Field(
        default=DEFAULT_JOINTS["handle"],
        description='how the handle carries the coupler\'s pin at B: "hole", drilled through the tube '
        '(the default), or "lug", a lug welded on that holds the pin (the tube is not drilled there; '
        "docs/workshop.md §2)",
    )
    handle_notch: float = Field(
        default=JOINT_NOTCH[DEFAULT_JOINTS["handle"]],
        ge=1.0,
        le=5.0,
        description="fatigue notch factor of the handle at B [-] (default from handle_joint: 3 at a "
        "drilled hole, 2 at a lug's weld toe; 1: plain)",
    )
    crank_diameter: float = Field(
        default=0.0127,
        ge=0.003,
        le=0.2,
        description="crank's diameter [m], a solid round bar (½\" by default)",
    )
    crank_joint: Literal["welded", "hole"] = Field(
        default=DEFAULT_JOINTS["crank"],
        description='how the crank is fixed to the axle O2: "welded" (the default; the crank is not '
        'drilled there) or "hole", drilled for the axle and pinned to it',
    )
    crank_notch: float = Field(
        default=JOINT_NOTCH[DEFAULT_JOINTS["crank"]],
        ge=1.0,
        le=5.0,
        description="fatigue notch factor of the crank at the axle [-] (default from crank_joint: 2 at "
        "a weld toe, 3 at a drilled hole; 1: plain)",
    )

    bush: Literal["steel", "polyethylene"] = Field(
        default="steel",
        description='what the pins turn in: "steel" (a welded steel bush or the drilled tube, the default) '
        'or "polyethylene" (a PE bush in a steel sleeve): the wear coefficient of the pin life '
        "(docs/workshop.md §5)",
    )
    wear_allowance: float = Field(
        default=0.0005,
        gt=0,
        le=0.01,
        description="radial play a joint may wear open before its pin and bush are replaced [m] "
        "(default 0.0005)",
    )

    @model_validator(mode="before")
    @classmethod
    def _notch_from_joint(cls, data: Any) -> Any:
        # a notch factor not given follows from how the part is joined (JOINT_NOTCH)
        if not isinstance(data, dict):
            return data
        data = dict(data)
        for part, joint in DEFAULT_JOINTS.items():
            joint = data.get(f"{part}_joint", joint)
            if f"{part}_notch" not in data and isinstance(joint, str) and joint in JOINT_NOTCH:
                data[f"{part}_notch"] = JOINT_NOTCH[joint]
        return data

    @model_validator(mode="after")
    def _wall_inside(self) -> Parts:
        if 2 * self.handle_wall > self.handle_diameter:
            raise ValueError(
                f"parts.handle_wall = {self.handle_wall:g} m is more than half the handle_diameter "
                f"{self.handle_diameter:g} m; give a wall of at most {self.handle_diameter / 2:g} m"
            )
        return self


class Ratchet(Section):
    torque: float = Field(
        gt=0,
        le=10_000,
        description="torque the ratchet (or another automatic back-stop on the wheel's axle) holds [N m]: "
        "at least the water column's, rho g head (pi d^2/4) rw (docs/workshop.md §3)",
    )
    teeth: int = Field(
        ge=0,
        le=10_000,
        description="places a turn of the wheel where its pawl catches (teeth x pawls, staggered); 0 for a "
        "back-stop with no play (a freewheel, a sprag)",
    )


class Use(Section):
    people: float | None = optional(
        "people the pump serves (default: as many as its hours a day serve, docs/water.md §5)",
        gt=0,
        le=1_000_000,
    )
    hours_per_day: float = Field(
        default=DEFAULT_DAILY_PUMPING_HOURS,
        gt=0,
        le=24,
        description="hours a day the pump is worked [h] (for the people it serves; default 8)",
    )
    litres_per_person_day: float = Field(
        default=DEFAULT_LITRES_PER_PERSON_DAY,
        gt=0,
        le=1000,
        description="water each person needs a day [l] (default 20, WHO basic access)",
    )


class PumpSpec(Section):
    # the characters a name may hold: Section (names go into tables, file names and JUnit XML)
    name: str = Field(default="pump", min_length=1, max_length=MAX_NAME_CHARS, description="design name")

    wheel: Wheel = Field(description="the [wheel] table: radius [m]")
    linkage: Linkage = Field(description="the [linkage] table: L1, D1, b, rocker, handle, swing")
    load: Load = Field(description="the [load] table: rope_force [N], or head [m] with pipe_diameter [m]")
    operator: Operator = Field(
        default=Operator(),
        description="the [operator] table: profile, force_limit, speed, dead_band, speed_fluctuation",
    )
    parts: Parts | None = Field(
        default=None,
        description="the [parts] table: pins, handle tube and crank bar; when given, the verdict checks "
        "pin bearing pressure and the handle's and crank's fatigue (docs/workshop.md)",
    )
    ratchet: Ratchet | None = Field(
        default=None,
        description="the [ratchet] table: torque [N m], teeth; the back-stop that keeps the water column "
        "from driving the handle back (docs/workshop.md §3)",
    )
    use: Use = Field(
        default=Use(),
        description="the [use] table: people, hours_per_day, litres_per_person_day (the people a pump "
        "serves, the crank turns a day)",
    )

    @model_validator(mode="after")
    def _pins_once(self) -> PumpSpec:
        hole = self.linkage.hole_diameter
        if hole is not None and self.parts is not None and hole != self.parts.pin_diameter:
            raise ValueError(
                f"linkage.hole_diameter = {hole:g} m and parts.pin_diameter = {self.parts.pin_diameter:g} m "
                "both give the pins' diameter (the template drills the holes for the pins of [parts]); "
                f"give it once, as parts.pin_diameter = {hole:g}"
            )
        return self

    @property
    def values(self) -> dict[str, Any]:
        """The spec's values by dotted key (:func:`spec_values`): what the evaluation reads."""
        return spec_values(self)

    @property
    def parts_or_defaults(self) -> Parts:
        """The parts the workshop builds: the spec's ``[parts]``, or their defaults (the pins' diameter
        linkage.hole_diameter where the spec gives it), which the verdict does not judge
        (docs/workshop.md)."""
        if self.parts is not None:
            return self.parts
        hole = self.linkage.hole_diameter
        return Parts() if hole is None else Parts(pin_diameter=hole)

    @property
    def wheel_torque(self) -> float:
        """Load torque Mw = Fw * rw on the wheel axle [N m] (Eq. 3 of the pump paper)."""
        return self.load.rope_force_N * self.wheel.radius

    @property
    def inertia(self) -> float | None:
        """Moment of inertia about the wheel axle [kg m^2] (:func:`pumplink.models.load.inertia`),
        or None when the spec gives none (:attr:`gives_inertia`)."""
        if not self.gives_inertia:
            return None
        w = self.wheel
        return _load.inertia(w.radius, w.inertia, w.mass, self.load.moving_mass_kg)

    @property
    def gives_inertia(self) -> bool:
        """True when the spec states wheel.inertia, wheel.mass or load.moving_mass: the wheel's
        inertia is known and the flywheel or full dynamics decides (docs/models.md §3); without
        them the design is analysed quasi-statically with the dead band."""
        w = self.wheel
        return not (w.inertia is None and w.mass is None and self.load.moving_mass is None)


#: The built-in default design (``pumplink force`` with no spec; ``pumplink init``).  It is the
#: prototype example: a 0.5 m wheel (20" rim class, docs/physics.md §5), a 1 m handle swung +-30 deg
#: about vertical, 45 N at the rim (about 8 m head through a 23 mm bore at 75 % efficiency).
DEFAULT_SPEC: dict[str, Any] = {
    "name": "Prototype",
    "wheel": {"radius": 0.25},
    "linkage": {"L1": 0.40, "D1": 0.20, "b": 0.10, "rocker": 0.20, "handle": 1.00, "swing": 60.0},
    "load": {"rope_force": 45.0},
    "operator": {"profile": "men", "speed": 360.0, "dead_band": 20.0},
}


def default_spec() -> PumpSpec:
    """The built-in default design as a validated spec."""
    return PumpSpec.model_validate(DEFAULT_SPEC)


def parse_spec(data: Any, source: str = "spec") -> PumpSpec:
    """Validate a spec mapping (as read from TOML).

    Raises
    ------
    SpecError
        One sentence per problem (the first in the message, the count of the others after it).
    """
    return validate_spec(data, source, PumpSpec)


def spec_values(spec) -> dict[str, Any]:
    """A spec's values by dotted key ("linkage.swing"): the mapping
    :func:`pumplink.evaluate.pump_designs` and :func:`~pumplink.evaluate.piston_designs` read (a
    key of a table the spec leaves out is absent; one it leaves empty is None)."""
    out: dict[str, Any] = {}
    for section in type(spec).model_fields:
        table = getattr(spec, section)
        if isinstance(table, Section):
            out.update({f"{section}.{name}": getattr(table, name) for name in type(table).model_fields})
    return out


def load_spec(path: str | Path) -> PumpSpec:
    """Read and validate a rope pump's TOML spec file (:func:`pumplink.inputs.toml.read_spec`);
    the name defaults to the file stem.

    Raises
    ------
    SpecError
        Unreadable file, invalid TOML, a batch file, a piston pump, or an invalid spec.
    """
    return read_spec(path, PumpSpec)


def spec_to_dict(spec: PumpSpec) -> dict[str, Any]:
    """The spec as a plain mapping for tomli-w (optional keys left out when unset)."""
    return spec.model_dump(exclude_none=True)


#: The commented spec ``pumplink init`` writes: the default design with every key's unit and
#: allowed range, and the optional keys commented out.  ``{name}`` is filled in.
SPEC_TEMPLATE = """\
# A pumplink spec: the rope pump's wheel, the four-bar linkage, the load and the operator.
# Units: metres, degrees, newtons, kilograms, seconds.  Check it with:  pumplink force {path}
# The keys are explained in docs/physics.md §1 (with a sketch of L1, D1 and b).
name = "{name}"

[wheel]
radius = 0.25          # wheel radius rw [m], 0.001-5 (a 20" tyre rim: about 0.25)
# axle_height = 0.55   # axle height above the ground [m], 0-5 (0 excluded): adds grip-height checks
# mass = 4.0           # wheel mass [kg] as a rim, J = mass rw^2: turns on the flywheel model,
#                      # where the wheel speed decides the verdict (docs/models.md §2)
# inertia = 0.25       # or the wheel's moment of inertia [kg m^2] instead of mass

[linkage]
L1 = 0.40              # rocker pivot beyond the stand, horizontally [m], 0-10
D1 = 0.20              # rocker pivot below the axle [m], -10..10 (negative: above)
b = 0.10               # width of the pump stand [m], 0-10
rocker = 0.20          # rocker length l4 [m], 0.001-10
handle = 1.00          # handle length H, rocker pivot to grip [m], 0.001-20
swing = 60.0           # total handle swing [deg], 2π-180 (degrees, not radians; 180 excluded),
                       # symmetric about vertical
# mass_per_length = 1.56  # handle and coupler tube [kg/m] (default: 3/4" steel tube)

[load]
rope_force = 45.0      # rope force at the wheel rim Fw [N], 0.001-10000; or instead:
# head = 10.0          # pumping head [m], 0.001-200
# pipe_diameter = 0.023  # rising-main bore [m], 0.001-0.5
# efficiency = 0.75    # rope-pump efficiency [-], 0.05-1 (with head and pipe_diameter)
# moving_mass = 4.0    # rope and water moving with the rim [kg] (flywheel model)
# piston_clearance = 0.00035  # bore minus piston diameter [m] (loss model, docs/water.md §2a)
# piston_spacing = 1.0  # distance between the pistons on the rope [m] (loss model)

[operator]
profile = "men"        # who pumps: "men", "women", "children" or "accessible" (docs/operators.md).
                       # Each sets the verdict's limits: the push/pull force, the power kept up
                       # for hours / for about an hour, the grip's height range over the swing
                       # (with wheel.axle_height) and the grip speeds at which it warns / fails:
{profiles}
                       # A key below overrides one of the profile's limits (the men's shown):
# force_limit = {force_limit}        # the largest push/pull [N], 1-10000
# sustained_power = {sustained_power}     # the power kept up for hours [W]
# hour_power = {hour_power}         # the power given for about an hour [W]
# grip_height_min = {grip_height_min}     # the grip's lowest and highest point over the swing [m]
# grip_height_max = {grip_height_max}    # (checked with wheel.axle_height)
# grip_speed_warn = {grip_speed_warn}     # the grip speeds at which the verdict warns and fails [m/s]
# grip_speed_fail = {grip_speed_fail}
# cadence_min = {cadence_min}        # the wheel turns a minute outside which the verdict warns
# cadence_max = {cadence_max}
# filling_power = {filling_power}       # the power while filling containers [W] (docs/water.md §6)
speed = 360.0          # wheel speed [deg/s], 0-7200 (0 excluded; 360 deg/s = 60 rpm)
dead_band = 20.0       # crank angle each side of a dead centre left to the wheel [deg], 0-90 (90 excluded)
# speed_fluctuation = 0.2  # largest (w_max - w_min) / w_mean [-], 0-1 (0 excluded; flywheel model)

# The pins, the handle tube and the crank bar (docs/workshop.md): given, the verdict checks the
# pins' bearing pressure and the fatigue of the handle and the crank, and `pumplink template`
# drills the pins' holes.  Uncomment the table and the keys to change; these are the defaults.
# [parts]
# pin_diameter = {pin_diameter}    # pins [m], and the template's holes, 0.001-0.1
# pin_width = {pin_width}     # bore each pin bears on [m]: both walls of the tube, or a bush's length
# handle_diameter = {handle_diameter}  # handle tube, outer diameter and wall [m] (3/4" medium tube)
# handle_wall = {handle_wall}
# handle_joint = "{handle_joint}"  # the coupler's pin at B: "hole" drilled through the handle, or
#                        # "lug" welded on (then the template does not drill the handle at B)
# handle_notch = {handle_notch}    # fatigue notch factor at B, 1-5 (default: 3 at a hole, 2 at a lug)
# crank_diameter = {crank_diameter}  # crank, a round bar [m] (1/2")
# crank_joint = "{crank_joint}"  # the crank at the axle: "welded", or "hole" (drilled and pinned)
# crank_notch = {crank_notch}     # fatigue notch factor at the axle, 1-5 (default: 2 welded, 3 at a hole)
# bush = "{bush}"        # what the pins turn in: "steel" or "polyethylene" (the pins' wear)
# wear_allowance = {wear_allowance}  # radial play a joint may wear open [m], 0-0.01 (0 excluded)

# The back-stop on the wheel's axle (docs/workshop.md §3): let go, the water column drives the wheel
# and the handle back unless a ratchet holds it.  Without it the verdict fails the kick-back check.
# [ratchet]
# torque = 20.0        # torque it holds [N m], 0-10000 (0 excluded): at least the column's
# teeth = 24           # places a turn where its pawl catches, 0-10000 (0: no play, a freewheel)

# How the water is used, for the people a pump serves (docs/water.md); these are the defaults.
# [use]
#   (people = 250 would count the crank turns of 250 people; default: as many as its hours serve)
# hours_per_day = {hours_per_day}     # hours a day the pump is worked [h], 0-24 (0 excluded)
# litres_per_person_day = {litres_per_person_day}  # water each person needs a day [l] (WHO basic access)
"""


def _profile_lines() -> str:
    """The operator profiles' limits, one commented line each, under the spec's ``profile`` key."""
    lines = []
    for p in PROFILES.values():
        lo, hi = p.grip_height_range
        force = f"{p.force_limit:g} N"
        power = f"{p.sustained_power:g} / {p.hour_power:g} W"
        speed = f"{p.grip_speed_warn:.1f} / {p.grip_speed_fail:.1f} m/s"
        lines.append(f"{' ' * 23}#   {p.name:<10} {force:>6}   {power:>10}   {lo:.2f}-{hi:.2f} m   {speed}")
    return "\n".join(lines)


def spec_template(name: str, path: str = "pump.toml") -> str:
    """The commented spec of :data:`SPEC_TEMPLATE` with this design ``name`` (TOML-quoted): the
    operator profiles' limits from :mod:`pumplink.profiles`, the defaults of ``[parts]`` and
    ``[use]`` from their models."""
    import json

    quoted = json.dumps(name, ensure_ascii=False)[1:-1]  # a TOML basic string is JSON-compatible
    men = DEFAULT_PROFILE
    limits = {k: getattr(men, k) for k in ("force_limit", "sustained_power", "hour_power")}
    limits.update(grip_speed_warn=men.grip_speed_warn, grip_speed_fail=men.grip_speed_fail)
    limits.update(grip_height_min=men.grip_height_range[0], grip_height_max=men.grip_height_range[1])
    limits.update(cadence_min=men.cadence_range[0], cadence_max=men.cadence_range[1])
    limits.update(filling_power=men.filling_power)
    values = {**Parts().model_dump(), **Use().model_dump(), **limits, "profiles": _profile_lines()}
    text = SPEC_TEMPLATE.replace("{name}", quoted).replace("{path}", path)
    for key, value in values.items():
        text = text.replace(f"{{{key}}}", value if isinstance(value, str) else repr(value))
    return text

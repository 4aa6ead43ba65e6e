"""The inputs of the evaluation: designs and their operating conditions as columns.

A spec is one design of floats; a batch chunk gives arrays for the keys it varies.
:func:`pump_designs` and :func:`piston_designs` build the columns from spec values (``values[key]``
gives a dotted spec key's value in spec units, or None where it is not given), so every route into
the evaluation assembles its inputs here.  SI units, radians.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields
from functools import cached_property
from typing import Any

import numpy as np

from pumplink.constants import (
    DEFAULT_ARM_MASS,
    DEFAULT_DAILY_PUMPING_HOURS,
    DEFAULT_EFFICIENCY,
    DEFAULT_LITRES_PER_PERSON_DAY,
    DEFAULT_VOLUMETRIC_EFFICIENCY,
    LINK_MASS_PER_METRE,
    LOSS_SHARE,
)
from pumplink.mechanisms.fourbar import FourBar
from pumplink.models import load as _load
from pumplink.models import losses as _losses
from pumplink.models.parts import PART_KEYS
from pumplink.models.wear import wear_rate as _wear_rate
from pumplink.profiles import DEFAULT_PROFILE, operator_limits

#: Spec keys that give the wheel's inertia (the flywheel or full dynamics can then decide).
INERTIA_KEYS = ("wheel.inertia", "wheel.mass", "load.moving_mass")
#: Which efficiencies a rope-pump design is evaluated with (``PumpDesigns.losses``), by index:
#: the constant defaults (the loss model within :data:`~pumplink.constants.LOSS_SHARE` of them),
#: the loss model's (docs/water.md §2a), or the spec's own ``load.efficiency`` /
#: ``load.volumetric_efficiency`` (a measurement: the loss model is not consulted).
LOSSES = ("constant", "loss model", "spec")


@dataclass(frozen=True)
class PumpDesigns:
    """Rope-pump designs (the pump paper's four-bar) and their operating conditions, as columns.

    Floats for one design, 1-D arrays over designs otherwise (broadcast together); SI units,
    angles in radians.

    Attributes
    ----------
    L1, D1, b : frame placement [m] (docs/physics.md §1);  rocker, handle : [m];  swing : [rad].
    wheel_radius : rw [m];  rope_force : Fw at the rim [N];  wheel_torque : Mw = Fw rw [N m].
    moving_mass : rope and water moving with the rim [kg];  inertia : J about the axle [kg m^2]
    (NaN: not given).
    speed : mean wheel speed ω̄ [rad/s];  dead_band : [rad];  speed_fluctuation : δ [-].
    force_limit : [N];  mass_per_length : [kg/m] of the handle and coupler tube.
    coupler_mass, handle_mass : [kg] (NaN: bars of ``mass_per_length``);  arm_mass : [kg].
    arms_in_verdict : the operator's arms in the verdict's force (one flag for all designs).
    axle_height : [m], or None (no height checks).
    linkage : a built four-bar (its pivot, link lengths, handle and branch as made), analysed as it
        is (:func:`pumplink.mechanisms.fourbar.analyse`) instead of synthesised from L1, D1, b,
        rocker and swing, which are then not read; None: synthesise.
    wheel_mass : [kg] (NaN: not given; its weight loads the axle).  parts : the pins, handle tube and
        crank bar (the spec's ``[parts]``: attributes pin_diameter, pin_width, handle_diameter,
        handle_wall, handle_notch, crank_diameter, crank_notch), or None: no part checks.
    head, pipe_diameter : pumping head and rising-main bore [m] (NaN: the spec gives a rope force,
        so there is no flow);  force_efficiency, volumetric_efficiency : [-].
    sustained_power, hour_power : the operator's power for hours and for an hour [W];
    grip_height_min, grip_height_max [m], grip_speed_warn, grip_speed_fail [m/s]: the operator
    profile's limits (:mod:`pumplink.profiles`, with the spec's own keys instead where given).
    hours_per_day [h], litres_per_person_day [l]: how the water is used (the people it serves);
    people : the people it serves (NaN: as many as its hours a day serve).
    cadence_min, cadence_max [turns/min]: the profile's cadence range;  filling_power [W]: the
    operator's power while filling containers (the filling duty).
    losses : index into :data:`LOSSES`, which efficiencies ``force_efficiency`` and
    ``volumetric_efficiency`` are;  model_force_efficiency, model_volumetric_efficiency : the loss
    model's at the design's rope speed [-] (docs/water.md §2a; NaN without a head);
    piston_clearance, piston_spacing : [m], the loss model's pistons.
    ratchet_torque [N m], ratchet_teeth [-]: the ``[ratchet]`` back-stop (NaN: none).
    wear_rate [m^2/N], wear_surfaces [-], wear_allowance [m]: the pins' material pair
    (:data:`pumplink.models.wear.PAIRS`, ``[parts] bush``) and the play they may wear open.
    """

    L1: Any
    D1: Any
    b: Any
    rocker: Any
    handle: Any
    swing: Any
    wheel_radius: Any
    rope_force: Any
    wheel_torque: Any
    moving_mass: Any
    inertia: Any
    speed: Any
    dead_band: Any
    speed_fluctuation: Any
    force_limit: Any
    mass_per_length: Any
    coupler_mass: Any
    handle_mass: Any
    arm_mass: Any
    head: Any = np.nan
    pipe_diameter: Any = np.nan
    force_efficiency: Any = DEFAULT_EFFICIENCY
    volumetric_efficiency: Any = DEFAULT_VOLUMETRIC_EFFICIENCY
    sustained_power: Any = DEFAULT_PROFILE.sustained_power
    hour_power: Any = DEFAULT_PROFILE.hour_power
    grip_height_min: Any = DEFAULT_PROFILE.grip_height_range[0]
    grip_height_max: Any = DEFAULT_PROFILE.grip_height_range[1]
    grip_speed_warn: Any = DEFAULT_PROFILE.grip_speed_warn
    grip_speed_fail: Any = DEFAULT_PROFILE.grip_speed_fail
    hours_per_day: Any = DEFAULT_DAILY_PUMPING_HOURS
    litres_per_person_day: Any = DEFAULT_LITRES_PER_PERSON_DAY
    cadence_min: Any = DEFAULT_PROFILE.cadence_range[0]
    cadence_max: Any = DEFAULT_PROFILE.cadence_range[1]
    filling_power: Any = DEFAULT_PROFILE.filling_power
    losses: Any = 0
    model_force_efficiency: Any = np.nan
    model_volumetric_efficiency: Any = np.nan
    piston_clearance: Any = _losses.PISTON_CLEARANCE
    piston_spacing: Any = _losses.PISTON_SPACING
    people: Any = np.nan
    ratchet_torque: Any = np.nan
    ratchet_teeth: Any = np.nan
    wear_rate: Any = np.nan
    wear_surfaces: Any = np.nan
    wear_allowance: Any = np.nan
    arms_in_verdict: bool = False
    axle_height: Any = None
    linkage: FourBar | None = None
    wheel_mass: Any = np.nan
    parts: Any = None

    @cached_property
    def columns(self) -> tuple[int, dict[str, np.ndarray]]:
        """The number of designs and their numeric fields as 1-D float arrays of that length
        (:func:`design_columns`), worked out once."""
        return design_columns(self)


def _or(value, default):
    return default if value is None else value


def pump_designs(values: Mapping[str, Any], speed=None) -> PumpDesigns:
    """The columns of rope-pump designs from their spec values.

    Parameters
    ----------
    values : a spec key's value by its dotted name (``values["linkage.swing"]``) in spec units
        (degrees, deg/s): a float, an array over designs, or None (or absent) where the key is not
        given (the spec's ``values``, :func:`pumplink.inputs.pump.spec_values`).
    speed : mean wheel speed [deg/s] instead of ``operator.speed`` (a float or an array).
    """
    value = values.get
    inertia = np.nan
    mass = _load.moving_mass(value("load.moving_mass"), value("load.head"), value("load.pipe_diameter"))
    if any(value(k) is not None for k in INERTIA_KEYS):
        inertia = _load.inertia(value("wheel.radius"), value("wheel.inertia"), value("wheel.mass"), mass)
    speed = np.radians(value("operator.speed") if speed is None else speed)
    by_head = value("load.head") is not None
    eff = _efficiencies(value, speed) if by_head else None
    force_efficiency = None if eff is None else eff[0]
    head, pipe = value("load.head"), value("load.pipe_diameter")
    rope = _load.rope_force(value("load.rope_force"), head, pipe, force_efficiency)
    limits = operator_limits(value)
    return PumpDesigns(
        L1=value("linkage.L1"),
        D1=value("linkage.D1"),
        b=value("linkage.b"),
        rocker=value("linkage.rocker"),
        handle=value("linkage.handle"),
        swing=np.radians(value("linkage.swing")),
        wheel_radius=value("wheel.radius"),
        rope_force=rope,
        wheel_torque=rope * value("wheel.radius"),  # Mw = Fw rw, Eq. (3) of the pump paper
        moving_mass=mass,
        inertia=inertia,
        speed=speed,
        dead_band=np.radians(value("operator.dead_band")),
        speed_fluctuation=value("operator.speed_fluctuation"),
        force_limit=limits.force_limit,
        mass_per_length=_or(value("linkage.mass_per_length"), LINK_MASS_PER_METRE),
        coupler_mass=_or(value("linkage.coupler_mass"), np.nan),
        handle_mass=_or(value("linkage.handle_mass"), np.nan),
        arm_mass=_or(value("operator.arm_mass"), DEFAULT_ARM_MASS),
        head=value("load.head") if by_head else np.nan,
        pipe_diameter=value("load.pipe_diameter") if by_head else np.nan,
        **({} if eff is None else dict(zip(_EFFICIENCY_FIELDS, eff))),
        sustained_power=limits.sustained_power,
        hour_power=limits.hour_power,
        grip_height_min=limits.grip_height_range[0],
        grip_height_max=limits.grip_height_range[1],
        grip_speed_warn=limits.grip_speed_warn,
        grip_speed_fail=limits.grip_speed_fail,
        hours_per_day=_or(value("use.hours_per_day"), DEFAULT_DAILY_PUMPING_HOURS),
        litres_per_person_day=_or(value("use.litres_per_person_day"), DEFAULT_LITRES_PER_PERSON_DAY),
        cadence_min=limits.cadence_range[0],
        cadence_max=limits.cadence_range[1],
        filling_power=limits.filling_power,
        people=_or(value("use.people"), np.nan),
        ratchet_torque=_or(value("ratchet.torque"), np.nan),
        ratchet_teeth=_or(value("ratchet.teeth"), np.nan),
        **_wear(value),
        arms_in_verdict=bool(value("operator.arms_in_verdict")),
        axle_height=value("wheel.axle_height"),
        wheel_mass=_or(value("wheel.mass"), np.nan),
        parts=_part_sizes(value),
    )


_EFFICIENCY_FIELDS = (
    "force_efficiency",
    "volumetric_efficiency",
    "losses",
    "model_force_efficiency",
    "model_volumetric_efficiency",
    "piston_clearance",
    "piston_spacing",
)


def _efficiencies(value, speed) -> tuple:
    """The efficiencies a rope pump given by its head and bore is evaluated with, by the rule of
    docs/water.md §2a: the spec's own where it gives one; else the constant defaults where the loss
    model's overall efficiency η_f η_v (the water a watt lifts) is within
    :data:`~pumplink.constants.LOSS_SHARE` of theirs, the loss model's elsewhere.  Returns the
    values of :data:`_EFFICIENCY_FIELDS` (arrays over designs)."""
    d, head, r_w = value("load.pipe_diameter"), value("load.head"), value("wheel.radius")
    clearance = _or(value("load.piston_clearance"), _losses.PISTON_CLEARANCE)
    spacing = _or(value("load.piston_spacing"), _losses.PISTON_SPACING)
    rope_speed = np.asarray(speed, float) * r_w
    model_v = _losses.volumetric_efficiency(d, rope_speed, head, clearance, spacing)
    model_f = _losses.force_efficiency(d, rope_speed)
    given = value("load.efficiency") is not None or value("load.volumetric_efficiency") is not None
    force = _or(value("load.efficiency"), DEFAULT_EFFICIENCY)
    volumetric = _or(value("load.volumetric_efficiency"), DEFAULT_VOLUMETRIC_EFFICIENCY)
    if given:
        index = np.full(np.shape(model_f), LOSSES.index("spec"))
    else:
        # the water one watt lifts, η_f η_v: the constants' split is not sourced, only their product
        off = _losses.off_by(force * volumetric, model_f * model_v)
        model = ~(off <= LOSS_SHARE)  # NaN (no rope speed): the model decides, and gives NaN
        index = np.where(model, LOSSES.index("loss model"), LOSSES.index("constant"))
        force, volumetric = np.where(model, model_f, force), np.where(model, model_v, volumetric)
    return force, volumetric, index, model_f, model_v, clearance, spacing


def _wear(value) -> dict[str, Any]:
    """The pins' wear columns from ``[parts] bush`` and ``wear_allowance`` (NaN without ``[parts]``)."""
    bush = value("parts.bush")
    if bush is None:
        return {}
    rate, surfaces = _wear_rate(bush)
    return dict(wear_rate=rate, wear_surfaces=surfaces, wear_allowance=value("parts.wear_allowance"))


@dataclass(frozen=True)
class PartSizes:
    """The pins, handle tube and crank bar of designs [m; notch factors -] (docs/workshop.md §2)."""

    pin_diameter: Any
    pin_width: Any
    handle_diameter: Any
    handle_wall: Any
    handle_notch: Any
    crank_diameter: Any
    crank_notch: Any

    def design(self, i: int) -> PartSizes:
        """The sizes of design ``i`` (a size given once holds for every design)."""
        return PartSizes(*(float(_of_design(getattr(self, k), i)) for k in PART_KEYS))


def _of_design(x, i: int):
    """Design ``i``'s value of a column: an array over designs, or one value for all of them."""
    a = np.ravel(np.asarray(x, float))
    return a[i] if a.size > 1 else a[0]


def _part_sizes(value) -> PartSizes | None:
    sizes = {k: value(f"parts.{k}") for k in PART_KEYS}
    return None if all(v is None for v in sizes.values()) else PartSizes(**sizes)


@dataclass(frozen=True)
class PistonDesigns:
    """Piston pumps (a crank-slider turned by a hand crank, docs/piston-pump.md) as columns.

    crank, rod, offset : r, l, e [m];  handle : radius R of the crank the operator turns [m];
    load_force : the piston's force on its working stroke [N] (Eq. P.1);  speed : [rad/s];
    force_limit : [N];  inertia : J on the crank shaft [kg m^2] (NaN: none);  speed_fluctuation : δ.
    bore, head [m], force_efficiency, volumetric_efficiency [-]: the flow (docs/water.md);
    sustained_power, hour_power [W]: the operator profile's;  hours_per_day, litres_per_person_day.
    """

    crank: Any
    rod: Any
    offset: Any
    handle: Any
    load_force: Any
    speed: Any
    force_limit: Any
    inertia: Any
    speed_fluctuation: Any
    bore: Any = np.nan
    head: Any = np.nan
    force_efficiency: Any = DEFAULT_EFFICIENCY
    volumetric_efficiency: Any = DEFAULT_VOLUMETRIC_EFFICIENCY
    sustained_power: Any = DEFAULT_PROFILE.sustained_power
    hour_power: Any = DEFAULT_PROFILE.hour_power
    hours_per_day: Any = DEFAULT_DAILY_PUMPING_HOURS
    litres_per_person_day: Any = DEFAULT_LITRES_PER_PERSON_DAY

    @cached_property
    def columns(self) -> tuple[int, dict[str, np.ndarray]]:
        """The number of designs and their numeric fields as 1-D float arrays of that length
        (:func:`design_columns`), worked out once."""
        return design_columns(self)


def piston_designs(values: Mapping[str, Any], speed=None) -> PistonDesigns:
    """The columns of piston pumps from their spec values (``values`` as in :func:`pump_designs`)."""
    value = values.get
    limits = operator_limits(value)
    inertia = np.nan
    if value("wheel.inertia") is not None or value("wheel.mass") is not None:
        inertia = _load.rim_inertia(value("wheel.inertia"), value("wheel.mass"), value("wheel.radius"))
    return PistonDesigns(
        crank=value("crank_slider.crank"),
        rod=value("crank_slider.rod"),
        offset=_or(value("crank_slider.offset"), 0.0),
        handle=value("operator.handle"),
        load_force=_load.piston_load_force(
            value("piston.bore"), value("piston.head"), value("piston.efficiency")
        ),
        speed=np.radians(value("operator.speed") if speed is None else speed),
        force_limit=limits.force_limit,
        inertia=inertia,
        speed_fluctuation=value("operator.speed_fluctuation"),
        bore=value("piston.bore"),
        head=value("piston.head"),
        force_efficiency=value("piston.efficiency"),
        volumetric_efficiency=_or(value("piston.volumetric_efficiency"), DEFAULT_VOLUMETRIC_EFFICIENCY),
        sustained_power=limits.sustained_power,
        hour_power=limits.hour_power,
        hours_per_day=_or(value("use.hours_per_day"), DEFAULT_DAILY_PUMPING_HOURS),
        litres_per_person_day=_or(value("use.litres_per_person_day"), DEFAULT_LITRES_PER_PERSON_DAY),
    )


def design_columns(designs) -> tuple[int, dict[str, np.ndarray]]:
    """The designs' numeric fields as 1-D float arrays of one length (the number of designs).

    The number of designs is that of every input that can vary, the axle height and the parts'
    sizes included (not broadcast here: they are read where their checks are), so a design that
    differs from the others only there is still one design of its own."""
    skip = ("arms_in_verdict", "axle_height", "linkage", "parts")
    names = [f.name for f in fields(designs) if f.name not in skip]
    others = [getattr(designs, "axle_height", None)]
    parts = getattr(designs, "parts", None)
    if parts is not None:
        others += [getattr(parts, f.name) for f in fields(parts)]
    shape = np.broadcast_shapes(
        *(np.shape(getattr(designs, k)) for k in names), *(np.shape(v) for v in others if v is not None)
    )
    cols = {k: np.broadcast_to(np.asarray(getattr(designs, k), float), shape).ravel() for k in names}
    return next(iter(cols.values())).size, cols

"""The one evaluation: design columns in; every quantity the verdict and the renderers need out;
the verdict from :func:`pumplink.verdict.assess`, called once per evaluation.

``pumplink force``, ``speed``, ``batch``, ``optimize``, ``report``, ``suggest`` and the piston
pumps all judge designs through :func:`evaluate`: one design is the n = 1 case of the same
vectorised route, so they cannot disagree.  Two mechanisms share it:

* the rope pump's four-bar (:class:`PumpDesigns`): dead-centre synthesis (Eq. 1-2 of the pump
  paper), the mean force (docs/physics.md §4), the quasi-static peak outside the dead bands
  (docs/models.md §1), the least model that is enough with the wheel's inertia and its least peak
  force (§2-3), the link-energy share, the grip's peak speed, stroke and heights, the power, and
  the operator's effort (§3a);
* the piston pump's crank-slider (:class:`PistonDesigns`, docs/piston-pump.md): the mean force
  (Eq. P.3), the quasi-static peak and the flywheel's least peak force (Eq. P.4), the power.

:func:`pump_designs` and :func:`piston_designs` build the columns from spec values (a spec is one
design of floats; a batch chunk gives arrays for the keys it varies), so the inputs of the
evaluation are also assembled in one place.  :mod:`pumplink.evaluate.motion` holds the rest of
what runs a force model: the deciding model's motion of one design (profiles, the time-domain
check, the best cadence).  Nothing outside this package calls a force model.

Pure functions on floats and numpy arrays; SI units, radians.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, fields
from functools import partial
from typing import Any

import numpy as np

from pumplink.constants import (
    DEFAULT_ARM_MASS,
    DEFAULT_DAILY_PUMPING_HOURS,
    DEFAULT_EFFICIENCY,
    DEFAULT_LITRES_PER_PERSON_DAY,
    DEFAULT_VOLUMETRIC_EFFICIENCY,
    GRAVITY,
    LINK_MASS_PER_METRE,
)
from pumplink.mechanisms import crank_slider as cs
from pumplink.mechanisms.fourbar import (
    FourBar,
    Synthesis,
    analyse,
    built_grip,
    grip_heights,
    grip_stroke,
    peak_rocker_rate,
    per_design,
    synthesize,
)
from pumplink.models import DYNAMICS, FLYWHEEL, MODELS, ORDER, Conditions, Masses
from pumplink.models import load as _load
from pumplink.models import quasi_static as _qs
from pumplink.models import water as _water_kernels
from pumplink.models.choice import EnergyModel, energy_model
from pumplink.profiles import DEFAULT_PROFILE, operator_limits
from pumplink.verdict import FAIL, Verdict, assess

#: Spec keys that give the wheel's inertia (the flywheel or full dynamics can then decide).
INERTIA_KEYS = ("wheel.inertia", "wheel.mass", "load.moving_mass")
#: The words of each model, by index into :data:`pumplink.models.ORDER` (reports, the model column).
MODEL_LABELS = tuple(MODELS[k].label for k in ORDER)
#: Designs swept together for the sampled peak: the kernel's temporaries (designs x samples)
#: stay in the processor's cache.
SUB_DESIGNS = 128


# ----------------------------------------------------------------------------- the inputs
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
    hours_per_day [h], litres_per_person_day [l]: how the water is used (the people it serves).
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
    arms_in_verdict: bool = False
    axle_height: Any = None
    linkage: FourBar | None = None
    wheel_mass: Any = np.nan
    parts: Any = None


def _or(value, default):
    return default if value is None else value


def pump_designs(value: Callable[[str], Any], speed=None) -> PumpDesigns:
    """The columns of rope-pump designs from their spec values.

    Parameters
    ----------
    value : ``value("linkage.swing")`` gives a spec key's value in spec units (degrees, deg/s):
        a float, an array over designs, or None where the key is not given.
    speed : mean wheel speed [deg/s] instead of ``operator.speed`` (a float or an array).
    """
    inertia = np.nan
    mass = _load.moving_mass(value("load.moving_mass"), value("load.head"), value("load.pipe_diameter"))
    if any(value(k) is not None for k in INERTIA_KEYS):
        inertia = _load.inertia(value("wheel.radius"), value("wheel.inertia"), value("wheel.mass"), mass)
    rope = _load.rope_force(
        value("load.rope_force"), value("load.head"), value("load.pipe_diameter"), value("load.efficiency")
    )
    limits = operator_limits(value)
    by_head = value("load.head") is not None
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
        speed=np.radians(value("operator.speed") if speed is None else speed),
        dead_band=np.radians(value("operator.dead_band")),
        speed_fluctuation=value("operator.speed_fluctuation"),
        force_limit=limits.force_limit,
        mass_per_length=_or(value("linkage.mass_per_length"), LINK_MASS_PER_METRE),
        coupler_mass=_or(value("linkage.coupler_mass"), np.nan),
        handle_mass=_or(value("linkage.handle_mass"), np.nan),
        arm_mass=_or(value("operator.arm_mass"), DEFAULT_ARM_MASS),
        head=value("load.head") if by_head else np.nan,
        pipe_diameter=value("load.pipe_diameter") if by_head else np.nan,
        force_efficiency=_or(value("load.efficiency"), DEFAULT_EFFICIENCY),
        volumetric_efficiency=_or(value("load.volumetric_efficiency"), DEFAULT_VOLUMETRIC_EFFICIENCY),
        sustained_power=limits.sustained_power,
        hour_power=limits.hour_power,
        grip_height_min=limits.grip_height_range[0],
        grip_height_max=limits.grip_height_range[1],
        grip_speed_warn=limits.grip_speed_warn,
        grip_speed_fail=limits.grip_speed_fail,
        hours_per_day=_or(value("use.hours_per_day"), DEFAULT_DAILY_PUMPING_HOURS),
        litres_per_person_day=_or(value("use.litres_per_person_day"), DEFAULT_LITRES_PER_PERSON_DAY),
        arms_in_verdict=bool(value("operator.arms_in_verdict")),
        axle_height=value("wheel.axle_height"),
        wheel_mass=_or(value("wheel.mass"), np.nan),
        parts=_part_sizes(value),
    )


#: The keys of a spec's ``[parts]`` table.
PART_KEYS = (
    "pin_diameter",
    "pin_width",
    "handle_diameter",
    "handle_wall",
    "handle_notch",
    "crank_diameter",
    "crank_notch",
)


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


def piston_designs(value: Callable[[str], Any], speed=None) -> PistonDesigns:
    """The columns of piston pumps from their spec values (``value`` as in :func:`pump_designs`)."""
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


def _columns(designs) -> tuple[int, dict[str, np.ndarray]]:
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


# ----------------------------------------------------------------------------- the results
@dataclass(frozen=True)
class Water:
    """The water a design delivers, and the most its operator could lift (arrays over designs,
    NaN where the spec gives a rope force instead of a head and a pipe; docs/water.md).

    flow : Q = η_v (π d²/4) ω̄ r_w for a rope pump, η_v A stroke f for a piston pump [m³/s].
    water_power : ρ g H Q [W];  efficiency : water power / the operator's power Mw ω̄ [-].
    limit : Q* = η_f η_v P_sustained / (ρ g H), the flow the operator's sustained power lifts at
        this head with this pump's efficiencies [m³/s];  share : Q / Q* [-].
    people : the people it serves, Q x hours a day / litres per person a day [-].
    head [m], sustained_power [W]: what ``limit`` was computed for.
    """

    flow: np.ndarray
    water_power: np.ndarray
    efficiency: np.ndarray
    limit: np.ndarray
    share: np.ndarray
    people: np.ndarray
    head: np.ndarray
    sustained_power: np.ndarray

    def design(self, i: int) -> Water:
        """The water of design ``i`` alone (floats)."""
        n = np.shape(self.flow)
        return Water(
            *(float(np.broadcast_to(np.asarray(getattr(self, f.name), float), n)[i]) for f in fields(self))
        )


def _water(
    flow, head, operator_power, sustained_power, force_efficiency, volumetric_efficiency, hours, litres
):
    """:class:`Water` from the flow [m³/s] and what it is judged against
    (:mod:`pumplink.models.water`)."""
    water_power = _water_kernels.water_power(flow, head)
    limit = _water_kernels.power_limited_flow(sustained_power, head, force_efficiency, volumetric_efficiency)
    return Water(
        flow,
        water_power,
        _water_kernels.overall_efficiency(water_power, operator_power),
        limit,
        _water_kernels.flow_share(flow, limit),
        _water_kernels.people_served(flow, hours, litres),
        head,
        sustained_power,
    )


@dataclass(frozen=True)
class Evaluation:
    """Every quantity the verdict and the renderers need, for rope-pump designs (arrays over
    designs; SI units, radians).

    Attributes
    ----------
    designs : the input columns;  synthesis : the dead-centre synthesis (Eq. 1-2).
    feasible : a crank-rocker with the requested swing exists.
    mean_force : F_mean = π Mw / S [N] (docs/physics.md §4).
    dead_band_peak_force, dead_band_peak_angle : the quasi-static peak outside the dead bands [N]
        and where [rad] (NaN where not computed).
    sampled_peak : the peak over a uniform sweep of ``samples`` crank angles outside the dead
        bands [N] (NaN where not asked for).
    model_index : 0 quasi-static, 1 flywheel, 2 full dynamics (:data:`pumplink.models.ORDER`).
    energy : the energy-model choice and its solved force (None without any inertia).
    least_peak_force : the energy model's least peak force [N] (NaN where none decides).
    min_passing_speed : the flywheel's slowest passing speed [rad/s] (NaN where it does not decide).
    effort_peak_force : least peak effort, the hand force plus the arms (full dynamics) [N].
    masses : the links' masses and, where the verdict takes them, the arms' [kg].
    power : Mw ω̄ [W];  rocker_rate : max|dθ4/dθ2| [-] (NaN without the verdict);
    grip_speed : the grip's peak speed at the wheel's top speed [m/s].
    stroke : horizontal grip stroke [m];  grip_height : (lowest, highest) or None.
    link_energy_share : the flywheel's neglected link energy / its band [%] (0 where the flywheel
        does not decide; None where it decides nowhere).
    verdict : :func:`pumplink.verdict.assess` (None when not asked for).
    """

    designs: PumpDesigns
    synthesis: Synthesis
    feasible: np.ndarray
    mean_force: np.ndarray
    dead_band_peak_force: np.ndarray
    dead_band_peak_angle: np.ndarray
    sampled_peak: np.ndarray
    model_index: np.ndarray
    energy: EnergyModel | None
    least_peak_force: np.ndarray
    min_passing_speed: np.ndarray
    effort_peak_force: np.ndarray
    masses: Masses
    power: np.ndarray
    rocker_rate: np.ndarray
    grip_speed: np.ndarray
    stroke: np.ndarray
    grip_height: tuple[np.ndarray, np.ndarray] | None
    link_energy_share: np.ndarray | None
    verdict: Verdict | None
    water: Water | None = None

    def __len__(self) -> int:
        return int(np.size(self.feasible))

    @property
    def energy_decides(self) -> np.ndarray:
        """True where an energy model (the flywheel or full dynamics) decides."""
        return self.model_index > 0

    @property
    def peak_force(self) -> np.ndarray:
        """The peak force that decides the verdict [N]: the energy model's, else the dead-band peak."""
        return np.where(self.energy_decides, self.least_peak_force, self.dead_band_peak_force)

    @property
    def model(self) -> np.ndarray:
        """The deciding model's key per design (:data:`pumplink.models.ORDER`)."""
        return np.asarray(ORDER, dtype=object)[self.model_index]

    @property
    def transmission_angle(self) -> np.ndarray:
        """The effective smallest transmission angle min(γmin, 180° − γmax) [rad]."""
        syn = self.synthesis
        return np.minimum(syn.transmission_min, np.pi - np.asarray(syn.transmission_max))

    @property
    def energy_band(self) -> np.ndarray:
        """W = J ω̄² δ [J] (NaN without inertia)."""
        return np.full(len(self), np.nan) if self.energy is None else self.energy.band


@dataclass(frozen=True)
class PistonEvaluation:
    """Every quantity the verdict and the renderers need, for piston pumps (arrays over designs)."""

    designs: PistonDesigns
    feasible: np.ndarray  # the crank turns fully: rod > crank + |offset|
    stroke: np.ndarray  # [m]
    time_ratio: np.ndarray  # [-]
    largest_pressure_angle: np.ndarray  # [rad]
    mean_force: np.ndarray  # [N] (Eq. P.3)
    quasi_static_peak: np.ndarray  # [N]
    quasi_static_peak_angle: np.ndarray  # [rad]
    model_index: np.ndarray  # 0 quasi-static, 1 flywheel
    energy_band: np.ndarray  # W = J ω² δ [J] (NaN without a flywheel)
    least_peak_force: np.ndarray  # the flywheel's Fp* [N] (Eq. P.4; NaN without one)
    power: np.ndarray  # F_load H ω / 2π [W]
    verdict: Verdict | None
    water: Water | None = None

    def __len__(self) -> int:
        return int(np.size(self.feasible))

    @property
    def peak_force(self) -> np.ndarray:
        """The peak force that decides the verdict [N]."""
        return np.where(self.model_index > 0, self.least_peak_force, self.quasi_static_peak)

    @property
    def model(self) -> np.ndarray:
        return np.asarray(ORDER, dtype=object)[self.model_index]


# ----------------------------------------------------------------------------- the evaluation
def evaluate(
    designs: PumpDesigns | PistonDesigns,
    model: str | None = None,
    *,
    judge: bool = True,
    dead_band_peak: bool = True,
    peak: bool = True,
    passing_speed: bool = True,
    effort: bool = False,
    arm_energy: bool = False,
    samples: int = 0,
    progress=None,
    parts_of_failing: bool = True,
) -> Evaluation | PistonEvaluation:
    """Judge designs: every quantity of the verdict, and the verdict.

    Parameters
    ----------
    designs : rope pumps (:class:`PumpDesigns`) or piston pumps (:class:`PistonDesigns`).
    model : a model key to decide every design that gives inertia (``--model``); default the least
        model that is enough, per design (docs/models.md §3).
    judge : False to leave the verdict out (a search that needs only the forces).
    dead_band_peak : the quasi-static peak outside the dead bands for every feasible design (it is
        reported beside an energy model's); False: only where it decides.
    peak : False for no peak force at all (a search on the mean force).
    passing_speed : the flywheel's slowest passing speed where it decides.
    effort : the operator's least peak effort (the hand force plus their arms, full dynamics)
        wherever the wheel's inertia is given.
    arm_energy : the arms' kinetic energy in the model-choice report even when they are not in the
        verdict (they always are where ``operator.arms_in_verdict``).
    samples : crank samples per revolution for :attr:`Evaluation.sampled_peak` (0: none);
        ``progress`` is given the fraction of that sweep done (one design at a time).
    parts_of_failing : False to judge the spec's ``[parts]`` only on designs no other check fails
        (a search, which drops failing designs anyway; the part checks are the costly ones, about
        50 ms a design): the others' part values are NaN, which fails, as they do already.
    """
    if isinstance(designs, PistonDesigns):
        return _evaluate_piston(designs, judge)
    n, c = _columns(designs)
    built = designs.linkage
    if built is not None:  # the linkage as built (a workshop's holes): analysed, not re-synthesised
        _, params = per_design(built, c["wheel_torque"])
        built = FourBar(*params[:7])
        syn = analyse(built)
        c["handle"], c["rocker"] = built.handle, built.rocker
    else:
        syn = synthesize(c["L1"], c["D1"], c["b"], c["rocker"], c["swing"], c["handle"])
    feasible = np.asarray(syn.feasible, bool)
    lk = syn.linkage
    mw, speed, band, limit = c["wheel_torque"], c["speed"], c["dead_band"], c["force_limit"]
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    nan = np.full(n, np.nan)
    ok = np.nonzero(feasible)[0]
    if built is None:
        stroke = grip_stroke(c["handle"], c["swing"])
    else:
        stroke = built_grip(
            0.0, built.pivot_y, built.handle, syn.rocker_angle_extended, syn.rocker_angle_folded
        )[0]
    mean, sampled = nan.copy(), nan.copy()
    qs_peak, qs_angle = nan.copy(), nan.copy()
    rate = nan.copy()
    sub = lk.take(ok)
    if ok.size:
        mean[ok] = _qs.mean_force(mw[ok], stroke[ok])
        if judge:  # the grip's peak speed, a check of the verdict
            rate[ok] = _peak_rocker_rate(sub)
        if samples:
            for s0 in range(0, ok.size, SUB_DESIGNS):  # cache-sized blocks of designs
                s = ok[s0 : s0 + SUB_DESIGNS]
                sampled[s] = _qs.sampled_peak(
                    lk.take(s), samples, mw[s], dce[s], dcf[s], band[s], progress=progress
                )

    # the energy models where the inertia is given: the least one that is enough, or the one asked for
    fly = ~np.isnan(c["inertia"])
    j, delta = c["inertia"], c["speed_fluctuation"]
    index = np.zeros(n, int)
    em = None
    least, passing, effort_force = nan.copy(), nan.copy(), nan.copy()
    # the links' masses, with the arms at the grip where the verdict takes them (``masses``); the
    # model choice also sizes the arms when a report asks (their energy is not in its force then)
    masses = _load.link_masses(
        syn.coupler_length,
        c["handle"],
        c["rocker"],
        c["mass_per_length"],
        c["coupler_mass"],
        c["handle_mass"],
        c["arm_mass"] if designs.arms_in_verdict else 0.0,
    )
    sized = (
        masses
        if designs.arms_in_verdict or not arm_energy
        else Masses(masses.coupler, masses.handle, c["arm_mass"])
    )
    if fly.any() and peak:
        em = energy_model(
            lk,
            dce,
            dcf,
            mw,
            j,
            speed,
            delta,
            sized,
            designs.arms_in_verdict,
            forced=model,
            solve=fly & feasible,
        )
        index = np.where(fly, em.index, 0)
        least = np.where(fly & feasible, em.peak_force, np.nan)
        flywheel = np.nonzero(fly & feasible & (index == ORDER.index(FLYWHEEL)))[0]
        if passing_speed and flywheel.size:
            from pumplink.models import flywheel as _fw

            passing[flywheel] = _fw.min_passing_speed(
                lk.take(flywheel), dce[flywheel], dcf[flywheel], mw[flywheel], limit[flywheel],
                j[flywheel], delta[flywheel],
            )  # fmt: skip
        rows = np.nonzero(fly & feasible)[0]
        if effort and rows.size:  # the hand force plus accelerating and lifting the operator's arms
            arms = Masses(
                *(np.broadcast_to(m, (n,))[rows] for m in (masses.coupler, masses.handle, c["arm_mass"]))
            )
            cond = Conditions(speed[rows], band[rows], j[rows], delta[rows], arms)
            effort_force[rows] = MODELS[DYNAMICS].peak_force(
                lk.take(rows), dce[rows], dcf[rows], mw[rows], cond
            )
    energy = index > 0
    todo = feasible & (dead_band_peak | ~energy) & peak
    if todo.any():
        r = np.nonzero(todo)[0]
        qs_peak[r], qs_angle[r] = _qs.dead_band_peak_force(lk.take(r), dce[r], dcf[r], band[r], mw[r])
    share = None
    if em is not None and (index == ORDER.index(FLYWHEEL)).any():
        # the flywheel's neglected link energy: a check of the flywheel model only (0 elsewhere)
        with np.errstate(divide="ignore", invalid="ignore"):
            share = np.where(em.band > 0, 100.0 * em.link_energy / em.band, np.inf)
        share = np.where(index == ORDER.index(FLYWHEEL), share, 0.0)
    grip_speed = _load.grip_speed(rate, speed, c["handle"], np.where(energy, delta, 0.0))
    axle = designs.axle_height
    if axle is None:
        heights = None
    elif built is None:
        heights = grip_heights(axle, c["D1"], c["handle"], c["swing"])
    else:
        ends = (syn.rocker_angle_extended, syn.rocker_angle_folded)
        heights = built_grip(axle, built.pivot_y, built.handle, *ends)[1:]
    power = mw * speed
    verdict = None
    if judge:
        mu = np.minimum(syn.transmission_min, np.pi - np.asarray(syn.transmission_max))
        judged = partial(
            assess,
            feasible,
            mean,
            np.where(energy, least, qs_peak),
            limit,
            link_energy_share=share,
            transmission_angle=np.degrees(mu),
            power=power,
            grip_speed=grip_speed,
            stroke=stroke,
            grip_height=heights,
            axle_height=axle,
            power_limits=(c["sustained_power"], c["hour_power"]),
            grip_speed_limits=(c["grip_speed_warn"], c["grip_speed_fail"]),
            grip_height_range=(c["grip_height_min"], c["grip_height_max"]),
        )
        if designs.parts is None:
            verdict = judged()
        else:  # the part checks need each design's loads over its cycle: the costly checks last
            judge_parts = feasible
            if not parts_of_failing:
                judge_parts = feasible & (np.atleast_1d(judged().level) < FAIL)
            verdict = judged(**_part_checks(designs, c, syn, index, least, masses, judge_parts))
    # Q = η_v (π d²/4) ω̄ r_w: the rope moves with the wheel rim (docs/water.md §1)
    flow = _water_kernels.rope_pump_flow(
        c["pipe_diameter"], speed, c["wheel_radius"], c["volumetric_efficiency"]
    )
    water = _water(
        flow,
        c["head"],
        power,
        c["sustained_power"],
        c["force_efficiency"],
        c["volumetric_efficiency"],
        c["hours_per_day"],
        c["litres_per_person_day"],
    )
    return Evaluation(
        designs,
        syn,
        feasible,
        mean,
        qs_peak,
        qs_angle,
        sampled,
        index,
        em,
        least,
        passing,
        effort_force,
        masses,
        power,
        rate,
        grip_speed,
        stroke,
        heights,
        share,
        verdict,
        water,
    )


def _part_checks(designs, c, syn, index, least, masses, feasible) -> dict:
    """The verdict's part checks (docs/workshop.md §2), design by design: the loads under the
    model that decided (:mod:`pumplink.evaluate.parts`) against the spec's ``[parts]``, where
    ``feasible`` (NaN elsewhere)."""
    from pumplink.evaluate import parts as _parts

    n = feasible.size
    out = {k: np.full(n, np.nan) for k in ("pin_pressure", "handle_fatigue", "crank_fatigue")}
    coupler, handle = (np.broadcast_to(np.asarray(v, float), (n,)) for v in (masses.coupler, masses.handle))
    model = np.asarray(index, int)
    wheel_mass = np.broadcast_to(np.asarray(c["wheel_mass"], float), (n,))
    weight = np.where(np.isnan(wheel_mass), 0.0, wheel_mass) * GRAVITY
    # the quasi-static designs all at once, in blocks that bound the peak search's memory
    quasi = np.nonzero(feasible & (model == 0))[0]
    for block in np.array_split(quasi, -(-quasi.size // PART_BLOCK)) if quasi.size else ():
        col = {k: np.broadcast_to(np.asarray(c[k], float), (n,))[block]
               for k in ("dead_band", "wheel_torque", "rope_force")}  # fmt: skip
        st = _parts.quasi_static_strength(
            FourBar(*(np.broadcast_to(np.asarray(v, float), (n,))[block] for v in syn.linkage.parameters)),
            syn.dead_centre_extended[block], syn.dead_centre_folded[block], col["dead_band"],
            col["wheel_torque"], col["rope_force"], weight[block],
            PartSizes(*(np.broadcast_to(np.asarray(getattr(designs.parts, k), float), (n,))[block]
                        for k in PART_KEYS)),
        )  # fmt: skip
        out["pin_pressure"][block] = st.pin_pressure / 1e6  # [MPa]
        out["handle_fatigue"][block] = st.handle.safety
        out["crank_fatigue"][block] = st.crank.safety
    for i in np.nonzero(feasible & (model != 0))[0].tolist():
        lk = FourBar(*(float(np.asarray(v)[i]) for v in syn.linkage.parameters))
        dce, dcf = float(syn.dead_centre_extended[i]), float(syn.dead_centre_folded[i])
        key = ORDER[int(index[i])]
        if key != ORDER[0] and not np.isfinite(least[i]):
            continue  # no finite force keeps the wheel turning: the peak-force check fails it
        links = Masses(coupler[i], handle[i], 0.0)  # the hand is the operator's, not a part
        sc = _parts.scene(lk, dce, dcf, c["wheel_torque"][i], c["inertia"][i], links, c["speed"][i],
                          c["speed_fluctuation"][i], float(least[i]), key)  # fmt: skip
        loads = _parts.part_loads(
            lk, dce, dcf, c["dead_band"][i], c["wheel_torque"][i], key, sc, c["rope_force"][i], weight[i]
        )
        st = _parts.strength(loads, designs.parts.design(i))
        out["pin_pressure"][i] = st.pin_pressure / 1e6  # [MPa]
        out["handle_fatigue"][i] = st.handle.safety
        out["crank_fatigue"][i] = st.crank.safety
    return out


#: Designs a block of the quasi-static part checks holds (its peak search holds ~1,500 crank angles
#: and ~30 arrays a design: ~100 MB a block).
PART_BLOCK = 256


#: Odd 64-bit multipliers that hash a design's seven four-bar parameters (their bits) to one word.
_HASH = np.array([0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9, 0xD6E8FEB86659FD93,
                  0xFF51AFD7ED558CCD, 0xC4CEB9FE1A85EC53, 0x94D049BB133111EB], dtype=np.uint64)  # fmt: skip


def _peak_rocker_rate(lk: FourBar) -> np.ndarray:
    """:func:`pumplink.mechanisms.fourbar.peak_rocker_rate` of designs (1-D arrays), solved once
    per distinct linkage: it depends on the geometry alone, and a grid that varies the load or
    the speed repeats each geometry many times (the same values, computed once).  Distinct
    linkages are found by a hash of their parameters' bits, checked row by row."""
    geom = np.ascontiguousarray(np.stack([np.asarray(v, float) for v in lk.parameters], axis=1))
    if geom.shape[0] < 2:
        return np.atleast_1d(peak_rocker_rate(lk))
    with np.errstate(over="ignore"):
        key = (geom.view(np.uint64) * _HASH).sum(axis=1, dtype=np.uint64)
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    if first.size == geom.shape[0] or not np.array_equal(geom[first][inverse], geom):
        return peak_rocker_rate(lk)  # all distinct, or a hash collision: every design on its own
    return peak_rocker_rate(FourBar(*geom[first].T))[inverse]


def _evaluate_piston(designs: PistonDesigns, judge: bool) -> PistonEvaluation:
    """:func:`evaluate` for piston pumps (docs/piston-pump.md); the crank-slider's kernels take
    one design at a time, so the designs are solved in turn."""
    from pumplink.models import flywheel as _fw
    from pumplink.models import piston as _pm

    n, c = _columns(designs)
    r, rod, e, handle, load = c["crank"], c["rod"], c["offset"], c["handle"], c["load_force"]
    feasible = np.asarray(cs.turns_fully(r, rod, e), bool)
    out = {k: np.full(n, np.nan) for k in ("stroke", "ratio", "pressure", "mean", "peak", "angle", "least")}
    band = np.where(
        np.isnan(c["inertia"]), np.nan, _fw.energy_band(c["inertia"], c["speed"], c["speed_fluctuation"])
    )
    index = np.where(np.isnan(c["inertia"]), 0, ORDER.index(FLYWHEEL))
    for i in np.nonzero(feasible)[0].tolist():
        args = (r[i], rod[i], e[i])
        out["stroke"][i] = float(cs.stroke(*args))
        out["ratio"][i] = float(cs.time_ratio(*args))
        out["pressure"][i] = float(cs.largest_pressure_angle(*args))
        out["mean"][i] = _pm.mean_force(*args, load[i], handle[i])  # Eq. (P.3)
        out["peak"][i], out["angle"][i] = _pm.quasi_static_peak(*args, load[i], handle[i])
        if index[i]:
            out["least"][i] = _pm.least_peak_force(*args, load[i], handle[i], band[i])  # Eq. (P.4)
    power = load * out["stroke"] * c["speed"] / (2.0 * math.pi)  # the work F_load H per revolution
    peak = np.where(index > 0, out["least"], out["peak"])
    verdict = None
    if judge:
        limits = (c["sustained_power"], c["hour_power"])
        verdict = assess(feasible, out["mean"], peak, c["force_limit"], power=power, power_limits=limits)
    # Q = η_v A H f for a single-acting piston (docs/water.md §1)
    flow = _water_kernels.piston_pump_flow(c["bore"], out["stroke"], c["speed"], c["volumetric_efficiency"])
    water = _water(
        flow,
        c["head"],
        power,
        c["sustained_power"],
        c["force_efficiency"],
        c["volumetric_efficiency"],
        c["hours_per_day"],
        c["litres_per_person_day"],
    )
    return PistonEvaluation(
        designs,
        feasible,
        out["stroke"],
        out["ratio"],
        out["pressure"],
        out["mean"],
        out["peak"],
        out["angle"],
        index,
        band,
        out["least"],
        power,
        verdict,
        water,
    )


__all__ = [
    "INERTIA_KEYS",
    "PART_KEYS",
    "PartSizes",
    "MODEL_LABELS",
    "Evaluation",
    "PistonDesigns",
    "PistonEvaluation",
    "PumpDesigns",
    "evaluate",
    "piston_designs",
    "pump_designs",
]

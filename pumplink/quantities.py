"""The catalogue of reported quantities: every number the evaluation reports, listed once.

Data outside the layers (as :mod:`pumplink.constants`): the evaluation fills the values, the views
read them through this table by their attribute paths, and neither imports the other for it.

Each :class:`Quantity` names where its value lives on an :class:`~pumplink.evaluate.Evaluation`
(SI units), the unit it is shown in and the factor to it, its words, its key in ``pumplink force
--format json`` and its column in batch CSV/JSON/Parquet (None where it is not there), and the
verdict check it feeds.  Every view iterates over :data:`CATALOGUE` instead of keeping a list of
its own: force's JSON and table, batch's rows, size, the report and docs/json.md (whose tables a
test holds to it).  A new quantity is a kernel, a stage line and a row here.

Headline quantities are a design's main figures: ``pumplink size`` and the report list them.
Those with a ``line`` are printed on a line of their own under the checks of ``pumplink force``
and in ``size``'s table (where the value is known); the others are worded in the views'
sentences (the water's, for one).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import EXTREMUM_ARGUMENT

#: The kick-back's travel is a closed form at a refined stop angle (flat there: to rounding), or, where
#: the run back ends early, a march of RK4 (docs/workshop.md §3): settled to this share.
KICK_BACK_RTOL = 1e-6

#: Factors from SI to the units shown: radians to degrees, m³/s to l/min and to m³/h.
DEGREES, L_PER_MIN, M3_PER_H = 180.0 / np.pi, 60_000.0, 3_600.0


@dataclass(frozen=True)
class Quantity:
    """One reported quantity.

    name : its name in words without spaces (unique);  source : the dotted attribute path of its
    SI value on an evaluation (``water.flow``);  unit : the unit shown, ``scale`` the factor from
    SI to it;  label : words for tables;  json : key in force's JSON (None: not there);
    column : batch column (None: not there);  check : the verdict check it is the value of;
    headline : one of a design's main figures (size's JSON, the report);  line : its line in force's
    and size's tables, a format string given the value in the unit shown (None: no line).
    rtol : the relative share to which an iterative method settles it (None: to rounding); the
    views keep the digits it determines (pumplink/output/precision.py).
    """

    name: str
    source: str
    unit: str
    label: str
    json: str | None = None
    column: str | None = None
    scale: float = 1.0
    check: str | None = None
    headline: bool = False
    line: str | None = None
    rtol: float | None = None


Q = Quantity
#: Every reported quantity, in batch-column order.
CATALOGUE = (
    Q("frame_length", "synthesis.frame_length", "m", "frame O2O4", column="frame_length"),
    Q("crank_length", "synthesis.crank_length", "m", "crank O2A", column="crank_length"),
    Q("coupler_length", "synthesis.coupler_length", "m", "coupler AB", column="coupler_length"),
    Q("time_ratio", "synthesis.time_ratio", "", "time ratio K", column="time_ratio"),
    Q("transmission_min", "synthesis.transmission_min", "deg", "smallest transmission angle",
      column="transmission_min_deg", scale=DEGREES),
    Q("transmission_max", "synthesis.transmission_max", "deg", "largest transmission angle",
      column="transmission_max_deg", scale=DEGREES),
    Q("wheel_torque", "designs.wheel_torque", "N·m", "wheel torque Mw", json="wheel_torque_Nm"),
    Q("mean_force", "mean_force", "N", "mean force", "mean_force_N", "mean_force_N", check="mean_force"),
    Q("peak_force", "peak_force", "N", "peak force (the deciding model's)", "peak_force_N",
      "peak_force_N", check="peak_force"),
    Q("dead_band_peak_force", "dead_band_peak_force", "N", "quasi-static peak outside the dead bands",
      "dead_band_peak_force_N", "dead_band_peak_force_N"),
    Q("dead_band_peak_angle", "dead_band_peak_angle", "deg", "crank angle of the quasi-static peak",
      "dead_band_peak_crank_deg", scale=DEGREES, rtol=EXTREMUM_ARGUMENT),
    Q("sampled_peak", "sampled_peak", "N", "sampled peak", "sampled_peak_force_N", "sampled_peak_force_N"),
    Q("power", "power", "W", "operator power", "power_W", "power_W", check="power", headline=True),
    Q("flow", "water.flow", "l/min", "flow", "flow_l_min", "flow_l_min", scale=L_PER_MIN, headline=True),
    Q("flow_m3_h", "water.flow", "m³/h", "flow", "flow_m3_h", scale=M3_PER_H, headline=True),
    Q("water_power", "water.water_power", "W", "water power", "water_power_W", "water_power_W"),
    Q("pump_efficiency", "water.efficiency", "", "water power / operator power", "pump_efficiency",
      "pump_efficiency"),
    Q("power_limited_flow", "water.limit", "l/min", "the flow the operator's sustained power lifts",
      "power_limited_flow_l_min", scale=L_PER_MIN, headline=True),
    Q("flow_share", "water.share", "", "share of that flow", "flow_share", "flow_share", headline=True),
    Q("people_served", "water.people", "", "people served", "people_served", "people_served",
      headline=True),
    Q("fill_time_20l", "water.fill_time", "s", "time to fill a 20-litre container", "fill_time_20l_s",
      "fill_time_20l_s", headline=True, line="time to fill a 20-litre container: {:.0f} s"),
    Q("fill_turns_20l", "water.fill_turns", "", "crank turns to fill a 20-litre container",
      "fill_turns_20l", "fill_turns_20l", headline=True, line="crank turns to fill it: {:.0f}"),
    Q("all_day_flow", "water.all_day_flow", "l/min", "flow all day, at the sustained power",
      "all_day_flow_l_min", "all_day_flow_l_min", scale=L_PER_MIN, headline=True),
    Q("all_day_cadence", "water.all_day_cadence", "/min", "cadence all day", "all_day_cadence_per_min",
      headline=True),
    Q("filling_power", "water.filling_power", "W", "power while filling containers", "filling_power_W",
      headline=True),
    Q("filling_flow", "water.filling_flow", "l/min", "flow filling containers, at the field's power",
      "filling_flow_l_min", "filling_flow_l_min", scale=L_PER_MIN, headline=True),
    Q("filling_cadence", "water.filling_cadence", "/min", "cadence filling containers",
      "filling_cadence_per_min", headline=True),
    Q("force_efficiency", "water.force_efficiency", "", "force efficiency used", "force_efficiency",
      "force_efficiency"),
    Q("volumetric_efficiency", "water.volumetric_efficiency", "", "volumetric efficiency used",
      "volumetric_efficiency", "volumetric_efficiency"),
    Q("model_force_efficiency", "water.model_force_efficiency", "", "loss model's force efficiency",
      "loss_model_force_efficiency"),
    Q("model_volumetric_efficiency", "water.model_volumetric_efficiency", "",
      "loss model's volumetric efficiency", "loss_model_volumetric_efficiency"),
    Q("cadence", "cadence", "/min", "cadence (wheel turns a minute)", "cadence_per_min", "cadence_per_min",
      check="cadence", headline=True),
    Q("rope_speed", "rope_speed", "m/s", "rope speed", "rope_speed_m_s", "rope_speed_m_s", check="rope_speed",
      headline=True),
    Q("column_fill_turns", "service.column_fill_turns", "", "crank turns before water reaches the spout",
      "column_fill_turns", "column_fill_turns", headline=True,
      line="crank turns before water reaches the spout (an empty rising main): {:.1f}"),
    Q("column_fill_time", "service.column_fill_time", "s", "time before water reaches the spout",
      "column_fill_time_s", "column_fill_time_s"),
    Q("kick_back", "service.kick_back", "m", "grip's kick-back, let go at the worst moment", "kick_back_m",
      "kick_back_m", check="kick_back", rtol=KICK_BACK_RTOL),
    Q("holding_torque_required", "service.holding_torque_required", "N·m",
      "torque a ratchet must hold (the water column's)", "holding_torque_required_Nm",
      "holding_torque_required_Nm", headline=True,
      line="a ratchet must hold {:.2f} N·m (the water column's ρ·g·H·(π·d²/4)·r_w)"),
    Q("holding_torque", "service.holding_torque", "N·m", "the ratchet's holding torque", "holding_torque_Nm",
      "holding_torque_Nm", check="holding_torque"),
    Q("holding_torque_margin", "service.holding_torque_margin", "N·m",
      "the ratchet's torque less the column's", "holding_torque_margin_Nm", "holding_torque_margin_Nm"),
    Q("crank_turns_per_day", "service.turns_per_day", "", "crank turns a day", "crank_turns_per_day",
      "crank_turns_per_day"),
    Q("crank_turns_per_year", "service.turns_per_year", "", "crank turns a year", "crank_turns_per_year",
      "crank_turns_per_year"),
    Q("pin_wear", "service.pin_wear", "mm", "play the worst pin wears open in 6 million turns",
      "pin_wear_6m_turns_mm", "pin_wear_6m_turns_mm", scale=1000.0, check="pin_wear"),
    Q("pin_life_turns", "service.pin_life_turns", "", "crank turns until the pins wear their allowance",
      "pin_life_turns", "pin_life_turns"),
    Q("pin_life_years", "service.pin_life_years", "years", "years until the pins wear their allowance",
      "pin_life_years", "pin_life_years", headline=True,
      line="pins and bushes wear their allowed play in {:.2g} years of the use"),
    Q("years_to_6m_turns", "service.years_to_endurance", "years", "years of the use to 6 million turns",
      "years_to_6m_turns", "years_to_6m_turns"),
    Q("endurance_test_hours", "service.endurance_hours", "h",
      "endurance test: hours to 6 million turns at the design cadence", "endurance_test_h",
      "endurance_test_h", headline=True,
      line="endurance test: 6 million turns at the design cadence take {:,.0f} h"),
    Q("grip_speed", "grip_speed", "m/s", "peak grip speed", column="grip_speed_m_s", check="grip_speed"),
    Q("stroke", "stroke", "m", "grip stroke", column="stroke_m", check="stroke"),
    Q("force_limit", "designs.force_limit", "N", "force limit", "force_limit_N", "force_limit_N"),
    Q("inertia", "inertia", "kg·m²", "inertia J", "inertia_kg_m2", "inertia_kg_m2"),
    Q("speed_fluctuation", "energy_speed_fluctuation", "", "speed fluctuation δ", "speed_fluctuation",
      "speed_fluctuation"),
    Q("energy_band", "energy_band", "J", "energy band W = J ω̄² δ", "energy_band_J"),
    Q("least_peak_force", "least_peak_force", "N", "least peak force of the energy model",
      "least_peak_force_N", "least_peak_force_N"),
    Q("min_passing_speed", "min_passing_speed", "deg/s", "slowest passing mean speed",
      "min_passing_speed_deg_s", "min_passing_speed_deg_s", scale=DEGREES),
    Q("link_energy", "energy.link_energy", "J", "links' largest kinetic energy", "link_kinetic_energy_J"),
    Q("link_weight", "energy.link_weight", "J", "range of the links' potential energy", "link_weight_J"),
    Q("arm_energy", "energy.arm_energy", "J", "arms' largest kinetic energy", "arm_kinetic_energy_J"),
    Q("effort_peak_force", "effort_peak_force", "N", "least peak effort, hand + arms", "effort_peak_force_N"),
)  # fmt: skip
del Q
BY_NAME = {q.name: q for q in CATALOGUE}


def values(evaluation, quantity: Quantity) -> np.ndarray:
    """The quantity's values over the evaluation's designs, in the unit shown (NaN where it has no
    value: a stage that did not run, or a group such as the energy model that is absent)."""
    n = len(evaluation)
    x = evaluation
    for part in quantity.source.split("."):
        x = getattr(x, part, None)
        if x is None:
            return np.full(n, np.nan)
    return np.broadcast_to(np.asarray(x, float), (n,)) * quantity.scale


def json_items(evaluation, i: int = 0) -> dict[str, tuple[Quantity, float]]:
    """Design ``i``'s quantities that force's JSON holds, by key, with their values in the unit
    shown (NaN kept)."""
    return {q.json: (q, float(values(evaluation, q)[i])) for q in CATALOGUE if q.json is not None}


def columns(evaluation) -> dict[str, np.ndarray]:
    """The batch's numeric columns of the evaluation's designs, by column, in the units shown."""
    return {q.column: values(evaluation, q) for q in CATALOGUE if q.column is not None}


def headline_items(evaluation, i: int = 0) -> dict[str, float]:
    """Design ``i``'s headline quantities by JSON key, in the unit shown (NaN kept)."""
    return {q.json: float(values(evaluation, q)[i]) for q in CATALOGUE if q.headline}


def lines(evaluation, i: int = 0) -> list[str]:
    """Design ``i``'s quantities printed on lines of their own (those known), as text."""
    out = []
    for q in CATALOGUE:
        if q.line is not None:
            v = float(values(evaluation, q)[i])
            if np.isfinite(v):
                out.append(q.line.format(v))
    return out

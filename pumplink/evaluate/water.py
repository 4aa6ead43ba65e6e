"""The evaluation's water stage: what a design delivers and what its operator could lift
(docs/water.md), for rope pumps and piston pumps alike.

:class:`Water` is the group of water quantities (arrays over designs, NaN where the spec gives a
rope force instead of a head and a pipe); :func:`water` fills it from the flow and the columns it
is judged against, with the kernels of :mod:`pumplink.models.water`.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from pumplink.constants import DEFAULT_EFFICIENCY, DEFAULT_VOLUMETRIC_EFFICIENCY, LOSS_SHARE
from pumplink.mechanisms.fourbar_kernel import alike_designs
from pumplink.models import losses as _losses
from pumplink.models import water as _kernels


def one_design(group, i: int, n: tuple, dtype=None) -> dict:
    """The fields of ``group`` (a dataclass of arrays over ``n`` designs, a value broadcast) for
    design ``i`` alone, as Python scalars (``dtype``: each read as it first)."""
    return {f.name: np.broadcast_to(np.asarray(getattr(group, f.name), dtype), n)[i].item()
            for f in fields(group)}  # fmt: skip


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
    fill_time [s], fill_turns [-]: to fill a 20-litre container, and the wheel's turns meanwhile.
    all_day_flow [m³/s], all_day_cadence [1/min]: the flow and the cadence at which this pump asks
        the operator for their sustained power (the all-day duty);  filling_power [W],
        filling_flow [m³/s], filling_cadence [1/min]: the same while filling containers, at the
        power the field's discharges imply (docs/water.md §6).
    losses : which efficiencies (index into :data:`pumplink.evaluate.designs.LOSSES`);
    force_efficiency, volumetric_efficiency : those used [-];  model_force_efficiency,
        model_volumetric_efficiency : the loss model's at the design's rope speed [-] (NaN for a
        piston pump).
    """

    flow: np.ndarray
    water_power: np.ndarray
    efficiency: np.ndarray
    limit: np.ndarray
    share: np.ndarray
    people: np.ndarray
    head: np.ndarray
    sustained_power: np.ndarray
    fill_time: np.ndarray
    fill_turns: np.ndarray
    all_day_flow: np.ndarray
    all_day_cadence: np.ndarray
    filling_power: np.ndarray
    filling_flow: np.ndarray
    filling_cadence: np.ndarray
    losses: np.ndarray
    force_efficiency: np.ndarray
    volumetric_efficiency: np.ndarray
    model_force_efficiency: np.ndarray
    model_volumetric_efficiency: np.ndarray

    def design(self, i: int) -> Water:
        """The water of design ``i`` alone (floats)."""
        return Water(**one_design(self, i, np.shape(self.flow), float))


#: The design columns :func:`water` reads (a piston pump's lack the rope pump's own).
WATER_KEYS = ("head", "speed", "pipe_diameter", "wheel_radius", "sustained_power", "filling_power",
              "force_efficiency", "volumetric_efficiency", "model_force_efficiency",
              "model_volumetric_efficiency", "losses", "piston_clearance", "piston_spacing", "hours_per_day",
              "litres_per_person_day")  # fmt: skip


def water(flow, columns: dict, operator_power) -> Water:
    """:class:`Water` from the flow [m³/s], the operator's power Mw ω̄ [W] and the design columns
    (head, the operator's sustained power, the pump's efficiencies, how the water is used)."""
    c = columns
    water_power = _kernels.water_power(flow, c["head"])  # Eq. (W.3)
    limit = _kernels.power_limited_flow(
        c["sustained_power"], c["head"], c["force_efficiency"], c["volumetric_efficiency"]
    )  # Eq. (W.5)
    fill_time, fill_turns = _kernels.fill(_kernels.CONTAINER_VOLUME, flow, c["speed"])  # Eq. (W.7)
    filling = c.get("filling_power", np.nan)
    all_day = duty(c["sustained_power"], flow, c, operator_power)
    fill_duty = duty(filling, flow, c, operator_power)
    nan = np.full(np.shape(flow), np.nan)
    return Water(
        flow=flow,
        water_power=water_power,
        efficiency=_kernels.overall_efficiency(water_power, operator_power),  # Eq. (W.4)
        limit=limit,
        share=_kernels.flow_share(flow, limit),
        people=_kernels.people_served(flow, c["hours_per_day"], c["litres_per_person_day"]),  # Eq. (W.6)
        head=c["head"],
        sustained_power=c["sustained_power"],
        fill_time=fill_time,
        fill_turns=fill_turns,
        all_day_flow=all_day[0],
        all_day_cadence=all_day[1],
        filling_power=filling,
        filling_flow=fill_duty[0],
        filling_cadence=fill_duty[1],
        losses=c.get("losses", nan),
        force_efficiency=c["force_efficiency"],
        volumetric_efficiency=c["volumetric_efficiency"],
        model_force_efficiency=c.get("model_force_efficiency", nan),
        model_volumetric_efficiency=c.get("model_volumetric_efficiency", nan),
    )


def duty(power, flow, columns: dict, operator_power):
    """The flow [m³/s] and the cadence [turns/min] at which the pump asks the operator for ``power``
    [W] (docs/water.md §6), by the rule of docs/water.md §2a at the duty's own rope speed: with the
    constant efficiencies the torque is constant, so flow and power scale with the speed; where the
    loss model's overall efficiency at that speed is more than the share off, the rope speed solves
    P = ρ g H A v / η_f(v) (:func:`pumplink.models.losses.duty_rope_speed`) and the flow is
    η_v(v) A v.  A spec's own efficiencies (``losses`` 2) and a piston pump's are constants."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # no power, no duty: inf, NaN
        return _duty(power, flow, columns, operator_power)


def _duty(power, flow, c: dict, operator_power):
    ratio = np.asarray(power, float) / np.asarray(operator_power, float)
    speed = c["speed"] * ratio
    out_flow = np.asarray(flow, float) * ratio
    if "losses" not in c:
        return out_flow, speed / (2.0 * np.pi) * 60.0
    d, head, r_w = c["pipe_diameter"], c["head"], c["wheel_radius"]
    clearance, spacing, area = c["piston_clearance"], c["piston_spacing"], _kernels.pipe_area(d)
    # the constants' rope speed, and the loss model there (the designs' rule, docs/water.md §2a)
    v = np.asarray(power, float) * DEFAULT_EFFICIENCY / _kernels.water_power(area, head)
    model = _losses.overall_efficiency(d, v, head, clearance=clearance, spacing=spacing)
    decides = ~(_losses.off_by(DEFAULT_EFFICIENCY * DEFAULT_VOLUMETRIC_EFFICIENCY, model) <= LOSS_SHARE)
    eta_v = np.full(np.shape(v), DEFAULT_VOLUMETRIC_EFFICIENCY)
    if np.any(decides):
        solved = _duty_rope_speed(power, head, d)
        v = np.where(decides, solved, v)
        eta_v = np.where(decides, _losses.volumetric_efficiency(d, v, head, clearance, spacing), eta_v)
    own = np.asarray(c["losses"]) == 2  # the spec's efficiencies: constants, the torque is
    out_flow = np.where(own, out_flow, eta_v * area * v)
    speed = np.where(own, speed, v / r_w)
    return out_flow, speed / (2.0 * np.pi) * 60.0


def _duty_rope_speed(power, head, pipe_diameter):
    """:func:`pumplink.models.losses.duty_rope_speed` with the loss model's force efficiency, solved
    once per distinct (power, head, bore): a grid's variants that differ in the linkage or the wheel
    share it (each speed from the same steps on its own inputs, so the same values)."""
    p, h, d = np.broadcast_arrays(*(np.asarray(v, float) for v in (power, head, pipe_diameter)))
    first, kind = alike_designs(p, h, d)  # (None, None) for one design or scalars
    if first is not None:
        p, h, d = p[first], h[first], d[first]
    solved = _losses.duty_rope_speed(p, h, d, lambda v: _losses.force_efficiency(d, v))
    return solved if first is None else solved[kind]

"""``pumplink validate``: every published one-person discharge the docs cite
(:data:`pumplink.field.DISCHARGES`), run through the one evaluation at its head, operator and duty,
against what was published (docs/water.md §6).

Each discharge is run on :data:`pumplink.field.PUMP` with the published head and the operator's
profile; the prediction is the evaluation's flow at the discharge's duty (filling containers: the
profile's filling power; all day: its sustained power), :class:`pumplink.evaluate.Water`'s
``filling_flow`` / ``all_day_flow``, with the efficiencies the loss rule chooses at that duty's rope
speed (docs/water.md §2a).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.evaluate import evaluate, pump_designs
from pumplink.field import DISCHARGES, LEFT_OUT, PUMP, TOLERANCE, Discharge
from pumplink.inputs.pump import parse_spec


@dataclass(frozen=True)
class Validated:
    """One discharge against its prediction: ``predicted`` [m³/s] at ``cadence`` [turns/min] and
    ``rope_speed`` [m/s] for ``power`` [W]; ``error`` = predicted / published − 1; ``ok`` within
    ``tolerance``."""

    discharge: Discharge
    predicted: float
    cadence: float
    rope_speed: float
    power: float
    tolerance: float

    @property
    def error(self) -> float:
        return self.predicted / self.discharge.flow - 1.0

    @property
    def ok(self) -> bool:
        return bool(abs(self.error) <= self.tolerance)


@dataclass(frozen=True)
class Validation:
    """Every discharge run, and those left out with the reason."""

    rows: tuple[Validated, ...]
    left_out: dict
    tolerance: float
    pump: str

    @property
    def passed(self) -> bool:
        return all(r.ok for r in self.rows)


def predict(d: Discharge, pump=None, filling_power: float | None = None) -> Validated:
    """The evaluation's flow for discharge ``d`` on ``pump`` (spec data), at its head, operator and
    duty; ``filling_power`` [W] replaces the profile's (a fit, ``scripts/field_fit.py``)."""
    pump = PUMP if pump is None else pump
    data = {**pump, "load": {**pump["load"], "head": d.head}}
    data["operator"] = {**pump["operator"], "profile": d.profile}
    if filling_power is not None:
        data["operator"]["filling_power"] = filling_power
    spec = parse_spec(data, source=f"the pump for {d.source}")
    w = evaluate(pump_designs(spec.values), ("water",)).water.design(0)
    flow, cadence, power = (
        (w.filling_flow, w.filling_cadence, w.filling_power)
        if d.duty == "filling"
        else (w.all_day_flow, w.all_day_cadence, w.sustained_power)
    )
    rope = cadence / 60.0 * 2.0 * np.pi * spec.wheel.radius
    return Validated(d, float(flow), float(cadence), float(rope), float(power), TOLERANCE)


def validate(discharges=None, pump=None) -> Validation:
    """Run every discharge (:func:`predict`): ``discharges`` default :data:`pumplink.field.DISCHARGES`,
    ``pump`` :data:`pumplink.field.PUMP`."""
    discharges = DISCHARGES if discharges is None else discharges
    pump = PUMP if pump is None else pump
    return Validation(tuple(predict(d, pump) for d in discharges), dict(LEFT_OUT), TOLERANCE, pump["name"])


__all__ = ["Validated", "Validation", "predict", "validate"]

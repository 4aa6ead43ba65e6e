"""The evaluation's water stage: what a design delivers and what its operator could lift
(docs/water.md), for rope pumps and piston pumps alike.

:class:`Water` is the group of water quantities (arrays over designs, NaN where the spec gives a
rope force instead of a head and a pipe); :func:`water` fills it from the flow and the columns it
is judged against, with the kernels of :mod:`pumplink.models.water`.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

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

    def design(self, i: int) -> Water:
        """The water of design ``i`` alone (floats)."""
        return Water(**one_design(self, i, np.shape(self.flow), float))


def water(flow, columns: dict, operator_power) -> Water:
    """:class:`Water` from the flow [m³/s], the operator's power Mw ω̄ [W] and the design columns
    (head, the operator's sustained power, the pump's efficiencies, how the water is used)."""
    c = columns
    water_power = _kernels.water_power(flow, c["head"])  # Eq. (W.3)
    limit = _kernels.power_limited_flow(
        c["sustained_power"], c["head"], c["force_efficiency"], c["volumetric_efficiency"]
    )  # Eq. (W.5)
    fill_time, fill_turns = _kernels.fill(_kernels.CONTAINER_VOLUME, flow, c["speed"])  # Eq. (W.7)
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
    )

"""The field's published one-person discharges of hand rope pumps, which ``pumplink validate``
reproduces through the evaluation (docs/water.md §6).

Data only, as :mod:`pumplink.profiles`: each discharge says where it was read (title, section), the
head, the flow, who pumped (an operator profile) and the duty (all published ones are for filling
containers: the power the field's figures imply, docs/water.md §6).  The figures the docs cite but
``validate`` leaves out are in :data:`LEFT_OUT`, each with the reason.

The pump: the published figures do not give the pump they were measured on, only "a hand rope
pump, if well made".  Each is run on :data:`PUMP`, the village design of
``configs/village-10m.toml`` (a 23 mm rising main, a 0.25 m wheel: the size of the 20" rims the
rope-pump manuals build wheels from, docs/physics.md §5) at the published head.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType


@dataclass(frozen=True)
class Discharge:
    """One published discharge: ``short`` its source in a word, ``source`` where it was read,
    ``quote`` what it says, ``head`` [m], ``flow`` [m³/s], ``profile`` who pumped (an operator
    profile's name), ``duty`` "filling" (filling containers) or "all day"."""

    short: str
    source: str
    quote: str
    head: float
    flow: float
    profile: str
    duty: str = "filling"


L_MIN = 1.0 / 60_000.0  # one litre per minute [m^3/s]
_AKVOPEDIA = "Akvopedia, 'Rope pump' (revision history)"
_ARRAKIS = "Arrakis, 'Hand rope pumps (continued)'"

#: The discharges ``pumplink validate`` reproduces (docs/water.md §6).
DISCHARGES = (
    Discharge(
        "Akvopedia", _AKVOPEDIA,
        "a hand rope pump, if well made, delivers 35 litres/min from 10 meters depth",
        10.0, 35.0 * L_MIN, "men",
    ),
    Discharge(
        "Akvopedia", _AKVOPEDIA, "and half of that if the well is 20 metres deep", 20.0, 17.5 * L_MIN, "men",
    ),
    Discharge(
        "Twente", "University of Twente WOT demonstration site, 'The Rope Pump'",
        "an adult can pump up about 25 liters per minute from 12 meters depth", 12.0, 25.0 * L_MIN,
        "men",
    ),
    Discharge(
        "Arrakis", _ARRAKIS,
        "when used by women and children, an output of 30 litre/minute with a pumping height of 10 m "
        "is normal",
        10.0, 30.0 * L_MIN, "women",
    ),
    Discharge(
        "Arrakis", _ARRAKIS, "when the height doubles to 20 m, the output halves to 15 l/min",
        20.0, 15.0 * L_MIN, "women",
    ),
)  # fmt: skip

#: Figures the docs cite that ``validate`` does not run, with the reason (docs/water.md §6).
LEFT_OUT = MappingProxyType(
    {
        "Practical Action, 'Hand pumps for water lifting' (p. 8): 40 l/min at depths of up to 10 m": (
            "the head is a range, not a head: 'rope pumps more commonly operate at depths of up to 10 m "
            "with a water yield of 40 litres/min'; at 10 m it is the yield of the deepest wells of the "
            "range, above which the shallower ones pump more"
        ),
        "Practical Action, 'Hand pumps for water lifting' (p. 8): 10 l/min at 35 m": (
            "not a measurement: 'at this depth the average yield is calculated as 10 litres/min'"
        ),
        "Akvopedia, 'India Mark 2 and 3': RWSN discharges at 75 W input": (
            "piston hand pumps, not rope pumps; their deep-well figures imply 98-100 % efficiency "
            "(docs/water.md §2)"
        ),
    }
)

#: The share a prediction may be off the published flow before ``pumplink validate`` fails.
TOLERANCE = 0.15

#: The pump every discharge is run on: configs/village-10m.toml's wheel, linkage and rising main
#: (a test holds them equal), without its [parts], which do not change a flow.
PUMP = MappingProxyType(
    {
        "name": "the village pump (configs/village-10m.toml)",
        "wheel": {"radius": 0.25, "mass": 10.0, "axle_height": 0.645},
        "linkage": {
            "L1": 0.464, "D1": 0.28, "b": 0.10, "rocker": 0.134, "handle": 0.899, "swing": 49.5,
            "mass_per_length": 2.407,
        },
        "load": {"head": 10.0, "pipe_diameter": 0.023},
        "operator": {"speed": 316.0, "dead_band": 20.0},
    }
)  # fmt: skip

__all__ = ["DISCHARGES", "LEFT_OUT", "PUMP", "TOLERANCE", "Discharge"]

"""Built by hand, used every day: the loads on a design's pins, crank and handle, what they mean
for the parts, and what the handle does when it is let go (``pumplink force --explain``,
docs/workshop.md).

The loads come from the model that decided (:mod:`pumplink.evaluate.parts`, the same route as
the verdict's part checks); the parts are the spec's ``[parts]``, or its defaults for information.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from pumplink.constants import GRAVITY, KICK_BACK_LIMIT_M, RATCHET_SERVICE_FACTOR
from pumplink.evaluate import (
    ORDER,
    PART_KEYS,
    PartSizes,
    column_torque,
    evaluate,
    motion,
    pin_life,
    pump_designs,
)
from pumplink.evaluate import parts as _parts
from pumplink.studies.force import ForceResult


@dataclass(frozen=True)
class Workshop:
    """The workshop's view of one design (SI units).

    loads : the peaks of the joint forces and bending moments (:class:`~pumplink.evaluate.parts.PartLoads`).
    strength : pin pressure and fatigue for ``parts`` (:class:`~pumplink.evaluate.parts.Strength`).
    parts : the sizes used;  parts_given : True when they are the spec's ``[parts]`` (then they are
        in the verdict too), False for the defaults, shown for information.
    release, release_free : the released handle with the pump's losses as friction and with none
        (:class:`pumplink.models.release.Release`), None without the wheel's inertia or a head.
    life : the pins' life with ``parts`` (:class:`PinLife`; docs/workshop.md §5), None without a
        flow (a rope force given: no turns a year from people).
    pin_pressure_limits : (warn, fail) [Pa], fatigue_limits : (warn, fail) [-]: the levels of the
        verdict's part checks (:mod:`pumplink.evaluate.parts`).
    """

    loads: Any
    strength: Any
    parts: PartSizes
    parts_given: bool
    release: Any = None
    release_free: Any = None
    life: Any = None
    pin_pressure_limits: tuple[float, float] = (_parts.PIN_PRESSURE_WARN, _parts.PIN_PRESSURE_FAIL)
    fatigue_limits: tuple[float, float] = (_parts.FATIGUE_WARN, _parts.FATIGUE_FAIL)

    @property
    def needs_brake(self) -> bool:
        """True when the released wheel runs back (the handle swings back at speed)."""
        return bool(self.release is not None and self.release.reverses)


@dataclass(frozen=True)
class PinLife:
    """The pins' life (docs/workshop.md §5): ``bush`` the material pair, ``allowance`` [m];
    ``wear`` the play opened in 6 million turns [m]; ``turns`` until the allowance is worn, ``years``
    at ``turns_per_day`` of the use."""

    bush: str
    allowance: float
    wear: float
    turns: float
    years: float
    turns_per_day: float


def _pin_life(r: ForceResult, pressure: float, pin_diameter: float) -> PinLife | None:
    """The pins' life at the worst joint's ``pressure`` [Pa] with the spec's parts or their defaults."""
    sv = r.evaluation.service
    if sv is None:
        return None
    sv = sv.design(0)
    shop = r.design.spec.parts_or_defaults
    wear, turns, years = pin_life(pressure, pin_diameter, shop.bush, shop.wear_allowance, sv.turns_per_year)
    return PinLife(shop.bush, shop.wear_allowance, float(wear), float(turns), float(years), sv.turns_per_day)


def _part_scene(r: ForceResult):
    """(model key, the deciding energy model's scene with the links' masses but not the operator's
    arms (None for the quasi-static model), its linkage and synthesis), or None when no finite force
    keeps the wheel turning or the design is infeasible."""
    ev = r.evaluation
    if ev is None or not r.design.feasible:
        return None
    key = ORDER[int(ev.model_index[0])]
    sc = motion.scene(ev)
    if key != ORDER[0] and (sc is None or not math.isfinite(sc.least_peak_force)):
        return None
    syn, lk = motion.at_design(ev)
    links = motion.link_masses_of(ev, arms=False)
    part_scene = sc
    if key != ORDER[0]:  # the loads are the links' and the hand's, not the operator's arms
        part_scene = _parts.scene(
            lk, syn.dead_centre_extended, syn.dead_centre_folded, r.wheel_torque, r.inertia, links,
            r.speed, r.speed_fluctuation, sc.least_peak_force, key,
        )  # fmt: skip
    return key, part_scene, lk, syn, links


def release(r: ForceResult, _scene=None):
    """The released handle of a force result's design (docs/workshop.md §3): (with the pump's
    losses as friction, with none), two :class:`pumplink.models.release.Release`; None without a
    head (a rope force given instead) or the wheel's inertia, or for an infeasible design."""
    found = _scene or _part_scene(r)
    spec = r.design.spec
    if found is None or found[1] is None or spec.load.head is None:
        return None
    _key, part_scene, _lk, _syn, links = found
    return _parts.released(
        part_scene, spec.load.head, spec.load.pipe_diameter, spec.wheel.radius, r.wheel_torque, links
    )


def workshop(r: ForceResult) -> Workshop | None:
    """The loads, the parts and the released handle of a force result's design (None when it is
    infeasible, or when no finite force keeps its wheel turning)."""
    found = _part_scene(r)
    if found is None:
        return None
    key, part_scene, lk, syn, _links = found
    ev = r.evaluation
    wheel = r.design.spec.wheel
    weight = 0.0 if wheel.mass is None else wheel.mass * GRAVITY
    rope = float(np.asarray(ev.designs.rope_force))
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    loads = _parts.part_loads(lk, dce, dcf, r.dead_band, r.wheel_torque, key, part_scene, rope, weight)
    given = ev.designs.parts is not None
    if given:
        sizes = ev.designs.parts.design(0)
    else:  # the defaults of [parts], for information
        shop = r.design.spec.parts_or_defaults
        sizes = PartSizes(*(getattr(shop, k) for k in PART_KEYS))
    strength = _parts.strength(loads, sizes)
    both = release(r, found)
    life = _pin_life(r, strength.pin_pressure, sizes.pin_diameter)
    return Workshop(loads, strength, sizes, given, *(both or (None, None)), life)


#: Teeth a ratchet wheel may have, for :func:`ratchet_needed` (the pawl catches once a tooth).
TEETH = (12, 16, 18, 20, 24, 30, 36, 40, 48, 60, 72, 90, 120)


def ratchet_needed(spec) -> dict | None:
    """The ``[ratchet]`` a spec with a water column and none needs (docs/workshop.md §3): a torque
    of :data:`~pumplink.constants.RATCHET_SERVICE_FACTOR` times the column's, up to the next whole
    N·m, and the fewest teeth of :data:`TEETH` that keep
    the grip's kick-back within 0.15 m (0, a freewheel with no play, where none does); None where
    the spec has a ratchet or no column."""
    load = spec.load
    if spec.ratchet is not None or load.head is None:
        return None
    need = float(column_torque(load.head, load.pipe_diameter, spec.wheel.radius))
    torque = float(math.ceil(RATCHET_SERVICE_FACTOR * need))
    teeth = np.array(TEETH, float)
    values = {**spec.values, "ratchet.torque": torque, "ratchet.teeth": teeth}
    kick = evaluate(pump_designs(values), ("service",)).service.kick_back
    fit = np.nonzero(kick <= KICK_BACK_LIMIT_M)[0]
    return {"torque": torque, "teeth": int(teeth[fit[0]]) if fit.size else 0}

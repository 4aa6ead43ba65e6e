"""The model-choice report of one design (``pumplink force --explain``): which effects the
deciding model includes, their size at this speed, and why that model is enough (docs/models.md
§3)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.constants import LINK_ENERGY_LIMIT
from pumplink.evaluate import FLYWHEEL, ORDER, motion
from pumplink.studies.force import ForceResult


@dataclass(frozen=True)
class Effect:
    """One physical effect in the model-choice report: included or not, and its size."""

    name: str
    included: bool
    value: float
    unit: str
    compared_with: str  # what the ratio measures the value against, in words ('of the force limit')
    ratio: float  # value / that reference [-] (NaN when there is none)
    note: str


#: The flywheel's index in :data:`pumplink.evaluate.ORDER`.
FLYWHEEL_INDEX = ORDER.index(FLYWHEEL)


def _ratio(a: float, b: float) -> float:
    """a / b, with inf (a > 0) or NaN (a = 0) for b = 0 (a flywheel of zero inertia has no band)."""
    return float(a) / float(b) if b else (float("inf") if a else float("nan"))


def explain(r: ForceResult) -> tuple[tuple[Effect, ...], str]:
    """Which effects the verdict's model includes, their size at this speed, and why it is enough.

    The "least model that is enough" rule made visible (docs/models.md §3): each effect the
    flywheel leaves out (the links' kinetic energy and weight, the operator's arms) against its
    energy band, and a sentence naming the model that decided and why it is enough.
    """
    spec = r.design.spec
    op = spec.operator
    nan = float("nan")
    syn = r.design.synthesis
    work = 2 * np.pi * r.wheel_torque  # load work per revolution [J]
    masses = motion.link_masses_of(r.evaluation, arms=True)
    em = r.effects
    if em is None:  # no inertia: the sizes for information, against the work per revolution
        sizes = motion.effect_sizes(syn.linkage, masses, r.speed)
    else:
        sizes = (em.link_energy, em.link_weight, em.arm_energy)
    link, weight, arm = sizes
    designs = r.evaluation.designs  # the operator profile's limits, as the verdict's
    sustained, hour = (
        float(np.asarray(v, float).ravel()[0]) for v in (designs.sustained_power, designs.hour_power)
    )
    effects = [
        Effect(
            "load torque Mw = Fw rw (pump efficiency in Fw)",
            True,
            r.wheel_torque,
            "N·m",
            "",
            nan,
            f"work per revolution 2π Mw = {work:.1f} J: what the operator supplies on average",
        )
    ]
    qs = r.dead_band_peak_force
    effects.append(
        Effect(
            f"quasi-static force, peak outside ±{op.dead_band:g}° of the dead centres",
            True,
            qs,
            "N",
            "of the force limit",
            qs / r.force_limit,
            "infinite at the dead centres themselves: something must carry the linkage through",
        )
    )
    if r.flywheel:
        moving = float(r.evaluation.designs.moving_mass) * spec.wheel.radius**2  # rope and water
        effects.append(
            Effect(
                "inertia of wheel + rope and water, J",
                True,
                r.inertia,
                "kg·m²",
                "rope and water",
                _ratio(moving, r.inertia),
                f"kinetic energy {0.5 * r.inertia * r.speed**2:.2f} J at {r.speed_deg_s:g} deg/s; band "
                f"W = J ω̄² δ = {r.energy_band:.2f} J",
            )
        )
        ref, ref_name = r.energy_band, "of the energy band W"
    else:
        ref, ref_name = work, "of the work per revolution"
    dyn, arms_in = r.dynamics, bool(op.arms_in_verdict)
    effects += [
        Effect(
            "kinetic energy of coupler + handle (largest)",
            dyn,
            link,
            "J",
            ref_name,
            _ratio(link, ref),
            f"coupler {float(masses.coupler):.2f} kg, handle {float(masses.handle):.2f} kg; grows as speed²",
        ),
        Effect(
            "weight of coupler + handle (range of potential energy)",
            dyn,
            weight,
            "J",
            ref_name,
            _ratio(weight, ref),
            "lifted and given back each revolution",
        ),
        Effect(
            "operator's arms at the grip (kinetic energy, largest)",
            dyn and arms_in,
            arm,
            "J",
            ref_name,
            _ratio(arm, ref),
            f"{op.arm_mass_kg:.2f} kg (hands, forearms, half the upper arms): in the effort"
            + (
                f" {r.effort_peak_force:.1f} N"
                if r.effort_peak_force is not None and math.isfinite(r.effort_peak_force)
                else ""
            )
            + ("" if arms_in else ", not in the hand force the verdict judges"),
        ),
        Effect(
            "operator power Mw ω̄",
            True,
            r.power,
            "W",
            f"of the {sustained:g} W {r.profile} sustain for hours",
            r.power / sustained,
            f"the {r.profile} profile's limit for about an hour is {hour:g} W (docs/operators.md)",
        ),
    ]
    return tuple(effects), _why(r, link, weight, arm, ref)


def _share(a: float, b: float) -> str:
    """a / b in words: '57%' below ten times, else '10.4×'."""
    x = _ratio(a, b)
    return f"{x:.0%}" if x < 10 else f"{x:.1f}×"


def _why(r: ForceResult, link: float, weight: float, arm: float, band: float) -> str:
    """The sentence of :func:`explain`: which model decided and why it is enough."""
    op = r.design.spec.operator
    limit = LINK_ENERGY_LIMIT
    if not r.flywheel:
        return (
            "Quasi-static + dead band decided: the spec gives no inertia, so no model with speed in it can "
            "answer. The force at each crank angle is exact by virtual work (the speed cancels out of "
            f"it) and its peak outside ±{op.dead_band:g}° of the dead centres is exact; the dead band "
            "stands in for the wheel's inertia at the dead centres, where the force is infinite. That is "
            "enough for the geometry (synthesis, transmission, where the force rises); whether a person "
            "carries the linkage through the dead centres needs the wheel: give wheel.mass or "
            "wheel.inertia and the flywheel or full dynamics decides."
        )
    sizes = (
        f"the links' kinetic energy is {_share(link, band)} of the flywheel's energy band W = "
        f"{band:.3g} J and their weight {_share(weight, band)}"
        + (f", the arms (in the verdict) {_share(arm, band)}" if op.arms_in_verdict else "")
    )
    small = r.effects.least == FLYWHEEL_INDEX  # the least model that is enough is the flywheel
    left_out = "Still left out: joint friction and the operator's posture."
    if r.dynamics:
        effort = (
            f" The arms ({op.arm_mass_kg:g} kg at the grip, {_share(arm, band)} of W) are in the "
            f"effort figure {r.effort_peak_force:.1f} N, not in the hand force that guidance such as the "
            f"{r.force_limit:g} N limit refers to."
            if not op.arms_in_verdict and r.effort_peak_force is not None
            else ""
        )
        if r.effects.forced and small:
            return (
                f"Full dynamics decided because --model dynamics asked for it; {sizes} (at most "
                f"{limit:.0%}), so the flywheel would have been enough.{effort} {left_out}"
            )
        return (
            f"Full dynamics decided: {sizes}, more than {limit:.0%}, so the flywheel alone is not enough. "
            "It is enough here: it keeps the wheel's, the coupler's and the handle's inertia and the "
            "links' weight exactly, with the same exact least-peak-force test as the flywheel "
            f"(docs/models.md §3a).{effort} {left_out}"
        )
    if r.effects.forced and not small:
        return (
            f"Flywheel decided because --model flywheel asked for it, but {sizes}: more than "
            f"{limit:.0%}, so treat the verdict as an estimate; the least model that is enough is full "
            "dynamics (leave out --model)."
        )
    return (
        "Flywheel decided: the quasi-static force is infinite at the dead centres, so the wheel's "
        f"energy must enter; {sizes}, at most {limit:.0%} each: the links' inertia and weight, which "
        "full dynamics adds, move the band's edges by about that share of its width at most, so the "
        f"flywheel is enough. {left_out}"
    )

"""Advice after a FAIL: the one or two single changes to a spec that help most, all judged in
one call of the one evaluation at the verdict's own speed, model and operator profile."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.errors import SpecError
from pumplink.evaluate import FAIL, JUDGED, Verdict, evaluate, excess, pump_designs
from pumplink.inputs.pump import PumpSpec, parse_spec, spec_to_dict
from pumplink.studies.force import ForceResult


@dataclass(frozen=True)
class Suggestion:
    """One change to one spec key and what it does to the verdict (:func:`suggest`)."""

    key: str  # dotted spec key, e.g. "linkage.handle"
    old: float
    new: float
    unit: str
    peak_force: float  # the verdict's peak force after the change [N]
    outcome: str  # PASS / PASS with warnings / FAIL after the change
    level: int
    excess: float  # how far the failing checks still are beyond their limits (0: none fail)
    failing: tuple[str, ...] = ()  # keys of the checks that still fail


#: The knobs :func:`suggest` turns: dotted key, unit, and the candidate changes, each a factor
#: (relative) or, for the frame placement, a step [m].
KNOBS = (
    ("linkage.handle", "m", ("x", 0.85, 1.15)),
    ("linkage.swing", "deg", ("x", 0.85, 1.15)),
    ("linkage.rocker", "m", ("x", 0.85, 1.15)),
    ("linkage.L1", "m", ("+", -0.05, 0.05)),
    ("linkage.D1", "m", ("+", -0.05, 0.05)),
    ("operator.speed", "deg/s", ("x", 0.75, 0.85, 1.15)),
    ("load.pipe_diameter", "m", ("x", 0.8, 0.9)),
    ("wheel.radius", "m", ("x", 0.8, 1.2)),
    ("wheel.mass", "kg", ("x", 1.5, 2.0)),
    ("wheel.inertia", "kg m^2", ("x", 1.5, 2.0)),
)


def _candidates(spec: PumpSpec, speed_deg: float):
    """Each single change of :data:`KNOBS` that the spec has and that makes a valid spec:
    (key, unit, old, new, the changed spec), the speed's change from ``speed_deg`` [deg/s]."""
    out = []
    for key, unit, (kind, *steps) in KNOBS:
        table, field = key.split(".")
        data = spec_to_dict(spec)
        old = speed_deg if key == "operator.speed" else data.get(table, {}).get(field)
        if old is None:
            continue
        for step in steps:
            new = float(f"{(old * step if kind == 'x' else old + step):.4g}")
            data[table][field] = new
            try:
                out.append((key, unit, float(old), new, parse_spec(data)))
            except SpecError:
                continue
    return out


#: Checks that a fitting answers, not the linkage: the kick-back and the ratchet's torque (a
#: [ratchet] on the wheel's axle, docs/workshop.md §3).  The knobs are not ranked on them.
FITTINGS = ("kick_back", "holding_torque")


def _ranked(v) -> tuple[int, float]:
    """(level, excess) of a verdict (one design) on the checks other than :data:`FITTINGS`."""
    kept = tuple(c for c in v.checks if c.key not in FITTINGS)
    return max([0, *(int(c.level) for c in kept)]), excess(Verdict(kept, 0))


def suggest(result: ForceResult, count: int = 2) -> list[Suggestion]:
    """The ``count`` single changes to the spec that help a failing design most.

    Each knob of :data:`KNOBS` that the spec has is changed alone, and every change is judged in
    one call of the one evaluation at the verdict's own speed, model and operator profile (what
    ``pumplink force --speed --model`` says of the changed spec).  The changes are ranked by the
    verdict they give, then by how far the failing checks remain beyond their limits (the sum of
    relative excesses).  Only changes that improve on the spec are returned, at most one per key.
    Empty for a design that does not fail, or fails only checks a fitting answers
    (:data:`FITTINGS`: their own advice names the fitting).
    """
    if result.verdict is None or result.passed or _ranked(result.verdict)[0] < FAIL:
        return []
    spec, speed = result.design.spec, result.speed_deg_s
    found = _candidates(spec, speed)
    if not found:
        return []
    changed = {key for key, *_ in found}
    each = [s.values for *_, s in found]
    values = {**spec.values, **{k: np.array([v[k] for v in each], float) for k in changed}}
    speeds = np.array([new if key == "operator.speed" else speed for key, _, _, new, _ in found])
    forced = None if result.effects is None or not result.effects.forced else result.model_key
    ev = evaluate(pump_designs(values, speeds), JUDGED, model=forced)
    base = _ranked(result.verdict)
    best: dict[str, Suggestion] = {}
    for i, (key, unit, old, new, _) in enumerate(found):
        if not ev.feasible[i]:
            continue
        v = ev.verdict.design(i)
        rank = _ranked(v)
        s = Suggestion(key, old, new, unit, float(ev.peak_force[i]), v.outcome, *rank,
                       tuple(c.key for c in v.failures))  # fmt: skip
        if (s.level, s.excess) < base and (
            key not in best or (s.level, s.excess) < (best[key].level, best[key].excess)
        ):
            best[key] = s
    return sorted(best.values(), key=lambda s: (s.level, s.excess))[:count]

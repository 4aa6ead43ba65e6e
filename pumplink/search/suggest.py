"""Advice after a FAIL: the one or two single changes to a spec that help most, each
re-evaluated by the same route as ``pumplink force``."""

from __future__ import annotations

from dataclasses import dataclass

from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.inputs.pump import PumpSpec, parse_spec, spec_to_dict
from pumplink.studies.force import ForceResult, force_analysis
from pumplink.verdict import excess


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


def suggest(spec: PumpSpec, result: ForceResult, count: int = 2) -> list[Suggestion]:
    """The ``count`` single changes to the spec that help a failing design most.

    Each knob of :data:`KNOBS` that the spec has is changed alone, the design is analysed again
    (the same model and checks as ``pumplink force``), and the changes are ranked by the
    verdict they give, then by how far the failing checks remain beyond their limits (the sum of
    relative excesses).  Only changes that improve on the spec are returned, at most one per key.
    Empty for a design that does not fail.
    """
    if result.verdict is None or result.passed:
        return []
    base = (int(result.verdict.level), excess(result.verdict))
    found: dict[str, Suggestion] = {}
    for key, unit, (kind, *steps) in KNOBS:
        table, field = key.split(".")
        data = spec_to_dict(spec)
        old = data.get(table, {}).get(field)
        if old is None:
            continue
        for step in steps:
            new = old * step if kind == "x" else old + step
            new = float(f"{new:.4g}")
            data[table][field] = new
            try:
                r = force_analysis(parse_spec(data), keep_samples=False, samples=0)
            except (SpecError, InfeasibleDesign):
                continue
            if r.verdict is None:
                continue
            s = Suggestion(
                key,
                float(old),
                new,
                unit,
                r.verdict_peak_force,
                r.outcome,
                int(r.verdict.level),
                excess(r.verdict),
                tuple(c.key for c in r.verdict.failures),
            )
            if (s.level, s.excess) < base and (
                key not in found or (s.level, s.excess) < (found[key].level, found[key].excess)
            ):
                found[key] = s
    return sorted(found.values(), key=lambda s: (s.level, s.excess))[:count]

"""The field sheet: one page a mechanic takes to the well (``pumplink sheet``, the report;
docs/water.md §5).

What a built pump should do, and what to look at when it does not: the crank turns and the time
to fill a 20-litre container at the design cadence (a bucket test, as UNICEF's India Mark II
manual counts strokes), the turns before water reaches the spout from an empty rising main, the
hand force to expect, the ratchet's catch, and a prototype's endurance test.  Every figure is the
one evaluation's (:class:`pumplink.studies.force.ForceResult`), and, with a tolerance study of the
design's builds (:func:`pumplink.studies.tolerance_study.study`), their 5-95 % band.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pumplink.errors import InfeasibleDesign
from pumplink.studies.force import ForceResult

#: How much more than expected a count may be before it points at a fault [-]: 15 % more turns for
#: the container is a volumetric efficiency 13 % below the design's, more than a new pump's
#: scatter (a stated threshold, docs/water.md §5).
OFF_BY = 0.15


@dataclass(frozen=True)
class Band:
    """A figure of the design and, with a tolerance study, its builds' 5th and 95th percentile
    (NaN without one)."""

    value: float
    p5: float = math.nan
    p95: float = math.nan

    @property
    def given(self) -> bool:
        return math.isfinite(self.p5) and math.isfinite(self.p95)


@dataclass(frozen=True)
class FieldSheet:
    """One design's field sheet (SI units; cadence in turns a minute).

    fill_time, fill_turns : to fill a 20-litre container at the design cadence [s, -] (Bands);
    column_turns, column_time : from an empty rising main until water reaches the spout [-, s];
    peak_force, mean_force : the hand force to expect [N] (peak a Band); force_limit [N];
    cadence_rpm : the design cadence;  stroke : the grip's stroke [m];  head [m];
    rope_force : the rope's pull, the rig's load without the water [N];
    kick_back : the grip's travel when let go [m];  ratchet_teeth, holding_torque,
    holding_torque_required [N m] (NaN: no ratchet);  endurance_turns, endurance_hours [h],
    endurance_years : the endurance test and the years of use it stands for;
    turns_per_day : of the use;  pin_allowance [m] (NaN without [parts]);  lengths : the hole
    centres of the crank, the coupler and the rocker, and the handle O4 to grip [m];  pipe, wheel_radius
    [m];  tolerance : the holes' tolerance of the builds [m] (NaN: no tolerance study);  builds : their
    number.
    verdict : PASS, PASS with warnings or FAIL.
    """

    name: str
    verdict: str
    fill_time: Band
    fill_turns: Band
    column_turns: float
    column_time: float
    peak_force: Band
    mean_force: float
    force_limit: float
    cadence_rpm: float
    stroke: float
    head: float
    rope_force: float
    kick_back: float
    ratchet_teeth: float
    holding_torque: float
    holding_torque_required: float
    endurance_turns: float
    endurance_hours: float
    endurance_years: float
    turns_per_day: float
    pin_allowance: float
    lengths: tuple[float, float, float, float] = (math.nan,) * 4
    pipe: float = math.nan
    wheel_radius: float = math.nan
    tolerance: float = math.nan
    builds: int = 0

    @property
    def slow_turns(self) -> float:
        """Turns for the container above which the pistons leak [-]: :data:`OFF_BY` more."""
        return self.fill_turns.value * (1.0 + OFF_BY)

    @property
    def hard_force(self) -> float:
        """A hand force above which to look for a misdrilled hole [N]: the builds' 95th percentile,
        else :data:`OFF_BY` above the design's peak."""
        return self.peak_force.p95 if self.peak_force.given else self.peak_force.value * (1.0 + OFF_BY)


def field_sheet(r: ForceResult, tolerance_result=None) -> FieldSheet:
    """The field sheet of a force result (and of its builds' tolerance study, when given).

    Raises
    ------
    InfeasibleDesign
        No crank-rocker: nothing to build.
    """
    if not r.design.feasible:
        raise InfeasibleDesign(f"{r.design.spec.name}: no field sheet, {r.design.error}")
    ev = r.evaluation
    sv = ev.service.design(0)
    w = ev.water.design(0)
    volume = w.fill_time * w.flow  # the container [m^3]
    fill_time, fill_turns, peak = Band(w.fill_time), Band(w.fill_turns), Band(r.verdict_peak_force)
    tol, builds = math.nan, 0
    if tolerance_result is not None:
        spread = tolerance_result.spread
        q = spread["flow"]  # more flow, less time: the 95th percentile of the flow is the 5th of the time
        turn = 2 * math.pi / r.speed
        fill_time = Band(w.fill_time, volume / q.p95, volume / q.p5)
        fill_turns = Band(w.fill_turns, volume / q.p95 / turn, volume / q.p5 / turn)
        p = spread["peak_force"]
        peak = Band(r.verdict_peak_force, p.p5, p.p95)
        tol = max(tolerance_result.problem.tolerances.holes)
        builds = int(tolerance_result.problem.samples)
    rpm = r.speed * 60.0 / (2 * math.pi)
    syn = r.design.synthesis
    return FieldSheet(
        name=r.design.spec.name,
        verdict=r.outcome,
        fill_time=fill_time,
        fill_turns=fill_turns,
        column_turns=sv.column_fill_turns,
        column_time=sv.column_fill_time,
        peak_force=peak,
        mean_force=r.mean_force,
        force_limit=r.force_limit,
        cadence_rpm=rpm,
        stroke=float(ev.stroke[0]),
        head=w.head,
        rope_force=float(ev.designs.rope_force),
        kick_back=sv.kick_back,
        ratchet_teeth=sv.ratchet_teeth,
        holding_torque=sv.holding_torque,
        holding_torque_required=sv.holding_torque_required,
        endurance_turns=sv.endurance_hours * 3600.0 * r.speed / (2 * math.pi),
        endurance_hours=sv.endurance_hours,
        endurance_years=sv.years_to_endurance,
        turns_per_day=sv.turns_per_day,
        pin_allowance=sv.wear_allowance,
        lengths=tuple(
            float(x) for x in (syn.crank_length, syn.coupler_length, syn.rocker_length, syn.handle_length)
        ),  # fmt: skip
        pipe=float(ev.designs.pipe_diameter),
        wheel_radius=float(ev.designs.wheel_radius),
        tolerance=tol,
        builds=builds,
    )

"""The textbook's mechanism problems as reports: lengths, quality indicators, a check by simulation
and a verdict.

One function per problem form of the commands ``pumplink slider``, ``slotted`` and ``rocker``
(synthesis from the textbook's data, or analysis of a given mechanism), and
:func:`~pumplink.studies.textbook_rocker.optimum_check` for ``pumplink transmission``.  Each runs
the kernel's closed forms, then runs the mechanism through a full crank turn
(:mod:`pumplink.mechanisms.simulation`, :func:`pumplink.mechanisms.crank_rocker.measure_motion`,
:func:`~pumplink.studies.textbook_rocker.fourbar_extremes`) and reports the requested, the
closed-form and the measured value of every indicator.  Here: the reports, the verdict, the
crank-slider and the slotted lever; the crank-rocker and the transmission check are
:mod:`pumplink.studies.textbook_rocker`.

The verdict uses the pump verdict's check machinery (:mod:`pumplink.verdict`: the same
:class:`~pumplink.verdict.Check`, levels and PASS / PASS with warnings / FAIL):

* ``pressure_angle`` (slider, slotted lever): the largest pressure angle warns above the
  textbook's permissible value for a mechanism with a sliding pair
  (``PERMISSIBLE_PRESSURE_SLIDING_DEG[0]``) and fails
  above ``90 deg - FAIL_TRANSMISSION_DEG`` = 60 deg;
* ``transmission_angle`` (crank-rocker): min(gamma_min, 180 deg - gamma_max) warns below
  ``MIN_TRANSMISSION_DEG`` and fails below ``FAIL_TRANSMISSION_DEG``, as in the pump verdict;
* ``simulation``: the largest deviation of a measured value from the asked one (the closed form
  where nothing was asked) fails above ``SIMULATION_TOL``.

:func:`pumplink.verdict.assess` itself does not fit: its force checks (mean and peak force
against the operator's limit) are required and mean nothing for a bare mechanism.  The limits
and their sources are in docs/mechanisms.md §4.

Pure functions: no I/O.  Angles in radians (the output layer converts).  Bad input raises
:class:`~pumplink.errors.SpecError` (exit 2); valid input outside a realisability condition raises
:class:`~pumplink.errors.InfeasibleDesign` (exit 1) with one sentence that states the condition,
never a mechanism that cannot turn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pumplink.constants import (
    FAIL_TRANSMISSION_DEG,
    MIN_TRANSMISSION_DEG,
    PERMISSIBLE_PRESSURE_REVOLUTE_DEG,
    PERMISSIBLE_PRESSURE_SLIDING_DEG,
)
from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.evaluate import Verdict, check
from pumplink.mechanisms import crank_slider as cs
from pumplink.mechanisms import simulation
from pumplink.mechanisms import slotted_lever as sl

#: Relative (absolute for angles, in rad) agreement demanded between asked and simulated values.
SIMULATION_TOL = 1e-9
#: Largest pressure angle [deg] above which a mechanism fails: 90 deg - FAIL_TRANSMISSION_DEG, the
#: upper end of the textbook's permissible 45-60 deg for revolute pairs (docs/mechanisms.md §4).
FAIL_PRESSURE_DEG = 90.0 - FAIL_TRANSMISSION_DEG
#: Permissible largest pressure angle [deg] (warn above the first value): with a sliding pair in the
#: mechanism, or revolute pairs only (the lever-mechanism textbook, §2.4).
PERMISSIBLE_PRESSURE_DEG = {
    "sliding": PERMISSIBLE_PRESSURE_SLIDING_DEG,
    "revolute": PERMISSIBLE_PRESSURE_REVOLUTE_DEG,
}

LENGTH, RATIO, ANGLE = "length", "ratio", "angle"
TAU = 2.0 * math.pi


def wrap_angle(x: float) -> float:
    """A crank angle in [0, 2 pi) (NaN stays NaN)."""
    return float(np.mod(x, TAU))


@dataclass(frozen=True)
class Indicator:
    """One quality indicator: the value asked for (None if not asked), the closed form's value
    and the value measured by simulation.  ``kind`` is length, ratio or angle [rad]; angles
    compare modulo a full turn (crank angles at the dead centres)."""

    key: str
    label: str
    kind: str
    asked: float | None
    closed_form: float
    simulated: float

    @property
    def deviation(self) -> float:
        """|simulated - asked| (the closed form if nothing was asked): relative for lengths and
        ratios, absolute in radians for angles; inf where either is not finite."""
        ref = self.closed_form if self.asked is None else self.asked
        if not (math.isfinite(ref) and math.isfinite(self.simulated)):
            return math.inf
        if self.kind == ANGLE:
            return abs(math.remainder(self.simulated - ref, TAU))
        return abs(self.simulated - ref) / max(abs(ref), 1e-300)

    @property
    def agrees(self) -> bool:
        """True when the simulation reproduces the asked value (or the closed form, if none asked)."""
        return self.deviation <= SIMULATION_TOL


@dataclass(frozen=True)
class SynthesisReport:
    """What a mechanism command prints.

    Attributes
    ----------
    mechanism, task : names for the title.
    given : the inputs as (key, label, kind, value).
    lengths : the lengths as (key, label, value), in the unit of the given lengths.
    indicators : asked / closed form / simulated.
    verdict : the checks (:class:`pumplink.verdict.Verdict`) and PASS / PASS with warnings / FAIL.
    pairs : "sliding" (the mechanism has a sliding pair) or "revolute" (revolute pairs only): the
        textbook's permissible pressure angle (§2.4) depends on it.
    ratios : exact ratios of the given lengths as (key, label, value) (analysis forms).
    notes : sentences (choices made, alternatives, the conventions), numbers already in them.
    """

    mechanism: str
    task: str
    given: tuple[tuple[str, str, str, float], ...]
    lengths: tuple[tuple[str, str, float], ...]
    indicators: tuple[Indicator, ...]
    verdict: Verdict
    pairs: str
    ratios: tuple[tuple[str, str, float], ...] = field(default=())
    notes: tuple[str, ...] = field(default=())

    @property
    def agrees(self) -> bool:
        """True when the simulated mechanism does what was asked (every indicator agrees)."""
        return all(i.agrees for i in self.indicators)

    @property
    def passed(self) -> bool:
        """True when the verdict is PASS or PASS with warnings (exit 0)."""
        return bool(self.verdict.passed)

    @property
    def permissible_pressure_deg(self) -> tuple[float, float]:
        """The textbook's permissible largest pressure angle for the mechanism's pairs [deg]
        (preferred, acceptable in preliminary design; §2.4)."""
        return PERMISSIBLE_PRESSURE_DEG[self.pairs]


def judge(
    indicators, *, pressure: float | None = None, pairs: str = "sliding", transmission: float | None = None
) -> Verdict:
    """The verdict of a mechanism: its force-transmission check and the simulation check.

    Parameters
    ----------
    indicators : the report's indicators; the largest deviation is the ``simulation`` check.
    pressure : measured largest pressure angle [rad] (slider, slotted lever), or None.
    pairs : "sliding" (a sliding pair in the mechanism) or "revolute" (revolute pairs only): the
        textbook's permissible pressure angle (§2.4).
    transmission : measured min(gamma_min, pi - gamma_max) [rad] (crank-rocker), or None.
    """
    checks = []
    if pressure is not None:
        warn = PERMISSIBLE_PRESSURE_DEG[pairs][0]
        checks.append(
            check("pressure_angle", math.degrees(pressure), "<=", "deg", True, warn, FAIL_PRESSURE_DEG)
        )
    if transmission is not None:
        checks.append(
            check(
                "transmission_angle",
                math.degrees(transmission),
                ">=",
                "deg",
                True,
                MIN_TRANSMISSION_DEG,
                FAIL_TRANSMISSION_DEG,
            )
        )
    deviation = max(i.deviation for i in indicators)
    checks.append(check("simulation", deviation, "<=", "-", True, fail=SIMULATION_TOL))
    return Verdict(tuple(checks), max(int(c.level) for c in checks))


def require_finite(**values):
    """SpecError naming the option (``--name``) of a value given that is not a finite number."""
    for name, v in values.items():
        if v is None:
            continue
        if not (isinstance(v, (int, float)) and math.isfinite(v)):
            raise SpecError(f"--{name.replace('_', '-')} {v!r} is not a finite number")


def require_positive(**values):
    """SpecError naming the option of a value given that is not a positive finite number."""
    require_finite(**values)
    for name, v in values.items():
        if v is not None and not v > 0:
            raise SpecError(f"--{name.replace('_', '-')} {v:g} must be positive")


def require_time_ratio(k):
    """SpecError for a time ratio K below 1 (the slow stroke's time over the fast one's)."""
    if k < 1:
        raise SpecError(
            f"--time-ratio {k:g} is below 1; K is the slow stroke's time over the fast one's, so K >= 1"
        )


# ----------------------------------------------------------------------------- crank-slider
def _slider_report(r, rod, e, *, mechanism_task, given, asked_stroke, asked_k, ratios=(), notes=()):
    """Indicators, simulation and verdict of the crank-slider (r, l, e)."""
    m = simulation.crank_slider(r, rod, e)
    if not m.turns:  # cannot happen for a crank that turns fully; guard the promise anyway
        raise InfeasibleDesign("the crank-slider does not turn fully in simulation")
    L, nu = rod / r, e / r
    h = math.sqrt((L + 1.0) ** 2 - nu * nu) - math.sqrt((L - 1.0) ** 2 - nu * nu)  # Eq. (1.10)
    extended, folded = (float(x) for x in cs.dead_centres(r, rod, e))
    t_far, t_near = m.extremes
    arc = float(np.mod(t_near - t_far, TAU))
    indicators = (
        Indicator("stroke", "stroke H", LENGTH, asked_stroke, float(cs.stroke(r, rod, e)), m.stroke),
        Indicator("relative_stroke", "relative stroke h = H/r", RATIO, None, h, m.stroke / r),
        Indicator(
            "time_ratio", "time ratio K", RATIO, asked_k, float(cs.time_ratio(r, rod, e)), m.time_ratio
        ),
        Indicator(
            "extreme_rod_angle",
            "angle θ between rods",
            ANGLE,
            None,
            float(cs.extreme_rod_angle(r, rod, e)),
            abs(arc - math.pi),
        ),
        Indicator(
            "largest_pressure_angle",
            "largest pressure angle",
            ANGLE,
            None,
            float(cs.largest_pressure_angle(r, rod, e)),
            m.largest_pressure_angle,
        ),
        Indicator(
            "dead_centre_extended",
            "dead centre, extended",
            ANGLE,
            None,
            wrap_angle(extended),
            wrap_angle(t_far),
        ),
        Indicator(
            "dead_centre_folded", "dead centre, folded", ANGLE, None, wrap_angle(folded), wrap_angle(t_near)
        ),
    )
    out = math.degrees(float(np.mod(folded - extended, TAU)))  # CCW, extended -> folded
    if abs(out - 180.0) <= 1e-9:
        stroke_words = "both strokes take 180° of crank"
    else:
        stroke_words = (
            f"the crank turning counter-clockwise takes {out:.6g}° from the extended dead centre "
            f"(slider farthest) to the folded one: the {'slow' if out > 180.0 else 'fast'} stroke, "
            "towards the crank pivot"
        )
    notes = (
        *notes,
        stroke_words,
        "crank pivot at the origin, guide y = e; crank angles counter-clockwise from +x "
        "(docs/mechanisms.md §1)",
    )
    mechanism, task = mechanism_task
    return SynthesisReport(
        mechanism=mechanism,
        task=task,
        given=tuple(given),
        lengths=(("crank", "crank r", r), ("rod", "rod l", rod), ("offset", "offset e", e)),
        indicators=indicators,
        verdict=judge(indicators, pressure=m.largest_pressure_angle, pairs="sliding"),
        pairs="sliding",
        ratios=tuple(ratios),
        notes=notes,
    )


def slider(stroke: float, rod_ratio: float, time_ratio: float | None = None, offset_ratio: float = 0.0):
    """Crank-slider, Task 1 (``time_ratio`` None: from H, L and nu = e/r) or Task 2 (from H, K, L).

    Realisability: L > 1 + |nu| (Task 1; the rod must be longer than crank + offset), and
    1 <= K < K_max(L) (Task 2, Eq. 1.12 of docs/mechanisms.md).

    Raises
    ------
    SpecError : non-finite input, H <= 0, K < 1, or an offset with Task 2.
    InfeasibleDesign : outside the realisability condition.
    """
    require_positive(stroke=stroke, rod_ratio=rod_ratio)
    require_finite(time_ratio=time_ratio, offset_ratio=offset_ratio)
    if time_ratio is None:
        d = cs.synthesize_from_stroke(stroke, rod_ratio, offset_ratio)
        task = "Task 1: from the stroke H and the rod ratio L = l/r"
        if int(d.reason) != cs.OK:
            raise InfeasibleDesign(
                f"no crank-slider with rod ratio L = {rod_ratio:g} and offset ratio e/r = {offset_ratio:g}: "
                f"the rod must be longer than crank + |offset|, L > 1 + |e/r| = {1 + abs(offset_ratio):g}; "
                "lengthen the rod"
            )
    else:
        if offset_ratio != 0.0:
            raise SpecError("--offset-ratio is for Task 1 only; Task 2 (--time-ratio) computes the offset")
        require_time_ratio(time_ratio)
        d = cs.synthesize_from_time_ratio(stroke, time_ratio, rod_ratio)
        task = "Task 2: from the stroke H, the time ratio K and the rod ratio L = l/r"
        if int(d.reason) != cs.OK:
            if rod_ratio <= 1:
                raise InfeasibleDesign(
                    f"no crank-slider with rod ratio L = {rod_ratio:g}: the rod must be longer than the "
                    "crank (L > 1); lengthen the rod"
                )
            kmax = float(cs.largest_time_ratio(rod_ratio))
            lmin = _least_rod_ratio(time_ratio)
            raise InfeasibleDesign(
                f"no crank-slider with rod ratio L = {rod_ratio:g} reaches K = {time_ratio:g}: with this L, "
                f"K must stay below {kmax:.6g} (else the rod would need to be shorter than crank + offset); "
                f"lower K or take L > {lmin:.6g}"
            )
    r, rod, e = float(d.crank_length), float(d.rod_length), float(d.offset)
    given = [("stroke", "stroke H", LENGTH, stroke), ("rod_ratio", "rod ratio L = l/r", RATIO, rod_ratio)]
    if time_ratio is None:
        given.append(("offset_ratio", "offset ratio ν = e/r", RATIO, offset_ratio))
    else:
        given.append(("time_ratio", "time ratio K", RATIO, time_ratio))
    k_asked = 1.0 if time_ratio is None and offset_ratio == 0.0 else time_ratio
    return _slider_report(
        r,
        rod,
        e,
        mechanism_task=("crank-slider", task),
        given=given,
        asked_stroke=stroke,
        asked_k=k_asked,
    )


def slider_analysis(crank: float, rod: float, offset: float = 0.0):
    """Analysis of a given crank-slider (r, l, e): stroke, K, theta, lambda_max, h = H/r, the
    dead-centre crank angles (docs/mechanisms.md §1, Eq. 1.4-1.10), each measured by simulation.

    Realisability: the crank turns fully iff l > r + |e| (Eq. 1.7).

    Raises
    ------
    SpecError : non-finite input, r <= 0 or l <= 0.
    InfeasibleDesign : the crank cannot turn fully.
    """
    require_positive(crank=crank, rod=rod)
    require_finite(offset=offset)
    if not bool(cs.turns_fully(crank, rod, offset)):
        raise InfeasibleDesign(
            f"a crank-slider with crank {crank:g}, rod {rod:g} and offset {offset:g} cannot turn fully: "
            f"the rod must be longer than crank + |offset| = {crank + abs(offset):g}; lengthen the rod "
            "or shorten the crank or the offset"
        )
    given = [
        ("crank", "crank r", LENGTH, crank),
        ("rod", "rod l", LENGTH, rod),
        ("offset", "offset e", LENGTH, offset),
    ]
    ratios = (("rod_ratio", "L = l/r", rod / crank), ("offset_ratio", "ν = e/r", offset / crank))
    return _slider_report(
        crank,
        rod,
        offset,
        mechanism_task=("crank-slider", "analysis of the given crank r, rod l and offset e"),
        given=given,
        asked_stroke=None,
        asked_k=None,
        ratios=ratios,
    )


def _and(words: list[str]) -> str:
    """'a', 'a and b', 'a, b and c'."""
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " and " + words[-1]


def _least_rod_ratio(time_ratio: float) -> float:
    """Smallest L with K < K_max(L): cos theta = (L - 1)/(L + 1) solved for L (Eq. 1.12)."""
    c = math.cos(math.pi * (time_ratio - 1.0) / (time_ratio + 1.0))
    return (1.0 + c) / (1.0 - c) if c < 1.0 else 1.0


# ----------------------------------------------------------------------------- slotted lever
def slotted(
    time_ratio: float | None = None,
    stroke: float | None = None,
    frame_length: float | None = None,
    *,
    crank: float | None = None,
    lever: float | None = None,
):
    """Crank and slotted lever (docs/mechanisms.md §2), in the problem forms of the textbooks.

    * Synthesis from K: one of ``crank`` r and ``frame_length`` d (or neither) sets the scale,
      one of ``stroke`` H and ``lever`` l (or neither) the lever; a length not given is chosen so
      that the slot just holds the block, l = d + r.  At least one length.
    * Analysis (no K): ``crank`` and ``frame_length`` given, with ``lever`` or ``stroke``
      (then the lever that gives it) or neither (then no stroke).

    Realisability: K > 1 and a lever that holds the block, l >= d + r (Eq. 2.9); for the
    analysis r < d (else the lever turns fully: a Whitworth mechanism).

    Raises
    ------
    SpecError : non-finite or non-positive input, K < 1, or a set of lengths that over- or
        under-determines the mechanism.
    InfeasibleDesign : outside the realisability conditions.
    """
    require_positive(stroke=stroke, frame=frame_length, crank=crank, lever=lever)
    require_finite(time_ratio=time_ratio)
    if stroke is not None and lever is not None:
        raise SpecError("--stroke and --lever each fix the lever; give one of them")
    if time_ratio is None:
        return _slotted_analysis(crank, frame_length, lever, stroke)
    require_time_ratio(time_ratio)
    if crank is not None and frame_length is not None:
        raise SpecError(
            "--time-ratio, --crank and --frame over-determine the slotted lever (K follows from "
            "crank/frame); give two of them"
        )
    if all(x is None for x in (crank, frame_length, stroke, lever)):
        raise SpecError("give a length with --time-ratio: --stroke, --lever, --crank or --frame")
    d = sl.synthesize_from_time_ratio(
        time_ratio, stroke, frame_length, crank_length=crank, lever_length=lever
    )
    reason = int(d.reason)
    psi = math.pi * (time_ratio - 1.0) / (time_ratio + 1.0)
    half = math.sin(0.5 * psi)
    if reason == sl.TIME_RATIO_NOT_ABOVE_ONE:
        raise InfeasibleDesign(
            "no slotted lever has K = 1: the swing would be 0, a zero crank and an infinite lever; "
            "ask for K > 1"
        )
    if reason == sl.SLOT_TOO_SHORT:
        length = stroke / (2.0 * half) if lever is None else lever
        if frame_length is not None:
            dd, what = frame_length, f"frame length d = {frame_length:g}"
            fix = f"take d <= {length / (1.0 + half):.6g}"
        else:
            dd, what = crank / half, f"crank r = {crank:g} (frame d = {crank / half:.6g})"
            fix = f"take r <= {length * half / (1.0 + half):.6g}"
        raise InfeasibleDesign(
            f"with {what} the lever (length {length:.6g}) is shorter than the block's farthest reach "
            f"d + r = {dd * (1 + half):.6g}, so the slot cannot hold the block; {fix}"
        )
    if reason != sl.OK:
        raise SpecError(sl.REASONS[reason])
    r, dd, ll = float(d.crank_length), float(d.frame_length), float(d.lever_length)
    given = [("time_ratio", "time ratio K", RATIO, time_ratio)]
    for key, label, value in (
        ("crank", "crank r", crank),
        ("frame_length", "frame d", frame_length),
        ("stroke", "stroke H (chord)", stroke),
        ("lever", "lever l", lever),
    ):
        if value is not None:
            given.append((key, label, LENGTH, value))
    notes = []
    if crank is None and frame_length is None:
        notes.append(f"crank and frame not given: the slot just holds the block, l = d + r = {ll:.6g}")
    if stroke is None and lever is None:
        notes.append(f"lever not given: the shortest that holds the block, l = d + r = {ll:.6g}")
    task = "from the time ratio K, " + _and([f"the {label}" for _, label, _, _ in given[1:]])
    return _slotted_report(
        r, dd, ll, task, given, asked_k=time_ratio, asked_stroke=stroke, asked_psi=psi, notes=notes
    )


def _slotted_analysis(crank, frame_length, lever, stroke):
    if crank is None or frame_length is None:
        raise SpecError(
            "give --time-ratio K (synthesis), or both --crank and --frame to analyse a given slotted lever"
        )
    if not crank < frame_length:
        raise InfeasibleDesign(
            f"with crank r = {crank:g} not shorter than the frame d = {frame_length:g} the lever turns "
            "fully (a rotating-lever, Whitworth mechanism), it does not oscillate; take r < d"
        )
    given = [("crank", "crank r", LENGTH, crank), ("frame_length", "frame d", LENGTH, frame_length)]
    notes = []
    if stroke is not None:
        lever = stroke * frame_length / (2.0 * crank)  # Eq. (2.8): H = 2 l r/d
        given.append(("stroke", "stroke H (chord)", LENGTH, stroke))
    elif lever is not None:
        given.append(("lever", "lever l", LENGTH, lever))
    else:
        notes.append("no stroke without the lever's length: give --lever (or --stroke for the lever)")
    if lever is not None and not lever >= (frame_length + crank) * (1.0 - 1e-15):
        raise InfeasibleDesign(
            f"the lever (length {lever:.6g}) is shorter than the block's farthest reach "
            f"d + r = {frame_length + crank:.6g}, so the slot cannot hold the block; take a lever of "
            f"at least {frame_length + crank:.6g}"
        )
    ratios = (("crank_to_frame", "r/d", crank / frame_length),)
    task = "analysis of the given " + _and([label for _, label, _, _ in given])
    return _slotted_report(
        crank,
        frame_length,
        lever,
        task,
        given,
        asked_k=None,
        asked_stroke=stroke,
        asked_psi=None,
        notes=notes,
        ratios=ratios,
    )


def _slotted_report(r, d, lever, task, given, *, asked_k, asked_stroke, asked_psi, notes, ratios=()):
    m = simulation.slotted_lever(r, d, math.nan if lever is None else lever)
    t_left, t_right = m.extremes  # (largest, smallest) lever angle: the lever's left, right extreme
    arc = float(np.mod(t_right - t_left, TAU))
    psi = float(sl.swing_angle(r, d))
    right, left = (float(x) for x in sl.extremes(r, d))
    indicators = []
    if lever is not None:
        indicators.append(
            Indicator(
                "stroke", "stroke H (chord)", LENGTH, asked_stroke, float(sl.stroke(r, d, lever)), m.stroke
            )
        )
    indicators += [
        Indicator("time_ratio", "time ratio K", RATIO, asked_k, float(sl.time_ratio(r, d)), m.time_ratio),
        Indicator("swing", "lever swing ψ", ANGLE, asked_psi, psi, m.swing),
        Indicator(
            "lever_inclination",
            "lever to line of centres",
            ANGLE,
            None,
            0.5 * psi,
            float(sl.lever_angle(r, d, t_left)) - 0.5 * math.pi,
        ),
        Indicator("slow_arc", "crank arc, slow stroke", ANGLE, None, math.pi + psi, max(arc, TAU - arc)),
        Indicator("fast_arc", "crank arc, fast stroke", ANGLE, None, math.pi - psi, min(arc, TAU - arc)),
        Indicator(
            "dead_centre_right", "dead centre, right", ANGLE, None, wrap_angle(right), wrap_angle(t_right)
        ),
        Indicator("dead_centre_left", "dead centre, left", ANGLE, None, wrap_angle(left), wrap_angle(t_left)),
    ]
    lengths = [("crank", "crank r", r), ("frame", "frame d", d)]
    if lever is not None:
        lengths.append(("lever", "lever l", lever))
    notes = [
        *notes,
        f"the block slides along the slot from {d - r:.6g} to {d + r:.6g} from the lever pivot",
        "lever pivot at the origin, crank pivot at (0, d); crank angles counter-clockwise from +x; "
        "with the crank turning counter-clockwise the slow stroke runs from the right extreme to "
        "the left (docs/mechanisms.md §2)",
    ]
    return SynthesisReport(
        mechanism="slotted lever",
        task=task,
        given=tuple(given),
        lengths=tuple(lengths),
        indicators=tuple(indicators),
        # the block pushes the lever square to the slot: pressure angle 0 (docs/mechanisms.md §2);
        # the block slides in the slot, so the limits are those of a mechanism with a sliding pair
        verdict=judge(indicators, pressure=m.largest_pressure_angle, pairs="sliding"),
        pairs="sliding",
        ratios=tuple(ratios),
        notes=tuple(notes),
    )

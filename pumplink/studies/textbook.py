"""The textbook's synthesis tasks as reports: lengths, quality indicators, a check by simulation.

One function per command (``pumplink slider``, ``slotted``, ``rocker``).  Each runs the kernel's
synthesis, then runs the synthesised mechanism through a full crank turn
(:mod:`pumplink.mechanisms.simulation`, :func:`pumplink.mechanisms.crank_rocker.measure_motion`)
and reports the requested, the closed-form and the measured value of every indicator, and the
largest pressure angle against the textbook's permissible values (docs/mechanisms.md §4).

Pure functions: no I/O.  Angles in radians (the output layer converts).  Bad input raises
:class:`~pumplink.errors.SpecError` (exit 2); valid input outside a realisability condition raises
:class:`~pumplink.errors.InfeasibleDesign` (exit 1) with one sentence that states the condition,
never a mechanism that cannot turn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pumplink.constants import PERMISSIBLE_PRESSURE_REVOLUTE_DEG, PERMISSIBLE_PRESSURE_SLIDING_DEG
from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.mechanisms import crank_rocker as cr
from pumplink.mechanisms import crank_slider as cs
from pumplink.mechanisms import simulation
from pumplink.mechanisms import slotted_lever as sl

#: Relative (absolute for angles, in rad) agreement demanded between asked and simulated values.
SIMULATION_TOL = 1e-9

LENGTH, RATIO, ANGLE = "length", "ratio", "angle"
PASS, MARGINAL, EXCEEDS = "pass", "marginal", "exceeds"


@dataclass(frozen=True)
class Indicator:
    """One quality indicator: the value asked for (None if not asked), the closed form's value
    and the value measured by simulation.  ``kind`` is length, ratio or angle [rad]."""

    key: str
    label: str
    kind: str
    asked: float | None
    closed_form: float
    simulated: float

    @property
    def agrees(self) -> bool:
        """True when the simulation reproduces the asked value (or the closed form, if none asked)."""
        ref = self.closed_form if self.asked is None else self.asked
        if not (math.isfinite(ref) and math.isfinite(self.simulated)):
            return False
        scale = 1.0 if self.kind == ANGLE else max(abs(ref), 1e-300)
        return abs(self.simulated - ref) <= SIMULATION_TOL * scale


@dataclass(frozen=True)
class PressureCheck:
    """Largest pressure angle [rad] against the textbook's permissible range [deg] (§2.4):
    ``pass`` up to the lower end, ``marginal`` inside the range, ``exceeds`` above it."""

    label: str
    value: float
    permissible_deg: tuple[float, float]
    driven: str  # "sliding" or "revolute"

    @property
    def result(self) -> str:
        v = math.degrees(self.value)
        lo, hi = self.permissible_deg
        return PASS if v <= lo else MARGINAL if v <= hi else EXCEEDS


@dataclass(frozen=True)
class SynthesisReport:
    """What a synthesis command prints.

    Attributes
    ----------
    mechanism, task : names for the title.
    given : the inputs as (key, label, kind, value).
    lengths : the synthesised lengths as (key, label, value), in the unit of the given lengths.
    indicators : asked / closed form / simulated.
    pressure : the pressure-angle check.
    notes : sentences (choices made, alternatives).
    """

    mechanism: str
    task: str
    given: tuple[tuple[str, str, str, float], ...]
    lengths: tuple[tuple[str, str, float], ...]
    indicators: tuple[Indicator, ...]
    pressure: PressureCheck
    notes: tuple[str, ...] = field(default=())

    @property
    def agrees(self) -> bool:
        """True when the simulated mechanism does what was asked (every indicator agrees)."""
        return all(i.agrees for i in self.indicators)


def _finite(**values):
    for name, v in values.items():
        if v is None:
            continue
        if not (isinstance(v, (int, float)) and math.isfinite(v)):
            raise SpecError(f"--{name.replace('_', '-')} {v!r} is not a finite number")


def _positive(**values):
    _finite(**values)
    for name, v in values.items():
        if v is not None and not v > 0:
            raise SpecError(f"--{name.replace('_', '-')} {v:g} must be positive")


def _time_ratio_at_least_one(k):
    if k < 1:
        raise SpecError(
            f"--time-ratio {k:g} is below 1; K is the slow stroke's time over the fast one's, so K >= 1"
        )


# ----------------------------------------------------------------------------- crank-slider
def slider(stroke: float, rod_ratio: float, time_ratio: float | None = None, offset_ratio: float = 0.0):
    """Crank-slider, Task 1 (``time_ratio`` None: from H, L and nu = e/r) or Task 2 (from H, K, L).

    Realisability: L > 1 + |nu| (Task 1; the rod must be longer than crank + offset), and
    1 <= K < K_max(L) (Task 2, Eq. 1.12 of docs/mechanisms.md).

    Raises
    ------
    SpecError : non-finite input, H <= 0, K < 1, or an offset with Task 2.
    InfeasibleDesign : outside the realisability condition.
    """
    _positive(stroke=stroke, rod_ratio=rod_ratio)
    _finite(time_ratio=time_ratio, offset_ratio=offset_ratio)
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
        _time_ratio_at_least_one(time_ratio)
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
    m = simulation.crank_slider(r, rod, e)
    if not m.turns:  # cannot happen for a realisable design; guard the promise anyway
        raise InfeasibleDesign("the synthesised crank-slider does not turn fully in simulation")
    given = [("stroke", "stroke H", LENGTH, stroke), ("rod_ratio", "rod ratio L = l/r", RATIO, rod_ratio)]
    if time_ratio is None:
        given.append(("offset_ratio", "offset ratio e/r", RATIO, offset_ratio))
    else:
        given.append(("time_ratio", "time ratio K", RATIO, time_ratio))
    k_asked = 1.0 if time_ratio is None and offset_ratio == 0.0 else time_ratio
    return SynthesisReport(
        mechanism="crank-slider",
        task=task,
        given=tuple(given),
        lengths=(("crank", "crank r", r), ("rod", "rod l", rod), ("offset", "offset e", e)),
        indicators=(
            Indicator("stroke", "stroke H", LENGTH, stroke, float(d.stroke), m.stroke),
            Indicator("time_ratio", "time ratio K", RATIO, k_asked, float(d.time_ratio), m.time_ratio),
            Indicator(
                "largest_pressure_angle",
                "largest pressure angle",
                ANGLE,
                None,
                float(d.largest_pressure_angle),
                m.largest_pressure_angle,
            ),
        ),
        pressure=PressureCheck(
            "largest pressure angle (rod on slider)",
            m.largest_pressure_angle,
            PERMISSIBLE_PRESSURE_SLIDING_DEG,
            "sliding",
        ),
        notes=(
            "crank pivot at the origin, guide y = e; with the crank turning counter-clockwise the slow "
            "stroke runs towards the crank pivot (docs/mechanisms.md §1)",
        ),
    )


def _least_rod_ratio(time_ratio: float) -> float:
    """Smallest L with K < K_max(L): cos theta = (L - 1)/(L + 1) solved for L (Eq. 1.12)."""
    c = math.cos(math.pi * (time_ratio - 1.0) / (time_ratio + 1.0))
    return (1.0 + c) / (1.0 - c) if c < 1.0 else 1.0


# ----------------------------------------------------------------------------- slotted lever
def slotted(time_ratio: float, stroke: float, frame_length: float | None = None):
    """Crank and slotted lever from K and the chord stroke H of the lever tip (docs/mechanisms.md §2).

    Realisability: K > 1 and a lever that holds the block, l >= d + r (Eq. 2.9).
    """
    _positive(stroke=stroke, frame_length=frame_length)
    _finite(time_ratio=time_ratio)
    _time_ratio_at_least_one(time_ratio)
    d = sl.synthesize_from_time_ratio(time_ratio, stroke, frame_length)
    reason = int(d.reason)
    if reason == sl.TIME_RATIO_NOT_ABOVE_ONE:
        raise InfeasibleDesign(
            "no slotted lever has K = 1: the swing would be 0, a zero crank and an infinite lever; "
            "ask for K > 1"
        )
    if reason == sl.SLOT_TOO_SHORT:
        psi = math.pi * (time_ratio - 1.0) / (time_ratio + 1.0)
        half = math.sin(0.5 * psi)
        dmax = stroke / (2.0 * half) / (1.0 + half)
        raise InfeasibleDesign(
            f"with frame length d = {frame_length:g} the lever (length {stroke / (2 * half):.6g}) is shorter "
            f"than the block's farthest reach d + r = {frame_length * (1 + half):.6g}, so the slot cannot "
            f"hold the block; take d <= {dmax:.6g}"
        )
    if reason != sl.OK:
        raise SpecError(sl.REASONS[reason])
    r, dd, lever = float(d.crank_length), float(d.frame_length), float(d.lever_length)
    m = simulation.slotted_lever(r, dd, lever)
    psi_asked = math.pi * (time_ratio - 1.0) / (time_ratio + 1.0)
    given = [
        ("time_ratio", "time ratio K", RATIO, time_ratio),
        ("stroke", "stroke H (chord)", LENGTH, stroke),
    ]
    notes = ["lever pivot at the origin, crank pivot at (0, d) (docs/mechanisms.md §2)"]
    if frame_length is None:
        notes.append("frame length not given: the largest d whose slot holds the block, l = d + r")
    else:
        given.append(("frame_length", "frame length d", LENGTH, frame_length))
    return SynthesisReport(
        mechanism="slotted lever",
        task="from the time ratio K and the stroke H of the lever tip",
        given=tuple(given),
        lengths=(("crank", "crank r", r), ("frame", "frame d", dd), ("lever", "lever l", lever)),
        indicators=(
            Indicator("stroke", "stroke H (chord)", LENGTH, stroke, float(d.stroke), m.stroke),
            Indicator("time_ratio", "time ratio K", RATIO, time_ratio, float(d.time_ratio), m.time_ratio),
            Indicator("swing", "lever swing", ANGLE, psi_asked, float(d.swing_angle), m.swing),
        ),
        pressure=PressureCheck(
            "largest pressure angle (block on lever)",
            m.largest_pressure_angle,
            PERMISSIBLE_PRESSURE_REVOLUTE_DEG,
            "revolute",
        ),
        notes=tuple(notes),
    )


# ----------------------------------------------------------------------------- crank-rocker
def rocker(
    swing: float,
    rocker_length: float,
    time_ratio: float | None = None,
    frame: float | None = None,
    pivot: tuple[float, float] | None = None,
):
    """Crank-rocker from the rocker's two extreme positions (swing, rocker) and the crank pivot.

    The crank pivot is chosen in one of three ways (docs/crank-rocker.md §7): ``pivot`` (a point:
    it fixes K), ``frame`` (with K: the design-circle points at that distance from the rocker
    pivot; the best transmission of up to four), or neither (with K > 1: the optimum of the
    optimal-transmission paper).

    Realisability: the crank pivot must see C1 and C2 on one side of the frame line (else the
    linkage swings to the mirror image of C1); for a frame length, the design circle must reach it.
    """
    _positive(rocker=rocker_length, frame=frame)
    _finite(swing=swing, time_ratio=time_ratio)
    if not 0.0 < swing < math.pi:
        raise SpecError(f"--swing {math.degrees(swing):g} deg must be between 0 and 180 deg")
    notes = [
        "rocker pivot D at the origin, swing bisector +y, extreme positions C1 (-x side) and C2 "
        "(docs/crank-rocker.md §7)"
    ]
    given = [("swing", "rocker swing", ANGLE, swing), ("rocker", "rocker length", LENGTH, rocker_length)]
    if pivot is not None:
        if time_ratio is not None or frame is not None:
            raise SpecError(
                "--pivot fixes the time ratio and the frame; give it without --time-ratio and --frame"
            )
        _finite(pivot_x=pivot[0], pivot_y=pivot[1])
        c = cr.crank_rocker_at_pivot(pivot[0], pivot[1], swing, rocker_length)
        if not c.admissible:
            raise InfeasibleDesign(
                f"the crank pivot ({pivot[0]:g}, {pivot[1]:g}) does not see both extreme positions "
                "on one side of the frame line, so the crank would swing the rocker to another "
                "position; move the pivot (e.g. onto the swing bisector's side away from the chord C1C2)"
            )
        given += [
            ("pivot_x", "crank pivot x", LENGTH, pivot[0]),
            ("pivot_y", "crank pivot y", LENGTH, pivot[1]),
        ]
        task = "from the two extreme rocker positions and a given crank pivot"
        k_asked = None
    else:
        if time_ratio is None:
            raise SpecError("give --time-ratio K (or a crank pivot with --pivot X,Y)")
        _time_ratio_at_least_one(time_ratio)
        given.insert(0, ("time_ratio", "time ratio K", RATIO, time_ratio))
        k_asked = time_ratio
        if frame is not None:
            found = cr.crank_rockers_at_frame(time_ratio, swing, rocker_length, frame)
            if not found:
                lo, hi = cr.frame_range(time_ratio, swing, rocker_length)
                raise InfeasibleDesign(
                    f"no crank pivot on the design circle for K = {time_ratio:g} lies at frame "
                    f"length {frame:g} with both extreme positions on one side of the frame line; "
                    "the crank-rockers for these "
                    f"K and swing have frame lengths from about {lo:.4g} to {hi:.4g}"
                )
            c = found[0]
            given.append(("frame", "frame length", LENGTH, frame))
            task = "from K, the two extreme rocker positions and the frame length"
            if len(found) > 1:
                notes.append(
                    f"{len(found)} crank pivots on the design circle have this frame length; shown: the one "
                    "with the best transmission angle"
                )
        else:
            if time_ratio <= 1.0:
                raise InfeasibleDesign(
                    "at K = 1 the best transmission angle has no optimum (it approaches 90 deg - swing/2 as "
                    "the frame grows without bound); give --frame, or K > 1"
                )
            c = cr.from_optimum(cr.optimal_crank_rocker(time_ratio, swing, rocker_length))
            task = "from K and the two extreme rocker positions, best minimum transmission angle"
    m = cr.measure_motion(cr.linkage(c))
    pressure = 0.5 * math.pi - c.transmission
    return SynthesisReport(
        mechanism="crank-rocker",
        task=task,
        given=tuple(given),
        lengths=(
            ("crank", "crank", c.crank),
            ("coupler", "coupler", c.coupler),
            ("rocker", "rocker", c.rocker),
            ("frame", "frame", c.frame),
            ("pivot_x", "crank pivot x", c.crank_pivot_x),
            ("pivot_y", "crank pivot y", c.crank_pivot_y),
        ),
        indicators=(
            Indicator("swing", "rocker swing", ANGLE, swing, swing, m.swing),
            Indicator("time_ratio", "time ratio K", RATIO, k_asked, c.time_ratio, m.time_ratio),
            Indicator(
                "min_transmission",
                "min transmission angle",
                ANGLE,
                None,
                c.transmission,
                m.transmission,
            ),
        ),
        pressure=PressureCheck(
            "largest pressure angle (coupler on rocker)",
            0.5 * math.pi - m.transmission if np.isfinite(m.transmission) else pressure,
            PERMISSIBLE_PRESSURE_REVOLUTE_DEG,
            "revolute",
        ),
        notes=tuple(notes),
    )

"""The textbook's crank-rocker problems as reports (``pumplink rocker``) and the check of the
optimal-transmission crank-rocker (``pumplink transmission``).

The reports, their indicators and the verdict are those of :mod:`pumplink.studies.textbook`
(docs/mechanisms.md); here the crank-rocker runs through a full crank turn
(:func:`fourbar_extremes`, :func:`pumplink.mechanisms.crank_rocker.measure_motion`).

Pure functions: no I/O.  Angles in radians (the output layer converts).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.errors import InfeasibleDesign, SpecError
from pumplink.evaluate import Verdict
from pumplink.mechanisms import crank_rocker as cr
from pumplink.mechanisms import crank_rocker_synthesis as crs
from pumplink.mechanisms.fourbar import FourBar
from pumplink.studies.textbook import (
    ANGLE,
    LENGTH,
    RATIO,
    TAU,
    Indicator,
    SynthesisReport,
    judge,
    require_finite,
    require_positive,
    require_time_ratio,
    wrap_angle,
)


# ----------------------------------------------------------------------------- crank-rocker
@dataclass(frozen=True)
class FourBarExtremes:
    """Extremes of a crank-rocker measured over one crank turn (angles in radians).

    Attributes
    ----------
    gamma_min, gamma_max : smallest and largest transmission angle.
    extended, folded : crank angles where the rocker stops with crank and coupler stretched out
        resp. folded (the dead centres), CCW from +x in [0, 2 pi).
    """

    gamma_min: float
    gamma_max: float
    extended: float
    folded: float


def fourbar_extremes(lk: FourBar, samples: int = 4096) -> FourBarExtremes:
    """Run a crank-rocker through a full crank turn: its transmission-angle extremes and dead centres.

    Only the position kinematics (:func:`pumplink.mechanisms.fourbar.kinematic_state`) are used:
    the transmission angle's extremes are refined from a sweep with a bracketing minimiser, the
    dead centres are the roots of the rocker rate
    (:func:`pumplink.mechanisms.crank_rocker.rocker_stops`), told apart by the distance of the
    coupler point from the crank pivot (coupler + crank when stretched out).
    """
    from scipy.optimize.elementwise import find_minimum

    from pumplink.mechanisms.fourbar import kinematic_state

    nan = float("nan")
    step = TAU / samples
    th = (np.arange(samples) + 0.5) * step  # half a step off round angles (symmetric designs)
    st = kinematic_state(lk, th)
    if not np.all(np.isfinite(st.coupler_x)):
        return FourBarExtremes(nan, nan, nan, nan)

    def smallest(f, values):
        j = int(np.argmin(values))
        res = find_minimum(f, (th[j] - step, th[j], th[j] + step), tolerances=dict(xatol=1e-14, xrtol=1e-15))
        return min(float(res.f_x), float(values[j])) if bool(res.success) else float(values[j])

    g = st.transmission_angle
    gmin = smallest(lambda x: kinematic_state(lk, x).transmission_angle, g)
    gmax = -smallest(lambda x: -kinematic_state(lk, x).transmission_angle, -g)
    rate = np.append(st.rocker_rate, st.rocker_rate[0])
    roots = cr.rocker_stops(lk, np.append(th, th[0] + TAU), rate)
    if roots is None:
        return FourBarExtremes(gmin, gmax, nan, nan)
    ends = kinematic_state(lk, roots)
    far = np.hypot(ends.coupler_x, ends.coupler_y) > float(lk.coupler)
    if bool(far[0]) == bool(far[1]):
        return FourBarExtremes(gmin, gmax, nan, nan)
    extended, folded = (roots[0], roots[1]) if far[0] else (roots[1], roots[0])
    return FourBarExtremes(gmin, gmax, wrap_angle(extended), wrap_angle(folded))


def rocker_dead_centres(c: crs.CrankRocker) -> tuple[float, float]:
    """Crank angles (CCW from +x, [0, 2 pi)) of a crank-rocker's dead centres, by construction.

    At the extended dead centre the crank points from A to the farther extreme position (|A C| =
    coupler + crank), at the folded one away from the nearer (|A C| = coupler - crank)
    (docs/crank-rocker.md §7).
    """
    (x1, y1), (x2, y2) = crs.extreme_positions(c.swing, c.rocker)
    ax, ay = c.crank_pivot_x, c.crank_pivot_y
    near, far = ((x1, y1), (x2, y2))
    if math.hypot(x1 - ax, y1 - ay) > math.hypot(x2 - ax, y2 - ay):
        near, far = far, near
    extended = math.atan2(far[1] - ay, far[0] - ax)
    folded = math.atan2(ay - near[1], ax - near[0])
    return wrap_angle(extended), wrap_angle(folded)


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
    require_positive(rocker=rocker_length, frame=frame)
    require_finite(swing=swing, time_ratio=time_ratio)
    if not 0.0 < swing < math.pi:
        raise SpecError(f"--swing {math.degrees(swing):g} deg must be between 0 and 180 deg")
    notes = [
        "rocker pivot D at the origin, swing bisector +y, extreme positions C1 (-x side) and C2; "
        "crank angles counter-clockwise from +x (docs/crank-rocker.md §7)"
    ]
    given = [("swing", "rocker swing", ANGLE, swing), ("rocker", "rocker length", LENGTH, rocker_length)]
    if pivot is not None:
        if time_ratio is not None or frame is not None:
            raise SpecError(
                "--pivot fixes the time ratio and the frame; give it without --time-ratio and --frame"
            )
        require_finite(pivot_x=pivot[0], pivot_y=pivot[1])
        c = crs.crank_rocker_at_pivot(pivot[0], pivot[1], swing, rocker_length)
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
        require_time_ratio(time_ratio)
        given.insert(0, ("time_ratio", "time ratio K", RATIO, time_ratio))
        k_asked = time_ratio
        if frame is not None:
            found = crs.crank_rockers_at_frame(time_ratio, swing, rocker_length, frame)
            if not found:
                lo, hi = crs.frame_range(time_ratio, swing, rocker_length)
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
                    "at K = 1 the best transmission angle has no optimum (it approaches "
                    f"{90.0 - math.degrees(swing) / 2:.6g}° as the frame grows without bound); give "
                    "--frame, or K > 1"
                )
            c = crs.from_optimum(cr.optimal_crank_rocker(time_ratio, swing, rocker_length))
            task = "from K and the two extreme rocker positions, best minimum transmission angle"
    lk = crs.linkage(c)
    m = cr.measure_motion(lk)
    x = fourbar_extremes(lk)
    extended, folded = rocker_dead_centres(c)
    indicators = (
        Indicator("swing", "rocker swing", ANGLE, swing, swing, m.swing),
        Indicator("time_ratio", "time ratio K", RATIO, k_asked, c.time_ratio, m.time_ratio),
        Indicator("min_transmission", "min transmission angle", ANGLE, None, c.transmission, m.transmission),
        Indicator("gamma_min", "transmission γmin", ANGLE, None, c.gamma_min, x.gamma_min),
        Indicator("gamma_max", "transmission γmax", ANGLE, None, c.gamma_max, x.gamma_max),
        Indicator("dead_centre_extended", "dead centre, extended", ANGLE, None, extended, x.extended),
        Indicator("dead_centre_folded", "dead centre, folded", ANGLE, None, folded, x.folded),
    )
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
        indicators=indicators,
        verdict=judge(indicators, transmission=m.transmission),
        pairs="revolute",
        notes=tuple(notes),
    )


# ----------------------------------------------------------------------------- transmission
@dataclass(frozen=True)
class OptimumCheck:
    """``pumplink transmission``'s check: the optimum against its own simulation, and the verdict.

    Attributes
    ----------
    indicators : swing and K (asked, closed form, simulated) and the effective minimum
        transmission angle (closed form, simulated).
    verdict : ``transmission_angle`` and ``simulation`` checks (:func:`judge`).
    """

    indicators: tuple[Indicator, ...]
    verdict: Verdict

    @property
    def agrees(self) -> bool:
        """True when the simulated linkage swings as asked, with the asked K and the optimum's
        transmission angle."""
        return all(i.agrees for i in self.indicators)


def optimum_check(opt: cr.OptimalCrankRocker, sim: cr.MeasuredMotion, time_ratio: float, swing: float):
    """Judge an optimal-transmission crank-rocker (scalar) by its simulation ``sim``.

    Parameters
    ----------
    opt : :func:`pumplink.mechanisms.crank_rocker.optimal_crank_rocker` for K and swing.
    sim : :func:`pumplink.mechanisms.crank_rocker.measure_motion` of its linkage.
    time_ratio : the asked K;  swing : the asked swing [rad].
    """
    indicators = (
        Indicator("swing", "rocker swing", ANGLE, swing, float(opt.swing), sim.swing),
        Indicator("time_ratio", "time ratio K", RATIO, time_ratio, float(opt.time_ratio), sim.time_ratio),
        Indicator(
            "min_transmission",
            "min transmission angle",
            ANGLE,
            None,
            float(opt.transmission),
            sim.transmission,
        ),
    )
    return OptimumCheck(indicators, judge(indicators, transmission=sim.transmission))


@dataclass(frozen=True)
class TransmissionStudy:
    """``pumplink transmission``: the optimal-transmission crank-rocker for K and the swing, its
    linkage run (the swing and K it really makes), the published designs it is compared with (the
    paper's worked example only) and the verdict on it (:func:`optimum_check`)."""

    optimum: cr.OptimalCrankRocker
    motion: cr.MeasuredMotion
    comparisons: list
    published_gamma_min_deg: float
    check: OptimumCheck


def transmission(time_ratio: float, swing: float, rocker: float, compare: bool = True) -> TransmissionStudy:
    """The optimal-transmission crank-rocker for the time ratio ``time_ratio``, the rocker swing
    ``swing`` [rad] and the rocker length ``rocker`` (the optimal-transmission paper's problem,
    solved exactly), run and judged.

    Raises
    ------
    InfeasibleDesign : no point of the design circle gives a crank-rocker.
    """
    opt = cr.optimal_crank_rocker(time_ratio, swing, rocker)
    if not math.isfinite(opt.transmission):  # no point of the design circle gives a crank-rocker
        raise InfeasibleDesign(
            f"no crank-rocker found for time ratio K = {time_ratio:g} and swing {math.degrees(swing):g}° "
            f"(extreme included angle θ = {math.degrees(opt.theta):.4g}°); give a time ratio closer to 1"
        )
    sim = cr.measure_motion(cr.optimum_linkage(opt))
    published = compare and cr.is_published_example(time_ratio, math.degrees(swing), rocker)
    comps = cr.published_comparisons() if published else []
    check = optimum_check(opt, sim, time_ratio, swing)
    return TransmissionStudy(opt, sim, comps, cr.PUBLISHED_GAMMA_MIN_DEG, check)


def design_chart():
    """The design chart of the optimal-transmission crank-rocker (``pumplink transmission --chart``;
    :func:`pumplink.mechanisms.crank_rocker.design_chart`)."""
    return cr.design_chart()

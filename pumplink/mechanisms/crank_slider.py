"""Crank-slider (piston drive) kinematics, quality indicators and synthesis.

Source: the lever-mechanism textbook, §2.4 (quality indicators) and §3 (synthesis of a
crank-slider mechanism, Tasks 1 and 2); derivations and the places where the printed textbook
is wrong are in docs/mechanisms.md §1.

Convention (docs/mechanisms.md §1)::

        y
        ^        A (crank pin)
        |       / \\  rod, length l
        |  r   /   \\
        |     /     [B]----  guide y = e (parallel to x)
        O ---+-------------> x
      crank pivot

* The crank pivot O is the origin, the crank angle ``crank_angle`` is measured
  counter-clockwise from +x: A = r (cos t, sin t).
* The slider B moves on the line y = ``offset`` (parallel to x); its position is its x
  coordinate s.  The assembly branch is the one with B to the +x side of the crank pin
  (s - x_A > 0), the usual piston drive with the cylinder on the +x side.
* The mechanism turns fully (a crank-slider) iff r > 0 and l > r + |e| (strict: at
  l = r + |e| the rod stands perpendicular to the guide once a turn, a dead position of the
  slider-driven mechanism and a branch point).

Every function is pure numpy and broadcasts over arrays of designs and angles; angles are in
radians, lengths in any one unit (the caller's).  Quantities of the whole cycle are NaN where
the design does not turn fully; positions at one crank angle are NaN where the linkage cannot
be assembled there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Reason codes of the synthesis functions (0 = a realisable crank-slider).
OK = 0
INPUT_NOT_FINITE = 1
STROKE_NOT_POSITIVE = 2
ROD_RATIO_NOT_ABOVE_ONE = 3
OFFSET_TOO_LARGE = 4
TIME_RATIO_BELOW_ONE = 5
TIME_RATIO_TOO_LARGE = 6

#: One sentence per reason code.
REASONS = {
    OK: "the design is a crank-slider that turns fully",
    INPUT_NOT_FINITE: "an input is not a finite number",
    STROKE_NOT_POSITIVE: "the stroke must be positive",
    ROD_RATIO_NOT_ABOVE_ONE: "the rod ratio l/r must exceed 1, else the crank cannot turn fully",
    OFFSET_TOO_LARGE: "the rod must be longer than crank + |offset| (l/r > 1 + |e/r|), "
    "else the crank cannot turn fully",
    TIME_RATIO_BELOW_ONE: "the time ratio K must be at least 1 (K is slow stroke over fast stroke)",
    TIME_RATIO_TOO_LARGE: "no crank-slider with this rod ratio reaches this time ratio; "
    "K must stay below largest_time_ratio(rod_ratio) - lengthen the rod ratio",
}


def _arrays(*values):
    return np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values))


def _out(x):
    """0-d arrays back to floats, so scalar calls return scalars."""
    x = np.asarray(x)
    return x[()] if x.ndim == 0 else x


def turns_fully(crank_length, rod_length, offset):
    """True where the crank can turn a full revolution (r > 0 and l > r + |e|).

    Parameters
    ----------
    crank_length, rod_length, offset : crank r, rod l, guide offset e [length].

    Returns
    -------
    bool or bool array.  Source: the lever-mechanism textbook, §3 (condition for the
    existence of a crank); docs/mechanisms.md §1.
    """
    r, rod, e = _arrays(crank_length, rod_length, offset)
    with np.errstate(invalid="ignore"):
        return _out((r > 0) & (rod > r + np.abs(e)))  # Eq. (1.7)


def _rod_run(r, rod, e, t):
    """Horizontal run of the rod, sqrt(l^2 - (e - r sin t)^2), NaN where it cannot assemble."""
    rise = e - r * np.sin(t)
    square = rod * rod - rise * rise
    with np.errstate(invalid="ignore"):
        run = np.sqrt(np.where(square >= 0.0, square, np.nan))
    return rise, run


def slider_position(crank_length, rod_length, offset, crank_angle):
    """Slider position s (x coordinate of B) at a crank angle.

    Parameters
    ----------
    crank_length, rod_length, offset : crank r, rod l, guide offset e [length].
    crank_angle : crank angle t, counter-clockwise from +x [rad].

    Returns
    -------
    s [length]: s = r cos t + sqrt(l^2 - (e - r sin t)^2) (Eq. 1.1); NaN where the linkage
    cannot be assembled at this angle.  Source: docs/mechanisms.md §1.
    """
    r, rod, e, t = _arrays(crank_length, rod_length, offset, crank_angle)
    _, run = _rod_run(r, rod, e, t)
    return _out(r * np.cos(t) + run)  # Eq. (1.1)


def velocity_ratio(crank_length, rod_length, offset, crank_angle):
    """Velocity ratio ds/dt of the slider [length/rad] (slider speed over crank speed).

    Parameters
    ----------
    crank_length, rod_length, offset : crank r, rod l, guide offset e [length].
    crank_angle : crank angle t [rad].

    Returns
    -------
    ds/dt = -r sin t + r cos t (e - r sin t) / sqrt(l^2 - (e - r sin t)^2) (Eq. 1.2); NaN where
    the linkage cannot be assembled or the rod stands perpendicular to the guide.
    Source: docs/mechanisms.md §1.
    """
    r, rod, e, t = _arrays(crank_length, rod_length, offset, crank_angle)
    rise, run = _rod_run(r, rod, e, t)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = -r * np.sin(t) + r * np.cos(t) * rise / np.where(run > 0.0, run, np.nan)  # Eq. (1.2)
    return _out(ratio)


def pressure_angle(crank_length, rod_length, offset, crank_angle):
    """Pressure angle of the slider: the acute angle between the rod and the guide [rad].

    The rod force on the slider acts along the rod, the slider's velocity along the guide, so
    this is the pressure angle of the driven slider (the lever-mechanism textbook, §2.4,
    Fig. 3.3).

    Parameters
    ----------
    crank_length, rod_length, offset : crank r, rod l, guide offset e [length].
    crank_angle : crank angle t [rad].

    Returns
    -------
    lambda in [0, pi/2] [rad]: atan2(|e - r sin t|, sqrt(l^2 - (e - r sin t)^2)), that is
    asin(|e - r sin t| / l) (Eq. 1.3); NaN where the linkage cannot be assembled.
    """
    r, rod, e, t = _arrays(crank_length, rod_length, offset, crank_angle)
    rise, run = _rod_run(r, rod, e, t)
    return _out(np.arctan2(np.abs(rise), run))  # Eq. (1.3)


def transmission_angle(crank_length, rod_length, offset, crank_angle):
    """Transmission angle gamma = pi/2 - pressure angle [rad] (the lever-mechanism textbook, §2.4).

    Parameters
    ----------
    crank_length, rod_length, offset : crank r, rod l, guide offset e [length].
    crank_angle : crank angle t [rad].
    """
    return _out(0.5 * np.pi - np.asarray(pressure_angle(crank_length, rod_length, offset, crank_angle)))


def dead_centres(crank_length, rod_length, offset):
    """Crank angles of the two extreme slider positions (crank and rod collinear) [rad].

    Parameters
    ----------
    crank_length, rod_length, offset : crank r, rod l, guide offset e [length].

    Returns
    -------
    extended, folded : crank angles [rad].  ``extended`` (crank and rod in line, slider
    farthest, |OB| = l + r) is atan2(e, sqrt((l + r)^2 - e^2)) in (-pi/2, pi/2); ``folded``
    (rod folded back over the crank, slider nearest, |OB| = l - r) is
    pi + atan2(e, sqrt((l - r)^2 - e^2)) in (pi/2, 3 pi/2) (Eq. 1.4).  NaN where the crank does
    not turn fully.  Source: docs/mechanisms.md §1.
    """
    r, rod, e = _arrays(crank_length, rod_length, offset)
    full = np.asarray(turns_fully(r, rod, e))
    with np.errstate(invalid="ignore"):
        far = np.sqrt(np.where(full, (rod + r) ** 2 - e * e, np.nan))
        near = np.sqrt(np.where(full, (rod - r) ** 2 - e * e, np.nan))
    extended = np.arctan2(e, far)  # Eq. (1.4)
    folded = np.pi + np.arctan2(e, near)  # Eq. (1.4)
    return _out(extended), _out(folded)


def stroke(crank_length, rod_length, offset):
    """Stroke H of the slider: distance between its two extreme positions [length].

    Returns
    -------
    H = sqrt((l + r)^2 - e^2) - sqrt((l - r)^2 - e^2) (Eq. 1.5); NaN where the crank does not
    turn fully.  Source: the lever-mechanism textbook, §2.4 (definition of the stroke);
    docs/mechanisms.md §1.
    """
    r, rod, e = _arrays(crank_length, rod_length, offset)
    full = np.asarray(turns_fully(r, rod, e))
    with np.errstate(invalid="ignore"):
        far = np.sqrt(np.where(full, (rod + r) ** 2 - e * e, np.nan))
        near = np.sqrt(np.where(full, (rod - r) ** 2 - e * e, np.nan))
    return _out(far - near)  # Eq. (1.5)


def extreme_rod_angle(crank_length, rod_length, offset):
    """Angle theta between the rod positions at the two dead centres (angle B1 O B2) [rad].

    Returns
    -------
    theta = |asin(e / (l - r)) - asin(e / (l + r))| in [0, pi/2) (Eq. 1.6); the crank turns
    pi + theta on one stroke and pi - theta on the other.  NaN where the crank does not turn
    fully.  Source: docs/mechanisms.md §1.
    """
    r, rod, e = _arrays(crank_length, rod_length, offset)
    full = np.asarray(turns_fully(r, rod, e))
    with np.errstate(invalid="ignore", divide="ignore"):
        near = np.arcsin(np.where(full, e / (rod - r), np.nan))
        far = np.arcsin(np.where(full, e / (rod + r), np.nan))
    return _out(np.abs(near - far))  # Eq. (1.6)


def time_ratio(crank_length, rod_length, offset):
    """Time ratio K >= 1 (slow stroke time over fast stroke time at constant crank speed).

    Returns
    -------
    K = (pi + theta) / (pi - theta) with theta from :func:`extreme_rod_angle` (Eq. 1.8); NaN where
    the crank does not turn fully.  With the crank turning counter-clockwise and e > 0 the slow
    stroke is the one towards the crank pivot (-x).  Source: the lever-mechanism textbook, §3.1.
    """
    theta = np.asarray(extreme_rod_angle(crank_length, rod_length, offset))
    return _out((np.pi + theta) / (np.pi - theta))  # Eq. (1.8)


def largest_pressure_angle(crank_length, rod_length, offset):
    """Largest pressure angle over a full crank turn [rad].

    Returns
    -------
    lambda_max = asin((r + |e|) / l) (Eq. 1.9), reached where the crank is perpendicular to the
    guide, on the side away from the guide (sin t = -sign(e)); NaN where the crank does not turn
    fully.  The textbook prints asin((1 + nu)/L), which holds for nu = e/r >= 0 only.
    Source: the lever-mechanism textbook, §3 (Fig. 3.3); docs/mechanisms.md §1.
    """
    r, rod, e = _arrays(crank_length, rod_length, offset)
    full = np.asarray(turns_fully(r, rod, e))
    with np.errstate(invalid="ignore", divide="ignore"):
        return _out(np.arcsin(np.where(full, (r + np.abs(e)) / rod, np.nan)))  # Eq. (1.9)


def extreme_angle_from_time_ratio(time_ratio):
    """theta = pi (K - 1) / (K + 1) [rad] (the lever-mechanism textbook, §3.1; Eq. 1.8 inverted)."""
    k = np.asarray(time_ratio, dtype=float)
    return _out(np.pi * (k - 1.0) / (k + 1.0))  # Eq. (1.8)


def largest_time_ratio(rod_ratio):
    """Supremum of the time ratio K of crank-sliders with rod ratio L = l/r > 1.

    Returns
    -------
    K_max = (pi + theta*) / (pi - theta*) with theta* = 2 atan(1/sqrt(L)), i.e.
    cos theta* = (L - 1)/(L + 1) (Eq. 1.12).  It is approached as the offset grows to
    e = l - r and is not reached by any crank that turns fully.  NaN for L <= 1.
    Source: docs/mechanisms.md §1.
    """
    L = np.asarray(rod_ratio, dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        theta = np.where(L > 1.0, 2.0 * np.arctan(1.0 / np.sqrt(np.where(L > 1.0, L, np.nan))), np.nan)
    return _out((np.pi + theta) / (np.pi - theta))  # Eq. (1.12)


@dataclass(frozen=True)
class CrankSliderDesign:
    """A synthesised crank-slider and its measured quality indicators.

    Lengths are in the caller's unit, angles in radians; the indicators are measured on the
    synthesised lengths with the analysis functions of this module (not copied from the request).
    Where ``reason != OK`` every field but ``reason`` is NaN.

    Attributes
    ----------
    crank_length, rod_length, offset : r, l, e [length] (e >= 0 for Task 2, see docs §1.3).
    stroke : measured stroke H [length].
    time_ratio : measured time ratio K [-].
    extreme_rod_angle : measured theta, angle B1 O B2 [rad].
    largest_pressure_angle : measured lambda_max [rad].
    reason : reason code (``OK`` = 0 or one of the module's codes, see ``REASONS``).
    """

    crank_length: np.ndarray | float
    rod_length: np.ndarray | float
    offset: np.ndarray | float
    stroke: np.ndarray | float
    time_ratio: np.ndarray | float
    extreme_rod_angle: np.ndarray | float
    largest_pressure_angle: np.ndarray | float
    reason: np.ndarray | int

    @property
    def ok(self):
        """True where the design is realisable."""
        return _out(np.asarray(self.reason) == OK)


def _design(r, rod, e, reason, too_large):
    good = reason == OK
    # on the boundary rounding may leave l - r - |e| <= 0: refuse rather than return NaN indicators
    with np.errstate(invalid="ignore"):
        fits = np.asarray(
            turns_fully(np.where(good, r, 1.0), np.where(good, rod, 3.0), np.where(good, e, 0.0))
        )
    reason = np.where(good & ~fits, too_large, reason)
    good = reason == OK
    r, rod, e = (np.where(good, x, np.nan) for x in (r, rod, e))
    return CrankSliderDesign(
        crank_length=_out(r),
        rod_length=_out(rod),
        offset=_out(e),
        stroke=stroke(r, rod, e),
        time_ratio=time_ratio(r, rod, e),
        extreme_rod_angle=extreme_rod_angle(r, rod, e),
        largest_pressure_angle=largest_pressure_angle(r, rod, e),
        reason=_out(reason.astype(int)),
    )


def synthesize_from_stroke(stroke, rod_ratio, offset_ratio=0.0):
    """Task 1: crank-slider from its stroke H and rod ratio L = l/r (and offset ratio nu = e/r).

    Parameters
    ----------
    stroke : H [length], > 0.
    rod_ratio : L = l/r [-].
    offset_ratio : nu = e/r [-] (0 for the central crank-slider of the textbook's Task 1).

    Returns
    -------
    CrankSliderDesign with r = H/h, h = sqrt((L + 1)^2 - nu^2) - sqrt((L - 1)^2 - nu^2)
    (Eq. 1.10; h = 2 for nu = 0), l = L r, e = nu r; realisable iff L > 1 + |nu|.
    Source: the lever-mechanism textbook, §3, Task 1; docs/mechanisms.md §1.
    """
    H, L, nu = _arrays(stroke, rod_ratio, offset_ratio)
    reason = np.full(H.shape, OK)
    finite = np.isfinite(H) & np.isfinite(L) & np.isfinite(nu)
    reason = np.where(~finite, INPUT_NOT_FINITE, reason)
    with np.errstate(invalid="ignore"):
        reason = np.where((reason == OK) & ~(H > 0), STROKE_NOT_POSITIVE, reason)
        reason = np.where((reason == OK) & ~(L > 1), ROD_RATIO_NOT_ABOVE_ONE, reason)
        reason = np.where((reason == OK) & ~(L > 1 + np.abs(nu)), OFFSET_TOO_LARGE, reason)
        good = reason == OK
        Lg, nug = np.where(good, L, 2.0), np.where(good, nu, 0.0)
        h = np.sqrt((Lg + 1) ** 2 - nug * nug) - np.sqrt((Lg - 1) ** 2 - nug * nug)  # Eq. (1.10)
        r = np.where(good, H, 1.0) / h
    return _design(r, Lg * r, nug * r, reason, OFFSET_TOO_LARGE)


def synthesize_from_time_ratio(stroke, time_ratio, rod_ratio):
    """Task 2: offset crank-slider from its stroke H, time ratio K and rod ratio L = l/r.

    Parameters
    ----------
    stroke : H [length], > 0.
    time_ratio : K >= 1 [-]; K < largest_time_ratio(L) is required.
    rod_ratio : L = l/r > 1 [-].

    Returns
    -------
    CrankSliderDesign with theta = pi (K - 1)/(K + 1) (Eq. 1.8),
    h = H/r = sqrt(2 [(L^2 + 1) - (L^2 - 1) cos theta]) (Eq. 1.11a),
    nu = e/r = (L^2 - 1) sin theta / h (Eq. 1.11b), r = H/h, l = L r, e = nu r >= 0.
    Realisable iff L > 1 and 1 <= K < largest_time_ratio(L); beyond that the formulas still
    give lengths, but the triangle O B1 B2 they solve is not the dead-centre triangle of any
    crank-slider (its angle at B2 is acute), so NaN and ``TIME_RATIO_TOO_LARGE`` are returned.
    Source: the lever-mechanism textbook, §3, Task 2 (printed formulas scrambled; see
    docs/mechanisms.md §1).
    """
    H, K, L = _arrays(stroke, time_ratio, rod_ratio)
    reason = np.full(H.shape, OK)
    finite = np.isfinite(H) & np.isfinite(K) & np.isfinite(L)
    reason = np.where(~finite, INPUT_NOT_FINITE, reason)
    with np.errstate(invalid="ignore"):
        reason = np.where((reason == OK) & ~(H > 0), STROKE_NOT_POSITIVE, reason)
        reason = np.where((reason == OK) & ~(L > 1), ROD_RATIO_NOT_ABOVE_ONE, reason)
        reason = np.where((reason == OK) & ~(K >= 1), TIME_RATIO_BELOW_ONE, reason)
        good = reason == OK
        Lg, Kg = np.where(good, L, 2.0), np.where(good, K, 1.0)
        theta = np.pi * (Kg - 1) / (Kg + 1)  # Eq. (1.8)
        # Eq. (1.12): K < K_max  <=>  cos theta > (L - 1)/(L + 1)  <=>  (L + 1) cos theta > L - 1
        reason = np.where(good & ~((Lg + 1) * np.cos(theta) > Lg - 1), TIME_RATIO_TOO_LARGE, reason)
        h = np.sqrt(2.0 * ((Lg * Lg + 1) - (Lg * Lg - 1) * np.cos(theta)))  # Eq. (1.11a)
        nu = (Lg * Lg - 1) * np.sin(theta) / h  # Eq. (1.11b)
        r = np.where(reason == OK, H, 1.0) / h
    return _design(r, Lg * r, nu * r, reason, TIME_RATIO_TOO_LARGE)


def infeasibility_reason(crank_length, rod_length, offset) -> str | None:
    """Why the crank of this crank-slider cannot turn a full revolution, with the fix, or None
    when it can (:func:`turns_fully`; one design, lengths in metres)."""
    r, rod, e = float(crank_length), float(rod_length), float(offset)
    if bool(turns_fully(r, rod, e)):
        return None
    return (
        f"rod {rod:g} m is not longer than crank {r:g} m + |offset| {abs(e):g} m, so the crank cannot "
        f"turn fully; lengthen the rod beyond {r + abs(e):g} m"
    )

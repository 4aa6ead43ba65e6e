"""Crank and slotted lever (oscillating-lever quick return): kinematics and synthesis from K.

Source: the lever-mechanism textbook, §3 ("synthesis of the rocker mechanism according to the
coefficient k"); derivations and where the printed textbook differs are in docs/mechanisms.md §2.

Convention (docs/mechanisms.md §2)::

                       B        lever tip, |CB| = lever_length
                      /
                     /
          O---------A           crank O-A, length r, angle t from +x (here t = 0);
          |        /            A carries the block that slides in the lever's slot
        d |       /
          |      /              the lever C-A-B is one straight slotted link
          |     /
          |    /
          |   /
          C--´                  lever pivot C = (0, 0); crank pivot O = (0, d)

* The lever pivot C is the origin and the crank pivot O = (0, d) lies on +y, d = ``frame_length``.
* The crank angle t is counter-clockwise from +x: A = O + r (cos t, sin t).
* The lever is the line C -> A; its angle ``lever_angle`` phi is counter-clockwise from +x and
  stays in (0, pi) when r < d.  The lever tip is B = lever_length (cos phi, sin phi).
* The mechanism is an oscillating-lever quick return iff 0 < r < d (for r >= d the lever turns
  fully: that is the rotating-lever (Whitworth) mechanism, not this one).

All functions are pure numpy and broadcast over designs and angles; angles in radians, lengths in
any one unit (the caller's); NaN where the design is not an oscillating slotted lever.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Reason codes of :func:`synthesize_from_time_ratio` (0 = realisable).
OK = 0
INPUT_NOT_FINITE = 1
STROKE_NOT_POSITIVE = 2
FRAME_NOT_POSITIVE = 3
TIME_RATIO_NOT_ABOVE_ONE = 4
SLOT_TOO_SHORT = 5
CRANK_NOT_POSITIVE = 6
LEVER_NOT_POSITIVE = 7

#: One sentence per reason code.
REASONS = {
    OK: "the design is a crank and slotted lever with the requested time ratio and stroke",
    INPUT_NOT_FINITE: "an input is not a finite number",
    STROKE_NOT_POSITIVE: "the stroke must be positive",
    FRAME_NOT_POSITIVE: "the frame length (crank pivot to lever pivot) must be positive",
    TIME_RATIO_NOT_ABOVE_ONE: "a slotted lever's time ratio exceeds 1 (K = 1 needs a zero crank "
    "and an infinite lever); ask for K > 1",
    SLOT_TOO_SHORT: "the lever is shorter than the block's farthest reach d + r, so the slot "
    "cannot hold the block; choose a shorter frame length",
    CRANK_NOT_POSITIVE: "the crank length must be positive",
    LEVER_NOT_POSITIVE: "the lever length must be positive",
}


def _arrays(*values):
    return np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values))


def _out(x):
    x = np.asarray(x)
    return x[()] if x.ndim == 0 else x


def oscillates(crank_length, frame_length):
    """True where 0 < r < d: the lever oscillates (docs/mechanisms.md §2, Eq. 2.6).

    Parameters
    ----------
    crank_length, frame_length : crank r and pivot distance d [length].
    """
    r, d = _arrays(crank_length, frame_length)
    with np.errstate(invalid="ignore"):
        return _out((r > 0) & (r < d))  # Eq. (2.6)


def _valid(r, d, *rest):
    ok = np.asarray(oscillates(r, d))
    return tuple(np.where(ok, x, np.nan) for x in (r, d, *rest))


def lever_angle(crank_length, frame_length, crank_angle):
    """Lever angle phi, counter-clockwise from +x [rad].

    Parameters
    ----------
    crank_length, frame_length : crank r, pivot distance d [length].
    crank_angle : crank angle t [rad].

    Returns
    -------
    phi = atan2(d + r sin t, r cos t) in (0, pi) (Eq. 2.1); NaN unless 0 < r < d.
    Source: docs/mechanisms.md §2.
    """
    r, d, t = _valid(*_arrays(crank_length, frame_length, crank_angle))
    return _out(np.arctan2(d + r * np.sin(t), r * np.cos(t)))  # Eq. (2.1)


def block_distance(crank_length, frame_length, crank_angle):
    """Distance of the block (crank pin A) from the lever pivot along the slot [length].

    Returns
    -------
    rho = sqrt(r^2 + d^2 + 2 d r sin t) in [d - r, d + r] (Eq. 2.2); NaN unless 0 < r < d.
    """
    r, d, t = _valid(*_arrays(crank_length, frame_length, crank_angle))
    return _out(np.sqrt((d - r) ** 2 + 2.0 * d * r * (1.0 + np.sin(t))))  # Eq. (2.2), as in lever_rate


def lever_rate(crank_length, frame_length, crank_angle):
    """Angular velocity ratio of lever and crank, dphi/dt [-].

    Returns
    -------
    dphi/dt = r (r + d sin t) / (r^2 + d^2 + 2 d r sin t) (Eq. 2.3); zero at the extremes
    (r + d sin t = 0, crank perpendicular to the lever); NaN unless 0 < r < d.
    Source: docs/mechanisms.md §2.
    """
    r, d, t = _valid(*_arrays(crank_length, frame_length, crank_angle))
    s = np.sin(t)
    # rho^2 = r^2 + d^2 + 2 d r sin t written as (d - r)^2 + 2 d r (1 + sin t): no cancellation
    # where the crank points away from the lever pivot (sin t = -1), so rho^2 > 0 whenever r < d
    return _out(r * (r + d * s) / ((d - r) ** 2 + 2.0 * d * r * (1.0 + s)))  # Eq. (2.3)


def swing_angle(crank_length, frame_length):
    """Lever swing psi between its two extremes [rad]: sin(psi/2) = r/d (Eq. 2.4); NaN unless 0 < r < d."""
    r, d = _valid(*_arrays(crank_length, frame_length))
    return _out(2.0 * np.arcsin(r / d))  # Eq. (2.4)


def extremes(crank_length, frame_length):
    """Crank angles at the lever's extremes, where the crank is perpendicular to the lever [rad].

    Returns
    -------
    right, left : t_right = -asin(r/d) (lever at pi/2 - psi/2) and t_left = pi + asin(r/d) (lever
    at pi/2 + psi/2) (Eq. 2.5).  Turning counter-clockwise from right to left the crank sweeps
    pi + psi (the slow stroke, lever turning counter-clockwise); back, pi - psi.  NaN unless
    0 < r < d.  Source: docs/mechanisms.md §2.
    """
    r, d = _valid(*_arrays(crank_length, frame_length))
    half = np.arcsin(r / d)
    return _out(-half), _out(np.pi + half)  # Eq. (2.5)


def time_ratio(crank_length, frame_length):
    """Time ratio K = (pi + psi)/(pi - psi) >= 1 (Eq. 2.7); NaN unless 0 < r < d.

    Source: the lever-mechanism textbook, §3.1 and §3 (rocker mechanism); docs/mechanisms.md §2.
    """
    psi = np.asarray(swing_angle(crank_length, frame_length))
    return _out((np.pi + psi) / (np.pi - psi))  # Eq. (2.7)


def stroke(crank_length, frame_length, lever_length):
    """Stroke of the lever tip B: the distance between its two extreme positions [length].

    Returns
    -------
    H = 2 l sin(psi/2) = 2 l r / d (Eq. 2.8), the chord; the textbook's H = psi l is the arc
    length of the tip's path instead.  NaN unless 0 < r < d.
    """
    r, d, lever = _valid(*_arrays(crank_length, frame_length, lever_length))
    return _out(2.0 * lever * r / d)  # Eq. (2.8)


def tip_position(crank_length, frame_length, lever_length, crank_angle):
    """Lever tip B = l (cos phi, sin phi) [length], as (x, y); NaN unless 0 < r < d."""
    phi = np.asarray(lever_angle(crank_length, frame_length, crank_angle))
    lever = np.asarray(lever_length, dtype=float)
    return _out(lever * np.cos(phi)), _out(lever * np.sin(phi))


def swing_from_time_ratio(time_ratio):
    """psi = pi (K - 1)/(K + 1) [rad] (Eq. 2.7 inverted; the lever-mechanism textbook, §3)."""
    k = np.asarray(time_ratio, dtype=float)
    return _out(np.pi * (k - 1.0) / (k + 1.0))  # Eq. (2.7)


@dataclass(frozen=True)
class SlottedLeverDesign:
    """A synthesised crank and slotted lever and its measured quality indicators.

    Lengths in the caller's unit, angles in radians; where ``reason != OK`` every field but
    ``reason`` is NaN.  The indicators are measured on the synthesised lengths with this module's
    analysis functions.

    Attributes
    ----------
    crank_length, frame_length, lever_length : r, d, l [length].
    swing_angle : measured lever swing psi [rad].
    stroke : measured chord stroke of the lever tip [length].
    time_ratio : measured K [-].
    reason : reason code (see ``REASONS``).
    """

    crank_length: np.ndarray | float
    frame_length: np.ndarray | float
    lever_length: np.ndarray | float
    swing_angle: np.ndarray | float
    stroke: np.ndarray | float
    time_ratio: np.ndarray | float
    reason: np.ndarray | int

    @property
    def ok(self):
        """True where the design is realisable."""
        return _out(np.asarray(self.reason) == OK)


def synthesize_from_time_ratio(
    time_ratio, stroke=None, frame_length=None, *, crank_length=None, lever_length=None
):
    """Slotted lever from its time ratio K, one length that sets the scale and one that sets the lever.

    K fixes the swing psi and so the ratio r/d = sin(psi/2) (Eq. 2.4, 2.7); one of the crank r
    and the frame d then fixes both, and one of the stroke H and the lever l fixes the lever.
    Whichever of the two pairs is not given is chosen so that the slot just holds the block,
    l = d + r (Eq. 2.9 with equality).  The textbook's construction (§3) picks the crank pivot
    on the bisector, i.e. d; Khurmi-style problems give the crank r instead.

    Parameters
    ----------
    time_ratio : K > 1 [-].
    stroke : H > 0 [length], chord between the tip's extreme positions (or None).
    frame_length : d [length], distance of the crank pivot from the lever pivot (or None).
    crank_length : r [length] (keyword; or None).  At most one of ``frame_length`` and
        ``crank_length``.
    lever_length : l [length] (keyword; or None).  At most one of ``stroke`` and
        ``lever_length``; at least one of the four lengths.

    Returns
    -------
    SlottedLeverDesign with psi = pi (K - 1)/(K + 1) (Eq. 2.7), r = d sin(psi/2) (Eq. 2.4),
    l = H / (2 sin(psi/2)) (Eq. 2.8); realisable iff K > 1 (then r < d holds) and l >= d + r
    (Eq. 2.9: the block's farthest reach lies on the lever).  Source: the lever-mechanism
    textbook, §3; docs/mechanisms.md §2.

    Raises
    ------
    ValueError : both of a pair, or no length at all (a programming error, not a reason code).
    """
    if frame_length is not None and crank_length is not None:
        raise ValueError("give at most one of frame_length and crank_length")
    if stroke is not None and lever_length is not None:
        raise ValueError("give at most one of stroke and lever_length")
    scale = frame_length if crank_length is None else crank_length
    size = stroke if lever_length is None else lever_length
    if scale is None and size is None:
        raise ValueError("give one of frame_length, crank_length, stroke, lever_length")
    given = [x for x in (scale, size) if x is not None]
    K, *given = _arrays(time_ratio, *given)
    a = given.pop(0) if scale is not None else None  # d or r
    b = given.pop(0) if size is not None else None  # H or l
    reason = np.where(np.isfinite(K), OK, INPUT_NOT_FINITE)
    for x in (a, b):
        if x is not None:
            reason = np.where(np.isfinite(x), reason, INPUT_NOT_FINITE)
    with np.errstate(invalid="ignore", divide="ignore"):
        checks = (
            (stroke, STROKE_NOT_POSITIVE, b),
            (lever_length, LEVER_NOT_POSITIVE, b),
            (frame_length, FRAME_NOT_POSITIVE, a),
            (crank_length, CRANK_NOT_POSITIVE, a),
        )
        for arg, code, x in checks:
            if arg is not None:
                reason = np.where((reason == OK) & ~(x > 0), code, reason)
        reason = np.where((reason == OK) & ~(K > 1), TIME_RATIO_NOT_ABOVE_ONE, reason)
        good = reason == OK
        Kg = np.where(good, K, 2.0)
        psi = np.pi * (Kg - 1.0) / (Kg + 1.0)  # Eq. (2.7)
        half = np.sin(0.5 * psi)
        if b is not None:
            bg = np.where(good, b, 1.0)
            lever = bg / (2.0 * half) if lever_length is None else bg  # Eq. (2.8)
        if a is not None:
            ag = np.where(good, a, 1.0)
            d = ag if crank_length is None else ag / half  # Eq. (2.4)
        if a is None:
            d = lever / (1.0 + half)  # Eq. (2.9) with equality
        if b is None:
            lever = d * (1.0 + half)  # Eq. (2.9) with equality
        r = ag if crank_length is not None else d * half  # Eq. (2.4)
        reason = np.where(good & ~(lever >= (d + r) * (1.0 - 1e-15)), SLOT_TOO_SHORT, reason)
        good = reason == OK
    r, d, lever = (np.where(good, x, np.nan) for x in (r, d, lever))
    return SlottedLeverDesign(
        crank_length=_out(r),
        frame_length=_out(d),
        lever_length=_out(lever),
        swing_angle=swing_angle(r, d),
        stroke=_stroke(r, d, lever),
        time_ratio=_time_ratio(r, d),
        reason=_out(reason.astype(int)),
    )


# the synthesis' parameter names shadow two analysis functions
_stroke = stroke
_time_ratio = time_ratio

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
    return _out(np.sqrt(r * r + d * d + 2.0 * d * r * np.sin(t)))  # Eq. (2.2)


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
    return _out(r * (r + d * s) / (r * r + d * d + 2.0 * d * r * s))  # Eq. (2.3)


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


def synthesize_from_time_ratio(time_ratio, stroke, frame_length=None):
    """Slotted lever from its time ratio K and the chord stroke H of the lever tip.

    Parameters
    ----------
    time_ratio : K > 1 [-].
    stroke : H > 0 [length], chord between the tip's extreme positions.
    frame_length : d [length], the chosen distance of the crank pivot from the lever pivot;
        None picks the largest d whose slot still holds the block (lever length = d + r).

    Returns
    -------
    SlottedLeverDesign with psi = pi (K - 1)/(K + 1) (Eq. 2.7), l = H / (2 sin(psi/2)) (Eq. 2.8),
    r = d sin(psi/2) (Eq. 2.4); realisable iff K > 1 (then r < d holds) and l >= d + r
    (Eq. 2.9: the block's farthest reach lies on the lever).  With ``frame_length=None``,
    d = l / (1 + sin(psi/2)).  Source: the lever-mechanism textbook, §3; docs/mechanisms.md §2.
    """
    if frame_length is None:
        K, H = _arrays(time_ratio, stroke)
        d = None
    else:
        K, H, d = _arrays(time_ratio, stroke, frame_length)
    finite = np.isfinite(K) & np.isfinite(H) & (True if d is None else np.isfinite(d))
    reason = np.where(finite, OK, INPUT_NOT_FINITE)
    with np.errstate(invalid="ignore", divide="ignore"):
        reason = np.where((reason == OK) & ~(H > 0), STROKE_NOT_POSITIVE, reason)
        if d is not None:
            reason = np.where((reason == OK) & ~(d > 0), FRAME_NOT_POSITIVE, reason)
        reason = np.where((reason == OK) & ~(K > 1), TIME_RATIO_NOT_ABOVE_ONE, reason)
        good = reason == OK
        psi = np.pi * (np.where(good, K, 2.0) - 1.0) / (np.where(good, K, 2.0) + 1.0)  # Eq. (2.7)
        half = np.sin(0.5 * psi)
        lever = np.where(good, H, 1.0) / (2.0 * half)  # Eq. (2.8)
        if d is None:
            d = lever / (1.0 + half)  # Eq. (2.9) with equality
        r = d * half  # Eq. (2.4)
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

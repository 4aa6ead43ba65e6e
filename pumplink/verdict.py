"""The one verdict: which checks a design passes, and PASS, PASS with warnings or FAIL.

Every command that judges a design (``force``, ``speed``, ``batch``, ``optimize``) calls
:func:`assess`; nothing else decides.  The checks, their limits and why each one fails or only
warns are in docs/models.md §4.  Inputs are floats or numpy arrays over designs (broadcast
together).  Each check has a *level* per design: 0 pass, 1 warn, 2 fail; the verdict's level
is the largest (an infeasible design, and a NaN value, fail).

Checks (``Check.key``), in the order they are reported, with the level a value beyond each
limit gets:

* ``mean_force``: the constant push/pull that does the cycle's work; fail above the force limit.
* ``peak_force``: the peak force of the model that decides (docs/models.md §1-2); fail above
  the force limit.
* ``link_energy_share``: the flywheel model's neglected link kinetic energy, as a share of the
  energy band; warn above ``LINK_ENERGY_LIMIT`` (docs/models.md §3).
* ``transmission_angle``: min(γmin, 180° − γmax); warn below ``MIN_TRANSMISSION_DEG``, fail below
  ``FAIL_TRANSMISSION_DEG``.
* ``power``: Mw ω̄; warn above ``SUSTAINED_POWER_W``, fail above ``HOUR_POWER_W``.
* ``cadence``: wheel turns (push-pull cycles) a minute, ω̄ · 60 / 2π; warn outside the operator
  profile's cadence range (30-60 turns a minute; docs/operators.md §6).
* ``rope_speed``: the rope's speed ω̄ r_w; warn outside ``ROPE_SPEED_RANGE_M_S`` (docs/water.md §2a).
* ``grip_speed``: the grip's peak speed at the mean wheel speed; warn above
  ``GRIP_SPEED_WARN_M_S``, fail above ``GRIP_SPEED_FAIL_M_S``.
* ``stroke``: the horizontal grip stroke; warn above ``STROKE_LIMIT_M``.
* ``grip_height``: lowest and highest grip height over the swing (with the axle height); warn
  outside ``GRIP_HEIGHT_RANGE_M``.
* ``axle_height``: warn outside the pump paper's ``AXLE_HEIGHT_RANGE_M``.
* ``pin_pressure``, ``handle_fatigue``, ``crank_fatigue``: with the spec's ``[parts]``, the pins'
  bearing pressure (warn above 12 MPa, fail above 30 MPa) and the fatigue safety factors of the
  handle and the crank (warn below 1.5, fail below 1); docs/workshop.md §2.
* ``kick_back``: the grip's travel back when the handle is let go with water in the rising main;
  fail above ``KICK_BACK_LIMIT_M`` (DGUV Vorschrift 54 § 6); docs/workshop.md §3.
* ``holding_torque``: with a ``[ratchet]``, the torque it holds over the column's; fail below 1.
* ``pin_wear``: with ``[parts]``, the play the worst pin wears open in 6 million turns; warn above
  the allowance (docs/workshop.md §5).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import (
    AXLE_HEIGHT_RANGE_M,
    FAIL_TRANSMISSION_DEG,
    GRIP_HEIGHT_RANGE_M,
    GRIP_SPEED_FAIL_M_S,
    GRIP_SPEED_WARN_M_S,
    HOUR_POWER_W,
    KICK_BACK_LIMIT_M,
    LINK_ENERGY_LIMIT,
    MIN_TRANSMISSION_DEG,
    ROPE_SPEED_RANGE_M_S,
    STROKE_LIMIT_M,
    SUSTAINED_POWER_W,
)

#: Levels of a check or a verdict.
PASS, WARN, FAIL = 0, 1, 2
#: The part checks (with the spec's ``[parts]``; docs/workshop.md §2).
PART_CHECKS = ("pin_pressure", "handle_fatigue", "crank_fatigue")
#: The checks a search judges only where no other check fails (screened): the part checks and the
#: pins' wear, which follows the pin pressure (docs/workshop.md §5).
SCREENED_CHECKS = (*PART_CHECKS, "pin_wear")
#: A level's word in JSON/CSV (``result`` of a check).
RESULTS = ("pass", "warn", "fail")
#: A verdict's words, by level.
OUTCOMES = ("PASS", "PASS with warnings", "FAIL")


@dataclass(frozen=True)
class Check:
    """One verdict line: ``value`` against ``warn_limit`` / ``fail_limit`` by ``relation``.

    ``relation`` is '<=' or '>=' (per design where a check has a limit on each side, like the
    heights); a limit of None does not apply to this check.  ``level`` is 0 pass, 1 warn, 2 fail.
    Scalars for one design, arrays over designs otherwise.
    """

    key: str
    value: np.ndarray | float
    relation: np.ndarray | str
    unit: str
    warn_limit: np.ndarray | float | None
    fail_limit: np.ndarray | float | None
    level: np.ndarray | int

    @property
    def passed(self) -> np.ndarray | bool:
        """True where this check does not fail the design (it may warn)."""
        return _scalar(np.asarray(self.level) < FAIL)

    @property
    def result(self) -> np.ndarray | str:
        """'pass', 'warn' or 'fail' (per design)."""
        return _scalar(np.asarray(RESULTS, dtype=object)[np.asarray(self.level)])

    @property
    def limit(self) -> np.ndarray | float:
        """The limit the value was judged against: the fail limit where it failed, else the warn
        limit (the fail limit for a check without one)."""
        if self.warn_limit is None:
            return self.fail_limit
        if self.fail_limit is None:
            return self.warn_limit
        return _scalar(np.where(np.asarray(self.level) == FAIL, self.fail_limit, self.warn_limit))


@dataclass(frozen=True)
class Verdict:
    """The checks in report order and the verdict's level (0 PASS, 1 PASS with warnings, 2 FAIL)."""

    checks: tuple[Check, ...]
    level: np.ndarray | int

    def __getitem__(self, key: str) -> Check:
        return next(c for c in self.checks if c.key == key)

    @property
    def passed(self) -> np.ndarray | bool:
        """True where no check fails (PASS or PASS with warnings)."""
        return _scalar(np.asarray(self.level) < FAIL)

    def passed_strict(self, strict: bool = True) -> np.ndarray | bool:
        """With ``strict``, True only where no check fails or warns (``--strict``)."""
        return _scalar(np.asarray(self.level) == PASS) if strict else self.passed

    @property
    def outcome(self) -> np.ndarray | str:
        """'PASS', 'PASS with warnings' or 'FAIL' (per design)."""
        return _scalar(np.asarray(OUTCOMES, dtype=object)[np.asarray(self.level)])

    def design(self, i: int) -> Verdict:
        """The verdict of design ``i`` alone (scalars), from a verdict over designs."""

        def at(x):
            if x is None:
                return None
            a = np.asarray(x)
            return a.item() if a.ndim == 0 else a[i].item()

        checks = tuple(
            Check(c.key, at(c.value), at(c.relation), c.unit, at(c.warn_limit), at(c.fail_limit), at(c.level))
            for c in self.checks
        )
        return Verdict(checks, at(self.level))

    @property
    def warnings(self) -> tuple[Check, ...]:
        """The checks that warn (one design)."""
        return tuple(c for c in self.checks if c.level == WARN)

    @property
    def failures(self) -> tuple[Check, ...]:
        """The checks that fail (one design)."""
        return tuple(c for c in self.checks if c.level == FAIL)


def _scalar(x):
    a = np.asarray(x)
    return a.item() if a.ndim == 0 else a


def _beyond(value, limit, relation):
    """True where ``value`` is on the wrong side of ``limit`` (NaN value: True)."""
    with np.errstate(invalid="ignore"):
        ok = np.where(np.asarray(relation) == "<=", value <= limit, value >= limit)
    return ~ok


def check(key, value, relation, unit, feasible, warn=None, fail=None) -> Check:
    """One check: its level per design from ``value`` against the warn and fail limits by
    ``relation`` ('<=' or '>='); an infeasible design (``feasible`` False) and a NaN value fail.
    The pump verdict's checks (:func:`assess`) and the textbook mechanisms' are built by it."""
    v = np.asarray(value, float)
    level = np.zeros(np.broadcast_shapes(v.shape, np.shape(feasible)), int)
    if warn is not None:
        level = np.where(_beyond(v, warn, relation), WARN, level)
    if fail is not None:
        level = np.where(_beyond(v, fail, relation), FAIL, level)
    level = np.where(np.asarray(feasible, bool), level, FAIL)

    def lim(x):
        return None if x is None else _scalar(np.asarray(x, float))

    return Check(key, _scalar(v), _scalar(relation), unit, lim(warn), lim(fail), _scalar(level))


def _range(key, value, bounds, unit, feasible) -> Check:
    """A warn check of ``value`` inside ``bounds`` = (lo, hi): the limit shown is the side it is on."""
    lo, hi = bounds
    v = np.asarray(value, float)
    low = v < lo
    return check(key, v, np.where(low, ">=", "<="), unit, feasible, warn=np.where(low, lo, hi))


def assess(
    feasible,
    mean_force,
    peak_force,
    force_limit,
    *,
    link_energy_share=None,
    transmission_angle=None,
    power=None,
    grip_speed=None,
    stroke=None,
    grip_height=None,
    axle_height=None,
    power_limits=(SUSTAINED_POWER_W, HOUR_POWER_W),
    grip_speed_limits=(GRIP_SPEED_WARN_M_S, GRIP_SPEED_FAIL_M_S),
    grip_height_range=GRIP_HEIGHT_RANGE_M,
    pin_pressure=None,
    handle_fatigue=None,
    crank_fatigue=None,
    part_limits=((12.0, 30.0), (1.5, 1.0)),
    cadence=None,
    rope_speed=None,
    cadence_range=(30.0, 60.0),
    rope_speed_range=ROPE_SPEED_RANGE_M_S,
    kick_back=None,
    holding_torque=None,
    pin_wear=None,
) -> Verdict:
    """Decide the checks and the verdict.

    Parameters
    ----------
    feasible : True where a crank-rocker exists.
    mean_force : F_mean [N] (docs/physics.md §4).
    peak_force : the deciding model's peak force [N] (inf: no finite force suffices).
    force_limit : the operator's force limit [N].
    link_energy_share : neglected link kinetic energy / energy band [%] (flywheel model only).
    transmission_angle : min(γmin, 180° − γmax) [deg].
    power : Mw ω̄ [W].
    grip_speed : the grip's peak speed at the mean wheel speed [m/s].
    stroke : horizontal grip stroke 2 H sin(Δθ/2) [m].
    grip_height : (lowest, highest) grip height above the ground over the swing [m]; only known
        with the axle height.
    axle_height : wheel-axle height above the ground [m].
    power_limits : (warn, fail) [W]: the power the operator sustains for hours and for an hour.
    grip_speed_limits : (warn, fail) [m/s].
    grip_height_range : (lowest, highest) comfortable grip height [m].
    The limits are the operator profile's (:mod:`pumplink.profiles`; floats or arrays over designs).
    pin_pressure : the pins' largest mean bearing pressure [MPa];  handle_fatigue, crank_fatigue :
        fatigue safety factors [-] (docs/workshop.md §2; given when the spec gives ``[parts]``).
    part_limits : ((warn, fail) of the pin pressure [MPa], (warn, fail) of a safety factor).
    cadence : wheel turns a minute [1/min];  rope_speed : ω̄ r_w [m/s] (a rope pump's).
    cadence_range : (fewest, most) turns a minute (the profile's);  rope_speed_range : [m/s].
    kick_back : the grip's travel back, let go at the worst moment [m] (docs/workshop.md §3).
    holding_torque : (the ratchet's torque, the column's torque it must hold) [N m]: judged as their
        ratio, fail below 1.
    pin_wear : (the play the worst pin wears open in 6 million turns, the allowance) [mm].

    Optional checks are left out when their input is None.
    """
    checks = [
        check("mean_force", mean_force, "<=", "N", feasible, fail=force_limit),
        check("peak_force", peak_force, "<=", "N", feasible, fail=force_limit),
    ]
    if link_energy_share is not None:
        checks.append(
            check("link_energy_share", link_energy_share, "<=", "%", feasible, warn=100.0 * LINK_ENERGY_LIMIT)
        )
    if transmission_angle is not None:
        checks.append(
            check(
                "transmission_angle",
                transmission_angle,
                ">=",
                "deg",
                feasible,
                warn=MIN_TRANSMISSION_DEG,
                fail=FAIL_TRANSMISSION_DEG,
            )
        )
    if power is not None:
        checks.append(check("power", power, "<=", "W", feasible, warn=power_limits[0], fail=power_limits[1]))
    if cadence is not None:
        checks.append(_range("cadence", cadence, cadence_range, "/min", feasible))
    if rope_speed is not None:
        checks.append(_range("rope_speed", rope_speed, rope_speed_range, "m/s", feasible))
    if grip_speed is not None:
        checks.append(
            check(
                "grip_speed",
                grip_speed,
                "<=",
                "m/s",
                feasible,
                warn=grip_speed_limits[0],
                fail=grip_speed_limits[1],
            )
        )
    if stroke is not None:
        checks.append(check("stroke", stroke, "<=", "m", feasible, warn=STROKE_LIMIT_M))
    if grip_height is not None:
        low, high = (np.asarray(h, float) for h in grip_height)
        lo, hi = (np.asarray(x, float) for x in grip_height_range)
        # the side that is out of range (the low end first), else the highest point
        value = np.where(low < lo, low, high)
        checks.append(_range("grip_height", value, (lo, hi), "m", feasible))
    if axle_height is not None:
        checks.append(_range("axle_height", axle_height, AXLE_HEIGHT_RANGE_M, "m", feasible))
    (p_warn, p_fail), (n_warn, n_fail) = part_limits
    if pin_pressure is not None:
        checks.append(check("pin_pressure", pin_pressure, "<=", "MPa", feasible, warn=p_warn, fail=p_fail))
    for key, value in (("handle_fatigue", handle_fatigue), ("crank_fatigue", crank_fatigue)):
        if value is not None:
            checks.append(check(key, value, ">=", "", feasible, warn=n_warn, fail=n_fail))
    if kick_back is not None:
        checks.append(check("kick_back", kick_back, "<=", "m", feasible, fail=KICK_BACK_LIMIT_M))
    if holding_torque is not None:  # the ratchet's torque over the column's: its margin, fail below 1
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.asarray(holding_torque[0], float) / np.asarray(holding_torque[1], float)
        checks.append(check("holding_torque", ratio, ">=", "", feasible, fail=1.0))

    if pin_wear is not None:
        checks.append(check("pin_wear", pin_wear[0], "<=", "mm", feasible, warn=pin_wear[1]))
    level = np.where(np.asarray(feasible, bool), PASS, FAIL)
    for c in checks:
        level = np.maximum(level, c.level)
    return Verdict(tuple(checks), _scalar(level))


def excess(verdict: Verdict, accept_warnings: bool = True, unbounded=np.inf, warned=(), screened=()):
    """How far a verdict's checks lie beyond their limits, per design; 0 exactly where no check
    that counts is beyond its limit.  The searches rank designs by it.

    For one check with value v, warn limit w and fail limit f (relation '<='; '>=' mirrors it),
    the relative distances beyond them are b_w = max(v − w, 0) / |w| and b_f = max(v − f, 0) / |f|.
    Where the check's warnings count (``accept_warnings`` False, or its key in ``warned``) it adds
    b_w + b_f; where only failures count, b_f.  A check with no warn limit adds b_f, one with no
    fail limit b_w (nothing where its warnings do not count).  Each term is continuous and
    non-decreasing in v, so the excess never drops as a value moves away from its limits: a
    failing value counts more than any warning value of the same check (past f, b_w alone already
    exceeds (f − w) / |w|, and b_f > 0 adds to it).  A value that is not finite counts
    ``unbounded``.

    ``screened``: keys of checks judged only on designs no other check fails (the part checks of a
    search's evaluation, ``screen_parts``); where another check fails they were not judged (NaN)
    and count nothing, the failing check already making the excess positive.  Counting their NaN
    ``unbounded`` would rank every design that fails anything below one with no crank-rocker.
    """
    other = np.full(np.shape(verdict.level), PASS)
    for c in verdict.checks:
        if c.key not in screened:
            other = np.maximum(other, c.level)
    total = 0.0
    for c in verdict.checks:
        counts_warnings = not accept_warnings or c.key in warned
        limits = [c.fail_limit] + ([c.warn_limit] if counts_warnings else [])
        limits = [lim for lim in limits if lim is not None]
        if not limits:
            continue
        v = np.asarray(c.value, float)
        sign = np.where(np.asarray(c.relation) == "<=", 1.0, -1.0)
        beyond = 0.0
        for limit in limits:
            lim = np.asarray(limit, float)
            with np.errstate(invalid="ignore", divide="ignore"):
                beyond = beyond + np.maximum(sign * (v - lim), 0.0) / np.abs(lim)
        beyond = np.where(np.isfinite(beyond), beyond, unbounded)
        if c.key in screened:
            beyond = np.where(other == FAIL, 0.0, beyond)
        total = total + beyond
    return _scalar(np.asarray(total, float))

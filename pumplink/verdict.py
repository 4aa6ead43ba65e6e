"""The one verdict: which checks a design passes, and PASS or FAIL, for one design or many.

Every command that judges a design (``force``, ``speed``, ``batch``, ``optimize``) calls
:func:`assess`; nothing else decides PASS/FAIL.  The checks and their limits, with sources, are in
docs/models.md §4.  Inputs are floats or numpy arrays over designs (broadcast together); a
check's ``passed`` is False for an infeasible design and for a NaN value.

Checks (``Check.key``), in the order they are reported:

* ``mean_force`` (fail): the constant push/pull that does the cycle's work <= the force limit.
* ``peak_force`` (fail): the peak force of the model that decides (docs/models.md §1-2) <= limit.
* ``link_energy_share`` (warn): the flywheel model's neglected link kinetic energy, as a share of
  the energy band, <= ``LINK_ENERGY_LIMIT`` (docs/models.md §3).
* ``transmission_angle`` (warn): min(γmin, 180° − γmax) >= ``MIN_TRANSMISSION_DEG``.
* ``power`` (warn): Mw ω <= ``SUSTAINED_POWER_W``.
* ``axle_height`` (warn): within the pump paper's ``AXLE_HEIGHT_RANGE_M``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import AXLE_HEIGHT_RANGE_M, LINK_ENERGY_LIMIT, MIN_TRANSMISSION_DEG, SUSTAINED_POWER_W

FAIL = "fail"
WARN = "warn"


@dataclass(frozen=True)
class Check:
    """One verdict line: ``value`` compared with ``limit`` by ``relation`` ('<=' or '>=').

    Scalars for one design, arrays over designs otherwise.  ``severity`` is ``"fail"`` (decides
    the verdict) or ``"warn"`` (reported only).
    """

    key: str
    value: np.ndarray | float
    limit: np.ndarray | float
    relation: np.ndarray | str
    unit: str
    severity: str
    passed: np.ndarray | bool


@dataclass(frozen=True)
class Verdict:
    """The checks in report order and the verdict: feasible and every ``fail`` check passed."""

    checks: tuple[Check, ...]
    passed: np.ndarray | bool

    def __getitem__(self, key: str) -> Check:
        return next(c for c in self.checks if c.key == key)

    @property
    def warnings(self) -> tuple[Check, ...]:
        """The ``warn`` checks that did not pass (scalar verdicts)."""
        return tuple(c for c in self.checks if c.severity == WARN and not c.passed)


def _scalar(x):
    a = np.asarray(x)
    return a.item() if a.ndim == 0 else a


def _check(key, value, limit, relation, unit, severity, feasible, ok=None) -> Check:
    with np.errstate(invalid="ignore"):
        if ok is None:
            ok = np.asarray(value) <= limit if relation == "<=" else np.asarray(value) >= limit
        passed = np.asarray(feasible, bool) & ok
    return Check(
        key,
        _scalar(np.asarray(value, float)),
        _scalar(np.asarray(limit, float)),
        _scalar(relation),
        unit,
        severity,
        _scalar(passed),
    )


def assess(
    feasible,
    mean_force,
    peak_force,
    force_limit,
    *,
    link_energy_share=None,
    transmission_angle=None,
    power=None,
    axle_height=None,
) -> Verdict:
    """Decide the checks and the verdict (PASS iff feasible and every ``fail`` check passes).

    Parameters
    ----------
    feasible : True where a crank-rocker exists.
    mean_force : F_mean [N] (docs/physics.md §4).
    peak_force : the deciding model's peak force [N] (inf: no finite force suffices).
    force_limit : the operator's force limit [N].
    link_energy_share : neglected link kinetic energy / energy band [%] (flywheel model only).
    transmission_angle : min(γmin, 180° − γmax) [deg].
    power : Mw ω [W].
    axle_height : wheel-axle height above the ground [m].

    Optional checks are left out when their input is None.
    """
    checks = [
        _check("mean_force", mean_force, force_limit, "<=", "N", FAIL, feasible),
        _check("peak_force", peak_force, force_limit, "<=", "N", FAIL, feasible),
    ]
    if link_energy_share is not None:
        checks.append(
            _check(
                "link_energy_share", link_energy_share, 100.0 * LINK_ENERGY_LIMIT, "<=", "%", WARN, feasible
            )
        )
    if transmission_angle is not None:
        checks.append(
            _check(
                "transmission_angle", transmission_angle, MIN_TRANSMISSION_DEG, ">=", "deg", WARN, feasible
            )
        )
    if power is not None:
        checks.append(_check("power", power, SUSTAINED_POWER_W, "<=", "W", WARN, feasible))
    if axle_height is not None:
        lo, hi = AXLE_HEIGHT_RANGE_M
        h = np.asarray(axle_height, float)
        low = h < lo
        checks.append(
            _check(
                "axle_height",
                h,
                np.where(low, lo, hi),
                np.where(low, ">=", "<="),
                "m",
                WARN,
                feasible,
                ok=(h >= lo) & (h <= hi),
            )
        )
    passed = np.asarray(feasible, bool)
    for c in checks:
        if c.severity == FAIL:
            passed = passed & c.passed
    return Verdict(tuple(checks), _scalar(passed))

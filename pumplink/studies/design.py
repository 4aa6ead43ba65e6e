"""Everything ``pumplink force`` shows of one design, from one call: the force result (a view of
the one evaluation) and what each option adds: why the model decided (``--explain``), the speeds
that pass and the best cadence, the loads on the parts and the released handle, the independent
check (``--verify``) and the advice after a FAIL.  Every figure is the evaluation's own, at the
same speed, model and operator profile as the verdict.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from pumplink.studies.advice import Suggestion, suggest
from pumplink.studies.force import ForceResult
from pumplink.studies.speed import Cadence, cadence

#: The checks whose result changes with the wheel's speed: after one of them fails, the speeds
#: at which the design passes are worth saying.
SPEED_CHECKS = ("peak_force", "power", "grip_speed", "link_energy_share", "pin_pressure", "handle_fatigue",
                "crank_fatigue")  # fmt: skip


@dataclass(frozen=True, kw_only=True)
class DesignStudy:
    """One design as ``pumplink force`` shows it.

    result : :class:`pumplink.studies.force.ForceResult`.
    effects, why : the model-choice report (``explain``; :func:`pumplink.studies.explain.explain`).
    cadence : the speeds that pass and the best cadence (:class:`pumplink.studies.speed.Cadence`),
        with ``explain`` where the spec gives the wheel's inertia, and after a FAIL of a check that
        depends on speed.
    workshop : the loads on the parts and the released handle (``explain``).
    release : the released handle (with the pump's losses as friction, with none), the workshop's
        with ``explain``; None without a head or the wheel's inertia.
    check : the independent check (``verify``): :class:`pumplink.studies.verify.Verification` or
        :class:`~pumplink.studies.verify.StaticCheck`; None when there is nothing to integrate.
    nothing_to_verify : ``verify`` asked, and no finite peak force keeps the wheel turning.
    advice : after a FAIL, the single changes that help most (:func:`pumplink.studies.advice.suggest`).
    """

    result: ForceResult
    explained: bool = False  # --explain was asked for
    verified: bool = False  # --verify was asked for
    effects: tuple = ()
    why: str | None = None
    cadence: Cadence | None = None
    workshop: Any = None
    release: Any = None
    check: Any = None
    nothing_to_verify: bool = False
    advice: tuple[Suggestion, ...] = ()

    @property
    def agrees(self) -> bool:
        """The independent check agrees (True when none was asked)."""
        return self.check is None or bool(self.check.agrees)


def study(r: ForceResult, explain: bool = False, verify: bool = False) -> DesignStudy:
    """``pumplink force`` of one spec: its force analysis ``r``
    (:func:`pumplink.studies.force.force_analysis`, the verdict's evaluation) and what ``explain``
    and ``verify`` add (:class:`DesignStudy`)."""
    from pumplink.studies import explain as _explain
    from pumplink.studies import verify as _verify
    from pumplink.studies import workshop as _workshop

    if not r.design.feasible:
        return DesignStudy(result=r, explained=explain, verified=verify)
    out: dict[str, Any] = dict(explained=explain, verified=verify)
    if explain:
        out["effects"], out["why"] = _explain.explain(r)
        shop = out["workshop"] = _workshop.workshop(r)
        if shop is not None and shop.release is not None:  # the same release as the workshop's
            out["release"] = (shop.release, shop.release_free)
    else:
        out["release"] = _workshop.release(r)
    failed_on_speed = any(c.key in SPEED_CHECKS for c in r.verdict.failures)
    if r.design.spec.gives_inertia and (explain or failed_on_speed):
        out["cadence"] = cadence(r)
    if verify and not r.flywheel:
        out["check"] = _verify.verify_quasi_static(r)
    elif verify and r.scene is not None and math.isfinite(r.scene.least_peak_force):
        out["check"] = _verify.verify(r)
    elif verify:
        out["nothing_to_verify"] = True
    return DesignStudy(result=r, advice=tuple(suggest(r)), **out)

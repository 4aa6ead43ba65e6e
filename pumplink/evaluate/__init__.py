"""The one evaluation: design columns in; every quantity the verdict and the renderers need out;
the verdict from :func:`pumplink.verdict.assess`, called once per evaluation.

``pumplink force``, ``speed``, ``batch``, ``optimize``, ``size``, ``tolerance``, ``report``, the
advice after a FAIL and the piston pumps all judge designs through :func:`evaluate`: one design is
the n = 1 case of the same vectorised route, so they cannot disagree.  The evaluation is a short
chain of named stages (:mod:`pumplink.evaluate.stages`); a caller names what it wants and the
stages those need run.  Two mechanisms share it:

* the rope pump's four-bar (:class:`PumpDesigns`): dead-centre synthesis (Eq. 1-2 of the pump
  paper), the mean force (docs/physics.md §4), the quasi-static peak outside the dead bands
  (docs/models.md §1), the least model that is enough with the wheel's inertia and its least peak
  force (§2-3), the link-energy share, the grip's peak speed, stroke and heights, the power, the
  operator's effort (§3a), the water (docs/water.md) and the parts (docs/workshop.md);
* the piston pump's crank-slider (:class:`PistonDesigns`, docs/piston-pump.md).

:func:`pump_designs` and :func:`piston_designs` build the columns from spec values, so the inputs
of the evaluation are also assembled in one place.  :mod:`pumplink.evaluate.motion` holds the
rest of what runs a force model for one design in depth.  Nothing outside this package calls a
force model or the verdict; the names other layers need of them are re-exported here.

Pure functions on floats and numpy arrays; SI units, radians.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from pumplink.evaluate import stages
from pumplink.evaluate.designs import (
    INERTIA_KEYS,
    PART_KEYS,
    PartSizes,
    PistonDesigns,
    PumpDesigns,
    piston_designs,
    pump_designs,
)
from pumplink.evaluate.piston import evaluate_piston
from pumplink.evaluate.results import Evaluation, PistonEvaluation
from pumplink.evaluate.service import Service, pin_life
from pumplink.evaluate.water import Water
from pumplink.models import DYNAMICS, FLYWHEEL, MODELS, ORDER, QUASI_STATIC
from pumplink.models.choice import EnergyModel
from pumplink.models.release import column_torque
from pumplink.models.water import rope_pump_flow
from pumplink.verdict import (
    FAIL,
    OUTCOMES,
    PART_CHECKS,
    PASS,
    RESULTS,
    SCREENED_CHECKS,
    WARN,
    Check,
    Verdict,
    check,
    excess,
)

#: The words of each model, by index into :data:`ORDER` (reports, the model column).
MODEL_LABELS = tuple(MODELS[k].label for k in ORDER)
#: What a search needs: the checks and the verdict (with the water, which it maximises).
JUDGED = ("verdict", "water")
#: What a report shows besides: the quasi-static peak of every design and the flywheel's slowest
#: passing speed.
REPORTED = (*JUDGED, "dead_band_peak", "passing_speed")


def evaluate(
    designs: PumpDesigns | PistonDesigns,
    want: Iterable[str] = REPORTED,
    *,
    model: str | None = None,
    samples: int = 0,
    progress: Callable[[float], None] | None = None,
    screen_parts: bool = False,
    fitted: bool = False,
) -> Evaluation | PistonEvaluation:
    """Evaluate designs: the stages ``want`` names (:data:`pumplink.evaluate.stages.STAGES`) and
    every stage they need.

    Parameters
    ----------
    designs : rope pumps (:class:`PumpDesigns`) or piston pumps (:class:`PistonDesigns`, which are
        judged whole whenever ``want`` holds "verdict").
    want : stage names; :data:`JUDGED` for the verdict, :data:`REPORTED` (default) for what a report
        shows; add "effort" for the operator's least peak effort and "sampled_peak" for a sweep.
    model : a model key that decides every design giving the wheel's inertia (``--model``); default
        the least model that is enough, per design (docs/models.md §3).
    samples : crank samples per revolution of the "sampled_peak" stage; ``progress`` is given the
        fraction of that sweep done.
    screen_parts : judge the spec's ``[parts]`` only on designs no other check fails (a search,
        which drops failing designs anyway; the part checks are the costly ones): the others' part
        values are NaN, which fails, as they do already.
    fitted : judge the designs as fitted with the ratchet their water column needs: the kick-back
        and the ratchet's checks are left out (a fitting answers them, not the linkage: the
        searches, the speeds that pass and the builds of a tolerance study).
    """
    want = tuple(want)
    if isinstance(designs, PistonDesigns):
        return evaluate_piston(designs, judge="verdict" in want)
    r = stages.Run(designs, model=model, samples=samples, progress=progress, screen_parts=screen_parts,
                   fitted=fitted)  # fmt: skip
    return Evaluation(designs=designs, **stages.run(r, want))


__all__ = [
    "DYNAMICS",
    "FAIL",
    "FLYWHEEL",
    "INERTIA_KEYS",
    "JUDGED",
    "MODELS",
    "MODEL_LABELS",
    "ORDER",
    "OUTCOMES",
    "PART_CHECKS",
    "SCREENED_CHECKS",
    "PART_KEYS",
    "PASS",
    "QUASI_STATIC",
    "REPORTED",
    "RESULTS",
    "WARN",
    "Check",
    "EnergyModel",
    "Evaluation",
    "PartSizes",
    "PistonDesigns",
    "PistonEvaluation",
    "PumpDesigns",
    "Service",
    "Verdict",
    "Water",
    "check",
    "column_torque",
    "evaluate",
    "excess",
    "pin_life",
    "piston_designs",
    "pump_designs",
    "rope_pump_flow",
]

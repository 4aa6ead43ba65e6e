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

from pumplink.evaluate.designs import (
    INERTIA_KEYS,
    PART_KEYS,
    PartSizes,
    PistonDesigns,
    PumpDesigns,
    piston_designs,
    pump_designs,
)
from pumplink.evaluate.results import Evaluation, PistonEvaluation
from pumplink.evaluate.service import Service, pin_life
from pumplink.evaluate.stages import JUDGED, REPORTED, evaluate
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

"""The pump design search's problem: its variables, objective and constraints, and the candidate
designs judged by the one evaluation (the search itself: :mod:`pumplink.search.optimize`).

Variables (by default, in spec units): ``rocker`` [m], ``L1`` [m], ``D1`` [m], ``swing`` [deg]
within :data:`DEFAULT_BOUNDS`; every other spec value stays fixed.  Objective: the peak force of
the verdict (as ``pumplink force``) or the mean force pi Mw / (2 H sin(swing/2)) (docs/physics.md).
The peak of the verdict depends on the model: when the spec gives inertia
(``wheel.inertia``, ``wheel.mass`` or ``load.moving_mass``) it is the least peak force at the
spec's speed and speed fluctuation of the least model that is enough for each candidate, the
flywheel or full dynamics (``pumplink.models.choice.energy_model``, vectorised over the population), or
of the model ``--model`` asks for; otherwise the exact windowed peak outside the dead bands
(``pumplink.models.quasi_static.peak_force``).  The pass flag is that verdict: mean and peak within the force
limit.  Constraints (all ``g >= 0``):

* the dead-centre synthesis gives a crank-rocker with the exact swing: 0 < psi2 < psi1 < pi
  (``pumplink.mechanisms.fourbar``);
* transmission angle: min(gamma_min, 180 deg - gamma_max) >= 45 deg
  (``pumplink.constants.MIN_TRANSMISSION_DEG``, docs/models.md §4, the lever-mechanism textbook:
  [lambda_max] <= 45 deg for a rotating driven link);
* hand-grip height over the whole swing within the operator profile's range above the ground
  (hands between knuckle and shoulder height; docs/operators.md); the grip is at axle height - D1 +
  H sin(theta4);
* horizontal grip stroke 2 H sin(swing/2) at most 1.0 m: the pump paper's own prototype
  (the pump paper: H = 1 m, swing 60 deg, chosen "as function of the motion capability of human
  operators"); no lower limit (a shorter stroke only raises the force);
* the crank arcs outside the dead bands are not empty (the peak is then defined); quasi-static
  model only: the flywheel's peak is defined for every crank-rocker, and the dead band plays no
  part in its verdict.
* ``--objective flow``: no check of the verdict fails and, where the search varies the cadence or
  the wheel radius, the cadence and the rope speed lie in their ranges (docs/models.md §4).

Pure functions; the CLI renders the result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from pumplink.constants import MIN_TRANSMISSION_DEG, STROKE_LIMIT_M
from pumplink.errors import SpecError
from pumplink.evaluate import (
    FLYWHEEL,
    JUDGED,
    MODELS,
    QUASI_STATIC,
    SCREENED_CHECKS,
    PumpDesigns,
    evaluate,
    excess,
    pump_designs,
)
from pumplink.inputs.pump import PumpSpec
from pumplink.mechanisms.fourbar import CHANGE_POINT_MARGIN, grip_heights, grip_stroke, synthesize
from pumplink.studies.tolerance import first_order_shares
from pumplink.studies.tolerance_study import Robust

#: Keys that may vary (the [linkage] table of the spec), with their units.
VARIABLE_UNITS = {
    "L1": "m",
    "D1": "m",
    "b": "m",
    "rocker": "m",
    "handle": "m",
    "swing": "deg",
    # what a builder chooses besides the linkage (as ``pumplink size`` searches them)
    "wheel.radius": "m",
    "wheel.mass": "kg",
    "wheel.axle_height": "m",
    "operator.speed": "deg/s",
    "load.pipe_diameter": "m",
}
#: The constraint ``--objective flow`` adds: no check of the verdict fails (its slack is minus the
#: relative excess beyond the fail limits, pumplink.verdict.excess).
VERDICT_CONSTRAINT = ("no check of the verdict fails", "relative")
#: Where the search varies the cadence or the wheel radius, the same constraint also holds the
#: cadence and the rope speed in their ranges (their checks only warn, and a search for water would
#: otherwise run to the fastest wheel the other checks allow; docs/models.md §4, docs/optimize.md).
SPEED_KEYS = ("operator.speed", "wheel.radius")
SPEED_CHECKS = ("cadence", "rope_speed")
SPEED_CONSTRAINT = "no check of the verdict fails, the cadence and the rope speed in range"
#: The objectives: the verdict's peak force or the mean force (least), or the flow (most, with no
#: check failing: ``--objective flow``).
OBJECTIVES = ("peak", "mean", "flow")
#: Default search space (spec units) when no --vary is given.
DEFAULT_BOUNDS = {"rocker": (0.10, 0.40), "L1": (0.0, 1.0), "D1": (-0.3, 1.2), "swing": (30.0, 100.0)}
#: Ergonomic defaults (see the module docstring for the sources).
#: The grip stroke the search allows by default [m]: no lower limit (a shorter stroke only raises
#: the force), the verdict's warning limit above (pumplink.constants.STROKE_LIMIT_M).
STROKE_M = (0.0, STROKE_LIMIT_M)
#: Wheel-axle height assumed when the spec has none: the middle of the pump paper's 0.40-0.70 m.
DEFAULT_AXLE_HEIGHT_M = 0.55
#: Objective value given to designs that are not crank-rockers (DE ranks them by violation).
INFEASIBLE_OBJECTIVE = 1e6
#: A constraint counts as binding when its slack is below this (in its unit: deg or m).
BINDING_TOL = 1e-4
#: Relative tolerance of the search (differential evolution's ``tol``: it stops when the spread of
#: its population's objective values is below this share of their mean).  The optimum's
#: coordinates are settled to about its square root (pumplink.output.precision).
SEARCH_TOL = 1e-8

CONSTRAINTS = (
    ("crank-rocker exists (swing clear of the frame line)", "deg"),
    (f"transmission angle >= {MIN_TRANSMISSION_DEG:g} deg", "deg"),
    ("lowest grip height >= {lo} m", "m"),
    ("highest grip height <= {hi} m", "m"),
    ("grip stroke >= {lo} m", "m"),
    ("grip stroke <= {hi} m", "m"),
    ("crank arcs outside the dead bands", "deg"),
)


@dataclass(frozen=True)
class Problem:
    """A design search: fixed spec values, the varied keys and their bounds (spec units)."""

    spec: PumpSpec
    names: tuple[str, ...]
    lower: np.ndarray
    upper: np.ndarray
    objective: str = "peak"
    axle_height: float = DEFAULT_AXLE_HEIGHT_M
    grip_height: tuple[float, float] = (0.0, 5.0)
    stroke: tuple[float, float] = STROKE_M
    forced: str | None = None  # a model key (--model); None: the least model that is enough
    robust: Robust | None = None  # at least this share of builds at these tolerances pass

    @property
    def needs_verdict(self) -> bool:
        """The constraints need the whole evaluation (the verdict), not the geometry alone."""
        return self.objective == "flow" or self.robust is not None

    @property
    def holds_speed(self) -> bool:
        """The flow's constraint also holds the cadence and the rope speed in range: a flow search
        that varies either (:data:`SPEED_KEYS`)."""
        return self.objective == "flow" and any(k in self.names for k in SPEED_KEYS)

    @property
    def flywheel(self) -> bool:
        """True when an energy model (flywheel or full dynamics) decides the peak: the spec gives
        inertia and --model does not ask for the quasi-static model."""
        return self.spec.gives_inertia and self.forced != QUASI_STATIC

    def spec_value(self, key: str) -> float:
        """The spec's own value of a varied key (NaN where it gives none, e.g. a wheel mass when it
        gives the wheel's inertia)."""
        section, _, name = key.rpartition(".")
        v = getattr(getattr(self.spec, section or "linkage"), name)
        if key == "wheel.axle_height":
            v = self.axle_height
        return math.nan if v is None else float(v)

    @property
    def force_limit(self) -> float:
        """The operator's force limit [N] (the profile's, or the spec's)."""
        return float(pump_designs(self.spec.values).force_limit)

    @property
    def inertia(self) -> float | None:
        """J about the wheel axle [kg m^2] (None: the spec gives no inertia)."""
        return float(pump_designs(self.spec.values).inertia) if self.spec.gives_inertia else None

    @property
    def model(self) -> str:
        """The model whose peak force is the objective and decides the pass flag, in words."""
        if not self.flywheel:
            return MODELS[QUASI_STATIC].label
        if self.forced is not None:
            return MODELS[self.forced].label
        return "flywheel or full dynamics (the least model that is enough, per design)"

    def constraint_names(self) -> list[str]:
        """Names of the constraints in force (the last of :data:`CONSTRAINTS` only for the
        quasi-static model)."""
        gl, gh = self.grip_height
        sl, sh = self.stroke
        fill = [{}, {}, {"lo": f"{gl:g}"}, {"hi": f"{gh:g}"}, {"lo": f"{sl:g}"}, {"hi": f"{sh:g}"}, {}]
        names = [name.format(**f) for (name, _), f in zip(CONSTRAINTS, fill)]
        names = names[:-1] if self.flywheel else names
        verdict = SPEED_CONSTRAINT if self.holds_speed else VERDICT_CONSTRAINT[0]
        names = names + [verdict] if self.objective == "flow" else names
        if self.robust is not None:
            r = self.robust
            names.append(
                f"at least {r.target:.0%} of builds at ±{r.tolerance * 1000:g} mm pass"
                f"{' without warnings' if r.strict else ''} (first order)"
            )
        return names

    def constraint_units(self) -> list[str]:
        """The unit of each constraint's slack, in :meth:`constraint_names` order."""
        units = [u for _, u in CONSTRAINTS]
        units = units[:-1] if self.flywheel else units
        units = units + [VERDICT_CONSTRAINT[1]] if self.objective == "flow" else units
        return units + ["share"] if self.robust is not None else units


@dataclass(frozen=True)
class Candidates:
    """Candidate designs as the search sees them (arrays over designs): objective, forces and
    constraint slacks g >= 0, from the one evaluation (:func:`evaluate_designs`).

    ``dead_band_peak_force`` is the windowed peak outside the dead bands, ``least_peak_force`` the
    flywheel's (NaN unless the spec gives inertia); ``verdict_peak_force`` is the one that
    decides.  The verdicts of the spec's design and of the optimum are those of ``pumplink force``
    (:attr:`OptimizationResult.spec_result`, :attr:`OptimizationResult.best_result`).
    """

    objective: np.ndarray
    dead_band_peak_force: np.ndarray
    mean: np.ndarray
    slack: np.ndarray  # (constraints, designs) in the units of CONSTRAINTS (deg or m)
    transmission: np.ndarray  # [deg]
    grip_low: np.ndarray  # [m]
    grip_high: np.ndarray  # [m]
    stroke: np.ndarray  # [m]
    least_peak_force: np.ndarray  # [N]
    flywheel: bool = False

    @property
    def verdict_peak_force(self) -> np.ndarray:
        return self.least_peak_force if self.flywheel else self.dead_band_peak_force


def parse_bounds(items: list[str] | None) -> dict[str, tuple[float, float]]:
    """``KEY=LO:HI`` strings -> {key: (lo, hi)}; default :data:`DEFAULT_BOUNDS`.

    Raises
    ------
    SpecError
        Unknown key, repeated key, missing '=' or ':', a value that is not a finite number,
        lo >= hi, or a bound outside what the spec allows; the message names the key.
    """
    if not items:
        return dict(DEFAULT_BOUNDS)
    out: dict[str, tuple[float, float]] = {}
    allowed = ", ".join(VARIABLE_UNITS)
    for item in items:
        key, sep, rng = item.partition("=")
        key = key.strip()
        if not sep:
            raise SpecError(f"--vary {item!r} is not KEY=LO:HI; write e.g. --vary rocker=0.1:0.4")
        if key not in VARIABLE_UNITS:
            raise SpecError(f"--vary key '{key}' is unknown; allowed keys: {allowed}")
        if key in out:
            raise SpecError(f"--vary key '{key}' is given twice; give each key once")
        lo_s, sep2, hi_s = rng.partition(":")
        if not sep2:
            raise SpecError(f"--vary {key}={rng!r} needs LO:HI; write e.g. --vary {key}=0.1:0.4")
        try:
            lo, hi = float(lo_s), float(hi_s)
        except ValueError:
            raise SpecError(
                f"--vary {key}={rng!r}: bounds must be numbers, e.g. --vary {key}=0.1:0.4"
            ) from None
        if not (math.isfinite(lo) and math.isfinite(hi)):
            raise SpecError(f"--vary {key}={rng!r}: bounds must be finite numbers")
        if lo >= hi:
            raise SpecError(f"--vary {key}: lower bound {lo:g} must be below the upper bound {hi:g}")
        _check_spec_range(key, lo, hi)
        out[key] = (lo, hi)
    return out


def _check_spec_range(key: str, lo: float, hi: float) -> None:
    """Bounds must lie inside the spec's allowed range for the key (the spec's fields)."""
    from pumplink.inputs.pump import PumpSpec

    section, _, name = key.rpartition(".")
    table = PumpSpec.model_fields[section or "linkage"].annotation
    info = table.model_fields[name]
    gt = ge = lt = le = None
    for m in info.metadata:
        gt = getattr(m, "gt", gt)
        ge = getattr(m, "ge", ge)
        lt = getattr(m, "lt", lt)
        le = getattr(m, "le", le)
    bad_lo = (gt is not None and lo <= gt) or (ge is not None and lo < ge)
    bad_hi = (lt is not None and hi >= lt) or (le is not None and hi > le)
    if bad_lo or bad_hi:
        lo_txt = f"> {gt:g}" if gt is not None else f">= {ge:g}"
        hi_txt = f"< {lt:g}" if lt is not None else f"<= {le:g}"
        unit = VARIABLE_UNITS[key]
        raise SpecError(
            f"--vary {key}={lo:g}:{hi:g} leaves the allowed range of "
            f"{key if '.' in key else 'linkage.' + key} "
            f"({lo_txt} and {hi_txt} {unit}); narrow the bounds"
        )


def parse_range(name: str, text: str | None, default: tuple[float, float]) -> tuple[float, float]:
    """``LO:HI`` for an ergonomic range option (metres); SpecError names the option."""
    if text is None:
        return default
    lo_s, sep, hi_s = text.partition(":")
    try:
        lo, hi = float(lo_s), float(hi_s)
    except ValueError:
        lo = hi = float("nan")
    if not sep or not (math.isfinite(lo) and math.isfinite(hi)) or lo < 0 or lo >= hi:
        raise SpecError(
            f"--{name} {text!r} must be LO:HI in metres with 0 <= LO < HI, e.g. --{name} "
            f"{default[0]:g}:{default[1]:g}"
        )
    return lo, hi


def make_problem(
    spec: PumpSpec,
    bounds: dict[str, tuple[float, float]] | None = None,
    objective: str = "peak",
    axle_height: float | None = None,
    grip_height=None,
    stroke=STROKE_M,
    model: str | None = None,
    robust: Robust | None = None,
) -> Problem:
    """Assemble a :class:`Problem`; the axle height is ``axle_height``, else the spec's
    ``wheel.axle_height``, else :data:`DEFAULT_AXLE_HEIGHT_M`.  ``model``: a model key that decides
    the peak (``--model``), else the least model that is enough for each design.  ``grip_height``:
    the range the grip keeps over the swing [m], default the operator profile's.  ``robust``: at
    least its share of builds at its tolerances must pass (docs/tolerance.md §5)."""
    bounds = dict(DEFAULT_BOUNDS) if bounds is None else bounds
    if grip_height is None:
        grip_height = spec.operator.limits.grip_height_range
    if model not in (None, QUASI_STATIC) and not spec.gives_inertia:
        raise SpecError(
            f"--model {model} needs the wheel's inertia, but {spec.name} gives none; add wheel.mass [kg] "
            "or wheel.inertia [kg m^2] to the spec"
        )
    if objective not in OBJECTIVES:
        raise SpecError(f"--objective {objective!r} is unknown; use peak, mean or flow")
    if objective == "flow" and spec.load.head is None:
        raise SpecError(
            f"--objective flow needs the pumping head, but {spec.name} gives load.rope_force; give "
            "load.head [m] and load.pipe_diameter [m] instead"
        )
    if "load.pipe_diameter" in bounds and spec.load.head is None:
        raise SpecError("--vary load.pipe_diameter needs load.head [m] in the spec (not load.rope_force)")
    if (
        spec.gives_inertia
        and float(pump_designs(spec.values).inertia) == 0.0
        and objective == "peak"
        and model == FLYWHEEL
    ):
        raise SpecError(
            f"{spec.name}: the inertia is 0 kg m^2 (load.moving_mass = 0 and no wheel mass), so there is no "
            "energy band (J w^2 delta = 0) and every design needs an infinite peak force; give wheel.mass "
            "[kg] or wheel.inertia [kg m^2], or leave out load.moving_mass for the quasi-static model"
        )
    if axle_height is None:
        axle_height = spec.wheel.axle_height if spec.wheel.axle_height is not None else DEFAULT_AXLE_HEIGHT_M
    if not (math.isfinite(axle_height) and 0 < axle_height <= 5):
        raise SpecError(
            f"--axle-height {axle_height:g} must be a height in metres with 0 < value <= 5, e.g. 0.55"
        )
    names = tuple(bounds)
    return Problem(
        spec,
        names,
        np.array([bounds[k][0] for k in names], float),
        np.array([bounds[k][1] for k in names], float),
        objective,
        float(axle_height),
        tuple(grip_height),
        tuple(stroke),
        model,
        robust,
    )


def _columns(problem: Problem, x: np.ndarray) -> dict[str, np.ndarray]:
    """Design parameters (spec units) for x of shape (variables, designs)."""
    x = np.atleast_2d(np.asarray(x, float))
    n = x.shape[1]
    lk = problem.spec.linkage
    cols = {k: np.full(n, float(getattr(lk, k))) for k in VARIABLE_UNITS if "." not in k}
    cols["wheel.axle_height"] = np.full(n, problem.axle_height)
    for i, k in enumerate(problem.names):
        cols[k] = x[i]
    return cols


@dataclass(frozen=True)
class _Terms:
    """The geometry of designs and their constraint slacks (no force model): see evaluate_designs."""

    syn: Any
    ok: np.ndarray
    slack: np.ndarray
    mu: np.ndarray
    grip_low: np.ndarray
    grip_high: np.ndarray
    stroke: np.ndarray
    win: np.ndarray
    handle: np.ndarray  # [m], per design
    rocker: np.ndarray  # [m], per design


def _terms(problem: Problem, x, syn=None) -> _Terms:
    """Synthesis and constraint slacks for x of shape (variables, designs) (vectorised); ``syn``:
    the designs' synthesis when it is already known."""
    p = _columns(problem, x)
    sw = np.radians(p["swing"])
    h = p["handle"]
    if syn is None:
        syn = synthesize(p["L1"], p["D1"], p["b"], p["rocker"], sw, h)
    ok = syn.feasible
    band = math.radians(problem.spec.operator.dead_band)

    margin = np.minimum(syn.psi2, np.pi - syn.psi1) - 2 * CHANGE_POINT_MARGIN
    margin = np.where(syn.frame_length > 1e-6, margin, -1.0)
    mu = np.minimum(syn.transmission_min, np.pi - syn.transmission_max)
    g_mu = np.where(ok, np.degrees(mu) - MIN_TRANSMISSION_DEG, 0.0)
    grip_low, grip_high = grip_heights(p["wheel.axle_height"], p["D1"], h, sw)
    stroke = grip_stroke(h, sw)
    plus = syn.stroke_plus_x
    win = np.where(ok, np.degrees(np.minimum(plus, 2 * np.pi - plus) - 2 * band), 0.0)
    slack = np.stack(
        [
            np.degrees(margin),
            g_mu,
            grip_low - problem.grip_height[0],
            problem.grip_height[1] - grip_high,
            stroke - problem.stroke[0],
            problem.stroke[1] - stroke,
            win,
        ]
    )
    if problem.flywheel:
        slack = slack[:-1]  # the dead-band window: quasi-static model only
    return _Terms(syn, ok, slack, mu, grip_low, grip_high, stroke, win, h, p["rocker"])


def designs(problem: Problem, x) -> PumpDesigns:
    """The evaluation's columns for x of shape (variables, designs): the varied linkage keys, the
    rest of the spec fixed."""
    p = _columns(problem, x)
    values = problem.spec.values
    if "wheel.mass" in problem.names:
        values["wheel.inertia"] = None  # the wheel's mass is varied instead
    values.update({k if "." in k else f"linkage.{k}": v for k, v in p.items()})
    return pump_designs(values)


def evaluate_designs(problem: Problem, x, search: bool = False) -> Candidates:
    """Objective and constraint slacks for x of shape (variables, designs) (vectorised).

    Slacks are in degrees (angles) or metres (heights, stroke); a design satisfies every
    constraint iff all its slacks are >= 0.  ``search``: only the force the objective needs (the
    flywheel's or the dead-band peak, neither for the mean objective); the other stays NaN.
    The forces come from :func:`pumplink.evaluate.evaluate` (the verdict's own route).
    """
    objective_peak = problem.objective == "peak"
    flow_objective = problem.objective == "flow"
    columns = designs(problem, x)
    want = ["mean_force"]
    if problem.needs_verdict:
        want += JUDGED
    if objective_peak or flow_objective or not search:
        want.append("peak")
    if not search:  # the quasi-static peak of every design, for the report
        want.append("dead_band_peak")
    ev = evaluate(columns, want, model=problem.forced, screen_parts=True, fitted=True)
    tm = _terms(problem, x, ev.synthesis)
    ok = tm.ok
    nan = np.full(ok.shape, np.nan)
    quasi_static = ev.dead_band_peak_force
    if quasi_static is None:  # a search: only where the quasi-static model decides
        quasi_static = nan if ev.peak_force is None else np.where(ev.energy_decides, np.nan, ev.peak_force)
    # the dead-band peak is defined where the crank arcs outside the dead bands are not empty
    peak = np.where(ok & (tm.win > 0), quasi_static, np.nan)
    required = ev.least_peak_force if problem.flywheel and ev.least_peak_force is not None else nan
    verdict = required if problem.flywheel else peak
    mean = np.where(ok, ev.mean_force, np.nan)
    obj = verdict if objective_peak else mean
    slack = tm.slack
    if flow_objective:  # the most water [l/min] with no check failing (the verdict's slack)
        obj = -ev.water.flow * 60_000.0
        warned = SPEED_CHECKS if problem.holds_speed else ()
        over = excess(ev.verdict, True, INFEASIBLE_OBJECTIVE, warned, screened=SCREENED_CHECKS)
        slack = np.vstack([slack, -np.atleast_1d(over)])
    if problem.robust is not None:  # the builds: their first-order share over the target
        r = problem.robust
        met = np.all(slack >= 0, axis=0)  # the shares cost 6 evaluations a design: only where needed
        shares = first_order_shares(columns, ev, r.tolerances, r.strict, problem.forced, only=met)
        slack = np.vstack([slack, shares - r.target])
    obj = np.where(np.isfinite(obj), obj, INFEASIBLE_OBJECTIVE)
    return Candidates(
        obj,
        peak,
        mean,
        slack,
        np.where(ok, np.degrees(tm.mu), np.nan),
        tm.grip_low,
        tm.grip_high,
        tm.stroke,
        required,
        problem.flywheel,
    )


def constraint_slack(problem: Problem, x) -> np.ndarray:
    """The constraints' slacks of designs x: from the geometry alone, but for ``--objective flow``
    and a robust search, whose constraints need the whole evaluation (a robust search without the
    flow's verdict constraint evaluates only the designs that meet the geometry's; the others
    count the builds' constraint missed by the whole target)."""
    if problem.robust is not None and problem.objective != "flow":
        x = np.atleast_2d(np.asarray(x, float))
        geometry = _terms(problem, x).slack
        slack = np.vstack([geometry, np.full((1, x.shape[1]), -problem.robust.target)])
        met = np.all(geometry >= 0, axis=0)
        if met.any():
            slack[:, met] = evaluate_designs(problem, x[:, met], search=True).slack
        return slack
    if problem.needs_verdict:
        return evaluate_designs(problem, x, search=True).slack
    return _terms(problem, x).slack

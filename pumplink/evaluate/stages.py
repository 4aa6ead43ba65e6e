"""The evaluation of rope-pump designs as a chain of named stages.

Each stage is small, reads the design columns and what earlier stages filled, and fills the
fields of :class:`pumplink.evaluate.results.Evaluation` it declares.  :func:`run` runs the stages
that the asked-for ones need, in the order of :data:`STAGES` (learn from pvlib's
``ModelChain.run_model``: a handful of named steps readable on one screen):

========================  ========================================  ==============================
stage                     fills                                     source
========================  ========================================  ==============================
geometry                  synthesis, feasible, stroke, heights,     Eq. (1)-(2) of the pump paper,
                          rocker_rate (max|dθ4/dθ2|)                docs/models.md §4
mean_force                mean_force                                docs/physics.md §4
model                     model_index, energy, least_peak_force     docs/models.md §2-3
dead_band_peak            the quasi-static peak of every design     docs/models.md §1
peak                      peak_force (the deciding model's)         docs/models.md §3
sampled_peak              sampled_peak                              docs/models.md §1
passing_speed             min_passing_speed                         docs/models.md §2
effort                    effort_peak_force                         docs/models.md §3a
motion                    power, grip_speed, link_energy_share,     docs/models.md §4
                          cadence, rope_speed
water                     water                                     docs/water.md
parts                     pin_pressure, handle/crank_fatigue        docs/workshop.md §2
service                   service (kick-back, pin life, field)      docs/workshop.md §3, §5
verdict                   verdict                                   docs/models.md §4
========================  ========================================  ==============================

Which model can solve a design is read from the registry's requirements
(:attr:`pumplink.models.Model.needs`): a model whose operating conditions a design does not give
(NaN) cannot decide it.  Pure functions on numpy arrays; SI units, radians.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from pumplink.evaluate import service as _service
from pumplink.evaluate.designs import PistonDesigns, PumpDesigns
from pumplink.evaluate.piston import evaluate_piston
from pumplink.evaluate.results import Evaluation, PistonEvaluation
from pumplink.evaluate.water import WATER_KEYS
from pumplink.evaluate.water import water as _water
from pumplink.mechanisms.fourbar import pump_geometry
from pumplink.models import DYNAMICS, FLYWHEEL, MODELS, ORDER, QUASI_STATIC, Conditions, Masses
from pumplink.models import kickback as _kickback
from pumplink.models import load as _load
from pumplink.models import parts as _parts
from pumplink.models import quasi_static as _qs
from pumplink.models import release as _release
from pumplink.models import water as _water_kernels
from pumplink.models.choice import energy_model
from pumplink.verdict import FAIL, PART_CHECKS, assess

#: Designs swept together for the sampled peak: the kernel's temporaries (designs x samples)
#: stay in the processor's cache (512: a 4,096-design chunk of the village's grid in 10.7 ms
#: against 16.9 ms in blocks of 128, the same values).
SUB_DESIGNS = 512


@dataclass
class Run:
    """One evaluation under way: the designs, their columns, what was asked and what is filled.

    model : a model key that decides every design giving the wheel's inertia (``--model``), or
    None for the least model that is enough;  samples : crank samples a turn for the sampled peak;
    progress : called with the fraction of that sweep done;  screen_parts : judge the part checks
    only on designs no other check fails (a search drops the others anyway);  fitted : leave the
    kick-back and the ratchet's checks out (the linkage judged as fitted with the ratchet it needs).
    """

    designs: PumpDesigns
    model: str | None = None
    samples: int = 0
    progress: Callable[[float], None] | None = None
    screen_parts: bool = False
    fitted: bool = False
    filled: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.n, self.c = self.designs.columns

    def __getitem__(self, name: str):
        return self.filled[name]

    def rows(self, mask) -> np.ndarray:
        """The indices where ``mask`` is True."""
        return np.nonzero(np.asarray(mask, bool))[0]


@dataclass(frozen=True)
class Stage:
    """A named step: the stages it needs run first and the fields it fills (names separated by
    spaces), and the function that fills them."""

    name: str
    needs: str
    fills: str
    fill: Callable[[Run], dict[str, Any]]


# ----------------------------------------------------------------------------- the stages
def geometry(r: Run) -> dict[str, Any]:
    """The dead-centre synthesis (Eq. 1-2 of the pump paper), or the linkage as built (a workshop's
    holes: analysed, not re-synthesised); the grip's stroke and heights (docs/physics.md §1); the
    rocker's largest rate max|dθ4/dθ2|: the grip's peak speed per unit wheel speed and handle
    (docs/models.md §4), and the arms' largest kinetic energy (§3).  One kernel call
    (:func:`pumplink.mechanisms.fourbar.pump_geometry`)."""
    c = r.c
    g = pump_geometry(c["L1"], c["D1"], c["b"], c["rocker"], c["swing"], c["handle"], r.designs.axle_height,
                      built=r.designs.linkage, designs=r.n)  # fmt: skip
    return dict(g._asdict(), feasible=np.asarray(g.synthesis.feasible, bool))


def mean_force(r: Run) -> dict[str, Any]:
    """F_mean = π Mw / S, the constant push/pull that does the cycle's work (docs/physics.md §4)."""
    ok = r.rows(r["feasible"])
    mean = np.full(r.n, np.nan)
    mean[ok] = _qs.mean_force(r.c["wheel_torque"][ok], r["stroke"][ok])
    return dict(mean_force=mean)


def _solvable(r: Run, key: str) -> np.ndarray:
    """True where a design gives every operating condition model ``key`` needs
    (:attr:`pumplink.models.Model.needs`: a NaN column is not given)."""
    given = np.ones(r.n, bool)
    for need in MODELS[key].needs:
        if need in r.c:
            given &= ~np.isnan(r.c[need])
    return given


def model(r: Run) -> dict[str, Any]:
    """The least model that is enough, per design, and the energy model's least peak force
    (docs/models.md §2-3): the flywheel or full dynamics where the design gives the wheel's
    inertia, the quasi-static model elsewhere."""
    c, syn, feasible = r.c, r["synthesis"], r["feasible"]
    arms_in = r.designs.arms_in_verdict
    masses = _load.link_masses(
        syn.coupler_length, r["handle"], r["rocker"], c["mass_per_length"], c["coupler_mass"],
        c["handle_mass"], c["arm_mass"] if arms_in else 0.0,
    )  # fmt: skip
    index, em = np.zeros(r.n, int), None
    least = np.full(r.n, np.nan)
    fly = _solvable(r, FLYWHEEL)
    if fly.any():
        sized = Masses(masses.coupler, masses.handle, c["arm_mass"])  # the arms' energy, for reports
        em = energy_model(
            syn.linkage, syn.dead_centre_extended, syn.dead_centre_folded, c["wheel_torque"],
            c["inertia"], c["speed"], c["speed_fluctuation"], sized, arms_in, forced=r.model,
            solve=fly & feasible, rocker_rate=r["rocker_rate"],
        )  # fmt: skip
        index = np.where(fly, em.index, 0)
        least = np.where(fly & feasible, em.peak_force, np.nan)
    return dict(model_index=index, energy=em, least_peak_force=least, masses=masses)


def dead_band_peak(r: Run) -> dict[str, Any]:
    """The quasi-static model's exact peak outside ±dead band of the dead centres, of every
    feasible design (docs/models.md §1): reported beside an energy model's."""
    return _dead_band_peaks(r, r["feasible"])


def _dead_band_peaks(r: Run, where) -> dict[str, Any]:
    syn, c = r["synthesis"], r.c
    peak, angle = np.full(r.n, np.nan), np.full(r.n, np.nan)
    i = r.rows(where)
    if i.size:
        peak[i], angle[i] = _qs.dead_band_peak_force(
            syn.linkage[i], syn.dead_centre_extended[i], syn.dead_centre_folded[i], c["dead_band"][i],
            c["wheel_torque"][i],
        )  # fmt: skip
    return dict(dead_band_peak_force=peak, dead_band_peak_angle=angle)


def peak(r: Run) -> dict[str, Any]:
    """The peak force that decides the verdict: the energy model's least peak force where one
    decides, else the quasi-static dead-band peak (docs/models.md §3)."""
    energy = r["model_index"] > 0
    qs = r.filled.get("dead_band_peak_force")
    if qs is None:  # only where it decides
        qs = _dead_band_peaks(r, r["feasible"] & ~energy)["dead_band_peak_force"]
    return dict(peak_force=np.where(energy, r["least_peak_force"], qs))


def sampled_peak(r: Run) -> dict[str, Any]:
    """The peak over a uniform sweep of ``samples`` crank angles outside the dead bands [N]
    (docs/models.md §1), in cache-sized blocks of designs."""
    syn, c = r["synthesis"], r.c
    out = np.full(r.n, np.nan)
    ok = r.rows(r["feasible"])
    for s0 in range(0, ok.size if r.samples else 0, SUB_DESIGNS):
        s = ok[s0 : s0 + SUB_DESIGNS]
        out[s] = _qs.sampled_peak(
            syn.linkage[s], r.samples, c["wheel_torque"][s], syn.dead_centre_extended[s],
            syn.dead_centre_folded[s], c["dead_band"][s], progress=r.progress,
        )  # fmt: skip
    return dict(sampled_peak=out)


def passing_speed(r: Run) -> dict[str, Any]:
    """The flywheel's slowest passing mean speed where the flywheel decides (docs/models.md §2)."""
    out = np.full(r.n, np.nan)
    i = r.rows(r["feasible"] & (r["model_index"] == ORDER.index(FLYWHEEL)))
    if i.size:
        from pumplink.models import flywheel as _fw  # loaded when first needed (start-up)

        syn, c = r["synthesis"], r.c
        out[i] = _fw.min_passing_speed(
            syn.linkage[i], syn.dead_centre_extended[i], syn.dead_centre_folded[i],
            c["wheel_torque"][i], c["force_limit"][i], c["inertia"][i], c["speed_fluctuation"][i],
        )  # fmt: skip
    return dict(min_passing_speed=out)


def effort(r: Run) -> dict[str, Any]:
    """The operator's least peak effort: the hand force plus accelerating and lifting their own
    arms, full dynamics (docs/models.md §3a), wherever the wheel's inertia is given."""
    out = np.full(r.n, np.nan)
    i = r.rows(_solvable(r, DYNAMICS) & r["feasible"])
    if i.size:
        syn, c, m = r["synthesis"], r.c, r["masses"]
        arms = Masses(*(np.broadcast_to(v, (r.n,))[i] for v in (m.coupler, m.handle, c["arm_mass"])))
        cond = Conditions(c["speed"][i], c["dead_band"][i], c["inertia"][i], c["speed_fluctuation"][i], arms)
        out[i] = MODELS[DYNAMICS].peak_force(
            syn.linkage[i], syn.dead_centre_extended[i], syn.dead_centre_folded[i],
            c["wheel_torque"][i], cond,
        )  # fmt: skip
    return dict(effort_peak_force=out)


def motion(r: Run) -> dict[str, Any]:
    """What the motion asks of the operator: the power Mw ω̄, the grip's peak speed at the wheel's
    top speed, and (where the flywheel decides) the link energy it neglects (docs/models.md §4)."""
    c, index, rate = r.c, r["model_index"], r["rocker_rate"]
    energy = index > 0
    share, em = None, r["energy"]
    if em is not None and (index == ORDER.index(FLYWHEEL)).any():
        with np.errstate(divide="ignore", invalid="ignore"):
            share = np.where(em.band > 0, 100.0 * em.link_energy / em.band, np.inf)
        share = np.where(index == ORDER.index(FLYWHEEL), share, 0.0)
    grip = _load.grip_speed(rate, c["speed"], r["handle"], np.where(energy, c["speed_fluctuation"], 0.0))
    power = c["wheel_torque"] * c["speed"]
    cadence = c["speed"] / (2.0 * np.pi) * 60.0  # wheel turns a minute
    rope_speed = c["speed"] * c["wheel_radius"]  # the rope moves with the rim (docs/water.md §1)
    return dict(power=power, grip_speed=grip, link_energy_share=share, cadence=cadence, rope_speed=rope_speed)


def water(r: Run) -> dict[str, Any]:
    """The water a rope pump delivers, Q = η_v (π d²/4) ω̄ r_w: the rope moves with the wheel rim
    (docs/water.md §1), and what it is judged against."""
    c = r.c
    flow = _water_kernels.rope_pump_flow(c["pipe_diameter"], c["speed"], c["wheel_radius"],
                                         c["volumetric_efficiency"])  # fmt: skip
    read = {k: c[k] for k in WATER_KEYS if k in c}  # what the water depends on, and no more
    return dict(water=_water(flow, read, c["wheel_torque"] * c["speed"]))


def parts(r: Run) -> dict[str, Any]:
    """The part checks' values under the model that decided (docs/workshop.md §2), where the spec
    gives ``[parts]``; with ``screen_parts`` only on designs no other check fails."""
    if r.designs.parts is None:
        return dict(pin_pressure=None, handle_fatigue=None, crank_fatigue=None)
    judged = r["feasible"]
    if r.screen_parts:
        judged = judged & (np.atleast_1d(_assess(r).level) < FAIL)
    syn, c = r["synthesis"], r.c
    return _parts.part_checks(
        syn, c, r.designs.parts, r["model_index"], r["least_peak_force"], r["masses"], judged
    )


def service(r: Run) -> dict[str, Any]:
    """Safe to let go (the kick-back, the ratchet's torque), the pins' life and the field's checks
    (docs/workshop.md §3, §5; docs/water.md §5).  The pins' wear where the parts stage has run
    before it (the verdict's evaluation; it runs first in :data:`STAGES`), NaN otherwise."""
    parts, c = r.designs.parts, r.c
    pins = None if parts is None else np.broadcast_to(np.asarray(parts.pin_diameter, float), (r.n,))
    required, pawl = _service.pawl_windows(
        c["head"], c["pipe_diameter"], c["wheel_radius"], c["ratchet_torque"], c["ratchet_teeth"]
    )
    return dict(service=_service.service(
        {k: c[k] for k in _service.SERVICE_KEYS}, r.n, required, _kick_back(r, required, pawl),
        r["water"].flow, r.filled.get("pin_pressure"), pins,
    ))  # fmt: skip


def _kick_back(r: Run, required, pawl) -> tuple:
    """The kick-back of each design whose head gives a water column (not ``fitted``;
    :func:`pumplink.models.kickback.kick_back`, docs/workshop.md §3): the grip's travel back, the
    stop angle, the run, how it ends and whether a grid decided, with the ``[ratchet]`` that
    holds (the column's torque ``required`` and the pawl's window,
    :func:`pumplink.evaluate.service.pawl_windows`); and, for one design, the travel without it.
    One call: the designs a ratchet holds are asked again without it beside the others."""
    c, n, syn, m = r.c, r.n, r["synthesis"], r["masses"]
    travel, angle, run, end = (np.full(n, np.nan) for _ in range(4))
    grid = np.zeros(n, bool)
    ok = r.rows(np.asarray(r["feasible"], bool) & np.isfinite(required) & (not r.fitted))
    held = ok[np.isfinite(pawl[ok])] if n == 1 else ok[:0]  # without it: one design's words only
    free = np.full(n, np.nan)
    if ok.size:
        rows = np.concatenate([ok, held])
        stops = np.concatenate([pawl[ok], np.full(held.size, np.nan)])
        masses = Masses(*(np.broadcast_to(np.asarray(v, float), (n,))[rows] for v in (m.coupler, m.handle)))
        column = _release.column_inertia(c["head"], c["pipe_diameter"], c["wheel_radius"])
        kb = _kickback.kick_back(
            syn.linkage[rows], syn.dead_centre_extended[rows], syn.dead_centre_folded[rows], masses,
            required[rows], c["head"][rows], c["wheel_radius"][rows], c["inertia"][rows], column[rows], stops,
            rocker_rate=np.asarray(r["rocker_rate"], float)[rows],
        )  # fmt: skip
        k = ok.size
        travel[ok], angle[ok], run[ok], end[ok], grid[ok] = (
            kb.travel[:k],
            kb.stop_angle[:k],
            kb.run[:k],
            kb.end[:k],
            kb.marched_all[:k],
        )
        free[ok] = travel[ok]
        free[held] = kb.travel[k:]
    return travel, angle, run, end, grid, free


def _service_checks(r: Run) -> dict[str, Any]:
    """The verdict's service checks: the kick-back where a head gives the column, the ratchet's
    torque where the spec has one (neither ``fitted``), the pins' wear with ``[parts]``."""
    sv, c = r["service"], r.c
    out: dict[str, Any] = {}
    if np.isfinite(sv.holding_torque_required).any() and not r.fitted:
        out["kick_back"] = sv.kick_back
    if np.isfinite(sv.holding_torque).any() and not r.fitted:
        out["holding_torque"] = (sv.holding_torque, sv.holding_torque_required)
    if r["pin_pressure"] is not None:
        out["pin_wear"] = (1000.0 * sv.pin_wear, 1000.0 * c["wear_allowance"])
    return out


def _assess(r: Run, with_parts: bool = False):
    """:func:`pumplink.verdict.assess` on what the stages filled, the profile's limits from the
    columns; the part checks only ``with_parts``."""
    c, syn = r.c, r["synthesis"]
    mu = np.minimum(syn.transmission_min, np.pi - np.asarray(syn.transmission_max))
    part_values = {k: r[k] for k in PART_CHECKS} if with_parts else {}
    if with_parts:
        part_values.update(_service_checks(r))
    return assess(
        r["feasible"], r["mean_force"], r["peak_force"], c["force_limit"],
        link_energy_share=r["link_energy_share"], transmission_angle=np.degrees(mu), power=r["power"],
        grip_speed=r["grip_speed"], stroke=r["stroke"], grip_height=r["grip_height"],
        axle_height=r.designs.axle_height, power_limits=(c["sustained_power"], c["hour_power"]),
        grip_speed_limits=(c["grip_speed_warn"], c["grip_speed_fail"]),
        grip_height_range=(c["grip_height_min"], c["grip_height_max"]), **part_values,
        cadence=r["cadence"], rope_speed=r["rope_speed"], cadence_range=(c["cadence_min"], c["cadence_max"]),
    )  # fmt: skip


def verdict(r: Run) -> dict[str, Any]:
    """Every check and the verdict (:func:`pumplink.verdict.assess`, docs/models.md §4), against
    the operator profile's limits."""
    return dict(verdict=_assess(r, with_parts=True))


#: The stages in the order they run: name, the stages it needs, the fields it fills, its function.
STAGES = (
    Stage("geometry", "", "synthesis feasible handle rocker stroke grip_height rocker_rate", geometry),
    Stage("mean_force", "geometry", "mean_force", mean_force),
    Stage("model", "geometry", "model_index energy least_peak_force masses", model),
    Stage("dead_band_peak", "geometry", "dead_band_peak_force dead_band_peak_angle", dead_band_peak),
    Stage("peak", "model", "peak_force", peak),
    Stage("sampled_peak", "geometry", "sampled_peak", sampled_peak),
    Stage("passing_speed", "model", "min_passing_speed", passing_speed),
    Stage("effort", "model", "effort_peak_force", effort),
    Stage("motion", "model", "power grip_speed link_energy_share cadence rope_speed", motion),
    Stage("water", "", "water", water),
    Stage("parts", "mean_force peak motion", "pin_pressure handle_fatigue crank_fatigue", parts),
    Stage("service", "model water", "service", service),
    Stage("verdict", "mean_force peak motion parts service", "verdict", verdict),
)
_BY_NAME = {s.name: s for s in STAGES}


def plan(want) -> tuple[Stage, ...]:
    """The stages that the stages named in ``want`` need (themselves included), in run order."""
    todo, stack = set(), list(want)
    while stack:
        name = stack.pop()
        if name not in _BY_NAME:
            raise ValueError(f"no evaluation stage {name!r}; the stages are {', '.join(_BY_NAME)}")
        if name not in todo:
            todo.add(name)
            stack.extend(_BY_NAME[name].needs.split())
    return tuple(s for s in STAGES if s.name in todo)


def run(r: Run, want) -> dict[str, Any]:
    """Run the stages ``want`` needs on ``r``; every field they filled, by name."""
    for stage in plan(want):
        filled = stage.fill(r)
        assert filled.keys() == set(stage.fills.split()), (stage.name, sorted(filled))  # a stage's contract
        r.filled.update(filled)
    return r.filled


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
    """Evaluate designs: the stages ``want`` names (:data:`STAGES`) and
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
    r = Run(designs, model=model, samples=samples, progress=progress, screen_parts=screen_parts,
            fitted=fitted)  # fmt: skip
    return Evaluation(designs=designs, **run(r, want))


__all__ = ["JUDGED", "QUASI_STATIC", "REPORTED", "STAGES", "Run", "Stage", "evaluate", "plan", "run"]

"""Accuracy and speed of the force methods, and the sampling study.

Sample sets, error statistics against the ``reference`` method, the timed comparison of every
method (:func:`compare_methods`), and what a uniform sweep of N samples reports for the peak and
mean force.  Results are plain dicts keyed by identifiers; the words are in
output layer (:data:`pumplink.output.methods.POINT_LABELS`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import DANGER, DEAD_CENTRE, NEAR_DEAD_CENTRE, UNIFORM
from pumplink.errors import InfeasibleDesign
from pumplink.evaluate import QUASI_STATIC, PumpDesigns, evaluate, motion, pump_designs
from pumplink.inputs.pump import PumpSpec
from pumplink.mechanisms.angles import crank_grid
from pumplink.mechanisms.fourbar import FourBar, kinematic_state
from pumplink.studies.methods import DANGER_KINDS, METHODS, MethodResult, danger_points

#: Offsets from each dead centre [deg] at which the methods are compared.
DEAD_CENTRE_OFFSETS_DEG = (1.0, 1e-2, 1e-4, 1e-6)
#: Sample counts of the sampling study.
SAMPLE_COUNTS = (12, 36, 72, 360, 3600)


def sample_sets(lk: FourBar, dead_centre_extended, dead_centre_folded, n: int = 360) -> dict[str, np.ndarray]:
    """Crank angles [rad] for each sampling of the comparison (single design).

    ``UNIFORM``: n uniform angles (offset by half a step, so no sample is a dead centre by
    construction); ``NEAR_DEAD_CENTRE``: both sides of both dead centres at
    :data:`DEAD_CENTRE_OFFSETS_DEG`; ``DEAD_CENTRE``: the two dead centres; ``DANGER``: every
    point of :func:`pumplink.studies.methods.danger_points` and 1e-9 rad either side.
    """
    dc = np.array([dead_centre_extended, dead_centre_folded], float)
    off = np.radians(np.array(DEAD_CENTRE_OFFSETS_DEG))
    near = (dc[:, None, None] + np.array([-1.0, 1.0])[None, :, None] * off[None, None, :]).ravel()
    pts = danger_points(lk)
    danger = np.concatenate([pts[k] for k in DANGER_KINDS])
    danger = (danger[:, None] + np.array([0.0, -1e-9, 1e-9])).ravel()
    return {UNIFORM: crank_grid(n, np.pi / n), NEAR_DEAD_CENTRE: near, DEAD_CENTRE: dc, DANGER: danger}


def error_stats(result: MethodResult, ref: MethodResult, tolerance: float) -> dict:
    """How a method's forces compare with the reference on one sample set.

    Returns
    -------
    dict with ``n`` (points), ``max_rel_error`` (over points both give a finite force; None if
    none), ``flagged`` (points the method flagged), ``missed_singular`` (reference singular but the
    method returned a finite force), ``wrong`` (unflagged finite values off by more than
    ``tolerance``, or NaN without a flag: silent garbage).
    """
    f, fr = np.asarray(result.force, float), np.asarray(ref.force, float)
    flagged = np.asarray(result.failed | result.singular)
    both = np.isfinite(f) & np.isfinite(fr)
    with np.errstate(divide="ignore", invalid="ignore"):
        err = np.where(both, np.abs(f - fr) / np.abs(fr), np.nan)
    wrong = (both & (err > tolerance)) | (~flagged & ~np.isfinite(f) & np.isfinite(fr))
    missed = np.asarray(ref.singular) & np.isfinite(f)
    return {
        "n": int(f.size),
        "max_rel_error": float(np.max(err[both])) if both.any() else None,
        "flagged": int(flagged.sum()),
        "missed_singular": int(missed.sum()),
        "wrong": int(wrong.sum()),
    }


def failures(stats_by_set: dict[str, dict]) -> list[dict]:
    """Where a method flagged or went silently wrong: one record per finding, ``{"kind", "what",
    "count", "n"}`` with ``what`` one of ``wrong`` (values off by more than the tolerance),
    ``missed_singular`` (dead centres returned as finite forces), ``flagged`` (points with no
    value; not reported for the exact dead centres, where no value is right)."""
    out = []
    for kind, s in stats_by_set.items():
        for what in ("wrong", "missed_singular", "flagged"):
            if s[what] and not (what == "flagged" and kind == DEAD_CENTRE):
                out.append({"kind": kind, "what": what, "count": s[what], "n": s["n"]})
    return out


def seconds_per_position(fn, args, n: int, repeats: int, budget: float = 1.0) -> float:
    """Median wall time of ``fn(*args)`` per position [s] over ``repeats`` runs (fewer if slow)."""
    import statistics
    import time

    times = []
    start = time.perf_counter()
    for _ in range(max(1, repeats)):
        t0 = time.perf_counter()
        fn(*args)
        times.append(time.perf_counter() - t0)
        if time.perf_counter() - start > budget:
            break
    return statistics.median(times) / n


def compare_methods(
    lk: FourBar,
    dead_centre_extended,
    dead_centre_folded,
    wheel_torque,
    names,
    samples: int,
    repeats: int,
    advance=None,
) -> list[dict]:
    """Time every method in ``names`` and compare it with the 50-digit reference on each sample set.

    Returns one dict per method: ``name``, ``summary``, ``cannot_handle``, ``seconds_per_position``
    (uniform sweep), ``max_rel_error_uniform``, ``max_rel_error_near_dead_centre``, ``failures``
    (:func:`failures`) and ``samplings`` (per sample set: :func:`error_stats` plus the timing).
    ``advance(1)``, when given, is called after each of the ``(len(names) + 1) * len(sets)``
    steps (the reference on each set, then each method on each set), for a progress bar.
    """
    step = advance or (lambda n: None)
    sets = sample_sets(lk, dead_centre_extended, dead_centre_folded, samples)
    refs = {}
    for k, a in sets.items():
        refs[k] = METHODS["reference"].function(lk, a, wheel_torque)
        step(1)
    rows = []
    for name in names:
        m = METHODS[name]
        per_set = {}
        for kind, angles in sets.items():
            tol = m.tolerance.get(kind, max(m.tolerance[k] for k in m.tolerance))
            stats = error_stats(m.function(lk, angles, wheel_torque), refs[kind], tol)
            stats["seconds_per_position"] = seconds_per_position(
                m.function, (lk, angles, wheel_torque), angles.size, repeats
            )
            per_set[kind] = stats
            step(1)
        rows.append(
            {
                "name": name,
                "summary": m.summary,
                "cannot_handle": m.cannot,
                "seconds_per_position": per_set[UNIFORM]["seconds_per_position"],
                "max_rel_error_uniform": per_set[UNIFORM]["max_rel_error"],
                "max_rel_error_near_dead_centre": per_set[NEAR_DEAD_CENTRE]["max_rel_error"],
                "failures": failures(per_set),
                "samplings": per_set,
            }
        )
    return rows


def silently_wrong(rows: list[dict]) -> bool:
    """True if any method returned a wrong value without a flag (the ``methods`` command's exit 1)."""
    return any(st["wrong"] or st["missed_singular"] for r in rows for st in r["samplings"].values())


def sampled_mean_force(lk: FourBar, n: int, wheel_torque) -> float:
    """Mean operator force a sweep of ``n`` uniform samples implies [N].

    The cycle's work 2 pi Mw divided by the grip travel the samples see,
    sum |Px(j+1) - Px(j)| around the closed sweep; the exact travel is twice the stroke
    2 H sin(swing/2) (docs/physics.md), which a coarse sweep underestimates at the turning points.
    """
    st = kinematic_state(lk, crank_grid(n), wheel_torque)
    gx = lk.pivot_x + lk.handle * np.cos(st.rocker_angle)
    travel = np.sum(np.abs(np.diff(np.append(gx, gx[0]))))
    return float(2.0 * np.pi * wheel_torque / travel)


def sampling_study(designs: PumpDesigns, counts=SAMPLE_COUNTS) -> list[dict]:
    """What a uniform sweep of N samples (from crank angle 0) reports, against the exact values.

    Returns one dict per N: ``n``; ``sampled_max`` (largest finite |F| of the sweep with no
    dead band: what "maximum below 100 N" means for a plain sweep); ``sampled_peak`` (largest
    |F| outside the dead bands) and ``exact_peak`` (the quasi-static peak outside the dead bands,
    :func:`pumplink.evaluate.evaluate`) with the relative error ``peak_error``; ``sampled_mean``
    (:func:`sampled_mean_force`), ``exact_mean`` (the evaluation's mean force) and ``mean_error``.
    Forces [N].  ``designs``: one rope-pump design.
    """
    rows = []
    for n in counts:
        ev = evaluate(
            designs, ("mean_force", "sampled_peak", "dead_band_peak"), model=QUASI_STATIC, samples=n
        )
        _, lk = motion.at_design(ev)
        exact_peak, exact_mean, peak = (
            float(v[0]) for v in (ev.dead_band_peak_force, ev.mean_force, ev.sampled_peak)
        )
        wheel_torque = float(designs.wheel_torque)
        st = kinematic_state(lk, crank_grid(n), wheel_torque)
        f = np.abs(st.force[np.isfinite(st.force)])
        mean = sampled_mean_force(lk, n, wheel_torque)
        rows.append(
            {
                "n": int(n),
                "sampled_max": float(f.max()) if f.size else None,
                "sampled_peak": peak if np.isfinite(peak) else None,
                "exact_peak": exact_peak,
                "peak_error": abs(peak - exact_peak) / exact_peak if np.isfinite(peak) else None,
                "sampled_mean": mean,
                "exact_mean": exact_mean,
                "mean_error": abs(mean - exact_mean) / exact_mean,
            }
        )
    return rows


@dataclass(frozen=True)
class MethodStudy:
    """``pumplink methods`` on one design: every method against the reference (:func:`compare_methods`)
    and what uniform sweeps report (:func:`sampling_study`)."""

    name: str
    methods: list[dict]
    sampling: list[dict]
    dead_band_deg: float


def method_study(spec: PumpSpec, names, samples: int, repeats: int, advance=None) -> MethodStudy:
    """The methods of ``names`` compared on the spec's design, and the sampling study.

    Raises
    ------
    InfeasibleDesign : no crank-rocker for this spec.
    """
    designs = pump_designs(spec.values)
    ev = evaluate(designs, ("mean_force",), model=QUASI_STATIC)
    if not ev.feasible[0]:
        from pumplink.studies.force import design

        raise InfeasibleDesign(f"{spec.name}: {design(spec).error}")
    syn, lk = motion.at_design(ev)
    mw = float(designs.wheel_torque)
    rows = compare_methods(
        lk, syn.dead_centre_extended, syn.dead_centre_folded, mw, names, samples, repeats, advance
    )
    return MethodStudy(spec.name, rows, sampling_study(designs), spec.operator.dead_band)


def method_steps(names) -> int:
    """The steps :func:`method_study` reports to ``advance``: the reference and each method on
    each of the four sample sets of :func:`sample_sets`."""
    return (len(names) + 1) * len((UNIFORM, NEAR_DEAD_CENTRE, DEAD_CENTRE, DANGER))

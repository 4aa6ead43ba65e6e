"""A piston pump in depth (``pumplink force`` on a spec with ``mechanism = "crank-slider"``,
docs/piston-pump.md): the force over the crank turn, the verdict, which model decided and why, and
an independent check.

The verdict and the numbers it judges come from the one evaluation
(:func:`pumplink.evaluate.evaluate` on :class:`pumplink.evaluate.PistonDesigns`, n = 1); this
module adds the force at sampled crank angles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.constants import PERMISSIBLE_PRESSURE_SLIDING_DEG
from pumplink.evaluate import FLYWHEEL, ORDER, Verdict, Water, evaluate, motion, piston_designs
from pumplink.inputs.piston import PistonSpec
from pumplink.mechanisms import crank_slider as cs


@dataclass(frozen=True)
class PistonResult:
    """Force analysis of one piston pump at one crank speed (SI units, radians).

    ``samples`` are the crank angles of the sweep (empty with ``keep_samples=False``) and the
    arrays beside them its slider position, velocity ratio, crank torque, operator force and
    pressure angle.
    """

    spec: PistonSpec
    error: str | None
    speed_deg_s: float
    speed: float
    load_force: float
    force_limit: float  # [N] (the operator profile's, or the spec's)
    stroke: float
    time_ratio: float
    largest_pressure_angle: float
    mean_force: float
    quasi_static_peak: float
    quasi_static_peak_angle: float
    model: str
    inertia: float | None
    energy_band: float | None
    least_peak_force: float | None
    power: float
    verdict: Verdict | None
    samples: np.ndarray
    slider_position: np.ndarray
    velocity_ratio: np.ndarray
    crank_torque: np.ndarray
    operator_force: np.ndarray
    pressure_angle: np.ndarray
    water: Water | None = None  # the water it delivers (pumplink.evaluate.Water, one design)

    @property
    def feasible(self) -> bool:
        return self.error is None

    @property
    def passed(self) -> bool:
        return bool(self.verdict is not None and self.verdict.passed)

    @property
    def flywheel(self) -> bool:
        return self.model == FLYWHEEL

    @property
    def verdict_peak_force(self) -> float:
        return self.least_peak_force if self.flywheel else self.quasi_static_peak

    @property
    def pressure_permissible_deg(self) -> tuple[float, float]:
        """The textbook's permissible pressure angle for a sliding driven link [deg] (§2.4)."""
        return PERMISSIBLE_PRESSURE_SLIDING_DEG


def force_analysis(
    spec: PistonSpec,
    speed_deg_s: float | None = None,
    samples: int = 360,
    at_deg=None,
    keep_samples: bool = True,
) -> PistonResult:
    """Force sweep, the deciding model's peak force and the verdict of one piston pump.

    Parameters
    ----------
    spec : validated piston-pump spec.
    speed_deg_s : crank speed [deg/s]; default ``spec.operator.speed``.
    samples : uniform crank samples; at_deg : explicit crank angles [deg] instead.
    keep_samples : False for the summary only.
    """
    cr, op = spec.crank_slider, spec.operator
    r, rod, e = cr.crank, cr.rod, cr.offset
    speed_deg = float(op.speed if speed_deg_s is None else speed_deg_s)
    w = math.radians(speed_deg)
    ev = evaluate(piston_designs(spec.values, speed_deg))
    load = float(ev.designs.load_force)
    inertia = float(ev.designs.inertia) if spec.gives_inertia else None
    model = ORDER[int(ev.model_index[0])]
    nan = float("nan")
    empty = np.empty(0)
    if not ev.feasible[0]:
        error = cs.infeasibility_reason(r, rod, e)
        return PistonResult(
            spec,
            error,
            speed_deg,
            w,
            load,
            float(ev.designs.force_limit),
            nan,
            nan,
            nan,
            nan,
            nan,
            nan,
            model,
            inertia,
            None,
            None,
            nan,
            None,
            empty,
            empty,
            empty,
            empty,
            empty,
            empty,
        )
    flywheel = inertia is not None
    if at_deg is not None:
        t = np.radians(np.asarray(at_deg, float))
    elif keep_samples:
        t = np.arange(samples) * (2.0 * math.pi / samples)
    else:
        t = empty
    torque = motion.piston_crank_torque(r, rod, e, load, t)
    return PistonResult(
        spec=spec,
        error=None,
        speed_deg_s=speed_deg,
        speed=w,
        load_force=load,
        force_limit=float(ev.designs.force_limit),
        stroke=float(ev.stroke[0]),
        time_ratio=float(ev.time_ratio[0]),
        largest_pressure_angle=float(ev.largest_pressure_angle[0]),
        mean_force=float(ev.mean_force[0]),
        quasi_static_peak=float(ev.quasi_static_peak[0]),
        quasi_static_peak_angle=float(ev.quasi_static_peak_angle[0]),
        model=model,
        inertia=inertia,
        energy_band=float(ev.energy_band[0]) if flywheel else None,
        least_peak_force=float(ev.least_peak_force[0]) if flywheel else None,
        power=float(ev.power[0]),
        verdict=ev.verdict.design(0),
        samples=t,
        slider_position=np.asarray(cs.slider_position(r, rod, e, t), float),
        velocity_ratio=np.asarray(cs.velocity_ratio(r, rod, e, t), float),
        crank_torque=torque,
        operator_force=torque / op.handle,
        pressure_angle=np.asarray(cs.pressure_angle(r, rod, e, t), float),
        water=ev.water.design(0),
    )


# ----------------------------------------------------------------------------- explain, verify
def explain(r: PistonResult) -> str:
    """Which model decided the piston pump's verdict and why it is enough (docs/piston-pump.md)."""
    left_out = (
        "Left out: the crank's, rod's and piston's inertia, the water column's acceleration and friction "
        "(in the efficiency)."
    )
    if r.flywheel:
        return (
            f"Flywheel decided: the spec gives the crank shaft's inertia (J = {r.inertia:.3g} kg·m²), so "
            f"the operator need not push the working stroke's peak: the least peak force that keeps the "
            f"speed within δ is exact (Eq. P.4, docs/piston-pump.md), enough while the crank and rod "
            f"are light beside the flywheel. {left_out}"
        )
    return (
        "Quasi-static decided: the operator turns the crank, so the handle force T/R is finite at every "
        "crank angle (no dead centre for the operator) and the speed does not enter it; its peak over "
        "the turn is exact, and that is enough for the verdict without a flywheel (nothing carries the "
        "crank past the working stroke's peak). Give wheel.inertia or wheel.mass for the flywheel "
        f"model. {left_out}"
    )


#: Crank angles of the dense sweeps of :func:`verify` over one turn.
VERIFY_SAMPLES = 400_000


@dataclass(frozen=True)
class PistonCheck:
    """A piston pump's answer checked on a dense sweep that shares none of its formulas: the work
    of one turn by quadrature, the peak against the sweep and (flywheel) the energy deficit."""

    samples: int
    work: float  # |integral of T over a turn / (F_load H) - 1| (trapezoid rule)
    sweep_peak: float  # largest F on the sweep [N]
    peak: float  # the exact quasi-static peak [N]
    deficit: float | None  # flywheel: the largest loss over an arc at Fp* by quadrature / W
    tolerance: float
    agrees: bool


def verify(r: PistonResult, rtol: float = 1e-6) -> PistonCheck:
    """Check the piston pump's answer on :data:`VERIFY_SAMPLES` crank angles: the trapezoid
    integral of the crank torque over a turn is the work F_load H (Eq. P.3) to ``rtol``; no sample
    of the handle force exceeds the exact quasi-static peak and the largest comes within ``rtol``
    of it (a smooth maximum); with a flywheel the largest energy lost over an arc at Fp*, by the
    same quadrature over two turns, is the energy band W (to ``rtol``; at most W where Fp* is the
    mean force)."""
    cr, op = r.spec.crank_slider, r.spec.operator
    t = np.linspace(0.0, 4.0 * math.pi, 2 * VERIFY_SAMPLES + 1)
    torque = motion.piston_crank_torque(cr.crank, cr.rod, cr.offset, r.load_force, t)
    one = t <= 2.0 * math.pi * (1 + 1e-15)
    work = float(np.trapezoid(torque[one], t[one]))
    err = abs(work / (r.load_force * r.stroke) - 1.0)
    top = float(np.max(torque[one]) / op.handle)
    ok = err <= rtol and top <= r.quasi_static_peak * (1 + 1e-12) and top >= r.quasi_static_peak * (1 - rtol)
    deficit = None
    if r.flywheel and r.least_peak_force is not None and math.isfinite(r.least_peak_force):
        step = t[1] - t[0]
        gain = np.concatenate([[0.0], np.cumsum(0.5 * step * (torque[1:] + torque[:-1]))]) - (
            r.least_peak_force * op.handle * t
        )  # integral of (T - Fp R): the energy lost
        deficit = float(np.max(gain - np.minimum.accumulate(gain))) / r.energy_band
        at_mean = r.least_peak_force <= r.mean_force * (1 + 1e-12)
        ok = ok and (deficit <= 1 + rtol if at_mean else abs(deficit - 1.0) <= rtol)
    return PistonCheck(VERIFY_SAMPLES, err, top, r.quasi_static_peak, deficit, rtol, bool(ok))

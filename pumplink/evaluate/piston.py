"""The evaluation of piston pumps (a crank-slider turned by a hand crank, docs/piston-pump.md):
the crank-slider's quality indicators, the mean force (Eq. P.3), the quasi-static peak and the
flywheel's least peak force (Eq. P.4), the power, the water and the verdict.  The crank-slider's
kernels take one design at a time, so the designs are solved in turn."""

from __future__ import annotations

import math

import numpy as np

from pumplink.evaluate.designs import PistonDesigns
from pumplink.evaluate.results import PistonEvaluation
from pumplink.evaluate.water import water
from pumplink.mechanisms import crank_slider as cs
from pumplink.models import FLYWHEEL, ORDER
from pumplink.models import water as _water_kernels
from pumplink.verdict import assess


def evaluate_piston(designs: PistonDesigns, judge: bool = True) -> PistonEvaluation:
    """Every quantity of the verdict of piston pumps, and the verdict (``judge``)."""
    from pumplink.models import flywheel as _fw
    from pumplink.models import piston as _pm

    n, c = designs.columns
    r, rod, e, handle, load = c["crank"], c["rod"], c["offset"], c["handle"], c["load_force"]
    feasible = np.asarray(cs.turns_fully(r, rod, e), bool)
    out = {k: np.full(n, np.nan) for k in ("stroke", "ratio", "pressure", "mean", "peak", "angle", "least")}
    band = np.where(
        np.isnan(c["inertia"]), np.nan, _fw.energy_band(c["inertia"], c["speed"], c["speed_fluctuation"])
    )
    index = np.where(np.isnan(c["inertia"]), 0, ORDER.index(FLYWHEEL))
    for i in np.nonzero(feasible)[0].tolist():
        args = (r[i], rod[i], e[i])
        out["stroke"][i] = float(cs.stroke(*args))
        out["ratio"][i] = float(cs.time_ratio(*args))
        out["pressure"][i] = float(cs.largest_pressure_angle(*args))
        out["mean"][i] = _pm.mean_force(*args, load[i], handle[i])  # Eq. (P.3)
        out["peak"][i], out["angle"][i] = _pm.quasi_static_peak(*args, load[i], handle[i])
        if index[i]:
            out["least"][i] = _pm.least_peak_force(*args, load[i], handle[i], band[i])  # Eq. (P.4)
    power = load * out["stroke"] * c["speed"] / (2.0 * math.pi)  # the work F_load H per revolution
    peak = np.where(index > 0, out["least"], out["peak"])
    verdict = None
    if judge:
        limits = (c["sustained_power"], c["hour_power"])
        verdict = assess(feasible, out["mean"], peak, c["force_limit"], power=power, power_limits=limits)
    # Q = η_v A H f for a single-acting piston (docs/water.md §1)
    flow = _water_kernels.piston_pump_flow(c["bore"], out["stroke"], c["speed"], c["volumetric_efficiency"])
    return PistonEvaluation(
        designs=designs,
        feasible=feasible,
        stroke=out["stroke"],
        time_ratio=out["ratio"],
        largest_pressure_angle=out["pressure"],
        mean_force=out["mean"],
        quasi_static_peak=out["peak"],
        quasi_static_peak_angle=out["angle"],
        model_index=index,
        energy_band=band,
        least_peak_force=out["least"],
        power=power,
        verdict=verdict,
        water=water(flow, c, power),
    )

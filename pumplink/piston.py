"""The piston-pump spec (``mechanism = "crank-slider"``): its validation, force analysis and batch.

A pump spec with ``mechanism = "crank-slider"`` describes a single-acting piston pump driven
through a crank-slider by a handle crank (docs/piston-pump.md); without the key a spec is a rope
pump (``pumplink.spec``).  ``pumplink force`` and ``pumplink batch`` dispatch on the key before
reading the spec.  Schema (SI units, angles in degrees)::

    name = "Village piston pump"
    mechanism = "crank-slider"
    [piston]         bore [m], head [m], efficiency [-]
    [crank_slider]   crank [m], rod [m], offset [m] (default 0)
    [operator]       handle [m] (radius of the crank the operator turns), force_limit [N],
                     speed [deg/s] (crank speed), speed_fluctuation [-]
    [wheel]          optional flywheel on the crank shaft: inertia [kg m^2], or mass [kg] with
                     radius [m] (a rim); turns on the flywheel model

The verdict is :func:`pumplink.verdict.assess` on the mean force and the deciding model's peak
force; the model is the one :func:`pumplink.models.choose_model` picks (flywheel with inertia,
else quasi-static), computed by :mod:`pumplink.models.piston`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal

import numpy as np
from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from pumplink.constants import DEFAULT_SPEED_FLUCTUATION, FORCE_LIMIT_N, PERMISSIBLE_PRESSURE_SLIDING_DEG
from pumplink.errors import SpecError
from pumplink.evaluate import evaluate, piston_designs
from pumplink.mechanisms import crank_slider as cs
from pumplink.models import FLYWHEEL, ORDER
from pumplink.models import piston as _pm
from pumplink.spec import batch_base, is_piston_data, read_toml, spec_values
from pumplink.verdict import Verdict

#: The mechanism kinds a spec may name (the rope pump's four-bar has no key).
MECHANISMS = ("crank-slider",)


class _Section(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


class Piston(_Section):
    bore: float = Field(ge=0.005, le=0.5, description="piston (cylinder) bore [m]")
    head: float = Field(gt=0, le=200, description="pumping head [m]")
    efficiency: float = Field(ge=0.05, le=1, description="pump efficiency (mechanical x volumetric) [-]")


class CrankSlider(_Section):
    crank: float = Field(ge=0.001, le=5, description="crank radius r [m] (half the stroke when offset = 0)")
    rod: float = Field(ge=0.001, le=20, description="connecting rod length l [m]")
    offset: float = Field(default=0.0, ge=-5, le=5, description="guide offset e from the crank pivot [m]")


class PistonOperator(_Section):
    handle: float = Field(ge=0.02, le=2, description="radius of the crank the operator turns [m]")
    force_limit: float = Field(default=FORCE_LIMIT_N, ge=1, le=10_000, description="force limit [N]")
    speed: float = Field(default=360.0, gt=0, le=7200, description="crank speed [deg/s]")
    speed_fluctuation: float = Field(
        default=DEFAULT_SPEED_FLUCTUATION, gt=0, le=1, description="largest (w_max - w_min)/w_mean [-]"
    )


class Flywheel(_Section):
    inertia: float | None = Field(
        default=None, gt=0, le=1000, description="inertia on the crank shaft [kg m^2]"
    )
    mass: float | None = Field(default=None, gt=0, le=1000, description="wheel mass [kg] (a rim)")
    radius: float | None = Field(default=None, ge=0.01, le=5, description="wheel radius [m] (with mass)")

    @model_validator(mode="after")
    def _one(self) -> Flywheel:
        if (self.inertia is None) == (self.mass is None):
            raise ValueError("give either wheel.inertia [kg m^2] or wheel.mass [kg] with wheel.radius [m]")
        if self.mass is not None and self.radius is None:
            raise ValueError("wheel.mass needs wheel.radius [m] (the wheel is taken as a rim: J = m r^2)")
        return self


class PistonSpec(_Section):
    name: str = Field(default="piston pump", min_length=1, max_length=200, description="design name")
    mechanism: Literal["crank-slider"] = Field(description="the mechanism kind: crank-slider")
    piston: Piston
    crank_slider: CrankSlider
    operator: PistonOperator
    wheel: Flywheel | None = None

    @property
    def inertia(self) -> float | None:
        """J on the crank shaft [kg m^2], or None (quasi-static model)."""
        w = self.wheel
        if w is None:
            return None
        return w.inertia if w.inertia is not None else w.mass * w.radius**2

    @property
    def load_force(self) -> float:
        """Piston force on the working stroke [N] (docs/piston-pump.md, Eq. P.1)."""
        p = self.piston
        return float(_pm.load_force(p.bore, p.head, p.efficiency))


# ----------------------------------------------------------------------------- reading
def _describe(err: dict) -> str:
    key = ".".join(str(p) for p in err["loc"]) or "the spec"
    kind = err["type"]
    if kind == "missing":
        return f"missing key '{key}'"
    if kind == "extra_forbidden":
        return f"unknown key '{key}'"
    if kind == "literal_error":
        return f"'{key}' = {err.get('input')!r} must be one of: {', '.join(MECHANISMS)}"
    if kind == "value_error":
        return str(err["msg"]).removeprefix("Value error, ")
    return f"'{key}' = {err.get('input')!r}: {err['msg']}"


def parse_piston(data: Any, source: str = "spec") -> PistonSpec:
    """Validate a piston-pump mapping; one sentence per problem naming the key (SpecError)."""
    try:
        return PistonSpec.model_validate(data)
    except ValidationError as exc:
        errs = sorted(exc.errors(), key=lambda e: e["type"] != "extra_forbidden")
        more = f" (and {len(errs) - 1} more)" if len(errs) > 1 else ""
        raise SpecError(f"{source}: {_describe(errs[0])}{more}.") from None


def load_piston(path: str | Path) -> PistonSpec:
    """Read and validate a piston-pump spec file; the name defaults to the file stem."""
    data = read_toml(path)
    if isinstance(data, dict) and "name" not in data:
        data = {"name": Path(path).stem, **data}
    return parse_piston(data, source=str(path))


# ----------------------------------------------------------------------------- analysis
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
    load = spec.load_force
    inertia = spec.inertia
    ev = evaluate(piston_designs(spec_values(spec), speed_deg))
    model = ORDER[int(ev.model_index[0])]
    nan = float("nan")
    empty = np.empty(0)
    if not ev.feasible[0]:
        error = (
            f"rod {rod:g} m is not longer than crank {r:g} m + |offset| {abs(e):g} m, so the crank cannot "
            f"turn fully; lengthen the rod beyond {r + abs(e):g} m"
        )
        return PistonResult(
            spec,
            error,
            speed_deg,
            w,
            load,
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
    torque = _pm.crank_torque(r, rod, e, load, t)
    return PistonResult(
        spec=spec,
        error=None,
        speed_deg_s=speed_deg,
        speed=w,
        load_force=load,
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
    torque = _pm.crank_torque(cr.crank, cr.rod, cr.offset, r.load_force, t)
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


# ----------------------------------------------------------------------------- batch
@dataclass(frozen=True)
class PistonVariant:
    name: str
    values: dict[str, float]
    result: PistonResult


def _axis(key: str, raw: Any, where: str) -> list[float]:
    if (
        isinstance(raw, list)
        and raw
        and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in raw)
    ):
        return [float(v) for v in raw]
    if isinstance(raw, dict) and set(raw) == {"start", "stop", "num"}:
        num = raw["num"]
        if isinstance(num, int) and not isinstance(num, bool) and 1 <= num <= 10_000:
            return [round(float(v), 12) for v in np.linspace(float(raw["start"]), float(raw["stop"]), num)]
    raise SpecError(
        f"{where}: [vary] '{key}' must be a list of numbers or {{ start, stop, num }} (num 1..10000)"
    )


def expand_batch(path: str | Path) -> list[tuple[str, dict[str, float], PistonSpec]]:
    """The variants of a piston-pump batch file (base spec + [vary], Cartesian product, the last
    axis fastest, as ``pumplink batch`` does for rope pumps) or of a plain piston spec file."""
    path = Path(path)
    data = read_toml(path)
    if is_piston_data(data):
        return [(load_piston(path).name, {}, load_piston(path))]
    unknown = set(data) - {"name", "base", "vary"}
    if unknown:
        raise SpecError(
            f"{path}: unknown key '{sorted(unknown)[0]}' in a batch file; allowed: name, base, vary"
        )
    base = batch_base(data, path)
    label = str(data.get("name", path.stem))
    parse_piston({"name": label, **base}, source=f"{path} [base]")
    vary = data.get("vary", {})
    if not isinstance(vary, dict):
        raise SpecError(f"{path}: [vary] must be a table of 'section.key' = [values]")
    axes = [(k, _axis(k, v, str(path))) for k, v in vary.items()]
    out = []
    width = len(str(max(1, math.prod(len(v) for _, v in axes) - 1)))
    for i, combo in enumerate(itertools.product(*(v for _, v in axes))):
        spec = {k: dict(v) if isinstance(v, dict) else v for k, v in base.items()}
        values = {}
        for (key, _), value in zip(axes, combo, strict=True):
            section, _, leaf = key.partition(".")
            if not leaf or section not in PistonSpec.model_fields or section in ("name", "mechanism"):
                raise SpecError(f"{path}: [vary] key '{key}' must be 'section.key', e.g. 'piston.bore'")
            spec.setdefault(section, {})[leaf] = value
            values[key] = value
        tag = " ".join(f"{k.rpartition('.')[2]}={v:g}" for k, v in values.items())
        name = f"{label}#{i:0{width}d}" + (f"[{tag}]" if tag else "")
        out.append((name, values, parse_piston({**spec, "name": name}, source=f"{path} variant {name}")))
    return out


def run_batch(paths, samples: int = 0) -> list[PistonVariant]:
    """Every variant of the given piston-pump spec or batch files, analysed (summary only)."""
    out = []
    for p in paths:
        for name, values, spec in expand_batch(p):
            out.append(PistonVariant(name, values, force_analysis(spec, keep_samples=False)))
    return out

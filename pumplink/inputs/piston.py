"""The piston-pump spec (``mechanism = "crank-slider"``), validated by pydantic.

A pump spec with ``mechanism = "crank-slider"`` describes a single-acting piston pump driven
through a crank-slider by a handle crank (docs/piston-pump.md); without the key a spec is a rope
pump (:mod:`pumplink.inputs.pump`).  Schema (SI units, angles in degrees)::

    name = "Village piston pump"
    mechanism = "crank-slider"
    [piston]         bore [m], head [m], efficiency [-]
    [crank_slider]   crank [m], rod [m], offset [m] (default 0)
    [operator]       handle [m] (radius of the crank the operator turns), force_limit [N],
                     speed [deg/s] (crank speed), speed_fluctuation [-]
    [wheel]          optional flywheel on the crank shaft: inertia [kg m^2], or mass [kg] with
                     radius [m] (a rim); turns on the flywheel model
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Literal

from pydantic import Field, model_validator

from pumplink.constants import DEFAULT_SPEED_FLUCTUATION
from pumplink.inputs.pump import HOUR_POWER, SUSTAINED_POWER, Use, limits_in_order, spec_values
from pumplink.inputs.toml import Section, optional, read_toml, spec_name, validate
from pumplink.models import load as _load
from pumplink.profiles import operator_limits

#: The mechanism kinds a spec may name (the rope pump's four-bar has no key).
MECHANISMS = ("crank-slider",)


class Piston(Section):
    bore: float = Field(ge=0.005, le=0.5, description="piston (cylinder) bore [m]")
    head: float = Field(gt=0, le=200, description="pumping head [m]")
    efficiency: float = Field(
        ge=0.05,
        le=1,
        description="force (mechanical) efficiency [-]: the piston force is the water column's weight "
        "over it",
    )
    volumetric_efficiency: float | None = optional(
        "delivered over swept volume [-] (leakage past the piston and valves; default 0.87)", ge=0.05, le=1
    )


class CrankSlider(Section):
    crank: float = Field(ge=0.001, le=5, description="crank radius r [m] (half the stroke when offset = 0)")
    rod: float = Field(ge=0.001, le=20, description="connecting rod length l [m]")
    offset: float = Field(default=0.0, ge=-5, le=5, description="guide offset e from the crank pivot [m]")


class PistonOperator(Section):
    handle: float = Field(ge=0.02, le=2, description="radius of the crank the operator turns [m]")
    profile: Literal["men", "women", "children", "accessible"] | None = optional(
        "who pumps: sets force_limit, sustained_power and hour_power (docs/operators.md); a key "
        "given here overrides it (default: men)"
    )
    force_limit: float | None = optional("force limit [N] (profile's)", ge=1, le=10_000)
    sustained_power: float | None = SUSTAINED_POWER
    hour_power: float | None = HOUR_POWER
    speed: float = Field(default=360.0, gt=0, le=7200, description="crank speed [deg/s]")
    speed_fluctuation: float = Field(
        default=DEFAULT_SPEED_FLUCTUATION, gt=0, le=1, description="largest (w_max - w_min)/w_mean [-]"
    )

    @model_validator(mode="after")
    def _limits_in_order(self) -> PistonOperator:
        limits_in_order(operator_limits(lambda key: getattr(self, key.split(".")[1], None)), grip=False)
        return self


class Flywheel(Section):
    inertia: float | None = optional("inertia on the crank shaft [kg m^2]", gt=0, le=1000)
    mass: float | None = optional("wheel mass [kg] (a rim)", gt=0, le=1000)
    radius: float | None = optional("wheel radius [m] (with mass)", ge=0.01, le=5)

    @model_validator(mode="after")
    def _one(self) -> Flywheel:
        if (self.inertia is None) == (self.mass is None):
            raise ValueError("give either wheel.inertia [kg m^2] or wheel.mass [kg] with wheel.radius [m]")
        if self.mass is not None and self.radius is None:
            raise ValueError("wheel.mass needs wheel.radius [m] (the wheel is taken as a rim: J = m r^2)")
        return self


class PistonSpec(Section):
    name: str = Field(default="piston pump", min_length=1, max_length=200, description="design name")
    mechanism: Literal["crank-slider"] = Field(description="the mechanism kind: crank-slider")
    piston: Piston
    crank_slider: CrankSlider
    operator: PistonOperator
    wheel: Flywheel | None = None
    use: Use = Use()

    @property
    def values(self) -> dict[str, Any]:
        """The spec's values by dotted key (:func:`pumplink.inputs.pump.spec_values`)."""
        return spec_values(self)

    @property
    def gives_inertia(self) -> bool:
        """True when the spec gives a flywheel on the crank shaft (the flywheel model decides)."""
        return self.wheel is not None

    @property
    def inertia(self) -> float | None:
        """J on the crank shaft [kg m^2] (:func:`pumplink.models.load.rim_inertia`), or None."""
        w = self.wheel
        return None if w is None else _load.rim_inertia(w.inertia, w.mass, w.radius)

    @property
    def load_force(self) -> float:
        """Piston force on the working stroke [N] (docs/piston-pump.md, Eq. P.1)."""
        p = self.piston
        return float(_load.piston_load_force(p.bore, p.head, p.efficiency))


# ----------------------------------------------------------------------------- reading
def parse_piston(data: Any, source: str = "spec") -> PistonSpec:
    """Validate a piston-pump mapping; one sentence per problem naming the key (SpecError)."""
    return validate(PistonSpec, data, source)


def load_piston(path: str | Path) -> PistonSpec:
    """Read and validate a piston-pump spec file; the name defaults to the file stem."""
    return parse_piston(spec_name(read_toml(path), path), source=str(path))

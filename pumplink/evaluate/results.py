"""What the evaluation fills: every quantity of the verdict and of its views, as arrays over
designs (SI units, radians), built by keyword by the stages of :mod:`pumplink.evaluate.stages`.
A field a stage did not fill (it was not asked for) is None."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from pumplink.evaluate.designs import PistonDesigns, PumpDesigns
from pumplink.evaluate.service import Service
from pumplink.evaluate.water import Water
from pumplink.models import ORDER
from pumplink.verdict import Verdict


@dataclass(frozen=True, kw_only=True)
class Evaluation:
    """Every quantity the verdict and the renderers need, for rope-pump designs (arrays over
    designs; SI units, radians).  Filled by the stages named in brackets
    (:data:`pumplink.evaluate.stages.STAGES`); None where that stage did not run.

    Attributes
    ----------
    designs : the input columns.
    synthesis : the dead-centre synthesis (Eq. 1-2 of the pump paper) [geometry].
    feasible : a crank-rocker with the requested swing exists [geometry].
    handle, rocker : the handle and rocker lengths as designed or built [m] [geometry].
    stroke : horizontal grip stroke [m];  grip_height : (lowest, highest) or None [geometry].
    mean_force : F_mean = π Mw / S [N] (docs/physics.md §4) [mean_force].
    model_index : 0 quasi-static, 1 flywheel, 2 full dynamics (:data:`pumplink.models.ORDER`);
        energy : the energy-model choice and its solved force (None without any inertia);
        least_peak_force : the energy model's least peak force [N] (NaN where none decides);
        masses : the links' masses and, where the verdict takes them, the arms' [kg] [model].
    dead_band_peak_force, dead_band_peak_angle : the quasi-static peak outside the dead bands [N]
        and where [rad], for every feasible design [dead_band_peak].
    peak_force : the peak force that decides the verdict [N] [peak].
    sampled_peak : the peak over a uniform sweep of ``samples`` crank angles outside the dead
        bands [N] [sampled_peak].
    min_passing_speed : the flywheel's slowest passing speed [rad/s] (NaN where it does not
        decide) [passing_speed].
    effort_peak_force : least peak effort, the hand force plus the arms (full dynamics) [N] [effort].
    power : Mw ω̄ [W];  rocker_rate : max|dθ4/dθ2| [-];  grip_speed : the grip's peak speed at the
        wheel's top speed [m/s];  link_energy_share : the flywheel's neglected link energy / its
        band [%] (0 where the flywheel does not decide; None where it decides nowhere);
        cadence : wheel turns a minute [1/min];  rope_speed : ω̄ r_w [m/s] [motion];
        rocker_rate from [geometry].
    water : :class:`pumplink.evaluate.water.Water` [water].
    pin_pressure [MPa], handle_fatigue, crank_fatigue [-] : the part checks' values (NaN where not
        judged) [parts].
    service : :class:`pumplink.evaluate.service.Service`: the kick-back, the ratchet's torque, the
        pins' life, the field's checks [service].
    verdict : :func:`pumplink.verdict.assess` [verdict].
    """

    designs: PumpDesigns
    synthesis: Any = None
    feasible: np.ndarray | None = None
    handle: np.ndarray | None = None
    rocker: np.ndarray | None = None
    stroke: np.ndarray | None = None
    grip_height: tuple[np.ndarray, np.ndarray] | None = None
    mean_force: np.ndarray | None = None
    model_index: np.ndarray | None = None
    energy: Any = None
    least_peak_force: np.ndarray | None = None
    masses: Any = None
    dead_band_peak_force: np.ndarray | None = None
    dead_band_peak_angle: np.ndarray | None = None
    peak_force: np.ndarray | None = None
    sampled_peak: np.ndarray | None = None
    min_passing_speed: np.ndarray | None = None
    effort_peak_force: np.ndarray | None = None
    power: np.ndarray | None = None
    rocker_rate: np.ndarray | None = None
    grip_speed: np.ndarray | None = None
    link_energy_share: np.ndarray | None = None
    cadence: np.ndarray | None = None
    rope_speed: np.ndarray | None = None
    water: Water | None = None
    pin_pressure: np.ndarray | None = None
    handle_fatigue: np.ndarray | None = None
    crank_fatigue: np.ndarray | None = None
    service: Service | None = None
    verdict: Verdict | None = None

    def __len__(self) -> int:
        return int(np.size(self.feasible))

    @property
    def energy_decides(self) -> np.ndarray:
        """True where an energy model (the flywheel or full dynamics) decides."""
        return self.model_index > 0

    @property
    def model(self) -> np.ndarray:
        """The deciding model's key per design (:data:`pumplink.models.ORDER`)."""
        return np.asarray(ORDER, dtype=object)[self.model_index]

    @property
    def transmission_angle(self) -> np.ndarray:
        """The effective smallest transmission angle min(γmin, 180° − γmax) [rad]."""
        syn = self.synthesis
        return np.minimum(syn.transmission_min, np.pi - np.asarray(syn.transmission_max))

    @property
    def energy_band(self) -> np.ndarray:
        """W = J ω̄² δ [J] (NaN without inertia)."""
        return np.full(len(self), np.nan) if self.energy is None else self.energy.band

    @property
    def inertia(self) -> np.ndarray:
        """J about the axle [kg m^2] (NaN where the design gives none)."""
        return np.broadcast_to(np.asarray(self.designs.inertia, float), (len(self),))

    @property
    def energy_speed_fluctuation(self) -> np.ndarray:
        """The speed fluctuation δ an energy model allows [-] (NaN without the wheel's inertia)."""
        return np.where(np.isnan(self.inertia), np.nan, self.designs.speed_fluctuation)


@dataclass(frozen=True, kw_only=True)
class PistonEvaluation:
    """Every quantity the verdict and the renderers need, for piston pumps (arrays over designs;
    docs/piston-pump.md)."""

    designs: PistonDesigns
    feasible: np.ndarray  # the crank turns fully: rod > crank + |offset|
    stroke: np.ndarray  # [m]
    time_ratio: np.ndarray  # [-]
    largest_pressure_angle: np.ndarray  # [rad]
    mean_force: np.ndarray  # [N] (Eq. P.3)
    quasi_static_peak: np.ndarray  # [N]
    quasi_static_peak_angle: np.ndarray  # [rad]
    model_index: np.ndarray  # 0 quasi-static, 1 flywheel
    energy_band: np.ndarray  # W = J ω² δ [J] (NaN without a flywheel)
    least_peak_force: np.ndarray  # the flywheel's Fp* [N] (Eq. P.4; NaN without one)
    power: np.ndarray  # F_load H ω / 2π [W]
    verdict: Verdict | None = None
    water: Water | None = None

    def __len__(self) -> int:
        return int(np.size(self.feasible))

    @property
    def peak_force(self) -> np.ndarray:
        """The peak force that decides the verdict [N]."""
        return np.where(self.model_index > 0, self.least_peak_force, self.quasi_static_peak)

    @property
    def model(self) -> np.ndarray:
        return np.asarray(ORDER, dtype=object)[self.model_index]

"""Physical constants, product defaults and the verdict's limits, each with its source.

Sources are named in docs/references.md; the physics that uses them is in docs/physics.md and
docs/models.md.
"""

from __future__ import annotations

import math

#: Gravity [m/s^2].
GRAVITY = 9.81
#: Density of water [kg/m^3] (docs/physics.md §5).
WATER_DENSITY = 1000.0
#: Force (mechanical) efficiency of the pump used with load.head and load.pipe_diameter when the
#: spec gives none [-]: the rope force is rho g head (pi d^2/4) / efficiency (docs/physics.md §5).
#: It covers friction only; leakage past the pistons costs flow, not force, and is the volumetric
#: efficiency below.  Overall efficiency = force x volumetric = 0.75 x 0.87 = 0.65, the field's
#: "typically 65 %" (Akvopedia, "Rope pump"; docs/water.md §2).
DEFAULT_EFFICIENCY = 0.75
#: Volumetric efficiency of a rope or piston pump when the spec gives none [-]: delivered flow over
#: the swept flow (pipe area x rope speed).  No published measurement was found; 0.87 is the
#: field's overall 65 % divided by the force efficiency 0.75 (docs/water.md §2).
DEFAULT_VOLUMETRIC_EFFICIENCY = 0.87
#: Water per person per day for basic access [l]: WHO, "Domestic water quantity, service level
#: and health" (Howard & Bartram 2003), about 20 l within 1 km / 30 min (docs/water.md §5).
DEFAULT_LITRES_PER_PERSON_DAY = 20.0
#: Hours a day a community hand pump is in use [h]: the Sphere Handbook's maximum numbers of people
#: per water source assume the water point is accessible about eight hours a day (docs/water.md §5).
DEFAULT_DAILY_PUMPING_HOURS = 8.0

#: Largest acceptable operator force [N]: UK HSE push/pull guidance, about 100 N for men to keep
#: a load moving (docs/models.md §4).
FORCE_LIMIT_N = 100.0
#: Sustained human power for hours [W] (human-power literature, docs/physics.md §5): above it
#: the verdict warns.
SUSTAINED_POWER_W = 75.0
#: Human power for about an hour, upper end [W] (the same literature: 50-150 W for an hour): above
#: it no operator keeps the pump going and the design fails (docs/models.md §4).
HOUR_POWER_W = 150.0
#: Smallest transmission angle [deg]: the lever-mechanism textbook's permissible pressure angle of
#: 40-45 deg for a rotating driven link (the crank), i.e. transmission within 45..135 deg.
MIN_TRANSMISSION_DEG = 45.0
#: Transmission angle below which the design fails [deg]: a pressure angle above 60 deg, beyond
#: the largest of the lever-mechanism textbook's permissible 45-60 deg for linkages with only
#: turning pairs; at 30 deg the coupler already carries twice the handle's tangential force, and
#: joint friction grows with it until the linkage jams (docs/models.md §4).
FAIL_TRANSMISSION_DEG = 30.0
#: Peak grip speed above which the verdict warns [m/s]: trained rowers' handle speed in the
#: drive, about 2.5 m/s, kept up for minutes, not hours (docs/models.md §4).
GRIP_SPEED_WARN_M_S = 2.5
#: Peak grip speed above which the design fails [m/s]: on a 1-1.4 m stroke the grip then
#: accelerates at ~2 v^2 / stroke >= 23 m/s^2, and ~5 kg of hands and forearms need more than the
#: 100 N force limit just to follow it (docs/models.md §4).
GRIP_SPEED_FAIL_M_S = 4.0
#: Grip height above the ground over the swing [m], checked (warn) when the axle height is known:
#: the men's profile (pumplink.profiles.MEN), hands between knuckle and shoulder height as UK HSE's
#: push/pull guideline figures assume, for British men from the 5th to the 95th percentile of
#: stature (docs/operators.md §3).  Each profile has its own; this is the default's.
GRIP_HEIGHT_RANGE_M = (0.90, 1.33)
#: Longest comfortable horizontal grip stroke [m]: the pump paper's prototype (Delta theta = 60 deg,
#: H = 1 m) has 1.0 m; a longer stroke makes a standing operator step or lean (warn).
STROKE_LIMIT_M = 1.0
#: Largest kick-back of a hand crank or lever under load, measured at the grip [m]: DGUV
#: Vorschrift 54 (Winden, Hub- und Zuggeräte) § 6 Nr. 1 and its implementing note (docs/workshop.md §3).
KICK_BACK_LIMIT_M = 0.15
#: The torque ``size`` rates a ``[ratchet]`` for, as a multiple of the water column's it must hold:
#: the links' weight and the pawl's impact when it catches come on top of the column's static
#: torque (docs/workshop.md §3). A service factor of 2 is pumplink's choice, not a sourced figure.
RATCHET_SERVICE_FACTOR = 2.0
#: How a run back after letting go ends (pumplink.models.kickback): the column is empty, the
#: ratchet's pawl catches, the wheel stops again (the links' weight), the march's limit, or a
#: ratchet with no play holds the column at once.
KICK_BACK_ENDS = ("column empty", "pawl", "stops", "limit", "held")
#: Wheel-axle height range of the pump paper [m] (axle 40-70 cm above the ground).
AXLE_HEIGHT_RANGE_M = (0.40, 0.70)
#: Rope speed range [m/s] outside which the verdict warns: around the best rope speed of about
#: 1.2 m/s that the mawama model equations give (Akvopedia, "Rope pump"), as far as each loss share
#: of docs/water.md §2a stays within about twice its value there: leakage as about 1/v (1.95 times at
#: 0.6 m/s), friction in the rising main as v^1.75 (twice at 1.2 x 2^(4/7) = 1.78 m/s, to 1.8).
ROPE_SPEED_RANGE_M_S = (0.6, 1.8)
#: The share by which the constant efficiencies may change a design's flow or force before the loss
#: model decides instead (docs/water.md §2a): a third of the 15 % within which `pumplink validate`
#: holds the published discharges.
LOSS_SHARE = 0.05

#: Coefficient of speed fluctuation used unless the spec says otherwise: 0.2, the loosest class of
#: the machine-design tables (crushers, hammers, punch presses: Shigley's "Mechanical Engineering
#: Design", Table 16-6; Machinery's Handbook, Cf).  A hand-driven rope pump has no machine to
#: protect from speed ripple; what limits delta is that the operator must follow the handle.
DEFAULT_SPEED_FLUCTUATION = 0.2
#: Mass per metre [kg/m] of the steel tube the link-energy estimate assumes: 3/4" medium steel
#: tube (EN 10255, 26.9 x 2.6 mm), 7850 kg/m^3 * pi/4 (26.9^2 - 21.7^2) mm^2.
LINK_MASS_PER_METRE = 7850.0 * math.pi / 4.0 * (26.9e-3**2 - 21.7e-3**2)
#: Link kinetic energy (or handle weight), as a fraction of the energy band, above which the
#: flywheel model stops being enough (docs/models.md §3).
LINK_ENERGY_LIMIT = 0.1

#: Mass of the operator's arms that moves with the grip [kg], as one point mass at the grip: both
#: hands (0.006 of body mass each), both forearms (0.016) and half of both upper arms (0.028, whose
#: shoulder end is nearly still), i.e. 0.072 of body mass (segment masses from Winter, "Biomechanics
#: and Motor Control of Human Movement", Table 4.1), for a 60 kg adult: 4.32 kg.
ARM_MASS_FRACTION = 2.0 * (0.006 + 0.016 + 0.5 * 0.028)
ARM_BODY_MASS_KG = 60.0
DEFAULT_ARM_MASS = ARM_MASS_FRACTION * ARM_BODY_MASS_KG
#: Permissible largest pressure angle [deg], (preferred, acceptable for preliminary design), of the
#: lever-mechanism textbook (§2.4): 30-45 deg where the driven link slides (a prismatic pair), 45-60
#: deg for mechanisms with revolute pairs only (docs/mechanisms.md §4).
PERMISSIBLE_PRESSURE_SLIDING_DEG = (30.0, 45.0)
PERMISSIBLE_PRESSURE_REVOLUTE_DEG = (45.0, 60.0)

#: The words of each force model in reports, by its key (``pumplink.models.ORDER``).
MODEL_WORDS = {
    "quasi-static": "quasi-static + dead band",
    "flywheel": "flywheel",
    "dynamics": "full dynamics",
}

#: Kinds of crank position the method comparison samples (``pumplink methods``; the keys of its
#: JSON): a uniform sweep, near and exactly at a dead centre, and the positions where a textbook
#: formula breaks down (docs/physics.md §3).
UNIFORM = "uniform"
NEAR_DEAD_CENTRE = "near_dead_centre"
DEAD_CENTRE = "dead_centre"
CRANK_PERPENDICULAR = "crank_perpendicular"
ROCKER_PERPENDICULAR = "rocker_perpendicular"
CRANK_PARALLEL_ROCKER = "crank_parallel_rocker"
CRANK_ALONG_FRAME = "crank_along_frame"
#: Every danger point together (and 1e-9 rad either side), a sample set of the comparison.
DANGER = "danger_points"

# The tolerances of the iterative methods whose figures are printed: the method stops at them, and
# the output layer rounds what it prints to the digits they determine (pumplink/output/precision.py).
#: The best cadence is located to this share of the speed (a bounded Brent search,
#: pumplink.models.dynamics.best_speed); what is read there carries the same digits.
CADENCE_RTOL = 1e-7
#: The ends of the passing mean speeds are located to this share of the best speed (brentq,
#: pumplink.models.dynamics.speed_range).
PASSING_SPEED_RTOL = 1e-9
#: Relative precision of a refined extremum's argument (a peak force's crank angle): the function is
#: flat to first order there, so its values (known to eps) settle the argument to about sqrt(eps).
EXTREMUM_ARGUMENT = 2.0**-26
#: Relative tolerance of the released handle's integration in time (pumplink.models.release).
RELEASE_RTOL = 1e-10
#: The released handle's figures are settled to this share (its integration's global error;
#: measured against RELEASE_RTOL / 1000 on the shipped energy-model specs: at most 7e-9, for the
#: time of the grip's peak speed, the argument of a maximum).
RELEASE_SETTLED = 100 * RELEASE_RTOL

"""The evaluation's service stage: safe to let go, how long the pins last, what a mechanic checks
at the well (docs/workshop.md §3 and §5, docs/water.md §5).

:class:`Service` is the group of these quantities (arrays over designs, NaN where a design gives
no head and pipe, no ``[parts]`` or no ``[ratchet]``); :func:`service` fills it from the design
columns and what the geometry, model, water and parts stages filled, with the kernels of
:mod:`pumplink.models.kickback`, :mod:`pumplink.models.release` and :mod:`pumplink.models.wear`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.evaluate.water import one_design
from pumplink.mechanisms.angles import TWO_PI
from pumplink.models import release as _release
from pumplink.models import wear as _wear


@dataclass(frozen=True)
class Service:
    """Safe to let go, the pins' life, the field's checks (arrays over designs; SI units).

    kick_back : the grip's travel back when the handle is let go at the worst moment [m], with the
        ``[ratchet]`` where it holds the column (docs/workshop.md §3); kick_back_stop_angle [rad],
        kick_back_run [rad], kick_back_end (index into :data:`pumplink.models.kickback.ENDS`),
        kick_back_grid (True: the largest on a grid of stop angles);  kick_back_free : the same
        without a back-stop [m] (the travel a ratchet must stop; computed for a single design only,
        NaN over many where a ratchet holds: the words of force and the report use it).
    holding_torque_required : the column's torque rho g head (pi d^2/4) rw [N m] a back-stop must
        hold;  holding_torque : the ``[ratchet]``'s [N m] (NaN: none);  holding_torque_margin : their
        difference [N m];  ratchet_teeth : [-] (NaN: none).
    turns_per_day, turns_per_year : crank turns of the use [-];  years_to_endurance : years to
        6 million turns [a];  endurance_hours : hours to 6 million turns at the design cadence [h].
    pin_wear : the play the worst pin opens in 6 million turns [m];  pin_life_turns : turns until it
        reaches ``wear_allowance`` [m];  pin_life_years [a] (NaN without ``[parts]``).
    column_fill_turns [-], column_fill_time [s] : from an empty rising main until water reaches
        the spout.
    """

    kick_back: np.ndarray
    kick_back_stop_angle: np.ndarray
    kick_back_run: np.ndarray
    kick_back_end: np.ndarray
    kick_back_grid: np.ndarray
    kick_back_free: np.ndarray
    holding_torque_required: np.ndarray
    holding_torque: np.ndarray
    holding_torque_margin: np.ndarray
    ratchet_teeth: np.ndarray
    turns_per_day: np.ndarray
    turns_per_year: np.ndarray
    years_to_endurance: np.ndarray
    endurance_hours: np.ndarray
    pin_wear: np.ndarray
    pin_life_turns: np.ndarray
    pin_life_years: np.ndarray
    wear_allowance: np.ndarray
    column_fill_turns: np.ndarray
    column_fill_time: np.ndarray

    def design(self, i: int) -> Service:
        """The quantities of design ``i`` alone (floats)."""
        return Service(**one_design(self, i, np.shape(self.kick_back)))


#: The design columns :func:`service` reads (the handle's length is not among them: the
#: kick-back, which needs the linkage, comes in worked out, :func:`pumplink.models.kickback.kick_back`).
SERVICE_KEYS = ("head", "wheel_radius", "speed", "ratchet_torque", "ratchet_teeth",
                "hours_per_day", "people", "litres_per_person_day", "wear_rate", "wear_surfaces",
                "wear_allowance", "volumetric_efficiency")  # fmt: skip


def pawl_windows(head, pipe_diameter, wheel_radius, ratchet_torque, ratchet_teeth) -> tuple:
    """The water column's torque a back-stop must hold, ρ g H (π d²/4) r_w [N m], and the pawl's
    window 2π / teeth [rad] of a ``[ratchet]`` whose torque [N m] holds it (0 with no play; NaN
    where none holds it) (docs/workshop.md §3)."""
    required = _release.column_torque(head, pipe_diameter, wheel_radius)
    holds = ratchet_torque >= required
    with np.errstate(divide="ignore"):
        return required, np.where(holds, np.where(ratchet_teeth > 0, TWO_PI / ratchet_teeth, 0.0), np.nan)


def service(columns: dict, n: int, required, kick, flow, pin_pressure, pin_diameter) -> Service:
    """:class:`Service` of ``n`` designs from their ``columns`` (:data:`SERVICE_KEYS`), the
    column's torque a back-stop must hold, ``required`` [N m] (:func:`pawl_windows`), the
    ``kick`` of :func:`pumplink.models.kickback.kick_back` over them (travel, stop angle, run,
    end, grid and the travel without a back-stop; NaN where not worked out), the ``flow``
    [m^3/s] and the part checks' largest ``pin_pressure`` [MPa] on pins of ``pin_diameter`` [m]
    (None without ``[parts]``)."""
    c = columns
    declared, teeth = c["ratchet_torque"], c["ratchet_teeth"]
    travel, angle, run, end, grid, free = kick
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # a speed near 0: inf, NaN
        per_turn = flow * TWO_PI / c["speed"]  # the water a crank turn delivers [m^3]
        day = _wear.turns_per_day(
            c["speed"], c["hours_per_day"], c["people"], c["litres_per_person_day"], per_turn
        )
        year = day * _wear.DAYS_PER_YEAR
        wear = life = np.nan
        if pin_pressure is not None:
            per = _wear.wear_per_turn(np.asarray(pin_pressure, float) * 1e6, pin_diameter, c["wear_rate"],
                                      c["wear_surfaces"])  # fmt: skip
            wear = per * _wear.ENDURANCE_TURNS
            life = c["wear_allowance"] / per
        fill = _wear.column_fill_turns(c["head"], c["wheel_radius"], c["volumetric_efficiency"])
        return Service(
            kick_back=travel,
            kick_back_stop_angle=angle,
            kick_back_run=run,
            kick_back_end=end,
            kick_back_grid=grid,
            kick_back_free=free,
            holding_torque_required=required,
            holding_torque=declared,
            holding_torque_margin=declared - required,
            ratchet_teeth=teeth,
            turns_per_day=day,
            turns_per_year=year,
            years_to_endurance=_wear.ENDURANCE_TURNS / year,
            endurance_hours=_wear.ENDURANCE_TURNS / (c["speed"] / TWO_PI) / 3600.0,
            pin_wear=np.broadcast_to(wear, (n,)),
            pin_life_turns=np.broadcast_to(life, (n,)),
            pin_life_years=np.broadcast_to(life, (n,)) / year,
            wear_allowance=c["wear_allowance"],
            column_fill_turns=fill,
            column_fill_time=fill * TWO_PI / c["speed"],
        )


def pin_life(pressure, pin_diameter, bush: str, allowance, turns_per_year) -> tuple:
    """The pins' life at a largest bearing ``pressure`` [Pa] on pins of ``pin_diameter`` [m]
    turning in a ``bush`` (:data:`pumplink.models.wear.PAIRS`): (the play opened in 6 million turns
    [m], the turns until ``allowance`` [m] is worn, and the years that take at ``turns_per_year``)."""
    rate, surfaces = _wear.wear_rate(bush)
    per = _wear.wear_per_turn(pressure, pin_diameter, rate, surfaces)
    turns = allowance / per
    return per * _wear.ENDURANCE_TURNS, turns, turns / turns_per_year

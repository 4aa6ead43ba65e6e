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
from pumplink.models import Masses
from pumplink.models import kickback as _kickback
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


def service(columns: dict, n: int, synthesis, feasible, masses, flow, pin_pressure, pin_diameter,
            rocker_rate=None, kick: bool = True) -> Service:  # fmt: skip
    """:class:`Service` of ``n`` designs from their ``columns``, the synthesis and its
    ``feasible`` designs, the links' ``masses``, the ``flow`` [m^3/s] and the part checks' largest
    ``pin_pressure`` [MPa] on pins of ``pin_diameter`` [m] (None without ``[parts]``);  ``kick``
    False: the kick-back is not computed (NaN; a fitted evaluation does not judge it)."""
    c = columns
    nan = np.full(n, np.nan)
    head, pipe, rw = c["head"], c["pipe_diameter"], c["wheel_radius"]
    required = _release.column_torque(head, pipe, rw)
    declared = c["ratchet_torque"]
    holds = declared >= required
    teeth = c["ratchet_teeth"]
    with np.errstate(divide="ignore"):
        pawl = np.where(holds, np.where(teeth > 0, TWO_PI / teeth, 0.0), np.nan)
    travel, angle, run, end, grid = nan.copy(), nan.copy(), nan.copy(), nan.copy(), np.zeros(n, bool)
    free = nan.copy()
    ok = np.nonzero(np.asarray(feasible, bool) & np.isfinite(required) & kick)[0]

    def kick_back(i, stop):
        links = Masses(
            *(np.broadcast_to(np.asarray(m, float), (n,))[i] for m in (masses.coupler, masses.handle))
        )
        return _kickback.kick_back(
            synthesis.linkage.take(i), synthesis.dead_centre_extended[i], synthesis.dead_centre_folded[i],
            links, required[i], head[i], rw[i], c["inertia"][i], _release.column_inertia(head, pipe, rw)[i],
            stop, rocker_rate=None if rocker_rate is None else np.asarray(rocker_rate, float)[i],
        )  # fmt: skip

    if ok.size:
        kb = kick_back(ok, pawl[ok])
        travel[ok], angle[ok], run[ok], end[ok], grid[ok] = (
            kb.travel,
            kb.stop_angle,
            kb.run,
            kb.end,
            kb.marched_all,
        )
        free[ok] = travel[ok]
        # without the ratchet that holds: how far it would go, for one design's words (force, the
        # report); over many designs (a batch, which has no column for it) not computed: NaN
        held = ok[np.isfinite(pawl[ok])]
        free[held] = kick_back(held, None).travel if n == 1 and held.size else np.nan
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):  # a speed near 0: inf, NaN
        per_turn = flow * TWO_PI / c["speed"]  # the water a crank turn delivers [m^3]
        day = _wear.turns_per_day(
            c["speed"], c["hours_per_day"], c["people"], c["litres_per_person_day"], per_turn
        )
        year = day * _wear.DAYS_PER_YEAR
        wear = life = nan
        if pin_pressure is not None:
            per = _wear.wear_per_turn(np.asarray(pin_pressure, float) * 1e6, pin_diameter, c["wear_rate"],
                                      c["wear_surfaces"])  # fmt: skip
            wear = per * _wear.ENDURANCE_TURNS
            life = c["wear_allowance"] / per
        fill = _wear.column_fill_turns(head, rw, c["volumetric_efficiency"])
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

"""The workshop's view of a design (``pumplink force --explain``, the report): the loads on the pins,
the crank and the handle, what they mean for the parts, and the released handle.

Renderers only render: every number comes from :func:`pumplink.studies.workshop.workshop`.
"""

from __future__ import annotations

import math
import sys
from typing import TYPE_CHECKING, Any

from pumplink.constants import KICK_BACK_ENDS, KICK_BACK_LIMIT_M, MODEL_WORDS, RELEASE_SETTLED
from pumplink.output.formats import console, deg, num, report_table
from pumplink.output.precision import known_to

if TYPE_CHECKING:
    from pumplink.studies.workshop import Workshop

#: The joints' words, in the order of the loads (pumplink.models.joints.JOINTS).
JOINT_WORDS = {
    "axle": "axle O2 (with the rope and the wheel)",
    "crank_pin": "crank pin A",
    "coupler_pin": "coupler-rocker pin B",
    "rocker_pivot": "rocker pivot O4",
}
JOINTS = tuple(JOINT_WORDS)


def workshop_row(w: Workshop | None) -> dict[str, Any] | None:
    """The JSON of the workshop's view (None where it has none: an infeasible design)."""
    if w is None:
        return None
    pk = w.loads.peaks
    st = w.strength
    p = w.parts
    out = {
        "joints": [
            {"joint": j, "peak_force_N": num(f), "crank_deg": deg(a)}
            for j, f, a in zip(JOINTS, pk.force, pk.angle)
        ],
        "crank_moment_Nm": {"peak": num(pk.crank_moment[0]), "crank_deg": deg(pk.crank_moment[1])},
        "handle_moment_Nm": {"peak": num(pk.handle_moment[0]), "crank_deg": deg(pk.handle_moment[1])},
        "parts": {
            "from_spec": w.parts_given,
            "pin_diameter_m": p.pin_diameter,
            "pin_width_m": p.pin_width,
            "handle_diameter_m": p.handle_diameter,
            "handle_wall_m": p.handle_wall,
            "handle_notch": p.handle_notch,
            "crank_diameter_m": p.crank_diameter,
            "crank_notch": p.crank_notch,
        },
        "pin_pressure_MPa": num(st.pin_pressure / 1e6),
        "pin_pressure_at": st.pin,
        "handle_fatigue_safety": num(st.handle.safety),
        "crank_fatigue_safety": num(st.crank.safety),
        "pin_life": pin_life_row(w.life),
        "release": release_row(None if w.release is None else (w.release, w.release_free)),
    }
    return out


def pin_life_row(life) -> dict[str, Any] | None:
    """The JSON of the pins' life (:class:`pumplink.studies.workshop.PinLife`, or None)."""
    if life is None:
        return None
    return {
        "bush": life.bush,
        "wear_allowance_mm": num(life.allowance * 1000.0),
        "wear_6m_turns_mm": num(life.wear * 1000.0),
        "life_turns": num(life.turns),
        "life_years": num(life.years),
        "turns_per_day": num(life.turns_per_day),
    }


def release_row(both) -> dict[str, Any] | None:
    """The JSON of the released handle (``both``: with and without losses, or None)."""
    if both is None:
        return None
    r, f = both

    def known(x):  # an integration in time: to its global error (pumplink.output.precision)
        return known_to(x, RELEASE_SETTLED)

    stopped = r.reverses or not r.stopped_early  # (stopped early still turning forward: not known)
    return {
        "needs_ratchet_or_brake": bool(r.reverses) if stopped else None,
        "stop_time_s": known(r.stop_time),
        "reverses": r.reverses if stopped else None,
        "grip_speed_1s_m_s": known(r.grip_speed_1s),
        "peak_grip_speed_m_s": known(r.peak_grip_speed),
        "peak_time_s": known(r.peak_time),
        "end": r.end_reason,
        "end_time_s": known(r.end_time),
        "stopped_early": r.stopped_early or f.stopped_early,
        "peak_grip_speed_without_losses_m_s": known(f.peak_grip_speed),
    }


def _early(r) -> str:
    """Why the released handle's simulation stopped with the wheel still turning, in words."""
    return {
        "horizon": f"its horizon of {r.end_time:g} s",
        "step limit": f"its limit of {r.max_steps:,} solver steps",
        "turn limit": f"its limit of {r.max_turned:,.0f} rad of crank",
    }[r.end_reason]


def _held(sv) -> bool:
    """The spec's ratchet holds the water column (``sv``: the design's Service)."""
    return bool(math.isfinite(sv.holding_torque) and sv.holding_torque >= sv.holding_torque_required)


def kick_back_words(sv) -> str | None:
    """The kick-back and the ratchet in one sentence (``sv``: one design's
    :class:`pumplink.evaluate.service.Service`), None without a water column."""
    if sv is None or not math.isfinite(sv.kick_back):
        return None
    rule = f"({KICK_BACK_LIMIT_M:g} m allowed, DGUV Vorschrift 54 § 6)"
    column = f"the water column's {sv.holding_torque_required:.1f} N·m"
    if _held(sv):
        catch = (
            "it holds at once"
            if sv.ratchet_teeth == 0
            else f"let go at the worst moment, the grip kicks back {sv.kick_back:.2f} m before its pawl "
            "catches"
        )
        return (
            f"released handle: the ratchet holds the water column ({sv.holding_torque:g} N·m for "
            f"{column}); {catch} {rule}; without it the grip would run back {sv.kick_back_free:,.1f} m"
        )
    weak = (
        f" (the ratchet's {sv.holding_torque:g} N·m does not hold it)"
        if math.isfinite(sv.holding_torque)
        else ""
    )
    ends = {
        "stops": "before the wheel stops again",
        "limit": "so far",
        "column empty": "before the column empties",
    }
    how = ends.get(KICK_BACK_ENDS[int(sv.kick_back_end)], "")
    return (
        f"released handle: NEEDS A RATCHET — let go at the worst moment, the water column drives the grip "
        f"back {sv.kick_back:,.1f} m {how} {rule}; a ratchet on the wheel's axle must hold {column}{weak}"
    )


def release_line(both, service=None) -> str | None:
    """The released handle in one line: the kick-back and the ratchet (``service``: the design's
    :class:`pumplink.evaluate.service.Service`, as the verdict's check reads them), then how the
    handle moves let go at full speed with its numbers, or None (``both``: with and without
    losses, as :func:`pumplink.studies.workshop.release` gives them).  A simulation that stopped
    with the wheel still turning says so (STOPPED EARLY) and why."""
    if both is None:
        return None
    head = kick_back_words(service)
    if head is not None and _held(service):
        return head
    r, free = both
    if head is not None:
        return head + "; " + _full_speed(r, free)
    return "released handle: " + _full_speed(r, free, needs=True)


def _full_speed(r, free, needs: bool = False) -> str:
    """The released handle let go at full speed (with the losses as friction, and without)."""
    bound = f"({free.peak_grip_speed:.1f} m/s if the pump had no losses)"
    if free.stopped_early and not r.stopped_early:  # (the other way round, r's words say it)
        bound = bound[:-1] + f", so far: that simulation STOPPED EARLY at {_early(free)})"
    if r.stopped_early and not r.reverses:
        return (
            f"STOPPED EARLY — let go at full speed, the simulation stopped at {_early(r)} with the wheel "
            f"still turning forward {r.end_time:.2f} s after the operator lets go, so whether the column "
            f"drives it back with the pump's losses as friction is not known; the grip's peak speed so "
            f"far {r.peak_grip_speed:.1f} m/s {bound}"
        )
    if not r.reverses:
        return (
            f"let go at full speed, the wheel stops in {r.stop_time:.2f} s and with all of the pump's losses "
            "counted as friction they would hold it there (friction is not relied on)"
        )
    one = (
        ""
        if not math.isfinite(r.grip_speed_1s)
        else f"1 s after letting go the grip moves at {r.grip_speed_1s:.1f} m/s, "
    )
    end = "empties" if r.end_reason == "column empty" else "stops"
    if r.stopped_early:
        end = f"empties: the simulation STOPPED EARLY at {_early(r)}, {r.end_time:.2f} s after letting go"
    lead = "NEEDS A RATCHET OR BRAKE — " if needs else ""
    return (
        f"{lead}let go at full speed, the wheel stops in "
        f"{r.stop_time:.2f} s and the water column drives it back; {one}and the grip reaches "
        f"{r.peak_grip_speed:.1f} m/s after {r.peak_time:.1f} s {bound} before the column {end}"
    )


def load_rows(w: Workshop) -> list[tuple[str, str, str]]:
    """The peak loads as (where, peak with its unit, crank angle) rows."""
    pk = w.loads.peaks
    rows = [
        (JOINT_WORDS[j], f"{f:.0f} N", f"{math.degrees(a):.1f}°")
        for j, f, a in zip(JOINTS, pk.force, pk.angle)
    ]
    for words, (value, angle) in (
        ("crank, bending at the axle", pk.crank_moment),
        ("handle, bending at pin B", pk.handle_moment),
    ):
        rows.append((words, f"{value:.1f} N·m", f"{math.degrees(angle):.1f}°"))
    return rows


def loads_title(w: Workshop) -> str:
    return f"Loads on the parts ({MODEL_WORDS[w.loads.model]}, the peak over a turn)"


def parts_sentence(w: Workshop) -> str:
    """What the loads mean for the parts, in one sentence."""
    st, p = w.strength, w.parts
    (pin_warn, pin_fail), (fatigue_warn, fatigue_fail) = w.pin_pressure_limits, w.fatigue_limits
    which = "the spec's [parts]" if w.parts_given else "the default parts (give [parts] to judge them)"
    return (
        f"with {which}: {p.pin_diameter * 1000:g} mm pins on {p.pin_width * 1000:g} mm of bore bear "
        f"{st.pin_pressure / 1e6:.1f} MPa at the {JOINT_WORDS[st.pin]} ({pin_warn / 1e6:g} MPa "
        f"allowed for a moving joint, {pin_fail / 1e6:g} MPa static); fatigue safety of the "
        f"{p.handle_diameter * 1000:g} x {p.handle_wall * 1000:g} mm handle tube {st.handle.safety:.2f} "
        f"(notch factor {p.handle_notch:g}), of the {p.crank_diameter * 1000:g} mm crank bar "
        f"{st.crank.safety:.2f} (notch factor {p.crank_notch:g}); below {fatigue_warn:g} warns, below "
        f"{fatigue_fail:g} fails (docs/workshop.md)"
    )


def pin_life_sentence(w: Workshop) -> str | None:
    """The pins' life in one sentence (docs/workshop.md §5), None where it is not known."""
    life = w.life
    if life is None or not math.isfinite(life.turns):
        return None
    pair = {"steel": "steel bushes (dry)", "polyethylene": "polyethylene bushes"}[life.bush]
    p = w.parts
    years = (
        f", {life.years:.2g} years at {life.turns_per_day:,.0f} turns a day"
        if math.isfinite(life.years)
        else ""
    )
    return (
        f"pin life: at {w.strength.pin_pressure / 1e6:.1f} MPa, {p.pin_diameter * 1000:g} mm pins in {pair} "
        f"open {life.wear * 1000:.3g} mm of play in 6 million turns (USAID's endurance tests); they wear the "
        f"{life.allowance * 1000:g} mm allowed in {life.turns / 1e6:.2g} million turns{years} "
        "(Archard's wear, docs/workshop.md §5)"
    )


def workshop_release_line(w: Workshop, service=None) -> str | None:
    return release_line(None if w.release is None else (w.release, w.release_free), service)


def render_workshop(w: Workshop | None, out=None, service=None) -> None:
    """The workshop's view as a table and sentences (after ``--explain``'s report)."""
    if w is None:
        return

    c = console(out or sys.stdout)
    t = report_table(loads_title(w))
    for h in ("where", "peak", "at crank"):
        t.add_column(h, justify="left" if h == "where" else "right")
    for row in load_rows(w):
        t.add_row(*row)
    c.print(t)
    c.print(parts_sentence(w), markup=False)
    life = pin_life_sentence(w)
    if life is not None:
        c.print(life, markup=False)
    line = workshop_release_line(w, service)
    if line is not None:
        c.print(line, markup=False)

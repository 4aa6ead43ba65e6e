"""Every figure printed beside a verdict agrees with the verdict, for every shipped spec and every
operator profile, and for the pumps ``pumplink size`` writes for each profile.

``pumplink force --explain`` (:func:`pumplink.studies.design.study`) prints, beside its verdict,
the speeds at which no check fails, the best cadence, the model-choice report's power limits
and, after a FAIL, the single changes that help most.  Each is checked here against the verdict of
``force`` itself (:func:`pumplink.studies.force.force_analysis`, the same as
``pumplink force --speed S --model M`` on the same or the changed spec):

* the speeds that pass: at each printed end the verdict passes, and one deg/s outside it fails
  (but at the ends of the speeds searched); the same without warnings;
* the best cadence, rounded to the whole deg/s it is printed as, passes (without a warning when
  some speed does);
* each advice line: ``force`` on the changed spec at the same speed and model gives its peak force
  and its verdict;
* the model-choice report's operator power is compared with the profile's own sustained power and
  quotes its hour power: the numbers of docs/operators.md's table (``pumplink.profiles``, data),
  not the men's.

The sized pumps (tests/data/sized-10m-*.toml) were written by ``pumplink size --head 10
--profile P --write`` (this checkout, seed 0), the accessible one with ``--allow-warnings``: with the
cadence held to 30-60 turns a minute no design at 10 m keeps a seated operator's grip below
1.1 m/s (size says so), and the warnings are what this test looks beside.  Each carries the
``[ratchet]`` size writes for a water column (``pumplink.studies.workshop.ratchet_needed``):
without it every speed fails the kick-back, and the passing speeds (judged fitted with it) would
not be the force command's.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from shipped import PROFILE_NAMES, ROPE_PUMP_SPECS, spec_id

from pumplink.inputs.pump import load_spec, parse_spec, spec_to_dict
from pumplink.profiles import PROFILES
from pumplink.studies.design import study
from pumplink.studies.force import force_analysis

DATA = Path(__file__).parent / "data"
SIZED = sorted(DATA.glob("sized-10m-*.toml"))
#: The operator keys a profile sets: dropped from the copy, so that the profile's own limits judge.
PROFILE_KEYS = ("force_limit", "sustained_power", "hour_power", "grip_height_min", "grip_height_max",
                "grip_speed_warn", "grip_speed_fail")  # fmt: skip


def with_profile(path: Path, profile: str | None):
    """The spec at ``path`` pumped by ``profile`` (None: as it is)."""
    spec = load_spec(path)
    if profile is None:
        return spec
    data = spec_to_dict(spec)
    op = {k: v for k, v in data["operator"].items() if k not in PROFILE_KEYS}
    data["operator"] = {**op, "profile": profile}
    return parse_spec(data, source=f"{path.name} ({profile})")


CASES = [pytest.param(p, q, id=f"{spec_id(p)}-{q}") for p in ROPE_PUMP_SPECS for q in PROFILE_NAMES]
CASES += [pytest.param(p, None, id=p.stem) for p in SIZED]
# advice at another speed and under another model than the spec's (well-12m: a FAIL everywhere)
WELL = next(p for p in ROPE_PUMP_SPECS if p.name == "well-12m-flywheel.toml")


def _force(spec, speed, model=None):
    return force_analysis(spec, speed, keep_samples=False, samples=0, model=model)


def _forced(r):
    return None if r.effects is None or not r.effects.forced else r.model_key


def _check_speeds(spec, st) -> None:
    c, model = st.cadence, _forced(st.result)
    lo_s, hi_s = (round(math.degrees(v)) for v in c.searched)
    for bands, strict in ((c.bands, False), (c.clean_bands, True)):
        for lo, hi in bands:
            lo, hi = round(math.degrees(lo)), round(math.degrees(hi))
            for v in {lo, hi}:  # each printed end passes
                assert _force(spec, v, model).passed_strict(strict), (v, strict)
            for v in (lo - 1,) * (lo > lo_s) + (hi + 1,) * (hi < hi_s):  # one deg/s outside fails
                assert not _force(spec, v, model).passed_strict(strict), (v, strict)
    if math.isfinite(c.speed):  # the best cadence, as printed, passes
        best = _force(spec, round(math.degrees(c.speed)), model)
        assert best.passed_strict(bool(c.clean_bands)), round(math.degrees(c.speed))


def _check_advice(spec, st) -> None:
    r = st.result
    for a in st.advice:
        data = spec_to_dict(spec)
        table, key = a.key.split(".")
        speed = r.speed_deg_s
        if a.key == "operator.speed":
            speed = a.new
        else:
            data[table][key] = a.new
        changed = _force(parse_spec(data), speed, _forced(r))
        assert changed.verdict_peak_force == pytest.approx(a.peak_force, rel=1e-12), a
        assert changed.outcome == a.outcome, a


def _check_explain(st, profile: str | None) -> None:
    p = PROFILES[profile or st.result.profile]
    spec_op = st.result.design.spec.operator
    sustained = p.sustained_power if spec_op.sustained_power is None else spec_op.sustained_power
    hour = p.hour_power if spec_op.hour_power is None else spec_op.hour_power
    power = next(e for e in st.effects if e.name.startswith("operator power"))
    assert f"of the {sustained:g} W" in power.compared_with and f"{hour:g} W" in power.note
    assert power.ratio == pytest.approx(st.result.power / sustained, rel=1e-15)


@pytest.mark.parametrize(("path", "profile"), CASES)
def test_figures_beside_the_verdict_agree_with_it(path, profile):
    spec = with_profile(path, profile)
    st = study(force_analysis(spec, keep_samples=False, samples=0), explain=True)
    if not st.result.design.feasible:
        return
    _check_explain(st, profile)
    assert (st.cadence is not None) == spec.gives_inertia  # --explain gives it wherever it can
    if st.cadence is not None:
        _check_speeds(spec, st)
    assert bool(st.advice) <= (not st.result.passed)  # advice only after a FAIL
    _check_advice(spec, st)


@pytest.mark.parametrize(("speed", "model"), [(540.0, None), (300.0, None), (None, "flywheel")])
def test_advice_is_judged_at_the_verdicts_speed_and_model(speed, model):
    """The issue's case: after --speed 540, --speed 300 and --model flywheel each advice line is
    what ``force`` says of the changed spec at that speed and model (it quoted the spec's own
    speed and the least model that is enough)."""
    spec = load_spec(WELL)
    st = study(force_analysis(spec, speed, keep_samples=False, samples=0, model=model))
    assert not st.result.passed and st.advice
    _check_advice(spec, st)
    assert st.cadence is not None and not st.cadence.bands  # no speed passes: the line says so

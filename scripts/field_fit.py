"""The filling duty's power per operator profile, fitted to the published discharges
(docs/water.md §6; the values pumplink/profiles.py holds).

For each profile with published figures (pumplink/field.py), the one power at which the
evaluation's filling flows come closest to them in the largest relative error (minimax: the
largest overshoot equals the largest shortfall), by bisection through the same evaluation as
``pumplink validate``; then the residuals at the power rounded to 1 W, the value the profile
holds.

    .venv/bin/python scripts/field_fit.py
"""

from __future__ import annotations

from pumplink.field import DISCHARGES
from pumplink.profiles import PROFILES
from pumplink.studies.validate import predict


def errors(profile: str, power: float) -> list[float]:
    """Each of the profile's discharges' relative error at this filling power."""
    return [predict(d, filling_power=power).error for d in DISCHARGES if d.profile == profile]


def minimax(profile: str, lo: float = 20.0, hi: float = 300.0) -> float:
    """The power whose largest overshoot equals its largest shortfall [W] (the errors grow with
    the power)."""
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        e = errors(profile, mid)
        if max(e) + min(e) > 0.0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def main() -> None:
    for profile in sorted({d.profile for d in DISCHARGES}):
        best = minimax(profile)
        held = PROFILES[profile].filling_power
        shown = ", ".join(f"{e:+.1%}" for e in errors(profile, round(best)))
        print(
            f"{profile}: fitted {best:.2f} W, rounded {round(best)} W (profiles.py holds {held:g} W); "
            f"residuals at {round(best)} W: {shown}"
        )


if __name__ == "__main__":
    main()

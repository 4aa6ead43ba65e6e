"""`pumplink slider`: crank-slider synthesis (the textbook's Tasks 1 and 2) or the analysis of a given
crank-slider, checked by simulation and judged."""

from __future__ import annotations

import typer

from pumplink.cli.common import Format, FormatOpt, app, optional
from pumplink.errors import SpecError


def _given(**options) -> list[str]:
    return [f"--{k.replace('_', '-')}" for k, v in options.items() if v is not None]


@app.command()
def slider(
    stroke: optional(float, "Slider stroke H (any length unit).", "--stroke", "-H") = None,
    rod_ratio: optional(float, "Rod ratio L = rod/crank > 1.", "--rod-ratio", "-L") = None,
    time_ratio: optional(
        float, "Time ratio K >= 1 (Task 2: the offset follows).", "--time-ratio", "-k"
    ) = None,
    offset_ratio: optional(
        float, "Offset ratio e/r (Task 1 only; default 0: a central crank-slider).", "--offset-ratio"
    ) = None,
    crank: optional(float, "Analysis: crank length r (any length unit).", "--crank") = None,
    rod: optional(float, "Analysis: rod (connecting-rod) length l.", "--rod") = None,
    offset: optional(
        float, "Analysis: offset e of the guide from the crank pivot (default 0).", "--offset"
    ) = None,
    fmt: FormatOpt = Format.table,
) -> None:
    """Crank-slider (piston drive): synthesis from the stroke, or analysis of given lengths.

    Synthesis, Task 1 (--stroke, --rod-ratio): crank r = H/h with h = 2 for a central
    crank-slider.  Task 2 (with --time-ratio): the offset crank-slider with time ratio K
    (docs/mechanisms.md §1).  Analysis (--crank, --rod and --offset): a given crank-slider.
    Prints the lengths, the stroke H, h = H/r, K, the angle θ between the extreme rod positions,
    the largest pressure angle and the dead-centre crank angles, each from its closed form and
    measured by running the mechanism through a full crank turn.  Verdict: the largest pressure
    angle warns above the textbook's 30° for a sliding driven link and fails above 60°; the
    simulation must reproduce every value.  Exit 0 on PASS or PASS with warnings, 1 on FAIL or if
    no crank-slider meets the task (K too large for L, rod not longer than crank + offset), 2 for
    bad input.

    Example: [bold]pumplink slider --stroke 0.1 --rod-ratio 4 --time-ratio 1.2[/]

    Example: [bold]pumplink slider --crank 0.1 --rod 0.4 --offset 0.02[/]
    """
    from pumplink.output.mechanisms import render_synthesis, synthesis_labels, synthesis_row
    from pumplink.studies import textbook as synthesis

    synth = _given(stroke=stroke, rod_ratio=rod_ratio, time_ratio=time_ratio, offset_ratio=offset_ratio)
    given = _given(crank=crank, rod=rod, offset=offset)
    if synth and given:
        raise SpecError(
            f"{', '.join(given)} (analysis of a given crank-slider) and {', '.join(synth)} (synthesis) "
            "cannot be mixed; give one set"
        )
    if given:
        if crank is None or rod is None:
            raise SpecError("the analysis needs both --crank and --rod (--offset is optional, default 0)")
        rep = synthesis.slider_analysis(crank, rod, 0.0 if offset is None else offset)
    else:
        if stroke is None or rod_ratio is None:
            raise SpecError(
                "give --stroke and --rod-ratio (synthesis), or --crank and --rod (analysis of a given "
                "crank-slider)"
            )
        rep = synthesis.slider(stroke, rod_ratio, time_ratio, 0.0 if offset_ratio is None else offset_ratio)
    render_synthesis(synthesis_row(rep), synthesis_labels(rep), fmt.value)
    raise typer.Exit(0 if rep.passed else 1)

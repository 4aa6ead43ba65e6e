"""The field sheet: one A4 page (PDF) and a section of the report (HTML) (docs/water.md §5).

Renderers only render: every number comes from :func:`pumplink.studies.sheet.field_sheet`.
"""

from __future__ import annotations

import html
import math
import textwrap
from pathlib import Path

from pumplink.constants import KICK_BACK_LIMIT_M
from pumplink.errors import SpecError
from pumplink.output.formats import atomic_write, check_output

#: A4 portrait [inch], the margins [inch], the characters a line holds at the body's size.
A4 = (210 / 25.4, 297 / 25.4)
MARGIN = 0.6
BODY, HEAD, TITLE = 9.0, 11.0, 15.0
CHARS = 104


def _band(b, unit: str, digits: str = "{:.0f}") -> str:
    """'35' or '35 (34 to 36 over the builds)'."""
    text = digits.format(b.value) + unit
    if b.given:
        low, high = digits.format(b.p5), digits.format(b.p95)
        same = low == high == digits.format(b.value)
        text += " (every build the same)" if same else f" ({low} to {high}{unit} over the builds, 5-95 %)"
    return text


def sections(fs) -> list[tuple[str, list[str]]]:
    """The sheet's sections as (heading, paragraphs), shared by the PDF and the HTML."""
    rpm = fs.cadence_rpm
    per_turn = 60.0 / rpm
    builds = (
        f" The 5-95 % bands are those of {fs.builds:,} builds with every hole within "
        f"±{fs.tolerance * 1000:g} mm (pumplink tolerance): the holes change the force, not the flow."
        if fs.builds
        else ""
    )
    crank, coupler, rocker, handle = (x * 1000 for x in fs.lengths)
    pipe = f", a {fs.pipe * 1000:g} mm rising main" if math.isfinite(fs.pipe) else ""
    out = [
        (
            "The pump as built",
            [
                f"{fs.head:g} m of head{pipe}, a wheel of Ø{2 * fs.wheel_radius * 1000:.0f} mm. Hole "
                "centres: "
                f"crank {crank:.1f} mm, coupler {coupler:.1f} mm, rocker {rocker:.1f} mm; the grip "
                f"{handle:.0f} mm from the rocker's pivot (pumplink template).",
            ],
        ),
        (
            "1. The bucket test: fill a 20-litre container",
            [
                f"Turn the handle at the design cadence, {rpm:.0f} turns a minute (a turn every "
                f"{per_turn:.1f} s), and count the crank turns from the first water until a 20-litre "
                f"container is full. Expected: {_band(fs.fill_turns, ' turns')} in "
                f"{_band(fs.fill_time, ' s')}.{builds}",
                f"More than {fs.slow_turns:.0f} turns: the pistons leak (worn or undersized washers, "
                "a stretched rope, a cracked or loose rising main). The count of turns does not depend on "
                "the cadence; the time does.",
                f"The right turns but more than {fs.fill_time.value * 1.15:.0f} s: the cadence is below "
                f"{rpm:.0f} turns a minute.",
            ],
        ),
        (
            "2. Before water comes",
            [
                f"From an empty rising main (a pump left standing), water reaches the spout after "
                f"{fs.column_turns:.1f} turns ({fs.column_time:.0f} s at the cadence) lifting it "
                f"{fs.head:g} m. More than {fs.column_turns * 1.15:.1f} turns: the pistons leak.",
            ],
        ),
        (
            "3. The hand force",
            [
                f"At the grip: a peak of {_band(fs.peak_force, ' N')}, a mean of {fs.mean_force:.0f} N "
                f"(the operator's limit {fs.force_limit:g} N).",
                f"Harder than {fs.hard_force:.0f} N, or harder one way than the other: check the crank's and "
                "the coupler's hole centres against the template (a misdrilled crank hole moves the dead "
                "centres and the stroke), then dry pins or worn bushes, and pistons or a rope too tight in "
                "the pipe.",
            ],
        ),
        ("4. Letting go: the ratchet", [_ratchet(fs)]),
        (
            "5. Endurance test of a prototype",
            [
                f"Drive the crank on a rig (or the handle over its {fs.stroke:.2f} m stroke) at {rpm:.0f} "
                f"turns a minute, with the water column in place or a weight of {fs.rope_force:.0f} N "
                "on the rope.",
                f"Run 6 million turns (USAID's laboratory tests of hand pumps): {fs.endurance_hours:,.0f} h, "
                f"which is {fs.endurance_years:.2g} years of the use ({fs.turns_per_day:,.0f} turns a day).",
                "Every 100 h: measure the play at each pin"
                + (f" (replace pin and bush at {fs.pin_allowance * 1000:g} mm)"
                   if math.isfinite(fs.pin_allowance) else "")
                + ", look for cracks at the welds of the crank, the lug and the bush sleeves, and repeat "
                "the bucket test (1).",
            ],
        ),
        (
            "Record",
            [
                "Date ________  turns for 20 l ______  time ______ s  turns before water ______  "
                "push/pull feel ________  play at A / B / O4 ______ mm  ratchet catches ______",
            ],
        ),
    ]  # fmt: skip
    if not math.isfinite(fs.fill_turns.value):  # a rope force given: no head, no pipe, no flow
        no_flow = "No flow figure: the spec gives a rope force; give load.head and load.pipe_diameter."
        out = [
            ("The pump as built", [out[0][1][0].split(". ", 1)[1]]),
            ("1. The bucket test", [no_flow]),
            *out[3:],
        ]
    return out


def _ratchet(fs) -> str:
    rule = f"{KICK_BACK_LIMIT_M:g} m allowed, DGUV Vorschrift 54 § 6"
    if not math.isfinite(fs.kick_back):
        return "No water column (the spec gives a rope force): nothing drives the handle back."
    if math.isfinite(fs.holding_torque) and fs.holding_torque >= fs.holding_torque_required:
        catch = (
            "at once (no play)"
            if fs.ratchet_teeth == 0
            else f"within {fs.kick_back:.2f} m at the grip ({fs.ratchet_teeth:.0f} teeth; {rule})"
        )
        return (
            f"With water in the rising main, let go of the handle at mid-stroke: the ratchet must catch "
            f"{catch} and hold the column's {fs.holding_torque_required:.1f} N·m (it is rated "
            f"{fs.holding_torque:g} N·m)."
        )
    return (
        f"NO RATCHET that holds the column: let go, the water column drives the grip back "
        f"{fs.kick_back:.1f} m ({rule}). Fit a ratchet on the wheel's axle that holds "
        f"{fs.holding_torque_required:.1f} N·m before the pump is used."
    )


def check_sheet_path(path) -> Path:
    """The sheet is a PDF: check the extension before any work is done."""
    path = Path(path)
    if path.suffix.lower() != ".pdf":
        raise SpecError(f"--out {path}: the field sheet is a PDF; use a file ending in .pdf")
    return check_output(path, "--out")


def write_sheet_pdf(fs, path, version: str = "") -> Path:
    """The sheet on one A4 page, written atomically to ``path`` (matplotlib's PDF backend)."""
    from matplotlib.figure import Figure

    path = check_sheet_path(path)
    fig = Figure(figsize=A4)
    width, height = A4
    y = height - MARGIN
    line = BODY * 1.35 / 72.0  # [inch]

    def text(x, s, size, **kw):
        fig.text(x / width, y / height, s, fontsize=size, va="top", ha="left", **kw)

    title_chars = int(0.85 * CHARS * BODY / TITLE)  # a long name wraps (bold letters are wider)
    for row in textwrap.wrap(f"Field sheet: {fs.name}", title_chars):
        text(MARGIN, row, TITLE, weight="bold")
        y -= TITLE * 1.25 / 72.0
    y -= TITLE * 0.25 / 72.0
    intro = f"What the built pump should do, and what to look at when it does not. Verdict: {fs.verdict}."
    for row in textwrap.wrap(intro + (f" pumplink {version}." if version else ""), CHARS):
        text(MARGIN, row, BODY, style="italic")
        y -= line
    y -= line
    for heading, paragraphs in sections(fs):
        text(MARGIN, heading, HEAD, weight="bold")
        y -= HEAD * 1.45 / 72.0
        for p in paragraphs:
            for row in textwrap.wrap(p, CHARS):
                text(MARGIN + 0.15, row, BODY)
                y -= line
            y -= 0.35 * line
        y -= 0.6 * line
    if y < MARGIN:  # one page, or no sheet
        raise SpecError(
            f"the field sheet of {fs.name!r} runs {MARGIN - y:.2f} in past its A4 page; shorten the name"
        )
    with atomic_write(path, binary=True) as f:
        fig.savefig(f, format="pdf")
    return path


def sheet_html(fs) -> str:
    """The sheet as a section of the report."""
    parts = []
    for heading, paragraphs in sections(fs):
        parts.append(f"<h3>{html.escape(heading)}</h3>")
        parts.extend(f"<p>{html.escape(p)}</p>" for p in paragraphs)
    return "\n".join(parts)

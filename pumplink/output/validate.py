"""`pumplink validate`: the published discharges against their predictions (table, JSON, CSV,
JUnit XML).  Renderers only render: every number comes from :func:`pumplink.studies.validate.validate`.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, Any

from pumplink.output.batchfiles import junit_case
from pumplink.output.formats import console, num, render
from pumplink.output.words import L_PER_MIN

if TYPE_CHECKING:
    from pumplink.studies.validate import Validated, Validation

#: The duties' words.
DUTIES = {"filling": "filling containers", "all day": "all day"}
#: The duties' words in the table.
DUTY_COLUMN = {"filling": "filling", "all day": "all day"}


def validated_row(r: Validated) -> dict[str, Any]:
    """One discharge against its prediction, as a JSON row."""
    d = r.discharge
    return {
        "source": d.source,
        "quote": d.quote,
        "head_m": d.head,
        "operator_profile": d.profile,
        "duty": d.duty,
        "power_W": num(r.power),
        "published_flow_l_min": num(d.flow * L_PER_MIN),
        "predicted_flow_l_min": num(r.predicted * L_PER_MIN),
        "cadence_per_min": num(r.cadence),
        "rope_speed_m_s": num(r.rope_speed),
        "error": num(r.error),
        "pass": r.ok,
    }


def validation_row(v: Validation) -> dict[str, Any]:
    """The JSON of ``pumplink validate``."""
    return {
        "pump": v.pump,
        "tolerance": v.tolerance,
        "pass": v.passed,
        "discharges": [validated_row(r) for r in v.rows],
        "left_out": [{"figure": k, "why": why} for k, why in v.left_out.items()],
    }


def _name(r: Validated) -> str:
    d = r.discharge
    return f"{d.source}: {d.flow * L_PER_MIN:g} l/min at {d.head:g} m ({d.profile}, {DUTIES[d.duty]})"


def junit_xml(v: Validation) -> str:
    """One JUnit testcase per discharge: a failure where the prediction is off by more than the
    tolerance."""
    cases = []
    for r in v.rows:
        fail = None
        if not r.ok:
            fail = (
                f"predicted {r.predicted * L_PER_MIN:.1f} l/min, published {r.discharge.flow * L_PER_MIN:g} "
                f"l/min: {r.error:+.1%}, beyond ±{v.tolerance:.0%}"
            )
        cases.append(junit_case(_name(r), "pumplink.validate", fail, None))
    failures = sum(not r.ok for r in v.rows)
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n<testsuites>\n'
        f'  <testsuite name="pumplink validate" tests="{len(v.rows)}" failures="{failures}" skipped="0">\n'
        + "".join(cases)
        + "  </testsuite>\n</testsuites>\n"
    )


def render_validation(v: Validation, fmt: str, out=None) -> None:
    """`pumplink validate`: the table, JSON or CSV rows."""
    out = out or sys.stdout
    row = validation_row(v)

    def table() -> None:
        from rich.table import Table

        c = console(out)
        c.print(f"Published one-person discharges against {v.pump} (docs/water.md §6)", markup=False)
        t = Table(show_edge=False, box=None, pad_edge=False)
        for h in ("source", "head", "who", "duty", "power", "published", "predicted", "cadence", "off"):
            t.add_column(h, justify="left" if h in ("source", "who", "duty") else "right", no_wrap=True)
        for r, x in zip(v.rows, row["discharges"]):
            t.add_row(
                r.discharge.short,
                f"{x['head_m']:g} m",
                x["operator_profile"],
                DUTY_COLUMN[x["duty"]],
                f"{x['power_W']:.0f} W",
                f"{x['published_flow_l_min']:g} l/min",
                f"{x['predicted_flow_l_min']:.1f} l/min",
                f"{x['cadence_per_min']:.0f}/min",
                f"{x['error']:+.1%}" + ("" if r.ok else " ✗"),
            )
        c.print(t)
        for r in v.rows:
            d = r.discharge
            c.print(f'{d.short}: {d.source}: "{d.quote}"', markup=False)
        for k, why in v.left_out.items():
            c.print(f"left out: {k}: {why}", markup=False)
        bad = sum(not r.ok for r in v.rows)
        c.print(
            f"{'PASS' if v.passed else 'FAIL'}: {len(v.rows) - bad} of {len(v.rows)} within "
            f"±{v.tolerance:.0%}",
            markup=False,
        )

    render(fmt, out, as_json=lambda: row, as_csv=lambda: row["discharges"], table=table)


__all__ = ["junit_xml", "render_validation", "validation_row"]

"""The workshop template marks the critical holes: each hole's tolerance under it, a red ring round
the holes whose tolerance is tighter than a hand-drilled hole holds, the stand's tolerance in the
note; read back from the figure objects and from the SVG and DXF files.

The tolerances themselves are :func:`pumplink.studies.tolerance.allocate`'s (tested in
tests/test_tolerance.py); here the template must show exactly those, on the right holes.  On the
village design the crank's two holes carry 80 % of the peak force's spread (their sensitivity,
2.07 N/mm, is checked against two `pumplink force` runs in tests/cli/test_tolerance_command.py),
so they are the ones ringed.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from pumplink.inputs.pump import load_spec
from pumplink.studies import tolerance as tl
from pumplink.studies.drawing import drawing, tolerance_marks

ROOT = Path(__file__).resolve().parents[2]
VILLAGE = ROOT / "tests" / "data" / "village-first-sized.toml"  # a fixed design: see its header


@pytest.fixture(scope="module")
def marked():
    spec = load_spec(VILLAGE)
    dr = drawing(spec)
    parts, marks = tolerance_marks(spec, dr.parts)
    allocation = tl.allocate(tl.sensitivities(tl.problem(spec, tl.tolerances(0.001))))
    return spec, dr, parts, marks, dict(zip((g for g, _ in tl.GROUPS), allocation.groups))


def test_the_parts_carry_the_allocation(marked):
    _, dr, parts, marks, groups = marked
    crank, coupler, rocker = parts
    assert crank.hole_tolerances == (groups["crank"],) * 2 and crank.hole_critical == (True, True)
    assert coupler.hole_tolerances == (groups["coupler"],) * 2 and coupler.hole_critical == (False, False)
    assert rocker.hole_tolerances == (groups["rocker"],) * 2 and rocker.end_tolerance == groups["grip"]
    assert marks.stand == groups["stand"] and marks.reason is None and marks.share >= 0.95
    # the holes themselves are where they were: only the notes are added
    assert [p.holes.tolist() for p in parts] == [p.holes.tolist() for p in dr.parts]


def test_the_page_rings_the_critical_holes_in_red(marked):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgba

    from pumplink.output.template import CRITICAL, _page, cut_list_rows, layout

    spec, dr, parts, marks, groups = marked
    pages = layout(parts, "A4")
    fig = _page(plt, parts, pages[0], 1, len(pages), "A4", spec.name, cut_list_rows(parts, True), marks)
    try:
        ax = fig.axes[0]
        by_gid = {a.get_gid(): a for a in ax.get_children() if a.get_gid()}
        # the crank is welded to the axle at O2 (the default parts): its centre is marked, not drilled
        assert "weld-crank-0" in by_gid and "hole-crank-0" not in by_gid
        for i, kind in ((0, "weld"), (1, "hole")):
            ring = by_gid[f"critical-crank-{i}"]
            centre = by_gid[f"{kind}-crank-{i}"].get_data()
            assert ring.center == pytest.approx((centre[0][0], centre[1][0]))  # round the hole's centre
            assert ring.get_edgecolor() == pytest.approx(to_rgba(CRITICAL))
            assert ring.radius > parts[0].hole_diameter * 500  # outside the hole
            text = by_gid[f"tolerance-crank-{i}"].get_text()
            assert text == f"±{groups['crank'] * 1000:g} mm  critical"
        assert by_gid["tolerance-coupler-0"].get_text() == f"±{groups['coupler'] * 1000:g} mm"
        assert not any(g.startswith("critical-coupler") for g in by_gid)
        note = by_gid["tolerance-note"].get_text()
        assert "95%" in note and f"stand ±{groups['stand'] * 1000:g} mm" in note
    finally:
        plt.close(fig)


def _run(*args):
    argv = ["pumplink", *map(str, args)]
    code = f"import sys; sys.argv = {argv!r}; from pumplink.cli import main; main()"
    return subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)


def test_the_svg_and_dxf_templates_carry_the_marks(tmp_path, marked):
    _, _, parts, _, groups = marked
    svg, dxf = tmp_path / "t.svg", tmp_path / "t.dxf"
    for out in (svg, dxf):
        p = _run("template", VILLAGE, "--out", out)
        assert p.returncode == 0, p.stderr
    ids = set(re.findall(r'id="((?:critical|tolerance)-[^"]*)"', svg.read_text()))
    assert {"critical-crank-0", "critical-crank-1", "tolerance-note"} <= ids
    assert not {i for i in ids if i.startswith("critical-") and "crank" not in i}
    import ezdxf

    doc = ezdxf.readfile(dxf)
    radius = parts[0].hole_diameter * 500
    rings = [c for c in doc.modelspace().query("CIRCLE") if c.dxf.radius == pytest.approx(radius + 2.5)]
    assert sorted(c.dxf.layer for c in rings) == ["crank", "crank"]
    texts = [t.dxf.text for t in doc.modelspace().query("TEXT") if t.dxf.layer == "crank"]
    assert texts.count(f"±{groups['crank'] * 1000:g} mm critical") == 2


def test_a_higher_yield_asks_for_tighter_holes():
    spec = load_spec(VILLAGE)
    loose, _ = tolerance_marks(spec, drawing(spec).parts, 0.9)
    tight, _ = tolerance_marks(spec, drawing(spec).parts, 0.99)
    assert tight[0].hole_tolerances[0] < loose[0].hole_tolerances[0]

"""The geometry behind the drawings and templates (pumplink.studies.drawing) and the template tiling.

Reference lengths from the 50-digit synthesis of tests/reference.py (its own route to Eq. (2)).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
import reference as ref
from shipped import ROPE_PUMP_SPECS, spec_id

from pumplink.inputs.pump import DEFAULT_SPEC, parse_spec
from pumplink.output.template import OVERLAP, tiles
from pumplink.studies.drawing import drawing, motion

PROTO = dict(L1=0.40, D1=0.20, b=0.10, rocker=0.20, swing=math.radians(60.0))
ROOT = Path(__file__).resolve().parents[1]


def proto():
    return parse_spec(DEFAULT_SPEC)


def test_dead_centre_poses_have_crank_and_coupler_on_one_line_with_the_reference_lengths():
    r = ref.synthesis(**PROTO)
    dr = drawing(proto())
    for pose, sign in zip(dr.poses, (+1, -1)):
        o2, a, b, o4, p = pose.joints
        u, v = a - o2, b - a
        assert np.hypot(*u) == pytest.approx(float(r["crank"]), abs=1e-12)
        assert np.hypot(*v) == pytest.approx(float(r["coupler"]), abs=1e-12)
        assert abs(u[0] * v[1] - u[1] * v[0]) / (np.hypot(*u) * np.hypot(*v)) < 1e-9
        assert np.sign(np.dot(u, v)) == sign  # extended: crank and coupler the same way
        # The handle at its extremes, 90 deg +- swing/2 (docs/physics.md §1), grip at H from O4.
        ang = math.degrees(math.atan2(*(p - o4)[::-1]))
        assert ang == pytest.approx(90 + sign * 30, abs=1e-9)
        assert np.hypot(*(p - o4)) == pytest.approx(1.0, abs=1e-12)


def test_parts_hole_centres_are_the_link_lengths_and_the_cut_list_adds_the_edges():
    r = ref.synthesis(**PROTO)
    crank, coupler, handle = drawing(proto()).parts
    assert crank.centre_distance == pytest.approx(float(r["crank"]), abs=1e-12)
    assert coupler.centre_distance == pytest.approx(float(r["coupler"]), abs=1e-12)
    assert handle.centre_distance == pytest.approx(0.2) and handle.end == pytest.approx(1.0)
    # the default parts' 12 mm pins, 1.5 d = 18 mm of bar beyond each outer hole; the handle ends at
    # the grip
    assert crank.hole_diameter == 0.012
    assert crank.cut_length == pytest.approx(float(r["crank"]) + 0.036)
    assert handle.cut_length == pytest.approx(1.018)


def test_motion_marks_the_step_nearest_each_dead_centre():
    dr, mo = drawing(proto()), motion(proto(), 36)
    assert mo.joints.shape == (36, 5, 2) and mo.force.shape == (36,)
    for name, pose in zip(("extended", "folded"), dr.poses):
        k = mo.dead_centre.index(name)
        assert abs(math.remainder(mo.crank_angle[k] - pose.crank_angle, 2 * math.pi)) <= math.pi / 36


@pytest.mark.parametrize("length", [50.0, 267.0, 268.0, 1015.0, 3000.0])
def test_tiles_cover_each_bar_with_overlapping_pieces_no_longer_than_the_page(length):
    class Bar:  # the two attributes tiling reads
        edge = 0.0
        cut_length = length / 1000

    usable = 267.0
    ts = tiles([Bar()], usable)
    assert ts[0].start == 0 and ts[-1].stop == pytest.approx(length)
    assert all(t.stop - t.start <= usable + 1e-9 for t in ts)
    for a, b in zip(ts, ts[1:]):
        assert a.stop - b.start == pytest.approx(OVERLAP)  # the overlap carries the alignment marks
    assert [t.index for t in ts] == list(range(len(ts))) and {t.count for t in ts} == {len(ts)}


# ----------------------------------------------------------------------------- the holes of [parts]
#: (handle_joint, crank_joint, pin_diameter) given in a copy of each spec's [parts]: None as shipped.
JOINTS = [None, ("lug", "welded", 0.016), ("hole", "hole", 0.010), ("lug", "hole", 0.020)]


def _with_joints(path, joints):
    from pumplink.inputs.pump import load_spec, spec_to_dict

    spec = load_spec(path)
    if joints is None:
        return spec
    data = spec_to_dict(spec)
    handle, crank, pin = joints
    parts = {k: v for k, v in data.get("parts", {}).items() if k not in ("handle_notch", "crank_notch")}
    data["parts"] = {**parts, "handle_joint": handle, "crank_joint": crank, "pin_diameter": pin}
    return parse_spec(data)


@pytest.mark.parametrize("joints", JOINTS, ids=lambda j: "as shipped" if j is None else "-".join(map(str, j)))
@pytest.mark.parametrize("path", ROPE_PUMP_SPECS, ids=spec_id)
def test_the_template_holes_are_the_pins_of_parts(path, joints):
    """Each link's holes are drilled to the pins' diameter of the spec's [parts] (or of their
    defaults, 12 mm, where it gives none), and none is drilled where [parts] welds the joint: the
    crank to the axle at O2 (crank_joint = "welded", the default), a lug to the handle at B
    (handle_joint = "lug"); the cut list counts the drilled holes and names the welded joints."""
    from pumplink.output.template import cut_list_rows
    from pumplink.studies.drawing import parts

    spec = _with_joints(path, joints)
    given = spec.parts is not None
    pin = joints[2] if joints else spec.parts.pin_diameter if given else 0.012
    handle = joints[0] if joints else spec.parts.handle_joint if given else "hole"
    crank = joints[1] if joints else spec.parts.crank_joint if given else "welded"
    links = {p.key: p for p in parts(spec)}
    drilled = {
        ("crank", "O2"): crank == "hole",
        ("crank", "A"): True,
        ("coupler", "A"): True,
        ("coupler", "B"): True,
        ("rocker-handle", "O4"): True,
        ("rocker-handle", "B"): handle == "hole",
    }
    for (key, joint), want in drilled.items():
        p = links[key]
        assert p.hole_diameter == pin, key
        assert p.drilled[p.hole_labels.index(joint)] is want, (key, joint)
    rows = {row[0]: row[1] for row in cut_list_rows(tuple(links.values()), False)[1:]}
    assert rows["crank (on the wheel)"] == f"{1 + (crank == 'hole')} x Ø{pin * 1000:g} mm" + (
        ", welded at O2" if crank == "welded" else ""
    )
    assert rows["rocker and handle"] == f"{1 + (handle == 'hole')} x Ø{pin * 1000:g} mm" + (
        ", lug at B" if handle == "lug" else ""
    )


def test_the_village_template_files_drill_no_hole_where_parts_welds(tmp_path):
    """The village well's [parts]: a lug welded to the handle at B, the crank welded to the axle at
    O2, 12 mm pins.  Read back from the SVG and the DXF: a circle of the pin's diameter at every
    other joint and none at those two, whose centres are marked instead (at the link lengths of
    the synthesis, from tests/reference.py)."""
    ezdxf = pytest.importorskip("ezdxf")
    from pumplink.inputs.pump import load_spec
    from pumplink.output.charts import pyplot
    from pumplink.output.template import template_dxf, template_svg
    from pumplink.studies.drawing import parts

    pyplot()
    spec = load_spec(ROOT / "configs" / "village-10m.toml")
    shop = spec.parts
    assert (shop.handle_joint, shop.crank_joint, shop.pin_diameter) == ("lug", "welded", 0.012)
    links = parts(spec)
    template_svg(links, tmp_path / "t.svg", spec.name)
    template_dxf(links, tmp_path / "t.dxf", spec.name)
    svg = (tmp_path / "t.svg").read_text(encoding="utf-8")
    ids = set(re.findall(r'<g id="((?:hole|weld)-[^"]+)">', svg))
    assert ids == {"weld-crank-0", "hole-crank-1", "hole-coupler-0", "hole-coupler-1",
                   "hole-rocker-handle-0", "weld-rocker-handle-1"}  # fmt: skip
    msp = ezdxf.readfile(tmp_path / "t.dxf").modelspace()
    circles = {key: msp.query(f'CIRCLE[layer=="{key}"]') for key in ("crank", "coupler", "rocker-handle")}
    assert {key: len(c) for key, c in circles.items()} == {"crank": 1, "coupler": 2, "rocker-handle": 1}
    assert {c.dxf.radius for cs in circles.values() for c in cs} == {6.0}
    r = ref.synthesis(spec.linkage.L1, spec.linkage.D1, spec.linkage.b, spec.linkage.rocker,
                      math.radians(spec.linkage.swing))  # fmt: skip
    lengths = {"crank": float(r["crank"]) * 1000, "rocker-handle": spec.linkage.rocker * 1000}
    for key, length in lengths.items():
        upright = [ln for ln in msp.query(f'LINE[layer=="{key}"]') if ln.dxf.start.x == ln.dxf.end.x]
        (circle,) = circles[key]
        assert len(upright) == 1 and abs(upright[0].dxf.start.x - circle.dxf.center.x) == pytest.approx(
            length, abs=1e-6
        ), key

"""The geometry behind the drawings and templates (pumplink.studies.drawing) and the template tiling.

Reference lengths from the 50-digit synthesis of tests/reference.py (its own route to Eq. (2)).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import reference as ref

from pumplink.inputs.pump import DEFAULT_SPEC, parse_spec
from pumplink.output.template import OVERLAP, tiles
from pumplink.studies.drawing import drawing, motion

PROTO = dict(L1=0.40, D1=0.20, b=0.10, rocker=0.20, swing=math.radians(60.0))


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
    # 10 mm holes, 1.5 d = 15 mm of bar beyond each outer hole; the handle ends at the grip.
    assert crank.cut_length == pytest.approx(float(r["crank"]) + 0.030)
    assert handle.cut_length == pytest.approx(1.015)


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

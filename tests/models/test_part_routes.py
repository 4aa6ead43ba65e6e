"""The part checks' two routes: many designs at once (the verdict's, ``evaluate`` with
``[parts]``) and one design in depth (``force --explain``'s workshop view).

The vector route (:func:`pumplink.models.parts.dynamics_strength`: the full-dynamics scenes of a
block of designs, the joint forces along their motions on the cycle, the peaks by
:func:`pumplink.models.joints.cycle_peak_loads`) must give what the one-design route
(:func:`pumplink.models.parts.scene`, :func:`~pumplink.models.parts.part_loads` and
:func:`~pumplink.models.parts.strength`) gives each design on its own.  The expected values are
the one-design route's, design by design; the two run the same operations on the same values,
so they are asked to agree bit for bit, whatever the other designs of the block.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pumplink.constants import GRAVITY
from pumplink.evaluate import evaluate, pump_designs
from pumplink.inputs.pump import load_spec, spec_values
from pumplink.mechanisms.fourbar import FourBar
from pumplink.models import DYNAMICS, ORDER, Masses
from pumplink.models import joints as J
from pumplink.models import parts as P

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def village_variants():
    """The village well and variants of it (swing, rocker, handle, head, speed varied; twelve
    designs, all decided by full dynamics), evaluated with its ``[parts]``."""
    values = spec_values(load_spec(ROOT / "configs" / "village-10m.toml"))
    rng = np.random.default_rng(35)
    n = 12
    vary = {
        "linkage.swing": values["linkage.swing"] * rng.uniform(0.85, 1.2, n),
        "linkage.rocker": values["linkage.rocker"] * rng.uniform(0.9, 1.3, n),
        "linkage.handle": values["linkage.handle"] * rng.uniform(0.9, 1.2, n),
        "load.head": rng.uniform(4.0, 16.0, n),
        "operator.speed": rng.uniform(200.0, 400.0, n),
    }
    for v in vary.values():
        v[0] = np.nan  # the first one: the spec as it is
    vary = {k: np.where(np.isnan(v), values[k], v) for k, v in vary.items()}
    designs = pump_designs({**values, **vary})
    ev = evaluate(designs, ("parts",))
    assert (np.asarray(ev.model_index) == ORDER.index(DYNAMICS)).all() and ev.feasible.all()
    return designs, ev


def _of(value, n, i) -> float:
    """Design ``i``'s value of a design column (a float or an array over ``n`` designs)."""
    return float(np.broadcast_to(np.asarray(value, float), (n,))[i])


def _one_design(ev, designs, i):
    """Design ``i``'s scene, loads and (pin pressure [MPa], handle and crank fatigue) by the
    one-design route."""
    n, syn = len(ev), ev.synthesis
    lk = FourBar(*(_of(v, n, i) for v in syn.linkage.parameters))
    dce, dcf = _of(syn.dead_centre_extended, n, i), _of(syn.dead_centre_folded, n, i)
    mw, rope = _of(designs.wheel_torque, n, i), _of(designs.rope_force, n, i)
    links = Masses(
        np.broadcast_to(ev.masses.coupler, (n,))[i], np.broadcast_to(ev.masses.handle, (n,))[i], 0.0
    )
    sc = P.scene(
        lk, dce, dcf, mw, _of(designs.inertia, n, i), links, _of(designs.speed, n, i),
        _of(designs.speed_fluctuation, n, i), _of(ev.least_peak_force, n, i), DYNAMICS,
    )  # fmt: skip
    weight = _of(designs.wheel_mass, n, i) * GRAVITY
    loads = P.part_loads(lk, dce, dcf, _of(designs.dead_band, n, i), mw, DYNAMICS, sc, rope, weight)
    st = P.strength(loads, designs.parts.design(i))
    return sc, loads, (st.pin_pressure / 1e6, st.handle.safety, st.crank.safety)


def _six(peaks, at: int):
    """The six loads' peak values (``at`` 0) or crank angles (1) of a :class:`PeakLoads`."""
    joints = peaks.force if at == 0 else peaks.angle
    return np.concatenate([joints, [peaks.crank_moment[at], peaks.handle_moment[at]]])


def test_the_verdicts_part_checks_are_each_designs_own(village_variants):
    """The evaluation's part checks of twelve designs at once equal the one-design route's of
    each, bit for bit (the verdict and the workshop view cannot disagree)."""
    designs, ev = village_variants
    got = np.stack([ev.pin_pressure, ev.handle_fatigue, ev.crank_fatigue], axis=1)
    want = np.array([_one_design(ev, designs, i)[2] for i in range(len(ev))])
    assert np.isfinite(want).all()
    np.testing.assert_array_equal(got, want)


def test_the_part_checks_do_not_depend_on_the_blocks(village_variants, monkeypatch):
    """In blocks of five designs (three blocks, the last of two) the part checks are those of
    one block of twelve."""
    designs, ev = village_variants
    monkeypatch.setattr(P, "SCENE_BLOCK", 5)
    again = evaluate(designs, ("parts",))
    for key in ("pin_pressure", "handle_fatigue", "crank_fatigue"):
        np.testing.assert_array_equal(getattr(again, key), getattr(ev, key))


def test_a_designs_peaks_do_not_depend_on_its_block(village_variants):
    """The cycle's peaks (the six loads and their crank angles) of the vector route equal
    :func:`pumplink.models.joints.peak_joint_forces` of each design on its own, in a block of
    all twelve, of the last seven and of one."""
    designs, ev = village_variants
    one = [_one_design(ev, designs, i) for i in range(len(ev))]
    want = np.array([_six(loads.peaks, 0) for _, loads, _ in one]).T
    want_at = np.array([_six(loads.peaks, 1) for _, loads, _ in one]).T
    for rows in (np.arange(len(ev)), np.arange(5, len(ev)), np.array([3])):
        scenes = [one[i][0] for i in rows]
        th = np.stack([_cycle(sc) for sc in scenes])

        def loads_at(r, angles, _read=None, rows=rows, scenes=scenes):
            """The six loads of designs ``r`` of ``rows`` at ``angles``, one design at a time."""
            return np.stack([J.six_loads(_forces(scenes[k], angles[j], designs, rows[k], len(ev)))
                             for j, k in enumerate(r)], axis=1)  # fmt: skip

        value, angle = J.cycle_peak_loads(loads_at, th, loads_at(np.arange(rows.size), th))
        np.testing.assert_array_equal(value, want[:, rows])
        np.testing.assert_array_equal(angle, want_at[:, rows])


def _cycle(sc):
    """The crank angles of :func:`pumplink.models.parts.part_loads`' cycle of a scene."""
    jumps = np.add.outer(
        [sc.dead_centre_extended, sc.dead_centre_folded], [-J.JUMP_OFFSET, J.JUMP_OFFSET]
    ).ravel()
    turn = np.arange(P.CYCLE_SAMPLES) * (2 * np.pi / P.CYCLE_SAMPLES)
    return np.sort(np.mod(np.concatenate([turn, jumps]), 2 * np.pi))


def _forces(sc, angles, designs, i, n):
    """The joint forces of the one-design route along a scene's motion at crank angles."""
    rope, weight = _of(designs.rope_force, n, i), _of(designs.wheel_mass, n, i) * GRAVITY
    return J.motion_forces(sc.linkage, J.dynamics_motion(sc, angles), GRAVITY, rope, weight)


def test_the_loads_without_the_force_vectors_are_the_forces_own(village_variants):
    """:func:`pumplink.models.joints.motion_loads` (the six loads, the moments and the axial
    forces, without stacking the force vectors) equals :func:`~pumplink.models.joints.six_loads`
    of :func:`~pumplink.models.joints.motion_forces` and its fields, on the motion of a scene,
    a quasi-static one and a flywheel-less one without the loop closure given."""
    designs, ev = village_variants
    sc, _, _ = _one_design(ev, designs, 2)
    th = np.linspace(-1.0, 8.0, 997)
    motions = (
        J.dynamics_motion(sc, th),
        J.quasi_static_motion(sc.linkage, th, sc.wheel_torque),
        J.Motion(th, np.full(th.shape, 30.0), np.full(th.shape, -4.0), np.full(th.shape, 50.0), sc.masses),
    )
    for motion in motions:
        forces = J.motion_forces(sc.linkage, motion, GRAVITY, 120.0, 98.0)
        six, read = J.motion_loads(sc.linkage, motion, GRAVITY, 120.0, 98.0)
        np.testing.assert_array_equal(six, J.six_loads(forces))
        names = ("handle_moment", "handle_axial", "crank_moment", "crank_axial")
        for name, got in zip(names, read, strict=True):
            np.testing.assert_array_equal(got, getattr(forces, name))


def test_peak_candidates_hold_every_angle_the_peak_search_reads():
    """The angles :func:`pumplink.models.parts.peak_candidates` picks from the joints' squares hold,
    for each joint and design, the first angle of the largest np.hypot and its two neighbours (all
    that the peak search reads): on forces of one magnitude in many directions, whose np.hypot
    ties or differs by an ulp while their squares differ by a few, on NaN and on a joint NaN over
    the whole cycle."""
    rng = np.random.default_rng(2)
    d, k = 40, 300
    angle = rng.uniform(0.0, 2 * np.pi, (4, d, k))
    size = np.where(rng.uniform(size=(4, d, k)) < 0.5, 123.456, rng.uniform(0.0, 123.456, (4, d, k)))
    x, y = size * np.cos(angle), size * np.sin(angle)
    x[0, 3, 10:20] = np.nan
    x[1, 5] = np.nan
    squares = x * x + y * y
    at = P.peak_candidates(squares)
    exact = np.where(np.isnan(np.hypot(x, y)), -np.inf, np.hypot(x, y))
    best = np.argmax(exact, axis=2)
    top = np.sort(exact, axis=2)[..., -5:]
    top = top[np.isfinite(top).all(axis=2)]
    assert (np.ptp(top, axis=-1) <= 1e-13).all()  # near-ties at the top
    for joint in range(4):
        for design in range(d):
            if joint == 1 and design == 5:
                continue  # NaN over the whole cycle: nothing to read
            j = best[joint, design]
            for i in (max(j - 1, 0), j, min(j + 1, k - 1)):
                assert i in at[design]


def test_the_cycles_cosines_are_numpys_of_its_angles():
    """:func:`pumplink.models.parts.cycle_angles` with ``trig``: the cosines and sines of the
    turn's angles computed once and merged with the nodes' in the angles' places must be
    np.cos and np.sin of the merged angles, bit for bit (dead centres anywhere, next to 0 and
    2 pi, and nodes falling between the same two angles of the turn)."""
    rng = np.random.default_rng(7)
    turn = 2 * np.pi / P.CYCLE_SAMPLES
    extended = np.concatenate([rng.uniform(0.0, 2 * np.pi, 40), [0.0, 1e-10, 2 * np.pi - 1e-10, 3.0, 3.0]])
    folded = np.concatenate([rng.uniform(0.0, 2 * np.pi, 40), [np.pi, 2.0, 5.0, 3.0 + 0.3 * turn, 5 * turn]])
    plain = P.cycle_angles(extended, folded)
    angles, cos, sin = P.cycle_angles(extended, folded, trig=True)
    assert angles.shape == (45, P.CYCLE_SAMPLES + 4)
    assert (np.diff(angles, axis=1) >= 0).all() and (angles >= 0).all() and (angles < 2 * np.pi).all()
    np.testing.assert_array_equal(angles, plain)
    np.testing.assert_array_equal(cos, np.cos(angles))
    np.testing.assert_array_equal(sin, np.sin(angles))


def test_the_row_buffer_is_set_within_the_part_checks_only(monkeypatch):
    """:func:`pumplink.models.parts.row_buffers` sets numpy's ufunc buffer for its block and gives
    the caller's back, also when the block raises; before numpy 2.3 it leaves the buffer alone."""
    before = np.getbufsize()
    monkeypatch.setattr(np, "__version__", "2.3.0")
    with P.row_buffers():
        assert np.getbufsize() == P.ROW_BUFFER != before
    assert np.getbufsize() == before
    with pytest.raises(RuntimeError), P.row_buffers(512):
        assert np.getbufsize() == 512
        raise RuntimeError
    assert np.getbufsize() == before
    monkeypatch.setattr(np, "__version__", "2.2.6")
    with P.row_buffers():
        assert np.getbufsize() == before

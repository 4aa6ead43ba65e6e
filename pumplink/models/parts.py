"""Will the parts last? The loads on the pins, the crank and the handle over the deciding model's
cycle, and what they mean for pins, tubes and bars a workshop builds (docs/workshop.md).

Two routes to the same numbers: one design in depth, :func:`part_loads` and :func:`strength` (the
workshop report of ``pumplink force --explain``, and the verdict's part checks of a design the
flywheel decides), and many designs at once, :func:`quasi_static_strength` and
:func:`dynamics_strength` (the verdict's part checks of the designs the quasi-static model or full
dynamics decides: a batch, a tolerance study, a search).  :func:`part_checks`, the evaluation's one
call, takes each design the route of its model.  The full-dynamics routes run the same operations
on the same values per design, so they agree bit for bit (tests/models/test_part_routes.py).

Pure functions on floats / arrays over designs; SI units, radians.
"""

from __future__ import annotations

from contextlib import contextmanager
from dataclasses import dataclass
from types import SimpleNamespace
from typing import NamedTuple

import numpy as np

from pumplink.constants import GRAVITY
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar
from pumplink.models import DYNAMICS, FLYWHEEL, ORDER, Masses
from pumplink.models import joints as _joints
from pumplink.models import strength as _strength

#: Crank angles per turn on which the fatigue cycle (the moments' amplitude and mean) is sampled
#: (0.25 deg), also the energy models' peak search's starting grid (at least PEAK_GRID_PER_RAD).
#: The cycle adds the crank angles of the reported peak moments (and, quasi-static, the dead
#: bands' edges): the village design's crank safety 2.8456 with them, 2.8480 on this grid alone,
#: 2.846 on 11,520 angles.
CYCLE_SAMPLES = 1440
#: The verdict's levels of the part checks (docs/workshop.md §2): pin bearing pressure warns above
#: the allowable of an alternating moving joint (12 MPa) and fails above the static one (30 MPa);
#: a fatigue safety factor warns below 1.5 and fails below 1.
PIN_PRESSURE_WARN, PIN_PRESSURE_FAIL = _strength.PIN_PRESSURE_ALTERNATING, _strength.PIN_PRESSURE_STATIC
FATIGUE_WARN, FATIGUE_FAIL = 1.5, 1.0
#: The part sizes the checks read, attributes of the sizes given (the keys of a spec's ``[parts]``
#: table, docs/workshop.md §2): the pins' diameter and bearing width, the handle tube's diameter,
#: wall and notch factor, the crank bar's diameter and notch factor [m; -].
PART_KEYS = (
    "pin_diameter",
    "pin_width",
    "handle_diameter",
    "handle_wall",
    "handle_notch",
    "crank_diameter",
    "crank_notch",
)


@dataclass(frozen=True)
class PartLoads:
    """The loads of one design over its cycle: the peaks (:class:`pumplink.models.joints.PeakLoads`:
    the four joints, the crank's and the handle's bending moments, each with its crank angle) and
    the loads on :data:`CYCLE_SAMPLES` crank angles (:class:`pumplink.models.joints.JointForces`)."""

    peaks: object
    cycle: object
    model: str


def part_loads(
    lk: FourBar,
    dead_centre_extended: float,
    dead_centre_folded: float,
    dead_band: float,
    wheel_torque: float,
    model: str,
    scene=None,
    rope_pull: float = 0.0,
    wheel_weight: float = 0.0,
) -> PartLoads:
    """The joint loads of one design under the model that decided (``model``: a key of
    :data:`pumplink.models.ORDER`; ``scene``: the energy model's, with a finite least peak force).

    The quasi-static model carries no load within ±``dead_band`` of the dead centres (its force is
    infinite there; the wheel carries the linkage through), so its loads are taken outside them.
    ``rope_pull`` and ``wheel_weight`` [N] add the rope and the wheel to the axle's load.
    """
    if model in (FLYWHEEL, DYNAMICS):
        motion_of = _joints.dynamics_motion if model == DYNAMICS else _joints.flywheel_motion
        # the cycle, with the one-sided nodes at the dead centres (where the push reverses), is the
        # peak search's starting grid: the motion is computed once on it
        th = cycle_angles(np.array([scene.dead_centre_extended]), np.array([scene.dead_centre_folded]))[0]
        cycle = _joints.motion_forces(scene.linkage, motion_of(scene, th), GRAVITY, rope_pull, wheel_weight)
        peaks = _joints.scene_peaks(scene, motion_of, GRAVITY, rope_pull, wheel_weight, cycle=(th, cycle))
        # the fatigue cycle holds the reported peak moments' crank angles too
        at = np.array([peaks.crank_moment[1], peaks.handle_moment[1]], float)
        more = _joints.motion_forces(scene.linkage, motion_of(scene, at), GRAVITY, rope_pull, wheel_weight)
        pairs = zip(vars(cycle).values(), vars(more).values())
        cycle = type(cycle)(*(np.concatenate([a, b], axis=-1) for a, b in pairs))
        return PartLoads(peaks, cycle, model)
    peaks = _joints.quasi_static_peaks(
        lk, dead_centre_extended, dead_centre_folded, dead_band, wheel_torque, rope_pull, wheel_weight
    )
    at = np.array([peaks.crank_moment[1], peaks.handle_moment[1]], float)
    cycle = quasi_static_cycle(lk, dead_centre_extended, dead_centre_folded, dead_band, wheel_torque,
                               rope_pull, wheel_weight, at)  # fmt: skip
    return PartLoads(peaks, cycle, model)


def cycle_angles(dead_centre_extended, dead_centre_folded, trig: bool = False):
    """The crank angles [rad] of the energy models' cycle of designs (arrays (n,)): CYCLE_SAMPLES
    a turn and the nodes :data:`pumplink.models.joints.JUMP_OFFSET` either side of both dead
    centres (where the push reverses), in [0, 2 pi) and sorted, shape (n, CYCLE_SAMPLES + 4).
    The turn's angles are in order already: the four nodes are merged into them (the values a
    sort of all of them gives).  ``trig``: (angles, their cosines, their sines), the turn's
    computed once for all designs (the same angles, so the same values)."""
    turn = np.arange(CYCLE_SAMPLES) * (TWO_PI / CYCLE_SAMPLES)
    ends = np.stack([dead_centre_extended, dead_centre_folded], axis=1)
    nodes = np.sort(np.mod((ends[:, :, None] + [-_joints.JUMP_OFFSET, _joints.JUMP_OFFSET]).reshape(-1, 4),
                           TWO_PI), axis=1)  # fmt: skip
    n = nodes.shape[0]
    # node j goes after the turn's angles up to it and the nodes before it
    at = np.searchsorted(turn, nodes, side="right") + np.arange(4)
    is_node = np.zeros((n, CYCLE_SAMPLES + 4), bool)
    np.put_along_axis(is_node, at, True, axis=1)
    on_turn = ~is_node

    def merged(of_turn, of_nodes):
        out = np.empty((n, CYCLE_SAMPLES + 4))
        out[is_node] = of_nodes.ravel()
        out[on_turn] = np.broadcast_to(of_turn, (n, CYCLE_SAMPLES)).ravel()
        return out

    angles = merged(turn, nodes)
    if not trig:
        return angles
    return angles, merged(np.cos(turn), np.cos(nodes)), merged(np.sin(turn), np.sin(nodes))


def quasi_static_cycle(lk, dead_centre_extended, dead_centre_folded, dead_band, wheel_torque, rope_pull=0.0,
                       wheel_weight=0.0, peak_angles=()):  # fmt: skip
    """The quasi-static loads (:class:`pumplink.models.joints.JointForces`) over a turn: on
    :data:`CYCLE_SAMPLES` crank angles, NaN within ±``dead_band`` of the dead centres (the model
    carries no load there), then at the four edges of the dead bands (the ends of the arcs the
    model judges, where its loads are largest next to a dead centre) and at ``peak_angles`` [rad]
    (the crank angles of the reported peak moments), so that the fatigue read from the cycle is
    that of the reported peaks.  Broadcasts over designs: with parameters and values of shape
    (n, 1) and ``peak_angles`` of shape (n, k) the loads have shape (n, CYCLE_SAMPLES + 4 + k)."""
    th = np.arange(CYCLE_SAMPLES) * (TWO_PI / CYCLE_SAMPLES)
    off = np.minimum(
        np.abs(np.mod(th - dead_centre_extended + np.pi, TWO_PI) - np.pi),
        np.abs(np.mod(th - dead_centre_folded + np.pi, TWO_PI) - np.pi),
    )
    th = np.where(off > dead_band, th, np.nan)
    # the arcs' ends, as pumplink.models.joints.quasi_static_peak_loads judges them (an arc the
    # dead bands overlap has none)
    plus = np.mod(dead_centre_folded - dead_centre_extended, TWO_PI)
    first, second = plus - 2 * dead_band >= 0, TWO_PI - plus - 2 * dead_band >= 0
    edges = np.stack(
        np.broadcast_arrays(
            np.where(first, dead_centre_extended + dead_band, np.nan),
            np.where(first, dead_centre_extended + plus - dead_band, np.nan),
            np.where(second, dead_centre_folded + dead_band, np.nan),
            np.where(second, dead_centre_folded + TWO_PI - plus - dead_band, np.nan),
        ),
        axis=-1,
    )
    lead = th.shape[:-1]
    peaks = np.asarray(peak_angles, float)
    th = np.concatenate(
        [th, edges.reshape(lead + (4,)), np.broadcast_to(peaks, lead + peaks.shape[-1:])], axis=-1
    )
    motion = _joints.quasi_static_motion(lk, th, wheel_torque)
    return _joints.motion_forces(lk, motion, GRAVITY, rope_pull, wheel_weight)


def quasi_static_strength(lk, dead_centre_extended, dead_centre_folded, dead_band, wheel_torque, rope_pull,
                          wheel_weight, parts) -> Strength:  # fmt: skip
    """:func:`strength` of many designs under the quasi-static model at once: ``lk`` with
    parameters of shape (n,), the other values of shape (n,) and ``parts`` columns
    (the attributes :data:`PART_KEYS`); the peaks by
    :func:`pumplink.models.joints.quasi_static_peak_loads`."""
    value, angle = _joints.quasi_static_peak_loads(
        lk, dead_centre_extended, dead_centre_folded, dead_band, wheel_torque, rope_pull, wheel_weight
    )
    n = value.shape[1]

    def column(v):
        return np.broadcast_to(np.asarray(v, float), (n,))[:, None]

    cycle = quasi_static_cycle(
        FourBar(*(column(v) for v in lk.parameters)),
        *(column(v) for v in (dead_centre_extended, dead_centre_folded, dead_band, wheel_torque, rope_pull,
                              wheel_weight)),
        angle[4:6].T,  # the crank's and the handle's peak moments, as the report gives them
    )  # fmt: skip
    return _strength_of(value[:4], cycle, parts, n)


def dynamics_strength(lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses, speed,
                      speed_fluctuation, force, rope_pull, wheel_weight, parts) -> Strength:  # fmt: skip
    """:func:`strength` of :func:`part_loads` for many designs under full dynamics at once: ``lk``
    with parameters of shape (n,), the other values of shape (n,) (``force`` each design's finite
    least peak force, ``masses`` the links' without the operator's arms) and ``parts`` columns
    (the attributes :data:`PART_KEYS`).  The scenes are :func:`pumplink.models.dynamics.scenes`,
    the cycle and its peaks those of :func:`part_loads` (:func:`pumplink.models.joints.cycle_peak_loads`):
    the same operations on the same values per design (tests/models/test_part_routes.py)."""
    from pumplink.models import dynamics as _dy

    scs = _dy.scenes(lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses, speed,
                     speed_fluctuation, force)  # fmt: skip
    n = scs.least_peak_force.shape[0]

    def column(v):
        return np.broadcast_to(np.asarray(v, float), (n,))[:, None]

    rope, weight = column(rope_pull), column(wheel_weight)
    ends = column(dead_centre_extended)[:, 0], column(dead_centre_folded)[:, 0]
    th, cos_th, sin_th = cycle_angles(*ends, trig=True)

    def loads_at(rows, angles, fatigue=False, out=None, squares=False, trig=None, read=None):
        sub = scs.take(rows)
        motion = _joints.dynamics_motion(sub, angles, trig)
        return _joints.motion_loads(
            sub.linkage, motion, GRAVITY, rope[rows], weight[rows], fatigue, out, squares, read
        )

    def six_at(rows, angles, read=None):
        return loads_at(rows, angles, read=read)[0]

    # the loads over the cycle, CYCLE_ROWS designs at a time (their arrays stay in the cache): the
    # six the peaks are searched on, and the moments and axial forces the fatigue reads, which
    # also holds the reported peak moments' crank angles (the last two)
    every, k = np.arange(n), th.shape[1]
    six = np.empty((6, n, k))
    fatigue = _Cycle(*(np.empty((n, k + 2)) for _ in _Cycle._fields))
    for s in range(0, n, CYCLE_ROWS):
        rows = slice(s, s + CYCLE_ROWS)
        trig = (cos_th[rows], sin_th[rows])
        carried = loads_at(every[rows], th[rows], fatigue=True, out=six[:, rows], squares=True, trig=trig)[1]
        for v, r in zip(fatigue, carried, strict=True):
            v[rows, :k] = r
    # the joints' magnitudes where the peak search reads them (np.hypot costs as much as the rest
    # of the joint forces): at the angles their squares rank near the top and those angles'
    # neighbours; the others hold -inf, below every load, as NaN does for the search
    at = peak_candidates(six[:4])
    exact = six_at(every, np.take_along_axis(th, at, axis=1))[:4]
    six[:4] = -np.inf
    np.put_along_axis(six[:4], np.broadcast_to(at, exact.shape), exact, axis=2)
    value, angle = _joints.cycle_peak_loads(six_at, th, six)
    for v, r in zip(fatigue, loads_at(every, angle[4:6].T, fatigue=True)[1], strict=True):
        v[:, k:] = r
    return _strength_of(value[:4], fatigue, parts, n)


#: Relative margin below the largest squared magnitude of a joint over a cycle within which a crank
#: angle may hold its largest magnitude: x^2 + y^2 is within 4e-16 of |R|^2 and np.hypot within
#: an ulp of |R|, so an angle whose np.hypot equals the largest is within 2e-15 of the largest square.
PEAK_MARGIN = 1e-9


def peak_candidates(squares):
    """Where the four joints' magnitudes may peak over a cycle, from their squares x^2 + y^2
    (:func:`pumplink.models.joints.motion_loads` with ``squares``; shape (4, D, K)): the crank
    angles whose square is within :data:`PEAK_MARGIN` of its joint's largest and their neighbours
    (the bracket the peak search zooms into), all that
    :func:`pumplink.models.joints.cycle_peak_loads` reads of a joint.  Returns the indices (D, C)
    of the angles that any joint needs, a design's first repeated where it needs fewer than C (an
    index into the angles of each design)."""
    top = np.fmax.reduce(squares, axis=2)  # NaN only where a joint is NaN over the whole cycle
    with np.errstate(invalid="ignore"):
        near = squares >= (top * (1.0 - PEAK_MARGIN))[..., None]
    need = near.copy()
    need[..., 1:] |= near[..., :-1]
    need[..., :-1] |= near[..., 1:]
    need = need.any(axis=0)  # (D, K)
    count = np.count_nonzero(need, axis=1)
    row, col = np.nonzero(need)  # in order, row by row
    at = np.zeros((need.shape[0], max(int(count.max(initial=0)), 1)), np.intp)
    at[row, np.arange(row.size) - np.repeat(np.cumsum(count) - count, count)] = col
    return np.where(np.arange(at.shape[1]) < count[:, None], at, at[:, :1])


class _Cycle(NamedTuple):
    """The loads over the cycle that the fatigue reads (designs, crank angles)."""

    handle_moment: np.ndarray
    handle_axial: np.ndarray
    crank_moment: np.ndarray
    crank_axial: np.ndarray


@dataclass(frozen=True)
class Strength:
    """What the loads mean for the parts (docs/workshop.md §2).

    pin_pressure : the largest mean bearing pressure of the four pins, F / (d w) [Pa], and
        ``pin`` the joint it is on;  handle, crank : :class:`pumplink.models.strength.Fatigue` of
        the handle's tube at the coupler pin and of the crank's bar at the axle (``safety`` is the
        fatigue safety factor, modified Goodman);  endurance : their endurance limits [Pa].
    """

    pin_pressure: float
    pin: str
    handle: object
    crank: object
    endurance: tuple


def strength(loads: PartLoads, parts) -> Strength:
    """Pin pressure and fatigue of the crank and the handle for ``parts`` (the spec's ``[parts]``
    table, or its defaults: 12 mm pins on 5.2 mm of bore, a 26.9 x 2.6 mm handle tube, a ½" bar
    crank, both of S235; docs/workshop.md §2)."""
    st = _strength_of(np.asarray(loads.peaks.force, float)[:, None], _batch(loads.cycle), parts, 1)
    return Strength(
        float(st.pin_pressure[0]),
        st.pin[0],
        _strength.Fatigue(*(float(np.asarray(v)[0]) for v in vars(st.handle).values())),
        _strength.Fatigue(*(float(np.asarray(v)[0]) for v in vars(st.crank).values())),
        tuple(float(np.asarray(v)[0]) for v in st.endurance),
    )


def _batch(cycle):
    """One design's cycle as the first row of a batch of one."""
    return type(cycle)(*(np.asarray(v, float)[..., None, :] for v in vars(cycle).values()))


def _strength_of(peak_force, cycle, parts, n) -> Strength:
    """Pin pressure and fatigue of n designs: ``peak_force`` (4, n) [N]; ``cycle`` the loads over a
    turn of shape (n, K), NaN where the model carries none; ``parts`` sizes (scalars or (n,))."""

    def size(k):
        return np.broadcast_to(np.asarray(getattr(parts, k), float), (n,))

    pressure = _strength.bearing_pressure(peak_force, size("pin_diameter"), size("pin_width"))  # (4, n)
    filled = np.where(np.isnan(pressure), -np.inf, pressure)
    k = np.argmax(filled, axis=0)
    ult = _strength.ULTIMATE_S235
    handle_d, crank_d = size("handle_diameter"), size("crank_diameter")
    tube = _strength.tube_section(handle_d[:, None], size("handle_wall")[:, None])
    bar = _strength.tube_section(crank_d[:, None], 0.5 * crank_d[:, None])
    se_handle = _strength.endurance_limit(ult, handle_d, size("handle_notch"))
    se_crank = _strength.endurance_limit(ult, crank_d, size("crank_notch"))
    # the samples where the model carries a load; the others take the value of one of them, which
    # leaves the cycle's extremes (all fatigue reads) as they are
    ok = np.isfinite(cycle.handle_moment) & np.isfinite(cycle.crank_moment)
    first = np.argmax(ok, axis=-1)[..., None]

    def fill(v):
        return np.where(ok, v, np.take_along_axis(v, first, -1))

    handle = _strength.fatigue(fill(cycle.handle_moment), fill(cycle.handle_axial), tube, se_handle, ult)
    crank = _strength.fatigue(fill(cycle.crank_moment), fill(cycle.crank_axial), bar, se_crank, ult)
    pin = np.asarray(_joints.JOINTS, dtype=object)[k]
    return Strength(np.take_along_axis(pressure, k[None], 0)[0], pin, handle, crank, (se_handle, se_crank))


def scene(lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia, masses: Masses, speed, delta,
          force, model):  # fmt: skip
    """The energy model's scene of one design solved at ``force`` (its least peak force), for
    the motion the loads are taken along; None for the quasi-static model."""
    design = (lk, dead_centre_extended, dead_centre_folded, wheel_torque, inertia)
    if model == DYNAMICS:
        from pumplink.models import dynamics as _dy

        return _dy.scene(*design, masses, speed, delta, force=force)
    if model == FLYWHEEL:
        from pumplink.models import flywheel as _fw

        return _fw.scene(*design, speed, delta, solved=force)
    return None


def part_checks(syn, c, sizes, index, least, masses, judged) -> dict:
    """The values of the verdict's part checks (docs/workshop.md §2) of many designs: the loads
    under the model that decided against the part sizes, where ``judged`` (NaN elsewhere).

    Parameters
    ----------
    syn : the synthesis (:class:`pumplink.mechanisms.fourbar.Synthesis`: the linkage and its dead
        centres, arrays over designs).
    c : the design columns by name (``dead_band``, ``wheel_torque``, ``inertia``, ``speed``,
        ``speed_fluctuation``, ``rope_force``, ``wheel_mass``; arrays over designs or scalars).
    sizes : the part sizes, the attributes :data:`PART_KEYS` [m; notch factors -] (scalars or
        arrays over designs: the spec's ``[parts]``).
    index : the deciding model of each design, an index into :data:`pumplink.models.ORDER`;
        least : its least peak force [N];  masses : the links' (:class:`pumplink.models.Masses`;
        the arms at the grip are the operator's, not a part);  judged : bool mask over designs.

    Returns
    -------
    dict of arrays over designs: ``pin_pressure`` [MPa], ``handle_fatigue`` and ``crank_fatigue``
    (fatigue safety factors [-]).  The quasi-static and the full-dynamics designs in blocks at
    once, the flywheel's one at a time.
    """
    n = judged.size
    out = {k: np.full(n, np.nan) for k in ("pin_pressure", "handle_fatigue", "crank_fatigue")}
    coupler, handle = (np.broadcast_to(np.asarray(v, float), (n,)) for v in (masses.coupler, masses.handle))
    model = np.asarray(index, int)
    wheel_mass = np.broadcast_to(np.asarray(c["wheel_mass"], float), (n,))
    weight = np.where(np.isnan(wheel_mass), 0.0, wheel_mass) * GRAVITY

    def part_sizes(rows):
        """The part sizes of designs ``rows`` (an index: arrays; one design: numpy floats)."""
        return SimpleNamespace(
            **{k: np.broadcast_to(np.asarray(getattr(sizes, k), float), (n,))[rows] for k in PART_KEYS}
        )

    def columns(block, keys):
        """The block's linkage, part sizes and design columns ``keys`` (arrays over the block)."""
        take = {k: np.broadcast_to(np.asarray(c[k], float), (n,))[block] for k in keys}
        lk = FourBar(*(np.broadcast_to(np.asarray(v, float), (n,))[block] for v in syn.linkage.parameters))
        return lk, part_sizes(block), take

    def store(block, st):
        out["pin_pressure"][block] = st.pin_pressure / 1e6  # [MPa]
        out["handle_fatigue"][block] = st.handle.safety
        out["crank_fatigue"][block] = st.crank.safety

    # the quasi-static designs all at once, in blocks that bound the peak search's memory
    quasi = np.nonzero(judged & (model == 0))[0]
    for block in np.array_split(quasi, -(-quasi.size // PART_BLOCK)) if quasi.size else ():
        lk, part, col = columns(block, ("dead_band", "wheel_torque", "rope_force"))
        store(block, quasi_static_strength(
            lk, syn.dead_centre_extended[block], syn.dead_centre_folded[block], col["dead_band"],
            col["wheel_torque"], col["rope_force"], weight[block], part,
        ))  # fmt: skip
    # full dynamics' designs all at once, in blocks that keep the cycle's arrays in the cache
    dyn = np.nonzero(judged & (model == ORDER.index(DYNAMICS)) & np.isfinite(least))[0]
    for block in np.array_split(dyn, -(-dyn.size // SCENE_BLOCK)) if dyn.size else ():
        lk, part, col = columns(
            block, ("wheel_torque", "inertia", "speed", "speed_fluctuation", "rope_force")
        )
        with row_buffers():
            st = dynamics_strength(
                lk, syn.dead_centre_extended[block], syn.dead_centre_folded[block], col["wheel_torque"],
                col["inertia"], Masses(coupler[block], handle[block], 0.0), col["speed"],
                col["speed_fluctuation"], least[block], col["rope_force"], weight[block], part,
            )  # fmt: skip
        store(block, st)
    for i in np.nonzero(judged & (model != 0) & (model != ORDER.index(DYNAMICS)))[0].tolist():
        lk = FourBar(*(float(np.asarray(v)[i]) for v in syn.linkage.parameters))
        dce, dcf = float(syn.dead_centre_extended[i]), float(syn.dead_centre_folded[i])
        key = ORDER[int(index[i])]
        if key != ORDER[0] and not np.isfinite(least[i]):
            continue  # no finite force keeps the wheel turning: the peak-force check fails it
        links = Masses(coupler[i], handle[i], 0.0)  # the hand is the operator's, not a part
        sc = scene(lk, dce, dcf, c["wheel_torque"][i], c["inertia"][i], links, c["speed"][i],
                   c["speed_fluctuation"][i], float(least[i]), key)  # fmt: skip
        loads = part_loads(
            lk, dce, dcf, c["dead_band"][i], c["wheel_torque"][i], key, sc, c["rope_force"][i], weight[i]
        )
        store(i, strength(loads, part_sizes(i)))
    return out


#: numpy's ufunc buffer [elements] while full dynamics' part checks run.  numpy 2.3 and later
#: (2.3.5 and 2.4.6 measured) run a ufunc on a (designs, angles) array and a (designs, 1) column
#: by copying the column, repeated, into a buffer of this many elements (8,192 by default) for
#: longer inner loops; a cycle's row of 1,444 angles fills more than half of 2,048, so its rows run
#: as they lie, without the copy: a product 0.27 ns an element instead of 0.58-0.61 ns, about 5 % of
#: a tolerance study's time.  numpy 2.2.6 is slower so (0.70 ns against 0.42 ns): before 2.3 the
#: buffer is left alone.  The same operations on each element, so the same values.
ROW_BUFFER = 2048
#: The first numpy whose ufuncs gain from :data:`ROW_BUFFER`.
ROW_BUFFER_NUMPY = "2.3.0"


@contextmanager
def row_buffers(size: int = ROW_BUFFER):
    """numpy's ufunc buffer set to ``size`` elements within the block (np.setbufsize; this
    thread's, restored after), from numpy :data:`ROW_BUFFER_NUMPY` on."""
    if np.lib.NumpyVersion(np.__version__) < ROW_BUFFER_NUMPY:
        yield
        return
    old = np.setbufsize(size)
    try:
        yield
    finally:
        np.setbufsize(old)


#: Designs a block of the quasi-static part checks holds (its peak search holds ~1,500 crank angles
#: and ~30 arrays a design: ~100 MB a block).
PART_BLOCK = 256
#: Designs a block of full dynamics' part checks holds: their scenes and the zooms of their peak
#: search at once (fewer, longer calls); their cycles (~1,450 crank angles a design) are computed
#: CYCLE_ROWS designs at a time, arrays that stay in the processor's cache.  A block of 256 held
#: more than glibc's trim threshold at once (pumplink.malloc): its pages were faulted in again.
SCENE_BLOCK = 128
CYCLE_ROWS = 32


__all__ = [
    "CYCLE_ROWS",
    "CYCLE_SAMPLES",
    "PART_BLOCK",
    "SCENE_BLOCK",
    "ROW_BUFFER",
    "ROW_BUFFER_NUMPY",
    "row_buffers",
    "PART_KEYS",
    "dynamics_strength",
    "part_checks",
    "peak_candidates",
    "FATIGUE_FAIL",
    "FATIGUE_WARN",
    "PIN_PRESSURE_FAIL",
    "PIN_PRESSURE_WARN",
    "PartLoads",
    "Strength",
    "cycle_angles",
    "part_loads",
    "quasi_static_cycle",
    "quasi_static_strength",
    "scene",
    "strength",
]

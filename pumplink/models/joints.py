"""Forces on the four joints of the pump linkage over the cycle (Newton-Euler, docs/workshop.md §1).

The joints
----------
Product coordinates (docs/physics.md §1): origin at the wheel axle O2, x horizontal, y up, crank
angle t CCW from +x; crank pin A = crank (cos t, sin t); coupler-rocker pin B; rocker pivot O4;
grip P = O4 + H e on the rocker's line (e the rocker's unit vector).  Each joint force is reported as
the force **on** one named body, in N:

* ``crank_pin`` (A): on the coupler, from the crank;
* ``coupler_pin`` (B): on the coupler, from the handle (the rocker extended to the grip);
* ``rocker_pivot`` (O4): on the handle, from the stand;
* ``axle`` (O2): on the wheel and crank, from the stand's bearings.  It is the crank-pin force
  carried through the crank plus the vertical loads given as ``rope_pull`` (the sum of the two
  rope strands' tensions; both strands of a rope pump leave the wheel downwards) and
  ``wheel_weight``.  With both 0 (the default) it is the **linkage's share** of the axle load only.

The bodies (the scene of docs/models.md §3a)
-------------------------------------------
The crank is part of the wheel (its inertia is in J, its weight is not modelled, as in the energy
models).  The coupler is a uniform bar A-B of mass ``masses.coupler`` (centre at (A + B)/2, moment
of inertia m k^2/12 about it); the handle a uniform bar from O4 along the rocker of length
L = max(H, rocker) and mass ``masses.handle``, with the point mass ``masses.grip`` at P.  The
operator pushes horizontally at P with the force F (+x positive).  Given the crank's angle t, speed
w and acceleration a, the links' motion follows from the loop closure: with u = B - A,
r = B - O4 and S = u x r,

    h3 = (V . r) / S,  h4 = (V . u) / S,  V = -dA/dt                        (velocity coefficients)
    d3 = (R . r) / S,  d4 = (R . u) / S,  R = -d2A/dt2 + h3^2 u - h4^2 r     (their derivatives)
    w3 = h3 w,  a3 = h3 a + d3 w^2  (coupler);  w4 = h4 w,  a4 = h4 a + d4 w^2  (handle)

(the formulas of :func:`pumplink.models.dynamics_terms.terms`).  Newton-Euler, with g = (0, -g_n):

    coupler:  R_A + R_B + m_c g = m_c a_Gc,     u x R_B - (u/2) x m_c (a_Gc - g) = I_c a3      (J1)
    handle:   R_O4 - R_B + F ex + (m_h + m_p) g = m_h a_Gh + m_p a_P                            (J2)
              -(r x R_B) + (P - O4) x F ex + sum of the weights' moments about O4 = I_O4 a4     (J3)
    wheel:    R_O2 - R_A - (rope_pull + wheel_weight) ey = 0  (its centre of mass on the axle) (J4)

(the coupler's moment equation (J1) is taken about its centre and R_A eliminated with its force
equation).  The two moment equations give R_B from a 2 x 2 system of determinant -S (never zero in a
crank-rocker); then R_A, R_O4 and R_O2 follow.  The torque the crank pin puts on the wheel,
T = A x (-R_A), closes the wheel's moment balance J a = T - Mw: for the model's motion this is the
model's equation of motion, which the tests check against virtual work.

The models' motions
-------------------
:func:`quasi_static_motion` (no speed, massless links, F = Mw / g: docs/models.md §1),
:func:`flywheel_motion` (massless links, F and w of the flywheel scene, a = (F g - Mw)/J: §2) and
:func:`dynamics_motion` (the masses, F and w of the full-dynamics scene, a from its equation of
motion I a + I' w^2 / 2 + V' = F g - Mw: §3a) give the motion the joint forces are taken along.

Pure functions on floats / numpy arrays (broadcasting over crank angles and designs); SI units,
radians.  The peak over the cycle: :func:`peak_joint_forces` per design, :func:`cycle_peak_loads`
and :func:`quasi_static_peak_loads` for many designs at once.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from pumplink.constants import GRAVITY
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar, kinematic_state
from pumplink.mechanisms.fourbar_kernel import loop_closure
from pumplink.models import Masses

#: The joints in the order of :attr:`JointForces.magnitudes` and :class:`PeakLoads`.
JOINTS = ("axle", "crank_pin", "coupler_pin", "rocker_pivot")


@dataclass(frozen=True)
class Motion:
    """The motion the joint forces are taken along (arrays broadcast over crank angles).

    Attributes
    ----------
    crank_angle : t [rad];  crank_speed : w = dt/dtime [rad/s];  crank_acceleration : a [rad/s^2].
    operator_force : F, horizontal at the grip, +x positive [N].
    masses : the moving link masses and the point mass at the grip [kg] (zero: massless links).
    closure : the loop closure at the crank angles where the model has it already
        (:attr:`pumplink.models.dynamics_terms.Terms.closure`: the values the joint forces would
        compute), else None.
    """

    crank_angle: np.ndarray
    crank_speed: np.ndarray
    crank_acceleration: np.ndarray
    operator_force: np.ndarray
    masses: Masses = Masses()
    closure: tuple | None = None


@dataclass(frozen=True)
class JointForces:
    """Joint forces and the internal loads of the crank and the handle at crank angles (SI units).

    The force vectors have shape (2, ...) (x, y), each the force **on** the body named in the module
    docstring: ``crank_pin`` on the coupler at A, ``coupler_pin`` on the coupler at B,
    ``rocker_pivot`` on the handle at O4, ``axle`` on the wheel at O2 [N].

    Attributes
    ----------
    crank_torque : T = A x (-R_A), the torque the crank pin puts on the wheel [N m] (J a = T - Mw).
    crank_moment, crank_axial : bending moment [N m] and axial force [N] (tension positive) in the
        crank at the axle, where it is fixed to the wheel (the crank is massless there:
        crank_moment = -crank_torque).
    handle_moment, handle_axial : bending moment [N m] and axial force [N] (tension positive) in the
        handle at the coupler pin B, on the pivot side (the section that carries the coupler's
        push; the moment is continuous across B).  The sign of a moment is CCW positive for the
        part of the link nearer the frame; it only matters for telling the two fibres apart.
    """

    crank_pin: np.ndarray
    coupler_pin: np.ndarray
    rocker_pivot: np.ndarray
    axle: np.ndarray
    crank_torque: np.ndarray
    crank_moment: np.ndarray
    crank_axial: np.ndarray
    handle_moment: np.ndarray
    handle_axial: np.ndarray

    @property
    def magnitudes(self) -> np.ndarray:
        """|force| of the joints in the order of :data:`JOINTS`, shape (4, ...) [N]."""
        return np.stack([np.hypot(*getattr(self, name)) for name in JOINTS])


def joint_forces(
    lk: FourBar,
    crank_angle,
    crank_speed,
    crank_acceleration,
    operator_force,
    masses: Masses = Masses(),
    gravity=GRAVITY,
    rope_pull=0.0,
    wheel_weight=0.0,
    closure=None,
) -> JointForces:
    """Joint forces from Newton-Euler on the coupler and the handle, Eq. (J1)-(J4) of the module.

    Parameters
    ----------
    lk : the linkage (floats or arrays broadcastable with the angles).
    crank_angle : t [rad];  crank_speed : w [rad/s];  crank_acceleration : a [rad/s^2].
    operator_force : F at the grip, horizontal, +x positive [N].
    masses : coupler, handle and grip masses [kg] (:class:`pumplink.models.Masses`; zero: massless).
    gravity : g_n [m/s^2].
    rope_pull : sum of the rope strands' tensions pulling the wheel down [N] (0: the linkage's
        share of the axle load only; docs/workshop.md §1).
    wheel_weight : weight of the wheel, crank and axle [N], carried by the axle.
    closure : the loop closure at the crank angles (:attr:`Motion.closure`), or None: found here.

    Returns
    -------
    JointForces
        NaN where the linkage cannot be assembled.
    """
    th = np.asarray(crank_angle, float)
    w = np.asarray(crank_speed, float)
    acc = np.asarray(crank_acceleration, float)
    force = np.asarray(operator_force, float)
    with np.errstate(all="ignore"):  # a non-assemblable linkage gives NaN, by design
        c = _joint_forces(lk, th, w, acc, force, masses, gravity, rope_pull, wheel_weight, closure)
    return JointForces(
        np.stack(c[0:2]), np.stack(c[2:4]), np.stack(c[4:6]), np.stack(c[6:8]), c[8], -c[8], *c[9:]
    )


def _joint_forces(lk, th, w, acc, force, masses, gravity, rope_pull, wheel_weight, closure=None, axial=True):
    """The components of :class:`JointForces`: R_A, R_B, R_O4, R_O2 (x, y each), the crank torque,
    the crank's axial force, the handle's moment and its axial force (None without ``axial``)."""
    px, py, c, k, r = lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker
    hh = lk.handle
    mc, mh, mp = masses.coupler, masses.handle, masses.grip
    if closure is None:
        cs, sn = np.cos(th), np.sin(th)
        _p1, _p2, _e2, t, q = loop_closure(lk, cs, sn)
        ax, ay = c * cs, c * sn  # the crank pin A
        dx, dy = px - ax, py - ay  # O4 - A
        ux, uy = t * dx - q * dy, t * dy + q * dx  # u = B - A (Eq. (6) of pumplink.mechanisms.fourbar)
        rx, ry = ux - dx, uy - dy  # r = B - O4
        s = ux * ry - uy * rx  # u x r
    else:  # the same, from the motion's terms
        cs, sn, ax, ay, dx, dy, ux, uy, rx, ry, s = closure
    # velocity coefficients and their derivatives (unit crank speed, no crank acceleration)
    vx, vy = ay, -ax  # V = -dA/dt
    h3 = (vx * rx + vy * ry) / s
    h4 = (vx * ux + vy * uy) / s
    h33, h44 = h3 * h3, h4 * h4  # each square once (the same values wherever it is used)
    qx = ax + h33 * ux - h44 * rx  # R = -d2A/dt2 + h3^2 u - h4^2 r
    qy = ay + h33 * uy - h44 * ry
    d3 = (qx * rx + qy * ry) / s
    d4 = (qx * ux + qy * uy) / s
    w2 = w * w
    w3, w4 = h3 * w, h4 * w
    w33, w44 = w3 * w3, w4 * w4
    a3 = h3 * acc + d3 * w2  # coupler's angular acceleration
    a4 = h4 * acc + d4 * w2  # handle's
    # accelerations: A on the crank; the coupler's centre A + u/2; points s e on the handle
    aax, aay = -ay * acc - ax * w2, ax * acc - ay * w2
    gcx = aax - 0.5 * (a3 * uy + w33 * ux)
    gcy = aay + 0.5 * (a3 * ux - w33 * uy)
    ex, ey = rx / r, ry / r  # the handle's direction
    ptx, pty = -a4 * ey - w44 * ex, a4 * ex - w44 * ey  # acceleration per metre along it
    arm = np.maximum(hh, r)  # the handle bar's length (docs/models.md §3a)
    i_c = mc * k * k / 12.0
    i_o4 = mh * arm * arm / 3.0 + mp * hh * hh
    # (J3): r x R_B = (P - O4) x F ex + weights' moments - I_O4 a4
    m_h = -hh * ey * force - gravity * ex * (0.5 * mh * arm + mp * hh) - i_o4 * a4
    # (J1): u x R_B = I_c a3 + (u/2) x m_c (a_Gc - g)
    fcx, fcy = mc * gcx, mc * (gcy + gravity)  # m_c (a_Gc - g)
    m_c = i_c * a3 + 0.5 * (ux * fcy - uy * fcx)
    # [[-ry, rx], [-uy, ux]] R_B = [m_h, m_c], determinant -s
    minus_s = -s
    bx_ = (m_h * ux - rx * m_c) / minus_s
    by_ = (uy * m_h - ry * m_c) / minus_s
    ax_, ay_ = fcx - bx_, fcy - by_  # (J1): R_A = m_c (a_Gc - g) - R_B
    # (J2): R_O4 = R_B - F ex + m_h (a_Gh - g) + m_p (a_P - g)
    lever = 0.5 * mh * arm + mp * hh  # first moment of the handle's masses about O4
    ox_ = bx_ - force + lever * ptx
    oy_ = by_ + lever * pty + (mh + mp) * gravity
    # (J4)
    wx_, wy_ = ax_, ay_ + (rope_pull + wheel_weight)
    torque = -(ax * ay_ - ay * ax_)  # A x (-R_A)
    # the handle on the pivot side of B: the bar's part [0, rocker] of mass m1, loaded by R_O4 and its
    # weight; the outer part's force on it F_in = m1 (a_G1 - g) - R_O4 and, about O4,
    # M + r x F_in + (r/2) e x m1 g = I1 a4 (a handle shorter than the rocker has no such section)
    m1 = mh * r / arm
    fix = m1 * 0.5 * r * ptx - ox_
    fiy = m1 * (0.5 * r * pty + gravity) - oy_
    moment = m1 * r * r / 3.0 * a4 - (rx * fiy - ry * fix) + 0.5 * r * ex * m1 * gravity
    outside = hh >= r  # a grip inside the rocker: no section beyond B
    if not np.all(outside):
        moment = np.where(outside, moment, np.nan)
    # the crank's root carries the pin force's moment about the axle: crank_moment = -torque
    crank_axial = (
        -(ax_ * cs + ay_ * sn) if axial else None
    )  # -R_A . e_crank: the pin pulls the crank outward = tension
    handle_axial = fix * ex + fiy * ey if axial else None  # the outer part pulling along +e: tension
    return ax_, ay_, bx_, by_, ox_, oy_, wx_, wy_, torque, crank_axial, moment, handle_axial


def motion_loads(lk: FourBar, motion: Motion, gravity=GRAVITY, rope_pull=0.0, wheel_weight=0.0, fatigue=True,
                 out=None, squares=False, read=None):  # fmt: skip
    """The loads a peak search and a fatigue check read along a :class:`Motion`, without the force
    vectors of :func:`motion_forces` (the same values): :func:`six_loads`, shape (6, ...) (written
    into ``out`` where given), and, with ``fatigue``, the handle's and the crank's bending
    moments and axial forces (a tuple ``(handle_moment, handle_axial, crank_moment,
    crank_axial)``; else None).  ``squares``: the four joints' x^2 + y^2 instead of their
    magnitudes (np.hypot where that is NaN: inf where a component is), to rank them by
    (:func:`pumplink.models.parts.peak_candidates`).  ``read``: the joints' magnitudes only on
    the rows (the first axis of the crank angles) where ``read`` (6, rows) holds (np.hypot costs as
    much as the rest of the joint forces), NaN on the others; None: everywhere."""
    with np.errstate(all="ignore"):  # a non-assemblable linkage gives NaN, by design
        ax_, ay_, bx_, by_, ox_, oy_, wx_, wy_, torque, crank_axial, moment, handle_axial = _joint_forces(
            lk, *(np.asarray(v, float) for v in (motion.crank_angle, motion.crank_speed,
                                                 motion.crank_acceleration, motion.operator_force)),
            motion.masses, gravity, rope_pull, wheel_weight, motion.closure, fatigue,
        )  # fmt: skip
        out = np.empty((6,) + np.shape(torque)) if out is None else out
        for i, (x, y) in enumerate(((wx_, wy_), (ax_, ay_), (bx_, by_), (ox_, oy_))):  # JOINTS' order
            if squares:
                np.multiply(x, x, out=out[i])
                np.add(out[i], y * y, out=out[i])
                if np.isnan(out[i]).any():  # a masked ufunc is slow: only where needed
                    np.hypot(x, y, out=out[i], where=np.isnan(out[i]))
            elif read is None or read[i].all():
                np.hypot(x, y, out=out[i])
            else:
                out[i] = np.nan
                rows = np.nonzero(read[i])[0]
                out[i, rows] = np.hypot(x[rows], y[rows])
        np.abs(torque, out=out[4])  # |crank moment| = |-torque|
        np.abs(moment, out=out[5])
        return out, ((moment, handle_axial, -torque, crank_axial) if fatigue else None)


# ----------------------------------------------------------------------------- the models' motions
def quasi_static_motion(lk: FourBar, crank_angle, wheel_torque) -> Motion:
    """The quasi-static model's motion (docs/models.md §1): no speed, massless links,
    F = Mw / (dPx/dt) (Eq. (3) of the pump paper); NaN at a dead centre."""
    th = np.asarray(crank_angle, float)
    st = kinematic_state(lk, th, wheel_torque)
    zero = np.zeros(np.shape(st.force))
    return Motion(th, zero, zero, st.force)


def flywheel_motion(scene, crank_angle) -> Motion:
    """The flywheel scene's motion (docs/models.md §2): massless links, the reported force profile
    F(t) and wheel speed w(t), and a = (F g - Mw) / J (its Eq. (1) in time).

    Parameters
    ----------
    scene : :class:`pumplink.models.flywheel.Scene` with a finite least peak force.
    crank_angle : t [rad].
    """
    from pumplink.models import flywheel as fw

    th = np.asarray(crank_angle, float)
    force = np.asarray(fw.operator_force(scene, th), float)
    speed = np.asarray(fw.wheel_speed(scene, th), float)
    g = kinematic_state(scene.linkage, th, 1.0).handle_rate
    acc = (force * g - scene.wheel_torque) / scene.inertia  # Eq. (1) of docs/models.md §2 in time
    return Motion(th, speed, acc, force)


def dynamics_motion(scene, crank_angle, trig=None) -> Motion:
    """The full-dynamics scene's motion (docs/models.md §3a): its masses, force profile F(t) and
    wheel speed w(t), and a from its equation of motion I a + I' w^2 / 2 + V' = F g - Mw.

    Parameters
    ----------
    scene : :class:`pumplink.models.dynamics.Scene` with a finite least peak force.
    crank_angle : t [rad].
    trig : (cos t, sin t) where known already (the same values; Scenes' crank angles only).
    """
    from pumplink.models import dynamics as dy
    from pumplink.models import dynamics_terms as dt

    th = np.asarray(crank_angle, float)
    force, speed, tm = dy.motion_state(scene, np.atleast_1d(th), trig)
    force, speed = force.reshape(th.shape), speed.reshape(th.shape)
    closure = tuple(np.reshape(v, th.shape) for v in tm.closure)
    tm = dt.Terms(
        **{k: None if v is None else np.reshape(v, th.shape) for k, v in vars(tm).items() if k != "closure"}
    )
    rhs = force * tm.grip_rate - scene.wheel_torque - tm.potential_rate - 0.5 * tm.inertia_rate * speed**2
    acc = rhs / (scene.inertia + tm.inertia)  # Eq. (7) of pumplink.models.dynamics_terms in time
    return Motion(th, speed, acc, force, scene.masses, closure)


def motion_forces(lk: FourBar, motion: Motion, gravity=GRAVITY, rope_pull=0.0, wheel_weight=0.0):
    """:func:`joint_forces` along a :class:`Motion`."""
    return joint_forces(
        lk,
        motion.crank_angle,
        motion.crank_speed,
        motion.crank_acceleration,
        motion.operator_force,
        motion.masses,
        gravity,
        rope_pull,
        wheel_weight,
        motion.closure,
    )


# ----------------------------------------------------------------------------- peaks over the cycle
#: Grid points per radian of crank angle on which the peak search starts (about 2 per degree).
PEAK_GRID_PER_RAD = 120
#: Offset [rad] of the extra nodes either side of a point where the motion may jump (a dead centre,
#: where the energy models' push reverses): the one-sided limits are sampled there.
JUMP_OFFSET = 1e-9
#: Absolute tolerance [rad] of the bracketed refinement of each peak: a smooth maximum's value is
#: then off by about |F''| XTOL^2 / 2, some 1e-14 of it; a supremum at a jump is the node's value.
REFINE_XTOL = 1e-7
#: Points across a bracket per zoom of the refinement (the bracket shrinks (points - 1) / 2 = 16
#: times a zoom: five zooms from a grid cell to REFINE_XTOL).
ZOOM_POINTS = 33
#: Grid points on each of the quasi-static model's two arcs (the density of PEAK_GRID_PER_RAD on
#: a whole turn, so on any arc).
ARC_POINTS = int(np.ceil(PEAK_GRID_PER_RAD * TWO_PI)) + 1


def _finite_or_floor(values: np.ndarray) -> np.ndarray:
    """NaN (no load defined there) as -inf, below every load, so a maximum never picks it."""
    return np.where(np.isnan(values), -np.inf, values)


@dataclass(frozen=True)
class PeakLoads:
    """Peak of each load over the searched crank angles of one design.

    Attributes
    ----------
    force : largest |joint force| per joint of :data:`JOINTS` [N], shape (4,).
    angle : crank angle of each [rad], in [0, 2 pi).
    crank_moment, handle_moment : largest |bending moment| [N m] and its crank angle [rad]
        (tuples (value, angle)).
    """

    force: np.ndarray
    angle: np.ndarray
    crank_moment: tuple
    handle_moment: tuple


def six_loads(forces: JointForces) -> np.ndarray:
    """The six magnitudes searched: the four joints, then |crank moment| and |handle moment|
    (shape (6, ...))."""
    out = np.empty((6,) + np.shape(forces.crank_moment))
    for i, name in enumerate(JOINTS):
        np.hypot(*getattr(forces, name), out=out[i])  # JointForces.magnitudes
    np.abs(forces.crank_moment, out=out[4])
    np.abs(forces.handle_moment, out=out[5])
    return out


def peak_joint_forces(
    loads_at: Callable,
    arcs=((0.0, TWO_PI),),
    jumps=(),
    nodes=None,
) -> PeakLoads:
    """Peaks of the joint forces and bending moments of one design over crank arcs.

    Each arc is scanned on a grid of :data:`PEAK_GRID_PER_RAD` points per radian including its ends,
    plus nodes :data:`JUMP_OFFSET` either side of each of ``jumps`` (where the loads may jump: the
    energy models reverse the push at the dead centres); the best node of each load is refined
    between its neighbours by zooming, all six loads at once: :data:`ZOOM_POINTS` points across
    the bracket, the best one's neighbours the next bracket, to :data:`REFINE_XTOL`; the largest
    value met is kept.  A smooth interior maximum is then exact
    to the tolerance; a supremum at a jump is the node's one-sided value, within the load's slope
    times JUMP_OFFSET of it.  Features narrower than a grid cell (0.5 deg) may be merged, as in the
    models' own peak searches.

    Parameters
    ----------
    loads_at : callable of crank angles (1-D array) returning :class:`JointForces` over them.
    arcs : (start, length) pairs [rad] to search (the whole turn by default).
    jumps : crank angles [rad] where the loads may jump.
    nodes : (angles, JointForces) already computed on a grid of at least the density above, to
        start from instead of the grid (the jumps' nodes are still added); one whole-turn arc.

    Returns
    -------
    PeakLoads
    """
    if nodes is None:
        grid = np.concatenate(
            [start + np.linspace(0.0, length, max(int(np.ceil(PEAK_GRID_PER_RAD * length)), 2) + 1)
             for start, length in arcs]
        )  # fmt: skip
        given = None
    else:
        grid, given = np.asarray(nodes[0], float), six_loads(nodes[1])
    extra = []
    for j in jumps:
        for start, length in arcs:
            off = np.mod(j - start, TWO_PI)
            if off <= length:
                e = start + off + np.array([-JUMP_OFFSET, JUMP_OFFSET])
                extra.append(e[(e >= start) & (e <= start + length)])
    extra = np.concatenate(extra) if extra else np.zeros(0)
    if given is None:
        grid = np.concatenate([grid, extra])
        vals = six_loads(loads_at(grid))
    else:
        vals = np.concatenate([given, six_loads(loads_at(extra))], axis=1) if extra.size else given
        grid = np.concatenate([grid, extra])
    order = np.argsort(grid, kind="stable")
    grid, vals = grid[order], _finite_or_floor(vals[:, order])  # (6, N)
    j = np.argmax(vals, axis=1)
    best, where = vals[np.arange(6), j], grid[j]
    lo_arc = np.array([s for s, _ in arcs])
    hi_arc = np.array([s + n for s, n in arcs])
    a, b = grid[np.maximum(j - 1, 0)], grid[np.minimum(j + 1, grid.size - 1)]
    inside = ((lo_arc <= a[:, None]) & (b[:, None] <= hi_arc)).any(axis=1)  # neighbours on one arc
    live = np.isfinite(best) & inside & (b > a)
    # zoom on every load's bracket at once: REFINE_POINTS points across it, then the cells either
    # side of the best point, until the bracket is narrower than REFINE_XTOL (a smooth maximum
    # inside a grid cell stays inside the bracket, as in a bounded golden-section search)
    steps = np.linspace(0.0, 1.0, ZOOM_POINTS)
    while live.any():
        rows = np.nonzero(live)[0]
        x = a[rows, None] + (b - a)[rows, None] * steps  # (k, ZOOM_POINTS)
        v = _finite_or_floor(six_loads(loads_at(x.ravel())))[rows].reshape(rows.size, -1, ZOOM_POINTS)
        v = v[np.arange(rows.size), np.arange(rows.size)]  # load i at its own points
        k = np.argmax(v, axis=1)
        up = v[np.arange(rows.size), k] > best[rows]
        best[rows[up]], where[rows[up]] = v[np.arange(rows.size), k][up], x[np.arange(rows.size), k][up]
        a[rows] = x[np.arange(rows.size), np.maximum(k - 1, 0)]
        b[rows] = x[np.arange(rows.size), np.minimum(k + 1, ZOOM_POINTS - 1)]
        live[rows] = (b[rows] - a[rows]) > REFINE_XTOL
    best = np.where(best == -np.inf, np.nan, best)
    where = np.mod(where, TWO_PI)
    return PeakLoads(best[:4], where[:4], (best[4], where[4]), (best[5], where[5]))


def quasi_static_peaks(
    lk: FourBar,
    dead_centre_extended,
    dead_centre_folded,
    dead_band,
    wheel_torque,
    rope_pull=0.0,
    wheel_weight=0.0,
):
    """Peak joint forces of the quasi-static model (one design) outside ±dead_band of the dead
    centres, where it is judged (docs/models.md §1; the force is infinite at the dead centres):
    :func:`quasi_static_peak_loads` for one design, as :class:`PeakLoads`.

    Parameters
    ----------
    lk : linkage (one design);  dead_centre_extended, dead_centre_folded : [rad];
    dead_band : [rad];  wheel_torque : Mw [N m];  rope_pull, wheel_weight : [N] on the axle, as
    :func:`joint_forces`.
    """
    value, angle = quasi_static_peak_loads(
        FourBar(*(np.reshape(np.asarray(v, float), (1,)) for v in lk.parameters)),
        *(np.reshape(np.asarray(v, float), (1,)) for v in (dead_centre_extended, dead_centre_folded)),
        *(np.reshape(np.asarray(v, float), (1,)) for v in (dead_band, wheel_torque, rope_pull, wheel_weight)),
    )
    best, where = value[:, 0], angle[:, 0]
    return PeakLoads(best[:4], where[:4], (best[4], where[4]), (best[5], where[5]))


def quasi_static_peak_loads(
    lk: FourBar,
    dead_centre_extended,
    dead_centre_folded,
    dead_band,
    wheel_torque,
    rope_pull=0.0,
    wheel_weight=0.0,
):
    """Peaks of the six loads of :func:`peak_joint_forces` under the quasi-static model, for many
    designs at once, outside ±dead_band of the dead centres (docs/models.md §1).

    The two arcs between the dead bands are each scanned on :data:`ARC_POINTS` points (at least
    :data:`PEAK_GRID_PER_RAD` per radian, whatever the arc's length); the best node of each load
    and design is refined by zooming inside its arc, all loads and designs at once
    (:data:`ZOOM_POINTS` points a bracket, to :data:`REFINE_XTOL`), as :func:`peak_joint_forces`
    does for one design.

    Parameters
    ----------
    lk : linkage whose parameters are arrays of shape (n,);  dead_centre_extended,
    dead_centre_folded, dead_band : [rad], shape (n,);  wheel_torque : Mw [N m];  rope_pull,
    wheel_weight : [N] on the axle, as :func:`joint_forces` (shape (n,) or scalars).

    Returns
    -------
    value, angle : arrays of shape (6, n): the four joints of :data:`JOINTS` [N], then |crank
        moment| and |handle moment| [N m], and the crank angle of each [rad] in [0, 2 pi); NaN
        where a design has no assemblable point outside its dead bands.
    """
    dce = np.asarray(dead_centre_extended, float).reshape(-1)
    n = dce.size
    dcf, band, torque, rope, weight = (
        np.broadcast_to(np.asarray(v, float), (n,)) for v in (dead_centre_folded, dead_band, wheel_torque,
                                                              rope_pull, wheel_weight)
    )  # fmt: skip
    column = FourBar(*(np.reshape(np.asarray(v, float), (n, 1)) for v in lk.parameters))

    def loads_at(th):  # (n, k) crank angles -> (6, n, k) loads, NaN as -inf
        motion = quasi_static_motion(column, th, torque[:, None])
        forces = motion_forces(column, motion, GRAVITY, rope[:, None], weight[:, None])
        return _finite_or_floor(six_loads(forces))

    plus = np.mod(dcf - dce, TWO_PI)
    start = np.stack([dce + band, dcf + band], axis=1)  # (n, 2): the two arcs judged
    length = np.stack([plus - 2 * band, TWO_PI - plus - 2 * band], axis=1)
    arc_ok = length >= 0
    length = np.where(arc_ok, length, 0.0)
    m = ARC_POINTS  # the same for every design, so a design's peaks do not depend on its batch
    grid = start[:, :, None] + length[:, :, None] * np.linspace(0.0, 1.0, m)  # (n, 2, m)
    vals = loads_at(grid.reshape(n, 2 * m)).reshape(6, n, 2, m)
    vals = np.where(arc_ok[None, :, :, None], vals, -np.inf).reshape(6, n, 2 * m)
    j = np.argmax(vals, axis=-1)  # (6, n)
    best = np.take_along_axis(vals, j[..., None], -1)[..., 0]
    arc, pos = np.divmod(j, m)
    design = np.arange(n)[None, :]
    where = grid[design, arc, pos]
    a = grid[design, arc, np.maximum(pos - 1, 0)]  # the bracket: the neighbours on the same arc
    b = grid[design, arc, np.minimum(pos + 1, m - 1)]
    live = np.isfinite(best) & (b > a)
    steps = np.linspace(0.0, 1.0, ZOOM_POINTS)
    six = np.arange(6)
    while live.any():
        x = a[..., None] + (b - a)[..., None] * steps  # (6, n, R)
        v = loads_at(x.transpose(1, 0, 2).reshape(n, 6 * ZOOM_POINTS)).reshape(6, n, 6, ZOOM_POINTS)
        v = v[six, :, six]  # load i at its own points: (6, n, R)
        k = np.argmax(v, axis=-1)
        top = np.take_along_axis(v, k[..., None], -1)[..., 0]
        up = live & (top > best)
        best = np.where(up, top, best)
        where = np.where(up, np.take_along_axis(x, k[..., None], -1)[..., 0], where)
        left, right = np.maximum(k - 1, 0), np.minimum(k + 1, ZOOM_POINTS - 1)
        a = np.where(live, np.take_along_axis(x, left[..., None], -1)[..., 0], a)
        b = np.where(live, np.take_along_axis(x, right[..., None], -1)[..., 0], b)
        live = live & ((b - a) > REFINE_XTOL)
    return np.where(best == -np.inf, np.nan, best), np.mod(where, TWO_PI)


def cycle_peak_loads(loads_at: Callable, grid, loads):
    """:func:`peak_joint_forces` from given nodes (``nodes``: one whole-turn arc, no jumps added)
    for many designs at once: the same grid, brackets and zooms per design (a design's peaks do
    not depend on its batch), the zooms of all designs and loads at once.  Loads of a design
    whose brackets are the same (the joints next to a jump often peak at the same node) share
    the points of a zoom: the same points, so the same values.

    Parameters
    ----------
    loads_at : callable of designs (R,) (indices of the D, repeats allowed), crank angles (R, k)
        and the loads read of each ((6, R) bool), returning their :func:`six_loads`, shape
        (6, R, k) (a load not read may hold any value).
    grid : (D, K) crank angles [rad] in [0, 2 pi): at least :data:`PEAK_GRID_PER_RAD` a radian,
        with the nodes :data:`JUMP_OFFSET` either side of each point where the loads may jump.
    loads : (6, D, K), :func:`six_loads` of the joint forces at ``grid`` (where the grid is sorted,
        its NaN are overwritten with -inf).

    Returns
    -------
    value, angle : arrays of shape (6, D), as :func:`quasi_static_peak_loads`.
    """
    grid = np.asarray(grid, float)
    n, m = grid.shape
    if (grid[:, 1:] >= grid[:, :-1]).all():  # sorted already (a stable sort leaves it as it is)
        vals = loads  # (6, D, K), NaN as -inf in place
        np.copyto(vals, -np.inf, where=np.isnan(vals))
    else:
        order = np.argsort(grid, axis=1, kind="stable")
        grid = np.take_along_axis(grid, order, axis=1)
        vals = _finite_or_floor(np.take_along_axis(loads, order[None], axis=2))
    j = np.argmax(vals, axis=2)  # (6, D)
    best = np.take_along_axis(vals, j[..., None], 2)[..., 0]
    design = np.arange(n)[None, :]
    where = grid[design, j]
    left, right = np.maximum(j - 1, 0), np.minimum(j + 1, m - 1)
    a, b = grid[design, left], grid[design, right]
    # each load's value at its bracket's ends, points met already (on the grid, then in a zoom)
    at_a = np.take_along_axis(vals, left[..., None], 2)[..., 0]
    at_b = np.take_along_axis(vals, right[..., None], 2)[..., 0]
    live = np.isfinite(best) & (0.0 <= a) & (b <= TWO_PI) & (b > a)  # neighbours on the arc
    steps = np.linspace(0.0, 1.0, ZOOM_POINTS)
    slot = np.full((6, n), -1)
    while live.any():
        load, dd = np.nonzero(live)
        # the first live load of the design with the same bracket zooms for it
        same = (a[:, None, dd] == a[None, :, dd]) & (b[:, None, dd] == b[None, :, dd]) & live[:, None, dd]
        first = np.argmax(same, axis=0)[load, np.arange(load.size)]  # (L,)
        own = first == load
        slot[load[own], dd[own]] = np.arange(np.count_nonzero(own))
        pick = slot[first, dd]  # the zoom's points of each live load
        read = np.zeros((6, np.count_nonzero(own)), bool)
        read[load, pick] = True
        lo, hi = a[load[own], dd[own]], b[load[own], dd[own]]
        x = lo[:, None] + (hi - lo)[:, None] * steps  # (U, ZOOM_POINTS)
        # load i at its own points: the first point is the bracket's lower end (lo + 0), the last
        # its upper end where lo + (hi - lo) rounds to hi (all but brackets next to 0): their
        # values are known, the points between are computed
        v = np.empty((load.size, ZOOM_POINTS))
        v[:, 0], v[:, -1] = at_a[load, dd], at_b[load, dd]
        v[:, 1:-1] = _finite_or_floor(loads_at(dd[own], x[:, 1:-1], read)[load, pick])
        anew = np.nonzero(x[:, -1] != hi)[0]
        if anew.size:
            row = np.full(hi.size, -1)
            row[anew] = np.arange(anew.size)
            these = row[pick] >= 0
            last = _finite_or_floor(loads_at(dd[own][anew], x[anew, -1:], read[:, anew])[:, :, 0])
            v[these, -1] = last[load[these], row[pick[these]]]
        k = np.argmax(v, axis=1)
        top = v[np.arange(load.size), k]
        xs = x[pick]
        up = top > best[load, dd]
        best[load[up], dd[up]] = top[up]
        where[load[up], dd[up]] = xs[np.arange(load.size), k][up]
        below, above = np.maximum(k - 1, 0), np.minimum(k + 1, ZOOM_POINTS - 1)
        a[load, dd] = xs[np.arange(load.size), below]
        b[load, dd] = xs[np.arange(load.size), above]
        at_a[load, dd] = v[np.arange(load.size), below]
        at_b[load, dd] = v[np.arange(load.size), above]
        live[load, dd] = (b[load, dd] - a[load, dd]) > REFINE_XTOL
    return np.where(best == -np.inf, np.nan, best), np.mod(where, TWO_PI)


def scene_peaks(scene, motion_of: Callable, gravity=GRAVITY, rope_pull=0.0, wheel_weight=0.0, cycle=None):
    """Peak joint forces over the whole turn of an energy model's scene (one design).

    Parameters
    ----------
    scene : a flywheel or full-dynamics scene;  motion_of : :func:`flywheel_motion` or
        :func:`dynamics_motion`;  gravity, rope_pull, wheel_weight : as :func:`joint_forces`.
    cycle : (crank angles, JointForces) over the whole turn already computed (at least
        :data:`PEAK_GRID_PER_RAD` a radian, and the nodes :data:`JUMP_OFFSET` either side of each
        dead centre), the search's starting grid.
    """
    return peak_joint_forces(
        lambda th: motion_forces(scene.linkage, motion_of(scene, th), gravity, rope_pull, wheel_weight),
        jumps=() if cycle is not None else (scene.dead_centre_extended, scene.dead_centre_folded),
        nodes=cycle,
    )

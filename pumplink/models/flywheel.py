"""The flywheel scene: the wheel's inertia carries the linkage through the dead centres.

The quasi-static force (``pumplink.mechanisms.fourbar``) is infinite at both dead centres, and speed
cancels out of it.  In the pump the upper wheel and the moving rope and water are a flywheel.
This module answers the question the quasi-static model cannot: *what is the least peak
force an operator needs to keep the wheel turning at a mean speed with a bounded speed
fluctuation?*  (docs/physics.md and docs/models.md §2).

The scene
---------
Crank angle t (the wheel's angle), kinetic energy E = J w^2 / 2 of the wheel plus the rope and
water that move with its rim; link inertias are neglected (their size is estimated by
:func:`link_energy`).  The load is a constant torque Mw; the operator applies a horizontal
force F at the grip with |F| <= Fp.  Per crank radian the energy balance is

    dE/dt = F g(t) - Mw,    g = dPx/dt  (grip travel per crank radian)          (1)

which does not contain w: in the crank angle the scene is the same at every speed.

Speed fluctuation
-----------------
The coefficient of speed fluctuation is delta = (w_max - w_min) / w_bar with the mean speed
w_bar = (w_max + w_min) / 2 (the machine-design definition).  Then exactly

    E_max - E_min = J (w_max^2 - w_min^2) / 2 = J w_bar^2 delta                  (2)

so a periodic motion with mean speed w_bar and delta <= delta_allow is a periodic E(t) whose
range is at most the *energy band* W = J w_bar^2 delta_allow.  J, w_bar and delta_allow enter
the answer only through W (the scaling law, tested).

The least peak force Fp* and the energy deficit D(Fp) of Eq. (3)-(4) are
:mod:`pumplink.models.flywheel_solver`; the grip travel G, :mod:`pumplink.models.grip_travel`.
Here: the band W, the slowest passing speed, one design in detail (the reported motion, its force
profile and wheel speed, their check by time integration) and the neglected link energy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import DEFAULT_SPEED_FLUCTUATION, LINK_ENERGY_LIMIT, LINK_MASS_PER_METRE  # noqa: F401  (re-exported)
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.bracket import find_minimum
from pumplink.mechanisms.fourbar import FourBar, kinematic_state
from pumplink.mechanisms.fourbar_kernel import loop_closure
from pumplink.models import quasi_static as _qs
from pumplink.models.flywheel_solver import (
    drawdown,
    energy_deficit,
    least_peak_force,
    prepare,
    refined_extrema,
    u_integral,
)


def energy_band(inertia, mean_speed, speed_fluctuation):
    """Kinetic-energy band of a cycle, W = J w_bar^2 delta [J] (Eq. (2) of this module).

    Parameters
    ----------
    inertia : J about the axle [kg m^2];  mean_speed : w_bar = (w_max + w_min)/2 [rad/s];
    speed_fluctuation : delta = (w_max - w_min)/w_bar [-].
    """
    return np.asarray(inertia, float) * np.asarray(mean_speed, float) ** 2 * speed_fluctuation  # Eq. (2)


def min_passing_speed(
    lk: FourBar,
    dead_centre_extended,
    dead_centre_folded,
    wheel_torque,
    force_limit,
    inertia,
    speed_fluctuation,
):
    """Least mean wheel speed [rad/s] at which ``force_limit`` suffices: w = sqrt(D(F_limit) / (J delta)).

    From Eq. (2)-(3) (:mod:`pumplink.models.flywheel_solver`): the design passes iff
    D(F_limit) <= J w_bar^2 delta.  Infinite when the limit is below F_mean (no speed helps), NaN
    for an infeasible design.
    """
    need = energy_deficit(lk, dead_centre_extended, dead_centre_folded, wheel_torque, force_limit)
    with np.errstate(all="ignore"):
        return np.sqrt(need / (np.asarray(inertia, float) * speed_fluctuation))


# ----------------------------------------------------------------------------- one design in detail
@dataclass(frozen=True)
class Scene:
    """The flywheel scene of one design at one speed (SI units, radians).

    Attributes
    ----------
    inertia : J [kg m^2];  mean_speed : w_bar [rad/s];  speed_fluctuation : delta_allow [-].
    energy_band : W = J w_bar^2 delta_allow [J].
    least_peak_force : Fp*, least peak operator force [N].
    mean_force : F_mean [N].
    fluctuation : delta of the reported motion [-] (= delta_allow unless Fp* = F_mean).
    max_speed, min_speed : w_max, w_min of the reported motion [rad/s].
    ceiling : (k, 2) crank angles [rad] of the arcs on which the wheel is at w_max and the
        operator pushes only the quasi-static force; elsewhere |F| = Fp*.
    top_angle : crank angle [rad] where the motion is at w_max (start of the verification).
    peaks_phi, peaks_u : the refined local maxima of U [rad from the extended dead centre, J] and
        drift : U(phi + 2 pi) - U(phi) [J], from which :func:`wheel_speed` follows.
    """

    inertia: float
    mean_speed: float
    speed_fluctuation: float
    energy_band: float
    least_peak_force: float
    mean_force: float
    fluctuation: float
    max_speed: float
    min_speed: float
    ceiling: np.ndarray
    top_angle: float
    linkage: FourBar
    wheel_torque: float
    dead_centre_extended: float
    dead_centre_folded: float
    peaks_phi: np.ndarray
    peaks_u: np.ndarray
    drift: float


def _local_maxima(x, u, a0):
    """Indices of the local maxima of U over one period (neighbours wrap with the drift a0)."""
    u_prev = np.concatenate([[u[-1] - a0], u[:-1]])
    u_next = np.concatenate([u[1:], [u[0] + a0]])
    return np.nonzero((u >= u_prev) & (u > u_next))[0]


def scene(
    lk: FourBar,
    dead_centre_extended: float,
    dead_centre_folded: float,
    wheel_torque: float,
    inertia: float,
    mean_speed: float,
    speed_fluctuation: float,
    solved: float | None = None,
) -> Scene:
    """Solve the flywheel scene of one design: Fp*, the operator's force profile and w(t).

    The reported motion is the "as full as possible" one of :mod:`pumplink.models.flywheel_solver` at Fp*: the
    operator pushes Fp* in the grip's direction of motion, except on the ``ceiling`` arcs where
    the wheel is at its top speed and the push is the quasi-static force.
    """
    from scipy.optimize.elementwise import find_root

    band = float(energy_band(inertia, mean_speed, speed_fluctuation))
    if solved is None:  # Fp* of this scene, unless the caller has it already
        solved = least_peak_force(lk, dead_centre_extended, dead_centre_folded, wheel_torque, band)
    fp = solved
    prep, _ = prepare(lk, dead_centre_extended, dead_centre_folded, wheel_torque)
    f_mean = float(_qs.mean_force(wheel_torque, prep.stroke[0]))
    nan = float("nan")
    if not np.isfinite(fp):
        return Scene(
            inertia,
            mean_speed,
            speed_fluctuation,
            band,
            fp,
            f_mean,
            nan,
            nan,
            nan,
            np.empty((0, 2)),
            nan,
            lk,
            wheel_torque,
            dead_centre_extended,
            dead_centre_folded,
            np.empty(0),
            np.empty(0),
            nan,
        )
    x, u, b, loc, a = refined_extrema(prep, np.array([fp]))
    a0 = max(float(a[0]), 0.0)
    drop = float(drawdown(x, u, b, loc, np.array([a0]), prep.stroke, fp, prep.mw[:1])[0][0])
    x, u = x[0], u[0]
    # local maxima of U (refined) and their running maximum over the previous revolution
    peaks = _local_maxima(x, u, a0)
    xm, um = x[peaks], u[peaks]
    ceil = []
    args = prep.args(slice(0, 1))
    for m in range(peaks.size):
        # maxima in (xm - 2 pi, xm): the earlier ones this revolution and the later ones shifted back
        before = np.concatenate([um[:m], um[m + 1 :] - a0, [um[m] - a0]])
        level = before.max()
        if um[m] <= level:
            continue  # below an earlier top: the wheel is not full here
        # the ceiling arc starts where U climbs back to `level`, after the previous local minimum
        k = peaks[m]
        lo_idx = k - 1
        while True:  # walk back to the preceding node below `level` (wrapping, at most one revolution)
            xl = x[lo_idx % x.size] - (TWO_PI if lo_idx < 0 else 0.0)
            ul = u[lo_idx % x.size] - (a0 if lo_idx < 0 else 0.0)
            if ul <= level or lo_idx < k - x.size:
                break
            lo_idx -= 1
        res = find_root(
            lambda t, *p, level=level: u_integral(t, fp, *p, prep.mw[:1]) - level,
            (xl, xm[m]),
            args=args,
            tolerances=dict(xatol=0.0, xrtol=1e-15),
        )
        ceil.append((float(res.x[0]), float(xm[m])))
    ceiling = np.mod(np.array(ceil).reshape(-1, 2) + dead_centre_extended, TWO_PI)
    top = float(np.mod(xm[np.argmax(um)] + dead_centre_extended, TWO_PI))
    fluct = drop / (inertia * mean_speed**2)  # Eq. (2): the range of E is the drawdown
    return Scene(
        inertia,
        mean_speed,
        speed_fluctuation,
        band,
        float(fp),
        f_mean,
        fluct,
        mean_speed * (1 + fluct / 2),
        mean_speed * (1 - fluct / 2),
        ceiling,
        top,
        lk,
        float(wheel_torque),
        float(dead_centre_extended),
        float(dead_centre_folded),
        xm,
        um,
        a0,
    )


def on_ceiling(sc: Scene, crank_angle):
    """True where a crank angle lies on one of the scene's ceiling arcs."""
    th = np.asarray(crank_angle, float)
    out = np.zeros(th.shape, bool)
    for s, e in sc.ceiling:
        out |= np.mod(th - s, TWO_PI) <= np.mod(e - s, TWO_PI)
    return out


def operator_force(sc: Scene, crank_angle):
    """The reported operator force profile F(t) [N], +x positive.

    Fp* in the grip's direction of motion, the quasi-static force on the ceiling arcs; at a
    dead centre (grip at rest) the push reverses and the force is reported as 0.
    """
    th = np.asarray(crank_angle, float)
    st = kinematic_state(sc.linkage, th, sc.wheel_torque)
    push = sc.least_peak_force * np.sign(st.handle_rate)
    return np.where(on_ceiling(sc, th) & ~st.singular, st.force, push)


def wheel_speed(sc: Scene, crank_angle):
    """Wheel speed w(t) [rad/s] of the reported motion (energy balance Eq. (1) from the top)."""
    th = np.asarray(crank_angle, float)
    prep, _ = prepare(sc.linkage, sc.dead_centre_extended, sc.dead_centre_folded, sc.wheel_torque)
    xm, um, a0 = sc.peaks_phi, sc.peaks_u, sc.drift
    phi = np.mod(th - sc.dead_centre_extended, TWO_PI)
    uphi = u_integral(phi, sc.least_peak_force, *prep.args(slice(0, 1)), prep.mw[:1])
    # running maximum of U over (phi - 2 pi, phi]: U(phi) itself or a local maximum in the window
    cand_x = np.concatenate([xm, xm - TWO_PI])
    cand_u = np.concatenate([um, um - a0])
    col = phi.reshape(-1, 1)
    inside = (cand_x <= col) & (cand_x > col - TWO_PI)
    top = np.maximum(uphi.reshape(-1), np.where(inside, cand_u, -np.inf).max(axis=1)).reshape(phi.shape)
    energy = 0.5 * sc.inertia * sc.max_speed**2 - (top - uphi)  # Eq. (1) from the top of the band
    return np.sqrt(2.0 * energy / sc.inertia)


# ----------------------------------------------------------------------------- cross-check
@dataclass(frozen=True)
class TimeIntegration:
    """Equation of motion integrated in time under the scene's force profile (scipy ``solve_ivp``).

    Attributes
    ----------
    cycles : revolutions integrated.
    speeds_at_start : w [rad/s] each time the crank passes the start angle again (periodic: all
        equal to the first).
    periodicity : max |w_k - w_0| / w_0 over those passes [-].
    max_speed, min_speed : over the last revolution [rad/s].
    mean_speed : (w_max + w_min) / 2 over the last revolution [rad/s].
    time_mean_speed : 2 pi / (duration of the last revolution) [rad/s].
    fluctuation : (w_max - w_min) / mean_speed [-].
    """

    cycles: int
    speeds_at_start: np.ndarray
    periodicity: float
    max_speed: float
    min_speed: float
    mean_speed: float
    time_mean_speed: float
    fluctuation: float


def integrate_motion(sc: Scene, cycles: int = 4, rtol: float = 1e-11) -> TimeIntegration:
    """Integrate J dw/dt = (F(t) g(t) - Mw) (Eq. (1) in time) from the reported top speed.

    The force is the reported profile F(t) as a function of the crank angle alone (open loop):
    an error in the profile shows as a drift from one revolution to the next.
    """
    j, mw = sc.inertia, sc.wheel_torque

    def rhs(_t, y):
        th = y[0]
        g = kinematic_state(sc.linkage, th, 1.0).handle_rate
        return [
            y[1],
            (float(operator_force(sc, th)) * float(g) - mw) / j,
        ]  # Eq. (1): J w dw/dt = (F g - Mw) w

    return revolutions(rhs, sc.top_angle, sc.max_speed, sc.min_speed, sc.max_speed, cycles, rtol)


def revolutions(
    rhs, start_angle, start_speed, min_speed, max_speed, cycles, rtol, pieces=None
) -> TimeIntegration:
    """Integrate the crank's motion ``y' = rhs(t, y)``, y = (angle [rad], speed [rad/s]), with
    scipy's ``solve_ivp`` for ``cycles`` revolutions from ``start_angle`` at ``start_speed``, and
    measure each revolution's start speed, the last revolution's speed range and mean; shared by
    the flywheel and full dynamics' ``--verify``.  A motion that stops or turns back (no revolution
    completed) gives NaN speeds and an infinite drift.

    ``pieces``: (ends, rhs_of) where the right-hand side jumps at known crank angles (the force
    profile changes regime): ``ends`` the angles (increasing, the last ``start_angle + 2 pi``) that
    end the pieces of one revolution from ``start_angle``, ``rhs_of[k]`` piece k's right-hand side,
    smooth across its ends.  Each piece is integrated up to its end (a terminal event) and the next
    one started there, so no step straddles a jump: the steps a jump costs (an error estimate that
    rejects step after step around it) are spared.  Where a piece does not reach its end (the wheel
    stops or turns back) the motion is integrated again with ``rhs`` as a whole.
    """
    options = dict(method="DOP853", rtol=rtol, atol=1e-12 * max_speed, dense_output=True,
                   # On the top-speed arcs dw/dt is exactly 0, so the error estimate vanishes and,
                   # unbounded, one step could jump over whole revolutions: at most 1/64 revolution
                   max_step=TWO_PI / 64 / max_speed)  # fmt: skip
    horizon = 4.0 * cycles * TWO_PI / min_speed
    found = None if pieces is None else _by_pieces(pieces, start_angle, start_speed, horizon, cycles, options)
    if found is None:
        found = _whole(rhs, start_angle, start_speed, horizon, cycles, options)
    times, speeds, speed_at = found
    if times.size == 0:  # the wheel stopped or turned back: no revolution completed
        nan = float("nan")
        return TimeIntegration(0, np.array([start_speed]), np.inf, nan, nan, nan, nan, np.inf)
    speeds = np.concatenate([[start_speed], speeds])
    last0, last1 = (times[-2] if times.size > 1 else 0.0), times[-1]
    tt = np.linspace(last0, last1, 40001)
    w = speed_at(tt)
    wmax, wmin = _extreme(speed_at, tt, w, 1.0), _extreme(speed_at, tt, w, -1.0)
    mean = 0.5 * (wmax + wmin)
    return TimeIntegration(
        int(times.size),
        speeds,
        float(np.max(np.abs(speeds - speeds[0])) / speeds[0]),
        wmax,
        wmin,
        mean,
        TWO_PI / (last1 - last0),
        (wmax - wmin) / mean,
    )


def _extreme(speed_at, tt, w, sign: float) -> float:
    """The fastest (``sign`` 1) or slowest (-1) speed of the samples ``w`` at times ``tt``, refined
    between the extreme sample's neighbours (Chandrupatla's bracket on the dense output): a dip
    narrower than the samples' spacing (a wheel that only the links turn, sped up and slowed down
    in a blink at each dead centre) is found."""
    k = int(np.argmax(sign * w))
    best = float(w[k])
    if 0 < k < tt.size - 1:
        found = find_minimum(lambda t: -sign * speed_at(np.atleast_1d(t)), (tt[k - 1], tt[k], tt[k + 1]))
        value = -sign * float(found.f_x)
        if bool(found.success) and sign * value > sign * best:
            best = value
    return best


def _whole(rhs, start_angle, start_speed, horizon, cycles, options):
    """:func:`revolutions`' integration in one call: the times the crank is back at the start (up
    to ``cycles``), its speed then, and the speed at any time of the run (dense output)."""
    from scipy.integrate import solve_ivp

    def turn(_t, y):
        return np.sin(0.5 * (y[0] - start_angle))  # zero each time the crank is back at the start

    turn.terminal = cycles + 1  # the start itself may count as a crossing
    sol = solve_ivp(rhs, (0.0, horizon), [start_angle, start_speed], events=turn, **options)
    times = sol.t_events[0]
    times = times[times > 1e-9 * horizon][:cycles]
    return times, np.array([float(sol.sol(t)[1]) for t in times]), lambda t: sol.sol(t)[1]


def _by_pieces(pieces, start_angle, start_speed, horizon, cycles, options):
    """:func:`_whole` piece by piece (:func:`revolutions`' ``pieces``); None where a piece does not
    reach its end."""
    from scipy.integrate import solve_ivp

    ends, rhs_of = pieces
    t, y = 0.0, np.array([start_angle, start_speed], float)
    spans, times, speeds = [], [], []  # (start, end, dense output) of each piece
    for turn in range(cycles):
        for end, rhs in zip(ends, rhs_of, strict=True):
            target = end + turn * TWO_PI

            def reach(_t, yy, target=target):
                return yy[0] - target

            reach.terminal, reach.direction = True, 1.0
            sol = solve_ivp(rhs, (t, horizon), y, events=reach, **options)
            if sol.status != 1:  # not at its end before the horizon: stopped or turned back
                return None
            spans.append((t, sol.t_events[0][0], sol.sol))
            t, y = sol.t_events[0][0], sol.y_events[0][0]
        times.append(t)
        speeds.append(float(y[1]))

    def speed_at(tt):
        out = np.full(tt.shape, np.nan)  # a time outside the run has no speed
        for a, b, dense in spans:
            inside = (tt >= a) & (tt <= b)
            if inside.any():
                out[inside] = dense(tt[inside])[1]
        return out

    return np.array(times), np.array(speeds), speed_at


# ----------------------------------------------------------------------------- neglected effects
def link_energy(lk: FourBar, crank_angle, mean_speed, mass_per_length=LINK_MASS_PER_METRE):
    """Kinetic energy [J] of the coupler and the handle at crank angles, turning at ``mean_speed``.

    Both are taken as uniform bars of ``mass_per_length`` [kg/m] (the handle from the rocker pivot
    to the grip, length max(H, rocker)); a uniform bar whose ends move at vA, vB has
    T = m (vA^2 + vA.vB + vB^2) / 6.  The crank is part of the wheel.
    """
    th = np.asarray(crank_angle, float)
    w = mean_speed
    px, py, c = lk.pivot_x, lk.pivot_y, lk.crank
    cs, sn = np.cos(th), np.sin(th)
    with np.errstate(all="ignore"):  # the coupler point and rocker rate of kinematic_state, no more
        p1, p2, e2, t, q = loop_closure(lk, cs, sn)
        dx, dy = px - c * cs, py - c * sn
        rx = c * cs + t * dx - q * dy - px
        ry = c * sn + t * dy + q * dx - py
        rate = -c * (t * p2 + q * (p1 - c)) / (q * e2)  # omega4 / omega2
    vax, vay = -w * c * sn, w * c * cs
    w4 = rate * w
    vbx, vby = -w4 * ry, w4 * rx
    coupler = (
        mass_per_length
        * lk.coupler
        / 6.0
        * (vax * vax + vay * vay + vax * vbx + vay * vby + vbx * vbx + vby * vby)
    )
    arm = np.maximum(lk.handle, lk.rocker)
    handle = mass_per_length * arm / 6.0 * (w4 * arm) ** 2
    return coupler + handle

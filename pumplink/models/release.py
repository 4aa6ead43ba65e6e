"""The released handle: what the water column does to the wheel when the operator lets go
(docs/workshop.md §3).

The scene
---------
The operator lets go at crank angle t0 with the wheel turning forward at w0 > 0 (the pumping
direction, CCW).  From then on no hand force acts.  The rope pump's rising main holds a water column
of height ``head`` on the pistons; its weight W = rho g head A pulls the rope back, a torque
M_col = W rw on the wheel **against** the pumping direction.  In operation the wheel torque is
Mw = M_col + M_loss: the pump's losses (piston friction in the pipe, everything the efficiency
eta = M_col / Mw leaves) oppose the motion.  After the release

1. the wheel coasts forward against M_col + M_loss and the links' weight, and stops;
2. if M_col plus the links' weight beats the losses there it turns **backwards**: the column runs
   back down the rising main, driving the wheel and the handle, with the losses now opposing the
   reverse motion;
3. as the rope runs back by s = rw (t_max - t) (t_max the farthest crank angle reached), the top of
   the column falls by s: the column above the well's water level, and with it the driving torque
   and the water's share of the inertia, shrink as (1 - s / head).  It is empty after the rope has
   run back the head, s = head, i.e. head / rw radians of crank.

Equation of motion, in the crank angle t, with the links' reduced inertia I_l(t) and potential
V_l(t) of full dynamics (:func:`pumplink.models.dynamics_terms.terms`, docs/models.md §3a), the wheel's
inertia J (wheel, rope and water) of which ``column_inertia`` = rho head A rw^2 is the water:

    (J - Jc (s / head) + I_l) t'' + I_l' t'^2 / 2 + V_l' = -M_col (1 - s / head) - M_loss sign(t')

for 0 <= s <= head (Lagrange's equation; the water leaving the pipe's foot leaves with the rope's
speed, so it takes its own momentum and adds no force: the variable mass only changes the inertia).
At rest (t' = 0) the losses hold the wheel while |M_col (1 - s/head) + V_l'| <= M_loss (static and
moving friction taken equal).  The integration (scipy ``solve_ivp``, DOP853) runs in phases of one
sign of t' and stops when the column is empty (s = head), the wheel is held at rest, or the horizon.

What it returns
---------------
The numbers of a "needs a ratchet or brake" line: when the wheel stops and reverses, the grip's
speed one second after the release, and the grip's peak speed before the column empties or the
wheel is held, with its time and crank angle.  The grip speed is H |dt4/dt| |t'|
(:func:`pumplink.mechanisms.fourbar.kinematic_state`).

Per design (an ODE); SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pumplink.constants import GRAVITY, RELEASE_RTOL
from pumplink.mechanisms.angles import TWO_PI
from pumplink.mechanisms.fourbar import FourBar, kinematic_state
from pumplink.models import Masses

#: Default length of the integration [s]: far beyond any column's emptying (the village well's
#: empties in about 4 s).
HORIZON = 60.0
#: Relative tolerance of the integration.
RTOL = RELEASE_RTOL
#: Dense-output samples per crank radian turned on which the grip's peak speed is searched before
#: it is refined (the grip speed has two humps per crank turn: about 40 samples per hump).
PEAK_SAMPLES_PER_RAD = 12
#: Most phases (changes of the turning direction) integrated before giving up.
MAX_PHASES = 50
#: Most solver steps of one release, all phases together: the dense output the peak search reads
#: is kept for every step, and a step costs about half a millisecond (some 20 evaluations of the
#: equation of motion).  The shipped specs take 121 to 376, deep wells on small, light, fast wheels
#: up to about 4,700 (40 m of head on a 0.1 m, 2 kg wheel at 540 deg/s); a wheel that a tiny column
#: and tiny losses leave turning takes far more (a 1 mm wheel under 168 m of 1 mm pipe: about
#: 13,500 a minute of coasting, and 168,000 rad of crank to empty its column).
MAX_STEPS = 5_000
#: Most crank angle one release turns, all phases together [rad]: the bound on the samples of the
#: peak search (:data:`PEAK_SAMPLES_PER_RAD` per radian) where the steps are long (light links).
#: A column empties after head / rw radians run back: this covers 200 m of head on a 2 cm wheel.
MAX_TURNED = 10_000.0
#: The ``end_reason`` of a motion that had not ended when the integration stopped: neither the
#: column empty nor the wheel held (:attr:`Release.stopped_early`).
EARLY_ENDS = ("horizon", "step limit", "turn limit")


@dataclass(frozen=True)
class Release:
    """The motion after letting go of the handle (SI units, radians, seconds from the release).

    Attributes
    ----------
    start_angle, start_speed : t0 [rad], w0 [rad/s].
    stop_time, stop_angle : when and where the forward coast ends (w = 0) [s, rad].
    reverses : True when the column then drives the wheel backwards.
    reverse_time : when the backward motion starts [s] (= stop_time; NaN if it does not reverse).
    grip_speed_1s : grip speed one second after the release [m/s] (NaN if the motion ended before).
    peak_grip_speed : the largest grip speed from the release to the end [m/s];
    peak_time [s], peak_angle [rad, in [0, 2 pi)], peak_rope_travel : the rope run back by then [m].
    peak_wheel_speed : largest |w| [rad/s] and its time [s] (a tuple).
    end_time [s], end_reason : "column empty", "held" (the losses hold the wheel at rest), or, with
        the wheel still turning, "horizon" (the time given), "step limit" (:data:`MAX_STEPS`) or
        "turn limit" (:data:`MAX_TURNED`);  end_rope_travel : the rope run back at the end [m];
    end_speed : the wheel's speed w at the end [rad/s] (negative: turning backwards).
    steps : the solver's steps, all phases together;  max_steps, max_turned [rad] : the limits it
        ran under (the step and turn limits of ``end_reason``).
    """

    start_angle: float
    start_speed: float
    stop_time: float
    stop_angle: float
    reverses: bool
    reverse_time: float
    grip_speed_1s: float
    peak_grip_speed: float
    peak_time: float
    peak_angle: float
    peak_rope_travel: float
    peak_wheel_speed: tuple
    end_time: float
    end_reason: str
    end_rope_travel: float
    end_speed: float
    steps: int = 0
    max_steps: int = MAX_STEPS
    max_turned: float = MAX_TURNED

    @property
    def stopped_early(self) -> bool:
        """True when the integration stopped with the wheel still turning (:data:`EARLY_ENDS`):
        the times and speeds are those up to then; the peak grip speed is the peak so far."""
        return self.end_reason in EARLY_ENDS


class _StepLimit:
    """A terminal event for ``solve_ivp`` that ends the integration at the end of its
    ``steps``-th step.  ``solve_ivp`` evaluates every event once at the start and once at the end
    of each step, so the calls count the steps; at the last one the event's value (``at - t``)
    falls to 0 at that step's end, where the event is then located."""

    terminal = True
    direction = -1.0

    def __init__(self, steps: int):
        self.calls_left = steps + 1  # the first call is at the start
        self.at = np.inf

    def __call__(self, t, _y):
        self.calls_left -= 1
        if self.calls_left == 0:
            self.at = t
        return self.at - t


def _grip_speed(lk, th, w):
    """H |dt4/dt| |w| [m/s] at crank angle(s) th and wheel speed(s) w."""
    return np.abs(lk.handle * kinematic_state(lk, th, 1.0).rocker_rate * w)


def release(
    lk: FourBar,
    crank_angle: float,
    crank_speed: float,
    column_torque: float,
    loss_torque: float,
    inertia: float,
    head: float,
    wheel_radius: float,
    masses: Masses = Masses(),
    column_inertia: float = 0.0,
    gravity: float = GRAVITY,
    horizon: float = HORIZON,
    rtol: float = RTOL,
    max_steps: int = MAX_STEPS,
    max_turned: float = MAX_TURNED,
) -> Release:
    """Integrate the released handle's motion (the equation of motion of the module docstring).

    Parameters
    ----------
    lk : the linkage (one design).
    crank_angle, crank_speed : the state at the release, t0 [rad] and w0 [rad/s] (w0 >= 0).
    column_torque : M_col = rho g head A rw, the full column's weight on the rope times rw [N m].
    loss_torque : M_loss, the losses' torque opposing the motion [N m] (Mw - M_col when all of the
        pump's inefficiency is friction; 0 for the worst case, docs/workshop.md §3).
    inertia : J of the wheel, rope and water about the axle [kg m^2].
    head : the column's height above the well's water level [m];  wheel_radius : rw [m].
    masses : the links' masses [kg] (the hand is gone: no grip mass unless something else is there).
    column_inertia : Jc = rho head A rw^2, the water's part of J [kg m^2] (0: J constant).
    gravity : [m/s^2];  horizon : longest time integrated [s];  rtol : of ``solve_ivp``.
    max_steps, max_turned : the most solver steps and crank angle [rad] of the whole motion
        (:data:`MAX_STEPS`, :data:`MAX_TURNED`); past either it stops early.

    Returns
    -------
    Release
    """
    from scipy.integrate import solve_ivp

    from pumplink.models import dynamics_terms as dt

    rw, jc, mcol, mloss = float(wheel_radius), float(column_inertia), float(column_torque), float(loss_torque)
    empty_angle = head / rw  # crank angle the rope must run back to empty the column

    # the links' terms one crank angle at a time on floats (the right-hand side is called ~8,000
    # times a release; dynamics_terms.terms on one angle costs several times more in numpy's per-call work)
    terms_at = dt.point_terms(lk, masses, gravity)

    def share(th, top):
        """Fraction of the column left, 1 - s / head, s = rw (top - th) clipped to [0, head]."""
        return 1.0 - min(max((top - th) / empty_angle, 0.0), 1.0)  # np.clip on one float

    def driving(th, top):
        """The torques at rest: column + links' weight, without the losses [N m] (forward positive)."""
        return -mcol * share(th, top) - terms_at(th)[3]

    def rhs_of(sign, top):
        def rhs(_t, y):
            th, w = float(y[0]), float(y[1])
            li, rate, _v, vrate = terms_at(th)[:4]
            left = share(th, top)
            i = inertia - jc * (1.0 - left) + li
            q = -mcol * left - sign * mloss - vrate - 0.5 * rate * w * w
            return [w, q / i]

        return rhs

    t0, y = 0.0, np.array([float(crank_angle), float(crank_speed)])
    top = y[0]
    pieces = []  # (solution, t_start, t_end)
    stop_time = stop_angle = np.nan
    reverse_time = np.nan
    reverses = False
    end_reason = "horizon"
    steps, turned = 0, 0.0
    sign = 1.0 if y[1] > 0 else 0.0
    for _ in range(MAX_PHASES):
        if sign == 0.0:  # at rest: does anything move it?
            drive = driving(y[0], top)
            if abs(drive) <= mloss:
                end_reason = "held"
                break
            sign = float(np.sign(drive))
            if sign < 0 and not reverses:
                reverses, reverse_time = True, t0

        def stopped(_t, yy):
            return yy[1]

        stopped.terminal, stopped.direction = True, -sign  # the speed returns to 0 (not leaves it)

        def turn_limit(_t, yy, start=float(y[0]), left=max_turned - turned):
            return left - abs(yy[0] - start)

        turn_limit.terminal, turn_limit.direction = True, -1.0
        events = [stopped, turn_limit, _StepLimit(max_steps - steps)]
        if sign < 0:

            def empty(_t, yy, top=top):
                return (top - yy[0]) - empty_angle

            empty.terminal, empty.direction = True, 1.0
            events.append(empty)
        sol = solve_ivp(
            rhs_of(sign, top),
            (t0, horizon),
            y,
            method="DOP853",
            rtol=rtol,
            atol=1e-12 * max(abs(y[1]), 1.0),
            events=events,
            dense_output=True,
        )
        t1 = float(sol.t[-1])
        pieces.append((sol.sol, t0, t1))
        steps += sol.t.size - 1
        turned += abs(float(sol.y[0, -1]) - float(y[0]))
        y = sol.y[:, -1].copy()
        t0 = t1
        if sign < 0 and sol.t_events[3].size:
            end_reason = "column empty"
            break
        if sol.t_events[1].size or sol.t_events[2].size:  # still turning: stopped early
            end_reason = "turn limit" if sol.t_events[1].size else "step limit"
            break
        if sol.t_events[0].size:  # the wheel stopped
            y[1] = 0.0
            if np.isnan(stop_time):
                stop_time, stop_angle = t1, float(y[0])
            top = max(top, float(y[0]))
            sign = 0.0
            continue
        break  # the horizon
    end_time = t0

    # the grip's and the wheel's speed along the motion: sampled on the dense output, refined
    best = _peak(pieces, lambda th, w: _grip_speed(lk, th, w))
    wheel = _peak(pieces, lambda th, w: np.abs(w))
    best_w = (wheel[0], wheel[1])

    def state_at(tt):
        for sol_fn, a, b in pieces:
            if a <= tt <= b:
                return sol_fn(tt)
        return None

    at1 = state_at(1.0)
    v1 = float(_grip_speed(lk, at1[0], at1[1])) if at1 is not None else np.nan
    travel_at_peak = rw * max(0.0, _top_before(pieces, best[1], float(crank_angle)) - best[2])
    end_travel = rw * max(0.0, top - float(y[0]))
    return Release(
        float(crank_angle),
        float(crank_speed),
        float(stop_time),
        float(stop_angle),
        bool(reverses),
        float(reverse_time),
        v1,
        best[0],
        best[1],
        float(np.mod(best[2], TWO_PI)),
        float(min(travel_at_peak, head)),
        best_w,
        float(end_time),
        end_reason,
        float(min(end_travel, head)),
        float(y[1]),
        steps,
        int(max_steps),
        float(max_turned),
    )


def _peak(pieces, speed):
    """Largest ``speed(theta, w)`` along the pieces of dense output: (value, time [s], angle [rad]).

    Sampled at :data:`PEAK_SAMPLES_PER_RAD` per crank radian turned (at least 200 per piece), the
    best sample refined by a bounded Brent search between its neighbours (scipy ``minimize_scalar``,
    to 1e-12 s): exact to the dense output's accuracy for a smooth maximum.
    """
    from scipy.optimize import minimize_scalar

    best = (-1.0, np.nan, np.nan)
    for sol_fn, a, b in pieces:
        if b <= a:
            continue
        turn = abs(float(sol_fn(b)[0] - sol_fn(a)[0]))
        n = max(int(PEAK_SAMPLES_PER_RAD * turn), 200)
        ts = np.linspace(a, b, n)
        th, w = sol_fn(ts)
        v = speed(th, w)
        j = int(np.argmax(v))
        cand = (float(v[j]), float(ts[j]), float(th[j]))
        lo, hi = ts[max(j - 1, 0)], ts[min(j + 1, n - 1)]
        if hi > lo:
            res = minimize_scalar(
                lambda tt, f=sol_fn: -float(speed(*f(tt))),
                bounds=(lo, hi),
                method="bounded",
                options=dict(xatol=1e-12 * max(b, 1.0)),
            )
            if -res.fun > cand[0]:
                cand = (float(-res.fun), float(res.x), float(sol_fn(res.x)[0]))
        if cand[0] > best[0]:
            best = cand
    return best


def _top_before(pieces, time, start_angle):
    """The farthest crank angle reached up to ``time`` [rad] (the column is full up to it)."""
    top = start_angle
    for sol_fn, a, b in pieces:
        if a > time:
            break
        hi = min(b, time)
        ts = np.linspace(a, hi, 64)
        top = max(top, float(np.max(sol_fn(ts)[0])))
    return top


def column_torque(head, pipe_diameter, wheel_radius, density=1000.0, gravity=GRAVITY):
    """M_col = rho g head (pi d^2 / 4) rw [N m]: the full column's weight on the rope times rw
    (docs/physics.md §5, the rope force without the efficiency)."""
    return density * gravity * head * np.pi * pipe_diameter**2 / 4.0 * wheel_radius


def column_inertia(head, pipe_diameter, wheel_radius, density=1000.0):
    """Jc = rho head (pi d^2 / 4) rw^2 [kg m^2]: the water in the rising main moving with the rim
    (docs/models.md §2, ``load.moving_mass``)."""
    return density * head * np.pi * pipe_diameter**2 / 4.0 * wheel_radius**2

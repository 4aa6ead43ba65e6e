"""One design in depth: the motion of the model that decided, and the searches over its speed.

:func:`pumplink.evaluate.evaluate` gives every design's verdict quantities; a study of one design
(``pumplink force``, ``speed``, ``--verify``, ``--explain``, the charts) also shows *how* the
deciding model moves the linkage: the operator's force and the wheel's speed at each crank angle,
the equation of motion integrated in time, the best cadence.  Those run the force models too, so
they live here, in the evaluation package, the only door to the models (docs/models.md §2-3a).

Floats for one design (SI units, radians); the scenes are the models' own
(:class:`pumplink.models.flywheel.Scene`, :class:`pumplink.models.dynamics.Scene`).
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np

from pumplink.evaluate import Evaluation
from pumplink.evaluate import parts as _parts
from pumplink.mechanisms.fourbar import FourBar, Synthesis
from pumplink.models import DYNAMICS, FLYWHEEL, ORDER, Masses
from pumplink.models.quasi_static import in_dead_band

__all__ = [
    "agrees",
    "at_design",
    "best_speed",
    "dynamics_peak_force",
    "effect_sizes",
    "in_dead_band",
    "integrate",
    "link_masses_of",
    "min_passing_speed",
    "on_ceiling",
    "piston_crank_torque",
    "operator_force",
    "scene",
    "speed_range",
    "wheel_speed",
]


def _at(x, i: int):
    return None if x is None else np.asarray(x)[i][()]


def at_design(ev: Evaluation, i: int = 0) -> tuple[Synthesis, FourBar]:
    """Design ``i`` of an evaluation: its synthesis and four-bar as scalars."""
    syn = ev.synthesis
    one = Synthesis(**{f.name: _at(getattr(syn, f.name), i) for f in fields(syn)})
    return one, one.linkage


def _one(x, i: int) -> float:
    """Design ``i``'s value of a column (a float stands for every design)."""
    a = np.asarray(x, float)
    return float(a) if a.ndim == 0 else float(a[i])


def link_masses_of(ev: Evaluation, i: int = 0, arms: bool | None = None) -> Masses:
    """The coupler's and handle's masses of design ``i`` and, at the grip, the operator's arms
    (``arms`` True), none (False) or as the verdict takes them (None) [kg]."""
    m = ev.masses
    d = ev.designs
    grip = _one(m.grip, i) if arms is None else (_one(d.arm_mass, i) if arms else 0.0)
    return Masses(_one(m.coupler, i), _one(m.handle, i), grip)


def scene(ev: Evaluation, i: int = 0):
    """The deciding energy model's scene of design ``i`` at its mean speed, solved at the
    evaluation's least peak force (the flywheel's or full dynamics' :class:`Scene`); None where
    the quasi-static model decided or the design is infeasible."""
    key = ORDER[int(ev.model_index[i])]
    if key not in (FLYWHEEL, DYNAMICS) or not ev.feasible[i]:
        return None
    syn, lk = at_design(ev, i)
    d = ev.designs
    args = (lk, syn.dead_centre_extended, syn.dead_centre_folded, _one(d.wheel_torque, i), _one(d.inertia, i))
    speed, delta, force = _one(d.speed, i), _one(d.speed_fluctuation, i), float(ev.least_peak_force[i])
    return _parts.scene(*args, link_masses_of(ev, i), speed, delta, force, key)


def _model(sc):
    from pumplink.models import dynamics as _dy
    from pumplink.models import flywheel as _fw

    return _dy if isinstance(sc, _dy.Scene) else _fw


def operator_force(sc, crank_angle):
    """The operator's force of the scene's motion at crank angles [N], +x positive."""
    return _model(sc).operator_force(sc, crank_angle)


def wheel_speed(sc, crank_angle):
    """The wheel's speed of the scene's motion at crank angles [rad/s]."""
    return _model(sc).wheel_speed(sc, crank_angle)


def on_ceiling(sc, crank_angle):
    """True where the scene's motion rides the top of its energy band (the operator follows)."""
    m = _model(sc)
    return (m.regime(sc, crank_angle) == 0) if hasattr(m, "regime") else m.on_ceiling(sc, crank_angle)


def integrate(sc):
    """The equation of motion integrated in time under the scene's force profile (scipy
    ``solve_ivp``): :class:`pumplink.models.flywheel.TimeIntegration`."""
    return _model(sc).integrate_motion(sc)


def agrees(sc, sim, rtol: float) -> bool:
    """The integration is periodic, inside the speed band and at the mean speed, to ``rtol``."""
    from pumplink.models import dynamics as _dy

    if isinstance(sc, _dy.Scene):
        return _dy.agrees(sc, sim, rtol)
    return bool(
        sim.periodicity <= rtol
        and abs(sim.mean_speed - sc.mean_speed) <= rtol * sc.mean_speed
        and sim.fluctuation <= sc.speed_fluctuation * (1 + rtol)
    )


def min_passing_speed(*args):
    """The flywheel's slowest passing mean speed [rad/s] (docs/models.md §2; inf: none), of
    (linkage, dead centres, Mw, force limit, J, δ) (:func:`pumplink.models.flywheel.min_passing_speed`)."""
    from pumplink.models import flywheel as _fw

    return _fw.min_passing_speed(*args)


def dynamics_peak_force(*args):
    """Full dynamics' least peak force [N] of (linkage, dead centres, Mw, J, masses, ω̄, δ)
    (docs/models.md §3a; :func:`pumplink.models.dynamics.least_peak_force`)."""
    from pumplink.models import dynamics as _dy

    return _dy.least_peak_force(*args)


def best_speed(*args):
    """The mean speed with the least full-dynamics peak force, and that force
    (:func:`pumplink.models.dynamics.best_speed`)."""
    from pumplink.models import dynamics as _dy

    return _dy.best_speed(*args)


def speed_range(*args):
    """The mean speeds where full dynamics' least peak force is within a limit
    (:func:`pumplink.models.dynamics.speed_range`)."""
    from pumplink.models import dynamics as _dy

    return _dy.speed_range(*args)


def effect_sizes(lk, masses: Masses, speed):
    """The links' largest kinetic energy, their weight's range and the arms' largest kinetic
    energy [J] (:func:`pumplink.models.dynamics.effect_sizes`)."""
    from pumplink.models import dynamics as _dy

    return _dy.effect_sizes(lk, masses, speed)


def piston_crank_torque(crank_length, rod_length, offset, load, crank_angle):
    """The piston pump's load torque on the crank at crank angles [N m] (Eq. P.2 of
    docs/piston-pump.md; :func:`pumplink.models.piston.crank_torque`)."""
    from pumplink.models import piston as _pm

    return _pm.crank_torque(crank_length, rod_length, offset, load, crank_angle)

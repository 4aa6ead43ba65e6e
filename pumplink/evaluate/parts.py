"""Will the parts last? The part checks of one design in depth, for the workshop view of
``pumplink force --explain`` (docs/workshop.md): the names of :mod:`pumplink.models.parts` the
studies use (they reach the models through the evaluation), and the released handle.

The verdict's part checks of many designs at once are :func:`pumplink.models.parts.part_checks`,
the evaluation's ``parts`` stage.
"""

from __future__ import annotations

import numpy as np

from pumplink.mechanisms.angles import TWO_PI
from pumplink.models import Masses
from pumplink.models.parts import CYCLE_SAMPLES
from pumplink.models.parts import FATIGUE_FAIL as FATIGUE_FAIL
from pumplink.models.parts import FATIGUE_WARN as FATIGUE_WARN
from pumplink.models.parts import PIN_PRESSURE_FAIL as PIN_PRESSURE_FAIL
from pumplink.models.parts import PIN_PRESSURE_WARN as PIN_PRESSURE_WARN
from pumplink.models.parts import PartLoads as PartLoads
from pumplink.models.parts import Strength as Strength
from pumplink.models.parts import part_loads as part_loads
from pumplink.models.parts import scene as scene
from pumplink.models.parts import strength as strength


def released(
    scene, head: float, pipe_diameter: float, wheel_radius: float, wheel_torque: float, masses: Masses
):
    """The released handle (docs/workshop.md §3): let go at the grip's fastest point of the energy
    model's motion, with the pump's losses counted as friction (``friction``) and with none (the
    upper bound, ``free``): two :class:`pumplink.models.release.Release`."""
    from pumplink.mechanisms.fourbar import kinematic_state
    from pumplink.models import release as _release

    lk = scene.linkage
    th = np.arange(CYCLE_SAMPLES) * (TWO_PI / CYCLE_SAMPLES)
    from pumplink.models import dynamics as _dy
    from pumplink.models import flywheel as _fw

    model = _dy if isinstance(scene, _dy.Scene) else _fw
    w = np.asarray(model.wheel_speed(scene, th), float)
    grip = np.abs(lk.handle * kinematic_state(lk, th, 1.0).rocker_rate * w)
    i = int(np.nanargmax(grip))
    column = float(_release.column_torque(head, pipe_diameter, wheel_radius))
    water = float(_release.column_inertia(head, pipe_diameter, wheel_radius))
    links = Masses(masses.coupler, masses.handle, 0.0)
    args = (lk, float(th[i]), float(w[i]), column)
    tail = (float(scene.inertia), float(head), float(wheel_radius), links, water)
    friction = _release.release(*args, max(float(wheel_torque) - column, 0.0), *tail)
    free = _release.release(*args, 0.0, *tail)
    return friction, free

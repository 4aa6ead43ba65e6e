"""What the drawings, the animation and the workshop templates show, computed from the synthesis.

Pure functions: a spec in, frozen dataclasses of floats and numpy arrays out (SI units, radians),
no I/O.  :mod:`pumplink.output.drawings`, :mod:`pumplink.output.template` and
:mod:`pumplink.output.report` only draw what is here.

Coordinates are those of docs/physics.md §1: origin at the wheel axle O2, x horizontal, y up,
angles counter-clockwise from +x; the wheel turns counter-clockwise.  The joints of a pose are,
in this order, the axle O2, the crank pin A, the coupler-rocker joint B, the rocker pivot O4 and
the grip P (the rocker extended to the handle length H: P = O4 + (H / l4)(B - O4)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.constants import LINK_MASS_PER_METRE
from pumplink.errors import InfeasibleDesign
from pumplink.inputs.pump import PumpSpec
from pumplink.mechanisms.fourbar import FourBar, kinematic_state
from pumplink.studies.force import Design, design, force_analysis

#: Names of the joints, in the order of :attr:`Pose.joints`.
JOINTS = ("O2", "A", "B", "O4", "P")
#: How a link holds each of its joints (:attr:`Part.hole_kinds`): "hole", drilled for the pin;
#: "lug", a lug welded on holds the pin (the handle at B); "welded", welded to the axle (the crank
#: at O2).  Only a "hole" is drilled.
HOLE_KINDS = ("hole", "lug", "welded")
#: Material beyond an outer hole centre, as a multiple of the hole diameter (edge distance of a
#: pinned joint, 1.5 d); the template's bar is twice that wide.
EDGE_FACTOR = 1.5
#: Crank angles of the grip path and the joint paths drawn on the drawing.
PATH_POINTS = 721


@dataclass(frozen=True)
class Pose:
    """The linkage at one crank angle.

    Attributes
    ----------
    label : what this pose is ("extended dead centre", ...).
    crank_angle : crank angle θ2 [rad].
    joints : (5, 2) positions [m] of O2, A, B, O4, P (:data:`JOINTS`).
    """

    label: str
    crank_angle: float
    joints: np.ndarray

    def joint(self, name: str) -> np.ndarray:
        return self.joints[JOINTS.index(name)]


@dataclass(frozen=True)
class Dimension:
    """A length to dimension: the distance ``start`` -> ``end`` [m] called ``label``.

    ``kind`` "aligned": the dimension line runs parallel to start -> end, shifted by ``line`` [m]
    along its left normal (negative: the right).  "horizontal" / "vertical": it runs at height
    y = ``line`` / at x = ``line`` [m] and measures the x / y distance.  ``value`` is the length
    written on it [m].
    """

    label: str
    value: float
    start: np.ndarray
    end: np.ndarray
    line: float
    kind: str = "aligned"  # "aligned", "horizontal" or "vertical"


@dataclass(frozen=True)
class Part:
    """One link as the fitter makes it: a straight bar with holes on its centre line.

    Positions are along the bar from its first hole centre [m].

    Attributes
    ----------
    key : short name (a DXF layer name).
    name : the link's name in words.
    holes : the joints' centres along the bar [m] (the first is 0): a hole drilled there, or the
        centre of a welded joint (``hole_kinds``).
    hole_labels : the joint each makes.
    hole_diameter : of the drilled holes, the pins' diameter [m] (``parts.pin_diameter``).
    end : the far end of the bar's useful length [m] (the grip for the handle, else the last hole).
    end_label : what is at ``end`` when it is not a hole (the grip), else None.
    edge : material beyond the outer hole centres [m] (:data:`EDGE_FACTOR` × hole diameter).
    mass_per_length : [kg/m] (linkage.mass_per_length or the 3/4-inch tube default).
    hole_tolerances, end_tolerance : how far each hole (and the grip) may be off [m] for the share
        of builds that pass to stay at the target (:func:`tolerance_marks`; empty / None: not
        allocated, NaN: tighter than a workshop holds).
    hole_critical, end_critical : the hole needs more care than a hand-drilled one gets.
    hole_kinds : how each joint is made, one of :data:`HOLE_KINDS` (all drilled when empty).
    """

    key: str
    name: str
    holes: np.ndarray
    hole_labels: tuple[str, ...]
    hole_diameter: float
    end: float
    end_label: str | None
    edge: float
    mass_per_length: float
    hole_tolerances: tuple[float, ...] = ()
    hole_critical: tuple[bool, ...] = ()
    end_tolerance: float | None = None
    end_critical: bool = False
    hole_kinds: tuple[str, ...] = ()

    @property
    def drilled(self) -> tuple[bool, ...]:
        """For each of ``holes``: True where a hole is drilled (not a welded joint)."""
        return tuple(k == "hole" for k in self.hole_kinds) if self.hole_kinds else (True,) * len(self.holes)

    @property
    def centre_distance(self) -> float:
        """First to last hole centre [m]."""
        return float(self.holes[-1] - self.holes[0])

    @property
    def cut_length(self) -> float:
        """Length of bar to cut [m]: the holes (or the grip) plus the edge at each end."""
        far = max(self.end, float(self.holes[-1]) + self.edge)
        return float(far - self.holes[0] + self.edge)

    @property
    def mass(self) -> float:
        """Mass of the cut bar [kg]."""
        return self.cut_length * self.mass_per_length


@dataclass(frozen=True)
class Marks:
    """The tolerance notes of a workshop template (docs/tolerance.md §4).

    target : the share of builds that pass the tolerances keep, to first order;
    distribution : how ±t is read ("uniform": anywhere within; "normal": t = 3σ);
    stand, stand_critical : the tolerance of the axle and the rocker pivot on the stand [m], and
        whether it needs more care than welding by eye gets;
    share : the first-order share at the allocated tolerances;
    reason : why nothing is allocated (the design itself fails), else None.
    """

    target: float
    distribution: str
    stand: float
    stand_critical: bool
    share: float
    reason: str | None = None


@dataclass(frozen=True)
class Drawing:
    """Everything the linkage drawing shows (SI units, radians).

    Attributes
    ----------
    name : the design's name.
    poses : extended dead centre, folded dead centre and, when asked for, the peak-force position.
    grip_path, coupler_path : (n, 2) paths [m] of P and B over one revolution.
    wheel_radius, stand_width : rw and b [m].
    axle_height : height of the axle above the ground [m], or None when the spec does not say.
    swing : total handle swing Δθ [rad]; the handle swings through 90° ± Δθ/2.
    rotation : +1: the wheel turns counter-clockwise (docs/physics.md §1).
    dimensions : the lengths to dimension.
    extent : (xmin, xmax, ymin, ymax) of everything drawn [m].
    parts : the links as made (the cut list).
    tube_given : True when the spec gives linkage.mass_per_length (else the default tube).
    """

    name: str
    poses: tuple[Pose, ...]
    grip_path: np.ndarray
    coupler_path: np.ndarray
    wheel_radius: float
    stand_width: float
    stand_bottom: float
    axle_height: float | None
    swing: float
    rotation: int
    dimensions: tuple[Dimension, ...]
    extent: tuple[float, float, float, float]
    parts: tuple[Part, ...]
    tube_given: bool


def joints(lk: FourBar, crank_angle) -> np.ndarray:
    """Joint positions O2, A, B, O4, P [m] at crank angles [rad], shape (..., 5, 2).

    B from the loop closure (:func:`pumplink.mechanisms.fourbar.kinematic_state`), A = l2 (cos θ2,
    sin θ2), P = O4 + (H / l4)(B - O4) (docs/physics.md §1).
    """
    th = np.asarray(crank_angle, float)
    st = kinematic_state(lk, th)
    o4 = np.broadcast_to(np.array([lk.pivot_x, lk.pivot_y], float), th.shape + (2,))
    a = lk.crank * np.stack([np.cos(th), np.sin(th)], axis=-1)
    b = np.stack([st.coupler_x, st.coupler_y], axis=-1)
    p = o4 + (lk.handle / lk.rocker) * (b - o4)
    return np.stack([np.zeros_like(a), a, b, o4, p], axis=-2)


def _feasible(spec: PumpSpec) -> Design:
    d = design(spec)
    if not d.feasible:
        raise InfeasibleDesign(f"{spec.name}: nothing to draw, {d.error}")
    return d


def parts(spec: PumpSpec, d: Design | None = None) -> tuple[Part, ...]:
    """The three moving links as bars with holes: crank, coupler, rocker with its handle.

    Hole centre distances are the synthesised link lengths; the holes are the pins of the spec's
    ``[parts]`` (or of their defaults: :attr:`pumplink.inputs.pump.PumpSpec.parts_or_defaults`),
    drilled to their diameter, and none where ``[parts]`` says the joint is welded (the crank to
    the axle at O2, a lug to the handle at B: ``crank_joint``, ``handle_joint``).
    """
    d = d or _feasible(spec)
    syn, lk = d.synthesis, spec.linkage
    shop = spec.parts_or_defaults
    hole = shop.pin_diameter
    mpl = lk.mass_per_length or LINK_MASS_PER_METRE
    edge = EDGE_FACTOR * hole
    crank, coupler, rocker = float(syn.crank_length), float(syn.coupler_length), float(syn.rocker_length)
    handle = float(syn.handle_length)
    crank_o2 = "hole" if shop.crank_joint == "hole" else "welded"
    handle_b = "hole" if shop.handle_joint == "hole" else "lug"
    return (
        Part(
            "crank",
            "crank (on the wheel)",
            np.array([0.0, crank]),
            ("O2", "A"),
            hole,
            crank,
            None,
            edge,
            mpl,
            hole_kinds=(crank_o2, "hole"),
        ),  # fmt: skip
        Part(
            "coupler",
            "coupler",
            np.array([0.0, coupler]),
            ("A", "B"),
            hole,
            coupler,
            None,
            edge,
            mpl,
            hole_kinds=("hole", "hole"),
        ),  # fmt: skip
        Part(
            "rocker-handle",
            "rocker and handle",
            np.array([0.0, rocker]),
            ("O4", "B"),
            hole,
            handle,
            "grip",
            edge,
            mpl,
            hole_kinds=("hole", handle_b),
        ),
    )


def tolerance_marks(spec: PumpSpec, parts_: tuple[Part, ...], target: float = 0.95):
    """The parts with each hole's tolerance for ``target`` of the builds to pass, and the notes:
    the allocation of :func:`pumplink.studies.tolerance.allocate` from the design's first-order
    sensitivities (the holes of one link share a tolerance; the grip has its own).  Returns
    ``(parts, Marks)``; where the design itself fails, the parts unchanged and the reason."""
    from dataclasses import replace

    from pumplink.studies import tolerance as tl

    fo = tl.sensitivities(tl.problem(spec, tl.tolerances(tl.WORKSHOP_TOLERANCE)))
    a = tl.allocate(fo, target)
    groups = dict(zip((g for g, _ in tl.GROUPS), zip(a.groups, a.critical)))
    if a.reason is not None:
        return parts_, Marks(target, a.distribution, math.nan, False, a.share, a.reason)
    marked = []
    for p in parts_:
        t, critical = groups["rocker" if p.key == "rocker-handle" else p.key]
        marked.append(
            replace(
                p,
                hole_tolerances=tuple(t for _ in p.holes),
                hole_critical=tuple(critical for _ in p.holes),
                end_tolerance=groups["grip"][0] if p.end_label else None,
                end_critical=bool(groups["grip"][1]) if p.end_label else False,
            )
        )
    stand, stand_critical = groups["stand"]
    return tuple(marked), Marks(target, a.distribution, stand, bool(stand_critical), a.share)


def drawing(spec: PumpSpec, peak: bool = False) -> Drawing:
    """The linkage at both dead centres (and at the peak-force position when ``peak``), its paths,
    the dimensions and the parts of one design.

    Raises
    ------
    InfeasibleDesign : the spec gives no crank-rocker.
    """
    d = _feasible(spec)
    syn, lk_spec = d.synthesis, spec.linkage
    lk = syn.linkage
    angles = [("extended dead centre", float(syn.dead_centre_extended))]
    angles.append(("folded dead centre", float(syn.dead_centre_folded)))
    if peak:
        r = force_analysis(spec, keep_samples=False)
        angles.append(("peak force (quasi-static, outside the dead bands)", float(r.dead_band_peak_angle)))
    js = joints(lk, np.array([a for _, a in angles]))
    poses = tuple(Pose(label, a, j) for (label, a), j in zip(angles, js))
    path = joints(lk, np.linspace(0.0, 2 * np.pi, PATH_POINTS))
    grip_path, coupler_path = path[:, 4], path[:, 2]

    rw, b = spec.wheel.radius, lk_spec.b
    ah = spec.wheel.axle_height
    o4 = np.array([float(syn.pivot_x), float(syn.pivot_y)])
    pts = np.concatenate([js.reshape(-1, 2), grip_path, [[-rw, -rw], [rw, rw]]])
    xmin, ymin = pts.min(axis=0)
    xmax, ymax = pts.max(axis=0)
    bottom = -ah if ah is not None else min(ymin, -rw) - 0.1 * (ymax - ymin)
    ymin = min(ymin, bottom)
    size = max(xmax - xmin, ymax - ymin)
    gap = 0.06 * size  # distance of a dimension line from what it measures
    ext = poses[0]
    a, bb, p = ext.joint("A"), ext.joint("B"), ext.joint("P")
    o2 = np.zeros(2)
    base = ymin - gap  # the chain L1 + b below everything
    dims = [
        Dimension("b", b, np.array([-b / 2, bottom]), np.array([b / 2, bottom]), base, "horizontal"),
        Dimension("L1", lk_spec.L1, o4, np.array([-b / 2, bottom]), base, "horizontal"),
        Dimension("D1", lk_spec.D1, np.zeros(2), o4, rw + gap, "vertical"),
        Dimension("l1 (frame)", float(syn.frame_length), o4, o2, -0.6 * gap),
        Dimension("l2 (crank)", float(syn.crank_length), o2, a, 0.8 * gap),
        Dimension("l3 (coupler)", float(syn.coupler_length), a, bb, -0.6 * gap),
        Dimension("l4 (rocker)", float(syn.rocker_length), o4, bb, 0.6 * gap),
        Dimension("H (handle)", float(syn.handle_length), o4, p, 1.6 * gap),
        Dimension(
            # steeply down to the right: its label, beyond the rim, clears the D1 dimension
            "rw (wheel)",
            rw,
            o2,
            rw * np.array([math.cos(-0.4 * math.pi), math.sin(-0.4 * math.pi)]),
            0.0,
        ),
    ]
    if ah is not None:
        dims.append(
            Dimension("axle height", ah, np.array([rw, -ah]), np.array([rw, 0.0]), xmax + 2 * gap, "vertical")
        )
    right = xmax + (3 if ah is not None else 2) * gap
    extent = (float(xmin - 2 * gap), float(right), float(base - gap), float(ymax + gap))
    return Drawing(
        spec.name,
        poses,
        grip_path,
        coupler_path,
        rw,
        b,
        float(bottom),
        ah,
        float(syn.swing),
        +1,
        tuple(dims),
        extent,
        parts(spec, d),
        lk_spec.mass_per_length is not None,
    )


@dataclass(frozen=True)
class Motion:
    """One revolution in equal crank steps, for the animation (SI units, radians).

    Attributes
    ----------
    crank_angle : (n,) crank angles θ2 = 2π k / n [rad].
    joints : (n, 5, 2) joint positions [m].
    force : (n,) horizontal operator force at the grip [N], +x positive; the flywheel model's
        profile when the spec gives the wheel's inertia, else the quasi-static force (NaN at a
        dead centre).
    force_limit : [N].
    model : the label of the model that gave ``force``.
    dead_centre : (n,) "extended", "folded" or "" when the step is the nearest to a dead centre.
    """

    crank_angle: np.ndarray
    joints: np.ndarray
    force: np.ndarray
    force_limit: float
    model: str
    dead_centre: tuple[str, ...]


def motion(spec: PumpSpec, steps: int = 72) -> Motion:
    """The linkage and the operator force at ``steps`` equal crank steps of one revolution.

    Raises
    ------
    InfeasibleDesign : the spec gives no crank-rocker.
    """
    d = _feasible(spec)
    syn = d.synthesis
    theta = np.arange(steps) * (2 * np.pi / steps)
    r = force_analysis(spec, at_deg=np.degrees(theta))
    force = r.samples.force
    if r.operator_force is not None:
        force = r.operator_force
    marks = [""] * steps
    for name, dc in (("extended", syn.dead_centre_extended), ("folded", syn.dead_centre_folded)):
        marks[int(np.rint(float(dc) / (2 * np.pi / steps))) % steps] = name
    return Motion(
        theta, joints(syn.linkage, theta), np.asarray(force, float), r.force_limit, r.model, tuple(marks)
    )

"""A build of a design: the holes a workshop drills, their coordinates, and the linkage a
build is (docs/tolerance.md).

A pump is built from its template: each link is a bar with holes drilled where they were
marked, and the stand carries the wheel axle O2 and the rocker pivot O4 where they were welded.
Every one of these *dimensions* is off by a little.  The holes (:data:`HOLES`) and their
coordinates (:data:`DIMENSIONS`):

* on each link, a hole is off **along** the bar (this changes the link's length) and **across**
  it (which changes it only to second order): crank O2 and A, coupler A and B, rocker O4 and B and
  the grip P on the handle (the rocker extended);
* on the stand, the axle O2 and the pivot O4 are off in **x** and **y** (O2's y also moves the
  axle height, so the grip's height above the ground follows O4 alone).

A build is analysed as the linkage it *is* (:func:`build`): each link's length is the distance
between its two holes as drilled, the handle the distance from O4 to the grip measured along the
rocker (O4 -> B), the pivot vector O4 - O2 as welded; nothing is re-synthesised, and the one
evaluation (:func:`pumplink.evaluate.evaluate` with ``PumpDesigns.linkage``, :func:`as_built`) judges it: the
deciding model's peak force, the swing it actually makes, its dead centres, the verdict.

Pure functions on floats and arrays (SI units).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from pumplink.evaluate import PumpDesigns
from pumplink.mechanisms.fourbar import FourBar

#: The holes and pivots of a build: key, the part it is on, words.  Link holes are off along and
#: across their bar, the stand's pivots in x and y (product coordinates, docs/physics.md §1).
HOLES = (
    ("crank.O2", "crank", "crank hole on the axle (O2)"),
    ("crank.A", "crank", "crank pin hole (A)"),
    ("coupler.A", "coupler", "coupler hole at the crank pin (A)"),
    ("coupler.B", "coupler", "coupler hole at the rocker (B)"),
    ("rocker.O4", "rocker", "rocker pivot hole (O4)"),
    ("rocker.B", "rocker", "rocker hole at the coupler (B)"),
    ("rocker.grip", "rocker", "grip on the handle (P)"),
    ("stand.O2", "stand", "wheel axle on the stand (O2)"),
    ("stand.O4", "stand", "rocker pivot on the stand (O4)"),
)
HOLE_KEYS = tuple(h[0] for h in HOLES)
#: The parts, in the order a tolerance per part is given (``--crank-hole`` ...).
PARTS = ("crank", "coupler", "rocker", "stand")
#: The coordinates of each hole: a link hole along and across its bar, a stand pivot in x and y.
DIMENSIONS = tuple(
    (key, axis) for key, part, _ in HOLES for axis in (("x", "y") if part == "stand" else ("along", "across"))
)

#: The linkage parameters a build changes, and the axle height (what :func:`build` returns).
PARAMETERS = ("pivot_x", "pivot_y", "crank", "coupler", "rocker", "handle", "axle_height")


def _index(key: str, axis: str) -> int:
    return DIMENSIONS.index((key, axis))


def build(nominal: FourBar, axle_height, offsets) -> tuple[FourBar, np.ndarray]:
    """The linkage a build *is*, and its axle height, from the design's and the offsets of its
    holes (exactly, not linearised).

    Parameters
    ----------
    nominal : the design's four-bar (floats, or arrays broadcasting with the builds).
    axle_height : the design's axle height [m] (NaN: not given).
    offsets : (builds, 18) offsets [m] of :data:`DIMENSIONS`: link holes along and across the bar
        from the first hole to the second (the grip along O4 -> B), stand pivots in x and y.

    Returns
    -------
    (FourBar, axle_height) over the builds: crank = |A - O2|, coupler = |B - A|, rocker = |B - O4|
    between the holes as drilled; handle = (P - O4) . (B - O4) / rocker, the grip measured along
    the rocker; pivot = O4 - O2 as welded; axle height + the axle's y offset.
    """
    u = np.asarray(offsets, float)

    def d(key, axis):
        return u[:, _index(key, axis)]

    def length(first, second, nominal_length):
        along = nominal_length + d(second, "along") - d(first, "along")
        across = d(second, "across") - d(first, "across")
        return along, across, np.hypot(along, across)

    _, _, crank = length("crank.O2", "crank.A", nominal.crank)
    _, _, coupler = length("coupler.A", "coupler.B", nominal.coupler)
    along, across, rocker = length("rocker.O4", "rocker.B", nominal.rocker)
    grip_along = nominal.handle + d("rocker.grip", "along") - d("rocker.O4", "along")
    grip_across = d("rocker.grip", "across") - d("rocker.O4", "across")
    handle = (grip_along * along + grip_across * across) / rocker
    px = nominal.pivot_x + d("stand.O4", "x") - d("stand.O2", "x")
    py = nominal.pivot_y + d("stand.O4", "y") - d("stand.O2", "y")
    branch = np.broadcast_to(np.asarray(nominal.branch, float), crank.shape)
    axle = np.asarray(axle_height, float) + d("stand.O2", "y")
    return FourBar(px, py, crank, coupler, rocker, handle, branch), axle


def first_order_map() -> np.ndarray:
    """(7, 18): how each of :data:`PARAMETERS` moves with each of :data:`DIMENSIONS` to first order
    (∂parameter/∂offset of :func:`build` at zero offsets: ±1 along a bar or on the stand, 0 across)."""
    m = np.zeros((len(PARAMETERS), len(DIMENSIONS)))
    rows = {
        "pivot_x": (("stand.O4", "x", 1), ("stand.O2", "x", -1)),
        "pivot_y": (("stand.O4", "y", 1), ("stand.O2", "y", -1)),
        "crank": (("crank.A", "along", 1), ("crank.O2", "along", -1)),
        "coupler": (("coupler.B", "along", 1), ("coupler.A", "along", -1)),
        "rocker": (("rocker.B", "along", 1), ("rocker.O4", "along", -1)),
        "handle": (("rocker.grip", "along", 1), ("rocker.O4", "along", -1)),
        "axle_height": (("stand.O2", "y", 1),),
    }
    for name, entries in rows.items():
        for key, axis, sign in entries:
            m[PARAMETERS.index(name), _index(key, axis)] = sign
    return m


def broadcast_column(value, n: int):
    """A value (one, or a column over designs) as a column of ``n`` floats (a read-only view)."""
    return np.broadcast_to(np.asarray(value, float), (n,))


def take(designs: PumpDesigns, idx) -> PumpDesigns:
    """The designs ``idx`` (an index array) of columns over designs: every column broadcast to
    the designs and indexed, the built linkage too."""
    idx = np.asarray(idx)
    n = max(
        [np.size(getattr(designs, f.name)) for f in dataclasses.fields(designs) if f.name != "linkage"]
        + ([np.size(designs.linkage.crank)] if designs.linkage is not None else [])
    )
    out = {}
    for f in dataclasses.fields(designs):
        v = getattr(designs, f.name)
        if f.name == "arms_in_verdict" or v is None:
            out[f.name] = v
        elif f.name == "linkage":
            out[f.name] = FourBar(*(broadcast_column(p, n)[idx] for p in v.parameters))
        elif dataclasses.is_dataclass(v):  # the spec's [parts]: each size a column too
            out[f.name] = type(v)(
                **{g.name: broadcast_column(getattr(v, g.name), n)[idx] for g in dataclasses.fields(v)}
            )
        else:
            out[f.name] = broadcast_column(v, n)[idx]
    return PumpDesigns(**out)


def as_built(designs: PumpDesigns, linkage: FourBar, axle_height) -> PumpDesigns:
    """The evaluation's columns for builds: ``designs`` (one design, or as many as the builds) with
    the built ``linkage`` and axle height (NaN: the design gives none)."""
    n = np.size(linkage.crank)
    axle = None if designs.axle_height is None else broadcast_column(axle_height, n)
    return dataclasses.replace(
        designs,
        linkage=linkage,
        rocker=broadcast_column(linkage.rocker, n),  # columns of n builds: the rest broadcast to them
        handle=broadcast_column(linkage.handle, n),
        axle_height=axle,
    )

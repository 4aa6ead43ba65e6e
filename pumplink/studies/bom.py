"""The bill of materials: every part of the pump's drive with a size a workshop can buy, its
length to cut and its mass (``pumplink bom``, the template's first page, the report;
docs/workshop.md §4).

The sizes come from the spec's ``[parts]`` where it gives them, else from pumplink's defaults
(:attr:`pumplink.inputs.pump.PumpSpec.parts_or_defaults`); the links' lengths and holes from the
drawing (:func:`pumplink.studies.drawing.parts`, the template's).  How each joint is made where
the spec does not say is pumplink's default construction, stated here once:

* the coupler and the handle are cut from the handle's tube (``[parts] handle_diameter``,
  ``handle_wall``), the crank from a round bar (``crank_diameter``), each to the template's cut
  length: the hole centres plus :data:`pumplink.studies.drawing.EDGE_FACTOR` pin diameters beyond
  the outer ones;
* a pin turns in a bush of ``pin_width`` welded across the end of the link that swings on it
  (the coupler at A and B, the handle at O4); where ``pin_width`` is not longer than both walls of
  the handle's tube the pin bears on the drilled tube and there is no bush;
* each pin is held by the other side of its joint: the crank's bar at A, the handle's tube (a
  drilled hole) or its lug at B, the stand's bracket of two :data:`PLATE` plates at O4; it is that
  long plus the bush plus :data:`PIN_END` for a washer and a split pin;
* a lug (``handle_joint = "lug"``) is two plates of :data:`PLATE` flat bar, 3 pin diameters wide
  and 4 long, either side of the coupler's bush, welded to the handle;
* a polyethylene bush (``[parts] bush``) is HDPE rod bored for the pin, pressed into a sleeve of
  the smallest medium steel tube (EN 10255) whose bore leaves it a wall of :data:`PE_WALL`.

Steel at 7850 kg/m³, HDPE at 950 kg/m³.  Pure functions of a spec; SI units.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pumplink.constants import LINK_MASS_PER_METRE
from pumplink.evaluate import column_torque
from pumplink.inputs.pump import PumpSpec
from pumplink.studies.drawing import EDGE_FACTOR, parts

#: Densities [kg/m³]: steel (EN 10255's basis, 7.85 kg/dm³) and high-density polyethylene.
STEEL, HDPE = 7850.0, 950.0
#: Medium steel tubes, EN 10255 series M: (nominal size, outer diameter [m], wall [m]).
MEDIUM_TUBES = (
    ('1/4"', 0.0135, 0.0023),
    ('3/8"', 0.0172, 0.0023),
    ('1/2"', 0.0213, 0.0026),
    ('3/4"', 0.0269, 0.0026),
    ('1"', 0.0337, 0.0032),
    ('1 1/4"', 0.0424, 0.0032),
    ('1 1/2"', 0.0483, 0.0032),
    ('2"', 0.0603, 0.0036),
)
#: Plate for the stand's pivot bracket and the lug [m] (6 mm flat bar).
PLATE = 0.006
#: A pin's length beyond what it passes through, for a washer and a split pin [m].
PIN_END = 0.010
#: The wall a steel bush leaves around its pin at least [m] (precision tube, EN 10305-1, whole mm).
BUSH_WALL = 0.003
#: The wall a polyethylene bush leaves around its pin at least [m].
PE_WALL = 0.004
#: Where a mass per metre and a tube's may differ as rounding [-]: EN 10255's tables round to 0.01 kg/m.
SAME_MASS = 0.01


def tube_mass(diameter, wall) -> float:
    """Mass per metre of a steel tube [kg/m]: ρ π (D − s) s."""
    return STEEL * math.pi * (diameter - wall) * wall


def bar_mass(diameter, density=STEEL) -> float:
    """Mass per metre of a round bar [kg/m]: ρ π d²/4."""
    return density * math.pi * diameter**2 / 4.0


def tube_name(diameter, wall) -> str:
    """'33.7 × 3.2 mm tube (1" medium, EN 10255)', or the size alone when it is not in the series."""
    size = f"{diameter * 1000:g} × {wall * 1000:g} mm steel tube"
    for nominal, d, s in MEDIUM_TUBES:
        if abs(d - diameter) < 1e-6 and abs(s - wall) < 1e-6:
            return f"{size} ({nominal} medium, EN 10255)"
    return size


@dataclass(frozen=True)
class Item:
    """One line of the bill of materials (SI units).

    part : what it is for;  stock : the size to buy;  count : how many;  length : of each piece to
    cut [m] (NaN: a part bought or made whole);  mass : of each [kg] (NaN: not known);  note : how
    it is made or fitted.
    """

    part: str
    stock: str
    count: int
    length: float
    mass: float
    note: str = ""

    @property
    def total_mass(self) -> float:
        return self.count * self.mass


@dataclass(frozen=True)
class Bom:
    """The bill of materials of a design: ``items``; the moving links' tubes between their joints
    (the coupler A to B, the handle O4 to the grip or the rocker's end) [kg], as the BOM's tube
    weighs them and as the dynamics counts them (``dynamics_``: linkage.mass_per_length, or the
    masses given), and a note where the spec's ``linkage.mass_per_length`` is not the tube's.  The
    pieces cut are longer by the edges beyond the outer holes (``items``).  ``ratchet_note``: where the
    ratchet goes and the torque it must hold (None without a water column)."""

    name: str
    items: tuple[Item, ...]
    coupler_mass: float
    handle_mass: float
    dynamics_coupler_mass: float
    dynamics_handle_mass: float
    tube_note: str | None
    ratchet_note: str | None = None

    @property
    def mass(self) -> float:
        """Everything with a known mass [kg]."""
        return sum(i.total_mass for i in self.items if math.isfinite(i.mass))


def bom(spec: PumpSpec, masses=None) -> Bom:
    """The bill of materials of ``spec`` (module docstring); ``masses`` the links' masses the
    dynamics counts (:class:`pumplink.models.Masses`: coupler, handle [kg]), else the bars of
    ``linkage.mass_per_length`` between their joints."""
    shop = spec.parts_or_defaults
    links = {p.key: p for p in parts(spec)}
    d, w = shop.pin_diameter, shop.pin_width
    tube = tube_name(shop.handle_diameter, shop.handle_wall)
    per_metre = tube_mass(shop.handle_diameter, shop.handle_wall)
    mpl = spec.linkage.mass_per_length or LINK_MASS_PER_METRE
    coupler, handle = links["coupler"], links["rocker-handle"]
    crank = links["crank"]
    at_o2 = "welded to the axle at O2" if shop.crank_joint == "welded" else f"drilled {d * 1000:g} mm at O2"
    bushed = w > 2 * shop.handle_wall + 1e-9
    items = [
        Item("coupler", tube, 1, coupler.cut_length, coupler.cut_length * per_metre,
             f"holes {d * 1000:g} mm, {coupler.centre_distance * 1000:.1f} mm apart"),
        Item("handle (rocker to grip)", tube, 1, handle.cut_length, handle.cut_length * per_metre,
             f"pivot O4 at one end, B {float(handle.holes[1]) * 1000:.1f} mm from it, the grip at "
             f"{handle.end * 1000:.1f} mm"),
        Item("crank", f"Ø{shop.crank_diameter * 1000:g} mm steel round bar (EN 10060)", 1, crank.cut_length,
             crank.cut_length * bar_mass(shop.crank_diameter),
             f"O2 to A {crank.centre_distance * 1000:.1f} mm; " + at_o2),
    ]  # fmt: skip
    # the pins: what each passes through besides its bush
    swinging = w if bushed else shop.handle_diameter  # the bush, or the drilled tube it turns in
    held = {
        "A": (shop.crank_diameter, "through the crank's end"),
        "B": (2 * PLATE, "through the lug's two plates")
        if shop.handle_joint == "lug"
        else (shop.handle_diameter, "through the handle's tube"),
        "O4": (2 * PLATE, "through the stand's bracket"),
    }
    for joint, (through, how) in held.items():
        length = swinging + through + PIN_END
        items.append(
            Item(
                f"pin {joint}",
                f"Ø{d * 1000:g} mm bright steel round bar (EN 10278)",
                1,
                length,
                length * bar_mass(d),
                f"{how}, a washer and a split pin",
            )  # fmt: skip
        )
    if bushed:
        items.extend(_bushes(shop, d, w))
    if shop.handle_joint == "lug":
        width, long = math.ceil(3 * d * 200 - 1e-9) / 200, 4 * d  # 3 pin diameters, to the next 5 mm
        items.append(
            Item(
                "lug at B",
                f"{width * 1000:g} × {PLATE * 1000:g} mm steel flat bar",
                2,
                long,
                long * width * PLATE * STEEL,
                f"drilled {d * 1000:g} mm, welded to the handle either side of the coupler's bush",
            )  # fmt: skip
        )
    wheel = spec.wheel
    inches = 2 * wheel.radius / 0.0254
    items.append(
        Item(
            "wheel",
            f'Ø{2 * wheel.radius * 1000:.0f} mm (a {inches:.0f}" tyre rim class)',
            1,
            math.nan,
            math.nan if wheel.mass is None else wheel.mass,
            "wheel.mass as the spec gives it" if wheel.mass is not None else "its mass not given",
        )  # fmt: skip
    )
    if spec.ratchet is not None:
        r = spec.ratchet
        teeth = "no play (a freewheel)" if r.teeth == 0 else f"{r.teeth} teeth"
        items.append(
            Item(
                "ratchet",
                f"ratchet and pawl, {teeth}, holding ≥ {r.torque:g} N·m",
                1,
                math.nan,
                math.nan,
                "on the wheel's axle, so that the wheel cannot turn back",
            )  # fmt: skip
        )
    masses_given = masses is not None
    arm = max(handle.end, float(handle.holes[1]))  # the handle as the dynamics takes it: O4 to max(H, rocker)
    dyn_coupler = float(np.ravel(masses.coupler)[0]) if masses_given else mpl * coupler.centre_distance
    dyn_handle = float(np.ravel(masses.handle)[0]) if masses_given else mpl * arm
    note = None
    if abs(mpl - per_metre) > SAME_MASS * per_metre:
        source = "linkage.mass_per_length" if spec.linkage.mass_per_length is not None else "its default"
        note = (
            f"the dynamics counts the links at {mpl:.3f} kg/m ({source}), the {tube} weighs "
            f"{per_metre:.3f} kg/m: give linkage.mass_per_length = {per_metre:.3f} to count the tube built"
        )
    between = (per_metre * coupler.centre_distance, per_metre * arm)
    return Bom(spec.name, tuple(items), *between, dyn_coupler, dyn_handle, note, _ratchet_note(spec))


def _ratchet_note(spec: PumpSpec) -> str | None:
    """Where the ratchet goes and what it must hold (None without a water column)."""
    load = spec.load
    if load.head is None:
        return None
    need = float(column_torque(load.head, load.pipe_diameter, spec.wheel.radius))
    r = spec.ratchet
    if r is None:
        return (
            f"fit a ratchet on the wheel's axle O2 that holds at least {need:.1f} N·m (the water column's): "
            "without it the column drives the handle back when it is let go (docs/workshop.md §3)"
        )
    teeth = "with no play" if r.teeth == 0 else f"{r.teeth} teeth"
    held = "holds" if r.torque >= need else "does NOT hold"
    return (
        f"the ratchet ({teeth}, {r.torque:g} N·m) goes on the wheel's axle O2; it {held} the column's "
        f"{need:.1f} N·m"
    )


def _bushes(shop, d, w) -> list[Item]:
    """The three bushes the pins turn in (coupler at A and B, handle at O4)."""
    where = "welded across the coupler's ends (A, B) and the handle at O4"
    if shop.bush == "steel":
        outer = math.ceil((d + 2 * BUSH_WALL) * 1000 - 1e-9) / 1000
        wall = (outer - d) / 2
        return [
            Item(
                "bush",
                f"{outer * 1000:g} × {wall * 1000:g} mm seamless precision tube (EN 10305-1)",
                3,
                w,
                w * tube_mass(outer, wall),
                f"reamed to the pin, {where}",
            )  # fmt: skip
        ]
    sleeve = next(((n, o, s) for n, o, s in MEDIUM_TUBES if o - 2 * s >= d + 2 * PE_WALL), MEDIUM_TUBES[-1])
    nominal, outer, wall = sleeve
    bore = outer - 2 * wall
    rod = math.ceil(bore * 200 - 1e-9) / 200  # the next 5 mm of rod to turn down
    pe = w * HDPE * math.pi * (bore**2 - d**2) / 4
    return [
        Item("bush sleeve", tube_name(outer, wall), 3, w, w * tube_mass(outer, wall), where),
        Item(
            "polyethylene bush",
            f"Ø{rod * 1000:g} mm HDPE rod",
            3,
            w,
            pe,
            f"turned to {bore * 1000:.1f} mm, bored {d * 1000:g} mm, pressed into its sleeve",
        ),  # fmt: skip
    ]


__all__ = ["Bom", "Item", "MEDIUM_TUBES", "bar_mass", "bom", "tube_mass", "tube_name", "EDGE_FACTOR"]

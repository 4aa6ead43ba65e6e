"""The bill of materials (``pumplink bom``, ``pumplink.studies.bom``).

Expected values are EN 10255's formula for the mass of tube per metre, hand
formulas for round bar (ρ π d²/4, ρ = 7850 kg/m³), the construction rules of docs/workshop.md §4
written out here, and the masses the evaluation's dynamics uses (its ``masses``: the coupler's and
the handle's).
"""

from __future__ import annotations

import math
import re

import pytest
from shipped import ROOT, ROPE_PUMP_SPECS, spec_id

from pumplink.evaluate import evaluate, pump_designs
from pumplink.inputs.pump import load_spec, parse_spec, spec_to_dict, spec_values
from pumplink.studies import bom as B

VILLAGE = ROOT / "configs" / "village-10m.toml"


@pytest.mark.parametrize("tube", B.MEDIUM_TUBES, ids=lambda t: t[0])
def test_medium_tube_masses_are_the_standard_s_formula(tube):
    """EN 10255 (and EN 10220) give a tube's mass per metre as M = 0.0246615 (D - T) T kg/m, D and
    T in mm (steel of 7.85 kg/dm³): the 1" tube, 33.7 x 3.2 mm, is 2.407 kg/m."""
    _, d, s = tube
    assert B.tube_mass(d, s) == pytest.approx(0.0246615 * (d * 1000 - s * 1000) * s * 1000, rel=1e-6)


def test_the_one_inch_tube_is_the_village_s_mass_per_metre():
    assert B.tube_mass(0.0337, 0.0032) == pytest.approx(2.407, abs=5e-4)


def test_the_village_bom_lists_every_part_with_a_size_to_buy():
    """configs/village-10m.toml: the coupler and the handle of 1" medium tube, the 20 mm crank bar,
    three 12 mm pins, three polyethylene bushes in steel sleeves, the lug, the wheel and the
    ratchet, each with a stock size one can buy and (the cut ones) a length and a mass."""
    b = B.bom(load_spec(VILLAGE))
    parts = {i.part: i for i in b.items}
    assert set(parts) == {"coupler", "handle (rocker to grip)", "crank", "pin A", "pin B", "pin O4",
                          "bush sleeve", "polyethylene bush", "lug at B", "wheel", "ratchet"}  # fmt: skip
    tube = '33.7 × 3.2 mm steel tube (1" medium, EN 10255)'
    assert parts["coupler"].stock == parts["handle (rocker to grip)"].stock == tube
    assert parts["crank"].stock == "Ø20 mm steel round bar (EN 10060)"
    assert {parts[f"pin {j}"].stock for j in ("A", "B", "O4")} == {"Ø12 mm bright steel round bar (EN 10278)"}
    assert parts["bush sleeve"].stock == '26.9 × 2.6 mm steel tube (3/4" medium, EN 10255)'
    assert re.fullmatch(r"Ø\d+ mm HDPE rod", parts["polyethylene bush"].stock)
    assert parts["lug at B"].stock == "40 × 6 mm steel flat bar"  # 3 x 12 mm, to the next 5 mm
    assert parts["ratchet"].stock == "ratchet and pawl, 24 teeth, holding ≥ 30 N·m"
    assert parts["wheel"].mass == 10.0
    for i in b.items:
        if i.part not in ("wheel", "ratchet"):
            assert math.isfinite(i.length) and i.length > 0 and math.isfinite(i.mass) and i.mass > 0, i
    # the pins by the rules of docs/workshop.md §4: the 40 mm bush, what holds the pin, 10 mm for
    # a washer and a split pin: 40 + 20 (the crank bar) + 10 at A, 40 + 2 x 6 (the lug's plates) + 10
    # at B, 40 + 2 x 6 (the stand's bracket) + 10 at O4
    assert [round(parts[f"pin {j}"].length * 1000, 9) for j in ("A", "B", "O4")] == [70.0, 62.0, 62.0]
    # a 12 mm pin of 70 mm: 7850 pi 0.012^2 / 4 x 0.070 = 0.0621 kg
    assert parts["pin A"].mass == pytest.approx(7850 * math.pi * 0.012**2 / 4 * 0.070, rel=1e-12)
    assert parts["crank"].mass == pytest.approx(
        7850 * math.pi * 0.020**2 / 4 * parts["crank"].length, rel=1e-12
    )
    assert "axle O2" in b.ratchet_note and "10.2 N·m" in b.ratchet_note


@pytest.mark.parametrize("path", ROPE_PUMP_SPECS, ids=spec_id)
def test_the_bom_s_links_weigh_what_the_dynamics_counts(path):
    """Every shipped spec: the coupler's and the handle's tube between their joints, as the BOM
    weighs them (its tube's mass per metre), are the masses the evaluation's dynamics uses, to
    EN 10255's rounding of the mass per metre (1 %); none needs a note."""
    spec = load_spec(path)
    ev = evaluate(pump_designs(spec_values(spec)), ("model",))
    b = B.bom(spec, ev.masses)
    assert b.coupler_mass == pytest.approx(float(ev.masses.coupler[0]), rel=B.SAME_MASS)
    assert b.handle_mass == pytest.approx(float(ev.masses.handle[0]), rel=B.SAME_MASS)
    assert b.tube_note is None


def test_a_spec_whose_tube_is_not_its_mass_per_metre_is_told():
    """[parts] says 1" tube (2.41 kg/m) but linkage.mass_per_length 1.0: the note says so and what
    to give."""
    data = spec_to_dict(load_spec(VILLAGE))
    data["linkage"]["mass_per_length"] = 1.0
    b = B.bom(parse_spec(data))
    assert b.tube_note is not None and "linkage.mass_per_length = 2.407" in b.tube_note


@pytest.mark.parametrize("joints", [None, ("hole", "hole", 0.010), ("lug", "welded", 0.016)],
                         ids=["as shipped", "hole-hole-10mm", "lug-welded-16mm"])  # fmt: skip
def test_the_template_s_holes_take_the_bom_s_pins(joints):
    """The village template's holes (pumplink template) and the BOM's pins: every joint drilled on
    a link (the crank's O2 on the axle aside) or on the lug has a pin of the BOM, of the holes'
    diameter, and every pin of the BOM goes through such a hole."""
    from test_drawing import _with_joints

    from pumplink.studies.drawing import parts

    spec = _with_joints(VILLAGE, joints)
    b = B.bom(spec)
    pins = {i.part.removeprefix("pin "): i for i in b.items if i.part.startswith("pin ")}
    holes = {}
    for p in parts(spec):
        for label, drilled in zip(p.hole_labels, p.drilled):
            if drilled and label != "O2":  # O2: the axle, not a pin
                holes.setdefault(label, set()).add(p.hole_diameter)
    lug = next((i for i in b.items if i.part == "lug at B"), None)
    if lug is not None:  # the lug's plates are drilled for pin B
        assert spec.parts.handle_joint == "lug"
        holes.setdefault("B", set()).add(float(re.search(r"drilled ([\d.]+) mm", lug.note)[1]) / 1000)
    assert set(pins) == set(holes) == {"A", "B", "O4"}
    for joint, item in pins.items():
        diameter = float(re.fullmatch(r"Ø([\d.]+) mm .*", item.stock)[1]) / 1000
        assert holes[joint] == {diameter}, joint
        if joints is not None:
            assert diameter == joints[2], joint  # the pins of the [parts] given

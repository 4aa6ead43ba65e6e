"""A batch that varies any one spec key writes one row per variant, in every format, or stops
with one line (exit 2) before writing anything.

The number of designs an evaluation holds was once taken from the inputs the synthesis reads, so
a batch varying only a key read elsewhere (``wheel.axle_height``, the ``[parts]``) or nowhere
(``linkage.hole_diameter``; ``wheel.radius`` beside a piston pump's ``wheel.inertia``) crashed
or wrote one row for all its variants.  Here every key a batch may vary (``VARIABLE_KEYS``,
``PISTON_VARIABLE_KEYS``) is varied alone over three values, through the real entry point in this
process, and the rows are counted in the CSV, the JSON, the table and the Parquet file.
"""

from __future__ import annotations

import csv
import io
import json
import re
import tomllib
from pathlib import Path

import pyarrow.parquet as pq
import pytest
import tomli_w
from in_process import run_main

from pumplink.inputs.batch import PISTON_VARIABLE_KEYS, VARIABLE_KEYS

ROOT = Path(__file__).resolve().parents[2]
PISTON = tomllib.loads((ROOT / "examples" / "piston-pump.toml").read_text(encoding="utf-8"))

#: A rope pump that gives every optional table a key can vary into: the prototype's linkage with
#: an axle height, a head and a pipe (so the water keys apply) and the [parts] (so the part keys do).
ROPE = {
    "name": "every-key",
    "wheel": {"radius": 0.25, "axle_height": 0.6},
    "linkage": {"L1": 0.40, "D1": 0.20, "b": 0.10, "rocker": 0.20, "handle": 1.00, "swing": 60.0},
    "load": {"head": 8.0, "pipe_diameter": 0.023},
    "operator": {"force_limit": 100.0, "speed": 360.0, "dead_band": 20.0},
    "parts": {"pin_diameter": 0.012},
}
#: The base for the keys that need another one: the rope force instead of a head and a pipe.
ROPE_BY_FORCE = {**ROPE, "load": {"rope_force": 45.0}}

#: Three valid values per numeric key (each with the base it is varied on).
ROPE_VALUES = {
    "wheel.radius": [0.24, 0.25, 0.26],
    "wheel.axle_height": [0.5, 0.6, 0.7],
    "wheel.inertia": [0.4, 0.5, 0.6],
    "wheel.mass": [8.0, 9.0, 10.0],
    "linkage.L1": [0.38, 0.40, 0.42],
    "linkage.D1": [0.19, 0.20, 0.21],
    "linkage.b": [0.09, 0.10, 0.11],
    "linkage.rocker": [0.19, 0.20, 0.21],
    "linkage.handle": [0.9, 1.0, 1.1],
    "linkage.swing": [55.0, 60.0, 65.0],
    "linkage.mass_per_length": [1.5, 2.0, 2.5],
    "linkage.coupler_mass": [0.5, 1.0, 1.5],
    "linkage.handle_mass": [1.0, 1.5, 2.0],
    "linkage.hole_diameter": [0.008, 0.010, 0.012],
    "load.rope_force": [40.0, 45.0, 50.0],
    "load.head": [7.0, 8.0, 9.0],
    "load.pipe_diameter": [0.020, 0.023, 0.025],
    "load.efficiency": [0.6, 0.7, 0.8],
    "load.volumetric_efficiency": [0.8, 0.85, 0.9],
    "load.moving_mass": [2.0, 3.0, 4.0],
    "load.piston_clearance": [0.0003, 0.00035, 0.0004],
    "load.piston_spacing": [0.8, 1.0, 1.2],
    "operator.force_limit": [90.0, 100.0, 110.0],
    "operator.sustained_power": [60.0, 70.0, 75.0],
    "operator.hour_power": [150.0, 160.0, 170.0],
    "operator.grip_height_min": [0.8, 0.85, 0.9],
    "operator.grip_height_max": [1.3, 1.35, 1.4],
    "operator.grip_speed_warn": [2.3, 2.4, 2.5],
    "operator.grip_speed_fail": [4.0, 4.5, 5.0],
    "operator.cadence_min": [25.0, 30.0, 35.0],
    "operator.cadence_max": [55.0, 60.0, 65.0],
    "operator.filling_power": [70.0, 81.0, 90.0],
    "operator.speed": [340.0, 360.0, 380.0],
    "operator.dead_band": [15.0, 20.0, 25.0],
    "operator.speed_fluctuation": [0.1, 0.2, 0.3],
    "operator.arm_mass": [3.0, 4.0, 5.0],
    "parts.pin_diameter": [0.010, 0.012, 0.014],
    "parts.pin_width": [0.004, 0.005, 0.006],
    "parts.handle_diameter": [0.025, 0.027, 0.030],
    "parts.handle_wall": [0.002, 0.0026, 0.003],
    "parts.handle_notch": [1.0, 1.5, 2.0],
    "parts.crank_diameter": [0.012, 0.0127, 0.015],
    "parts.crank_notch": [1.0, 1.5, 2.0],
    "parts.wear_allowance": [0.0004, 0.0005, 0.0006],
    "ratchet.torque": [15.0, 20.0, 25.0],
    "ratchet.teeth": [12, 24, 36],
    "use.hours_per_day": [6.0, 8.0, 10.0],
    "use.litres_per_person_day": [15.0, 20.0, 25.0],
    "use.people": [100.0, 200.0, 300.0],
}
PISTON_VALUES = {
    "piston.bore": [0.04, 0.05, 0.06],
    "piston.head": [8.0, 10.0, 12.0],
    "piston.efficiency": [0.5, 0.6, 0.7],
    "piston.volumetric_efficiency": [0.8, 0.85, 0.9],
    "crank_slider.crank": [0.04, 0.05, 0.06],
    "crank_slider.rod": [0.2, 0.25, 0.3],
    "crank_slider.offset": [0.0, 0.01, 0.02],
    "operator.handle": [0.25, 0.3, 0.35],
    "operator.force_limit": [90.0, 100.0, 110.0],
    "operator.sustained_power": [60.0, 70.0, 75.0],
    "operator.hour_power": [150.0, 160.0, 170.0],
    "operator.speed": [220.0, 240.0, 260.0],
    "operator.speed_fluctuation": [0.1, 0.2, 0.3],
    "wheel.inertia": [0.4, 0.5, 0.6],
    "wheel.mass": [4.0, 5.0, 6.0],
    "wheel.radius": [0.2, 0.25, 0.3],
    "use.hours_per_day": [6.0, 8.0, 10.0],
    "use.litres_per_person_day": [15.0, 20.0, 25.0],
    "use.people": [100.0, 200.0, 300.0],
}
#: Keys that are not numbers: a batch refuses to vary them (one line, exit 2).
NOT_NUMBERS = {
    "operator.profile": ["men", "women"],
    "operator.arms_in_verdict": [True, False],
    "parts.handle_joint": ["hole", "lug"],
    "parts.crank_joint": ["welded", "hole"],
    "parts.bush": ["steel", "polyethylene"],
}


def rope_base(key: str) -> dict:
    if key.startswith("ratchet."):  # a ratchet that holds the 8 m column's 7.9 N m
        return {**ROPE, "ratchet": {"torque": 20.0, "teeth": 24}}
    if key == "load.rope_force":
        return ROPE_BY_FORCE
    if key in ("wheel.inertia", "wheel.mass", "load.moving_mass"):  # the energy models: no [parts]
        return {k: v for k, v in ROPE.items() if k != "parts"}  # (their part checks cost ~50 ms each)
    if key == "linkage.hole_diameter":  # the older name of parts.pin_diameter: a spec gives one
        return {k: v for k, v in ROPE.items() if k != "parts"}
    return ROPE


def piston_base(key: str) -> dict:
    if key == "wheel.mass":
        return {**PISTON, "wheel": {"mass": 5.0, "radius": 0.25}}
    if key == "wheel.radius":  # beside the inertia the radius is read nowhere: still one row each
        return {**PISTON, "wheel": {"inertia": 0.5}}
    return PISTON


CASES = [("rope", k, v) for k, v in ROPE_VALUES.items()] + [
    ("piston", k, v) for k, v in PISTON_VALUES.items()
]


def batch_file(folder: Path, base: dict, key: str, values: list) -> Path:
    path = folder / "batch.toml"
    path.write_text(tomli_w.dumps({"name": "k", "base": base, "vary": {key: values}}), encoding="utf-8")
    return path


def test_the_cases_cover_every_key_a_batch_may_vary():
    assert set(ROPE_VALUES) | set(NOT_NUMBERS) == set(VARIABLE_KEYS)
    assert set(PISTON_VALUES) | {"operator.profile"} == set(PISTON_VARIABLE_KEYS)


def rows_in_every_format(folder: Path, path: Path) -> dict[str, list]:
    """The rows a batch file gives as CSV, JSON, table (the lines that start with an index) and
    Parquet, each run required to complete (exit 0 with ``--fail-on none``)."""
    common = ("batch", path, "--samples", "12", "--fail-on", "none", "--workers", "1")
    rows = {}
    code, out, err = run_main(*common, "--format", "csv")
    assert code == 0, err
    rows["csv"] = list(csv.DictReader(io.StringIO(out)))
    code, out, err = run_main(*common, "--format", "json")
    assert code == 0, err
    rows["json"] = json.loads(out)["variants"]
    code, out, err = run_main(*common, "--format", "table")
    assert code == 0, err
    rows["table"] = re.findall(r"^#(\d+) ", out, flags=re.M)
    code, _, err = run_main(*common, "--format", "parquet", "--out", folder / "rows.parquet")
    assert code == 0, err
    rows["parquet"] = pq.read_table(folder / "rows.parquet").to_pylist()
    return rows


@pytest.mark.parametrize(("pump", "key", "values"), CASES, ids=[f"{p}:{k}" for p, k, _ in CASES])
def test_a_batch_varying_one_key_writes_a_row_per_variant(tmp_path, pump, key, values):
    base = rope_base(key) if pump == "rope" else piston_base(key)
    rows = rows_in_every_format(tmp_path, batch_file(tmp_path, base, key, values))
    for fmt, got in rows.items():
        assert len(got) == len(values), (fmt, len(got))
    assert rows["table"] == ["0", "1", "2"]
    # each row carries its own variant's value (the CSV column of the key, or the piston pump's name)
    names = [r.get("name") or r.get("variant") for r in rows["csv"]]
    assert [re.search(r"=([^\]]+)\]$", n).group(1) for n in names] == [f"{v:g}" for v in values]


def test_an_infeasible_batch_varying_the_axle_height_writes_a_row_per_variant(tmp_path):
    # L1 = 0 puts the frame line above the handle's forward extreme (test_batch.SMALL): every
    # variant is infeasible, which once gave one row for three and an exit as if complete
    base = {**ROPE, "linkage": {**ROPE["linkage"], "L1": 0.0}}
    rows = rows_in_every_format(tmp_path, batch_file(tmp_path, base, "wheel.axle_height", [0.5, 0.6, 0.7]))
    for fmt, got in rows.items():
        assert len(got) == 3, (fmt, len(got))
    assert [r["feasible"] for r in rows["csv"]] == ["False"] * 3


@pytest.mark.parametrize(("key", "values"), NOT_NUMBERS.items())
@pytest.mark.parametrize("pump", ["rope", "piston"])
def test_a_key_that_is_not_a_number_cannot_vary(tmp_path, pump, key, values):
    if pump == "piston" and key not in PISTON_VARIABLE_KEYS:
        return  # a piston pump has no such key (the unknown-key message is tested in test_batch)
    path = batch_file(tmp_path, ROPE if pump == "rope" else PISTON, key, values)
    code, out, err = run_main("batch", path, "--format", "csv")
    assert (code, out) == (2, "")
    assert err.count("\n") == 1 and f"'{key}'" in err and "not a number" in err

"""The time and the wheel's turns to fill a 20-litre container (docs/water.md §5, Eq. W.7), in every
view that shows a design's water: force's table and JSON, batch's columns, size and the report.

Reference: the hand formulas with the spec's own numbers, t = V / Q with Q = η_v (π d²/4) ω̄ r_w
(Eq. W.1) and turns = t ω̄ / 2π, written out here.
"""

from __future__ import annotations

import csv
import io
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from pumplink.inputs.pump import load_spec
from pumplink.models.water import fill

ROOT = Path(__file__).resolve().parents[1]
VILLAGE = ROOT / "configs" / "village-10m.toml"


def _hand(spec, speed_deg_s=None):
    """(t [s], turns) of the village well by hand."""
    w = math.radians(spec.operator.speed if speed_deg_s is None else speed_deg_s)
    eta_v = 0.87 if spec.load.volumetric_efficiency is None else spec.load.volumetric_efficiency
    q = eta_v * math.pi * spec.load.pipe_diameter**2 / 4 * w * spec.wheel.radius  # Eq. (W.1)
    t = 0.020 / q
    return t, t * w / (2 * math.pi)


def _run(*args):
    p = subprocess.run([sys.executable, "-m", "pumplink", *args], capture_output=True, text=True, cwd=ROOT)
    return p


def test_the_kernel_is_volume_over_flow():
    t, turns = fill(0.020, 0.5e-3, 2 * math.pi)  # 0.5 l/s at one turn a second
    assert float(t) == 40.0 and float(turns) == 40.0
    t, turns = fill(0.020, [0.0, float("nan"), -1.0], 1.0)
    assert math.isinf(t[0]) and math.isnan(t[1]) and math.isnan(t[2])  # no flow, not known, invalid


def test_force_table_and_json_give_it():
    spec = load_spec(VILLAGE)
    t, turns = _hand(spec)
    j = json.loads(_run("force", str(VILLAGE), "--summary", "--format", "json").stdout)
    assert j["fill_time_20l_s"] == pytest.approx(t, rel=1e-12)
    assert j["fill_turns_20l"] == pytest.approx(turns, rel=1e-12)
    table = _run("force", str(VILLAGE), "--summary").stdout
    assert f"time to fill a 20-litre container: {t:.0f} s" in table
    assert f"crank turns to fill it: {turns:.0f}" in table


def test_batch_has_it_as_columns(tmp_path):
    spec = load_spec(VILLAGE)
    batch = tmp_path / "speeds.toml"
    batch.write_text(f'base = "{VILLAGE}"\n[vary]\n"operator.speed" = [250.0, 316.0]\n', encoding="utf-8")
    rows = list(csv.DictReader(io.StringIO(_run("batch", str(batch), "--format", "csv").stdout)))
    assert len(rows) == 2
    for row, speed in zip(rows, (250.0, 316.0)):
        t, turns = _hand(spec, speed)
        assert float(row["fill_time_20l_s"]) == pytest.approx(t, rel=1e-12)
        assert float(row["fill_turns_20l"]) == pytest.approx(turns, rel=1e-12)


def test_the_report_prints_it(tmp_path):
    spec = load_spec(VILLAGE)
    t, _ = _hand(spec)
    out = tmp_path / "r.html"
    _run("report", str(VILLAGE), "--out", str(out))
    assert f"time to fill a 20-litre container: {t:.0f} s" in out.read_text(encoding="utf-8")

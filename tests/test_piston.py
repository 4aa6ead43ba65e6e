"""Piston-pump spec and models (docs/piston-pump.md), against hand derivations and brute force.

Independent routes:

* the harmonic limit (rod ratio L -> infinity, offset 0): s = r cos t, so the operator force is
  F_load r sin t / R on the working stroke; the mean F_load r / (pi R), the peak F_load r / R,
  and the energy deficit of (P.4) in closed form, D = F_load r [2 sqrt(1 - k^2) - k (pi - 2 asin k)]
  with k = Fp R / (F_load r) (the arc between the two points where the load torque equals Fp R);
* a dense brute-force scan of (P.4) written here (cumulative sum of the load torque minus Fp R);
* the piston force by hand: rho g head pi bore^2 / 4 / efficiency.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from pumplink.errors import SpecError
from pumplink.inputs.piston import load_piston, parse_piston
from pumplink.models import piston as P
from pumplink.studies.piston import force_analysis

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "piston-pump.toml"


def harmonic_deficit(load, r, handle, fp):
    k = fp * handle / (load * r)
    return load * r * (2 * math.sqrt(1 - k * k) - k * (math.pi - 2 * math.asin(k)))


def test_harmonic_limit_by_hand():
    r, load, handle = 0.05, 1000.0, 0.3
    rod = 1e7 * r  # L -> infinity: errors O(1/L)
    assert P.mean_force(r, rod, 0.0, load, handle) == pytest.approx(load * r / (math.pi * handle), rel=1e-7)
    assert P.quasi_static_peak(r, rod, 0.0, load, handle)[0] == pytest.approx(load * r / handle, rel=1e-7)
    for fp in (60.0, 100.0, 150.0):
        assert P.energy_deficit(r, rod, 0.0, load, handle, fp) == pytest.approx(
            harmonic_deficit(load, r, handle, fp), rel=1e-6
        )


def brute_deficit(r, rod, e, load, handle, fp, n=400_000):
    t = np.linspace(0.0, 4 * math.pi, 2 * n, endpoint=False)
    rise = e - r * np.sin(t)
    rate = -r * np.sin(t) + r * np.cos(t) * rise / np.sqrt(rod * rod - rise * rise)
    sigma = -1.0 if e >= 0 else 1.0
    torque = load * np.clip(sigma * rate, 0.0, None)
    c = np.concatenate([[0.0], np.cumsum((torque - fp * handle) * (t[1] - t[0]))])
    return float(np.max(c - np.minimum.accumulate(c)))


@pytest.mark.parametrize("e", [0.0, 0.02, -0.02])
def test_least_peak_force_meets_the_band_exactly(e):
    r, rod, load, handle, band = 0.05, 0.2, 800.0, 0.3, 1.5
    fp = P.least_peak_force(r, rod, e, load, handle, band)
    assert P.mean_force(r, rod, e, load, handle) < fp < P.quasi_static_peak(r, rod, e, load, handle)[0]
    assert brute_deficit(r, rod, e, load, handle, fp) == pytest.approx(band, rel=1e-4)
    assert brute_deficit(r, rod, e, load, handle, fp * 0.99) > band  # a little less force fails


def test_flywheel_limits():
    r, rod, load, handle = 0.05, 0.2, 800.0, 0.3
    assert (
        P.least_peak_force(r, rod, 0.0, load, handle, 0.0)
        == P.quasi_static_peak(r, rod, 0.0, load, handle)[0]
    )
    assert P.least_peak_force(r, rod, 0.0, load, handle, 1e6) == P.mean_force(r, rod, 0.0, load, handle)


def test_example_spec_by_hand():
    res = force_analysis(load_piston(EXAMPLE))
    load = 1000 * 9.81 * 10.0 * math.pi * 0.05**2 / 4 / 0.6
    assert res.load_force == pytest.approx(load, rel=1e-14)
    assert res.stroke == pytest.approx(0.1, rel=1e-14)  # central crank-slider: 2 r
    assert res.mean_force == pytest.approx(load * 0.1 / (2 * math.pi * 0.3), rel=1e-14)
    assert res.passed and res.model == "quasi-static"
    # the sweep's torque is load * |ds/dt| on the working stroke, zero on the return
    assert np.all(res.operator_force >= 0) and np.max(res.operator_force) <= res.quasi_static_peak


def test_spec_errors_name_the_key():
    data = {
        "mechanism": "crank-slider",
        "piston": {"bore": 0.05, "head": 10, "efficiency": 0.6},
        "crank_slider": {"crank": 0.05, "rod": 0.25},
        "operator": {"handle": 0.3},
    }
    parse_piston(data)
    with pytest.raises(SpecError, match="crank_slider.rodd"):
        parse_piston({**data, "crank_slider": {"crank": 0.05, "rodd": 0.25}})
    with pytest.raises(SpecError, match="mechanism"):
        parse_piston({**data, "mechanism": "four-bar"})
    with pytest.raises(SpecError, match="wheel.mass needs wheel.radius"):
        parse_piston({**data, "wheel": {"mass": 5.0}})


def test_rod_too_short_is_infeasible_not_a_mechanism():
    data = {
        "mechanism": "crank-slider",
        "piston": {"bore": 0.05, "head": 10, "efficiency": 0.6},
        "crank_slider": {"crank": 0.05, "rod": 0.06, "offset": 0.02},
        "operator": {"handle": 0.3},
    }
    res = force_analysis(parse_piston(data))
    assert not res.feasible and not res.passed and "longer than" in res.error


def test_batch_grid_expands_in_file_order():
    """A piston-pump grid is a batch like any other (one variant expander): the last axis
    varies fastest and the variants are named as a rope pump's."""
    from pumplink.inputs.batch import load_batch, variant_name, variant_spec

    b = load_batch(ROOT / "configs" / "grids" / "piston-bore.toml")
    assert b.mechanism == "crank-slider" and b.size == 8
    one = variant_spec(b, 1)
    assert (one["piston"]["bore"], one["operator"]["handle"]) == (0.04, 0.3)  # last axis fastest
    assert variant_name(b, 1) == "piston-bore#1[bore=0.04 handle=0.3]"


FLYWHEEL_SPEC = """\
name = "piston with flywheel"
mechanism = "crank-slider"
[piston]
bore = 0.050
head = 10.0
efficiency = 0.6
[crank_slider]
crank = 0.050
rod = 0.250
offset = 0.02
[operator]
handle = 0.30
force_limit = 100.0
speed = 240.0
[wheel]
inertia = 0.05
"""


def test_verify_checks_the_work_the_peak_and_the_flywheels_deficit(tmp_path):
    """--verify of a piston pump by quadrature on 400,000 crank angles: the work of a turn is
    F_load H, the sweep's peak is the exact one, and with a flywheel the energy lost over the worst
    arc at Fp* is the band W; a slightly weaker operator (negative control) loses more than W."""
    import dataclasses

    from pumplink.studies.piston import explain, verify

    qs = force_analysis(load_piston(EXAMPLE))
    check = verify(qs)
    assert check.agrees and check.work < 1e-9 and check.deficit is None
    assert explain(qs).startswith("Quasi-static decided") and "enough" in explain(qs)
    f = tmp_path / "fly.toml"
    f.write_text(FLYWHEEL_SPEC)
    fly = force_analysis(load_piston(f))
    assert fly.flywheel and fly.mean_force < fly.least_peak_force < fly.quasi_static_peak
    check = verify(fly)
    assert check.agrees and check.deficit == pytest.approx(1.0, abs=1e-6)
    assert explain(fly).startswith("Flywheel decided")
    weak = dataclasses.replace(fly, least_peak_force=fly.least_peak_force * (1 - 1e-3))
    assert not verify(weak).agrees and verify(weak).deficit > 1 + 1e-5

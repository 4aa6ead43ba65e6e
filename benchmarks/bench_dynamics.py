"""Full-dynamics benchmarks: the least peak force with link masses (pumplink.models.dynamics).

Medians over repeated runs in one process.  Targets: one design <= 5 ms, a batch >= 10,000
designs/s per core.  Run with `make bench`.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_core import ROOT, machine, median_time  # noqa: E402

from pumplink.analysis import design  # noqa: E402
from pumplink.mechanisms.fourbar import FourBar  # noqa: E402
from pumplink.models import dynamics as dy  # noqa: E402
from pumplink.spec import load_spec  # noqa: E402

EXAMPLE = ROOT / "examples" / "well-12m-flywheel.toml"


def main() -> None:
    print(f"machine: {machine()}")
    spec = load_spec(EXAMPLE)
    syn = design(spec).synthesis
    lk, mw, j = syn.linkage, spec.wheel_torque, spec.inertia
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    ms = dy.bar_masses(lk, 1.56)
    t1 = median_time(lambda: dy.least_peak_force(lk, dce, dcf, mw, j, ms, 2 * np.pi, 0.2), 31)
    print(f"least peak force (full dynamics), one design:  {t1 * 1e3:8.2f} ms  (target <= 5 ms)")
    n = 5000
    rep = FourBar(*(np.full(n, float(v)) for v in lk.parameters))
    speeds = np.radians(np.linspace(200.0, 700.0, n))
    msn = dy.bar_masses(rep, 1.56, np.linspace(0.0, 5.0, n))
    tn = median_time(lambda: dy.least_peak_force(rep, dce, dcf, mw, j, msn, speeds, 0.2), 3)
    print(f"least peak force, {n:,} designs vectorised: {tn:.3f} s ({n / tn:,.0f} designs/s; target 10,000)")


if __name__ == "__main__":
    main()

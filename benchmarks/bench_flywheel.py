"""Benchmarks of the flywheel scene (least peak force, Eq. (4) of pumplink.models.flywheel).

Medians over repeated runs in one process; end-to-end commands in subprocesses.  Targets: one
design <= 2 ms, >= 20,000 designs/s vectorised on one core; beside the quasi-static check's cost.
Run with `make bench`.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _record import record  # noqa: E402
from bench_core import EXE, ROOT, machine, median_time  # noqa: E402

from pumplink.analysis import design  # noqa: E402
from pumplink.mechanisms.fourbar import FourBar  # noqa: E402
from pumplink.models import flywheel as fw  # noqa: E402
from pumplink.models.quasi_static import dead_band_peak_force  # noqa: E402
from pumplink.spec import load_spec  # noqa: E402

EXAMPLE = ROOT / "examples" / "well-12m-flywheel.toml"


def main() -> None:
    print(f"machine: {machine()}")
    spec = load_spec(EXAMPLE)
    syn = design(spec).synthesis
    lk, mw, j = syn.linkage, spec.wheel_torque, spec.inertia
    dce, dcf = syn.dead_centre_extended, syn.dead_centre_folded
    band = float(fw.energy_band(j, 2 * np.pi, 0.2))
    t1 = median_time(lambda: fw.least_peak_force(lk, dce, dcf, mw, band), 15)
    tq = median_time(lambda: dead_band_peak_force(lk, dce, dcf, np.radians(20), mw), 15)
    print(
        f"least peak force (flywheel), one design:                 {t1 * 1e3:8.2f} ms  "
        f"(quasi-static windowed peak: {tq * 1e3:.2f} ms, ratio {t1 / tq:.1f}x)"
    )
    n = 10_000
    rep = FourBar(
        *(
            np.full(n, float(v))
            for v in (lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker, lk.handle, lk.branch)
        )
    )
    bands = np.linspace(0.5, 15.0, n)  # 10,000 designs x speeds in one vectorised call
    tn = median_time(lambda: fw.least_peak_force(rep, dce, dcf, mw, bands), 3)
    tqn = median_time(lambda: dead_band_peak_force(rep, dce, dcf, np.radians(20), mw), 3)
    print(
        f"least peak force, 10,000 designs vectorised:             {tn:8.3f} s   ({n / tn:,.0f} designs/s; "
        f"quasi-static peak {n / tqn:,.0f} designs/s)"
    )
    note = f"{t1 / tq:.0f}x the quasi-static peak"
    record("flywheel least peak force, one design", t1 * 1e3, "ms", "<= 2 ms", t1 <= 2e-3, note)
    rate = n / tn
    record("flywheel least peak force, vectorised", rate, "designs/s", ">= 20,000/s", rate >= 20_000)
    ts = median_time(lambda: fw.integrate_motion(fw.scene(lk, dce, dcf, mw, j, 2 * np.pi, 0.2)), 3)
    print(f"scene + solve_ivp cross-check (4 revolutions):           {ts:8.3f} s")
    for label, args in (
        ("pumplink force EXAMPLE --summary", [EXE, "force", str(EXAMPLE), "--summary"]),
        ("pumplink force EXAMPLE --summary --verify", [EXE, "force", str(EXAMPLE), "--summary", "--verify"]),
        ("pumplink speed EXAMPLE (21 speeds)", [EXE, "speed", str(EXAMPLE)]),
    ):
        t = median_time(lambda args=args: subprocess.run(args, stdout=subprocess.DEVNULL, check=False), 5)
        print(f"{label:<56} {t:8.3f} s wall (median of 5)")


if __name__ == "__main__":
    main()

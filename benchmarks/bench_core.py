"""Benchmarks of the core: sweep throughput, the 5 M-sample summary end to end, start-up time.

Medians over repeated runs in one process (subprocesses for the end-to-end commands).
Targets: >= 30 M crank positions/s for kinematics + force; `pumplink --help` and
`pumplink synth spec.toml` under 0.5 s wall.  Run with `make bench`.
"""

from __future__ import annotations

import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from pumplink.analysis import design
from pumplink.mechanisms.angles import offset_table, shifted_directions
from pumplink.mechanisms.fourbar import force_kernel, kernel_work, kinematic_state
from pumplink.spec import default_spec

ROOT = Path(__file__).resolve().parents[1]
EXE = str(Path(sys.executable).with_name("pumplink"))


def median_time(fn, repeat=7):
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def machine() -> str:
    model = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores, Python {platform.python_version()}, numpy {np.__version__}"


def main() -> None:
    spec = default_spec()
    syn = design(spec).synthesis
    lk, mw = syn.linkage, spec.wheel_torque
    print(f"machine: {machine()}")

    theta = np.arange(3600) * (2 * np.pi / 3600)
    t = median_time(lambda: kinematic_state(lk, theta, mw), 50)
    print(
        f"sweep of 3600 crank angles, full state (evaluate):       {t * 1e3:8.3f} ms  "
        f"({3600 / t / 1e6:6.1f} M positions/s)"
    )

    n, chunk = 5_000_000, 8192
    step = 2 * np.pi / n
    table, work = offset_table(step, chunk), kernel_work((chunk,))

    def stream():
        for a in range(0, n, chunk):
            size = min(chunk, n - a)
            cs, sn = shifted_directions(a * step, table, 0, size)
            force_kernel(lk, cs, sn, mw, work[:, :size])

    t = median_time(stream)
    rate = n / t / 1e6
    print(
        f"kinematics + force, 5 M positions streamed (one design):  {t * 1e3:8.1f} ms  "
        f"({rate:6.1f} M positions/s; target >= 30)"
    )

    cfg = str(ROOT / "configs" / "prototype.toml")
    for label, args, target in (
        ("pumplink --help", [EXE, "--help"], 0.5),
        ("pumplink synth configs/prototype.toml", [EXE, "synth", cfg], 0.5),
        (
            "pumplink force --samples 5000000 --summary",
            [EXE, "force", "--samples", "5000000", "--summary"],
            None,
        ),
    ):
        t = median_time(lambda args=args: subprocess.run(args, stdout=subprocess.DEVNULL, check=False), 7)
        goal = f"; target < {target} s" if target else ""
        print(f"{label:<56} {t:8.3f} s wall (median of 7{goal})")


if __name__ == "__main__":
    main()

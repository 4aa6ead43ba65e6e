"""Benchmarks of the core: sweep throughput, start-up of the commands a person waits for, and the
5-million-position sweep end to end against pylinkage.

Kernel figures are medians over repeats in this process.  Commands run as subprocesses, the
cases interleaved round by round (so load from other jobs falls on all of them alike), medians
of the rounds.  `python -c "import numpy"` is timed in the same rounds: on a shared machine the
start-up figures are best read against it.  The package's byte-code is compiled first, as any
run after the first finds it (unless PYTHONDONTWRITEBYTECODE is set).

Targets: >= 30 M crank positions/s for kinematics + force; `pumplink synth SPEC`,
`pumplink force SPEC --summary` and `pumplink force SPEC` (360 samples) <= 0.25 s wall;
`pumplink --help` < 0.5 s.  Run with `make bench` (figures also go to its summary table);
``--smoke``: one round, sweeps of a few thousand positions, no target judged (benchmarks/_record.py).
"""

from __future__ import annotations

import compileall
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from _record import machine, record, repeats, smoke

from pumplink.inputs.pump import default_spec
from pumplink.mechanisms.angles import offset_table, shifted_directions
from pumplink.mechanisms.fourbar import kinematic_state
from pumplink.mechanisms.fourbar_kernel import force_kernel, kernel_work
from pumplink.studies.force import design

ROOT = Path(__file__).resolve().parents[1]
EXE = str(Path(sys.executable).with_name("pumplink"))
#: Rounds of the start-up measurements (the median is reported).
STARTUP_ROUNDS = 10
#: Start-up target of the single-spec commands [s].
STARTUP_TARGET = 0.25

#: pylinkage 1.3.0 (the bench extra) sweeping the same four-bar in its own process: import,
#: build, numba's step_fast over N crank positions (joint positions only, no force).
PYLINKAGE = """
import sys
import numpy as np
from pylinkage.actuators import Crank
from pylinkage.components import Ground
from pylinkage.dyads import RRRDyad
from pylinkage.simulation import Linkage
px, py, crank, coupler, rocker = map(float, sys.argv[1:6])
n = int(sys.argv[6])
o2, o4 = Ground(0.0, 0.0, name="O2"), Ground(px, py, name="O4")
c = Crank(anchor=o2, radius=crank, angular_velocity=2 * np.pi / n)
r = RRRDyad(c.output, o4, distance1=coupler, distance2=rocker)
linkage = Linkage([o2, o4, c, r], name="pump four-bar")
linkage.compile()
xy = linkage.step_fast(iterations=n)[:, -1, :]  # the rocker joint B
assert np.nanmax(np.abs(np.hypot(xy[:, 0] - px, xy[:, 1] - py) - rocker)) < 1e-9
"""


def positions(n: int) -> str:
    """A count of crank positions as the figures' names say it: "5 M", or "24,576" below a million."""
    return f"{n / 1e6:g} M" if n >= 1_000_000 else f"{n:,}"


def median_time(fn, repeat=7):
    """Median wall time [s] of ``repeat`` calls (one in a smoke run)."""
    ts = []
    for _ in range(repeats(repeat)):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def run(args: list[str]) -> tuple[float, float]:
    """Wall and CPU time (user + system) [s] of one run of ``args``; output discarded, a failure
    stops the benchmark.  pumplink runs on one thread (it asks OpenBLAS for one), so on an idle
    machine its wall ~ CPU, and on a shared one the CPU time is the steadier of the two; a plain
    ``import numpy`` starts an OpenBLAS thread per core and shows more CPU than wall time."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def interleaved(cases: dict[str, list[str]], rounds: int) -> dict[str, tuple[float, float]]:
    """Median wall and CPU time of each command, the commands run one after the other in every
    round (so load from other jobs falls on all of them alike)."""
    times: dict[str, list[tuple[float, float]]] = {k: [] for k in cases}
    for _ in range(rounds):
        for k, args in cases.items():
            times[k].append(run(args))
    return {
        k: (statistics.median(w for w, _ in v), statistics.median(c for _, c in v)) for k, v in times.items()
    }


def kernels(lk, mw) -> None:
    theta = np.arange(3600) * (2 * np.pi / 3600)
    t = median_time(lambda: kinematic_state(lk, theta, mw), 50)
    print(
        f"sweep of 3600 crank angles, full state (evaluate):       {t * 1e3:8.3f} ms  "
        f"({3600 / t / 1e6:6.1f} M positions/s)"
    )
    record("full state (evaluate) of a 3600-angle sweep", t * 1e3, "ms")

    n, chunk = (3 * 8192 if smoke() else 5_000_000), 8192  # a smoke run: three chunks, the last one full
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
        f"kinematics + force, {positions(n)} positions streamed (one design):  {t * 1e3:8.1f} ms  "
        f"({rate:6.1f} M positions/s; target >= 30)"
    )
    record(
        f"kinematics + force, {positions(n)} positions streamed, one design",
        rate,
        "M/s",
        ">= 30 M/s",
        rate >= 30,
    )


def startup() -> None:
    compileall.compile_dir(ROOT / "pumplink", quiet=1)  # as every run after the first finds it
    cfg = "configs/prototype.toml"
    cases = {
        'python -c "import numpy"': [sys.executable, "-c", "import numpy"],
        "pumplink --help": [EXE, "--help"],
        f"pumplink synth {cfg}": [EXE, "synth", cfg],
        f"pumplink force {cfg} --summary": [EXE, "force", cfg, "--summary"],
        f"pumplink force {cfg}": [EXE, "force", cfg],
    }
    os.chdir(ROOT)
    rounds = repeats(STARTUP_ROUNDS)
    t = interleaved(cases, rounds)
    numpy_s, numpy_cpu = t['python -c "import numpy"']
    print(f"start-up, median of {rounds} interleaved rounds (cwd: the repository); wall, CPU,")
    print("and both as multiples of python -c 'import numpy' measured in the same rounds:")
    for label, (s, cpu) in t.items():
        if label.startswith("python"):
            print(f"  {label:<48} {s:5.3f} s  CPU {cpu:5.3f} s")
            record(f"{label}, for scale", s, "s", note=f"CPU {cpu:.3f} s; what any numpy program pays here")
            continue
        goal = 0.5 if label == "pumplink --help" else STARTUP_TARGET
        cmp = "<" if goal == 0.5 else "<="
        met = s < goal if goal == 0.5 else s <= goal
        ratios = f"{s / numpy_s:.1f}x, CPU {cpu / numpy_cpu:.1f}x"
        print(f"  {label:<48} {s:5.3f} s  CPU {cpu:5.3f} s  ({ratios}; target {cmp} {goal} s)")
        record(
            f"{label}, start-up", s, "s", f"{cmp} {goal} s", met, note=f"CPU {cpu:.3f} s; x numpy: {ratios}"
        )


def end_to_end(lk) -> None:
    """The 5-million-position sweep as a user runs it (start-up included) against pylinkage's (a
    smoke run: 1,000 positions)."""
    n = 1_000 if smoke() else 5_000_000
    cases = {"pumplink": [EXE, "force", "--samples", str(n), "--summary"]}
    try:
        import pylinkage  # noqa: F401
    except ImportError:
        print("pylinkage not installed (pip install '.[bench]'): the end-to-end comparison is skipped")
    else:
        geometry = [repr(float(v)) for v in (lk.pivot_x, lk.pivot_y, lk.crank, lk.coupler, lk.rocker)]
        cases["pylinkage"] = [sys.executable, "-c", PYLINKAGE, *geometry, str(n)]
    rounds = repeats(5)
    t = {k: wall for k, (wall, _) in interleaved(cases, rounds).items()}
    print(f"{positions(n)} crank positions end to end, wall, median of {rounds} interleaved rounds:")
    print(f"  pumplink force --samples {n} --summary                 {t['pumplink']:6.3f} s (B + force)")
    record(f"pumplink force --samples {n} --summary, end to end", t["pumplink"], "s")
    if "pylinkage" in t:
        ratio = t["pylinkage"] / t["pumplink"]
        print(f"  pylinkage step_fast process (numba; positions only)      {t['pylinkage']:6.3f} s")
        print(f"  pylinkage / pumplink:                                    {ratio:6.1f}x")
        record(
            f"pylinkage step_fast process / pumplink, {positions(n)} positions",
            ratio,
            "x",
            note=f"pylinkage {t['pylinkage']:.2f} s (positions only, numba); kernels alone: bench_methods",
        )


def main() -> None:
    spec = default_spec()
    syn = design(spec).synthesis
    lk, mw = syn.linkage, spec.wheel_torque
    print(f"machine: {machine()}")
    kernels(lk, mw)
    startup()
    end_to_end(lk)


if __name__ == "__main__":
    main()

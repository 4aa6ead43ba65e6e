"""Benchmark of `pumplink batch --scheduler local:2` (Dask) against the local pool (--workers 2).

The real command end to end (start-up, cluster start and stop, evaluation, CSV written) in a
subprocess, on configs/grids/design-space.toml (27,216 variants that give inertia, the village
well's 8 kg wheel: the flywheel or full dynamics decides each) and on the same grid without the
wheel mass (quasi-static), both on a copy of the village well without its ``[parts]`` table: the
part checks cost the same on either backend, so with them the comparison would say nothing more
(the grid with them is benchmarks/bench_parts.py's).
Wall and CPU time (user + system of the command and every process it started, from
resource.getrusage in a wrapper process), medians of interleaved runs; the two backends' CSV files
must be byte-identical.  One more Dask run on the inertia grid leaves out the workers' malloc
tuning (pumplink.batch.cluster.WorkerSetup), to show what it is worth.  With
``PUMPLINK_BENCH_OUT`` set (``make bench``) the figures also go to the summary table.  The fixed cost of each
backend (start and stop: two variants in two tasks) and the cost per variant beyond it give the
extrapolation to 10 million variants; the quasi-static grid is also written as Parquet, for the
size against the CSV.  The driver renders every row (the workers send arrays), so its rendering
time per variant, timed in this process, bounds how many workers one run can feed.

    .venv/bin/python benchmarks/bench_dask.py [--repeat 3] [--quick] [--smoke]

``--smoke``: every run once on a thousandth of each grid (``--chunk 1/1000``, 27 variants), Dask
with one worker (``local:1``, the cheapest cluster to start), no target judged (benchmarks/_record.py).

Target: Dask costs no more CPU per variant than the local pool on the same grid (ratio <= 1.05:
the spread of repeated runs on this machine), beyond the fixed cost of starting each backend,
which is reported beside it: Dask's scheduler and worker processes cost about a second of CPU
once per run, which is the whole difference on a 27,216-variant quasi-static grid (about 2 s of
work) and nothing on the runs Dask is for (10 million variants: the per-variant cost, below).
The whole-run ratios are recorded too.  The machine has 2 cores shared with other jobs: wall
times move with their load, CPU times much less.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

import tomli_w

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _record import SMOKE_HELP, judged, machine, record, repeats, smoke  # noqa: E402
from bench_batch import WRAPPER, free_cores  # noqa: E402  (one measuring wrapper: wall, CPU)
from bench_core import ROOT  # noqa: E402

GRID = ROOT / "configs" / "grids" / "design-space.toml"
#: The Dask cluster measured: two workers as the local pool has, one in a smoke run.
DASK = "local:1" if smoke() else "local:2"
#: Measurement spread allowed by the target (repeated runs here differ by a few per cent).
TOLERANCE = 1.05

# pumplink batch with the malloc plugin left out (the driver never registers it).
UNTUNED = (
    "import distributed, sys; distributed.Client.register_plugin = lambda *a, **k: None; "
    "from pumplink.cli import main; main(sys.argv[1:])"
)


def measure(cmd: list[str]) -> dict:
    out = subprocess.run([sys.executable, "-c", WRAPPER, *cmd], capture_output=True, text=True, check=True)
    res = json.loads(out.stdout)
    if res["rc"] != 0:
        raise SystemExit(f"command failed ({res['rc']}): {' '.join(cmd)}\n{res['stderr']}")
    return res


def grid_copies(folder: Path) -> tuple[Path, Path]:
    """The design-space grid on the village well without its ``[parts]`` (inertia), and on the
    village well without its wheel mass either (quasi-static)."""
    village = tomllib.loads((ROOT / "configs" / "village-10m.toml").read_text())
    del village["parts"]
    out = []
    for name in ("inertia", "quasi-static"):
        if name == "quasi-static":
            del village["wheel"]["mass"]
        (folder / name).mkdir()
        (folder / name / "village-10m.toml").write_text(tomli_w.dumps(village))
        path = folder / name / "design-space.toml"
        path.write_text(GRID.read_text().replace('base = "../village-10m.toml"', 'base = "village-10m.toml"'))
        out.append(path)
    return out[0], out[1]


def render_costs(grid: Path) -> dict[str, float]:
    """Seconds per variant the driver spends turning chunks into rows, by format (a twelfth of the
    inertia grid, evaluated here first; a smoke run: a thousandth)."""
    import time

    from pumplink import batch as B
    from pumplink.output import batchfiles as rb

    batches = B.load_inputs([grid])
    vkeys = rb.varied_keys(batches)
    chunks = [c for c, _ in B.run(batches, 360, (1, 1000 if smoke() else 12))]
    n = sum(len(c) for c in chunks)
    out = {}
    for fmt, render in (
        ("CSV", lambda c: rb.csv_text(batches[0], c, vkeys)),
        ("Parquet", lambda c: rb.parquet_table(batches[0], c, vkeys)),
        ("JUnit", lambda c: rb.junit_text(batches[0], c, ("mean", "peak", "infeasible"))),
    ):
        render(chunks[0])  # imports
        t = time.perf_counter()
        for c in chunks:
            render(c)
        out[fmt] = (time.perf_counter() - t) / n
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="a third of each grid (--chunk 1/3), one run")
    ap.add_argument("--smoke", action="store_true", help=SMOKE_HELP)
    args = ap.parse_args()
    repeat = 1 if args.quick else repeats(args.repeat)
    chunk = ["--chunk", "1/1000"] if smoke() else ["--chunk", "1/3"] if args.quick else []
    print(f"machine: {machine()}; shared with other jobs, cores free for us: {free_cores():.1f}")
    verdicts, verdicts_per = [], []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        two = [str(ROOT / "configs" / "prototype.toml"), str(ROOT / "configs" / "women-operators-6m.toml")]
        fixed: dict[str, list[dict]] = {}
        for _ in range(repeat):
            for name, opts in (("pool", ["--workers", "2"]), ("dask", ["--scheduler", DASK])):
                cmd = [sys.executable, "-m", "pumplink", "batch", *two, "--format", "csv", *opts]
                fixed.setdefault(name, []).append(measure([*cmd, "--out", str(tmp / "two.csv")]))
        start = {k: statistics.median(r["cpu"] for r in v) for k, v in fixed.items()}
        walls = {k: statistics.median(r["wall"] for r in v) for k, v in fixed.items()}
        print(
            f"fixed cost (2 variants, 2 tasks): pool --workers 2 wall {walls['pool']:.2f} s CPU "
            f"{start['pool']:.2f} s; Dask {DASK} wall {walls['dask']:.2f} s CPU {start['dask']:.2f} s"
        )
        inertia_grid, quasi_static_grid = grid_copies(tmp)
        for label, grid in (("quasi-static", quasi_static_grid), ("inertia", inertia_grid)):
            base = [str(grid), "--fail-on", "none", "--format", "csv", *chunk]
            runs = {
                "pool": lambda out, b=base: (
                    [sys.executable, "-m", "pumplink", "batch", *b, "--workers", "2"] + ["--out", out]
                ),
                "dask": lambda out, b=base: (
                    [sys.executable, "-m", "pumplink", "batch", *b] + ["--scheduler", DASK, "--out", out]
                ),
            }
            if label == "inertia":
                runs["untuned"] = lambda out, b=base: (
                    [sys.executable, "-c", UNTUNED, "batch", *b]
                    + [
                        "--scheduler",
                        DASK,
                        "--out",
                        out,
                    ]
                )
            res: dict[str, list[dict]] = {}
            for _ in range(repeat):  # interleaved, so the other jobs' load hits every backend alike
                for name, cmd in runs.items():
                    res.setdefault(name, []).append(measure(cmd(str(tmp / f"{name}.csv"))))
            data = {name: (tmp / f"{name}.csv").read_bytes() for name in runs}
            assert all(d == data["pool"] for d in data.values()), "the backends' CSV files differ"
            n = data["pool"].count(b"\n") - 1
            med = {
                k: (statistics.median(r["wall"] for r in v), statistics.median(r["cpu"] for r in v))
                for k, v in res.items()
            }
            (pw, pc), (dw, dc) = med["pool"], med["dask"]
            print(
                f"{label} grid, {n:,} variants, CSV identical: pool --workers 2 wall {pw:.2f} s CPU "
                f"{pc:.2f} s; Dask {DASK} wall {dw:.2f} s CPU {dc:.2f} s; Dask/pool CPU {dc / pc:.2f}x, "
                f"wall {dw / pw:.2f}x (medians of {repeat})"
            )
            if "untuned" in med:
                uw, uc = med["untuned"]
                print(
                    f"{label} grid, Dask {DASK} without the workers' malloc tuning: wall {uw:.2f} s CPU "
                    f"{uc:.2f} s; the tuning saves {100 * (1 - dc / uc):.0f} % of Dask's CPU time"
                )
                record(
                    "Dask without / with the workers' malloc plugin, CPU, inertia grid",
                    uc / dc,
                    "x",
                    note="Dask's MALLOC_TRIM_THRESHOLD_=65536 pins glibc's mmap threshold at 128 kB",
                )
            record(
                f"Dask {DASK} / pool --workers 2, CPU of the whole run, {label} grid ({n:,} variants)",
                dc / pc,
                "x",
                note=f"CPU {dc:.1f} s against {pc:.1f} s; wall {dw:.1f} s against {pw:.1f} s; start-up "
                f"included",
            )
            per = {k: (med[k][1] - start[k]) / n for k in ("pool", "dask")}
            verdicts_per.append((label, per["dask"]))
            verdicts.append((label, per["dask"] / per["pool"]))
            record(
                f"Dask / pool, CPU per variant beyond the start-up, {label} grid",
                per["dask"] / per["pool"],
                "x",
                f"<= {TOLERANCE}x",
                per["dask"] / per["pool"] <= TOLERANCE,
                note=f"{per['dask'] * 1e6:.0f} us against {per['pool'] * 1e6:.0f} us; start-up: Dask "
                f"{start['dask']:.1f} s CPU, pool {start['pool']:.1f} s",
            )
            print(
                f"{label} grid, CPU per variant beyond the fixed cost: pool {per['pool'] * 1e6:.0f} us, "
                f"Dask {per['dask'] * 1e6:.0f} us (ratio {per['dask'] / per['pool']:.2f}); 10 million "
                f"variants: {per['dask'] * 1e7 / 3600:.2f} core-hours on Dask, "
                f"{per['dask'] * 1e7 / 3600 / 2:.2f} h on 2 free cores"
            )
            if label == "quasi-static":
                pq = tmp / "rows.parquet"
                measure([*runs["pool"](str(pq))[:-2], "--format", "parquet", "--out", str(pq)])
                csv_bytes, pq_bytes = len(data["pool"]), pq.stat().st_size
                record(
                    "batch --format parquet: bytes a row, quasi-static grid",
                    pq_bytes / n,
                    "B",
                    note=f"CSV: {csv_bytes / n:.0f} B a row",
                )
                print(
                    f"{label} grid as Parquet: {pq_bytes / n:.0f} bytes a row against {csv_bytes / n:.0f} "
                    f"for the CSV; 10 million rows: {pq_bytes / n * 1e7 / 1e9:.2f} GB against "
                    f"{csv_bytes / n * 1e7 / 1e9:.1f} GB"
                )
        cost = render_costs(inertia_grid)
    per_variant = dict(verdicts_per)["inertia"]
    print(
        "driver rendering per variant: "
        + ", ".join(f"{k} {v * 1e6:.1f} us" for k, v in cost.items())
        + f"; one driver keeps up with {per_variant / cost['Parquet']:.0f} workers (inertia grid) "
        f"writing Parquet, {per_variant / (cost['CSV'] + cost['JUnit']):.0f} writing CSV and JUnit"
    )
    for label, ratio in verdicts:
        met = judged(ratio <= TOLERANCE)
        print(
            f'target "Dask costs no more CPU per variant than the local pool" ({label} grid, beyond '
            f"the start-up, ratio {ratio:.2f} <= {TOLERANCE}): met: {met}"
        )
    print(
        "(the fixed cost of starting Dask's scheduler and worker processes is the difference on a short "
        "run: the whole-run ratios above include it)"
    )
    print(
        "command: pumplink batch GRID --fail-on none --format csv --out out.csv "
        "(--workers 2 | --scheduler local:2)"
    )


if __name__ == "__main__":
    main()

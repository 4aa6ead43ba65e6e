"""`pumplink batch --scheduler`: the Dask backend gives the local pool's output byte for byte.

The reference is the run on one process (``--workers 1``, no pool, no Dask): the same planner and
renderers, so any difference is the backend's (a lost, duplicated or reordered chunk).  One
local cluster of two workers serves the library-level tests of this module (a cluster takes
seconds to start); the CLI tests start their own, as a user's run does.
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from pumplink import batch as B
from pumplink.batch import cluster as C
from pumplink.errors import SpecError
from pumplink.output import batchfiles as rb

ROOT = Path(__file__).resolve().parents[2]
PROTOTYPE = (ROOT / "configs" / "prototype.toml").as_posix()
VILLAGE = (ROOT / "configs" / "village-10m.toml").as_posix()
CMD = [sys.executable, "-m", "pumplink"]

# 4 x 10 x 6 x 5 = 1,200 quasi-static variants (feasible and infeasible: L1 = 0, see test_batch)
QS = f"""\
name = "qs"
base = "{PROTOTYPE}"
[vary]
"linkage.L1" = [0.0, 0.2, 0.4, 0.6]
"linkage.rocker" = {{ start = 0.15, stop = 0.3, num = 10 }}
"linkage.swing" = {{ start = 40, stop = 80, num = 6 }}
"load.rope_force" = [30, 45, 60, 75, 90]
"""
# 3 x 3 x 4 x 2 x 2 = 144 variants that give inertia (the village well's wheel): the least model
# that is enough decides 72 by the flywheel and 72 by full dynamics
FLY = f"""\
name = "fly"
base = "{VILLAGE}"
[vary]
"wheel.mass" = [0.5, 4.0, 20.0]
"operator.speed" = [180, 360, 540]
"linkage.rocker" = {{ start = 0.15, stop = 0.3, num = 4 }}
"linkage.L1" = [0.4, 0.0]
"operator.speed_fluctuation" = [0.1, 0.2]
"""


def pumplink(*args, **kw) -> subprocess.CompletedProcess:
    return subprocess.run(
        [*CMD, *map(str, args)], cwd=ROOT, capture_output=True, text=True, timeout=120, **kw
    )


@pytest.fixture(scope="module")
def grids(tmp_path_factory) -> list[Path]:
    folder = tmp_path_factory.mktemp("grids")
    out = []
    for name, text in (("qs", QS), ("fly", FLY)):
        (folder / f"{name}.toml").write_text(text)
        out.append(folder / f"{name}.toml")
    return out


@pytest.fixture(scope="module")
def client():
    with C.connect(C.Scheduler(None, 2)) as c:
        yield c


def _write(tmp_path: Path, name: str, batches, results, fmt="csv", chunk=(1, 1)) -> tuple[bytes, bytes]:
    out, junit = tmp_path / f"{name}.{fmt}", tmp_path / f"{name}.xml"
    total = sum(e - s for _, s, e in B.plan(batches, chunk))
    rb.write_stream(batches, results, total, fmt, out, junit, B.FAIL_CHECKS, 90, chunk)
    return out.read_bytes(), junit.read_bytes()


def _post(batches, fmt="csv"):
    return lambda b, c: rb.render_chunk(b, c, fmt, rb.varied_keys(batches), B.FAIL_CHECKS, True)


# ----------------------------------------------------------------------------- the library
@pytest.mark.parametrize("fmt", ["csv", "json", "parquet"])
def test_local_cluster_gives_the_rows_of_one_process(tmp_path, grids, client, fmt):
    """All three models in one run, cut into 22 tasks of at most 64 variants (Dask completes them out
    of order): the file and the JUnit report are byte-identical, the Parquet file too."""
    batches = B.load_inputs(grids)
    post = _post(batches, fmt)
    ref = _write(tmp_path, "ref", batches, B.run(batches, 90, designs=64, post=post), fmt)
    got = _write(tmp_path, "dask", batches, C.run(batches, client, 90, designs=64, post=post), fmt)
    assert len(B.plan(batches, designs=64)) == 22
    assert got == ref
    assert ref[1].count(b"<testcase ") == 1200 + 144
    if fmt == "parquet":
        import pyarrow.parquet as pq

        models = pq.read_table(tmp_path / "dask.parquet").column("model").to_pylist()
        assert len(models) == 1344 and models.count(B.FLYWHEEL_LABEL) == models.count(B.DYNAMICS_LABEL) == 72
        return
    fly = [r for r in ref[0].decode().splitlines() if r.startswith(("fly#", '{"name": "fly#'))]
    for label in (B.FLYWHEEL_LABEL, B.DYNAMICS_LABEL):  # the energy models share the grid
        assert sum(f",{label}," in r or f'"model": "{label}"' in r for r in fly) == 72


def test_slices_on_the_cluster_partition_the_run(tmp_path, grids, client):
    """--chunk K/N composes with the cluster: slice K on Dask is slice K of the one-process run,
    and the slices together are the whole run."""
    batches = B.load_inputs(grids)
    post = _post(batches)
    full = _write(tmp_path, "full", batches, B.run(batches, 90, designs=100, post=post))[0].splitlines()
    rows = []
    for k in (1, 2, 3):
        ref = _write(
            tmp_path, f"r{k}", batches, B.run(batches, 90, (k, 3), designs=100, post=post), chunk=(k, 3)
        )
        got = _write(
            tmp_path,
            f"d{k}",
            batches,
            C.run(batches, client, 90, (k, 3), designs=100, post=post),
            chunk=(k, 3),
        )
        assert got == ref
        lines = got[0].splitlines()
        assert lines[0] == full[0] and len(lines) > 1
        rows += lines[1:]
    assert rows == full[1:]


def test_chunks_come_back_as_arrays(grids, client):
    """What a worker sends back is the chunk's columns as numpy arrays, not rows."""
    batches = B.load_inputs(grids[:1])
    (c, post), *_ = C.run(batches, client, 30, designs=400)
    assert post is None and isinstance(c, B.Chunk) and len(c) == 400
    assert isinstance(c.mean_force, np.ndarray) and c.mean_force.shape == (400,)
    assert c.values.shape == (400, 4)


def test_workers_malloc_is_tuned(client):
    """Dask starts its workers with MALLOC_TRIM_THRESHOLD_=65536, which pins glibc's mmap
    threshold at 128 kB: every 1 MB temporary is mapped afresh and its 256 pages faulted in.
    With the plugin's thresholds the heap is reused: 200 such arrays fault in a few pages, not
    200 x 256 = 51,200."""

    def faults() -> int:
        import resource

        import numpy

        r0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        for _ in range(200):
            a = numpy.ones(131072)  # 1 MB
            del a
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - r0

    got = client.run(faults)
    assert len(got) == 2 and all(n < 2_000 for n in got.values()), got
    envs = client.run(lambda: os.environ.get("MALLOC_TRIM_THRESHOLD_"))
    assert set(envs.values()) == {"65536"}  # Dask's setting is there: the plugin is what helps


def test_local_workers_do_no_dashboard_work(client):
    """The local cluster's workers neither profile their tasks nor tick every 20 ms (for a
    dashboard nobody watches): the settings reach the worker processes."""
    import dask

    keys = ("distributed.worker.profile.enabled", "distributed.admin.tick.interval")
    got = client.run(lambda: tuple(dask.config.get(k) for k in keys))
    assert set(got.values()) == {(False, "1s")}


def test_the_readme_grid_of_ten_million_variants(tmp_path):
    """The 10-million-variant recipe grid of docs/batch.md is valid: 10^7 variants that give
    inertia in 2,442 tasks, and its first 200 evaluate (one process)."""
    import re

    readme = (ROOT / "docs" / "batch.md").read_text(encoding="utf-8")
    (text,) = re.findall(r"^```toml\n(# grid-10m\.toml.*?)^```", readme, re.S | re.M)
    (tmp_path / "configs").symlink_to(ROOT / "configs")
    (tmp_path / "grid-10m.toml").write_text(text)
    batches = B.load_inputs([tmp_path / "grid-10m.toml"])
    assert batches[0].size == 10**7 and batches[0].flywheel
    assert len(B.plan(batches, designs=B.run_module.task_designs(360))) == 2442
    rows = list(B.run(batches, 360, (1, 50_000)))
    assert sum(len(c) for c, _ in rows) == 200


def test_scheduler_text():
    assert C.parse_scheduler("local:3") == C.Scheduler(None, 3)
    assert C.parse_scheduler("local") == C.parse_scheduler("local:0") == C.Scheduler(None, 0)
    assert C.parse_scheduler("tcp://10.0.0.5:8786") == C.Scheduler("tcp://10.0.0.5:8786")
    for bad in ("local:x", "local:-1", "local:257", "10.0.0.5", "tcp://", ""):
        with pytest.raises(SpecError, match="--scheduler"):
            C.parse_scheduler(bad)


# ----------------------------------------------------------------------------- the command
def test_cli_local_cluster_with_chunk_equals_one_worker(tmp_path, grids):
    """The real entry point: --scheduler local:2 with --chunk 2/3, CSV and JUnit, as --workers 1."""
    out = {}
    for name, opts in (("one", ["--workers", "1"]), ("dask", ["--scheduler", "local:2"])):
        r = pumplink(
            "batch", *grids, "--fail-on", "none", "--format", "csv", "--samples", 90, "--chunk", "2/3",
            "--out", tmp_path / f"{name}.csv", "--junit", tmp_path / f"{name}.xml", *opts,
        )  # fmt: skip
        assert r.returncode == 0, r.stderr
        assert r.stderr.count("\n") == 1 and "(slice 2/3)" in r.stderr, r.stderr
        out[name] = (tmp_path / f"{name}.csv").read_bytes(), (tmp_path / f"{name}.xml").read_bytes()
    assert out["dask"] == out["one"]
    assert out["one"][0].count(b"\n") == (1200 + 144) // 3 + 1


def test_cli_existing_cluster_by_address(tmp_path, grids, client):
    """--scheduler tcp://host:port: a cluster started elsewhere (here the module's) runs the tasks."""
    address = client.scheduler.address
    assert address.startswith("tcp://")
    r1 = pumplink("batch", *grids, "--fail-on", "none", "--format", "json", "--samples", 90)
    r2 = pumplink(
        "batch", *grids, "--fail-on", "none", "--format", "json", "--samples", 90, "--scheduler", address
    )
    assert r1.returncode == r2.returncode == 0, r2.stderr
    assert r2.stdout == r1.stdout and r1.stdout.count('\n{"name": ') == 1200 + 144


def _children(pid: int) -> list[tuple[int, str]]:
    out = []
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        with contextlib.suppress(OSError, ValueError, IndexError):
            ppid = int((d / "stat").read_text().rsplit(")", 1)[1].split()[1])
            if ppid == pid:
                out.append((int(d.name), (d / "cmdline").read_bytes().replace(b"\0", b" ").decode()))
    return out


def _workers(pid: int) -> list[int]:
    """The local cluster's worker processes (multiprocessing spawns them as children)."""
    return [p for p, cmd in _children(pid) if "spawn_main" in cmd]


def _writing(pid: int, folder: Path, size: int = 20_000) -> bool:
    """True when ``pid`` holds a file open in ``folder`` with more than ``size`` bytes: rows are
    being written to the (unnamed) output file."""
    with contextlib.suppress(OSError):
        for fd in Path(f"/proc/{pid}/fd").iterdir():
            with contextlib.suppress(OSError):
                if os.readlink(fd).startswith(str(folder)) and os.stat(fd).st_size > size:
                    return True
    return False


# 4 x 40 x 30 = 4,800 quasi-static variants at 20,000 crank samples: ~130 tasks of 150 variants,
# some seconds of work for two workers.
LONG = f"""\
base = "{PROTOTYPE}"
[vary]
"linkage.L1" = [0.0, 0.2, 0.4, 0.6]
"linkage.rocker" = {{ start = 0.15, stop = 0.3, num = 40 }}
"linkage.swing" = {{ start = 40, stop = 80, num = 30 }}
"""


def _start_long(tmp_path: Path, scheduler: str = "local:2") -> tuple[subprocess.Popen, Path]:
    grid = tmp_path / "long.toml"
    grid.write_text(LONG)
    out = tmp_path / "out"
    out.mkdir()
    p = subprocess.Popen(
        [*CMD, "batch", grid, "--fail-on", "none", "--samples", "20000", "--format", "csv",
         "--out", out / "rows.csv", "--junit", out / "r.xml", "--scheduler", scheduler],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
    )  # fmt: skip
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and p.poll() is None and not _writing(p.pid, out):
        time.sleep(0.05)
    assert p.poll() is None, "the run finished before it could be interrupted: " + p.communicate()[1]
    return p, out


def test_a_killed_worker_loses_no_row(tmp_path):
    """SIGKILL of a worker mid-run (what the out-of-memory killer does): Dask runs its tasks again
    on the other worker and on the restarted one; the output is that of one process, every row
    once, and the run exits 0 with nothing but its summary on stderr."""
    p, out = _start_long(tmp_path)
    workers = _workers(p.pid)
    assert len(workers) == 2
    os.kill(workers[0], signal.SIGKILL)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 0, err
    assert err.count("\n") == 1 and err.startswith("batch: 4800 variants"), err
    ref = pumplink(
        "batch", tmp_path / "long.toml", "--fail-on", "none", "--samples", "20000", "--format", "csv",
        "--out", tmp_path / "ref.csv", "--junit", tmp_path / "ref.xml",
    )  # fmt: skip
    assert ref.returncode == 0, ref.stderr
    assert (out / "rows.csv").read_bytes() == (tmp_path / "ref.csv").read_bytes()
    assert (out / "r.xml").read_bytes() == (tmp_path / "ref.xml").read_bytes()


def test_ctrl_c_stops_the_cluster_and_writes_nothing(tmp_path):
    """Ctrl-C to the whole process group, as a terminal sends it: the workers ignore it, the
    driver stops them; exit 130, one line, no file, no worker left behind."""
    p, out = _start_long(tmp_path)
    workers = _workers(p.pid)
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130 and err == "interrupted; no output file written\n", err
    assert sorted(out.iterdir()) == []
    time.sleep(0.5)
    assert not [w for w in workers if Path(f"/proc/{w}").exists() and "Z" not in _state(w)]


def test_a_lost_scheduler_ends_the_run_in_seconds(tmp_path):
    """The remote cluster goes away mid-run: exit 130 and one line, no file, no hang."""
    with C.connect(C.Scheduler(None, 2)) as c:
        p, out = _start_long(tmp_path, c.scheduler.address)
        t0 = time.monotonic()
    _, err = p.communicate(timeout=60)
    assert time.monotonic() - t0 < 15
    assert p.returncode == 130, err
    assert err == "interrupted: lost the connection to the Dask scheduler; no output file written\n"
    assert sorted(out.iterdir()) == []


def test_workers_running_another_pumplink_are_refused(client, monkeypatch):
    """The workers must run this pumplink, or the rows would not be those of one process."""
    theirs = C.fingerprint()
    monkeypatch.setattr(C, "installed_version", lambda: "0.0.0-other")  # in this process only
    assert C.fingerprint() == "0.0.0-other " + theirs.split()[1]
    words = f"a worker runs pumplink {re.escape(theirs)}, this is 0\\.0\\.0-other"
    with pytest.raises(SpecError, match=words):
        C._check_workers(client, C.Scheduler(client.scheduler.address))


def _state(pid: int) -> str:
    with contextlib.suppress(OSError):
        return (Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split() or ["?"])[0]
    return "gone"


@pytest.mark.parametrize(
    "args,words",
    [
        (["--scheduler", "local:x"], "--scheduler 'local:x': the worker count must be"),
        (["--scheduler", "localhost"], "neither local:N nor a scheduler address"),
        (["--scheduler", "local:2", "--workers", "2"], "--workers 2 is for the local pool"),
    ],
)
def test_bad_scheduler_options_exit_2_with_one_line(args, words):
    r = pumplink("batch", PROTOTYPE, *args)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.count("\n") == 1 and words in r.stderr and "Traceback" not in r.stderr, r.stderr


def test_a_run_holds_one_kind_of_pump():
    """Piston-pump and rope-pump files have different columns: one line and exit 2 when mixed."""
    r = pumplink("batch", "configs/grids/piston-bore.toml", PROTOTYPE)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "separate runs" in r.stderr


def test_an_unreachable_scheduler_fails_in_seconds():
    """Nothing listens on port 1: one line and exit 2 after the connect timeout, no hang."""
    t0 = time.monotonic()
    r = pumplink("batch", PROTOTYPE, "--scheduler", "tcp://127.0.0.1:1")
    assert time.monotonic() - t0 < C.CONNECT_TIMEOUT + 10
    assert r.returncode == 2 and r.stdout == "" and r.stderr.count("\n") == 1, r.stderr
    assert "tcp://127.0.0.1:1" in r.stderr and "no Dask scheduler answered within 5 s" in r.stderr


def test_without_dask_the_scheduler_says_how_to_install_it():
    """An install without the extra: ``import distributed`` fails (a None entry in sys.modules
    makes any import of it raise ImportError, as an absent package does)."""
    code = textwrap.dedent(
        f"""
        import sys
        sys.modules["distributed"] = None
        from pumplink.cli import main
        main(["batch", {PROTOTYPE!r}, "--scheduler", "local:2"])
        """
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr == (
        "error: --scheduler needs Dask, which is not installed; "
        "install it with pip install 'pumplink[dask]'\n"
    )


def test_the_default_install_imports_neither_dask_pyarrow_nor_numba(tmp_path, grids):
    """`make run` (pumplink force) and a batch on the local pool, JUnit included, in one process:
    the optional extras stay unimported."""
    code = textwrap.dedent(
        f"""
        import sys
        import pumplink.cli
        from pumplink.cli import main
        for args in (["force", "--speed", "360"],
                     ["batch", {str(grids[1])!r}, "--workers", "2", "--format", "csv",
                      "--out", {str(tmp_path / "o.csv")!r}, "--junit", {str(tmp_path / "o.xml")!r}]):
            try:
                main(args)
            except SystemExit as exc:
                assert exc.code in (0, 1), (args, exc.code)
        extras = ("dask", "distributed", "pyarrow", "numba")
        loaded = sorted(m for m in sys.modules if m.split(".")[0] in extras)
        print(loaded)
        """
    )
    r = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines()[-1] == "[]"
    assert (tmp_path / "o.csv").exists()

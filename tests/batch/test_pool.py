"""The batch worker pool: a dead worker ends the run, worker counts are capped, big runs say
how long they will take before they start."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import loky

from pumplink import batch as B

ROOT = Path(__file__).parents[2]
PROTOTYPE = ROOT / "configs" / "prototype.toml"
CMD = [sys.executable, "-m", "pumplink"]

BILLION = (
    f'base = "{PROTOTYPE}"\n[vary]\n'
    '"linkage.rocker" = { start = 0.15, stop = 0.3, num = 1000 }\n'
    '"linkage.swing" = { start = 40, stop = 80, num = 1000 }\n'
    '"load.rope_force" = { start = 30, stop = 80, num = 1000 }\n'
)


def _children(pid: int) -> list[tuple[int, str]]:
    out = []
    for d in Path("/proc").iterdir():
        if not d.name.isdigit():
            continue
        try:
            ppid = int((d / "stat").read_text().rsplit(")", 1)[1].split()[1])
            cmd = (d / "cmdline").read_bytes().replace(b"\0", b" ").decode()
        except (OSError, ValueError, IndexError):
            continue
        if ppid == pid:
            out.append((int(d.name), cmd))
    return out


def _workers(pid: int) -> list[int]:
    return [p for p, cmd in _children(pid) if "popen_loky" in cmd]


def _start(tmp_path: Path, *extra) -> subprocess.Popen:
    grid = tmp_path / "billion.toml"
    grid.write_text(BILLION)
    return subprocess.Popen(
        [*CMD, "batch", grid, "--format", "csv", "--out", tmp_path / "rows.csv", *map(str, extra)],
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def test_a_killed_worker_ends_the_run_within_seconds_and_writes_nothing(tmp_path):
    # What the out-of-memory killer does.  The standard library's pool never noticed and the
    # run hung (once for more than 10 minutes at 100 % of a core).
    p = _start(tmp_path, "--workers", "2", "--junit", tmp_path / "r.xml")
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and p.poll() is None and len(_workers(p.pid)) < 2:
        time.sleep(0.1)
    time.sleep(1.0)  # let the workers take tasks
    assert p.poll() is None, p.communicate()
    os.kill(_workers(p.pid)[0], signal.SIGKILL)
    t0 = time.monotonic()
    _, err = p.communicate(timeout=60)
    assert time.monotonic() - t0 < 10, err
    assert p.returncode == 130, err
    assert "worker process was killed" in err and "Traceback" not in err
    assert sorted(f.name for f in tmp_path.iterdir()) == ["billion.toml"]  # nothing, not even hidden


def test_a_large_batch_prints_its_size_and_estimate_before_starting(tmp_path):
    p = _start(tmp_path)
    line = p.stderr.readline()  # before any row is computed
    p.send_signal(signal.SIGINT)
    _, rest = p.communicate(timeout=60)
    assert line.startswith("batch: 1,000,000,000 variants in ") and "estimated" in line, line
    assert p.returncode == 130 and "Traceback" not in rest
    assert sorted(f.name for f in tmp_path.iterdir()) == ["billion.toml"]


def test_workers_are_capped_at_the_number_of_tasks(monkeypatch):
    made = []
    real = loky.ProcessPoolExecutor

    def spy(*a, max_workers=None, **k):
        made.append(max_workers)
        return real(*a, max_workers=max_workers, **k)

    monkeypatch.setattr(loky, "ProcessPoolExecutor", spy)
    batches = B.load_inputs([PROTOTYPE, PROTOTYPE])  # two tasks
    rows = list(B.run(batches, 36, workers=256))
    assert len(rows) == 2 and made == [2]
    made.clear()
    assert len(list(B.run(batches[:1], 36, workers=256))) == 1 and made == []  # one task: no pool


def test_the_estimate_is_days_for_a_billion_variants(tmp_path):
    grid = tmp_path / "g.toml"
    grid.write_text(BILLION)
    b = B.load_inputs([grid])
    tasks = B.plan(b, (1, 1), 8192)
    t0 = time.perf_counter()
    one = B.run_module.estimate_seconds(b, tasks, 360, 1)
    assert time.perf_counter() - t0 < 5  # a probe, not a run
    # 1e9 variants: a hand timing on this kind of machine gives some 10 us to 1 ms per variant
    assert 1e4 < one < 1e6 * 1e3, one


#: A worker that dies half-way through sending its result back: the killer thread fires while
#: the worker's main thread is blocked writing a 64 MB message into the pool's pipe (the
#: kernel's wait channel says so), else after 2 s.  The pool's manager thread used to wait for
#: the rest of that message forever (a hang the kill test above met in 2 runs of 33).
DIES_WHILE_SENDING = """
import os, signal, sys, threading, time
from concurrent.futures.process import BrokenProcessPool
from pumplink.batch.runner import map_ordered

def die_while_sending(i):
    if i != 1:
        time.sleep(5)  # the others outlast the killer's 2 s
        return i
    tid = threading.get_native_id()
    def killer():
        stop = time.monotonic() + 2
        while time.monotonic() < stop:
            with open(f"/proc/self/task/{tid}/wchan") as f:
                if "pipe_write" in f.read():
                    break
            time.sleep(0.0005)
        os.kill(os.getpid(), signal.SIGKILL)
    threading.Thread(target=killer, daemon=True).start()
    return b"x" * (64 << 20)

try:
    list(map_ordered(die_while_sending, [(i,) for i in range(6)], workers=2))
except BrokenProcessPool:
    print("broken")
"""


def test_a_worker_killed_while_sending_its_result_ends_the_run():
    p = subprocess.Popen([sys.executable, "-c", DIES_WHILE_SENDING], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, cwd=ROOT, start_new_session=True)  # fmt: skip
    try:
        out, err = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)  # the run and its workers
        raise
    assert out.strip() == "broken", err

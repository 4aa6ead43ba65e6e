"""Batch runs on a Dask cluster (``pumplink batch --scheduler``): a local one or a remote one.

The run is planned exactly as on the local pool (:func:`pumplink.batch.runner.plan`: the same
tasks, the same ``--chunk`` slices); each task is evaluated on a Dask worker by
:func:`pumplink.batch.runner.evaluate_chunk` and comes back as a :class:`~pumplink.batch.Chunk`,
one numpy array per column (no Python row objects).  The driver takes the chunks in plan order
and renders them (``post``: CSV, JSON, Parquet, JUnit), so the output is byte for byte that of
``--workers 1``.

Fault tolerance is Dask's: a task whose worker dies (SIGKILL, the out-of-memory killer, a lost
machine) is run again on another worker, and the driver receives exactly one result per task,
so no row is lost or written twice.  A task that kills
``distributed.scheduler.allowed-failures`` + 1 workers (default 4) ends the run.

The workers' malloc is tuned by a worker plugin (:class:`WorkerSetup`, :func:`pumplink.malloc.tune_malloc`):
Dask starts its workers
with ``MALLOC_TRIM_THRESHOLD_=65536``, which also freezes glibc's mmap threshold at 128 kB, so
every temporary array of the kernels is mapped and unmapped afresh and its pages faulted in; on
the flywheel design-space grid that cost twice the CPU time (``benchmarks/bench_dask.py``).

This module imports Dask (``pip install 'pumplink[dask]'``); the rest of pumplink does not (the
CLI only checks that it can be imported when ``--scheduler`` is given).
"""

from __future__ import annotations

import contextlib
import logging
import os
import signal
import threading
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from typing import Any

import dask
import distributed

from pumplink.batch.runner import Chunk, evaluate_chunk, plan, task_designs
from pumplink.errors import SpecError, shown
from pumplink.inputs.batch import Batch
from pumplink.malloc import tune_malloc

#: Seconds to wait for a remote scheduler to answer (a reachable one answers in milliseconds).
CONNECT_TIMEOUT = 5.0
#: Seconds to wait for a remote scheduler to have a worker (workers take seconds to start).
WORKER_TIMEOUT = 60.0

#: Dask settings of the local cluster: its background work, for a dashboard nobody watches here,
#: is cut from ~9 % of a core (idle, 2 workers; the statistical profiler samples every task's
#: stack every 10 ms) to ~1.5 %.  A cluster started elsewhere keeps its own settings.
LOCAL_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "2s",
    "distributed.worker.memory.monitor-interval": "1s",
}


@dataclass(frozen=True)
class Scheduler:
    """Where to run: ``address`` of a running Dask scheduler, or None for a local cluster of
    ``workers`` processes (0: one per CPU)."""

    address: str | None
    workers: int = 0

    def __str__(self) -> str:
        return self.address if self.address is not None else f"local:{self.workers}"


def parse_scheduler(text: str) -> Scheduler:
    """``--scheduler local:N`` (a local cluster of N worker processes; ``local`` or ``local:0``:
    one per CPU) or the address of a running scheduler (``tcp://host:8786``)."""
    text = text.strip()
    if text == "local" or text.startswith("local:"):
        n = text.partition(":")[2] or "0"
        try:
            workers = int(n)
        except ValueError:
            workers = -1
        if not 0 <= workers <= 256:
            raise SpecError(
                f"--scheduler {shown(text)}: the worker count must be an integer 0-256 "
                "(0: one per CPU); give e.g. --scheduler local:4"
            )
        return Scheduler(None, workers)
    if "://" not in text or not text.partition("://")[2]:
        raise SpecError(
            f"--scheduler {shown(text)} is neither local:N nor a scheduler address; "
            "give e.g. --scheduler local:4 or --scheduler tcp://host:8786"
        )
    return Scheduler(text)


class WorkerSetup(distributed.WorkerPlugin):
    """Worker plugin: :func:`tune_malloc` on every worker, including those that join or are
    restarted later; with ``local`` (the workers of the cluster pumplink started), also ignore
    Ctrl-C and SIGTERM, which the driver handles (see :func:`_stop_signals_ignored`)."""

    name = "pumplink-worker-setup"
    idempotent = True

    def __init__(self, local: bool = False):
        self.local = local

    def setup(self, worker) -> None:
        tune_malloc()
        if self.local and threading.current_thread() is threading.main_thread():
            for s in (signal.SIGINT, signal.SIGTERM):
                signal.signal(s, signal.SIG_IGN)


# ----------------------------------------------------------------------------- the cluster
@contextlib.contextmanager
def connect(
    scheduler: Scheduler, timeout: float = CONNECT_TIMEOUT, worker_timeout: float = WORKER_TIMEOUT
) -> Iterator[distributed.Client]:
    """A client on ``scheduler`` with :class:`WorkerSetup` registered; a local cluster is started
    here (one single-threaded worker process per core asked for) and closed on exit.

    A scheduler that does not answer within ``timeout`` seconds, or has no worker after
    ``worker_timeout`` seconds, is a :class:`~pumplink.errors.SpecError` (one line, exit 2).
    """
    with contextlib.ExitStack() as stack:
        for log in _loggers():  # a lost worker or scheduler is said in one line by the caller
            stack.callback(log.setLevel, log.level)
            log.setLevel(logging.CRITICAL)
        if scheduler.address is None:
            n = scheduler.workers or os.cpu_count() or 1
            with _stop_signals_ignored(), dask.config.set(LOCAL_CONFIG):
                cluster = stack.enter_context(
                    distributed.LocalCluster(
                        n_workers=n,
                        threads_per_worker=1,
                        processes=True,
                        dashboard_address=":0",  # any free port: never collides with another cluster
                        silence_logs=logging.CRITICAL,  # a restarted worker is not the user's business
                    )
                )
            client = stack.enter_context(distributed.Client(cluster))
        else:
            where = f"--scheduler {shown(scheduler.address)}"
            try:
                client = stack.enter_context(distributed.Client(scheduler.address, timeout=timeout))
            except (OSError, TimeoutError, ValueError) as exc:
                raise SpecError(
                    f"{where}: no Dask scheduler answered within {timeout:g} s{_reason(exc)}; start "
                    "one with `dask scheduler` and workers with `dask worker ADDRESS`, or use "
                    "--scheduler local:N"
                ) from None
            try:
                client.wait_for_workers(1, timeout=worker_timeout)
            except (OSError, TimeoutError) as exc:
                raise SpecError(
                    f"{where}: the scheduler has no worker after {worker_timeout:g} s{_reason(exc)}; start "
                    f"some with `dask worker {scheduler.address} --nthreads 1`"
                ) from None
        _check_workers(client, scheduler)
        yield client


@contextlib.contextmanager
def _stop_signals_ignored() -> Iterator[None]:
    """Ctrl-C and SIGTERM ignored while a local cluster starts its worker processes.

    An ignored signal stays ignored in a child process across exec, and Python then leaves it
    so: a terminal's Ctrl-C or a CI runner's SIGTERM to the process group reaches only the
    driver, which stops the workers through Dask, as the local pool's workers ignore both
    (:func:`pumplink.batch.runner.run`).  Workers restarted later ignore them from
    :class:`WorkerSetup`.  A signal sent during these 1-2 s is lost.
    """
    stop = (signal.SIGINT, signal.SIGTERM)
    old = [signal.signal(s, signal.SIG_IGN) for s in stop]
    try:
        yield
    finally:
        for s, handler in zip(stop, old):
            signal.signal(s, handler)


def installed_version() -> str:
    """The version of pumplink installed here (its package metadata)."""
    from importlib.metadata import version

    return version("pumplink")


def fingerprint() -> str:
    """pumplink's version and a digest of its source files: the driver and the workers must run
    the same code, or the rows would not be those of ``--workers 1``."""
    import hashlib
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]  # the pumplink package
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        digest.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes())
    return f"{installed_version()} ({digest.hexdigest()[:12]})"


def _check_workers(client: distributed.Client, scheduler: Scheduler) -> None:
    """Register :class:`WorkerSetup` and check that every worker runs this pumplink
    (:func:`fingerprint`); a worker without it, or with another version, is a SpecError."""
    fix = "install this pumplink, with its dask extra, on every worker"
    try:
        client.register_plugin(WorkerSetup(local=scheduler.address is None), name=WorkerSetup.name)
        theirs = client.run(fingerprint)
    except Exception as exc:  # the workers cannot unpickle a pumplink object: no pumplink there
        where = f"--scheduler {shown(str(scheduler))}"
        raise SpecError(f"{where}: a worker cannot load pumplink{_reason(exc)}; {fix}") from None
    ours = fingerprint()
    other = sorted({v for v in theirs.values() if v != ours})
    if other:
        raise SpecError(
            f"--scheduler {shown(str(scheduler))}: a worker runs pumplink {other[0]}, this is {ours}; {fix}"
        )


def _loggers() -> list[logging.Logger]:
    """Dask's loggers with a level of their own (``distributed`` and those its config sets)."""
    names = ["distributed", *(n for n in logging.root.manager.loggerDict if n.startswith("distributed."))]
    return [log for log in map(logging.getLogger, names) if log.level != logging.NOTSET]


def _reason(exc: BaseException) -> str:
    """`` (why)`` for a message, or nothing where Dask only says that it timed out."""
    text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return "" if text.startswith("Timed out") or isinstance(exc, TimeoutError) else f" ({text.rstrip('.:')})"


def threads(client: distributed.Client) -> int:
    """Tasks the cluster runs at once (its workers' threads)."""
    return max(1, sum(client.nthreads().values()))


def _evaluate(batch: Batch, index: int, start: int, stop: int, samples: int, model: str | None) -> Chunk:
    """One task on a worker: the chunk's arrays."""
    return evaluate_chunk(batch, start, stop, samples, index, model)


def map_ordered(fn: Callable[..., Any], items: Sequence[tuple], client: distributed.Client) -> Iterator[Any]:
    """``fn(*item)`` for each item on the cluster, yielded in the items' order, as
    :func:`pumplink.batch.runner.map_ordered` does on the local pool: at most two items per worker
    thread in flight, a task that keeps killing its workers or a lost scheduler raises
    ``BrokenProcessPool`` (with the reason).  ``fn`` must be importable on the workers (a
    module-level function of pumplink)."""
    it = iter(items)
    width = 2 * threads(client)
    pending: deque = deque(client.submit(fn, *item, pure=False) for _, item in zip(range(width), it))
    try:
        while pending:
            future = pending.popleft()
            result = _result(future)
            nxt = next(it, None)
            if nxt is not None:
                pending.append(client.submit(fn, *nxt, pure=False))
            del future  # released on the cluster once the driver holds the result
            yield result
    finally:
        if pending:
            client.cancel(list(pending))


def _result(future: distributed.Future) -> Any:
    """A task's result; a task that killed its workers, or a lost scheduler, is BrokenProcessPool."""
    try:
        return future.result()
    except distributed.KilledWorker:
        raise BrokenProcessPool("a task killed its Dask workers (out of memory?)") from None
    except distributed.client.FutureCancelledError:  # the scheduler went away
        raise BrokenProcessPool("lost the connection to the Dask scheduler") from None


def run(
    batches: Sequence[Batch],
    client: distributed.Client,
    samples: int = 360,
    chunk: tuple[int, int] = (1, 1),
    designs: int | None = None,
    post: Callable[[Batch, Chunk], Any] | None = None,
    model: str | None = None,
) -> Iterator[tuple[Chunk, Any]]:
    """Evaluate slice ``chunk`` of the run on the cluster, yielding ``(Chunk, post(batch, chunk))``
    in variant order, as :func:`pumplink.batch.runner.run` does (``model`` as there: a model key
    to decide every variant that gives inertia, else the least model that is enough).

    At most two tasks per worker thread are in flight, so the driver's memory stays bounded
    whatever the grid size; ``post`` (the rendering) runs here, in the driver, on each chunk
    as it is taken in order.  A task that keeps killing its workers, or a lost scheduler,
    raises ``BrokenProcessPool`` (with the reason), as a killed worker of the local pool does.
    """
    if designs is None:
        designs = task_designs(samples)
    tasks = iter(plan(batches, chunk, designs))
    width = 2 * threads(client)

    def submit(task: tuple[int, int, int]) -> distributed.Future:
        i, start, stop = task
        return client.submit(_evaluate, batches[i], i, start, stop, samples, model, pure=False)

    pending: deque = deque(submit(t) for _, t in zip(range(width), tasks))
    try:
        while pending:
            future = pending.popleft()
            c = _result(future)
            nxt = next(tasks, None)
            if nxt is not None:
                pending.append(submit(nxt))
            del future  # released on the cluster once the driver holds the arrays
            yield c, (post(batches[c.batch], c) if post is not None else None)
    finally:
        # Ctrl-C between two chunks leaves this generator suspended while the client's context
        # closes; it is finalised later, when a closed client cannot cancel ("IOLoop is closed")
        # and has nothing left to cancel
        if pending and client.status == "running":
            client.cancel(list(pending))

"""Batch evaluation: variants in chunks, vectorised over designs, through the one verdict.

Chunks are planned in variant order and evaluated in this process or on a pool of worker
processes (loky, which notices a worker that dies - SIGKILL, the out-of-memory killer - and
raises instead of waiting for it forever); the rows come back in order.  The numbers
per variant are bit-for-bit those of :func:`pumplink.studies.force.force_analysis` (``pumplink force
--summary``) on the same variant: the same kernels, vectorised over designs.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from pumplink.evaluate import (
    DYNAMICS,
    FAIL,
    FLYWHEEL,
    MODEL_LABELS,
    ORDER,
    QUASI_STATIC,
    REPORTED,
    WARN,
    Evaluation,
    PistonEvaluation,
    Verdict,
    evaluate,
    piston_designs,
    pump_designs,
)
from pumplink.inputs.batch import CRANK_SLIDER, FOUR_BAR, Batch, axis_indices
from pumplink.malloc import tune_malloc
from pumplink.mechanisms import crank_slider as cs
from pumplink.mechanisms.fourbar import infeasibility_reason

#: The ``model`` column's words for the models a batch variant can be decided by.
FLYWHEEL_LABEL, QUASI_STATIC_LABEL, DYNAMICS_LABEL = (MODEL_LABELS[ORDER.index(k)] for k in
                                                      (FLYWHEEL, QUASI_STATIC, DYNAMICS))  # fmt: skip
#: Most designs per chunk (rows handed to the writer at once, one task for a worker process).
CHUNK_DESIGNS = 8192


#: Crank samples per chunk: fewer designs per chunk at large --samples, so a task stays short
#: (an interrupted run waits for the running tasks) and its rows arrive steadily.
TASK_SAMPLES = 3_000_000


#: Most designs per chunk for variants that give inertia: full dynamics costs ~50 us a design (a
#: chunk a fifth of a second) and solves a chunk in blocks of its own (its CHUNK, cache-sized), so
#: the rows are the same bytes whatever this is; four blocks a chunk pay each stage's cost per call
#: (~15 ms: the kick-back's, the rocker rate's and the duty's searches) a quarter as often.
FLYWHEEL_DESIGNS = 4096


class _Judged:
    """What a chunk of either pump gives the run, read from its evaluation (``evaluation``): its
    size, the verdict and its level per variant, the forces, and the one ``--fail-on`` rule."""

    def __len__(self) -> int:
        return self.stop - self.start

    @property
    def feasible(self) -> np.ndarray:
        return self.evaluation.feasible

    @property
    def verdict(self) -> Verdict:
        """Every check, per variant (:func:`pumplink.verdict.assess`)."""
        return self.evaluation.verdict

    @property
    def mean_ok(self) -> np.ndarray:
        return np.asarray(self.verdict["mean_force"].passed)

    @property
    def peak_ok(self) -> np.ndarray:
        return np.asarray(self.verdict["peak_force"].passed)

    @property
    def passed(self) -> np.ndarray:
        return np.asarray(self.verdict.passed)

    @property
    def mean_force(self) -> np.ndarray:
        return self.evaluation.mean_force

    @property
    def verdict_peak_force(self) -> np.ndarray:
        """The peak force that decides the verdict [N]."""
        return self.evaluation.peak_force

    @property
    def least_peak_force(self) -> np.ndarray:
        return self.evaluation.least_peak_force

    @property
    def level(self) -> np.ndarray:
        """The verdict per variant: 0 PASS, 1 PASS with warnings, 2 FAIL."""
        return np.asarray(self.verdict.level)

    def failed(self, fail_on: Sequence[str]) -> np.ndarray:
        """True where a variant fails one of the checks selected by ``--fail-on``: ``mean``,
        ``peak``, ``infeasible``, ``checks`` (any other check that fails) and ``warnings`` (any
        check that warns, as ``--strict``)."""
        out = np.zeros(len(self), bool)
        if "infeasible" in fail_on:
            out |= ~self.feasible
        if "mean" in fail_on:
            out |= self.feasible & ~self.mean_ok
        if "peak" in fail_on:
            out |= self.feasible & ~self.peak_ok
        for c in self.verdict.checks:
            level = np.asarray(c.level)
            if "checks" in fail_on and c.key not in ("mean_force", "peak_force"):
                out |= self.feasible & (level == FAIL)
            if "warnings" in fail_on:
                out |= self.feasible & (level == WARN)
        return out


@dataclass(frozen=True, kw_only=True)
class Chunk(_Judged):
    """Results for variants ``start..stop-1`` of one batch: a view of the one evaluation over
    those variants (``evaluation``, arrays over them, SI units) with what a batch adds: the varied
    values and the infeasibility sentences (``reason``: None where feasible).

    The checks follow :func:`pumplink.verdict.assess`, as for ``pumplink force``: ``mean_ok`` =
    mean <= limit, ``peak_ok`` = verdict peak <= limit (False when it is NaN), ``passed`` = no check
    fails.  The numbers per variant are those of ``pumplink force --summary`` on the variant.
    """

    batch: int  # index of the batch in the run
    start: int
    stop: int
    values: np.ndarray  # (n, axes) varied values
    reason: list
    evaluation: Evaluation

    mechanism = FOUR_BAR

    @property
    def flywheel(self) -> np.ndarray:
        """True where an energy model (the flywheel or full dynamics) decides."""
        return self.evaluation.energy_decides

    @property
    def model(self) -> list[str]:
        """The words of the model that decided each variant (``model`` column)."""
        return [MODEL_LABELS[i] for i in self.evaluation.model_index.tolist()]

    @property
    def force_limit(self) -> np.ndarray:
        return np.broadcast_to(np.asarray(self.evaluation.designs.force_limit, float), (len(self),))

    @property
    def inertia(self) -> np.ndarray:
        return self.evaluation.inertia

    @property
    def speed_fluctuation(self) -> np.ndarray:
        """δ where the variant gives the wheel's inertia (NaN elsewhere)."""
        return self.evaluation.energy_speed_fluctuation


@dataclass(frozen=True)
class PistonChunk(_Judged):
    """Results for piston-pump variants ``start..stop-1`` of one batch: the one evaluation's
    (:class:`pumplink.evaluate.PistonEvaluation`) with the variants' spec values it shows
    (``spec``: dotted key -> a value per variant, spec units) and the infeasibility sentences."""

    batch: int
    start: int
    stop: int
    values: np.ndarray  # (n, axes) varied values
    evaluation: PistonEvaluation
    spec: dict[str, np.ndarray]
    reason: list

    mechanism = CRANK_SLIDER

    @property
    def flywheel(self) -> np.ndarray:
        return self.evaluation.model_index > 0

    @property
    def inertia(self) -> np.ndarray:
        return np.broadcast_to(np.asarray(self.evaluation.designs.inertia, float), (len(self),))

    @property
    def speed_fluctuation(self) -> np.ndarray:
        return self.spec["operator.speed_fluctuation"]

    @property
    def force_limit(self) -> np.ndarray:
        return self.spec["operator.force_limit"]

    @property
    def model(self) -> list[str]:
        return [MODEL_LABELS[i] for i in self.evaluation.model_index.tolist()]


def batch_values(batch: Batch, cols: dict[str, np.ndarray], n: int | None = None) -> dict:
    """The spec values :func:`pumplink.evaluate.pump_designs` reads: the varied values of a key (an
    array over the chunk's variants), else the base spec's value (None where it gives none).

    With ``n`` (the chunk's variants) a base value that is a number is given as ``n`` copies, so
    the evaluation has one design per variant whichever keys vary: also a key the evaluation
    reads apart from the others (``wheel.axle_height``, the ``[parts]``) or not at all
    (``linkage.hole_diameter``; ``wheel.radius`` beside a piston pump's ``wheel.inertia``)."""

    def per_variant(v):
        if n is not None and isinstance(v, (int, float)) and not isinstance(v, bool):
            return np.full(n, float(v))
        return v

    return {**{k: per_variant(v) for k, v in batch.spec.values.items()}, **cols}


def evaluate_chunk(
    batch: Batch, start: int, stop: int, samples: int = 360, batch_index: int = 0, model: str | None = None
) -> Chunk:
    """Synthesis, force checks and verdict for variants ``start..stop-1`` of a batch.

    One call of :func:`pumplink.evaluate.evaluate` over the variants; the numbers equal
    :func:`pumplink.studies.force.force_analysis` (``keep_samples=False``) on each variant's spec
    exactly, the energy models included where the variant gives inertia.

    Parameters
    ----------
    samples : uniform crank samples per revolution for the sampled-peak column (0: skip it).
        The peak force itself is exact whatever the sampling
        (:func:`pumplink.models.quasi_static.dead_band_peak_force`).
    model : a model key (``--model``) to decide every variant that gives inertia; default the
        least model that is enough, per variant.
    """
    n = stop - start
    if batch.axes:
        ij = axis_indices(batch, start, stop)
        values = np.stack([a.values[ij[:, j]] for j, a in enumerate(batch.axes)], axis=1)
    else:
        values = np.empty((n, 0))
    cols = {a.key: values[:, j] for j, a in enumerate(batch.axes)}
    value = batch_values(batch, cols, n)
    if batch.mechanism == CRANK_SLIDER:
        return _piston_chunk(batch, start, stop, batch_index, values, value)
    designs = pump_designs(value)
    ev = _one_per_variant(evaluate(designs, (*REPORTED, "sampled_peak"), model=model, samples=samples), n)
    reasons: list = [None] * n
    bad = np.nonzero(~ev.feasible)[0]
    if bad.size:
        cache: dict = {}
        codes = np.asarray(ev.synthesis.reason)
        L1, D1, b, swing = (np.broadcast_to(np.asarray(v, float), (n,)) for v in
                            (designs.L1, designs.D1, designs.b, designs.swing))  # fmt: skip
        for i in bad.tolist():
            k = (int(codes[i]), float(L1[i]), float(D1[i]), float(b[i]), float(swing[i]))
            if k not in cache:
                cache[k] = infeasibility_reason(*k)
            reasons[i] = cache[k]
    return Chunk(batch=batch_index, start=start, stop=stop, values=values, reason=reasons, evaluation=ev)


def _one_per_variant(ev, n: int):
    """The evaluation of a chunk's ``n`` variants, checked to hold ``n`` designs: a row per
    variant, or the run stops here (before a row of the chunk is written) rather than lose rows."""
    if len(ev) != n:
        raise RuntimeError(f"a batch chunk of {n} variants was evaluated as {len(ev)} designs")
    return ev


#: The piston spec's keys a batch row shows, per variant (spec units).
PISTON_KEYS = (
    "crank_slider.crank",
    "crank_slider.rod",
    "crank_slider.offset",
    "operator.handle",
    "piston.bore",
    "piston.head",
    "operator.speed",
    "operator.force_limit",
    "operator.speed_fluctuation",
)


def _piston_chunk(batch: Batch, start: int, stop: int, batch_index: int, values, value) -> PistonChunk:
    """:func:`evaluate_chunk` for a piston-pump batch (one evaluation over its variants)."""
    n = stop - start
    ev = _one_per_variant(evaluate(piston_designs(value)), n)
    spec = {
        k: np.broadcast_to(np.asarray(value.get(k) if value.get(k) is not None else 0.0, float), (n,))
        for k in PISTON_KEYS
    }
    spec["operator.force_limit"] = np.broadcast_to(np.asarray(ev.designs.force_limit, float), (n,))
    reasons: list = [None] * n
    for i in np.nonzero(~ev.feasible)[0].tolist():
        reasons[i] = cs.infeasibility_reason(
            spec["crank_slider.crank"][i], spec["crank_slider.rod"][i], spec["crank_slider.offset"][i]
        )
    return PistonChunk(batch_index, start, stop, values, ev, spec, reasons)


# ----------------------------------------------------------------------------- scheduling
def plan(
    batches: Sequence[Batch], chunk: tuple[int, int] = (1, 1), designs: int = CHUNK_DESIGNS
) -> list[tuple[int, int, int]]:
    """Tasks ``(batch, start, stop)`` for slice K of N of the run, in order.

    The run is all variants of all batches, concatenated; slice K (1-based) of N is the
    contiguous range ``[(K-1) T // N, K T // N)`` of that sequence, so the N slices partition it
    and every variant keeps its name.  A task has at most ``designs`` variants, and at most
    :data:`FLYWHEEL_DESIGNS` for a batch that gives inertia (its variants cost far more).
    """
    k, n = chunk
    total = sum(b.size for b in batches)
    lo, hi = (k - 1) * total // n, k * total // n
    tasks, offset = [], 0
    for i, b in enumerate(batches):
        s, e = max(lo, offset) - offset, min(hi, offset + b.size) - offset
        step = min(designs, FLYWHEEL_DESIGNS) if b.flywheel else designs
        for a in range(s, e, step):
            tasks.append((i, a, min(e, a + step)))
        offset += b.size
    return tasks


_worker_batches: Sequence[Batch] = ()


def _ignore_stop_signals() -> None:
    import signal

    # The parent handles Ctrl-C and SIGTERM (sent to the whole process group by a terminal or a
    # CI runner): it cancels the queued chunks and the workers exit after their current one.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)


def _init_worker(batches: Sequence[Batch]) -> None:
    global _worker_batches
    _worker_batches = batches


def _evaluate_one(batches: Sequence[Batch], task: tuple[int, int, int], samples: int, post, model=None):
    i, start, stop = task
    c = evaluate_chunk(batches[i], start, stop, samples, i, model)
    return c, (post(batches[i], c) if post is not None else None)


def _task(task: tuple[int, int, int], samples: int, post, model=None):
    return _evaluate_one(_worker_batches, task, samples, post, model)


def map_ordered(
    fn: Callable[..., Any],
    items: Sequence[tuple],
    workers: int = 1,
    initializer: Callable[..., None] | None = None,
    initargs: tuple = (),
) -> Iterator[Any]:
    """``fn(*item)`` for each item, yielded in the items' order: the batch engine's scheduling.

    With ``workers`` > 1 the items are run by that many processes (at most one per item;
    ``loky.ProcessPoolExecutor``: a worker killed mid-run raises ``BrokenProcessPool`` here
    instead of hanging), at most 2 items per worker in flight, so memory stays bounded however
    many there are; the workers ignore Ctrl-C and SIGTERM, which this process handles.  ``fn``
    and the items must pickle; ``initializer(*initargs)`` runs once in each worker (after the
    signals are set), to hand it what every item shares.  Else, one after the other here
    (``initializer`` first).

    A worker hands its result back in a file of a private temporary folder (removed at the
    end) and sends the pool only the file's name: a message that short is written into the
    pool's pipe in one piece, so a worker killed while sending cannot leave half a message
    there, which the pool's reader would wait for forever.
    """
    workers = min(workers, len(items))  # never more processes than items
    if workers <= 1:
        tune_malloc()  # pumplink.malloc: the kernels' temporaries on the heap
        if initializer is not None:
            initializer(*initargs)
        for item in items:
            yield fn(*item)
        return
    import shutil
    import tempfile
    from collections import deque

    from loky import ProcessPoolExecutor

    folder = tempfile.mkdtemp(prefix="pumplink-")
    pool = ProcessPoolExecutor(max_workers=workers, initializer=_init_pool, initargs=(initializer, initargs))
    pending: deque = deque()
    try:
        it = iter(items)
        for item in it:
            pending.append(pool.submit(_result_to_file, folder, fn, *item))
            if len(pending) >= 2 * workers:
                break
        while pending:
            result = _result_from_file(pending.popleft().result())
            nxt = next(it, None)
            if nxt is not None:
                pending.append(pool.submit(_result_to_file, folder, fn, *nxt))
            yield result
    finally:
        # Ctrl-C, SIGTERM, a dead worker or an error: drop the queued items and let the running
        # ones finish (tasks are sized to take well under a second at ordinary --samples).
        for f in pending:
            f.cancel()
        pool.shutdown(wait=True)
        shutil.rmtree(folder, ignore_errors=True)


def _result_to_file(folder: str, fn: Callable[..., Any], *item) -> str:
    """``fn(*item)`` pickled into a new file of ``folder`` (in a worker); the file's name."""
    import os
    import pickle
    import tempfile

    result = fn(*item)
    handle, path = tempfile.mkstemp(dir=folder, suffix=".pickle")
    with os.fdopen(handle, "wb") as f:
        pickle.dump(result, f, protocol=pickle.HIGHEST_PROTOCOL)
    return path


def _result_from_file(path: str) -> Any:
    """The result :func:`_result_to_file` left in ``path``; the file is removed."""
    import os
    import pickle

    with open(path, "rb") as f:
        result = pickle.load(f)
    os.unlink(path)
    return result


def _init_pool(initializer, initargs) -> None:
    _ignore_stop_signals()
    tune_malloc()  # a worker evaluates many designs: keep the kernels' temporaries on the heap
    if initializer is not None:
        initializer(*initargs)


def run(
    batches: Sequence[Batch],
    samples: int = 360,
    chunk: tuple[int, int] = (1, 1),
    workers: int = 1,
    designs: int | None = None,
    post: Callable[[Batch, Chunk], Any] | None = None,
    model: str | None = None,
) -> Iterator[tuple[Chunk, Any]]:
    """Evaluate slice ``chunk`` of the run, yielding ``(Chunk, post(batch, chunk))`` in variant order.

    With ``workers`` > 1 the chunks are evaluated by that many processes (:func:`map_ordered`: at
    most one per task, at most 2 tasks per worker in flight, a killed worker raises
    ``BrokenProcessPool``); the batches go to each worker once.  ``post`` (a picklable
    module-level function, e.g. the row formatting) runs in the worker too, so it is parallel as
    well.  ``model``: a model key to decide every variant that gives inertia (``--model``), else
    the least model that is enough.
    """
    if designs is None:
        designs = task_designs(samples)
    tasks = plan(batches, chunk, designs)
    if min(workers, len(tasks)) <= 1:
        tune_malloc()  # pumplink.malloc: the kernels' temporaries on the heap
        for t in tasks:
            yield _evaluate_one(batches, t, samples, post, model)
        return
    items = [(t, samples, post, model) for t in tasks]
    yield from map_ordered(_task, items, workers, _init_worker, (tuple(batches),))


def task_designs(samples: int) -> int:
    """Designs per task: about :data:`TASK_SAMPLES` crank samples per task, whatever --samples is."""
    return max(64, min(CHUNK_DESIGNS, TASK_SAMPLES // max(samples, 1)))


#: Variants timed per batch for :func:`estimate_seconds` (enough to amortise a call's overhead).
PROBE_DESIGNS = 256


def estimate_seconds(
    batches: Sequence[Batch], tasks: Sequence[tuple[int, int, int]], samples: int, workers: int
) -> float:
    """Wall time [s] the run ``tasks`` will take on ``workers`` processes, estimated by timing the
    first :data:`PROBE_DESIGNS` variants of each batch (fewer for the flywheel, whose variants
    cost ~0.5 ms each) and scaling by the number of variants of that batch in the run."""
    import time

    counts: dict[int, list[int]] = {}
    for i, s, e in tasks:
        c = counts.setdefault(i, [s, 0])
        c[1] += e - s
    total = 0.0
    for i, (start, n) in counts.items():
        probe = min(n, PROBE_DESIGNS // 4 if batches[i].flywheel else PROBE_DESIGNS)
        evaluate_chunk(batches[i], start, start + 1, samples, i)  # untimed: first-call imports
        t0 = time.perf_counter()
        evaluate_chunk(batches[i], start, start + probe, samples, i)
        total += (time.perf_counter() - t0) / probe * n
    return total / max(1, min(workers, len(tasks)))

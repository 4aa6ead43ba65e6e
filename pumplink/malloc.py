"""glibc's malloc for runs that evaluate many designs: the kernels' temporaries kept on the heap.

The kernels allocate temporary arrays of a few hundred kB to a few MB per call, many times a
second.  glibc maps a block above its mmap threshold afresh and unmaps it when freed, and gives
free memory at the top of the heap back above its trim threshold: either way the next array's
pages are faulted in again (system time; on the full-dynamics part checks of a block of designs,
a third of the CPU time, ``benchmarks/bench_parts.py``).  :func:`tune_malloc` raises both
thresholds: a long run (a batch, a tolerance study, a robust search's check) keeps up to
:data:`TRIM_THRESHOLD` of free heap instead.  Dask starts its workers with
``MALLOC_TRIM_THRESHOLD_=65536``, which also freezes glibc's mmap threshold at 128 kB
(:mod:`pumplink.batch.cluster` tunes them with a worker plugin).
"""

from __future__ import annotations

import ctypes

#: glibc's mmap threshold [bytes]: blocks below it come from the heap, which is reused.  32 MiB is
#: the ceiling of glibc's own dynamic threshold (``DEFAULT_MMAP_THRESHOLD_MAX`` on 64-bit systems),
#: which rises to the largest block freed.
MMAP_THRESHOLD = 32 * 1024 * 1024
#: glibc's trim threshold [bytes]: free memory at the top of the heap beyond this goes back to the
#: system (twice the mmap threshold, as glibc's dynamic rule sets it).
TRIM_THRESHOLD = 2 * MMAP_THRESHOLD

_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3  # mallopt parameters, <malloc.h>


def tune_malloc(mmap_threshold: int = MMAP_THRESHOLD, trim_threshold: int = TRIM_THRESHOLD) -> bool:
    """Set this process's glibc mmap and trim thresholds (``mallopt``); False where the C
    library is not glibc (macOS, musl), which then keeps its own behaviour."""
    try:
        libc = ctypes.CDLL("libc.so.6")
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return bool(mallopt(_M_MMAP_THRESHOLD, mmap_threshold)) and bool(
        mallopt(_M_TRIM_THRESHOLD, trim_threshold)
    )

"""The batch files' float text (``pumplink.output.batchfiles.float_texts``): repr's, whatever the float.

The CSV writes each float as Python's repr (the shortest text that reads back to the same float) by
way of orjson, whose text differs from repr below 1e-4 and for the non-finite values; those are
handed to repr.  The expected text is repr itself, value by value: random bit patterns over every
exponent, the edges where either formatter changes notation, and hypothesis' floats.
"""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pumplink.output.batchfiles import SMALL_TEXT, float_texts


def _repr(values):
    return [repr(v) if math.isfinite(v) else "" for v in values]


def test_random_bit_patterns_read_as_repr():
    """400,000 floats drawn as random 64-bit patterns (every exponent, subnormals, NaN payloads)."""
    bits = np.random.default_rng(11).integers(0, 2**64, size=400_000, dtype=np.uint64, endpoint=False)
    values = bits.view(np.float64).tolist()
    assert float_texts(values) == _repr(values)


def test_the_edges_of_each_notation_read_as_repr():
    """Each side of 1e-4 (repr's switch to an exponent below it), of 1e16 (its switch above), the
    smallest and largest floats, zeros of both signs, whole numbers, and the non-finite values."""
    tiny, huge = 2.2250738585072014e-308, 1.7976931348623157e308  # the smallest normal, the largest
    edges = [SMALL_TEXT, 1e16, 1e-5, 1e-7, 1e15, 1e17, 5e-324, tiny, huge]
    values = [0.0, -0.0, 1.0, 44.0, 0.1, 2.0**53, float("nan"), float("inf"), float("-inf")]
    for e in edges:
        for v in (e, math.nextafter(e, 0.0), math.nextafter(e, math.inf)):
            values += [v, -v]
    values += (10.0 ** np.arange(-20, 23)).tolist() + (np.arange(1, 200) * 1e-6).tolist()
    assert float_texts(values) == _repr(values)
    assert float_texts([]) == []


@settings(max_examples=300, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=1, max_size=50))
def test_any_floats_read_as_repr(values):
    assert float_texts(values) == _repr(values)

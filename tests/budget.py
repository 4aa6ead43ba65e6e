"""Example budgets of the slow property tests (test support, not product code).

``make test`` must stay within its time budget on a 2-core machine, so a property test whose
examples cost tens of milliseconds (a whole spec or batch file through the CLI contract) gets
``default`` examples there and ``thorough`` ones with ``HYPOTHESIS_PROFILE=thorough`` (or
``explore``, which also draws fresh examples).  Both are real runs with assertions; the
default is chosen so that every branch the test names is still reached (each test says why).
"""

from __future__ import annotations

import os

THOROUGH = os.environ.get("HYPOTHESIS_PROFILE", "default") in ("thorough", "explore")


def examples(default: int, thorough: int) -> int:
    """``max_examples`` for a slow property test: ``thorough`` in a thorough run, else ``default``."""
    return thorough if THOROUGH else default

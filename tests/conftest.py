"""Shared test set-up: make ``tests/reference.py`` importable and pin the hypothesis profile.

The numerical tests compare pumplink with an independent 50-digit mpmath reference
(``tests/reference.py``); the hypothesis example counts are set per test (``max_examples``)
so that the whole suite stays within its time budget.
"""

import sys
from pathlib import Path

from hypothesis import HealthCheck, Phase, settings

sys.path.insert(0, str(Path(__file__).parent))

# Derandomised by default so a CI run is reproducible, and without the shrink phase so that a
# failure (reported with its example) cannot blow the suite's time budget on 50-digit
# shrinking; HYPOTHESIS_PROFILE=explore draws fresh examples and shrinks them.
settings.register_profile(
    "default",
    derandomize=True,
    deadline=None,
    phases=[Phase.explicit, Phase.reuse, Phase.generate],
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
settings.register_profile(
    "explore",
    derandomize=False,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
settings.load_profile(__import__("os").environ.get("HYPOTHESIS_PROFILE", "default"))

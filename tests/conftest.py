"""Shared test set-up: make ``tests/reference.py`` importable and pin the hypothesis profile.

The numerical tests compare pumplink with an independent 50-digit mpmath reference
(``tests/reference.py``); the hypothesis example counts are set per test (``max_examples``, each
with the reason for its count), and the few slow property tests take a smaller budget in the
default run than in a thorough one (``tests/budget.py``: HYPOTHESIS_PROFILE=thorough).
"""

import os
import sys
from pathlib import Path

from hypothesis import HealthCheck, Phase, settings

sys.path.insert(0, str(Path(__file__).parent))

# Derandomised by default so a CI run is reproducible, and without the shrink phase so that a
# failure (reported with its example) cannot blow the suite's time budget on 50-digit
# shrinking; HYPOTHESIS_PROFILE=explore draws fresh examples and shrinks them, and
# HYPOTHESIS_PROFILE=thorough is the default run with the slow tests' full budgets.
# No filter_too_much suppression: the strategies draw valid cases directly.
settings.register_profile(
    "default",
    derandomize=True,
    deadline=None,
    phases=[Phase.explicit, Phase.reuse, Phase.generate],
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "thorough",
    derandomize=True,
    deadline=None,
    phases=[Phase.explicit, Phase.reuse, Phase.generate],
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "explore", derandomize=False, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))

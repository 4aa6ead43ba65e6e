"""The duty of the design columns (``pumplink.evaluate.water.duty``, docs/water.md §6).

A grid's variants that differ only in the linkage or the wheel ask the same duty rope speed: it is
solved once per distinct (power, head, bore).  The expected values are each variant's duty solved
on its own (one design, nothing shared), to the bit.
"""

import numpy as np

from pumplink.evaluate import water
from pumplink.models import losses


def _columns(head, bore):
    n = head.size
    return {
        "speed": np.full(n, 5.5),
        "losses": np.ones(n),
        "pipe_diameter": bore,
        "head": head,
        "wheel_radius": np.full(n, 0.25),
        "piston_clearance": np.full(n, losses.PISTON_CLEARANCE),
        "piston_spacing": np.full(n, losses.PISTON_SPACING),
    }


def test_alike_variants_share_the_duty_speed_each_its_own_to_the_bit(monkeypatch):
    """300 variants of 6 kinds (heads of 4-40 m, bores of 12.7 and 23 mm, in a shuffled order):
    flow and cadence of each are those of the variant alone, and the fixed point ran on 6 designs."""
    rng = np.random.default_rng(5)
    kinds = np.array(
        [(4.0, 0.0127), (10.0, 0.0127), (40.0, 0.0127), (4.0, 0.023), (10.0, 0.023), (40.0, 0.023)]
    )
    pick = rng.permutation(np.arange(300) % 6)
    head, bore = kinds[pick, 0].copy(), kinds[pick, 1].copy()
    power, flow, operator = np.full(300, 75.0), rng.uniform(2e-4, 8e-4, 300), np.full(300, 70.0)
    sizes = []
    solve = losses.duty_rope_speed

    def spy(power, head, d, efficiency):
        sizes.append(np.size(head))
        return solve(power, head, d, efficiency)

    monkeypatch.setattr(losses, "duty_rope_speed", spy)
    shared = water.duty(power, flow, _columns(head, bore), operator)
    assert sizes == [6]
    for i in range(300):
        one = water.duty(
            power[i : i + 1], flow[i : i + 1], _columns(head[i : i + 1], bore[i : i + 1]), operator[i : i + 1]
        )
        assert shared[0][i].tobytes() == one[0][0].tobytes()
        assert shared[1][i].tobytes() == one[1][0].tobytes()
    assert np.all(np.isfinite(shared[0])) and np.all(np.isfinite(shared[1]))

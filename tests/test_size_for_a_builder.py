"""`pumplink size` for a builder (docs/optimize.md, "Sizing the whole pump"): what it keeps, the
bounds it states, the smallest rising main, the pit it names and what a base spec holds.  No search
runs here (the searches are run by tests/test_water_and_size.py and the docs' output blocks).

Expected values: the bounds as docs/optimize.md's table states them, the ½" bore (12.7 mm), the
pit depth D1 - axle height by hand, the base spec's values as configs/village-10m.toml writes them.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pumplink.errors import SpecError
from pumplink.inputs.pump import default_spec, load_spec, parse_spec, spec_to_dict
from pumplink.search import size as S

ROOT = Path(__file__).resolve().parents[1]
VILLAGE = load_spec(ROOT / "configs" / "village-10m.toml")
BIN = Path(sys.executable).parent

#: docs/optimize.md's table of the search's bounds (spec units: deg/s, m, kg, deg).
DOCUMENTED = {
    "operator.speed": (60.0, 540.0),  # 10-90 turns a minute
    "wheel.radius": (0.15, 0.35),
    "wheel.mass": (1.0, 15.0),
    "wheel.axle_height": (0.40, 0.70),
    "linkage.handle": (0.5, 1.6),
    "linkage.rocker": (0.10, 0.40),
    "linkage.swing": (30.0, 100.0),
    "linkage.L1": (0.0, 1.0),
    "linkage.D1": (-0.6, 0.6),
}


def pumplink(*args) -> subprocess.CompletedProcess:
    return subprocess.run([BIN / "pumplink", *map(str, args)], capture_output=True, text=True, cwd=ROOT)


def test_the_bounds_are_the_documented_ones_and_help_states_them():
    assert S.BOUNDS == DOCUMENTED and S.MIN_PIPE == 0.0127
    text = " ".join(pumplink("size", "--help").stdout.split())
    for words in (
        '½", ¾", 1", 1¼", 1½"', "none below ½\", 12.7 mm", "10-90 turns a minute", "radius (0.15-0.35 m)",
        "mass at its rim (1-15 kg)", "handle (0.5-1.6 m)", "rocker (0.10-0.40 m)", "swing (30-100 deg)",
        "L1 0-1 m", "D1 0.6 m above to 0.6 m below", "--allow-pit", "(0.40-0.70 m)", "30-60 turns a minute",
        "0.6-1.8 m/s", "--keep",
    ):  # fmt: skip
        assert words in text, words


def test_a_rising_main_no_rope_piston_is_made_for_is_refused_before_any_search():
    r = pumplink("size", "--head", "10", "--pipes", "8,20mm")
    assert r.returncode == 2 and r.stderr.count("\n") == 1
    assert '8 mm is smaller than the ½" (12.7 mm) rope pistons are made for' in r.stderr
    S.problem_for(default_spec(), head=10.0, pipes=(0.0127,))  # ½" itself is accepted


def test_keep_holds_the_base_specs_wheel_pipe_and_handle():
    p = S.problem_for(VILLAGE, head=15.0, profile="women", keep=("wheel", "pipe", "handle"))
    assert p.pipes == (0.023,) and p.kept == ("wheel", "pipe", "handle")
    assert not {"wheel.radius", "wheel.mass", "linkage.handle"} & set(p.bounds)
    x = np.array([[DOCUMENTED[k][0]] for k in p.names])  # one design at the lower bounds
    values = S._values(p, 0.023, x)
    assert (values["wheel.radius"], values["wheel.mass"], values["linkage.handle"]) == (0.25, 10.0, 0.899)
    free = S.problem_for(VILLAGE, head=15.0)
    assert {"wheel.radius", "wheel.mass", "linkage.handle"} <= set(free.bounds) and len(free.pipes) == 5


@pytest.mark.parametrize(
    ("kwargs", "words"),
    [
        ({"keep": ("frame",)}, "choose from wheel, pipe, handle"),
        ({"keep": ("pipe",), "pipes": (0.02,)}, "not both"),
    ],
)
def test_keep_misuse_says_so(kwargs, words):
    with pytest.raises(SpecError, match=words):
        S.problem_for(VILLAGE, head=15.0, **kwargs)


def test_the_pit_is_the_pivot_below_the_ground_and_size_counts_it(tmp_path):
    """D1 0.65 m under an axle 0.55 m high: a pit 0.100 m deep, said by force; size's constraint
    is that depth (0 where the pivot is above the ground), unless the pit is allowed."""
    data = spec_to_dict(default_spec())
    data["wheel"]["axle_height"] = 0.55
    data["linkage"]["D1"] = 0.65
    spec = parse_spec(data)
    p = S.problem_for(spec, head=5.0)
    x = np.array([[0.65, -0.2] if k == "linkage.D1" else [0.55, 0.55] if k == "wheel.axle_height" else
                  [np.mean(DOCUMENTED[k])] * 2 for k in p.names])  # fmt: skip
    assert S.pit_depth(p, x) == pytest.approx([0.10, -0.75], abs=1e-12)
    from pumplink.output.words import pit_words

    assert pit_words(spec).startswith("pit: the rocker pivot sits 0.100 m below the ground")
    assert pit_words(default_spec()) == ""  # no axle height: no ground to be below
    import tomli_w

    path = tmp_path / "pit.toml"
    path.write_text(tomli_w.dumps(data), encoding="utf-8")
    shown = " ".join(pumplink("force", path, "--summary").stdout.split())
    assert (
        "pit: the rocker pivot sits 0.100 m below the ground (D1 0.65 m under an axle 0.55 m high)" in shown
    )


def test_a_base_spec_says_what_it_holds_that_the_built_in_design_does_not():
    held = dict((k, (v, b)) for k, v, b in S.problem_for(VILLAGE, head=15.0).held)
    assert held["linkage.mass_per_length"] == (2.407, None)
    assert held["parts.pin_diameter"] == (0.012, None)
    assert "load.head" not in held and "wheel.radius" not in held  # the question, and a varied key
    assert S.problem_for(default_spec(), head=15.0).held == ()

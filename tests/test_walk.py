"""The walk of one value from ``pumplink force`` to the verdict stays short: the handle length of the
village well (with the wheel's inertia and ``[parts]``: full dynamics decides, the part checks and
the kick-back run) reaches :func:`pumplink.verdict.assess` in at most 14 calls and at most 4 steps
back up a layer.

The walk is traced, not written down: every call from one pumplink module into another whose
arguments carry the handle length (the float itself, or an array, mapping, tuple, dataclass or spec
holding it) is a step, in the order made, from the command to the verdict.  Left out: what a kernel
calls inside the kernel layers (models, mechanisms: folded into the call that entered them),
attribute reads (properties), subscripts and other dunder methods, and calls within one module.
The spec file is read and validated in one module (:func:`pumplink.inputs.toml.read_spec`); that
reading is counted as the first step.  A step goes *back up a layer* when its callee sits in a
higher layer of the import contract (nearer the CLI) than the previous step's callee: the value
went down into a kernel and comes back up before it goes on.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import inspect
import io
import sys

import numpy as np
import pytest

from tests.examples import ROOT

#: The layers of the import contract (pyproject.toml), nearest the CLI first.
RANK = {"pumplink.cli": 0, "pumplink.output": 1, "pumplink.search": 2, "pumplink.studies": 3,
        "pumplink.batch": 3, "pumplink.inputs": 4, "pumplink.evaluate": 5, "pumplink.verdict": 6,
        "pumplink.models": 6, "pumplink.mechanisms": 7}  # fmt: skip
KERNELS = ("pumplink.models", "pumplink.mechanisms")
VILLAGE = ROOT / "configs" / "village-10m.toml"
HANDLE = 0.899  # the village well's linkage.handle [m]


def _layer(module: str) -> str:
    return max((k for k in RANK if module == k or module.startswith(k + ".")), key=len)


def _carries(x, depth: int = 0) -> bool:
    if depth > 4:
        return False
    if isinstance(x, float):
        return x == HANDLE
    if isinstance(x, np.ndarray):
        return x.dtype.kind == "f" and x.size < 10**7 and bool(np.any(x == HANDLE))
    if isinstance(x, dict):
        return any(_carries(v, depth + 1) for v in x.values())
    if isinstance(x, (list, tuple)):
        return any(_carries(v, depth + 1) for v in x[:50])
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return any(_carries(getattr(x, f.name, None), depth + 1) for f in dataclasses.fields(x))
    if type(x).__module__.startswith("pumplink") and hasattr(x, "__dict__"):
        return any(_carries(v, depth + 1) for v in vars(x).values())
    return False


def walk(argv: list[str]) -> list[tuple[str, str]]:
    """The steps (caller module, callee module.function) of the handle length, running ``argv``
    in this process until the verdict is assessed."""
    from pumplink.cli import main

    steps: list[tuple[str, str]] = []

    def profile(frame, event, arg):
        if event != "call":
            return
        module, code = frame.f_globals.get("__name__", ""), frame.f_code
        if not module.startswith("pumplink") or code.co_name.startswith(("<", "__")):
            return
        owner, _, name = code.co_qualname.rpartition(".")
        if owner in frame.f_globals:  # a property's getter is an attribute read
            attr = inspect.getattr_static(frame.f_globals[owner], name, None)
            if isinstance(attr, (property, functools.cached_property)):
                return
        caller = frame.f_back.f_globals.get("__name__", "") if frame.f_back else ""
        if caller == module or not caller.startswith("pumplink") or caller.startswith(KERNELS):
            return
        if module == "pumplink.inputs.toml" and code.co_name == "read_spec":
            steps.append((caller, f"{module}.{code.co_qualname}"))  # the handle length is read here
        else:
            arguments = code.co_varnames[: code.co_argcount + code.co_kwonlyargcount]
            if any(_carries(frame.f_locals.get(a)) for a in arguments):
                steps.append((caller, f"{module}.{code.co_qualname}"))
        if module == "pumplink.verdict" and code.co_name == "assess":
            sys.setprofile(None)

    old = sys.argv
    sys.argv = ["pumplink", *argv]
    sys.setprofile(profile)
    try:
        with contextlib.redirect_stdout(io.StringIO()), pytest.raises(SystemExit):
            main()
    finally:
        sys.setprofile(None)
        sys.argv = old
    return steps


def back_ups(steps) -> int:
    layers = [RANK[_layer(callee.rsplit(".", 1)[0])] for _, callee in steps]
    return sum(b < a for a, b in zip(layers, layers[1:]))


def test_the_handle_length_reaches_the_verdict_in_at_most_14_calls_and_4_steps_back_up():
    steps = walk(["force", str(VILLAGE), "--summary"])
    shown = "\n".join(f"{a} -> {b}" for a, b in steps)
    assert steps[0][1] == "pumplink.inputs.toml.read_spec", shown
    assert any(b.startswith("pumplink.models.kickback") for _, b in steps), shown  # traced to the end
    assert len(steps) <= 14, shown
    assert back_ups(steps) <= 4, shown


def test_the_tracer_sees_a_walk_that_goes_back_up():
    """The counting itself, on a made-up walk: down into a kernel and back up to the evaluation."""
    steps = [("pumplink.cli.force", "pumplink.studies.force.f"), ("a", "pumplink.evaluate.stages.g"),
             ("a", "pumplink.mechanisms.fourbar.h"), ("a", "pumplink.evaluate.parts.k"),
             ("a", "pumplink.models.joints.m"), ("a", "pumplink.verdict.assess")]  # fmt: skip
    assert back_ups(steps) == 1

"""The piston-pump path of ``pumplink force`` and ``pumplink batch`` (a spec with
``mechanism = "crank-slider"``, docs/piston-pump.md).  Not a command of its own: the two commands
dispatch here on the spec's mechanism kind before reading it as a rope pump."""

from __future__ import annotations

from pathlib import Path

import typer

from pumplink.errors import SpecError


def force(spec: Path, speed, samples: int, at, summary: bool, plot, explain: bool, verify: bool, fmt: str):
    """``pumplink force SPEC`` for a piston-pump spec; exits 0 (PASS) or 1 (FAIL, infeasible, a
    --verify disagreement)."""
    if plot is not None:
        raise SpecError(
            f"--plot is for rope-pump specs; {spec} is a piston pump (mechanism = 'crank-slider')"
        )
    from pumplink import piston as _piston
    from pumplink.output.piston import render_checks, render_force

    result = _piston.force_analysis(
        _piston.load_piston(spec), speed, samples, at_deg=at or None, keep_samples=not summary
    )
    why = _piston.explain(result) if explain and result.feasible else None
    check = _piston.verify(result) if verify and result.feasible else None
    render_force(result, fmt, summary=summary, why=why, check=check)
    if fmt != "json":
        render_checks(result, why, check)
    raise typer.Exit(0 if result.passed and (check is None or check.agrees) else 1)


def batch(inputs: list[Path], fmt: str, out: Path | None, fail_on: set[str], junit=None, chunk=None):
    """``pumplink batch`` over piston-pump spec and batch files; exits 1 if a variant fails a
    --fail-on check (mean, peak, infeasible)."""
    for flag, value in (("--junit", junit), ("--chunk", chunk)):
        if value is not None:
            raise SpecError(f"{flag} is for rope-pump batches; piston-pump batches run whole, without it")
    from pumplink.output.piston import render_batch
    from pumplink.piston import run_batch

    variants = run_batch(inputs)
    failed = []
    for v in variants:
        r = v.result
        bad = ("infeasible" in fail_on and not r.feasible) or (
            r.feasible
            and (
                ("mean" in fail_on and not r.verdict["mean_force"].passed)
                or ("peak" in fail_on and not r.verdict["peak_force"].passed)
            )
        )
        failed.append(bool(bad))
    if out is not None:
        from pumplink.output.formats import atomic_write

        with atomic_write(out) as fh:
            render_batch(variants, fmt, failed, out=fh)
    else:
        render_batch(variants, fmt, failed)
    raise typer.Exit(1 if any(failed) else 0)


def is_piston_input(inputs: list[Path]) -> bool:
    """True when the inputs are piston-pump files; mixing them with rope-pump files is an error."""
    from pumplink.spec import is_piston_file

    kinds = {is_piston_file(p) for p in inputs}
    if kinds == {True, False}:
        raise SpecError(
            "give piston-pump files (mechanism = 'crank-slider') and rope-pump files in separate runs"
        )
    return kinds == {True}

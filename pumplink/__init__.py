"""pumplink: design the four-bar linkage that drives a rope pump from a hand lever.

The Python API, for notebooks and scripts (SI units; speeds in deg/s as in the spec)::

    import pumplink
    spec = pumplink.load("configs/village-10m.toml")   # or a dict, or pumplink.default()
    result = pumplink.analyse(spec, speed=300)          # the force analysis and the verdict
    result                  # one line: name, verdict, peak and mean force
    result.to_dict()        # the JSON of `pumplink force --format json --summary`
    result.verdict.outcome  # 'PASS', 'PASS with warnings' or 'FAIL'
    pumplink.synthesize(spec).synthesis.crank_length   # the dead-centre synthesis alone

In Jupyter a result shows as a table of its checks.  A longer example is in docs/api.md.

The package by role (data flows one way, spec -> models -> verdict -> output):

* :mod:`pumplink.spec` - the TOML spec and the physics derived from it;
* :mod:`pumplink.mechanisms` - pure numpy kernels, one module per mechanism (the pump four-bar,
  the crank-rocker, crank-slider, slotted lever, structure analysis);
* :mod:`pumplink.models` - the force models that can decide (quasi-static, flywheel), one
  signature and a registry;
* :mod:`pumplink.verdict` - the one place that decides PASS, PASS with warnings or FAIL;
* :mod:`pumplink.analysis`, :mod:`pumplink.optimize`, :mod:`pumplink.batch` - one design, the
  design search, many variants;
* :mod:`pumplink.output` - tables, JSON/CSV, batch files and charts;
* :mod:`pumplink.cli` - the command line.

The physics is in the repository's docs/ folder (docs/physics.md, docs/models.md).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from pathlib import Path

    from pumplink.analysis import Design, ForceResult
    from pumplink.spec import PumpSpec

__version__ = "0.1.0"
__all__ = ["load", "default", "analyse", "synthesize", "examples", "__version__"]


def load(source: str | Path | dict[str, Any]) -> PumpSpec:
    """A validated pump spec from a TOML file path or a mapping of the same keys.

    Raises :class:`pumplink.errors.SpecError` with a one-sentence message for a bad spec.
    """
    from pumplink.spec import load_spec, parse_spec

    if isinstance(source, dict):
        return parse_spec(source)
    return load_spec(source)


def default() -> PumpSpec:
    """The built-in design (the pump paper's prototype), as ``pumplink force`` with no spec uses."""
    from pumplink.spec import default_spec

    return default_spec()


def analyse(
    spec: PumpSpec | str | Path | dict[str, Any], speed: float | None = None, samples: int = 360
) -> ForceResult:
    """The force analysis and verdict of ``pumplink force`` for one spec.

    Parameters
    ----------
    spec : a spec, or anything :func:`load` takes.
    speed : mean wheel speed [deg/s]; default the spec's ``operator.speed``.
    samples : uniform crank samples kept in ``result.samples`` (the verdict does not depend on it).
    """
    from pumplink.analysis import force_analysis
    from pumplink.spec import PumpSpec

    s = spec if isinstance(spec, PumpSpec) else load(spec)
    return force_analysis(s, speed, samples)


def synthesize(spec: PumpSpec | str | Path | dict[str, Any]) -> Design:
    """The dead-centre synthesis alone (``pumplink synth``): link lengths, dead centres, K."""
    from pumplink.analysis import design
    from pumplink.spec import PumpSpec

    return design(spec if isinstance(spec, PumpSpec) else load(spec))


def examples() -> dict[str, str]:
    """The shipped example specs: name -> design name (``pumplink init --example NAME``)."""
    from pumplink.examples import example_names

    return example_names()

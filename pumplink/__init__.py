"""pumplink: design the four-bar linkage that drives a rope pump from a hand lever.

The Python API, for notebooks and scripts (SI units; speeds in deg/s as in the spec)::

    import pumplink
    spec = pumplink.load("configs/village-10m.toml")   # or a dict, or pumplink.default()
    result = pumplink.analyse(spec, speed=300)          # the force analysis and the verdict
    result                  # one line: name, verdict, peak and mean force, the deciding model
    pumplink.to_dict(result)  # the JSON of `pumplink force --format json --summary`
    result.verdict.outcome  # 'PASS', 'PASS with warnings' or 'FAIL'
    pumplink.synthesize(spec).synthesis.crank_length   # the dead-centre synthesis alone

In Jupyter a result shows as a table of its checks (:func:`to_html`).  A longer example is in
docs/api.md.

The package by role (data flows one way, inputs -> models -> evaluation -> verdict -> output):

* :mod:`pumplink.inputs` - every file pumplink reads: pump and piston specs, batch files,
  mechanism files, their JSON Schemas;
* :mod:`pumplink.mechanisms` - pure numpy kernels, one module per mechanism (the pump four-bar,
  the crank-rocker, crank-slider, slotted lever, structure analysis);
* :mod:`pumplink.models` - the force models (quasi-static, flywheel, full dynamics, the piston
  pump's), one signature and a registry, and the load and masses they take;
* :mod:`pumplink.evaluate` - the one evaluation: design columns in, every quantity the verdict
  needs out; the only caller of the force models;
* :mod:`pumplink.verdict` - the one place that decides PASS, PASS with warnings or FAIL;
* :mod:`pumplink.studies` - one design in depth (force, speed, checks, the textbook mechanisms);
* :mod:`pumplink.search`, :mod:`pumplink.batch` - the design search, many variants;
* :mod:`pumplink.output` - tables, JSON/CSV, batch files and charts;
* :mod:`pumplink.cli` - the command line.

The physics is in the repository's docs/ folder (docs/physics.md, docs/models.md).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from pathlib import Path

    from pumplink.inputs.pump import PumpSpec
    from pumplink.studies.force import Design, ForceResult

__version__ = "0.1.0"
__all__ = ["load", "default", "analyse", "synthesize", "to_dict", "to_html", "examples", "__version__"]


def load(source: str | Path | dict[str, Any]) -> PumpSpec:
    """A validated pump spec from a TOML file path or a mapping of the same keys.

    Raises :class:`pumplink.errors.SpecError` with a one-sentence message for a bad spec.
    """
    from pumplink.inputs.pump import load_spec, parse_spec

    if isinstance(source, dict):
        return parse_spec(source)
    return load_spec(source)


def default() -> PumpSpec:
    """The built-in design (the pump paper's prototype), as ``pumplink force`` with no spec uses."""
    from pumplink.inputs.pump import default_spec

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
    from pumplink.inputs.pump import PumpSpec
    from pumplink.studies.force import force_analysis

    s = spec if isinstance(spec, PumpSpec) else load(spec)
    return force_analysis(s, speed, samples)


def synthesize(spec: PumpSpec | str | Path | dict[str, Any]) -> Design:
    """The dead-centre synthesis alone (``pumplink synth``): link lengths, dead centres, K."""
    from pumplink.inputs.pump import PumpSpec
    from pumplink.studies.force import design

    return design(spec if isinstance(spec, PumpSpec) else load(spec))


def to_dict(result: ForceResult, samples: bool = False) -> dict[str, Any]:
    """The JSON of ``pumplink force --format json`` for a result of :func:`analyse` (``--summary``
    unless ``samples``): plain numbers, ``None`` where a value is infinite or undefined."""
    from pumplink.output.force import force_summary, sample_rows

    out = force_summary(result)
    if samples:
        out["samples"] = sample_rows(result)
    return out


def to_html(result: ForceResult) -> str:
    """A result of :func:`analyse` as an HTML table of its checks (how Jupyter shows it)."""
    from pumplink.output.force import force_html

    return force_html(result)


def examples() -> dict[str, str]:
    """The shipped example specs: name -> design name (``pumplink init --example NAME``)."""
    from pumplink.inputs.examples import example_names

    return example_names()


def _show_results_in_notebooks() -> None:
    """Jupyter shows a force result as :func:`to_html` (registered by name: nothing is imported)."""
    import sys

    shell = getattr(sys.modules.get("IPython"), "get_ipython", lambda: None)()
    if shell is not None:
        html = shell.display_formatter.formatters["text/html"]
        html.for_type_by_name("pumplink.studies.force", "ForceResult", to_html)


_show_results_in_notebooks()

"""pumplink: design the four-bar linkage that drives a rope pump from a hand lever.

The package by role (data flows one way, spec -> models -> verdict -> output):

* :mod:`pumplink.spec` - the TOML spec and the physics derived from it;
* :mod:`pumplink.mechanisms` - pure numpy kernels, one module per mechanism (the pump four-bar,
  the crank-rocker, crank-slider, slotted lever, structure analysis);
* :mod:`pumplink.models` - the force models that can decide (quasi-static, flywheel), one
  signature and a registry;
* :mod:`pumplink.verdict` - the one place that decides PASS/FAIL;
* :mod:`pumplink.analysis`, :mod:`pumplink.optimize`, :mod:`pumplink.batch` - one design, the
  design search, many variants;
* :mod:`pumplink.output` - tables, JSON/CSV, batch files and charts;
* :mod:`pumplink.cli` - the command line.

The physics is in the repository's docs/ folder (docs/physics.md, docs/models.md).
"""

__version__ = "0.1.0"

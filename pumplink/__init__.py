"""pumplink: design the four-bar linkage that drives a rope pump from a hand lever.

Numerics are pure functions in :mod:`pumplink.mechanisms.fourbar`, :mod:`pumplink.mechanisms.fourbar` and
:mod:`pumplink.models.quasi_static`; :mod:`pumplink.analysis` turns a :class:`pumplink.spec.PumpSpec` into
results; :mod:`pumplink.output.tables` renders them; :mod:`pumplink.cli` is the command line.
"""

__version__ = "0.1.0"

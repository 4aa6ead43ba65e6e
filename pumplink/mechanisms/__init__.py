"""Pure numpy kernels, one module per mechanism: no spec, no I/O, no printing.

Angles in radians, lengths in the caller's unit (metres for the pump); every function broadcasts
over designs and crank angles.  The physics is in docs/physics.md, docs/crank-rocker.md and
docs/mechanisms.md.
"""

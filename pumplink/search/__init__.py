"""Searches over designs, each judged by the one evaluation: the design search (``optimize``)
and the advice after a FAIL (``suggest``)."""

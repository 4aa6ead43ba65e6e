"""The digits a printed figure carries, decided once for every view (tables, JSON and CSV).

No printed digit that the method does not determine (docs/json.md, "Digits").  A closed form, or
a root solved to rounding, is determined to a few units in its last place: JSON and CSV give it in
full (the float's shortest form), tables to the digits a reader needs.  A figure that an iterative
method stopped at a tolerance is determined to that tolerance only, and moves within it when the
solver's path moves (another processor's rounding moves it); every view rounds it there:

* a figure that moves by up to a relative ``rtol`` keeps the digits 10 rtol leaves,
  floor(-log10 rtol) - 1 (:func:`known_to`): one digit is kept back so that the last one printed
  moves only when the figure is within a tenth of a rounding step of a boundary.  The best cadence
  (its bounded search's tolerance), the released handle (its integration's global error), the
  argument of a refined extremum (a peak force's crank angle: sqrt(eps), the function being flat
  to first order there) and a --verify integration (the check's tolerance);
* a root to its final bracket: no digit below ten times the bracket's width (:func:`to_bracket`);
* a searched optimum (``pumplink optimize``): the search stops once its objective is settled to a
  relative ``tol``; at a minimum the objective is flat to first order, so a coordinate that only
  the objective settles is known to about sqrt(tol) of its size, and so is every figure read
  there (the optimum's forces, heights and angles).  They keep floor(-log10 sqrt(tol)) digits
  (:func:`at_optimum`; 4 for the search's 1e-8): the square root is the worst case, and the
  optimum's coordinates usually sit on the search's limits, held there far more sharply;
* a constraint's slack at a searched optimum is the figure it bounds (a grip height, an angle)
  less its limit: it keeps that figure's last decimal (:func:`difference`), and a constraint that
  binds has slack 0: its computed slack is below the search's binding tolerance, the solver's
  noise (:func:`slack`);
* a residual at or below the tolerance it is checked against is 0, "within" that tolerance
  (:func:`residual`): it says the check holds, and its digits are the integrator's noise.

tests/test_solver_perturbation.py runs every documented command with every iterative solver's
tolerances loosened ten times and its start moved, and the text must not change.
"""

from __future__ import annotations

import math

from pumplink.output.formats import num


def shown(quantity, x) -> float | None:
    """A catalogue quantity's value (:data:`pumplink.quantities.CATALOGUE`) to the digits its method
    determines (:func:`known_to` its ``rtol``), in full where it is settled to rounding."""
    return num(x) if quantity.rtol is None else known_to(x, quantity.rtol)


def significant(x, n: int) -> float | None:
    """``x`` rounded to ``n`` significant digits (None for None, NaN and inf).

    >>> significant(66.64025965782777, 4)
    66.64
    """
    x = num(x)
    if x is None or x == 0.0:
        return x
    return float(f"{x:.{n - 1}e}")


def digits(rtol: float) -> int:
    """Significant digits kept of a figure that moves by up to a relative ``rtol``: those 10 rtol
    leaves (at least 1)."""
    return max(1, math.floor(-math.log10(rtol)) - 1)


def known_to(x, rtol: float) -> float | None:
    """``x``, which moves by up to a relative ``rtol``, to :func:`digits` significant digits.

    >>> known_to(409.7646442994298, 1e-7)
    409.765
    """
    return significant(x, digits(rtol))


def to_bracket(x, width: float) -> float | None:
    """A root located to a final bracket ``width`` wide (absolute): to the decimal of the least power
    of ten at least ten times as wide.

    >>> to_bracket(300.90121601458327, 4.1e-7)
    300.90122
    """
    x = num(x)
    if x is None or not width > 0:
        return x
    return float(round(x, -math.ceil(math.log10(10 * width)))) + 0.0  # + 0.0: no -0.0


def optimum_digits(tol: float) -> int:
    """Significant digits of a searched optimum's figures, the search's objective settled to a
    relative ``tol``: those sqrt(tol) leaves (at least 1)."""
    return max(1, math.floor(-math.log10(math.sqrt(tol))))


def at_optimum(x, tol: float) -> float | None:
    """A figure of a searched optimum (a coordinate, or anything read there), its search stopped at
    the relative tolerance ``tol`` of its objective: to :func:`optimum_digits`."""
    return significant(x, optimum_digits(tol))


def _decimals(scale, tol: float) -> int | None:
    """Decimals :func:`at_optimum` gives a figure of size ``scale`` (None: no size to go by)."""
    scale = num(scale)
    if not scale:
        return None
    return optimum_digits(tol) - 1 - math.floor(math.log10(abs(scale)))


def difference(x, scale, tol: float) -> float | None:
    """A difference ``x`` from a searched optimum's figure of size ``scale`` (the optimum's
    objective; the figure a constraint bounds): to the last decimal :func:`at_optimum` gives that
    figure, so a difference below it is 0.

    >>> difference(0.006041, 1.323959, 1e-8)  # 1.33 m less a grip height known to 1.324 m
    0.006
    """
    x, places = num(x), _decimals(scale, tol)
    if x is None or places is None:
        return x
    return float(round(x, places)) + 0.0  # + 0.0: no -0.0


def slack(x, binds: bool, tol: float, figure) -> float | None:
    """A constraint's slack at a searched optimum: 0 where it binds, else to the last decimal of
    the figure the constraint bounds (:func:`difference`; the figure itself for a slack that is
    one)."""
    return 0.0 if binds else difference(x, figure, tol)


def residual(x, tolerance: float) -> float | None:
    """A residual checked against ``tolerance``: 0 at or below it (the check holds; the digits are
    noise), else the residual."""
    x = num(x)
    return 0.0 if x is not None and abs(x) <= tolerance else x


def text(x, n: int, none: str = "—") -> str:
    """``x`` for a table with ``n`` significant digits, trailing zeros kept ('1.000', '60.00',
    '0.1219'); ``none`` for None, NaN and inf."""
    x = num(x)
    if x is None:
        return none
    out = f"{x:#.{n}g}"
    return out[:-1] if out.endswith(".") else out


def optimum_text(x, tol: float, none: str = "—") -> str:
    """A figure of a searched optimum for a table (:func:`at_optimum`'s digits)."""
    return text(x, optimum_digits(tol), none)


def known_text(x, rtol: float, none: str = "—") -> str:
    """A figure that moves by up to a relative ``rtol``, for a table (:func:`known_to`'s digits)."""
    return text(x, digits(rtol), none)

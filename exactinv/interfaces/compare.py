"""How conservative is the paper?  For each method: the paper's threshold
(taken literally), the corrected one and the exact largest one, side by side.

It sits in ``interfaces``: it joins the paper's thresholds (``thresholds``) and the
exact valid sets (``validset``) into one report.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from ..core.algebraic import Real
from ..core.real_algebraic import RealAlgebraic
from ..core.scalars import Infinity
from ..model import LinearSystem, Polyhedron
from ..thresholds.steplength import steplength_threshold
from ..validset.engine import largest_threshold

__all__ = ["ThresholdComparison", "compare_thresholds"]


@dataclass(frozen=True)
class ThresholdComparison:
    """The paper's threshold (taken literally), the corrected one and the exact
    largest one for a method on a problem, with ratios corrected/largest."""

    method: str
    paper: Real
    corrected: Real
    largest: Real
    largest_attained: bool

    @property
    def ratio(self) -> Fraction | None:
        """corrected / largest as an exact rational when both are rational,
        else a float-free ``None`` (see ``ratio_interval``)."""
        if isinstance(self.corrected, Fraction) and isinstance(self.largest, Fraction) and self.largest:
            return self.corrected / self.largest
        return None

    @property
    def ratio_interval(self) -> tuple[Fraction, Fraction] | None:
        """A rational enclosure of corrected/largest (None if either is 0 or oo)."""
        lo_c, hi_c = _bounds(self.corrected)
        lo_l, hi_l = _bounds(self.largest)
        if lo_c is None or lo_l is None or lo_l <= 0:
            return None
        return lo_c / hi_l, hi_c / lo_l

    def row(self) -> dict:
        """One row of the comparison table, as text.

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
        >>> compare_thresholds(S, P, [ei.methods.taylor(1)])[0].row()
        {'method': 'taylor(1)', 'paper': '1', 'corrected': '1', 'largest': '1', 'corrected/largest': '1'}
        """
        return {"method": self.method, "paper": str(self.paper), "corrected": str(self.corrected),
                "largest": str(self.largest) + ("" if self.largest_attained else " (open)"),
                "corrected/largest": _ratio_text(self)}


def _bounds(v):
    if isinstance(v, Infinity):
        return None, None
    if isinstance(v, RealAlgebraic):
        v.refine(40)
        return v.lower, v.upper
    return v, v


def _ratio_text(c: ThresholdComparison) -> str:
    """corrected/largest exactly when rational, else a certified 6-digit enclosure."""
    if c.ratio is not None:
        return str(c.ratio)
    if isinstance(c.largest, Infinity):
        return "0 (largest = oo)" if not isinstance(c.corrected, Infinity) else "1"
    interval = c.ratio_interval
    if interval is None:
        return "0" if c.corrected == 0 else "-"
    lo, hi = interval
    scale = 10**6
    return f"[{_decimal(lo, scale, floor=True)}, {_decimal(hi, scale, floor=False)}]"


def _decimal(q: Fraction, scale: int, floor: bool) -> str:
    n = q.numerator * scale // q.denominator if floor else -((-q.numerator * scale) // q.denominator)
    return f"{n // scale}.{n % scale:06d}"


def compare_thresholds(system: LinearSystem, polyhedron: Polyhedron, methods) -> list[ThresholdComparison]:
    """For each method: the paper's, the corrected and the exact largest threshold.

    >>> import exactinv as ei
    >>> S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    >>> [(c.method, c.corrected, c.largest) for c in compare_thresholds(S, P, [ei.methods.taylor(1)])]
    [('taylor(1)', Fraction(1, 1), Fraction(1, 1))]
    """
    rows = []
    for m in methods:
        t = steplength_threshold(system, polyhedron, m)
        L = largest_threshold(system, polyhedron, m)
        rows.append(ThresholdComparison(m.name, t.paper, t.value, L.value, L.attained))
    return rows

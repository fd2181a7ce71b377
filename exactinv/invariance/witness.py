"""The exact witness of non-invariance (paper, Section 2): a point of P where
the flow or the map leaves P through a facet.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from ..core.encode import vec
from ..core.scalars import Vector, vector_text

__all__ = ["FacetWitness", "push_along_ray"]


@dataclass(frozen=True)
class FacetWitness:
    """An exact point ``x`` of P and a row ``facet`` of G that certify
    non-invariance.  Continuous case: g_j.x = b_j and g_j.Ax = ``rate`` > 0.
    Discrete case: g_j.A_d x = ``value`` > b_j (so A_d x is not in P)."""

    x: Vector
    facet: int
    value: Fraction

    def record(self) -> dict:
        """The witness as exact strings (for a claim).

        >>> FacetWitness((Fraction(1),), 0, Fraction(1)).record()
        {'x': ['1'], 'facet': 0, 'value': '1'}
        """
        return {"x": vec(self.x), "facet": self.facet, "value": str(self.value)}

    def __repr__(self) -> str:
        return f"FacetWitness(x={vector_text(self.x)}, facet={self.facet}, value={self.value})"


def push_along_ray(x: Vector, ray: Vector, objective: Vector, bound: Fraction) -> Vector:
    """A point x + t ray (t > 0 exact) of an unbounded LP's ray with objective
    value above ``bound``: a witness the LP's ray proves exists.

    >>> push_along_ray((Fraction(0),), (Fraction(1),), (Fraction(2),), Fraction(3))   # 2 x > 3 at x = 5/2
    (Fraction(5, 2),)
    """
    slope = sum(c * d for c, d in zip(objective, ray))
    now = sum(c * xi for c, xi in zip(objective, x))
    t = max(Fraction(0), (bound - now) / slope) + 1
    return tuple(xi + t * d for xi, d in zip(x, ray))

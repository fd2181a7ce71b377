"""Shared by the pruning tests (polynomial and rational routes): a problem's data as Fraction
lists for the kernel's functions (the ``forced`` fixture is in conftest.py)."""

from fractions import Fraction


def fractions_of(S, P):
    """(A, G, b, vertices) of a system and a polyhedron, as Fraction lists."""
    A = [[Fraction(x) for x in r] for r in S.A]
    return A, [[Fraction(x) for x in r] for r in P.G], [Fraction(x) for x in P.b], [list(map(Fraction, v)) for v in P.vertices]

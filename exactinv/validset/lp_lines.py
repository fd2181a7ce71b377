"""The LP route on a P with lines (rank G < n): P = L + Q, L = ker G (docs/design.md, "P with lines").

Let l_1, ..., l_k be a basis of L = ker G (k = n - rank G > 0) and
P' = {x : G x <= b, l_j^T x <= 0 (j = 1..k)} -- the rows of a basis of L appended
to G with right-hand side 0.  P' is a subset of P, it is pointed (its lineality
space is ker G intersected with the l_j's orthogonal complement: 0), and
P = P' + L (any x in P is q + l with q its projection on L's orthogonal
complement, q in P').  For facet i with c_i(h) = N(h)^T g_i:

* e_ij(h) = c_i(h)^T l_j = g_i N(h) l_j (the *line conditions*, built here
  from G N_k without any generator list).  Where some e_ij(h) != 0,
  max g_i A_d(h) x over P is +oo (x + t l_j with t of the right sign) and
  facet i fails: each e_ij = 0 is necessary, the same line-facet equality as
  the vertex route's.
* where every e_ij(h) = 0, c_i(h) is orthogonal to L, so
  max c_i^T x over P = max over P' (every x of P is x' + l, x' in P',
  c_i^T l = 0): the LP route's pieces on P', whose bases are n rows of
  G' = [G; L^T] (each basis holds every l_j, as rank G = n - k), prove the
  maximizers x_B (points of P' in P) by weak duality, and their conditions
  are necessary for P (x_B is a point of P, a ray of P' is a ray of P).

So {h : D(h) != 0, every e_ij(h) = 0, every piece condition >= 0} is the valid
set exactly.  Whether e_ij vanishes identically (facet i sees only Q: the
current route) or at finitely many h (isolated steplengths, decided by the
pieces of P' at those points) is not a case of the code: the equalities and
the pieces together decide both.  The certificate is the LP route's record of
P' with the key ``lines`` (exactinv_check.routes.lp_pieces proves G l_j = 0 and
recomputes the line conditions itself).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import flint

from ..conditions.polyhedron import Condition, ConditionSet, Kind
from ..core.encode import vec
from ..core.flintq import fraction_of
from ..model.polyhedron import Polyhedron
from .lp_route import LPRoute, LPRouteDeclined, remembered, walk_facets

__all__ = ["lineality_basis", "LPLinesRoute", "LPLinesCache", "line_conditions", "lp_lines"]


def lineality_basis(G: flint.fmpq_mat) -> tuple[tuple[Fraction, ...], ...]:
    """A basis of ker G = {x : G x = 0} (the lineality space of {Gx <= b} when nonempty), each vector
    with coprime integer entries, from the reduced row echelon form: one vector per free column
    (exact; empty when rank G = n).

    >>> lineality_basis(flint.fmpq_mat([[1, 0], [-1, 0]]))      # the slab |x_1| <= 1 in R^2: the x_2 axis
    ((Fraction(0, 1), Fraction(1, 1)),)
    >>> lineality_basis(flint.fmpq_mat([[1, 1, 0]]))
    ((Fraction(-1, 1), Fraction(1, 1), Fraction(0, 1)), (Fraction(0, 1), Fraction(0, 1), Fraction(1, 1)))
    """
    R, rank = G.rref()
    n = G.ncols()
    pivots: list[int] = []
    for r in range(rank):
        pivots.append(next(c for c in range(n) if R[r, c] != 0))
    out = []
    for free in (c for c in range(n) if c not in pivots):
        v = [Fraction(0)] * n
        v[free] = Fraction(1)
        for r, p in enumerate(pivots):
            v[p] = -fraction_of(R[r, free])
        den = math.lcm(*(x.denominator for x in v))
        ints = [int(x * den) for x in v]
        g = math.gcd(*ints)
        out.append(tuple(Fraction(x // g) for x in ints))
    return tuple(out)


@dataclass(frozen=True)
class LPLinesRoute(LPRoute):
    """The LP route's pieces on P' = P with the rows l_j^T x <= 0 of ``lines`` (a basis of ker G)
    appended: a basis's row m + j is l_j.  Its record is the LP route's with the key ``lines``."""

    lines: tuple[tuple[Fraction, ...], ...] = field(default=(), repr=False)

    def record(self) -> dict:
        """The LP route's record plus ``lines``.

        >>> import exactinv as ei
        >>> cs = ConditionSet(ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1]),
        ...                   ei.methods.taylor(1))
        >>> _, _, route = lp_lines(cs)
        >>> record = route.record()   # basis [0, 2]: x_1 <= 1 and the line row (0, 1) x <= 0: x_B = (1, 0)
        >>> record["lines"], record["facets"][0]
        ([['0', '1']], {'ends': ['1', 'oo'], 'bases': [[0, 2], [1, 2]]})
        """
        out = super().record()
        out["lines"] = [vec(line) for line in self.lines]
        return out


@dataclass
class LPLinesCache:
    """The work of :func:`lp_lines` on one :class:`ConditionSet` (``ConditionSet.cache(LPLinesCache)``)."""

    found: tuple[list[Condition], list[Condition], LPLinesRoute] | None = None
    declined: LPRouteDeclined | None = None


def line_conditions(cs: ConditionSet, lines: tuple[tuple[Fraction, ...], ...]) -> list[Condition]:
    """The line-facet equalities e_ij(h) = g_i N(h) l_j = 0 that are not identically zero (from G N_k;
    ``generator`` j indexes ``lines``), facet by facet.

    The slab |x_1| <= 1 under A = [[-1, 1], [0, -1]], Taylor(2): r(hA)_12 = h - h^2 for both facets (+-).

    >>> import exactinv as ei
    >>> cs = ConditionSet(ei.LinearSystem([[-1, 1], [0, -1]]), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1]),
    ...                   ei.methods.taylor(2))
    >>> [(c.facet, c.poly) for c in line_conditions(cs, lineality_basis(cs.G))]
    [(0, (Fraction(0, 1), Fraction(1, 1), Fraction(-1, 1))), (1, (Fraction(0, 1), Fraction(-1, 1), Fraction(1, 1)))]
    """
    out = []
    GN = cs.GN
    for i in range(cs.polyhedron.m):
        for j, line in enumerate(lines):
            e = flint.fmpq_poly([sum((GN[k][i][l] * flint.fmpq(v.numerator, v.denominator)
                                      for l, v in enumerate(line) if v), flint.fmpq(0))
                                 for k in range(len(GN))])
            if not e.is_zero():
                out.append(Condition(Kind.LINE, j, i, e))
    return out


def lp_lines(cs: ConditionSet) -> tuple[list[Condition], list[Condition], LPLinesRoute]:
    """(inequalities, equalities, route) of a P with lines (rank G < n), computed once per
    :class:`ConditionSet`: the pieces of every facet on P' (module docstring), their vertex and ray
    conditions, and the line equalities.  Raises :class:`LPRouteDeclined` where the LP route on P'
    declines (and for rank G = n: use :func:`~exactinv.validset.lp_route.lp_route`).

    The slab |x_1| <= 1 in R^2 under x' = -x, forward Euler: valid exactly on [0, 2], as on [-1, 1].

    >>> import exactinv as ei
    >>> cs = ConditionSet(ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1]),
    ...                   ei.methods.taylor(1))
    >>> inequalities, equalities, route = lp_lines(cs)
    >>> [c.poly for c in inequalities], equalities
    ([(Fraction(2, 1), Fraction(-1, 1)), (Fraction(2, 1), Fraction(-1, 1))], [])
    """
    return remembered(cs.cache(LPLinesCache), lambda: _build(cs))


def _build(cs: ConditionSet) -> tuple[list[Condition], list[Condition], LPLinesRoute]:
    lines = lineality_basis(cs.G)
    if not lines:
        raise LPRouteDeclined("P has no lines (rank G = n): the LP route itself handles it")
    P = cs.polyhedron
    G2 = [list(row) for row in P.G] + [list(line) for line in lines]
    b2 = list(P.b) + [Fraction(0)] * len(lines)
    pointed = ConditionSet(cs.system, Polyhedron(G2, b2), cs.method)
    inequalities, route = walk_facets(pointed, P.m)
    lined = LPLinesRoute(route.facets, route.vertices, route.float_lps, route.exact_lps, route.seconds,
                         route.point, lines)
    return inequalities, line_conditions(cs, lines), lined

"""Exact valid sets on boxes without vertex enumeration (issue 13).

P = {lo <= x <= hi} (lo < hi, finite).  Write x = c + W u with c = (lo + hi)/2,
W = diag(w), w = (hi - lo)/2 > 0, |u|_oo <= 1.  With D(h) and N(h) = D(h) r(hA)
as in :mod:`.conditions`, the entry polynomials of row j are

    v_j0(h) = (N(h) c)_j - D(h) c_j,   v_jl(h) = N_jl(h) w_l  (l = 1..n),

and for a sign vector s = (s_0, s_1..s_n) in {-1, 1}^(n+1)

    q_{j,s}(h) = w_j D(h) - sum_l s_l v_jl(h)
               = a^-1 (b_k D(h) - g_k N(h) v)   with v = c + W (s_0 s_1, .., s_0 s_n),

k the row of G giving hi_j (s_0 = 1) or lo_j (s_0 = -1) and a = |G_kj| > 0: the
general route's condition of vertex v and facet k is c_{j,s} = a q_{j,s} D.
Every sign vector is a vertex-facet pair, so the valid set V_S of any family
S_j of sign vectors per row contains the full valid set V.

Why V_S = V when S_j holds the sign pattern sigma_j(h) = sign(v_j(h)) on every
open cell between consecutive positive roots of row j's n + 1 entry
polynomials (and, if D may change sign on (0, oo), its negation too).  Take
h >= 0 in V_S; D(h) != 0 (both sets exclude the poles).  If D(h) > 0: for
every s, s . v_j(h) <= sum_l |v_jl(h)| = sigma . v_j(h) for any sigma that
agrees with sign(v_j(h)) on the entries not vanishing at h -- and the pattern
of the cell containing h, or of either cell next to h when h is a root (an
entry nonzero at h keeps its sign nearby; h = 0 has the cell right of it), is
such a sigma.  So c_{j,s}(h) >= c_{j,sigma}(h) >= 0.  If D(h) < 0 the
condition says q_{j,s}(h) <= 0 for all s, and max_s q_{j,s}(h) is attained at
-sigma, which S_j holds too.  Hence every vertex-facet condition holds at h:
V_S is a subset of V.  Rows of G that are not the tightest bound of their
coordinate are implied by the others (P is the box), so their conditions
change nothing.

Cost: n (n + 1) entry polynomials and at most n (number of entry roots + 1)
(twice that with a sign-changing D) conditions, instead of 2n 2^n pairs.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from fractions import Fraction

import flint

from ..core.algebraic import ExactKey
from ..core.encode import vec
from ..core.flintq import fmpq_of
from ..core.polys import integer_part, sign_variations
from ..core.real_algebraic import RealAlgebraic
from ..core.roots import real_roots
from .polyhedron import Condition, ConditionSet, Kind, never_binds

__all__ = ["Box", "BoxRoute", "detect_box", "box_route", "vertex_index"]


@dataclass(frozen=True)
class Box:
    """P = {lo <= x <= hi} exactly; ``upper[l]`` / ``lower[l]`` is the first row of G
    giving the bound hi_l / lo_l, ``scale`` its |G_kl| (every other row is implied)."""

    lo: tuple[Fraction, ...]
    hi: tuple[Fraction, ...]
    upper: tuple[int, ...]
    lower: tuple[int, ...]
    scale_upper: tuple[Fraction, ...] = field(repr=False)
    scale_lower: tuple[Fraction, ...] = field(repr=False)

    def record(self) -> dict:
        """The certificate's box record (the kernel proves it from G and b itself).

        >>> detect_box([[2, 0], [0, 1], [-1, 0], [0, -1]], [2, 3, 1, 0]).record()
        {'lo': ['-1', '0'], 'hi': ['1', '3']}
        """
        return {"lo": vec(self.lo), "hi": vec(self.hi)}


def detect_box(G, b) -> Box | None:
    """The box that P = {Gx <= b} is, or None: every row has one nonzero entry, every
    coordinate a lower and an upper bound (the tightest ones count), lo < hi.

    >>> detect_box([[1], [-1], [3]], [1, 0, 6])            # x <= 1, x >= 0, x <= 2 (implied)
    Box(lo=(Fraction(0, 1),), hi=(Fraction(1, 1),), upper=(0,), lower=(1,))
    >>> detect_box([[1, 1], [-1, 0], [0, -1]], [1, 0, 0]) is None    # a triangle
    True
    """
    n = len(G[0])
    bounds: dict[tuple[int, bool], tuple[Fraction, int, Fraction]] = {}
    for k, (row, beta) in enumerate(zip(G, b)):
        support = [l for l, x in enumerate(row) if x != 0]
        if len(support) != 1:
            return None
        l = support[0]
        a = Fraction(row[l])
        bound, is_upper = Fraction(beta) / a, a > 0
        old = bounds.get((l, is_upper))
        if old is None or (bound < old[0] if is_upper else bound > old[0]):
            bounds[l, is_upper] = (bound, k, abs(a))
    if len(bounds) != 2 * n or any(bounds[l, False][0] >= bounds[l, True][0] for l in range(n)):
        return None
    up, down = [bounds[l, True] for l in range(n)], [bounds[l, False] for l in range(n)]
    return Box(tuple(d[0] for d in down), tuple(u[0] for u in up), tuple(u[1] for u in up),
               tuple(d[1] for d in down), tuple(u[2] for u in up), tuple(d[2] for d in down))


def vertex_index(u) -> int:
    """The index in ``Polyhedron.vertices`` (sorted) of the box vertex with u_l = +1 at hi_l,
    -1 at lo_l: bit n - 1 - l is set iff u_l = +1 (lexicographic order, lo_l < hi_l).

    >>> vertex_index((-1, -1)), vertex_index((-1, 1)), vertex_index((1, -1))
    (0, 1, 2)
    """
    i = 0
    for s in u:
        i = 2 * i + (s > 0)
    return i


@dataclass(frozen=True)
class BoxRoute:
    """The box route's result: the ``box``, the number of ``entries`` (entry polynomials),
    ``cells`` (sign patterns found, over all rows), ``conditions`` built, seconds per stage."""

    box: Box
    entries: int
    cells: int
    conditions: int
    seconds: tuple[tuple[str, float], ...] = field(default=(), compare=False)


def _entry_polynomials(cs: ConditionSet, box: Box) -> list[list[flint.fmpq_poly]]:
    """rows[j] = [v_j0, v_j1, .., v_jn] (module docstring), exactly."""
    n = len(box.lo)
    c = flint.fmpq_mat(n, 1, [fmpq_of((a + b) / 2) for a, b in zip(box.lo, box.hi)])
    w = [fmpq_of((b - a) / 2) for a, b in zip(box.lo, box.hi)]
    Dc = cs.D.coeffs() + [flint.fmpq(0)] * (len(cs.N) - len(cs.D.coeffs()))
    Nc = [(Nk * c).entries() for Nk in cs.N]
    NW = [Nk.entries() for Nk in cs.N]
    rows = []
    for j in range(n):
        v0 = [Nc[k][j] - (Dc[k] if k < len(Dc) else 0) * c[j, 0] for k in range(len(cs.N))]
        v0 += [-d * c[j, 0] for d in Dc[len(cs.N):]]
        rows.append([flint.fmpq_poly(v0)] + [flint.fmpq_poly([E[j * n + l] * w[l] for E in NW]) for l in range(n)])
    return rows


def _samples(entries: list[flint.fmpq_poly]) -> list[Fraction]:
    """One rational in every open cell of (0, oo) cut by the positive roots of the entries:
    the roots of their distinct irreducible factors (distinct roots), exactly ordered,
    and a point between each two.

    >>> _samples([flint.fmpq_poly([2, -3, 1]), flint.fmpq_poly([-1, 1]), flint.fmpq_poly([5])])
    [Fraction(1, 2), Fraction(3, 2), Fraction(3, 1)]
    """
    factors: dict[tuple[int, ...], flint.fmpz_poly] = {}
    for p in entries:
        if p.degree() > 0:
            for f, _ in integer_part(p).factor()[1]:
                f = f if f.leading_coefficient() > 0 else -f
                factors[tuple(int(c) for c in f.coeffs())] = f
    roots = sorted((r for f in factors.values() for r, _ in real_roots(flint.fmpq_poly(f)) if r > 0), key=ExactKey)
    points: list = [Fraction(0)] + roots
    out = [_between(a, b) for a, b in zip(points, points[1:])]
    last = points[-1]
    return out + [(last.upper if isinstance(last, RealAlgebraic) else last) + 1]


def _between(a, b) -> Fraction:
    """A rational strictly between the exact reals a < b (refining their enclosures).

    >>> _between(Fraction(1), Fraction(2))
    Fraction(3, 2)
    """
    bits = 8
    while True:
        top = a.upper if isinstance(a, RealAlgebraic) else a
        bottom = b.lower if isinstance(b, RealAlgebraic) else b
        if top < bottom:
            return (top + bottom) / 2
        if top == bottom and isinstance(a, RealAlgebraic) and isinstance(b, RealAlgebraic):
            return top  # a < a.upper = b.lower < b
        for x in (a, b):
            if isinstance(x, RealAlgebraic):
                x.refine(bits)
        bits *= 2


def _patterns(entries: list[flint.fmpq_poly], negate: bool) -> set[tuple[int, ...]]:
    """The sign patterns of the row on its cells (identically zero entries: +1), and their negations."""
    out = set()
    for t in _samples(entries):
        x = fmpq_of(t)
        s = tuple(-1 if p(x) < 0 else 1 for p in entries)
        out.add(s)
        if negate:
            out.add(tuple(-v for v in s))
    return out


def _condition(cs: ConditionSet, box: Box, j: int, row: list, s: tuple[int, ...]) -> Condition | None:
    """c_{j,s} = a (w_j D - s . v_j) D, exactly the general route's condition of its vertex and facet."""
    w = fmpq_of((box.hi[j] - box.lo[j]) / 2)
    q = cs.D * w
    for sign, p in zip(s, row):
        q = q - p if sign > 0 else q + p
    facet, a = (box.upper[j], box.scale_upper[j]) if s[0] > 0 else (box.lower[j], box.scale_lower[j])
    c = q * cs.D * fmpq_of(a)
    if never_binds(c.coeffs()):
        return None
    return Condition(Kind.VERTEX, vertex_index(tuple(s[0] * x for x in s[1:])), facet, c)


def box_route(cs: ConditionSet) -> tuple[list[Condition], BoxRoute] | None:
    """(conditions, statistics) of the box route, or None if P is not a box; computed
    once per :class:`ConditionSet`.  The conditions' valid set is exactly that of all
    vertex-facet pairs (module docstring).

    x' = -x on [0, 2] (c = 1, w = 1), forward Euler: v_0 = (1 - h) - 1 = -h, v_1 = 1 - h;
    the pattern (-1, 1) on (0, 1) gives q = 1 - (h + 1 - h) = 0 (vertex 0 stays at 0:
    skipped), (-1, -1) on (1, oo) gives 2 - 2h >= 0: vertex 2 (index 1), facet -x <= 0 (row 1).

    >>> import exactinv as ei
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron.box([0], [2]), ei.methods.forward_euler())
    >>> conditions, stats = box_route(cs)
    >>> [(c.generator, c.facet, c.poly) for c in conditions], stats.entries
    ([(1, 1, (Fraction(2, 1), Fraction(-2, 1)))], 2)
    """
    if box_route not in cs.derived:  # keyed by this function, not by a name
        box = detect_box(cs.polyhedron.G, cs.polyhedron.b)
        cs.derived[box_route] = None if box is None else _build(cs, box)
    return cs.derived[box_route]  # type: ignore[return-value]


def _build(cs: ConditionSet, box: Box) -> tuple[list[Condition], BoxRoute]:
    t0 = time.perf_counter()
    rows = _entry_polynomials(cs, box)
    t1 = time.perf_counter()
    negate = sign_variations(cs.D.coeffs()) > 0  # D may be negative somewhere on (0, oo)
    patterns = [sorted(_patterns(row, negate)) for row in rows]
    t2 = time.perf_counter()
    out = [c for j, row in enumerate(rows) for s in patterns[j] if (c := _condition(cs, box, j, row, s)) is not None]
    t3 = time.perf_counter()
    stages = (("entry polynomials", t1 - t0), ("roots and patterns", t2 - t1), ("conditions", t3 - t2))
    return out, BoxRoute(box, sum(len(r) for r in rows), sum(len(p) for p in patterns), len(out), stages)

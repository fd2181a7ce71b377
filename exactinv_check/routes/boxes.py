"""Valid sets on a box without its 2^n vertices: the conditions of a ``box`` claim.

A claim with ``"box": {"lo": [...], "hi": [...]}`` (instead of generator lists)
says that P = {Gx <= b} is the box {lo <= x <= hi} and that its conditions come
from the box route.  The kernel trusts none of it:

(a) :func:`prove_box`: every row of G has exactly one nonzero entry a, so it
    reads x_l <= b/a (a > 0) or x_l >= b/a (a < 0); the intersection of the
    rows is, coordinate by coordinate, [max of the lower bounds, min of the
    upper bounds] -- exactly the box, once every coordinate has both and
    lo < hi.  The first row attaining a bound is its facet; the other rows are
    implied by P itself, so their conditions change nothing.  The claim's lo
    and hi must equal what the kernel derived.
(b) with c = (lo + hi)/2, w = (hi - lo)/2 > 0 and D, N = D r(hA) rebuilt
    (:func:`exactinv_check.conditions.method_matrices`), row j's n + 1 entry
    polynomials are v_j0 = (N c)_j - D c_j and v_jl = N_jl w_l.
(c) every positive root of every entry is isolated (Descartes), the roots of a row
    are merged in exact order, a rational sample is taken in each open cell
    between consecutive roots (and right of the last), and the sign pattern
    s (s_l = sign v_jl(sample); +1 for an identically zero entry) is recorded;
    if D has a sign variation (it may be negative somewhere on (0, oo)), -s too.
(d) each pattern s is the vertex u = s_0 (s_1, .., s_n) (x = c + W u; its index
    in the sorted vertex list has bit n-1-l set iff u_l = +1) with the facet of
    hi_j (s_0 = +1) or lo_j (s_0 = -1), row k with G_kj = +-a; its condition
        a (w_j D - s . v_j) D = (b_k D - g_k N x) D >= 0
    is exactly that vertex-facet condition.  The valid set (or first end) of
    these conditions is recomputed by :mod:`exactinv_check.validset`.
Pricing: the rebuild of D, N and the conditions against the work budget before
it starts; the root isolation of the entries, then of the conditions, by
Descartes' rule with bisection, each node charged to the certificate's account
as it runs (at least one node per polynomial is priced before any starts).

Why these conditions give the valid set of all 2n 2^n vertex-facet pairs.
Each is one of those pairs, so the set V_S they cut out contains the true
valid set V.  Conversely let h >= 0 be in V_S (so D(h) != 0).  A_d(h) maps the
box into itself iff, for every row j, |v_j0(h)| + sum_l |v_jl(h)| <= w_j |D(h)|
(write x = c + W u, |u|_oo <= 1: the extreme values of row j of D A_d x are
attained at the vertices), i.e. iff q_s(h) = w_j D(h) - s . v_j(h) has the sign
of D(h) for EVERY s in {-1, 1}^(n+1).  If D(h) > 0 the smallest q_s(h) is at
any s with s_l = sign v_jl(h) wherever v_jl(h) != 0: the pattern of the cell
containing h is such an s, and so is the pattern of either cell next to h when
h is a root (an entry nonzero at h keeps its sign nearby; for h = 0 the cell
right of 0).  If D(h) < 0 the largest q_s(h) is at -s, also recorded.  So
every condition holds at h, and V_S = V: the recomputed set is exact.
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd
from typing import Any, Sequence

from .. import poly_arithmetic, polys
from ..budget import affordable, descartes_node_cost, within_budget
from ..conditions import method_matrices, rebuild_size
from ..failure import require, require_budget
from ..rationals import vector
from ..reals import Real, separate
from ..validset import breakpoints


def prove_box(G: Sequence[list[Fraction]], b: Sequence[Fraction]) -> Any:
    """(lo, hi, facets): P = {Gx <= b} is exactly the box [lo, hi] (see (a));
    facets[l] = ((row, |a|) of hi_l, (row, |a|) of lo_l) (|a| > 0 scales a condition, no sign).  Rejects anything else."""
    n = len(G[0])
    best: dict[Any, Any] = {}
    for k, (row, beta) in enumerate(zip(G, b)):
        support = [l for l, x in enumerate(row) if x != 0]
        require(len(support) == 1, f"row {k} of G has {len(support)} nonzero entries: P is not given as a box")
        l = support[0]
        a = row[l]
        bound, upper = beta / a, a > 0
        old = best.get((l, upper))
        if old is None or (bound < old[0] if upper else bound > old[0]):
            best[l, upper] = (bound, k, abs(a))
    for l in range(n):
        require((l, True) in best and (l, False) in best, f"coordinate {l} is not bounded both ways: P is no box")
        require(best[l, False][0] < best[l, True][0], f"coordinate {l}: lo >= hi, P is no full-dimensional box")
    lo = [best[l, False][0] for l in range(n)]
    hi = [best[l, True][0] for l in range(n)]
    return lo, hi, [(best[l, True][1:], best[l, False][1:]) for l in range(n)]


def vertex_of(index: int, lo: Sequence[int | Fraction], hi: Sequence[int | Fraction]) -> list[int | Fraction]:
    """The box vertex of that index in the sorted vertex list: hi_l where bit n-1-l is set."""
    n = len(lo)
    return [hi[l] if index >> (n - 1 - l) & 1 else lo[l] for l in range(n)]


def _price(A: Sequence[list[Fraction]], numerator: Sequence[Fraction], denominator: Sequence[Fraction]) -> None:
    """Reject, before any work, a rebuild of D, N and the conditions over the kernel's work budget:
    the rebuild as priced by :func:`exactinv_check.conditions.rebuild_size`, then about 2 n^3 d^2 w
    word operations for the conditions (n rows, up to (n + 1) d + 1 sign patterns each, n + 1
    entries of degree d; twice that with a sign-changing D)."""
    n = len(A)
    cost, d, w = rebuild_size(A, numerator, denominator)
    cost += 2 * n ** 3 * (d + 1) ** 2 * w * (2 if len(denominator) > 1 else 1)
    within_budget(cost, f"the box route of a {n} x {n} problem with entries of degree {d}")


def _price_roots(polynomials: Any, what: str) -> None:
    """Reject, before any root isolation, polynomials whose isolation cannot fit in what is left of the
    certificate's account: at least one Descartes node (a Moebius transform, O(d^2) additions) per
    polynomial with a sign variation.  The isolation itself (Descartes' rule with bisection, no Sturm
    sequence) is then charged node by node as it runs (:func:`exactinv_check.polys.isolate`)."""
    least = 0
    for p in {tuple(p) for p in polynomials if len(p) > 1}:
        ints = poly_arithmetic.integer_coefficients(list(p))
        if len({c > 0 for c in ints if c}) > 1:  # no sign variation: no positive root, no isolation (Descartes)
            least += descartes_node_cost(len(ints) - 1, max(abs(c).bit_length() for c in ints))
    require_budget(affordable(least), f"over the certificate's work budget: root isolation of {what} "
            f"(at least {least:.1e} word operations, more than the certificate has left)")


def _entries(D: Sequence[Fraction], N: Sequence[list[list[Any]]], lo: Sequence[Fraction],
             hi: Sequence[Fraction]) -> tuple[list[list[Any]], list[Fraction]]:
    """rows[j] = [v_j0, v_j1, .., v_jn] (see (b)) and the half-widths w."""
    n = len(lo)
    c = [(a + b) / 2 for a, b in zip(lo, hi)]
    w = [(b - a) / 2 for a, b in zip(lo, hi)]
    rows = []
    for j in range(n):
        v0 = poly_arithmetic.sub([sum(Nk[j][l] * c[l] for l in range(n)) for Nk in N], [d * c[j] for d in D])
        rows.append([v0] + [poly_arithmetic.trim([Nk[j][l] * w[l] for Nk in N]) for l in range(n)])
    return rows, w


def _samples(row: Sequence[list[Fraction]]) -> list[Fraction]:
    """A rational in every open cell of (0, oo) cut by the positive roots of the row's entries."""
    distinct = {tuple(p): p for p in row if len(p) > 1}
    points = [Real.rational(0)] + [real for real, _ in breakpoints(list(distinct.items()), {})]
    out = []
    for a, b in zip(points, points[1:]):
        a1, b0 = separate(a, b)
        out.append((a1 + b0) / 2)
    return out + [points[-1].bounds()[1] + 1]


def _patterns(row: Sequence[list[Fraction]], negate: bool) -> Any:
    """The sign patterns of the row at its cell samples (and their negations)."""
    out = set()
    ints = [poly_arithmetic.integer_coefficients(p) for p in row]  # positive multiples: the same signs
    for t in _samples(row):
        s = tuple(-1 if polys.sign_at(q, t) < 0 else 1 for q in ints)
        out.add(s)
        if negate:
            out.add(tuple(-x for x in s))
    return out


def _integer_row(row: Sequence[list[Fraction]]) -> tuple[int, list[list[Any]]]:
    """(L, [L p for p in row]) with L > 0 clearing every denominator, each padded to one length."""
    L, width = 1, max(len(p) for p in row)
    for p in row:
        for x in p:
            L = L * x.denominator // gcd(L, x.denominator)
    return L, [[int(x * L) for x in p] + [0] * (width - len(p)) for p in row]


def box_conditions(A: Any, G: Any, b: Any, numerator: Any, denominator: Any, claimed: Any) -> Any:
    """(D, inequalities, box): the conditions of (d), keyed like
    :func:`exactinv_check.conditions.condition_polynomials` to (kind, vertex index, facet),
    after proving P is the claimed box; box = (lo, hi)."""
    lo, hi, facets = prove_box(G, b)
    n = len(lo)
    require(isinstance(claimed, dict) and set(claimed) == {"lo", "hi"}, "box has the keys lo, hi")
    require(vector(claimed["lo"], "box lo", n) == lo and vector(claimed["hi"], "box hi", n) == hi,
            f"the box is [{[str(x) for x in lo]}, {[str(x) for x in hi]}], not the claimed one")
    _price(A, numerator, denominator)
    D, N = method_matrices(A, numerator, denominator)
    rows, w = _entries(D, N, lo, hi)
    _price_roots([p for row in rows for p in row], "the box route's entry polynomials")
    negate = not all(c >= 0 for c in D) and not all(c <= 0 for c in D)  # D may change sign on (0, oo)
    D_int = poly_arithmetic.integer_coefficients(D)  # a positive multiple of D: the same signs
    inequalities: dict[Any, Any] = {}
    for j, row in enumerate(rows):
        scale, ints = _integer_row([poly_arithmetic.scale(D, w[j])] + row)  # scale * (w_j D, v_j0, .., v_jn), scale > 0
        for s in sorted(_patterns(row, negate)):
            q = list(ints[0])
            for sign, p in zip(s, ints[1:]):
                for k, x in enumerate(p):
                    q[k] -= sign * x
            # a positive multiple of (w_j D - s.v_j) D
            c = poly_arithmetic.trim(poly_arithmetic.mul_integers(q, D_int) if len(D_int) > 1 else q)
            if c:
                facet = facets[j][0 if s[0] > 0 else 1][0]
                index = int("".join("1" if s[0] * x > 0 else "0" for x in s[1:]), 2)
                inequalities.setdefault(tuple(poly_arithmetic.integer_coefficients(c)), ("vertex", index, facet))
    _price_roots(inequalities, "the box route's conditions")
    return D, inequalities, (lo, hi)

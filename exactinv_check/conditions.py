"""The exact conditions of "A_d(h) P is a subset of P" as polynomials in h.

For a method r = g/h_r and x' = Ax, let D(h) = det h_r(hA) and
N(h) = D(h) r(hA) = sum_k h^k N_k, a polynomial matrix (for a polynomial
method D = 1 and N_k = sigma_k A^k).  With the proved generators of P
(vertices v, rays r, lines l) and facets (g_j, b_j):

    vertex v, facet j:  (b_j D(h) - g_j N(h) v) D(h) >= 0
    ray r, facet j:     -(g_j N(h) r) D(h) >= 0
    line l, facet j:    g_j N(h) l = 0

Where D(h) != 0 these say exactly A_d(h) v in P, A_d(h) r in rec(P),
A_d(h) l in lin(P) (multiplying by D(h)^2 > 0 keeps the sign); where
D(h) = 0, r(hA) does not exist and h is not a valid steplength.
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd
from typing import Any, Iterator, Sequence

from . import budget, poly_arithmetic
from .budget import MAX_CONDITIONS, charge, condition_cost, within_budget
from .failure import require
from .linalg import integer_solve
from .rationals import integer_matrix


def rebuild_size(A: Sequence[list[Fraction]], numerator: Sequence[Fraction],
                 denominator: Sequence[Fraction]) -> tuple[int, int, int]:
    """(cost, d, w) of rebuilding D and N (:func:`method_matrices`): d = deg N (and so of D up to n deg h_r),
    w the words of an entry, cost in word operations.  With A = Ai / L (Ai integral, entries of b bits):
    polynomial methods n^3 deg g products of numbers of about k b bits (the powers Ai^k) and the
    method's coefficients over their common denominator (mb bits, at most the sum of theirs); rational ones
    one fraction-free elimination of about n^3 w^2 per interpolation point (the minors of c h_r(tA) have
    about n (s b + s log t) bits) and n^2 count^2 w for the interpolation."""
    n = len(A)
    L, Ai = integer_matrix(A)
    b = max([abs(x).bit_length() for row in Ai for x in row] + [L.bit_length(), 1])
    dh, dg = len(denominator) - 1, len(numerator) - 1
    # the method's coefficients over a common denominator (at most the product of theirs)
    mb = max(sum(c.denominator.bit_length() for c in p) + max(abs(c.numerator).bit_length() for c in p)
             for p in (numerator, denominator))
    if dh == 0:
        w = 1 + (dg * b + mb) // 64
        return n ** 3 * dg * w, dg, w
    s, d = max(dg, dh), max(n * dh, (n - 1) * dh + dg)
    count = d + 1
    w = 1 + n * (s * (b + (count + n * dh).bit_length()) + mb) // 64
    return (count + n * dh) * n ** 3 * w * w + n * n * count * count * w, d, w


def _integer_powers(Ai: Sequence[list[int]], top: int) -> list[list[list[Any]]]:
    """[Ai^0, .., Ai^top] for an integer matrix Ai, products over Z."""
    n = len(Ai)
    columns = list(zip(*Ai))
    out = [[[int(i == j) for j in range(n)] for i in range(n)]]
    for _ in range(top):
        out.append([[sum(map(int.__mul__, row, col)) for col in columns] for row in out[-1]])
    return out


def method_matrices(A: Any, numerator: Any, denominator: Any) -> Any:
    """(D, [N_0, N_1, ...]): D(h) = det h_r(hA), N(h) = D(h) r(hA) = sum_k h^k N_k.

    Integers throughout: A = Ai / L (Ai integral); with c = den L^s (den clearing the
    coefficients of g and h_r, s = max(deg g, deg h_r)), c h_r(tA) and c g(tA) are integer
    matrices at integer t, so D(t) c^n and N(t) c^n = adj(c h_r(tA)) c g(tA) come from one
    fraction-free elimination (linalg.integer_solve) per point; polynomial methods need
    only the powers of Ai.  Priced first (:func:`rebuild_size`): over the work budget, nothing runs."""
    within_budget(rebuild_size(A, numerator, denominator)[0], f"D(h) and N(h) of a {len(A)} x {len(A)} problem")
    n = len(A)
    L, Ai = integer_matrix(A)
    if len(denominator) == 1:
        d0 = denominator[0]
        powers = _integer_powers(Ai, len(numerator) - 1)
        return [Fraction(1)], [[[s / d0 / L**k * v if v else Fraction(0) for v in row] for row in powers[k]]
                               for k, s in enumerate(numerator)]
    dh, dg = len(denominator) - 1, len(numerator) - 1
    s = max(dh, dg)
    den = _common_denominator(list(numerator) + list(denominator))
    hs = [int(x * den) * L ** (s - k) for k, x in enumerate(denominator)]
    gs = [int(x * den) * L ** (s - k) for k, x in enumerate(numerator)]
    powers = _integer_powers(Ai, s)
    count = max(n * dh, (n - 1) * dh + dg) + 1
    points: list[Any] = []
    dets: list[Any] = []
    mats: list[Any] = []
    for t in range(count + n * dh + 1):  # at most n*dh points are singular
        if len(points) == count:
            break
        Hi, Gi = (_combination(coeffs, powers, t) for coeffs in (hs, gs))
        d, X = integer_solve(Hi, Gi)
        if d != 0:
            points.append(t)
            dets.append(d)
            mats.append(X)
    require(len(points) == count, "internal: too few regular interpolation points")
    scale = Fraction(1, (den * L**s) ** n)  # 1 / c^n
    basis, delta = _lagrange_basis(points)
    D = poly_arithmetic.trim([Fraction(x, delta) * scale for x in _interpolate_integers(basis, dets)])
    entries = [[_interpolate_integers(basis, [X[i][j] for X in mats]) for j in range(n)] for i in range(n)]  # type: ignore[index]
    degree = max([len(poly_arithmetic.trim(e)) for row in entries for e in row] + [1])
    N = [[[Fraction(e[k], delta) * scale if e[k] else Fraction(0) for e in row] for row in entries] for k in range(degree)]
    return D, N


def method_matrix_at(A: Any, numerator: Any, denominator: Any, dt: Any) -> Any:
    """r(dt A) at one rational dt >= 0, or None where h_r(dt A) is singular: one fraction-free solve
    h_r(dt A) X = g(dt A) over the integers (with dt A = p Ai / (q L), both sides scaled by
    den (q L)^s), priced first like one interpolation point of :func:`method_matrices`."""
    n = len(A)
    L, Ai = integer_matrix(A)
    p, q = dt.numerator, dt.denominator
    s = max(len(numerator), len(denominator)) - 1
    b = max([abs(x).bit_length() for row in Ai for x in row] + [L.bit_length(), p.bit_length(), q.bit_length(), 1])
    w = 1 + n * s * 2 * b // 64
    within_budget(n ** 3 * w * w + s * n ** 3 * w, f"r(dt A) for a {n} x {n} matrix A at dt = a {b}-bit rational")
    den = _common_denominator(list(numerator) + list(denominator))
    powers = _integer_powers(Ai, s)
    def scaled(coeffs: Sequence[Fraction]) -> Any:
        return [int(x * den) * p ** k * (q * L) ** (s - k) for k, x in enumerate(coeffs)]

    Hi, Gi = (_combination(scaled(c), powers, 1) for c in (denominator, numerator))
    d, X = integer_solve(Hi, Gi)
    return None if d == 0 else [[Fraction(x, d) for x in row] for row in X]  # type: ignore[union-attr]


def _combination(coeffs: Sequence[int], powers: Sequence[list[list[Any]]], t: int) -> list[list[int]]:
    """sum_k coeffs[k] t^k powers[k], an integer matrix."""
    n = len(powers[0])
    out = [[0] * n for _ in range(n)]
    for k, c in enumerate(coeffs):
        if c:
            f = c * t**k
            out = [[x + f * p for x, p in zip(row, prow)] for row, prow in zip(out, powers[k])]
    return out


def _lagrange_basis(points: Sequence[int]) -> tuple[list[list[Any]], int]:
    """(basis, delta): integer polynomials with delta * l_i = basis[i] for the Lagrange basis l_i
    of the integer points (delta > 0), so p = sum_i p(t_i) l_i = (sum_i p(t_i) basis[i]) / delta."""
    numerators, denominators = [], []
    for i, t in enumerate(points):
        poly, d = [1], 1
        for j, u in enumerate(points):
            if j != i:
                poly = [(poly[m - 1] if m else 0) - u * (poly[m] if m < len(poly) else 0) for m in range(len(poly) + 1)]
                d *= t - u
        numerators.append(poly)
        denominators.append(d)
    delta = 1
    for d in denominators:
        delta = delta * abs(d) // gcd(delta, abs(d))
    return [[c * (delta // d) for c in poly] for poly, d in zip(numerators, denominators)], delta


def _interpolate_integers(basis: Sequence[list[int]], values: Sequence[int]) -> Any:
    """sum_i values[i] basis[i], coefficient by coefficient (integers)."""
    out = [0] * len(basis[0])
    for v, b in zip(values, basis):
        if v:
            for m, c in enumerate(b):
                out[m] += v * c
    return out


def _common_denominator(values: Sequence[Fraction] | Iterator[Any]) -> int:
    d = 1
    for x in values:
        d = d * x.denominator // gcd(d, x.denominator)
    return d


def condition_polynomials(A: Any, G: Any, b: Any, numerator: Any, denominator: Any, generators: Any,
                          facets_of: Any = None, without_D: Any = None) -> Any:
    """(D, inequalities, equalities): the distinct nonzero condition polynomials
    (each inequality must be >= 0, each equality = 0), as tuples of coprime
    integers (a positive multiple of the condition, so with its signs), keyed to
    where they come from ((kind, index, facet) of one generator-facet pair).
    ``facets_of(kind, index)``, if given, names the facets to build for that
    generator (None: all of them).  ``without_D(kind, index)``, if given and true,
    builds q instead of c = q D for that generator: the caller has proved D > 0 on
    the range where the sign of that condition matters.  The conditions' degree
    2 deg N is bounded before anything is built."""
    degree = 2 * rebuild_size(A, numerator, denominator)[1]
    require(degree <= budget.MAX_DEGREE, f"the conditions have degree {degree}, over the kernel's bound {budget.MAX_DEGREE}")
    D, N = method_matrices(A, numerator, denominator)
    m = len(G)
    facet_lists = {}
    for kind, vectors in (("vertex", generators.vertices), ("ray", generators.rays), ("line", generators.lines)):
        for index in range(len(vectors)):
            chosen = None if facets_of is None else facets_of(kind, index)
            facet_lists[kind, index] = range(m) if chosen is None else chosen
    pairs = sum(len(f) for f in facet_lists.values())
    require(pairs <= MAX_CONDITIONS, f"{pairs} generator-facet conditions exceed the kernel's bound")
    # integers throughout: row j of G N_k = GN_int[k][j] / L[j] (L[j] = the denominators of g_j and of N),
    # D = D_int / dD, w = w_int / d_w, b_j = bn_j / bd_j; each condition is a positive multiple of its own
    dN = _common_denominator(x for Nk in N for row in Nk for x in row)
    N_int = [[[int(x * dN) for x in row] for row in Nk] for Nk in N]
    L, GN_rows = [], []
    for g in G:
        dg = _common_denominator(g)
        g_int = [int(x * dg) for x in g]
        L.append(dg * dN)
        GN_rows.append([[sum(a * Nk[l][c] for l, a in enumerate(g_int) if a) for c in range(len(g))] for Nk in N_int])
    GN_int = [[GN_rows[j][k] for j in range(m)] for k in range(len(N))]  # L[j] * g_j N_k
    dD = _common_denominator(D)
    D_int = [int(c * dD) for c in D]
    inequalities: dict[Any, Any] = {}
    equalities: dict[Any, Any] = {}
    each = condition_cost(len(GN_int), len(G[0]) if G else 0, len(D_int))
    for kind, vectors in (("vertex", generators.vertices), ("ray", generators.rays), ("line", generators.lines)):
        for index, w in enumerate(vectors):
            charge(each * len(facet_lists[kind, index]), "the generator-facet conditions")
            dw = _common_denominator(w)
            w_int = [int(x * dw) for x in w]
            for j in facet_lists[kind, index]:
                e = poly_arithmetic.trim([sum(a * x for a, x in zip(M[j], w_int)) for M in GN_int])  # L[j] dw (g_j N(h) w)
                if kind == "line":
                    if e:
                        equalities.setdefault(tuple(poly_arithmetic.integer_coefficients(e)), (kind, index, j))
                    continue
                if kind == "vertex":  # (b_j D - g_j N v) times the positive L[j] dw dD bd_j
                    bn, bd = b[j].numerator, b[j].denominator
                    width = max(len(D_int), len(e))
                    q = [bn * L[j] * dw * (D_int[i] if i < len(D_int) else 0) - dD * bd * (e[i] if i < len(e) else 0)
                         for i in range(width)]
                else:
                    q = [-c for c in e]
                plain = len(D_int) == 1 or (without_D is not None and without_D(kind, index))
                c = poly_arithmetic.trim(q if plain else poly_arithmetic.mul_integers(q, D_int))
                if c:
                    inequalities.setdefault(tuple(poly_arithmetic.integer_coefficients(c)), (kind, index, j))
    return D, inequalities, equalities

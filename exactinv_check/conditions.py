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

from fractions import Fraction
from math import gcd

from . import polys
from .rationals import determinant, integer_matrix, matmul, require, solve

MAX_CONDITIONS = 20_000_000


def _matrix_polynomial(coeffs, M):
    """sum_k coeffs[k] M^k (Horner)."""
    n = len(M)
    out = [[Fraction(0)] * n for _ in range(n)]
    for c in reversed(coeffs):
        out = matmul(out, M)
        for i in range(n):
            out[i][i] += c
    return out


def method_matrices(A, numerator, denominator):
    """(D, [N_0, N_1, ...]): D(h) = det h_r(hA), N(h) = D(h) r(hA) = sum_k h^k N_k."""
    n = len(A)
    if len(denominator) == 1:  # A = Ai / L with Ai integral: A^k = Ai^k / L^k, products over Z
        d0 = denominator[0]
        L, Ai = integer_matrix(A)
        columns = list(zip(*Ai))
        power, out = [[int(i == j) for j in range(n)] for i in range(n)], []
        for k, s in enumerate(numerator):
            factor = s / d0 / L**k
            out.append([[factor * v if v else Fraction(0) for v in row] for row in power])
            if k + 1 < len(numerator):
                power = [[sum(map(int.__mul__, row, col)) for col in columns] for row in power]
        return [Fraction(1)], out
    dh, dg = len(denominator) - 1, len(numerator) - 1
    count = max(n * dh, (n - 1) * dh + dg) + 1
    points, dets, mats = [], [], []
    t = Fraction(0)
    for _ in range(count + n * dh + 1):  # at most n*dh points are singular
        if len(points) == count:
            break
        tA = [[t * a for a in row] for row in A]
        H = _matrix_polynomial(denominator, tA)
        d = determinant(H)
        if d != 0:
            X = solve(H, _matrix_polynomial(numerator, tA))
            points.append(t)
            dets.append(d)
            mats.append([[d * v for v in row] for row in X])
        t += 1
    require(len(points) == count, "internal: too few regular interpolation points")
    D = polys.interpolate(points, dets)
    entries = [[polys.interpolate(points, [X[i][j] for X in mats]) for j in range(n)] for i in range(n)]
    degree = max([len(e) for row in entries for e in row] + [1])
    N = [[[e[k] if k < len(e) else Fraction(0) for e in row] for row in entries] for k in range(degree)]
    return D, N


def _common_denominator(values):
    d = 1
    for x in values:
        d = d * x.denominator // gcd(d, x.denominator)
    return d


def _integer_polynomial_product(p, q):
    out = [0] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        if a:
            for j, c in enumerate(q):
                out[i + j] += a * c
    return out


def condition_polynomials(A, G, b, numerator, denominator, generators, facets_of=None):
    """(D, inequalities, equalities): the distinct nonzero condition polynomials
    (each inequality must be >= 0, each equality = 0), as tuples of coprime
    integers (a positive multiple of the condition, so with its signs), keyed to
    where they come from ((kind, index, facet) of one generator-facet pair).
    ``facets_of(kind, index)``, if given, names the facets to build for that
    generator (None: all of them)."""
    D, N = method_matrices(A, numerator, denominator)
    m = len(G)
    facet_lists = {}
    for kind, vectors in (("vertex", generators.vertices), ("ray", generators.rays), ("line", generators.lines)):
        for index in range(len(vectors)):
            chosen = None if facets_of is None else facets_of(kind, index)
            facet_lists[kind, index] = range(m) if chosen is None else chosen
    pairs = sum(len(f) for f in facet_lists.values())
    require(pairs <= MAX_CONDITIONS, f"{pairs} generator-facet conditions exceed the kernel's bound")
    # integers throughout: G N_k = GN_k / d_k, D = D_int / dD, w = w_int / d_w, b_j = bn_j / bd_j
    GN = [matmul(G, Nk) for Nk in N]
    dk = [_common_denominator(x for row in M for x in row) for M in GN]
    L = 1
    for d in dk:
        L = L * d // gcd(L, d)
    GN_int = [[[int(x * d) * (L // d) for x in row] for row in M] for M, d in zip(GN, dk)]  # L * G N_k
    dD = _common_denominator(D)
    D_int = [int(c * dD) for c in D]
    inequalities, equalities = {}, {}
    for kind, vectors in (("vertex", generators.vertices), ("ray", generators.rays), ("line", generators.lines)):
        for index, w in enumerate(vectors):
            dw = _common_denominator(w)
            w_int = [int(x * dw) for x in w]
            for j in facet_lists[kind, index]:
                e = polys.trim([sum(a * x for a, x in zip(M[j], w_int)) for M in GN_int])  # L dw (g_j N(h) w)
                if kind == "line":
                    if e:
                        equalities.setdefault(tuple(polys.integer_coefficients(e)), (kind, index, j))
                    continue
                if kind == "vertex":  # (b_j D - g_j N v) times the positive L dw dD bd_j
                    bn, bd = b[j].numerator, b[j].denominator
                    width = max(len(D_int), len(e))
                    q = [bn * L * dw * (D_int[i] if i < len(D_int) else 0) - dD * bd * (e[i] if i < len(e) else 0)
                         for i in range(width)]
                else:
                    q = [-c for c in e]
                c = polys.trim(_integer_polynomial_product(q, D_int) if len(D_int) > 1 else q)
                if c:
                    inequalities.setdefault(tuple(polys.integer_coefficients(c)), (kind, index, j))
    return D, inequalities, equalities

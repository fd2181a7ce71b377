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

from . import polys
from .rationals import determinant, identity, matmul, require, solve

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
    if len(denominator) == 1:
        d0 = denominator[0]
        power, out = identity(n), []
        for s in numerator:
            out.append([[s / d0 * v for v in row] for row in power])
            power = matmul(power, A)
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


def condition_polynomials(A, G, b, numerator, denominator, generators):
    """(D, inequalities, equalities): the distinct nonzero condition polynomials
    (each inequality must be >= 0, each equality = 0), keyed by where they come
    from ((kind, index, facet) of one generator-facet pair producing it)."""
    D, N = method_matrices(A, numerator, denominator)
    m = len(G)
    pairs = m * (len(generators.vertices) + len(generators.rays) + len(generators.lines))
    require(pairs <= MAX_CONDITIONS, f"{pairs} generator-facet conditions exceed the kernel's bound")
    GN = [matmul(G, Nk) for Nk in N]  # m x n per power of h
    inequalities, equalities = {}, {}
    for kind, vectors in (("vertex", generators.vertices), ("ray", generators.rays), ("line", generators.lines)):
        for index, w in enumerate(vectors):
            images = [[sum(a * x for a, x in zip(row, w)) for row in GNk] for GNk in GN]  # per k: m values
            for j in range(m):
                e = polys.trim([images[k][j] for k in range(len(GN))])
                if kind == "line":
                    if e:
                        equalities.setdefault(tuple(polys.primitive(e)), (kind, index, j))
                    continue
                q = polys.sub(polys.scale(D, b[j]), e) if kind == "vertex" else [-c for c in e]
                c = polys.mul(q, D)
                if c:
                    inequalities.setdefault(tuple(polys.primitive(c)), (kind, index, j))
    return D, inequalities, equalities

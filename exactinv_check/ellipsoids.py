"""Ellipsoids E = {x : x^T Q x <= 1}: exact semidefiniteness and the
coefficient polynomials of "A_d(h) E is a subset of E".

* psd(M): symmetric Gaussian elimination on positive diagonal pivots; a
  negative diagonal entry, or a zero diagonal beside a nonzero entry, refutes.
  M >= 0 iff the elimination ends with a zero remainder.
* For r = g/h_r, G(h) = g(hA), H(h) = h_r(hA): where H(h) is invertible,
  Q - A_d^T Q A_d >= 0 iff M(h) = H^T Q H - G^T Q G >= 0 (congruence by H).
  g(0) = h_r(0) gives M(0) = 0, so M(h) = h M'(h).  A symmetric matrix is PSD
  iff every e_k (sum of k x k principal minors, (-1)^k times a coefficient of
  its characteristic polynomial) is >= 0.  The conditions are
  c_k(h) = h e_k(M'(h)) >= 0 (k = 1..n): for h > 0 the sign of
  e_k(M(h)) = h^k e_k(M'(h)), and 0 at h = 0, where A_d = I is always valid.
  Each c_k is rebuilt by evaluating M'(t) at integer t, characteristic
  polynomials (Hessenberg) and interpolation of each coefficient.
"""

from fractions import Fraction

from . import polys
from .linalg import characteristic_polynomial
from .rationals import determinant, identity, matmul, require, transpose


def quadratic_form(M, v):
    return sum(vi * sum(m * vj for m, vj in zip(row, v)) for vi, row in zip(v, M))


def is_symmetric(M):
    return all(M[i][j] == M[j][i] for i in range(len(M)) for j in range(i))


def psd(M):
    """(is M >= 0, is M > 0) for a symmetric rational M, by exact elimination."""
    S = [list(r) for r in M]
    rest = list(range(len(S)))
    while rest:
        k = next((i for i in rest if S[i][i] > 0), None)
        if k is None:
            zero = all(S[i][j] == 0 for i in rest for j in rest)
            return zero, False
        rest.remove(k)
        d = S[k][k]
        for a in rest:
            f = S[a][k] / d
            if f:
                for b in rest:
                    S[a][b] -= f * S[k][b]
    return True, True


def _scaled(M, c):
    return [[c * v for v in row] for row in M]


def _added(X, Y):
    return [[a + b for a, b in zip(r, s)] for r, s in zip(X, Y)]


def coefficient_matrices(A, Q, numerator, denominator):
    """[M_1, ..., M_2s]: M(h) = sum_j M_j h^j = H^T Q H - G^T Q G (M_0 = 0)."""
    n = len(A)
    s = max(len(numerator), len(denominator)) - 1
    g = list(numerator) + [Fraction(0)] * (s + 1 - len(numerator))
    d = list(denominator) + [Fraction(0)] * (s + 1 - len(denominator))
    powers = [identity(n)]
    for _ in range(s):
        powers.append(matmul(powers[-1], A))
    out = []
    for j in range(1, 2 * s + 1):
        Mj = [[Fraction(0)] * n for _ in range(n)]
        for a in range(max(0, j - s), min(j, s) + 1):
            c = d[a] * d[j - a] - g[a] * g[j - a]
            if c:
                Mj = _added(Mj, _scaled(matmul(matmul(transpose(powers[a]), Q), powers[j - a]), c))
        out.append(Mj)
    return out


def _at(coefficients, t):
    """M'(t) = sum_j M_{j+1} t^j."""
    out = coefficients[-1]
    for Mj in reversed(coefficients[:-1]):
        out = _added(_scaled(out, t), Mj)
    return out


def condition_polynomials(A, Q, numerator, denominator):
    """(D, [c_1, ..., c_n]) with D(h) = det h_r(hA) (module docstring); a c_k that
    vanishes identically is the empty list."""
    n = len(A)
    coefficients = coefficient_matrices(A, Q, numerator, denominator)
    degree = len(coefficients) - 1  # of M'
    count = n * max(degree, len(denominator) - 1) + 1
    require(count - 1 <= polys.MAX_DEGREE, f"n (2s - 1) = {count - 1} exceeds the kernel's degree bound {polys.MAX_DEGREE}")
    points = [Fraction(t) for t in range(count)]
    values = []
    for t in points:
        p = characteristic_polynomial(_at(coefficients, t))  # det(x I - M'(t)), low to high
        values.append([(-1) ** k * p[n - k] for k in range(1, n + 1)])
    conditions = [polys.trim([Fraction(0)] + polys.interpolate(points, [row[k] for row in values])) for k in range(n)]
    D = [Fraction(1)]
    if len(denominator) > 1:
        dets = [determinant(_hA(A, denominator, t)) for t in points]
        D = polys.interpolate(points, dets)
    return D, conditions


def _hA(A, denominator, t):
    n = len(A)
    out = [[Fraction(0)] * n for _ in range(n)]
    for c in reversed(denominator):  # Horner in tA
        out = matmul(out, [[t * a for a in row] for row in A])
        for i in range(n):
            out[i][i] += c
    return out

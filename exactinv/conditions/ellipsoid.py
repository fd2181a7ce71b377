"""The polynomial conditions of A_d(h) E subset of E for an ellipsoid (beyond the paper).

For E = {x : x^T Q x <= 1} (Q > 0) and x+ = A_d x, E is invariant iff
Q - A_d^T Q A_d >= 0 (||A_d x||_Q <= ||x||_Q for all x).  For a method
r = g/h, A_d(h) = H(h)^{-1} G(h) with G(h) = g(hA), H(h) = h(hA) (they
commute); wherever H(h) is invertible the congruence x = H(h) y gives

    Q - A_d^T Q A_d >= 0   iff   M(h) = H(h)^T Q H(h) - G(h)^T Q G(h) >= 0,

a symmetric matrix polynomial in h of degree 2 max(deg g, deg h) -- far lower
than D(h)^2 Q - N(h)^T Q N(h) with D = det H (Sylvester's law of inertia:
congruence keeps semidefiniteness).  A symmetric matrix is PSD iff every
elementary symmetric function e_k of its eigenvalues (the sum of its k x k
principal minors, (-1)^k times a characteristic polynomial coefficient) is
>= 0: if all e_k >= 0 then det(tI + M) = sum_k e_k t^(n-k) > 0 for t > 0, so no
eigenvalue is negative.

Dividing out h: g(0) = h(0) gives M(0) = 0, so M(h) = h M'(h) with M' a matrix
polynomial, and e_k(M(h)) = h^k e_k(M'(h)).  For h > 0 the signs agree, so
the conditions are q_k(h) = e_k(M'(h)) >= 0, k = 1..n (h = 0 is always valid:
A_d(0) = I).  The q_k are computed fraction-free by evaluation: M'(t) at
integer points t, its characteristic polynomial in FLINT, and exact
interpolation of each coefficient (deg q_k <= k (2s - 1)).
"""

from __future__ import annotations

from fractions import Fraction

import flint

from ..core.flintq import fmpq_of
from ..model.methods import Method
from ..model.system import LinearSystem

__all__ = ["step_matrix", "coefficient_matrices", "psd_polynomials"]


def _powers(A: flint.fmpq_mat, s: int) -> list[flint.fmpq_mat]:
    out = [flint.fmpq_mat(A.nrows(), A.ncols(), [int(i == j) for i in range(A.nrows()) for j in range(A.ncols())])]
    for _ in range(s):
        out.append(out[-1] * A)
    return out


def _padded(coeffs, s: int) -> list[flint.fmpq]:
    return [fmpq_of(Fraction(c)) for c in coeffs] + [flint.fmpq(0)] * (s + 1 - len(coeffs))


def coefficient_matrices(system: LinearSystem, Q: flint.fmpq_mat, method: Method) -> list[flint.fmpq_mat]:
    """[M_1, ..., M_2s] with M(h) = sum_j M_j h^j (M_0 = 0):
    M_j = sum_{a+b=j} (d_a d_b - g_a g_b) (A^a)^T Q A^b, exactly.

    >>> from exactinv.model import methods
    >>> M = coefficient_matrices(LinearSystem([[-1]]), flint.fmpq_mat([[1]]), methods.forward_euler())
    >>> [m[0, 0] for m in M]                   # 1 - (1 - h)^2 = 2h - h^2
    [2, -1]
    """
    s = max(len(method.numerator), len(method.denominator)) - 1
    g, d = _padded(method.numerator, s), _padded(method.denominator, s)
    P = _powers(system.A_flint, s)
    T = {}
    for a in range(s + 1):
        left = P[a].transpose() * Q
        for b in range(a, s + 1):
            T[a, b] = left * P[b]
    out = []
    for j in range(1, 2 * s + 1):
        Mj = flint.fmpq_mat(Q.nrows(), Q.ncols())
        for a in range(max(0, j - s), min(j, s) + 1):
            c = d[a] * d[j - a] - g[a] * g[j - a]
            if c:
                Mj += (T[a, j - a] if a <= j - a else T[j - a, a].transpose()) * c
        out.append(Mj)
    return out


def step_matrix(coefficients: list[flint.fmpq_mat], h: Fraction) -> flint.fmpq_mat:
    """M'(h) = M(h)/h = sum_j M_{j+1} h^j, exactly (Horner).

    For forward Euler, A = [[-1, -2], [2, -1]] and Q = I: M'(h) = K - hB with
    K = -(A^T + A) = 2I and B = A^T A = 5I, so M'(1/5) = I.

    >>> from exactinv.model import methods
    >>> S = LinearSystem([[-1, -2], [2, -1]])
    >>> M = coefficient_matrices(S, flint.fmpq_mat([[1, 0], [0, 1]]), methods.forward_euler())
    >>> step_matrix(M, Fraction(1, 5)).entries()
    [1, 0, 0, 1]
    """
    hq = fmpq_of(Fraction(h))
    out = coefficients[-1]
    for Mj in reversed(coefficients[:-1]):
        out = out * hq + Mj
    return out


def _points(count: int) -> list[int]:
    """0, 1, -1, 2, -2, ...: small interpolation nodes."""
    return [(k + 1) // 2 * (1 if k % 2 else -1) for k in range(count)]


def _interpolate(points: list[int], values: list[list[flint.fmpq]]) -> list[flint.fmpq_poly]:
    """For each column of ``values``, the polynomial of degree < len(points) through it
    (one exact Vandermonde solve in FLINT for all columns)."""
    N = len(points)
    V = flint.fmpq_mat(N, N, [flint.fmpq(p) ** e for p in points for e in range(N)])
    Y = flint.fmpq_mat(N, len(values[0]), [v for row in values for v in row])
    C = V.solve(Y)
    return [flint.fmpq_poly([C[e, k] for e in range(N)]) for k in range(Y.ncols())]


def psd_polynomials(system: LinearSystem, Q: flint.fmpq_mat, method: Method) -> tuple[list[flint.fmpq_poly], flint.fmpq_poly]:
    """([q_1, ..., q_n], D): q_k(h) = e_k(M'(h)) (see the module docstring) and
    D(h) = det h(hA) (the constant 1 for polynomial methods).

    r = 1 (s = 0) gives A_d = I and M = 0 for every h: every q_k is the zero
    polynomial (no condition), so every h >= 0 is valid.

    Forward Euler, A = [[-1, -2], [2, -1]], Q = I: M'(h) = (2 - 5h) I, so
    q_1 = trace = 4 - 10h and q_2 = det = (2 - 5h)^2.

    >>> from exactinv.model import methods
    >>> S = LinearSystem([[-1, -2], [2, -1]])
    >>> qs, D = psd_polynomials(S, flint.fmpq_mat([[1, 0], [0, 1]]), methods.forward_euler())
    >>> [q.coeffs() for q in qs], D
    ([[4, -10], [4, -20, 25]], 1)

    Backward Euler on x' = -x, Q = 1: H = 1 + h, G = 1, M(h) = (1 + h)^2 - 1, so
    q_1 = M'(h) = 2 + h and D(h) = 1 + h.

    >>> qs, D = psd_polynomials(LinearSystem([[-1]]), flint.fmpq_mat([[1]]), methods.backward_euler())
    >>> qs[0].coeffs(), D.coeffs()
    ([2, 1], [1, 1])
    """
    coefficients = coefficient_matrices(system, Q, method)
    n, degree = Q.nrows(), len(coefficients) - 1
    if not coefficients:
        return [flint.fmpq_poly([]) for _ in range(n)], flint.fmpq_poly([1])
    points = _points(n * max(degree, len(method.denominator) - 1) + 1)
    rows = []
    for t in points:
        c = step_matrix(coefficients, Fraction(t)).charpoly().coeffs()  # det(x I - M'), low to high
        rows.append([c[n - k] * (-1) ** k for k in range(1, n + 1)])
    if len(method.denominator) > 1:
        A = system.A_flint
        for t, row in zip(points, rows):
            Ht = flint.fmpq_mat(n, n)
            for dk, Ak in zip(method.denominator, _powers(A * t, len(method.denominator) - 1)):
                Ht += Ak * fmpq_of(Fraction(dk))
            row.append(Ht.det())
    polys = _interpolate(points, rows)
    return polys[:n], polys[n] if len(polys) > n else flint.fmpq_poly([1])


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
  Each c_k is rebuilt, up to a positive constant factor, by evaluating
  L M'(t) (L clears denominators) at integer t, characteristic polynomials over
  Z (Berkowitz, division-free) and interpolation of each coefficient.
* Work budgets (budget.within_budget): each elimination and each rebuild
  of the conditions is priced before it runs; over the budget the claim is
  rejected with "over the kernel's work budget", never left to run for minutes.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from . import budget, poly_arithmetic, resultants
from .budget import within_budget
from .failure import require
from .linalg import integer_characteristic_polynomial, integer_determinant
from .rationals import integer_matrix, matmul, transpose


def quadratic_form(M: Any, v: Any) -> Any:
    return sum(vi * sum(m * vj for m, vj in zip(row, v)) for vi, row in zip(v, M))


def is_symmetric(M: Any) -> bool:
    return all(M[i][j] == M[j][i] for i in range(len(M)) for j in range(i))


def psd(M: Any) -> tuple[bool, bool]:
    """(is M >= 0, is M > 0) for a symmetric rational M.

    M is scaled to the integer L M (L > 0: no sign changes), then eliminated
    fraction-free (symmetric Bareiss) on positive diagonal pivots: after the
    pivots K each remaining entry is det (L M)[K + a, K + b], the Schur complement
    entry times the last pivot det (L M)[K, K] > 0, so its sign is the Schur
    complement's.  A remainder with no positive diagonal entry is PSD iff it is
    zero (a negative diagonal, or a zero diagonal beside a nonzero entry,
    refutes).  Over the work budget the kernel rejects before eliminating."""
    _, S = integer_matrix(M)
    n = len(S)
    bits = max((abs(x).bit_length() for row in S for x in row), default=0)
    within_budget(n ** 3 * (1 + n * (bits + n.bit_length()) // 64) // 3,
                  f"exact elimination of a {n} x {n} matrix with {bits}-bit entries")
    rest, last = list(range(n)), 1
    while rest:
        k = next((i for i in rest if S[i][i] > 0), None)
        if k is None:
            return all(S[i][j] == 0 for i in rest for j in rest), False
        rest.remove(k)
        d, pivot_row = S[k][k], S[k]
        for a in rest:
            row, f = S[a], S[a][k]
            for b in rest:
                row[b] = (d * row[b] - f * pivot_row[b]) // last  # exact (Bareiss)
        last = d
    return True, True


def _scaled(M: Any, c: int) -> list[list[int]]:
    return [[c * v for v in row] for row in M]


def _added(X: Sequence[list[int]], Y: Sequence[list[int]]) -> list[list[int]]:
    return [[a + b for a, b in zip(r, s)] for r, s in zip(X, Y)]


def _bits(M: Sequence[list[int]]) -> int:
    return max((abs(x).bit_length() for row in M for x in row), default=0)


def coefficient_matrices(A: Any, Q: Any, numerator: Any, denominator: Any) -> list[list[list[Any]]]:
    """Integer matrices [K_0, ..., K_{2s-1}] with L M'(h) = sum_j K_j h^j for one
    constant L > 0, where M(h) = H^T Q H - G^T Q G = sum_j M_j h^j (M_0 = 0) and
    M'(h) = M(h)/h.  With A = Ai/alpha, Q = Qi/beta and gamma g, gamma h_r integral:
    gamma^2 beta alpha^j M_j = sum_{a+b=j} (gamma^2 (d_a d_b - g_a g_b)) (Ai^a)^T Qi Ai^b,
    so L = gamma^2 beta alpha^(2s) and K_j = alpha^(2s-j-1) (gamma^2 beta alpha^(j+1) M_{j+1}).
    [] for s = 0 (r = 1).  Priced before it runs (integer products only)."""
    n, s = len(A), max(len(numerator), len(denominator)) - 1
    alpha, Ai = integer_matrix(A)
    _, Qi = integer_matrix(Q)
    _, (gi, di) = integer_matrix([list(numerator) + [Fraction(0)] * (s + 1 - len(numerator)),
                                  list(denominator) + [Fraction(0)] * (s + 1 - len(denominator))])
    bits = _bits(Qi) + 2 * s * (_bits(Ai) + n.bit_length()) + _bits([gi, di])
    within_budget((s + 1) ** 2 * n ** 3 * (1 + bits // 64), f"the coefficient matrices of a {n} x {n} problem, s = {s}")
    powers = [[[int(i == j) for j in range(n)] for i in range(n)]]
    for _ in range(s):
        powers.append(matmul(powers[-1], Ai))
    left = [matmul(transpose(P), Qi) for P in powers]
    out = []
    for j in range(1, 2 * s + 1):
        Kj = [[0] * n for _ in range(n)]
        for a in range(max(0, j - s), min(j, s) + 1):
            c = di[a] * di[j - a] - gi[a] * gi[j - a]
            if c:
                Kj = _added(Kj, _scaled(matmul(left[a], powers[j - a]), c))
        out.append(_scaled(Kj, alpha ** (2 * s - j)))
    return out


def _at(coefficients: Sequence[list[list[Any]]], t: int) -> Any:
    """sum_j K_j t^j (Horner)."""
    out = coefficients[-1]
    for Mj in reversed(coefficients[:-1]):
        out = _added(_scaled(out, t), Mj)
    return out


def _conditions_cost(coefficients: Sequence[list[list[Any]]], n: int, count: int) -> int:
    """Estimated word operations of condition_polynomials: Berkowitz (~n^4/4
    products of numbers up to n (bits + log n) bits) at `count` points, and the
    Newton interpolation of n value columns."""
    bits = max(_bits(Kj) for Kj in coefficients) + (len(coefficients) - 1) * count.bit_length() + n.bit_length()
    words = 1 + n * bits // 64
    return count * n ** 4 * words // 4 + (n + 1) * count ** 2 * words + count * n ** 3 * words


def condition_polynomials(A: Any, Q: Any, numerator: Any, denominator: Any) -> Any:
    """(D, [c_1, ..., c_n]) with D(h) = det h_r(hA) and c_k(h) = h e_k(L M'(h)) for
    a constant L > 0 (module docstring; e_k(L M') = L^k e_k(M') has the same signs
    and roots); a c_k that vanishes identically is the empty list.  r = 1 (s = 0)
    has M = 0: every c_k vanishes (every h >= 0 is valid, A_d = I).  The
    characteristic polynomials are Berkowitz's over Z at integer points; over
    the work budget the kernel rejects before evaluating."""
    n = len(A)
    s = max(len(numerator), len(denominator)) - 1
    if s == 0:
        return [Fraction(1)], [[] for _ in range(n)]
    count = n * max(2 * s - 1, len(denominator) - 1) + 1
    require(count - 1 <= budget.MAX_DEGREE, f"n (2s - 1) = {count - 1} exceeds the kernel's degree bound {budget.MAX_DEGREE}")
    coefficients = coefficient_matrices(A, Q, numerator, denominator)
    within_budget(_conditions_cost(coefficients, n, count),
                  f"the characteristic polynomial of a {n} x {n} matrix at {count} points")
    points = list(range(count))
    values = []
    for t in points:
        p = integer_characteristic_polynomial(_at(coefficients, t))  # det(x I - L M'(t)), low to high
        values.append([(-1) ** k * p[n - k] for k in range(1, n + 1)])
    points = [Fraction(t) for t in points]  # type: ignore[misc]
    conditions = [poly_arithmetic.trim([Fraction(0)] + resultants.interpolate(points, [Fraction(row[k]) for row in values]))
                  for k in range(n)]
    D = [Fraction(1)]
    if len(denominator) > 1:
        B = _denominator_matrices(A, denominator)
        D = resultants.interpolate(points, [Fraction(integer_determinant(_at(B, int(t)))) for t in points])
    return D, conditions


def _denominator_matrices(A: Any, denominator: Any) -> Any:
    """Integer matrices B_k with gamma alpha^m h_r(tA) = sum_k B_k t^k (m = deg h_r,
    A = Ai/alpha, gamma h_r integral): D(t) = det of it is det h_r(tA) times the
    positive constant (gamma alpha^m)^n."""
    alpha, Ai = integer_matrix(A)
    _, (di,) = integer_matrix([list(denominator)])
    m, power, out = len(denominator) - 1, [[int(i == j) for j in range(len(A))] for i in range(len(A))], []
    for k in range(m + 1):
        out.append(_scaled(power, di[k] * alpha ** (m - k)))
        power = matmul(power, Ai)
    return out

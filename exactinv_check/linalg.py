"""Characteristic polynomials, the largest real eigenvalue, fraction-free determinants and solves, exactly."""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from . import polys
from .reals import Real


def characteristic_polynomial(M: Sequence[list[Fraction]]) -> list[Fraction]:
    """det(xI - M), low to high: Hessenberg reduction by similarity, then the
    Hessenberg recurrence (O(n^3) rational operations)."""
    n = len(M)
    H = [list(r) for r in M]
    for col in range(n - 2):
        pivot = next((r for r in range(col + 1, n) if H[r][col] != 0), None)
        if pivot is None:
            continue
        if pivot != col + 1:  # swap rows and columns pivot <-> col+1
            H[pivot], H[col + 1] = H[col + 1], H[pivot]
            for row in H:
                row[pivot], row[col + 1] = row[col + 1], row[pivot]
        for r in range(col + 2, n):
            f = H[r][col] / H[col + 1][col]
            if f:
                H[r] = [a - f * c for a, c in zip(H[r], H[col + 1])]  # row_r -= f row_{col+1}
                for row in H:  # column_{col+1} += f column_r
                    row[col + 1] += f * row[r]
    # p_k = det(xI - H[:k,:k]) by the recurrence on the upper Hessenberg matrix
    p = [[Fraction(1)]]
    for k in range(1, n + 1):
        acc = polys.mul([-H[k - 1][k - 1], Fraction(1)], p[k - 1])
        prod = Fraction(1)
        for i in range(1, k):
            prod *= H[k - i][k - i - 1]
            if prod == 0:
                break
            acc = polys.sub(acc, polys.scale(p[k - i - 1], prod * H[k - i - 1][k - 1]))
        p.append(acc)
    return p[n]


def integer_characteristic_polynomial(M: Sequence[list[int]]) -> list[int]:
    """det(xI - M), low to high, for an integer matrix M: Berkowitz's algorithm,
    division-free (integer additions and multiplications only, O(n^4)), so it is
    exact over Z with no fraction and no gcd.  Step k multiplies the characteristic
    polynomial of the leading k x k block by the Toeplitz matrix with first column
    1, -a_kk, -R C, -R B C, ..., -R B^(k-1) C (B the block, R its row, C its column)."""
    p = [1]  # high to low
    for k in range(len(M)):
        row, v = M[k][:k], [M[i][k] for i in range(k)]
        column = [1, -M[k][k]]
        for _ in range(k):
            column.append(-sum(r * x for r, x in zip(row, v)))
            v = [sum(m * x for m, x in zip(M[i][:k], v)) for i in range(k)]
        p = [sum(column[i - j] * p[j] for j in range(max(0, i - k - 1), min(i, k) + 1)) for i in range(k + 2)]
    return p[::-1]


def integer_determinant(M: Sequence[list[int]]) -> Any:
    """det M for an integer matrix M: Bareiss's fraction-free elimination (every
    intermediate entry is a minor of M, so each division is exact)."""
    S, sign, last = [list(r) for r in M], 1, 1
    n = len(S)
    for k in range(n):
        pivot = next((i for i in range(k, n) if S[i][k]), None)
        if pivot is None:
            return 0
        if pivot != k:
            S[k], S[pivot], sign = S[pivot], S[k], -sign
        for i in range(k + 1, n):
            S[i] = [(S[k][k] * S[i][j] - S[i][k] * S[k][j]) // last if j > k else 0 for j in range(n)]
        last = S[k][k]
    return sign * last if n else 1


def integer_solve(M: Sequence[list[int]], B: Sequence[list[int]]) -> tuple[int, list[list[Any]] | None]:
    """(d, X) with d = det M and X = d M^-1 B = adj(M) B, for integer matrices M (square)
    and B: Bareiss's fraction-free elimination on [M | B], then back substitution whose
    divisions are exact (X is integral); (0, None) if M is singular."""
    n = len(M)
    S, sign, last = [list(M[i]) + list(B[i]) for i in range(n)], 1, 1
    width = len(S[0]) if S else 0
    for k in range(n):
        pivot = next((i for i in range(k, n) if S[i][k]), None)
        if pivot is None:
            return 0, None
        if pivot != k:
            S[k], S[pivot], sign = S[pivot], S[k], -sign
        for i in range(k + 1, n):
            a, c = S[k][k], S[i][k]
            S[i] = [0] * (k + 1) + [(a * S[i][j] - c * S[k][j]) // last for j in range(k + 1, width)]
        last = S[k][k]
    d = sign * last if n else 1
    X = [[0] * (width - n) for _ in range(n)]
    for i in range(n - 1, -1, -1):  # U x = c with x = X / last: U_ii X_i = last c_i - sum_{k>i} U_ik X_k
        row = S[i]
        for j in range(width - n):
            acc = last * row[n + j] - sum(row[k] * X[k][j] for k in range(i + 1, n))
            X[i][j] = acc // row[i]
    return d, [[sign * x for x in r] for r in X]


def largest_real_root(p: Any) -> Any:
    """The largest real root of p as a Real, or None if p has none."""
    p = polys.trim(p)
    if len(p) <= 1:
        return None
    bound = polys.cauchy_bound(p)
    shifted = [Fraction(0)] * len(p)  # p(x - bound): its positive roots are p's roots + bound
    for k, c in enumerate(p):  # expand c (x - B)^k
        binom = 1
        for i in range(k + 1):
            shifted[i] += c * binom * (-bound) ** (k - i)
            binom = binom * (k - i) // (i + 1)
    roots = polys.positive_roots(shifted)
    if not roots:
        return None
    lo, hi = roots[-1]
    if lo == hi:
        return Real.rational(lo - bound)
    return Real.algebraic(p, lo - bound, hi - bound, "largest eigenvalue")

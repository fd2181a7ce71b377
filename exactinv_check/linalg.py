"""Characteristic polynomials and the largest real eigenvalue, exactly."""

from fractions import Fraction

from . import polys
from .reals import Real


def characteristic_polynomial(M):
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


def largest_real_root(p):
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

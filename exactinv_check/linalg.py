"""Characteristic polynomials, the largest real eigenvalue, fraction-free determinants and solves, exactly."""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from . import poly_arithmetic, polys
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
        acc = poly_arithmetic.mul([-H[k - 1][k - 1], Fraction(1)], p[k - 1])
        prod = Fraction(1)
        for i in range(1, k):
            prod *= H[k - i][k - i - 1]
            if prod == 0:
                break
            acc = poly_arithmetic.sub(acc, poly_arithmetic.scale(p[k - i - 1], prod * H[k - i - 1][k - 1]))
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
    """The largest real root of p as a Real, or None if p has none.

    Isolated on each side of 0 without shifting p: the positive roots of p's squarefree part
    decide if there is one; else 0 if p(0) = 0; else the negative root nearest 0 is -(the
    smallest positive root of p(-x)).  (Shifting p by its root bound first would multiply the
    coefficients' size by the degree: x^k (x + 1)^k gained thousands of bits.)"""
    p = poly_arithmetic.trim(p)
    if len(p) <= 1:
        return None
    q = polys.squarefree(p)
    positive = polys.positive_roots(q)
    if positive:  # isolated for q without its root at 0 (an interval (0, hi) must not end at a root of the Real)
        return _root(poly_arithmetic.strip_zero_roots(q), positive[-1], 1)
    if q[0] == 0:
        return Real.rational(Fraction(0))
    negative = polys.positive_roots([c if k % 2 == 0 else -c for k, c in enumerate(q)])
    return _root(q, negative[0], -1) if negative else None


def _root(q: Any, interval: Any, sign: Any) -> Any:
    """The root of q isolated by ``interval`` (found for q(sign x))."""
    lo, hi = interval
    if sign < 0:
        lo, hi = -hi, -lo
    if lo == hi:
        return Real.rational(lo)
    return Real.algebraic(q, lo, hi, "largest eigenvalue")


def strongly_connected_blocks(rows: Any) -> Any:
    """The strongly connected components of the graph i -> k for every off-diagonal entry
    (i, k) != 0 of a square matrix in sparse rows, as sorted index lists (Tarjan, iterative).

    Ordering the components topologically makes the matrix block triangular by a symmetric
    permutation P^T M P, so det(xI - M) is the product of the diagonal blocks' characteristic
    polynomials: M's eigenvalues are the union of its blocks'."""
    n = len(rows)
    succ = [[k for k, x in row if k != i and x != 0] for i, row in enumerate(rows)]
    index: list[int | None] = [None] * n
    low, on_stack, stack, blocks, counter = [0] * n, [False] * n, [], [], 0
    for root in range(n):
        if index[root] is not None:
            continue
        work = [(root, 0)]
        while work:
            v, i = work.pop()
            if i == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on_stack[v] = True
            if i < len(succ[v]):
                work.append((v, i + 1))
                w = succ[v][i]
                if index[w] is None:
                    work.append((w, 0))
                elif on_stack[w]:
                    low[v] = min(low[v], index[w])
                continue
            if low[v] == index[v]:
                block = []
                while True:
                    w = stack.pop()
                    on_stack[w] = False
                    block.append(w)
                    if w == v:
                        break
                blocks.append(sorted(block))
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[v])
    return blocks

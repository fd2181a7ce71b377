"""The largest forward-Euler step on an ellipsoid as a generalised eigenvalue (beyond the paper).

Forward Euler, r(z) = 1 + z: M(h)/h = K - h B with K = -(A^T Q + Q A) and
B = A^T Q A, affine in h, so the valid set is an interval [0, tau] and
tau = sup{h : K - hB >= 0} is a generalised eigenvalue: with
range(B) in range(K) (else tau = 0) and W a basis of range(K),
tau = 1 / lambda_max((W^T K W)^{-1} W^T B W) (INF if that is <= 0).  This is
the second derivation of the forward-Euler step on E; the first is the valid
set of the one engine (:mod:`exactinv.validset.engine`), and they must agree.
"""

from __future__ import annotations

from fractions import Fraction

import flint

from ..core.algebraic import Real
from ..core.flintq import matrix_of
from ..core.psd import psd_decision
from ..core.roots import real_roots
from ..core.scalars import INF

__all__ = ["generalised_eigenvalue_step", "pivot_columns"]


def generalised_eigenvalue_step(A: flint.fmpq_mat, Q: flint.fmpq_mat) -> Real:
    """sup{h >= 0 : K - hB >= 0}, K = -(A^T Q + Q A), B = A^T Q A (module docstring), exact.

    A = [[-1, -2], [2, -1]], Q = I: K = 2I, B = 5I, so tau = 2/5.

    >>> generalised_eigenvalue_step(flint.fmpq_mat([[-1, -2], [2, -1]]), flint.fmpq_mat([[1, 0], [0, 1]]))
    Fraction(2, 5)
    """
    K = -(A.transpose() * Q + Q * A)
    B = A.transpose() * Q * A
    if not psd_decision(matrix_of(K)).psd:
        return Fraction(0)
    n = K.nrows()
    rank_K = K.rank()
    KB = [v for i in range(n) for v in [K[i, j] for j in range(n)] + [B[i, j] for j in range(n)]]
    if flint.fmpq_mat(n, 2 * n, KB).rank() > rank_K:
        return Fraction(0)  # some v in ker K has v^T B v > 0: K - hB fails for every h > 0
    if rank_K == 0:
        return INF
    _, pivots = pivot_columns(K)
    W = flint.fmpq_mat(n, len(pivots), [K[i, j] for i in range(n) for j in pivots])
    C = (W.transpose() * K * W).inv() * (W.transpose() * B * W)
    mu = C.charpoly()  # eigenvalues real and >= 0 (similar to a PSD matrix); tau = 1/mu_max
    h_poly = flint.fmpq_poly(list(reversed(mu.coeffs())))  # roots 1/mu for mu != 0
    if h_poly.degree() < 1:
        return INF
    roots = [r for r, _ in real_roots(h_poly) if r > 0]
    return roots[0] if roots else INF


def pivot_columns(K: flint.fmpq_mat) -> tuple[flint.fmpq_mat, list[int]]:
    """(rref of K, its pivot columns).

    >>> pivot_columns(flint.fmpq_mat([[1, 2], [2, 4]]))[1]
    [0]
    """
    R, rank = K.rref()
    pivots, row = [], 0
    for j in range(K.ncols()):
        if row < rank and R[row, j] != 0:
            pivots.append(j)
            row += 1
    return R, pivots

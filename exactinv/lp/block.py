"""Step 1, batched: K LPs sharing one constraint matrix as ONE float LP.

The K LPs  max c_k.x_k  s.t.  A x_k (= | <=) r_k,  x_k,i >= 0 (nonnegative
columns of LP k)  are independent, so their sum is one LP with the
block-diagonal matrix diag(A, ..., A): it is optimal exactly when every LP k
is, and then its optimal points and duals are, block by block, optimal points
and duals of the K LPs.  HiGHS solves it in one call -- with presolve, which
for sparse A (e.g. the row LPs of gamma* on a box) removes most of the LP
before any simplex step -- instead of K warm-started calls.

Untrusted like every hint: the caller rounds and verifies in Q.
"""

from __future__ import annotations

from typing import NamedTuple

import highspy
import numpy as np

from .highs import silent_highs
from .hint_types import LPStatus

__all__ = ["BlockHint", "block_hints"]


class BlockHint(NamedTuple):
    """The float answer for K LPs: ``status`` (OPTIMAL only when every LP is
    optimal; otherwise UNKNOWN: the caller solves them one by one), ``X``
    (K x N: row k the point of LP k) and ``Y`` (K x R: row k its dual, >= 0 on
    inequality rows, A^T y - c_k >= 0 on nonnegative columns, = 0 on free ones)."""

    status: LPStatus
    X: np.ndarray | None = None
    Y: np.ndarray | None = None


def block_hints(A: np.ndarray, equality: np.ndarray, costs: np.ndarray, rhss: np.ndarray, nonneg: np.ndarray,
                presolve: bool = True) -> BlockHint:
    """Float points and duals of the K LPs  max costs[k].x  s.t.
    A x (= | <=) rhss[k],  x_i >= 0 where nonneg[k, i]  (A: R x N floats;
    costs, nonneg: K x N; rhss: K x R), from one HiGHS solve of the
    block-diagonal LP.  Rows are scaled to max-norm 1 for the float model only.

    >>> A = np.array([[1.0, 1.0]])              # x1 + x2 <= r, x >= 0
    >>> hint = block_hints(A, np.array([False]), np.array([[1.0, 0.0], [1.0, 2.0]]), np.array([[3.0], [4.0]]),
    ...                    np.ones((2, 2), dtype=bool))
    >>> hint.status, hint.X.tolist(), hint.Y.tolist()
    (<LPStatus.OPTIMAL: 'optimal'>, [[3.0, 0.0], [0.0, 4.0]], [[1.0], [2.0]])
    >>> empty = block_hints(A, np.array([False]), np.array([[-1.0, -1.0]]), np.array([[-1.0]]), np.ones((1, 2), bool))
    >>> empty.status   # x1 + x2 <= -1 with x >= 0 is empty: no answer, the LPs go one by one
    <LPStatus.UNKNOWN: 'unknown'>
    """
    (R, N), K = A.shape, len(costs)
    norms = np.abs(A).max(axis=1) if N else np.ones(R)
    scale = 1.0 / np.where(norms > 0, norms, 1.0)
    rows, cols = np.nonzero((A * scale[:, None]).T)  # column-wise nonzeros of the scaled A
    values = (A * scale[:, None]).T[rows, cols]
    counts = np.bincount(rows, minlength=N)
    start = np.concatenate([[0], np.cumsum(np.tile(counts, K))]).astype(np.int32)
    index = (cols[None, :] + R * np.arange(K)[:, None]).ravel().astype(np.int32)
    inf = highspy.kHighsInf
    rhs = (rhss * scale[None, :]).ravel()
    row_lower = np.where(np.tile(equality, K), rhs, -inf)
    h = silent_highs()
    h.setOptionValue("presolve", "on" if presolve else "off")
    status = h.passModel(K * N, K * R, len(index), int(highspy.MatrixFormat.kColwise),
                         int(highspy.ObjSense.kMinimize), 0.0, -costs.ravel().astype(float),
                         np.where(nonneg.ravel(), 0.0, -inf), np.full(K * N, inf),
                         row_lower, rhs, start, index, np.tile(values, K).astype(float), np.zeros(K * N, np.int32))
    if status == highspy.HighsStatus.kError:
        return BlockHint(LPStatus.UNKNOWN)
    h.run()
    if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
        return BlockHint(LPStatus.UNKNOWN)
    solution = h.getSolution()
    X = np.asarray(solution.col_value, dtype=float).reshape(K, N)
    Y = -np.asarray(solution.row_dual, dtype=float).reshape(K, R) * scale[None, :]
    if not (np.all(np.isfinite(X)) and np.all(np.isfinite(Y))):
        return BlockHint(LPStatus.UNKNOWN)
    return BlockHint(LPStatus.OPTIMAL, X, Y)

"""The spectral abscissa alpha(H) of a Metzler certificate H, only as far as erratum E2 needs it.

E2 caps the rational threshold by z_p/alpha(H) when alpha(H) > 0 (:mod:`.rational`).
A dense characteristic polynomial of the m x m matrix H costs O(m^3) operations on
numbers that grow with m (minutes at m = 150, hours at m = 1000), and most of the
time the bound cannot bind.  What is decided here, exactly, and in this order:

1. **Collatz-Wielandt**: for a Metzler H (H + cI >= 0) and any v > 0,
   alpha(H) <= max_i (Hv)_i / v_i (:func:`collatz_wielandt_upper`).  With v = b when
   b > 0, Hb <= 0 gives alpha(H) <= 0: no E2 bound at all.  The kernel applies the same
   test (exactinv_check/claims_thresholds.py, ``_e2_may_bind``).
2. **The eigenvalues of A** (:func:`abscissa_is_nonpositive`): let w >= 0, w != 0, be
   a left Perron vector of H (w^T H = alpha w^T).  Then (G^T w)^T A = w^T H G =
   alpha (G^T w)^T, so either G^T w != 0 and alpha is a real eigenvalue of A, or
   G^T w = 0; then for an interior point x of P, w^T b > w^T G x = 0 and
   alpha w^T b = w^T H b <= 0 give alpha <= 0.  Hence for a full-dimensional P
   whose A has no positive real eigenvalue, alpha(H) <= 0: one Sturm count on
   the degree-n characteristic polynomial of A.
3. Only then the exact value (:func:`spectral_abscissa`): alpha(H) is the largest
   alpha over the strongly connected components of H's off-diagonal graph (the
   diagonal blocks of its Frobenius normal form); each block is bounded in Q by
   Collatz-Wielandt with a float Perron vector as a hint (upper: max ratio for a
   positive v; lower: min ratio on the support of any v >= 0, since
   Hv >= mu v there and (Hv)_i >= 0 off it), and only the blocks whose upper bound
   reaches the best lower bound get an exact characteristic polynomial.

Every bound is a rational computed exactly; floats only choose the vectors.  H may be
given by rows (:class:`~exactinv.core.sparse.SparseRows`, what gamma* produces) or as
an fmpq matrix: products, the graph and the blocks use its nonzero entries only, and
no m x m matrix is built (only the components' blocks, where a characteristic
polynomial needs them).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Sequence

import flint
import numpy as np

from ..core.algebraic import ExactKey
from ..core.flintq import fraction_of
from ..core.float_hint import float_hints
from ..core.real_algebraic import RealAlgebraic
from ..core.roots import positive_roots, real_roots
from ..core.sparse import SparseRows

__all__ = ["collatz_wielandt_upper", "perron_lower", "abscissa_is_nonpositive", "components", "spectral_abscissa"]


def collatz_wielandt_upper(H: flint.fmpq_mat | SparseRows, v: Sequence[Fraction]) -> Fraction:
    """max_i (Hv)_i / v_i for a vector v > 0: an upper bound on alpha(H) for a Metzler H, exact.

    >>> collatz_wielandt_upper(flint.fmpq_mat([[-2, 1], [1, -2]]), [1, 1])   # alpha = -1
    Fraction(-1, 1)
    """
    Hv = SparseRows.of(H).times(v)
    return max(fraction_of(Hv[i]) / Fraction(x) for i, x in enumerate(v))


def perron_lower(H: flint.fmpq_mat | SparseRows, v: Sequence[Fraction]) -> Fraction | None:
    """min over {i : v_i > 0} of (Hv)_i / v_i for a vector v >= 0, v != 0 (None otherwise): a lower
    bound on alpha(H) for a Metzler H, exact (Hv >= mu v on the support, and (Hv)_i >= 0 off it
    since the off-diagonal entries are >= 0; subinvariance).

    >>> perron_lower(flint.fmpq_mat([[-2, 1], [1, -2]]), [1, 0])   # alpha = -1 >= -2
    Fraction(-2, 1)
    """
    support = [i for i, x in enumerate(v) if x > 0]
    if not support or any(x < 0 for x in v):
        return None
    Hv = SparseRows.of(H).times(v)
    return min(fraction_of(Hv[i]) / Fraction(v[i]) for i in support)


def abscissa_is_nonpositive(A: flint.fmpq_mat, full_dimensional: bool) -> bool:
    """True when alpha(H) <= 0 for every certificate H of a full-dimensional P (HG = GA,
    Hb <= 0, H Metzler): A has no positive real eigenvalue (module docstring, step 2).
    False means "not proved" (P not full-dimensional, or A has a positive real eigenvalue).

    >>> abscissa_is_nonpositive(flint.fmpq_mat([[-2, 0], [0, -2]]), True)
    True
    >>> abscissa_is_nonpositive(flint.fmpq_mat([[-1, 2], [0, 1]]), True)     # eigenvalue 1
    False
    """
    if not full_dimensional:
        return False
    if A.nrows() == 0:
        return True
    return not positive_roots(flint.fmpq_poly(A.charpoly().coeffs()))


def components(H: flint.fmpq_mat | SparseRows) -> list[list[int]]:
    """The strongly connected components of the graph i -> j (i != j, H_ij != 0), each sorted
    (Tarjan, iterative).  For a Metzler H, alpha(H) is the largest alpha over the principal
    submatrices on these components (the diagonal blocks of the Frobenius normal form).

    >>> components(flint.fmpq_mat([[-1, 1, 0], [1, -1, 0], [1, 0, -3]]))
    [[0, 1], [2]]
    """
    S = SparseRows.of(H)
    m = S.m
    succ = S.successors()
    index, low, on_stack, stack, out = [-1] * m, [0] * m, [False] * m, [], []
    counter = 0
    for root in range(m):
        if index[root] >= 0:
            continue
        work = [(root, 0)]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on_stack[root] = True
        while work:
            i, k = work[-1]
            if k < len(succ[i]):
                work[-1] = (i, k + 1)
                j = succ[i][k]
                if index[j] < 0:
                    index[j] = low[j] = counter
                    counter += 1
                    stack.append(j)
                    on_stack[j] = True
                    work.append((j, 0))
                elif on_stack[j]:
                    low[i] = min(low[i], index[j])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[i])
            if low[i] == index[i]:
                comp = []
                while True:
                    j = stack.pop()
                    on_stack[j] = False
                    comp.append(j)
                    if j == i:
                        break
                out.append(sorted(comp))
    return sorted(out)


def _perron_hint(B: flint.fmpq_mat) -> np.ndarray | None:
    """A float right Perron vector of the block (entries > 0), or None (a hint only)."""
    k = B.nrows()
    M = float_hints(B.entries()).reshape(k, k)
    if not np.all(np.isfinite(M)):
        return None
    try:
        values, vectors = np.linalg.eig(M)
    except np.linalg.LinAlgError:
        return None
    u = np.real(vectors[:, int(np.argmax(np.real(values)))])
    u = u * np.sign(u.sum() or 1.0)
    if not np.all(np.isfinite(u)) or not np.all(u > 0):
        return None
    return u / u.max()


def _bounds(B: flint.fmpq_mat) -> tuple[Fraction | None, Fraction | None]:
    """(lower, upper) rational bounds on alpha(B) from a float Perron vector (None: no bound)."""
    u = _perron_hint(B)
    if u is None:
        return None, None
    v = [Fraction(float(x)).limit_denominator(1 << 30) for x in u]
    v = [x if x > 0 else Fraction(1, 1 << 30) for x in v]
    return perron_lower(B, v), collatz_wielandt_upper(B, v)


def _exact(B: flint.fmpq_mat) -> Fraction | RealAlgebraic:
    return real_roots(B.charpoly())[-1][0]


def spectral_abscissa(H: flint.fmpq_mat | SparseRows) -> Fraction | RealAlgebraic:
    """alpha(H) = max Re(lambda) over the eigenvalues of a Metzler matrix H (off-diagonal
    >= 0): by Perron-Frobenius for H + cI >= 0 the largest real eigenvalue, exact.  Block by
    block over the strongly connected components; a block whose certified upper bound is below
    another's certified lower bound is never expanded (module docstring, step 3).

    >>> spectral_abscissa(flint.fmpq_mat([[-2, 1], [1, -2]]))   # eigenvalues -1 and -3
    Fraction(-1, 1)
    >>> spectral_abscissa(flint.fmpq_mat([[0, 1], [2, 0]])).poly  # +-sqrt(2): the root of x^2 - 2
    x^2 + (-2)
    >>> spectral_abscissa(flint.fmpq_mat([[1, 0, 0], [5, -1, 1], [0, 1, -1]]))   # blocks {0}: 1, {1, 2}: 0
    Fraction(1, 1)
    """
    S = SparseRows.of(H)
    blocks = [S.block(rows) for rows in components(S)]
    bounds = [(fraction_of(B[0, 0]),) * 2 if B.nrows() == 1 else _bounds(B) for B in blocks]
    floor = max((lo for lo, _ in bounds if lo is not None), default=None)
    unbounded = [k for k in range(len(blocks)) if bounds[k][1] is None]
    order = unbounded + sorted((k for k in range(len(blocks)) if bounds[k][1] is not None), key=lambda k: -bounds[k][1])
    best = None
    for k in order:
        lo, hi = bounds[k]
        if hi is not None and (floor is not None and hi < floor or best is not None and ExactKey(hi) < ExactKey(best)):
            continue  # this block's alpha is below another's: never expanded
        B = blocks[k]
        value = fraction_of(B[0, 0]) if B.nrows() == 1 else _exact(B)
        if best is None or ExactKey(best) < ExactKey(value):
            best = value
    return best

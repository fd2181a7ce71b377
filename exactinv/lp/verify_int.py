"""Step 3, fast path: the batch check of :func:`~exactinv.lp.verify.optimal_values`
in integer arithmetic carried by doubles.

A double represents every integer of magnitude < 2^53 exactly, and a sum or
product of such integers is computed exactly as long as every partial result
stays below 2^53 (whatever the order of summation, since each partial sum is
an integer bounded by the sum of the magnitudes).  So when the LP data and
the proposed points are integers over common denominators with bounds that
keep every product and sum below 2^53 -- proved beforehand with Python
integers -- the whole batch check (A X, A^T Y, signs, zeros, objectives) runs
in numpy/BLAS and is still exact.  Otherwise :func:`optimal_values_int`
returns None and the caller takes the FLINT route.
"""

from __future__ import annotations

from typing import Sequence

import flint
import numpy as np

from .verify import LPData

__all__ = ["integer_image", "optimal_values_int"]

_EXACT = 2 ** 53


def integer_image(M: flint.fmpq_mat) -> tuple[np.ndarray, int] | None:
    """(N, d) with M = N / d, N a float64 array of exact integers (|N| < 2^53) and d > 0; None if too large.

    >>> N, d = integer_image(flint.fmpq_mat([[1, 2], [3, 4]]) / 6)
    >>> N.tolist(), d
    ([[1.0, 2.0], [3.0, 4.0]], 6)
    >>> integer_image(flint.fmpq_mat([[2 ** 60]])) is None
    True
    """
    numerators, d = M.numer_denom()
    try:
        values = np.array(numerators.entries(), dtype=float).reshape(M.nrows(), M.ncols())
    except OverflowError:  # beyond double range
        return None
    if values.size and not np.abs(values).max() < _EXACT:  # a rounded double is >= 2^53 too
        return None
    return values, int(d)


def optimal_values_int(data: LPData, C: flint.fmpq_mat, B: flint.fmpq_mat, signs: Sequence[Sequence[bool]],
                       Xn: np.ndarray, Yn: np.ndarray, d: int) -> list[flint.fmpq | None] | None:
    """:func:`~exactinv.lp.verify.optimal_values` for X = Xn / d and Y = Yn / d
    (Xn N x K, Yn R x K: integer-valued float64 arrays), exact; None when the
    bounds do not keep every integer below 2^53 (then use the FLINT route).

    >>> data = LPData(flint.fmpq_mat([[1], [-1]]), (False, False))
    >>> optimal_values_int(data, flint.fmpq_mat([[1, 1]]), flint.fmpq_mat([[2, 2], [0, 0]]), [(False,)] * 2,
    ...                    np.array([[2.0, 1.0]]), np.array([[1.0, 1.0], [0.0, 0.0]]), 1)
    [2, None]
    """
    images = [_image_of(data), integer_image(C), integer_image(B)]
    if any(image is None for image in images):
        return None
    if not (np.abs(Xn).max(initial=0) < _EXACT and np.abs(Yn).max(initial=0) < _EXACT):
        return None
    (A, dA), (Cn, dC), (Bn, dB) = images
    mA, mC, mB, mX, mY = (int(np.abs(M).max(initial=0)) for M in (A, Cn, Bn, Xn, Yn))
    R, N = A.shape
    bounds = (dB * N * mA * mX + mB * dA * d,  # slack numerators
              dC * R * mA * mY + mC * dA * d,  # reduced-cost numerators
              N * mC * mX, R * mB * mY)  # objectives
    if max(bounds) >= _EXACT or max(dA * d, dB, dC) >= _EXACT:  # the factors enter float arrays too
        return None
    nonneg = np.array(signs, dtype=bool).T if len(signs) and N else np.zeros((N, len(signs)), dtype=bool)
    slack = Bn * (dA * d) - dB * (A @ Xn)  # (b - A x) * dA dB d
    reduced = dC * (A.T @ Yn) - Cn * (dA * d)  # (A^T y - c) * dA dC d
    eq = np.array(data.equality, dtype=bool)
    ok = ~((Xn < 0) & nonneg).any(axis=0)
    ok &= ~(slack[eq] != 0).any(axis=0) & ~(slack[~eq] < 0).any(axis=0) & ~(Yn[~eq] < 0).any(axis=0)
    ok &= ~(reduced < 0).any(axis=0) & ~((reduced != 0) & ~nonneg).any(axis=0)
    cx, by = (Cn * Xn).sum(axis=0), (Bn * Yn).sum(axis=0)
    values: list[flint.fmpq | None] = []
    for k in range(len(ok)):
        c_num, b_num = int(cx[k]), int(by[k])
        values.append(flint.fmpq(c_num, dC * d) if ok[k] and c_num * dB == b_num * dC else None)
    return values


def _image_of(data: LPData) -> tuple[np.ndarray, int] | None:
    """The integer image of A, once per LPData (kept in its __dict__, as cached_property does)."""
    cache = data.__dict__
    if "_integer_image" not in cache:
        cache["_integer_image"] = integer_image(data.A)
    return cache["_integer_image"]

"""Exact positive semidefiniteness of a rational symmetric matrix (LDL^T).

A symmetric M in Q^{n x n} is decided by symmetric Gaussian elimination
with diagonal pivoting, in exact arithmetic:

* a positive diagonal pivot d = S_kk is eliminated: S = [[d, d l^T], [d l, S']]
  with S' = (Schur complement) and S is PSD iff S' is (d > 0);
* a negative diagonal entry S_kk < 0 refutes: v = e_k has v^T S v < 0;
* if no diagonal entry is positive and none negative but S_ij != 0, then
  v = e_i - sign(S_ij) e_j has v^T S v = -2 |S_ij| < 0;
* an all-zero remainder is PSD (zero pivots).

PSD: P^T M P = L D L^T with L unit lower triangular and D >= 0 (``proof``).
Not PSD: a rational ``witness`` v with v^T M v < 0, lifted through the
eliminations by v_k = -l^T w (then v^T S v = w^T S' w exactly).  No float.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Sequence

import flint

from ..errors import InvalidInput
from .flintq import fraction_of
from .scalars import Matrix, Vector, to_matrix, vector_text

__all__ = ["LDLT", "PSDDecision", "psd_decision", "quadratic_form", "symmetric_matrix"]


@dataclass(frozen=True)
class LDLT:
    """M[perm][:, perm] = L diag(D) L^T, L unit lower triangular, exact."""

    perm: tuple[int, ...]
    L: Matrix
    D: Vector

    def __repr__(self) -> str:
        return f"LDLT(perm={self.perm}, D={vector_text(self.D)})"


@dataclass(frozen=True)
class PSDDecision:
    """``psd`` with its ``proof`` (an :class:`LDLT` with D >= 0), or a
    ``witness`` v with ``value`` = v^T M v < 0.  Truthy iff M is PSD."""

    psd: bool
    proof: LDLT | None
    witness: Vector | None
    value: Fraction | None

    def __bool__(self) -> bool:
        return self.psd

    @property
    def definite(self) -> bool:
        """M is positive definite (PSD with every pivot D_i > 0)."""
        return self.psd and all(d > 0 for d in self.proof.D)

    def __repr__(self) -> str:
        if self.psd:
            return f"PSDDecision(psd=True, D={vector_text(self.proof.D)})"
        return f"PSDDecision(psd=False, witness={vector_text(self.witness)}, value={self.value})"


def symmetric_matrix(M: Any, name: str = "M", *, allow_float: bool = False) -> Matrix:
    """M as an exact square symmetric matrix, or :class:`~exactinv.InvalidInput` naming ``name``.

    >>> symmetric_matrix([[1, "1/2"], ["1/2", 3]])
    ((Fraction(1, 1), Fraction(1, 2)), (Fraction(1, 2), Fraction(3, 1)))
    >>> symmetric_matrix([[1, 2], [0, 1]], "Q")
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: Q: not symmetric, Q[1][0] = 0 but Q[0][1] = 2
    """
    Mm = to_matrix(M, name, square=True, allow_float=allow_float)
    for i, row in enumerate(Mm):
        for j in range(i):
            if row[j] != Mm[j][i]:
                raise InvalidInput(f"{name}: not symmetric, {name}[{i}][{j}] = {row[j]} but {name}[{j}][{i}] = {Mm[j][i]}")
    return Mm


def quadratic_form(M: Sequence[Sequence[Any]], v: Sequence[Any]) -> Fraction:
    """v^T M v, exactly.

    >>> quadratic_form([[2, 1], [1, 2]], [1, -1])
    Fraction(2, 1)
    """
    return Fraction(sum(vi * sum(mij * vj for mij, vj in zip(row, v)) for vi, row in zip(v, M)))


def psd_decision(M: Any) -> PSDDecision:
    """Decide M >= 0 exactly (see the module docstring); M symmetric rational.

    >>> psd_decision([[1, 1], [1, 1]]).psd
    True
    >>> d = psd_decision([[1, 2], [2, 1]]); d.witness, d.value
    ((Fraction(-2, 1), Fraction(1, 1)), Fraction(-3, 1))
    """
    Mm = symmetric_matrix(M)
    n = len(Mm)
    S = {(i, j): flint.fmpq(v.numerator, v.denominator) for i, row in enumerate(Mm) for j, v in enumerate(row)}
    rest = list(range(n))
    steps: list[tuple[int, dict[int, flint.fmpq]]] = []  # (pivot, multipliers l_j)
    pivots: list[flint.fmpq] = []
    while rest:
        k = next((i for i in rest if S[i, i] > 0), None)
        if k is None:
            w = _refute_nonpositive_diagonal(S, rest)
            if w is None:
                break  # the remainder is zero
            v = _lift(w, steps)
            return PSDDecision(False, None, tuple(fraction_of(v.get(i, 0)) for i in range(n)),
                               quadratic_form(Mm, [fraction_of(v.get(i, 0)) for i in range(n)]))
        d = S[k, k]
        rest.remove(k)
        ell = {j: S[j, k] / d for j in rest}
        for a in rest:
            if ell[a]:
                for b in rest:
                    S[a, b] -= ell[a] * d * ell[b]
        steps.append((k, ell))
        pivots.append(d)
    return PSDDecision(True, _ldlt(n, steps, pivots, rest), None, None)


def _refute_nonpositive_diagonal(S: dict, rest: list[int]) -> dict[int, flint.fmpq] | None:
    """No positive diagonal entry left: a w with w^T S w < 0, or None if S = 0."""
    for i in rest:
        if S[i, i] < 0:
            return {i: flint.fmpq(1)}
    for i in rest:
        for j in rest:
            if i != j and S[i, j] != 0:
                return {i: flint.fmpq(1), j: flint.fmpq(-1 if S[i, j] > 0 else 1)}
    return None


def _lift(w: dict[int, flint.fmpq], steps) -> dict[int, flint.fmpq]:
    """Undo the eliminations, last first: v_k = -sum_j l_j w_j keeps v^T S v = w^T S' w."""
    v = dict(w)
    for k, ell in reversed(steps):
        v[k] = -sum((ell[j] * x for j, x in v.items() if j in ell), flint.fmpq(0))
    return v


def _ldlt(n: int, steps, pivots, zeros: list[int]) -> LDLT:
    perm = [k for k, _ in steps] + zeros
    position = {k: i for i, k in enumerate(perm)}
    L = [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]
    for col, (_, ell) in enumerate(steps):
        for j, l in ell.items():
            L[position[j]][col] = fraction_of(l)
    D = [fraction_of(d) for d in pivots] + [Fraction(0)] * len(zeros)
    return LDLT(tuple(perm), tuple(tuple(r) for r in L), tuple(D))


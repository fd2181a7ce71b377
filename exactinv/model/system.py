"""The linear dynamical system x' = Ax, immutable and exact (entries are Fractions)."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any

import flint

from ..core.flintq import fmpq_matrix
from ..core.latex import LatexMixin, latex_matrix
from ..core.scalars import Matrix, matrix_text, to_matrix

__all__ = ["LinearSystem"]


@dataclass(frozen=True, init=False)
class LinearSystem(LatexMixin):
    """The linear dynamical system x' = A x with an exact square matrix A.

    >>> LinearSystem([[-1, 1], [-1, "-1"]]).A
    ((Fraction(-1, 1), Fraction(1, 1)), (Fraction(-1, 1), Fraction(-1, 1)))
    """

    A: Matrix

    def __init__(self, A: Any, *, allow_float: bool = False):
        object.__setattr__(self, "A", to_matrix(A, "A", square=True, allow_float=allow_float))

    @classmethod
    def closed_loop(cls, A0: Any, B: Any, F: Any, *, allow_float: bool = False) -> "LinearSystem":
        """The closed loop x' = (A0 + B F) x of x' = A0 x + B u under the
        linear feedback u = F x.

        >>> LinearSystem.closed_loop([[0, 1], [0, 0]], [[0], [1]], [[-1, -2]]).A   # A0 + B F
        ((Fraction(0, 1), Fraction(1, 1)), (Fraction(-1, 1), Fraction(-2, 1)))
        """
        A0m = to_matrix(A0, "A0", square=True, allow_float=allow_float)
        n = len(A0m)
        Bm = to_matrix(B, "B", shape=(n, None), allow_float=allow_float)
        Fm = to_matrix(F, "F", shape=(len(Bm[0]), n), allow_float=allow_float)
        A = fmpq_matrix(A0m) + fmpq_matrix(Bm) * fmpq_matrix(Fm)
        return cls([[A[i, j] for j in range(n)] for i in range(n)])

    @property
    def n(self) -> int:
        """The state dimension."""
        return len(self.A)

    @cached_property
    def A_flint(self) -> flint.fmpq_mat:
        return fmpq_matrix(self.A)

    def to_latex(self) -> str:
        """LaTeX: the system x' = A x.

        >>> print(LinearSystem([[-1, '1/2'], [0, -1]]).to_latex())
        \\dot x = \\begin{pmatrix} -1 & \\frac{1}{2} \\\\ 0 & -1 \\end{pmatrix}\\, x
        """
        return rf"\dot x = {latex_matrix(self.A)}\, x"

    def __repr__(self) -> str:
        return f"LinearSystem(A={matrix_text(self.A)})"

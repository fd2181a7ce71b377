"""The ellipsoid E = {x : x^T Q x <= 1}, immutable and exact (Q a rational
symmetric positive definite matrix; proved definite at construction).

Beyond the paper: the other half of the invariant sets of linear systems,
the sublevel sets of quadratic Lyapunov functions V(x) = x^T Q x.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any, ClassVar, Sequence

import flint
import numpy as np

from ..core.flintq import fmpq_matrix
from ..core.float_hint import ldexp_hint, log2_hint
from ..core.latex import LatexMixin, latex_matrix
from ..core.psd import LDLT, psd_decision, quadratic_form, symmetric_matrix
from ..core.scalars import Matrix, matrix_text, nearest_rational, to_matrix, to_vector
from ..errors import InvalidInput, Undecided
from .system import LinearSystem

__all__ = ["Ellipsoid"]

_DENOMINATORS = (10**3, 10**6, 10**9, 10**12)


@dataclass(frozen=True, init=False)
class Ellipsoid(LatexMixin):
    """E = {x in R^n : x^T Q x <= 1} with Q = Q^T > 0, exact.

    Q > 0 is proved at construction by an exact LDL^T with positive pivots
    (:mod:`exactinv.core.psd`, kept as ``proof``); a Q that is not
    symmetric or not positive definite raises :class:`~exactinv.InvalidInput`
    naming ``Q``.  Only the centre 0 is supported: for x' = Ax the invariance
    criteria below are those of a centred ellipsoid.

    >>> E = Ellipsoid([[2, 0], [0, "1/2"]])
    >>> E.contains([0, 1]), E.contains([1, 0])
    (True, False)
    """

    Q: Matrix
    family: ClassVar[str] = "ellipsoid"  # the set type, for exactinv.model.sets.set_family

    def __init__(self, Q: Any, center: Any = 0, *, allow_float: bool = False):
        Qm = symmetric_matrix(Q, "Q", allow_float=allow_float)
        if not (isinstance(center, int) and not isinstance(center, bool) and center == 0):
            c = to_vector(center, "center", length=len(Qm), allow_float=allow_float)
            if any(c):
                raise InvalidInput("center: only ellipsoids centred at 0 are supported (the invariance "
                                   "criterion Q - A_d^T Q A_d >= 0 is that of a centred ellipsoid)")
        decision = psd_decision(Qm)
        if not decision.definite:
            why = (f"x = {list(map(str, decision.witness))} has x^T Q x = {decision.value} <= 0"
                   if not decision.psd else "Q is singular (a zero pivot), E would be an unbounded cylinder")
            raise InvalidInput(f"Q: must be positive definite; {why}")
        object.__setattr__(self, "Q", Qm)
        self.__dict__["proof"] = decision.proof

    @classmethod
    def from_lyapunov(cls, A: Any, *, solver: str | None = None) -> "Ellipsoid":
        """An invariant ellipsoid of x' = Ax for a Hurwitz A, found by an SDP and proved exactly.

        cvxpy (an optional extra) solves Q >= I, A^T Q + Q A <= -I in floats;
        Q is rounded to rationals (denominators 10^3, 10^6, ...) and kept only
        once Q > 0 and -(A^T Q + Q A) > 0 are proved by exact LDL^T -- so
        rounding cannot break the Lyapunov inequality.  Raises
        :class:`~exactinv.InvalidInput` if the SDP is infeasible (A is not
        Hurwitz) and :class:`~exactinv.Undecided` if no rounding proves it.

        >>> E = Ellipsoid.from_lyapunov([[-1, 2], [0, -1]])
        >>> L = lyapunov_matrix([[-1, 2], [0, -1]], E.Q)
        >>> psd_decision(E.Q).definite, psd_decision([[-v for v in row] for row in L]).definite
        (True, True)
        """
        import cvxpy as cp  # optional extra

        Am = A.A if isinstance(A, LinearSystem) else to_matrix(A, "A", square=True)
        n = len(Am)
        # the SDP for A / 2^e, 2^e ~ max |a_ij| (a hint; A^T Q + Q A < 0 is scale-free and is proved for A itself)
        e = int(max((log2_hint(v) for row in Am for v in row if v != 0), default=0.0))
        Af = np.array([[ldexp_hint(v, -e) for v in row] for row in Am])
        X = cp.Variable((n, n), symmetric=True)
        eye = np.eye(n)
        problem = cp.Problem(cp.Minimize(cp.trace(X)), [X >> eye, Af.T @ X + X @ Af << -eye])
        problem.solve(solver=solver)
        if X.value is None or problem.status not in ("optimal", "optimal_inaccurate"):
            raise InvalidInput(f"A: the Lyapunov SDP is {problem.status}; A is not Hurwitz (or badly scaled)")
        return cls._rounded(Am, X.value)

    @classmethod
    def _rounded(cls, A: Matrix, Xf: Any) -> "Ellipsoid":
        n = len(A)
        for den in _DENOMINATORS:
            Q = [[nearest_rational((float(Xf[i][j]) + float(Xf[j][i])) / 2, den) for j in range(n)] for i in range(n)]
            lyap = lyapunov_matrix(A, Q)
            if psd_decision(Q).definite and psd_decision([[-v for v in r] for r in lyap]).definite:
                return cls(Q)
        raise Undecided("from_lyapunov: no rounding of the SDP solution satisfies A^T Q + Q A < 0 exactly")

    @property
    def n(self) -> int:
        """The ambient dimension."""
        return len(self.Q)

    @property
    def proof(self) -> LDLT:  # set in __init__ (the LDL^T with positive pivots)
        return self.__dict__["proof"]

    @cached_property
    def Q_flint(self) -> flint.fmpq_mat:
        return fmpq_matrix(self.Q)

    def contains(self, x: Sequence[Any]) -> bool:
        """Exact membership x^T Q x <= 1 for a rational point x.

        >>> E = Ellipsoid([[2, 0], [0, "1/2"]])
        >>> E.contains(["1/2", 1])       # 2/4 + 1/2 = 1: on the boundary
        True
        >>> E.contains(["1/2", "11/10"])  # 1/2 + 121/200 > 1
        False
        """
        return quadratic_form(self.Q, to_vector(x, "x", length=self.n)) <= 1

    def __contains__(self, x: Sequence[Any]) -> bool:
        return self.contains(x)

    def to_latex(self) -> str:
        """LaTeX: E = {x : x^T Q x <= 1}.

        >>> print(Ellipsoid([[2, 0], [0, "1/2"]]).to_latex())
        E = \\{x : x^T \\begin{pmatrix} 2 & 0 \\\\ 0 & \\frac{1}{2} \\end{pmatrix} x \\le 1\\}
        """
        return rf"E = \{{x : x^T {latex_matrix(self.Q)} x \le 1\}}"

    def __repr__(self) -> str:
        return f"Ellipsoid(Q={matrix_text(self.Q)})"


def lyapunov_matrix(A: Sequence[Sequence[Any]], Q: Sequence[Sequence[Any]]) -> Matrix:
    """A^T Q + Q A, exactly (the derivative of x^T Q x along x' = Ax is x^T (A^T Q + Q A) x).

    >>> lyapunov_matrix([[-1, 0], [0, -2]], [[1, 0], [0, 1]])
    ((Fraction(-2, 1), Fraction(0, 1)), (Fraction(0, 1), Fraction(-4, 1)))
    """
    Aq, Qq = fmpq_matrix(to_matrix(A, "A")), fmpq_matrix(to_matrix(Q, "Q"))
    L = Aq.transpose() * Qq + Qq * Aq
    return to_matrix(L, "A^T Q + Q A")

"""Step 1 of the exact LP engine: the float image of an exact LP family.

The exact data are mapped to doubles once, rows scaled for the float model
only, and handed to a hint backend (:mod:`exactinv.lp.hint`); what comes back
is sanitised (a malformed hint or basis is dropped) and scaled back.  Nothing
here is trusted: every hint is reconstructed and verified in Q afterwards.
"""

from __future__ import annotations

from functools import partial
from typing import Any, Callable, Sequence

import flint
import numpy as np

from ..core.float_hint import float_hints
from .hint_types import UNKNOWN_HINT, Basis, Hint, HintBackend, HintModel, LPStatus

__all__ = ["FloatLP", "floats_of"]


class FloatLP:
    """Step 1 of the exact LP engine: the float image of an exact LP family.

    The float model of the exact R x N matrix ``A`` is built once (rows
    scaled to max-norm 1 for the float model only: PPL-made rows can carry
    10^15-sized integers) and re-solved with new data; the hint's duals are
    scaled back to the exact rows, and a malformed hint or basis is dropped.
    Data beyond double range give an UNKNOWN hint (the exact route only).

    >>> from exactinv.lp.hint import HighsHint
    >>> lp = FloatLP(flint.fmpq_mat([[10**12, 0], [0, 1]]), (False, False), HighsHint())
    >>> hint = lp.solve(flint.fmpq_mat([[1], [1]]), flint.fmpq_mat([[10**12], [2]]), (False, False))
    >>> hint.status, hint.x.tolist(), hint.y.tolist()
    (<LPStatus.OPTIMAL: 'optimal'>, [1.0, 2.0], [1e-12, 1.0])
    """

    def __init__(self, A: flint.fmpq_mat, equality: Sequence[bool], backend: HintBackend):
        self.R, self.N = A.nrows(), A.ncols()
        self.equality, self.backend = tuple(equality), backend
        self._model: HintModel | None = None
        self.A: np.ndarray | None = None
        floats = floats_of(A.entries())
        if floats is not None:
            A_float = floats.reshape(self.R, self.N)
            norms = np.abs(A_float).max(axis=1) if self.N else np.ones(self.R)
            self.row_scale = np.where(norms > 0, 1.0 / np.where(norms > 0, norms, 1.0), 1.0)
            self.A = A_float * self.row_scale[:, None]

    def solve(self, c: flint.fmpq_mat, b: flint.fmpq_mat, nonneg: Sequence[bool]) -> Hint:
        """The backend's float answer for max c.x s.t. A x (= | <=) b, x_i >= 0 (nonneg).

        >>> from exactinv.lp.hint import HighsHint
        >>> lp = FloatLP(flint.fmpq_mat([[1, 1]]), (False,), HighsHint())
        >>> hint = lp.solve(flint.fmpq_mat([[1], [0]]), flint.fmpq_mat([[3]]), (True, True))
        >>> hint.status, hint.x.tolist(), hint.y.tolist()   # max x1 s.t. x1 + x2 <= 3, x >= 0
        (<LPStatus.OPTIMAL: 'optimal'>, [3.0, 0.0], [1.0])
        """
        return self.solve_floats(floats_of(c.entries()), floats_of(b.entries()), nonneg)

    def solve_floats(self, cost: np.ndarray | None, rhs: np.ndarray | None, nonneg: Sequence[bool]) -> Hint:
        """:meth:`solve` from the float images of c and b (None: beyond double range).

        >>> from exactinv.lp.hint import HighsHint
        >>> lp = FloatLP(flint.fmpq_mat([[1, 1]]), (False,), HighsHint())
        >>> lp.solve_floats(np.array([1.0, 0.0]), np.array([3.0]), (True, True)).x.tolist()
        [3.0, 0.0]
        >>> lp.solve_floats(None, np.array([3.0]), (True, True)).status   # beyond double range
        <LPStatus.UNKNOWN: 'unknown'>
        """
        if self.A is None or cost is None or rhs is None:
            return UNKNOWN_HINT
        if self._model is None:
            self._model = self.backend.model(self.A, self.equality)
        hint = self._model.solve(cost, rhs * self.row_scale, nonneg)
        if hint.status != LPStatus.OPTIMAL:
            return hint
        if (hint.x is None or hint.y is None or len(hint.x) != self.N or len(hint.y) != self.R
                or not (np.all(np.isfinite(hint.x)) and np.all(np.isfinite(hint.y)))):
            return UNKNOWN_HINT  # a malformed hint is no hint
        y = np.asarray(hint.y, dtype=float) * self.row_scale
        # a malformed basis is dropped: the engine guesses one from the point instead
        basis = hint.basis if self._well_formed(hint.basis) else None
        basis_of = None if hint.basis_of is None else partial(self._checked, hint.basis_of)
        return Hint(LPStatus.OPTIMAL, np.asarray(hint.x, dtype=float), y, basis, basis_of)

    def rhs(self, b: flint.fmpq_mat) -> np.ndarray:
        """The float image of the right-hand side b, scaled like the model's rows.

        >>> from exactinv.lp.hint import HighsHint
        >>> lp = FloatLP(flint.fmpq_mat([[4, 0], [0, 1]]), (False, False), HighsHint())
        >>> lp.rhs(flint.fmpq_mat([[2], [3]])).tolist()   # row 0 scaled by 1/4
        [0.5, 3.0]
        """
        return floats_of(b.entries()) * self.row_scale

    def _checked(self, fetch: Callable[[], Basis | None]) -> Basis | None:
        basis = fetch()
        return basis if self._well_formed(basis) else None

    def _well_formed(self, basis: Basis | None) -> bool:
        if basis is None or len(basis) != 2:
            return False
        cols, rows = basis
        return (all(0 <= i < self.N for i in cols) and all(0 <= r < self.R for r in rows)
                and len(set(cols)) == len(cols) and len(set(rows)) == len(rows))


def floats_of(values: Sequence[Any]) -> np.ndarray | None:
    """The float images of exact values, or None if one overflows a double.

    >>> floats_of([flint.fmpq(1, 4), 3]).tolist(), floats_of([flint.fmpz(10) ** 400])
    ([0.25, 3.0], None)
    """
    floats = float_hints(values)
    return floats if np.all(np.isfinite(floats)) else None

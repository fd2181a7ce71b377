"""The float-hint stage of the exact LP engine: pluggable backends.

:class:`~exactinv.lp.solver.ExactLPSolver` asks a *hint backend* for a float
solution of the LP it poses ::

    maximize  cost.x   subject to   a_r.x  = rhs_r  (equality rows)
                                    a_r.x <= rhs_r  (the other rows)
                                    x_i >= 0        (nonnegative columns; the others are free)

and then reconstructs, verifies in Q, or falls back to PPL's exact simplex.
The hint is never trusted, so the backend's choice (and its bugs, tolerances
or lies) cannot change a returned result -- only how fast it is found.

Two backends:

* :class:`HighsHint` (the default) -- HiGHS' dual simplex through highspy,
  one model per :class:`ExactLPSolver`, warm-started from LP to LP; it gives
  an optimal basis, which the engine solves exactly when rounding fails;
* :class:`CvxpyHint` -- the same LP written once in cvxpy with parameters
  (cost, right-hand side, sign mask), solved by any LP-capable solver cvxpy
  has configured (``solver=None``: cvxpy's own choice; ``"CLARABEL"``,
  ``"HIGHS"``, ``"GUROBI"``, ...).  cvxpy reports no basis; the engine guesses
  the active set from the float point instead.  cvxpy is imported only when
  this backend is used (it is an optional dependency).

Choose one globally with :func:`set_hint_backend`, for a block of code with
:func:`hint_backend`, or per solver with ``ExactLPSolver(A, eq, hint=...)``::

    import exactinv as ei
    with ei.lp.hint_backend("cvxpy", solver="CLARABEL"):
        g = ei.optimal_gamma(S, P)     # same exact value and certificate
"""

from __future__ import annotations

import contextlib
import contextvars
import importlib.util
from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any, Callable, Iterator, Sequence

import highspy
import numpy as np

__all__ = [
    "LPStatus",
    "Basis",
    "Hint",
    "HintBackend",
    "HintModel",
    "HighsHint",
    "CvxpyHint",
    "set_hint_backend",
    "get_hint_backend",
    "hint_backend",
    "resolve_hint_backend",
]


class LPStatus(StrEnum):
    """The outcome of an LP (equal to its old string: ``LPStatus.OPTIMAL == "optimal"``)."""

    OPTIMAL = "optimal"
    INFEASIBLE = "infeasible"
    UNBOUNDED = "unbounded"
    UNKNOWN = "unknown"  # a float hint that gave up (never a returned result)


Basis = tuple[tuple[int, ...], tuple[int, ...]]  # (basic columns, tight rows)


@dataclass(frozen=True)
class Hint:
    """An untrusted float answer: ``status``; for OPTIMAL a primal ``x`` and a
    dual ``y`` (one entry per row, >= 0 on inequality rows, A^T y = cost on
    free columns) and, where the backend knows it, ``basis`` =
    (basic columns, tight rows) -- or ``basis_of``, a function that fetches it
    on demand (valid until the backend's model solves again).

    >>> Hint(LPStatus.INFEASIBLE).has_basis
    False
    >>> Hint(LPStatus.OPTIMAL, basis_of=lambda: ((0,), (1,))).fetch_basis()
    ((0,), (1,))
    """

    status: LPStatus
    x: np.ndarray | None = None
    y: np.ndarray | None = None
    basis: Basis | None = None
    basis_of: Callable[[], Basis | None] | None = field(default=None, repr=False, compare=False)

    @property
    def has_basis(self) -> bool:
        """Whether the hint comes from a simplex basis (given or fetchable)."""
        return self.basis is not None or self.basis_of is not None

    def fetch_basis(self) -> Basis | None:
        """The basis: given, or fetched now from the backend.

        >>> Hint(LPStatus.OPTIMAL, basis=((1,), (0,))).fetch_basis()
        ((1,), (0,))
        """
        if self.basis is not None or self.basis_of is None:
            return self.basis
        return self.basis_of()


UNKNOWN_HINT = Hint(LPStatus.UNKNOWN)


class HintModel(ABC):
    """One float model of a constraint matrix, re-solved with new data."""

    @abstractmethod
    def solve(self, cost: np.ndarray, rhs: np.ndarray, nonneg: Sequence[bool]) -> Hint:
        """Maximize cost.x subject to the model's rows with right-hand side ``rhs``.

        >>> model = HighsHint().model(np.array([[1.0], [-1.0]]), [False, False])
        >>> model.solve(np.array([1.0]), np.array([0.0, -1.0]), [False]).status   # x <= 0 and x >= 1
        <LPStatus.INFEASIBLE: 'infeasible'>
        """


class HintBackend(ABC):
    """A float LP solver the exact engine may ask for hints."""

    name: str = "?"

    @abstractmethod
    def model(self, A: np.ndarray, equality: Sequence[bool]) -> HintModel:
        """A model for the R x N float matrix ``A`` (rows already scaled by the engine).

        >>> model = HighsHint().model(np.array([[1.0, 1.0]]), [False])
        >>> model.solve(np.array([1.0, 2.0]), np.array([4.0]), [True, True]).x.tolist()
        [0.0, 4.0]
        """

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


# ----------------------------------------------------------------- HiGHS
class HighsHint(HintBackend):
    """HiGHS' simplex through highspy: bases and warm starts (the default)."""

    name = "highs"

    def model(self, A, equality):
        """A HiGHS model of the float matrix ``A`` (built on its first solve, then warm-started).

        >>> hint = HighsHint().model(np.array([[2.0, 1.0]]), [True]).solve(np.array([1.0, 1.0]), np.array([2.0]), [True, True])
        >>> hint.status, hint.x.tolist(), hint.fetch_basis()   # max x1 + x2 on 2 x1 + x2 = 2: the vertex (0, 2)
        (<LPStatus.OPTIMAL: 'optimal'>, [0.0, 2.0], ((1,), (0,)))
        """
        return _HighsModel(A, equality)


class _HighsModel(HintModel):
    def __init__(self, A: np.ndarray, equality: Sequence[bool]):
        self.A = A
        self.equality = np.array(equality, dtype=bool)
        self.R, self.N = A.shape
        self._highs: highspy.Highs | None = None

    def solve(self, cost, rhs, nonneg):
        cost = -cost  # HiGHS minimizes
        lower = np.where(np.asarray(nonneg, dtype=bool), 0.0, -highspy.kHighsInf) if self.N else np.zeros(0)
        row_lower = np.where(self.equality, rhs, -highspy.kHighsInf)
        if self._highs is None:
            self._highs = self._build(cost, lower, row_lower, rhs)
        else:
            self._update(cost, lower, row_lower, rhs)
        h = self._highs
        h.run()
        status = h.getModelStatus()
        S = highspy.HighsModelStatus
        if status == S.kOptimal:
            sol = h.getSolution()
            return Hint(LPStatus.OPTIMAL, np.asarray(sol.col_value), -np.asarray(sol.row_dual), basis_of=self._basis)
        if status in (S.kInfeasible, S.kUnbounded):
            return Hint(LPStatus.INFEASIBLE if status == S.kInfeasible else LPStatus.UNBOUNDED)
        self._highs = None  # a model in an odd state is rebuilt next time
        return UNKNOWN_HINT

    def _build(self, cost, lower, row_lower, rhs) -> highspy.Highs:
        h = highspy.Highs()
        h.setOptionValue("output_flag", False)
        h.setOptionValue("presolve", "off")
        lp = highspy.HighsLp()
        lp.num_col_, lp.num_row_ = self.N, self.R
        lp.col_cost_, lp.col_lower_, lp.col_upper_ = cost, lower, np.full(self.N, highspy.kHighsInf)
        lp.row_lower_, lp.row_upper_ = row_lower, rhs
        cols = self.A.T
        nz = [np.nonzero(cols[i])[0] for i in range(self.N)]
        lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
        lp.a_matrix_.start_ = np.concatenate([[0], np.cumsum([len(z) for z in nz])]).astype(np.int32)
        lp.a_matrix_.index_ = np.concatenate(nz).astype(np.int32) if nz else np.zeros(0, np.int32)
        lp.a_matrix_.value_ = np.concatenate([cols[i][z] for i, z in enumerate(nz)]) if nz else np.zeros(0)
        h.passModel(lp)
        return h

    def _update(self, cost, lower, row_lower, rhs) -> None:
        h, idx, ridx = self._highs, np.arange(self.N, dtype=np.int32), np.arange(self.R, dtype=np.int32)
        h.changeColsCost(self.N, idx, cost)
        h.changeColsBounds(self.N, idx, lower, np.full(self.N, highspy.kHighsInf))
        h.changeRowsBounds(self.R, ridx, row_lower, rhs)

    def _basis(self) -> Basis | None:
        """(basic columns, tight rows = rows whose slack is nonbasic), fetched
        only when rounding does not verify (a Python loop over all statuses).
        (Not ``getBasicVariables``: highspy 1.15 crashes on it for LPs solved without pivots.)"""
        if self._highs is None:
            return None
        basis = self._highs.getBasis()
        if not basis.valid:
            return None
        basic = highspy.HighsBasisStatus.kBasic
        return (tuple(i for i, st in enumerate(basis.col_status) if st == basic),
                tuple(r for r, st in enumerate(basis.row_status) if st != basic))


# ----------------------------------------------------------------- cvxpy
class CvxpyHint(HintBackend):
    """Any LP solver configured in cvxpy (``solver=None``: cvxpy chooses).

    The LP is written once per constraint matrix as a DPP-compliant cvxpy
    problem with parameters for the cost, the right-hand side and the sign
    mask (``mask_i x_i >= 0``), so re-solving skips cvxpy's canonicalisation.
    ``solver_options`` are passed to ``Problem.solve``.  cvxpy gives no basis:
    the engine guesses one from the float point."""

    name = "cvxpy"

    def __init__(self, solver: str | None = None, **solver_options: Any):
        if importlib.util.find_spec("cvxpy") is None:
            raise ImportError("the cvxpy hint backend needs cvxpy, an optional dependency: pip install cvxpy")
        self.solver = solver
        self.solver_options = solver_options

    def model(self, A, equality):
        """The LP as a parametrised cvxpy problem (compiled once, re-solved with new data).

        >>> hint = CvxpyHint('CLARABEL').model(np.array([[1.0, 1.0]]), [False]).solve(np.array([1.0, 0.0]), np.array([3.0]), [True, True])
        >>> hint.status, [round(float(v), 6) for v in hint.x], hint.basis   # an interior-point solver: no basis
        (<LPStatus.OPTIMAL: 'optimal'>, [3.0, 0.0], None)
        """
        return _CvxpyModel(A, equality, self.solver, self.solver_options)

    def __repr__(self) -> str:
        return f"CvxpyHint(solver={self.solver!r})"


class _CvxpyModel(HintModel):
    def __init__(self, A: np.ndarray, equality: Sequence[bool], solver: str | None, options: dict):
        import cvxpy as cp  # optional dependency: imported only by this backend

        self.cp = cp
        self.solver, self.options = solver, options
        self.R, self.N = A.shape
        eq = np.array(equality, dtype=bool)
        self.eq_rows, self.le_rows = np.flatnonzero(eq), np.flatnonzero(~eq)
        self.x = cp.Variable(self.N)
        self.cost = cp.Parameter(self.N)
        self.mask = cp.Parameter(self.N, nonneg=True)
        constraints = [cp.multiply(self.mask, self.x) >= 0]
        self.b_eq = self.b_le = self.c_eq = self.c_le = None
        if len(self.eq_rows):
            self.b_eq = cp.Parameter(len(self.eq_rows))
            self.c_eq = A[self.eq_rows] @ self.x == self.b_eq
            constraints.append(self.c_eq)
        if len(self.le_rows):
            self.b_le = cp.Parameter(len(self.le_rows))
            self.c_le = A[self.le_rows] @ self.x <= self.b_le
            constraints.append(self.c_le)
        self.problem = cp.Problem(cp.Maximize(self.cost @ self.x), constraints)

    def solve(self, cost, rhs, nonneg):
        cp = self.cp
        if self.N == 0:
            return UNKNOWN_HINT
        self.cost.value = np.asarray(cost, dtype=float)
        self.mask.value = np.array([1.0 if v else 0.0 for v in nonneg])
        if self.b_eq is not None:
            self.b_eq.value = rhs[self.eq_rows]
        if self.b_le is not None:
            self.b_le.value = rhs[self.le_rows]
        try:
            self.problem.solve(solver=self.solver, **self.options)
        except (cp.SolverError, ValueError, ArithmeticError):
            return UNKNOWN_HINT
        status = self.problem.status
        if status in (cp.INFEASIBLE, cp.INFEASIBLE_INACCURATE):
            return Hint(LPStatus.INFEASIBLE)
        if status in (cp.UNBOUNDED, cp.UNBOUNDED_INACCURATE):
            return Hint(LPStatus.UNBOUNDED)
        if status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or self.x.value is None:
            return UNKNOWN_HINT
        y = np.zeros(self.R)
        for rows, con in ((self.eq_rows, self.c_eq), (self.le_rows, self.c_le)):
            if con is not None:
                if con.dual_value is None:
                    return UNKNOWN_HINT
                y[rows] = np.asarray(con.dual_value, dtype=float).reshape(-1)
        x = np.asarray(self.x.value, dtype=float).reshape(-1)
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            return UNKNOWN_HINT
        return Hint(LPStatus.OPTIMAL, x, y, None)


# ------------------------------------------------------------- selection
_BACKENDS = {"highs": HighsHint, "cvxpy": CvxpyHint}
_default: HintBackend = HighsHint()
_current: contextvars.ContextVar[HintBackend | None] = contextvars.ContextVar("exactinv_hint_backend", default=None)


def resolve_hint_backend(backend: str | HintBackend | None = None, **options: Any) -> HintBackend:
    """A backend from a name (``"highs"``, ``"cvxpy"``) and options, an
    instance, or None (the current one: :func:`hint_backend` block, else the global).

    >>> resolve_hint_backend('highs'), resolve_hint_backend('cvxpy', solver='SCS')
    (HighsHint(), CvxpyHint(solver='SCS'))
    """
    if backend is None:
        if options:
            raise TypeError("hint backend options need a backend name")
        current = _current.get()
        return _default if current is None else current
    if isinstance(backend, HintBackend):
        if options:
            raise TypeError("options are given with a backend name, not with an instance")
        return backend
    if isinstance(backend, str) and backend.lower() in _BACKENDS:
        return _BACKENDS[backend.lower()](**options)
    raise ValueError(f"unknown hint backend {backend!r}: use one of {sorted(_BACKENDS)} or a HintBackend")


def set_hint_backend(backend: str | HintBackend = "highs", **options: Any) -> HintBackend:
    """Set the global float-hint backend (``"highs"``, the default, or
    ``"cvxpy"`` with e.g. ``solver="CLARABEL"``); returns the previous one.

    >>> previous = set_hint_backend('cvxpy', solver='CLARABEL')
    >>> previous, get_hint_backend()
    (HighsHint(), CvxpyHint(solver='CLARABEL'))
    >>> set_hint_backend(previous)   # restore the default
    CvxpyHint(solver='CLARABEL')
    """
    global _default
    previous, _default = _default, resolve_hint_backend(backend, **options)
    return previous


def get_hint_backend() -> HintBackend:
    """The backend in effect here (a :func:`hint_backend` block, else the global one).

    >>> get_hint_backend()
    HighsHint()
    >>> with hint_backend('cvxpy', solver='CLARABEL'):
    ...     print(get_hint_backend())
    CvxpyHint(solver='CLARABEL')
    """
    return resolve_hint_backend()


@contextlib.contextmanager
def hint_backend(backend: str | HintBackend, **options: Any) -> Iterator[HintBackend]:
    """Use ``backend`` for the float hints of every LP solved inside the block
    (thread- and task-local: a :mod:`contextvars` variable).

    >>> with hint_backend('cvxpy', solver='CLARABEL') as chosen:
    ...     print(chosen, get_hint_backend() is chosen)
    CvxpyHint(solver='CLARABEL') True
    >>> get_hint_backend()
    HighsHint()
    """
    chosen = resolve_hint_backend(backend, **options)
    token = _current.set(chosen)
    try:
        yield chosen
    finally:
        _current.reset(token)

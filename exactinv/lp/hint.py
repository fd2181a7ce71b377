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
from typing import Any, Iterator

from ..core.moved import moved_names
from .backends import CvxpyHint, HighsHint
from .hint_types import HintBackend

__all__ = [
    "set_hint_backend",
    "get_hint_backend",
    "hint_backend",
    "resolve_hint_backend",
]

# the backend interface lives in exactinv.lp.hint_types, the two backends in exactinv.lp.backends;
# their old spelling here warns
__getattr__ = moved_names(__name__, {**dict.fromkeys(["LPStatus", "Basis", "Hint", "UNKNOWN_HINT", "HintModel"],
                                                     "exactinv.lp.hint_types")})

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

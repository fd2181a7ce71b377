"""The float-hint stage's types: an LP's status, an (untrusted) float hint,
and the interface a hint backend implements (:mod:`exactinv.lp.backends`).

Nothing a backend says is trusted: every hint is reconstructed and verified
in Q by the engine (:mod:`exactinv.lp.solver`).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Callable, Sequence

import numpy as np

__all__ = ["LPStatus", "Basis", "Hint", "UNKNOWN_HINT", "HintModel", "HintBackend"]


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

        >>> from exactinv.lp.backends import HighsHint
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

        >>> from exactinv.lp.backends import HighsHint
        >>> model = HighsHint().model(np.array([[1.0, 1.0]]), [False])
        >>> model.solve(np.array([1.0, 2.0]), np.array([4.0]), [True, True]).x.tolist()
        [0.0, 4.0]
        """

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"

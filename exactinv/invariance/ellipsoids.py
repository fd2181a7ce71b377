"""Invariance of an ellipsoid E = {x : x^T Q x <= 1}, decided exactly (beyond the paper).

* Continuous: E is invariant for x' = Ax iff L = A^T Q + Q A <= 0 (the
  derivative of V(x) = x^T Q x along the flow is x^T L x; if v^T L v > 0 the
  boundary point v/||v||_Q leaves E at once).
* Discrete: A_d E is a subset of E iff Q - A_d^T Q A_d >= 0.

Each is decided by an exact LDL^T (:mod:`exactinv.core.psd`).  When it fails
the witness is a rational *direction* v with v^T Q v = ``norm`` and

* continuous: ``value`` = v^T (A^T Q + Q A) v > 0, so at the boundary point
  x = v / sqrt(norm) the Lyapunov derivative is value / norm > 0;
* discrete: ``value`` = v^T (A_d^T Q A_d - Q) v > 0, so the boundary point
  x = v / sqrt(norm) is mapped to A_d x with (A_d x)^T Q (A_d x) = 1 + value / norm > 1.

(The boundary point itself is in general irrational; every statement about
it is a statement about v, scaled.)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from exactinv_check.format import ClaimType

from ..core.encode import mat, vec
from ..core.flintq import fmpq_matrix, matrix_of
from ..core.latex import LatexMixin, latex_column
from ..core.psd import LDLT, psd_decision, quadratic_form
from ..core.scalars import Matrix, Vector, vector_text
from ..errors import InvalidInput
from ..model import Ellipsoid, LinearSystem
from ..model.ellipsoid import lyapunov_matrix
from ..model.record import certificate as make_certificate
from ..model.sets import expect_set
from ..model.validate import discrete_map

__all__ = ["QuadraticWitness", "EllipsoidInvariance", "ellipsoid_continuous_invariance",
           "ellipsoid_discrete_invariance", "check_ellipsoid_pair"]


@dataclass(frozen=True)
class QuadraticWitness:
    """A rational direction ``v`` with ``norm`` = v^T Q v > 0 and ``value`` > 0
    (see the module docstring): x = v / sqrt(norm) is a boundary point of E that leaves E."""

    v: Vector
    value: Fraction
    norm: Fraction

    def record(self) -> dict:
        """The certificate record {"v", "value"} (``norm`` is recomputed by the checker).

        >>> QuadraticWitness((Fraction(3, 2), Fraction(1)), Fraction(5, 2), Fraction(13, 4)).record()
        {'v': ['3/2', '1'], 'value': '5/2'}
        """
        return {"v": vec(self.v), "value": str(self.value)}

    def __repr__(self) -> str:
        return f"QuadraticWitness(v={vector_text(self.v)}, value={self.value}, norm={self.norm})"


@dataclass(frozen=True, repr=False)
class EllipsoidInvariance(LatexMixin):
    """Is E invariant (``kind`` "continuous" for x' = Ax, "discrete" for x+ = A_d x)?
    ``proof`` is the exact LDL^T of -(A^T Q + Q A) or of Q - A_d^T Q A_d with
    D >= 0 when it is; ``witness`` a :class:`QuadraticWitness` when it is not."""

    holds: bool
    proof: LDLT | None
    witness: QuadraticWitness | None
    kind: str
    system: LinearSystem | None = field(default=None)
    ellipsoid: Ellipsoid | None = field(default=None)
    Ad: Matrix | None = field(default=None)
    method: Any = field(default=None)
    dt: Fraction | None = None

    def __bool__(self) -> bool:
        return self.holds

    def claims(self) -> list[dict]:
        """The certificate claim: the kind, ``holds``, A_d (and dt) if discrete, the witness if it fails.

        A = [[-1, 3], [0, -1]], Q = I: -(A^T + A) = [[2, -3], [-3, 2]] is indefinite
        (v = (3/2, 1): v^T (A^T + A) v = -9/2 - 2 + 9 = 5/2 > 0).

        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> ellipsoid_continuous_invariance(LinearSystem([[-1, 3], [0, -1]]), E).claims()
        [{'type': 'ellipsoid_continuous_invariance', 'holds': False, 'witness': {'v': ['3/2', '1'], 'value': '5/2'}}]
        >>> ellipsoid_discrete_invariance([["1/2", 0], [0, -1]], E).claims()
        [{'type': 'ellipsoid_discrete_invariance', 'holds': True, 'Ad': [['1/2', '0'], ['0', '-1']]}]
        """
        claim: dict = {"type": ClaimType(f"ellipsoid_{self.kind}_invariance"), "holds": self.holds}
        if self.kind == "discrete":
            claim["Ad"] = mat(self.Ad)
            if self.dt is not None:
                claim["dt"] = str(self.dt)
        if not self.holds:
            claim["witness"] = self.witness.record()
        return [claim]

    @property
    def certificate(self) -> dict | None:
        """The JSON certificate for :func:`exactinv.check` (None for a bare A_d without a system)."""
        if self.system is None:
            return None
        return make_certificate(self.system, self.ellipsoid, self.method, [self])

    certificate_json = certificate

    def to_latex(self) -> str:
        """LaTeX: the exact proof, or the witness direction v.

        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> print(ellipsoid_continuous_invariance(LinearSystem([[-1, 3], [0, -1]]), E).to_latex())
        \\text{not invariant: } v = \\begin{pmatrix} \\frac{3}{2} \\\\ 1 \\end{pmatrix}
        """
        if self.holds:
            return r"\text{invariant (exact } LDL^T,\ D \ge 0)"
        return rf"\text{{not invariant: }} v = {latex_column(self.witness.v)}"

    def __repr__(self) -> str:
        name = f"EllipsoidInvariance[{self.kind}]"
        if self.holds:
            return f"{name}(holds=True, {self.proof!r})"
        return f"{name}(holds=False, witness={self.witness!r})"


def check_ellipsoid_pair(system: Any, ellipsoid: Any) -> tuple[LinearSystem, Ellipsoid]:
    """(system, ellipsoid), if both have the right type and dimension (else InvalidInput).

    >>> check_ellipsoid_pair(LinearSystem([[-1, 3], [0, -1]]), Ellipsoid([[2, 0], [0, "1/2"]]))
    (LinearSystem(A=[[-1, 3], [0, -1]]), Ellipsoid(Q=[[2, 0], [0, 1/2]]))
    >>> check_ellipsoid_pair(LinearSystem([[-1]]), Ellipsoid([[1, 0], [0, 1]]))
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: system/ellipsoid: A is 1x1 but Q is 2x2
    """
    if not isinstance(system, LinearSystem):
        raise InvalidInput(f"system: expected an exactinv.LinearSystem, got {type(system).__name__}")
    expect_set(ellipsoid, "ellipsoid", "ellipsoid")
    if system.n != ellipsoid.n:
        raise InvalidInput(f"system/ellipsoid: A is {system.n}x{system.n} but Q is {ellipsoid.n}x{ellipsoid.n}")
    return system, ellipsoid


def _witness(Q: Matrix, v: Vector, value: Fraction) -> QuadraticWitness:
    return QuadraticWitness(v, value, quadratic_form(Q, v))


def ellipsoid_continuous_invariance(system: LinearSystem, ellipsoid: Ellipsoid) -> EllipsoidInvariance:
    """Decide exactly whether E is invariant for x' = Ax: -(A^T Q + Q A) >= 0 by LDL^T.

    >>> E = Ellipsoid([[1, 0], [0, 1]])
    >>> ellipsoid_continuous_invariance(LinearSystem([[-1, -2], [2, -1]]), E).holds
    True
    >>> ellipsoid_continuous_invariance(LinearSystem([[-1, 3], [0, -1]]), E).witness
    QuadraticWitness(v=[3/2, 1], value=5/2, norm=13/4)
    """
    S, E = check_ellipsoid_pair(system, ellipsoid)
    L = lyapunov_matrix(S.A, E.Q)
    d = psd_decision([[-x for x in row] for row in L])
    if d.psd:
        return EllipsoidInvariance(True, d.proof, None, "continuous", S, E)
    return EllipsoidInvariance(False, None, _witness(E.Q, d.witness, -d.value), "continuous", S, E)


def ellipsoid_discrete_invariance(Ad: Any, ellipsoid: Ellipsoid, method: Any = None, dt: Any = None, *,
                                  allow_float: bool = False) -> EllipsoidInvariance:
    """Decide exactly whether A_d E is a subset of E: Q - A_d^T Q A_d >= 0 by LDL^T.

    ``Ad`` is the matrix A_d, or a LinearSystem with ``method`` and a rational
    ``dt`` (then A_d = r(dt A) exactly, and the certificate names dt).

    >>> E = Ellipsoid([[1, 0], [0, 1]])
    >>> ellipsoid_discrete_invariance([["1/2", 0], [0, "-1"]], E).holds
    True
    >>> ellipsoid_discrete_invariance([[0, 2], [0, 0]], E).witness
    QuadraticWitness(v=[0, 1], value=3, norm=1)
    """
    expect_set(ellipsoid, "ellipsoid", "ellipsoid")
    if isinstance(Ad, LinearSystem):
        check_ellipsoid_pair(Ad, ellipsoid)
    Adm, origin = discrete_map(Ad, method, dt, ellipsoid.n, "E", allow_float)
    A = fmpq_matrix(Adm)
    M = matrix_of(ellipsoid.Q_flint - A.transpose() * ellipsoid.Q_flint * A)
    d = psd_decision(M)
    if d.psd:
        return EllipsoidInvariance(True, d.proof, None, "discrete", ellipsoid=ellipsoid, Ad=Adm, **origin)
    return EllipsoidInvariance(False, None, _witness(ellipsoid.Q, d.witness, -d.value), "discrete",
                               ellipsoid=ellipsoid, Ad=Adm, **origin)

"""Invariance of a polyhedron (paper, Section 2); gamma* is in :mod:`exactinv.invariance.gamma_star`.

* Continuous invariance: P = {x : Gx <= b} is invariant for x' = Ax iff there
  is H with nonnegative off-diagonal entries, HG = GA and Hb <= 0.
* Discrete invariance: P is invariant for x+ = A_d x iff there is an
  entrywise nonnegative H~ with H~G = GA_d and H~b <= b.
* gamma* = min{gamma : H + gamma I >= 0, HG = GA, Hb <= 0}.

All three are answered row by row with the exact LP engine (:mod:`exactinv.lp`);
every returned certificate has been re-checked in Q.  When invariance fails
the result carries an exact witness instead: a point of P where the flow (or
the map) leaves P through a facet.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint

from exactinv_check.format import ClaimType

from ..core.encode import mat, sparse_of_dense
from ..core.flintq import fmpq_matrix, fraction_of
from ..core.latex import LatexMixin, latex_column, latex_matrix
from ..core.scalars import Matrix, matrix_text
from ..errors import EmptyPolyhedron, VerificationFailed
from ..lp import INFEASIBLE, UNBOUNDED, ExactLPSolver
from ..model import LinearSystem, Polyhedron
from ..model.record import certificate as make_certificate
from ..model.validate import check_polyhedron, discrete_map
from .gamma_star import OptimalGamma, optimal_gamma
from .witness import FacetWitness, push_along_ray

__all__ = [
    "FacetWitness",
    "ContinuousInvariance",
    "DiscreteInvariance",
    "OptimalGamma",
    "continuous_invariance",
    "discrete_invariance",
    "optimal_gamma",
]


class _Invariance(LatexMixin):
    """What the continuous and the discrete answer share: ``holds``, the
    certificate matrix ``H`` or the ``witness``, and their claim."""

    holds: bool
    H: Matrix | None
    witness: FacetWitness | None
    _kind = ""
    _H_name = "H"
    _H_text = "H"

    def __bool__(self) -> bool:
        return self.holds

    @property
    def certificate(self) -> Matrix | None:
        """Deprecated alias of :attr:`H` (the JSON certificate is ``certificate_json``)."""
        return self.H

    def _claim(self, **data) -> list[dict]:
        claim = {"type": self._kind, "holds": self.holds, **data}
        if self.holds:
            claim["H"] = sparse_of_dense(self.H)  # certificate version 3: the nonzero entries by row
        else:
            claim["witness"] = self.witness.record()
        return [claim]

    def to_latex(self) -> str:
        if self.holds:
            return rf"\text{{invariant}},\ {self._H_name} = {latex_matrix(self.H)}"
        w = self.witness
        return rf"\text{{not invariant: }} x = {latex_column(w.x)},\ \text{{facet {w.facet}}}"

    def __repr__(self) -> str:
        name = type(self).__name__
        if self.holds:
            return f"{name}(holds=True, {self._H_text}={matrix_text(self.H)})"
        return f"{name}(holds=False, witness={self.witness!r})"


@dataclass(frozen=True, repr=False)
class ContinuousInvariance(_Invariance):
    """Is P invariant for x' = Ax?  ``H`` is an exact H (off-diagonal
    >= 0, HG = GA, Hb <= 0) when it is, ``witness`` a :class:`FacetWitness`
    when it is not.  ``certificate_json`` is the JSON certificate;
    ``certificate`` is kept as an alias of ``H`` (deprecated name)."""

    holds: bool
    H: Matrix | None
    witness: FacetWitness | None
    system: LinearSystem = field(repr=False)
    polyhedron: Polyhedron = field(repr=False)
    _kind = ClaimType.CONTINUOUS_INVARIANCE

    @property
    def certificate_json(self) -> dict:
        """The JSON certificate of this claim for :func:`exactinv.check`."""
        return make_certificate(self.system, self.polyhedron, None, [self])

    def claims(self) -> list[dict]:
        """The continuous_invariance claim: H, or the facet witness.

        x' = -x on P = [-1, 1] (G = (1, -1)^T, b = (1, 1)): HG = GA gives
        h11 = h12 - 1, h22 = h21 - 1, and Hb <= 0 gives h12, h21 <= 1/2.

        >>> P = Polyhedron([[1], [-1]], [1, 1])
        >>> continuous_invariance(LinearSystem([[-1]]), P).claims()[0]["holds"]
        True
        >>> continuous_invariance(LinearSystem([[1]]), P).claims()   # x' = x leaves through x = 1
        [{'type': 'continuous_invariance', 'holds': False, 'witness': {'x': ['1'], 'facet': 0, 'value': '1'}}]
        """
        return self._claim()


@dataclass(frozen=True, repr=False)
class DiscreteInvariance(_Invariance):
    """Is P invariant for x+ = A_d x?  ``H`` is an exact H~ >= 0 with
    H~G = GA_d and H~b <= b, or ``witness`` a point x in P with A_d x not in P
    (``witness.facet`` the violated row).  ``certificate`` is kept as an
    alias of ``H`` (deprecated name)."""

    holds: bool
    H: Matrix | None
    witness: FacetWitness | None
    Ad: Matrix = field(repr=False)
    polyhedron: Polyhedron = field(repr=False)
    system: LinearSystem | None = field(default=None, repr=False)
    method: Any = field(default=None, repr=False)
    dt: Fraction | None = None
    _kind = ClaimType.DISCRETE_INVARIANCE
    _H_name = r"\tilde H"
    _H_text = "H~"

    def claims(self) -> list[dict]:
        """With dt (A_d = r(dt A) built from a system and a method), the claim names
        dt, and the kernel recomputes A_d itself (certificate version 2); H~ is written by
        rows, its nonzero entries only (version 3).

        Forward Euler with dt = 3 on x' = -x: A_d = 1 - 3 = -2 maps x = -1 in
        P = [-1, 1] to 2 > b_0 = 1.

        >>> from exactinv.model import methods
        >>> P = Polyhedron([[1], [-1]], [1, 1])
        >>> discrete_invariance(LinearSystem([[-1]]), P, methods.forward_euler(), 3).claims()
        [{'type': 'discrete_invariance', 'holds': False, 'Ad': [['-2']], 'dt': '3', 'witness': {'x': ['-1'], 'facet': 0, 'value': '2'}}]
        >>> discrete_invariance([["1/2"]], P).claims()   # H~ = I/2: H~G = G/2, H~b = b/2 <= b
        [{'type': 'discrete_invariance', 'holds': True, 'Ad': [['1/2']], 'H': {'sparse': [[[0, '1/2']], [[1, '1/2']]]}}]
        """  # noqa: E501 (doctest output)
        return self._claim(Ad=mat(self.Ad), **({} if self.dt is None else {"dt": str(self.dt)}))

    @property
    def certificate_json(self) -> dict | None:
        """The JSON certificate (only when A_d = r(dt A) came from a system and a method)."""
        if self.system is None:
            return None
        return make_certificate(self.system, self.polyhedron, self.method, [self])


def continuous_invariance(system: LinearSystem, polyhedron: Polyhedron) -> ContinuousInvariance:
    """Decide exactly whether P is invariant for x' = Ax (paper, Theorem on
    continuous invariance), with an exact H or an exact facet witness.

    >>> P = Polyhedron([[1], [-1]], [1, 1])
    >>> continuous_invariance(LinearSystem([[-1]]), P)
    ContinuousInvariance(holds=True, H=[[-1/2, 1/2], [1/2, -1/2]])
    >>> continuous_invariance(LinearSystem([[1]]), P).witness   # g_0.x = 1 = b_0, g_0.Ax = 1 > 0
    FacetWitness(x=[1], facet=0, value=1)
    """
    g = optimal_gamma(system, polyhedron)
    if g.witness is not None:
        return ContinuousInvariance(False, None, g.witness, g.system, g.polyhedron)
    return ContinuousInvariance(True, g.H, None, g.system, g.polyhedron)


def discrete_invariance(
    Ad: Any,
    polyhedron: Polyhedron,
    method: Any = None,
    dt: Any = None,
    *,
    allow_float: bool = False,
) -> DiscreteInvariance:
    """Decide exactly whether P is invariant for x+ = A_d x.

    ``Ad`` is the matrix A_d, or a :class:`LinearSystem` together with a
    discretization ``method`` and a rational steplength ``dt`` (then A_d =
    r(dt A) is built exactly).  Row j is the LP  max{g_j^T A_d x : x in P}:
    by LP duality its optimal dual is row j of H~ when the optimum is <= b_j,
    and its optimal point is a witness x in P with A_d x not in P otherwise.
    The m LPs share G and are verified as one batch (:meth:`ExactLPSolver.solve_many`).

    On P = [-1, 1], x+ = a x keeps P iff |a| <= 1:

    >>> P = Polyhedron([[1], [-1]], [1, 1])
    >>> discrete_invariance([["1/2"]], P)
    DiscreteInvariance(holds=True, H~=[[1/2, 0], [0, 1/2]])
    >>> discrete_invariance([[-2]], P).witness   # g_0.A_d x = -2 * -1 = 2 > 1
    FacetWitness(x=[-1], facet=0, value=2)
    """
    P = check_polyhedron(polyhedron)
    Adm, origin = discrete_map(Ad, method, dt, P.n, "P", allow_float)
    m, n = P.m, P.n
    GAd = P.G_flint * fmpq_matrix(Adm)
    solver = ExactLPSolver(P.G_flint, [False] * m)
    rhss = flint.fmpq_mat(m, m, [P.b_flint[r, 0] for r in range(m) for _ in range(m)])  # column j: b
    results = solver.solve_many(GAd.transpose(), rhss, [[False] * n] * m)  # column j: A_d^T g_j
    H_rows = []
    for j, res in enumerate(results):
        objective = [fraction_of(GAd[j, i]) for i in range(n)]
        if res.status == UNBOUNDED:
            x = push_along_ray(res.x, res.ray, objective, P.b[j])
            value = sum(c * xi for c, xi in zip(objective, x))
            return DiscreteInvariance(False, None, FacetWitness(x, j, value), Adm, P, **origin)
        if res.status == INFEASIBLE:
            raise EmptyPolyhedron("polyhedron: P = {x : Gx <= b} is empty")
        if res.value > P.b[j]:
            return DiscreteInvariance(False, None, FacetWitness(res.x, j, res.value), Adm, P, **origin)
        H_rows.append(res.y)
    H = tuple(H_rows)
    _recheck_discrete(P, Adm, H)
    return DiscreteInvariance(True, H, None, Adm, P, **origin)


def _recheck_discrete(P: Polyhedron, Ad: Matrix, H: Matrix) -> None:
    Hq = fmpq_matrix(H)
    ok = Hq * P.G_flint == P.G_flint * fmpq_matrix(Ad)
    ok = ok and all(fraction_of(v) <= beta for v, beta in zip((Hq * P.b_flint).entries(), P.b))
    ok = ok and all(v >= 0 for row in H for v in row)
    if not ok:
        raise VerificationFailed("discrete_invariance: the assembled H~ failed its exact re-check")

"""The optimal gamma* (paper, Section 2 and Lemma 3.14).

gamma* = min{gamma : H + gamma I >= 0, HG = GA, Hb <= 0}, answered row by row
(one float solve and one exact integer check for all rows, the exact LP engine
:mod:`exactinv.lp` for the rest): row j of H is the optimal dual of
the LP max{g_j^T A x : x in P, g_j^T x = b_j}.  Every returned H has been
re-checked in Q; when continuous invariance fails the result carries an exact
:class:`~exactinv.invariance.witness.FacetWitness` instead.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property, partial
from typing import Callable

import flint
import numpy as np

from exactinv_check.format import ClaimType

from ..core.algebraic import ExactKey
from ..core.encode import encode_real, vec
from ..core.flintq import fmpq_of, fraction_of, matrix_of
from ..core.latex import LatexMixin, latex_column, latex_matrix, latex_real
from ..core.scalars import INF, Infinity, Matrix, Vector
from ..core.sparse import SparseRows
from ..errors import VerificationFailed
from ..lp import OPTIMAL, UNBOUNDED, ExactLPSolver, HighsHint, LPResult, get_hint_backend
from ..model import LinearSystem, Polyhedron
from ..model.record import certificate as make_certificate
from ..model.validate import check_pair
from .gamma_batch import RowBatch, batch_rows, integer_G, is_sparse
from .gamma_dense import DenseRows, dense_rows
from .witness import FacetWitness, push_along_ray

__all__ = ["GammaRow", "OptimalGamma", "optimal_gamma"]


@dataclass(frozen=True)
class GammaRow:
    """The verified row LP j of gamma*:  max h_j  s.t.  h^T G = g_j^T A,
    h^T b <= 0, h_k >= 0 (k != j).  ``gamma = -max h_j`` (``-INF`` when the
    row LP is unbounded, ``INF`` when it is infeasible).  For an optimal row,
    ``dual = (y, lam)`` proves the bound:  g_k.y + lam b_k >= 0 (k != j),
    g_j.y + lam b_j = 1, lam >= 0 and (A^T g_j).y = max h_j.  For an
    unbounded row, ``h`` is feasible and ``ray`` increases h_j.  ``lp_of``
    returns the verified :class:`~exactinv.lp.LPResult` (built on first use
    when the row was proved in a batch of integers)."""

    gamma: Fraction | Infinity
    path: str
    lp_of: Callable[[], LPResult] = field(repr=False, compare=False)

    @cached_property
    def lp(self) -> LPResult:
        """The verified row LP.

        >>> row = optimal_gamma(LinearSystem([[-1]]), Polyhedron([[1], [-1]], [1, 1])).rows[0]
        >>> row.gamma, row.lp.value, row.h, row.dual
        (Fraction(1, 2), Fraction(-1, 2), (Fraction(-1, 2), Fraction(1, 2)), ((Fraction(1, 2),), Fraction(1, 2)))
        """
        return self.lp_of()

    @property
    def h(self) -> Vector | None:
        return self.lp.x

    @property
    def ray(self) -> Vector | None:
        return self.lp.ray

    @property
    def dual(self) -> tuple[Vector, Fraction] | None:
        if self.lp.y is None:
            return None
        y = self.lp.y
        return tuple(y[:-1]), y[-1]


@dataclass(frozen=True)
class OptimalGamma(LatexMixin):
    """gamma* = min{gamma : H + gamma I >= 0, HG = GA, Hb <= 0}, exactly.

    ``H_sparse`` is H by rows, its nonzero entries only (at most n + 1 per row:
    a :class:`~exactinv.core.sparse.SparseRows`); ``H_flint`` and ``H`` are the
    dense m x m matrix, built only when asked for (the engine never needs it).
    ``value`` is a Fraction, ``INF`` (P is not invariant; ``witness`` then
    holds a :class:`FacetWitness`) or ``-INF`` (every row LP is unbounded,
    e.g. for a lower-dimensional P).  ``H`` attains the value (for a finite
    gamma*: H + gamma* I >= 0); ``binding_row`` is the row whose LP dual
    ``dual`` proves that no smaller gamma is feasible.  ``rows`` holds every
    verified row LP and ``paths`` counts which engine route produced them.
    """

    value: Fraction | Infinity
    H_of: Callable[[], SparseRows | None] = field(repr=False, compare=False)
    binding_row: int | None
    rows: tuple[GammaRow, ...] = field(repr=False)
    witness: FacetWitness | None
    system: LinearSystem = field(repr=False)
    polyhedron: Polyhedron = field(repr=False)

    @cached_property
    def H_sparse(self) -> SparseRows | None:
        """The exact certificate H by rows, nonzero entries only (built on first use from the proved rows).

        >>> optimal_gamma(LinearSystem([[-1]]), Polyhedron([[1], [-1]], [1, 1])).H_sparse.rows
        (((0, -1/2), (1, 1/2)), ((0, 1/2), (1, -1/2)))
        """
        return self.H_of()

    @cached_property
    def H_flint(self) -> flint.fmpq_mat | None:
        """The exact certificate H as a dense fmpq matrix (m x m: built only on request).

        >>> optimal_gamma(LinearSystem([[-1]]), Polyhedron([[1], [-1]], [1, 1])).H_flint
        [-1/2,  1/2]
        [ 1/2, -1/2]
        """
        return None if self.H_sparse is None else self.H_sparse.to_flint()

    @cached_property
    def H(self) -> Matrix | None:
        """The exact certificate H (Fractions)."""
        return None if self.H_flint is None else matrix_of(self.H_flint)

    @property
    def dual(self) -> tuple[Vector, Fraction] | None:
        """(y, lambda) of the binding row: the proof that gamma* is not smaller."""
        return None if self.binding_row is None else self.rows[self.binding_row].dual

    @property
    def paths(self) -> dict[str, int]:
        counts: dict[str, int] = {}
        for row in self.rows:
            counts[row.path] = counts.get(row.path, 0) + 1
        return counts

    @property
    def certificate(self) -> dict:
        """The JSON certificate (H and the binding row's dual, the rays, or
        the witness) for :func:`exactinv.check`."""
        return make_certificate(self.system, self.polyhedron, None, [self])

    def claims(self) -> list[dict]:
        """The gamma_star claim: the witness, the rows' points and rays (-oo),
        or H with the binding row's dual.

        x' = -x on P = [-1, 1]: row 0 is max h_0 s.t. h_0 - h_1 = -1,
        h_0 + h_1 <= 0, h_1 >= 0, so h = (-1/2, 1/2) and gamma* = 1/2; its dual
        (y, lambda) = (1/2, 1/2) has y + lambda = 1 (row 0), -y + lambda = 0 >= 0
        (row 1) and (A^T g_0) y = -1/2 = max h_0.

        >>> P = Polyhedron([[1], [-1]], [1, 1])
        >>> c = optimal_gamma(LinearSystem([[-1]]), P).claims()[0]
        >>> c["value"], c["H"], c["binding_row"], c["dual"]
        ('1/2', {'sparse': [[[0, '-1/2'], [1, '1/2']], [[0, '1/2'], [1, '-1/2']]]}, 0, {'y': ['1/2'], 'lambda': '1/2'})
        >>> optimal_gamma(LinearSystem([[1]]), P).claims()[0]["witness"]
        {'x': ['1'], 'facet': 0, 'value': '1'}
        """
        claim = {"type": ClaimType.GAMMA_STAR, "value": encode_real(self.value), "paths": self.paths}
        if self.witness is not None:
            claim["witness"] = self.witness.record()
        elif isinstance(self.value, Infinity):  # -oo: a point and a ray per row
            claim["rows"] = [{"h": vec(r.h), "ray": vec(r.ray)} for r in self.rows]
            claim["H"] = self.H_sparse.encode()
        else:
            y, lam = self.dual
            claim.update(H=self.H_sparse.encode(), binding_row=self.binding_row, dual={"y": vec(y), "lambda": str(lam)})
        return [claim]

    def to_latex(self) -> str:
        """LaTeX: gamma* with H, or gamma* = oo with the facet witness.

        >>> P = Polyhedron([[1], [-1]], [1, 1])
        >>> print(optimal_gamma(LinearSystem([[-1]]), P).to_latex())
        \\gamma^* = \\frac{1}{2}, \\quad H = \\begin{pmatrix} -\\frac{1}{2} & \\frac{1}{2} \\\\ \\frac{1}{2} & -\\frac{1}{2} \\end{pmatrix}
        """  # noqa: E501 (doctest output)
        if self.witness is not None:
            w = self.witness
            return (rf"\gamma^* = \infty \text{{ (not invariant: }} x = {latex_column(w.x)}"
                    rf"\text{{ on facet {w.facet}, }} g^T A x = {latex_real(w.value)} > 0)")
        return rf"\gamma^* = {latex_real(self.value)}, \quad H = {latex_matrix(self.H)}"

    @property
    def forward_euler_step(self) -> Fraction | Infinity:
        """1/gamma*: the largest forward-Euler steplength (INF when gamma* <= 0)."""
        if isinstance(self.value, Infinity):
            return INF if self.value.sign < 0 else Fraction(0)
        return INF if self.value <= 0 else 1 / self.value

    def __repr__(self) -> str:
        if self.witness is not None:
            return f"OptimalGamma(value=INF, not invariant, witness={self.witness!r})"
        return f"OptimalGamma(value={self.value!r}, binding_row={self.binding_row}, paths={self.paths})"


def optimal_gamma(system: LinearSystem, polyhedron: Polyhedron) -> OptimalGamma:
    """gamma* of the paper (Section 2), solved as m independent verified row LPs.

    Row j of H only meets row j of the constraints, so
    gamma* = max_j ( -max{h_j : h^T G = g_j^T A, h^T b <= 0, h_k >= 0 (k != j)} ).
    The m row LPs share their constraint matrix [G^T; b^T]: for a sparse G
    they are solved in float as ONE block-diagonal LP
    (:mod:`~exactinv.invariance.gamma_batch`), otherwise by one HiGHS model
    warm-started from row to row (:mod:`~exactinv.invariance.gamma_dense`); either
    way all rows are then proved optimal in one exact integer check.  Rows
    that check fails, other hint backends, and infeasible or unbounded rows go
    through the general engine (:mod:`exactinv.lp`).  Exact: every row value
    is verified by primal and dual certificates in Q.

    x' = -x on [-1, 1]: gamma* = 1/2, so forward Euler keeps P for h <= 2
    (1 - h >= -1); x' = x is not invariant (gamma* = oo, witness x = 1).

    >>> P = Polyhedron([[1], [-1]], [1, 1])
    >>> g = optimal_gamma(LinearSystem([[-1]]), P)
    >>> g.value, g.forward_euler_step
    (Fraction(1, 2), Fraction(2, 1))
    >>> optimal_gamma(LinearSystem([[1]]), P)
    OptimalGamma(value=INF, not invariant, witness=FacetWitness(x=[1], facet=0, value=1))
    """
    S, P = check_pair(system, polyhedron)
    batch = _row_batch(S, P)
    if batch is not None and batch.ok.all():
        return _from_batch(S, P, batch)
    proved = {} if batch is None else {j: _batch_row(batch, j) for j in np.flatnonzero(batch.ok).tolist()}
    rows = _solve_rows(S, P, [j for j in range(P.m) if j not in proved])
    rows = [proved[j] if j in proved else rows.pop(0) for j in range(P.m)]
    if any(row.gamma == INF for row in rows):
        witness = _continuous_witness(S, P, first=[j for j, r in enumerate(rows) if r.gamma == INF])
        return OptimalGamma(INF, _none, None, tuple(rows), witness, S, P)
    value = max((row.gamma for row in rows), key=ExactKey)
    binding = None if value == -INF else next(j for j, r in enumerate(rows) if r.gamma == value)
    H = _assemble_H(rows, value)
    _recheck_continuous(S, P, H, value)
    return OptimalGamma(value, partial(_identity, H), binding, tuple(rows), None, S, P)


def _row_batch(S: LinearSystem, P: Polyhedron) -> RowBatch | DenseRows | None:
    """Every row LP solved in float and proved in one batch: one block-diagonal
    float LP for a sparse G with short integer data, warm-started row solves and
    one FLINT integer check otherwise -- also when the sparse route cannot decide
    (long data: no row falls back to the general engine for that) (HiGHS hints only)."""
    if not isinstance(get_hint_backend(), HighsHint) or not P.m or not P.n:
        return None
    G = integer_G(P)
    batch = batch_rows(S, P, G) if is_sparse(G) else None
    return batch if batch is not None else dense_rows(S, P)


def _solve_rows(S: LinearSystem, P: Polyhedron, which: list[int]) -> list[GammaRow]:
    """The row LPs ``which`` through the general engine (warm-started, verified as one batch)."""
    if not which:
        return []
    m, n = P.m, P.n
    GA = P.G_flint * S.A_flint
    constraint = flint.fmpq_mat(n + 1, m, P.G_flint.transpose().entries() + P.b_flint.entries())
    solver = ExactLPSolver(constraint, [True] * n + [False])
    costs = flint.fmpq_mat(m, len(which))  # column t: e_j for j = which[t]
    for t, j in enumerate(which):
        costs[j, t] = 1
    GA_rows = GA.entries()  # row j: A^T g_j
    rhss = flint.fmpq_mat(len(which), n + 1, [v for j in which for v in GA_rows[j * n:(j + 1) * n] + [0]]).transpose()
    signs = [[k != j for k in range(m)] for j in which]
    return [_gamma_row(res) for res in solver.solve_many(costs, rhss, signs)]


def _from_batch(S: LinearSystem, P: Polyhedron, batch: RowBatch | DenseRows) -> OptimalGamma:
    """gamma* from a batch in which every row is proved optimal: H = Hn/D has
    every row checked (primal feasible, H_jj = -gamma_j >= -gamma*), and the
    binding row's dual proves the value; nothing is re-checked."""
    rows = tuple(_batch_row(batch, j) for j in range(P.m))
    value = max(row.gamma for row in rows)
    binding = next(j for j, row in enumerate(rows) if row.gamma == value)
    return OptimalGamma(value, batch.H_rows, binding, rows, None, S, P)


def _batch_row(batch: RowBatch | DenseRows, j: int) -> GammaRow:
    return GammaRow(batch.gamma(j), batch.path(j), partial(batch.result, j))


def _gamma_row(res: LPResult) -> GammaRow:
    if res.status == OPTIMAL:
        return GammaRow(-res.value, res.path, partial(_identity, res))
    return GammaRow(-INF if res.status == UNBOUNDED else INF, res.path, partial(_identity, res))


def _identity(value):
    return value


def _none() -> None:
    return None


def _assemble_H(rows: list[GammaRow], gamma) -> SparseRows:
    """H from the row LPs, by rows (nonzero entries only); an unbounded row is pushed along its
    ray until h_jj >= -gamma* (for gamma* = -INF: h_jj >= 0, any gamma >= 0 then works)."""
    out = []
    target = flint.fmpq(0) if isinstance(gamma, Infinity) else -fmpq_of(gamma)
    for j, row in enumerate(rows):
        h = row.lp.x_q
        ray = row.lp.ray_q
        if ray is not None and h[j, 0] < target:
            h = h + ray * ((target - h[j, 0]) / ray[j, 0])
        out.append([(k, v) for k, v in enumerate(h.entries()) if v != 0])
    return SparseRows.of_rows(len(rows), out)


def _continuous_witness(S: LinearSystem, P: Polyhedron, first: list[int]) -> FacetWitness:
    """A point x in P with g_j.x = b_j and g_j.Ax > 0, from the facet LPs
    max{g_j^T A x : x in P, g_j^T x = b_j} (rows whose gamma LP failed first).
    For a nonempty P such a facet exists whenever some row LP is infeasible
    (Farkas' lemma; see docs)."""
    GA = P.G_flint * S.A_flint
    order = first + [j for j in range(P.m) if j not in first]
    for j in order:
        solver = ExactLPSolver(P.G_flint, [k == j for k in range(P.m)])
        objective = [fraction_of(GA[j, i]) for i in range(P.n)]
        res = solver.solve(objective, P.b, [False] * P.n)
        if res.status == UNBOUNDED:
            x = push_along_ray(res.x, res.ray, objective, Fraction(0))
            return FacetWitness(x, j, sum(c * xi for c, xi in zip(objective, x)))
        if res.status == OPTIMAL and res.value > 0:
            return FacetWitness(res.x, j, res.value)
    raise VerificationFailed("continuous invariance: a row LP is infeasible but no facet witness was found")


def _recheck_continuous(S: LinearSystem, P: Polyhedron, H: SparseRows, gamma) -> None:
    """HG = GA, Hb <= 0, off-diagonal >= 0 and H + gamma I >= 0, over H's nonzero entries (exact)."""
    n = P.n
    G_entries = P.G_flint.entries()
    G_rows = [G_entries[k * n:(k + 1) * n] for k in range(P.m)]
    GA = (P.G_flint * S.A_flint).entries()
    zero = flint.fmpq(0)
    ok = all(x >= 0 for i, row in enumerate(H.rows) for k, x in row if k != i)
    ok = ok and all(v <= 0 for v in H.times(P.b))
    for i, row in enumerate(H.rows):
        if not ok:
            break
        ok = [sum((x * G_rows[k][c] for k, x in row), zero) for c in range(n)] == GA[i * n:(i + 1) * n]
    if not isinstance(gamma, Infinity):
        g = fmpq_of(gamma)
        ok = ok and all(h + g >= 0 for h in H.diagonal())
    if not ok:
        raise VerificationFailed("optimal_gamma: the assembled H failed its exact re-check")

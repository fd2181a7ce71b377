"""gamma*'s m row LPs for a dense G: warm-started float solves, exact basis
solves, and one FLINT check of all rows with a denominator per row.

Row LP j and its dual are those of :mod:`~exactinv.invariance.gamma_batch`; so are
the three checks (primal, dual, equal objectives) that prove row j optimal.
Here every row is solved in float by HiGHS (one model, warm-started from row
to row), rounded to multiples of 1/5040 or else solved exactly on its optimal
basis, so h_j lives on its basic columns (at most n + 1 of the m).  The rows
are then checked together in integers: with G = Gn/dG, b = bn/db, A = An/dA,
h_j = Hn_j/d_j and (y_j, lam_j) = Wn_j/e_j,

* primal  -- dA (Hn Gn)_j = d_j (Gn An)_j,  (Hn bn)_j <= 0,  Hn_jk >= 0 (k != j);
* dual    -- K = [db Gn | dG bn] Wn^T has K_jj = dG db e_j and K_kj >= 0
  (k != j), and lam_j >= 0;
* optimal -- d_j (Gn An)_j . (Wn_j without lam) = dG dA e_j Hn_jj.

FLINT matrix products of integers (no size limit) and one sign test per
entry: exact; the m x m products are never formed (the primal checks run over
each row's support, the dual ones in blocks of 64 rows).  Long data is
scaled to integers once (Gn, bn, An and their common denominators).  A row
whose float hint fails (HiGHS "unknown" after a retry from a fresh model) or
misleads (ill-conditioned data: the check fails) is solved alone by PPL's
exact simplex -- the row LP has only n + 1 rows -- and goes through the same
check; only a row that fails even then goes through the general engine.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from operator import mul

import flint
import numpy as np

from ..core.float_hint import float_hints
from ..core.sparse import SparseRows
from ..lp import OPTIMAL, LPResult
from ..lp.backends import HighsHint
from ..lp.exact import ppl_maximize
from ..lp.floatlp import FloatLP
from ..lp.reconstruct import COMMON_DENOMINATOR, basis_solution, snap_tolerance, snapped_numerators
from ..lp.solver import LPPath
from ..lp.verify import LPData
from ..model import LinearSystem, Polyhedron

__all__ = ["SparseRow", "DenseRows", "dense_rows"]


@dataclass(frozen=True)
class SparseRow:
    """A proposed row: h_j = (numerators ``h`` on columns ``support``)/d and
    (y_j, lam_j) = ``w``/e (n + 1 numerators), found by ``path``."""

    support: tuple[int, ...]
    h: tuple[int, ...]
    d: int
    w: tuple[int, ...]
    e: int
    path: LPPath

    def diagonal(self, j: int) -> int:
        """The numerator of h_jj (0 off the support).

        >>> SparseRow((0, 2), (-3, 1), 2, (1, 1), 2, LPPath.BASIS).diagonal(2)
        1
        """
        return self.h[self.support.index(j)] if j in self.support else 0


@dataclass(frozen=True)
class DenseRows:
    """The proposed rows, and ``ok[j]``: row j proved optimal (gamma_j = -h_jj)."""

    rows: tuple[SparseRow, ...]
    ok: np.ndarray
    m: int

    def gamma(self, j: int) -> Fraction:
        """gamma_j = -h_jj of a proved row.

        >>> DenseRows((SparseRow((0,), (-3,), 2, (1, 1), 2, LPPath.BASIS),), np.array([True]), 1).gamma(0)
        Fraction(3, 2)
        """
        return Fraction(-self.rows[j].diagonal(j), self.rows[j].d)

    def path(self, j: int) -> LPPath:
        """How row j was reconstructed (rounded, or solved on its basis).

        >>> DenseRows((SparseRow((0,), (-3,), 2, (1, 1), 2, LPPath.BASIS),), np.array([True]), 1).path(0)
        <LPPath.BASIS: 'float-basis'>
        """
        return self.rows[j].path

    def result(self, j: int) -> LPResult:
        """Row j as a verified :class:`~exactinv.lp.LPResult`.

        >>> rows = DenseRows((SparseRow((0,), (-3,), 2, (4, 1), 2, LPPath.BASIS),), np.array([True]), 1)
        >>> rows.result(0).x, rows.result(0).y
        ((Fraction(-3, 2),), (Fraction(2, 1), Fraction(1, 2)))
        """
        row = self.rows[j]
        x = flint.fmpq_mat(self.m, 1)
        for k, v in zip(row.support, row.h):
            x[k, 0] = flint.fmpq(v, row.d)
        y = flint.fmpq_mat(len(row.w), 1, [flint.fmpq(v, row.e) for v in row.w])
        return LPResult(OPTIMAL, -self.gamma(j), x, y, None, row.path)

    def H_rows(self) -> SparseRows:
        """H by rows, row j = h_j on its support (no m x m object).

        >>> DenseRows((SparseRow((0,), (-3,), 2, (4, 1), 2, LPPath.BASIS),), np.array([True]), 1).H_rows().rows
        (((0, -3/2),),)
        """
        return SparseRows.of_rows(self.m, ([(k, flint.fmpq(v, row.d)) for k, v in zip(row.support, row.h)]
                                           for row in self.rows))


def dense_rows(system: LinearSystem, polyhedron: Polyhedron) -> DenseRows | None:
    """All m row LPs: HiGHS hints warm-started row to row, rounded or solved
    on their basis, then proved together (module docstring).  A row without an
    optimal float hint (after one retry from a fresh model) is not proved here
    (``ok[j]`` False: the general engine decides that LP); None if no row has one.

    >>> rows = dense_rows(LinearSystem([[-1]]), Polyhedron.box([-1], [1]))
    >>> rows.ok.tolist(), rows.gamma(0), rows.result(0).y
    ([True, True], Fraction(1, 2), (Fraction(1, 2), Fraction(1, 2)))
    """
    m, n = polyhedron.m, polyhedron.n
    G, b, A = polyhedron.G_flint, polyhedron.b_flint, system.A_flint
    constraint = flint.fmpq_mat(n + 1, m, G.transpose().entries() + b.entries())
    data = LPData(constraint, (True,) * n + (False,))
    float_lp = FloatLP(constraint, data.equality, HighsHint())
    GA = G * A
    GA_rows = GA.entries()
    GA_float = float_hints(GA_rows).reshape(m, n) if n else np.zeros((m, 0))
    if not np.all(np.isfinite(GA_float)):  # beyond double range: no float hints, the exact route
        return None
    rows, hinted = [], np.ones(m, dtype=bool)
    for j in range(m):
        cost = np.zeros(m)
        cost[j] = 1.0
        hint = float_lp.solve_floats(cost, np.append(GA_float[j], 0.0), np.arange(m) != j)
        if hint.status != OPTIMAL:  # a warm start gone astray (HiGHS: status unknown): once more, from a fresh model
            hint = float_lp.solve_floats(cost, np.append(GA_float[j], 0.0), np.arange(m) != j)
        if hint.status != OPTIMAL:  # this row alone is left to the general engine
            hinted[j] = False
            rows.append(SparseRow((), (), 1, (0,) * (n + 1), 1, LPPath.BASIS))
            continue
        rhs = flint.fmpq_mat(n + 1, 1, GA_rows[j * n:(j + 1) * n] + [0])
        rows.append(_proposal(data, j, rhs, hint))
    if not hinted.any():
        return None
    ok = _verify(system, polyhedron, GA, rows) & hinted
    failed = np.flatnonzero(~ok).tolist()
    for j in failed:  # the float hint misled (ill-conditioned data): the row LP alone, exactly, then the same check
        rhs = flint.fmpq_mat(n + 1, 1, GA_rows[j * n:(j + 1) * n] + [0])
        repaired = _exact_proposal(data, constraint, j, rhs)
        if repaired is not None:
            rows[j] = repaired
    if failed:
        ok[failed] = _verify(system, polyhedron, GA, rows, failed)[failed]
    return DenseRows(tuple(rows), ok, m)


def _proposal(data: LPData, j: int, rhs: flint.fmpq_mat, hint) -> SparseRow:
    """Row j rounded to multiples of 1/5040, else solved on the hint's basis
    (a row that has neither is proposed as zero and fails the check)."""
    tol = snap_tolerance(hint.has_basis)
    x, w = snapped_numerators(hint.x, tol), snapped_numerators(hint.y, tol)
    if x is not None and w is not None:
        support = tuple(np.flatnonzero(x).tolist())
        return SparseRow(support, tuple(x[k] for k in support), COMMON_DENOMINATOR, tuple(w), COMMON_DENOMINATOR,
                         LPPath.ROUNDED)
    cost = flint.fmpq_mat(data.N, 1)
    cost[j, 0] = 1
    pair, basis = None, _support_basis(data, j, hint, tol)
    if basis is not None:
        pair = basis_solution(data, cost, rhs, basis)
    if pair is None:
        basis = hint.fetch_basis()
        pair = None if basis is None else basis_solution(data, cost, rhs, basis)
    if pair is None:
        return SparseRow((), (), 1, (0,) * data.R, 1, LPPath.BASIS)
    xq, yq = pair
    support = tuple(k for k in basis[0] if xq[k, 0] != 0)
    h, d = flint.fmpq_mat(len(support), 1, [xq[k, 0] for k in support]).numer_denom()
    w, e = yq.numer_denom()
    return SparseRow(support, tuple(map(int, h.entries())), int(d), tuple(map(int, w.entries())), int(e), LPPath.BASIS)


def _exact_proposal(data: LPData, constraint: flint.fmpq_mat, j: int, rhs: flint.fmpq_mat) -> SparseRow | None:
    """Row j by PPL's exact simplex (the row LP has n + 1 rows: a few hundredths of a second at
    m = 1000), its dual from the basis on the optimal point's support: a proposal for the same
    integer check (None: not optimal, or a degenerate support that gives no square basis)."""
    m = data.N
    cost = flint.fmpq_mat(m, 1)
    cost[j, 0] = 1
    status, x = ppl_maximize(constraint, data.equality, rhs, cost, [k != j for k in range(m)])
    if status != OPTIMAL:
        return None
    cols = tuple(sorted({k for k in range(m) if x[k, 0] != 0} | {j}))
    equalities = tuple(data.eq_rows)
    for rows in (equalities + (data.R - 1,), equalities):
        if len(rows) == len(cols):
            pair = basis_solution(data, cost, rhs, (cols, rows))
            if pair is not None:
                xq, yq = pair
                support = tuple(k for k in cols if xq[k, 0] != 0)
                h, d = flint.fmpq_mat(len(support), 1, [xq[k, 0] for k in support]).numer_denom()
                w, e = yq.numer_denom()
                return SparseRow(support, tuple(map(int, h.entries())), int(d), tuple(map(int, w.entries())), int(e),
                                 LPPath.PPL)
    return None


def _support_basis(data: LPData, j: int, hint, tol: float):
    """The basis read off the float point when it is not degenerate: the
    columns off zero (and the free column j) against the tight rows; None if
    they are not as many (then HiGHS' own basis is fetched).  A guess: solved and verified."""
    scale = max(1.0, float(np.abs(hint.x).max()))
    cols = set(np.flatnonzero(np.abs(hint.x) > tol * scale).tolist()) | {j}
    rows = list(data.eq_rows)
    if hint.y[-1] != 0:  # the row b^T h <= 0 carries a dual: tight
        rows.append(data.R - 1)
    return (tuple(sorted(cols)), tuple(rows)) if len(cols) == len(rows) else None


def _verify(system: LinearSystem, polyhedron: Polyhedron, GA: flint.fmpq_mat, rows: list[SparseRow],
            which: list[int] | None = None) -> np.ndarray:
    """Per row (of ``which``; default all): the three checks of the module docstring, exact (FLINT
    integers).  The primal checks run over each row's support (at most n + 1 entries); the dual
    ones as products of the m x (n + 1) matrix [dG db Gn | dG bn] with blocks of ``_CHUNK`` duals
    -- no m x m matrix.  Rows outside ``which`` are False."""
    m, n = polyhedron.m, polyhedron.n
    (Gn, dG), (bn, db), (An, dA) = (M.numer_denom() for M in (polyhedron.G_flint, polyhedron.b_flint, system.A_flint))
    GAn = Gn * An
    G_entries, GA_rows, b_list = Gn.entries(), GAn.entries(), bn.entries()
    G_rows = [G_entries[k * n:(k + 1) * n] for k in range(m)]
    zero = flint.fmpz(0)
    ok = np.zeros(m, dtype=bool)
    which = list(range(m)) if which is None else list(which)
    for j in which:
        row = rows[j]
        pairs = list(zip(row.support, row.h))
        ok[j] = (all(sum((h * G_rows[k][c] for k, h in pairs), zero) * dA == row.d * GA_rows[j * n + c] for c in range(n))
                 and sum((h * b_list[k] for k, h in pairs), zero) <= 0 and row.w[n] >= 0
                 and all(h >= 0 for k, h in pairs if k != j)
                 and sum(map(mul, GA_rows[j * n:(j + 1) * n], row.w[:n]), zero) * row.d
                 == row.diagonal(j) * dG * dA * row.e)
    GbT = flint.fmpz_mat(n + 1, m, [G_entries[i * n + k] * db for k in range(n) for i in range(m)]
                         + [v * dG for v in b_list])
    for start in range(0, len(which), _CHUNK):
        block = which[start:start + _CHUNK]
        W = flint.fmpz_mat(len(block), n + 1, [v for j in block for v in rows[j].w])
        K = (W * GbT).entries()  # row t: (g_k.y_j + lam_j b_k) dG db e_j over k, j = start + t
        for t, j in enumerate(block):
            if not ok[j]:
                continue
            k_row = K[t * m:(t + 1) * m]
            others = k_row[:j] + k_row[j + 1:]
            ok[j] = k_row[j] == dG * db * rows[j].e and (not others or min(others) >= zero)
    return ok


_CHUNK = 64  # duals checked per FLINT product: a 64 x m block, never m x m

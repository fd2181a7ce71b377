"""Invariance of a polyhedron and the optimal gamma* (paper, Section 2).

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
from functools import cached_property
from typing import Any

import flint

from ..core.algebraic import ExactKey
from ..core.encode import encode_real, mat, vec
from ..core.latex import LatexMixin, latex_column, latex_matrix, latex_real
from ..core.scalars import (
    INF,
    Infinity,
    Matrix,
    Vector,
    fmpq_matrix,
    fmpq_of,
    fraction_of,
    matrix_of,
    matrix_text,
    vector_text,
)
from ..core.tags import ClaimType
from ..errors import EmptyPolyhedron, VerificationFailed
from ..lp import INFEASIBLE, OPTIMAL, UNBOUNDED, ExactLPSolver, LPResult
from ..model import LinearSystem, Polyhedron
from ..model.record import certificate as make_certificate
from ..model.validate import check_pair, check_polyhedron, discrete_map

__all__ = [
    "FacetWitness",
    "ContinuousInvariance",
    "DiscreteInvariance",
    "OptimalGamma",
    "continuous_invariance",
    "discrete_invariance",
    "optimal_gamma",
]


@dataclass(frozen=True)
class FacetWitness:
    """An exact point ``x`` of P and a row ``facet`` of G that certify
    non-invariance.  Continuous case: g_j.x = b_j and g_j.Ax = ``rate`` > 0.
    Discrete case: g_j.A_d x = ``value`` > b_j (so A_d x is not in P)."""

    x: Vector
    facet: int
    value: Fraction

    def record(self) -> dict:
        """The witness as exact strings (for a claim).

        >>> FacetWitness((Fraction(1),), 0, Fraction(1)).record()
        {'x': ['1'], 'facet': 0, 'value': '1'}
        """
        return {"x": vec(self.x), "facet": self.facet, "value": str(self.value)}

    def __repr__(self) -> str:
        return f"FacetWitness(x={vector_text(self.x)}, facet={self.facet}, value={self.value})"


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
            claim["H"] = mat(self.H)
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
        dt, and the kernel recomputes A_d itself (certificate version 2).

        Forward Euler with dt = 3 on x' = -x: A_d = 1 - 3 = -2 maps x = -1 in
        P = [-1, 1] to 2 > b_0 = 1.

        >>> from exactinv.model import methods
        >>> P = Polyhedron([[1], [-1]], [1, 1])
        >>> discrete_invariance(LinearSystem([[-1]]), P, methods.forward_euler(), 3).claims()
        [{'type': 'discrete_invariance', 'holds': False, 'Ad': [['-2']], 'dt': '3', 'witness': {'x': ['-1'], 'facet': 0, 'value': '2'}}]
        >>> discrete_invariance([["1/2"]], P).claims()   # H~ = I/2: H~G = G/2, H~b = b/2 <= b
        [{'type': 'discrete_invariance', 'holds': True, 'Ad': [['1/2']], 'H': [['1/2', '0'], ['0', '1/2']]}]
        """
        return self._claim(Ad=mat(self.Ad), **({} if self.dt is None else {"dt": str(self.dt)}))

    @property
    def certificate_json(self) -> dict | None:
        """The JSON certificate (only when A_d = r(dt A) came from a system and a method)."""
        if self.system is None:
            return None
        return make_certificate(self.system, self.polyhedron, self.method, [self])


@dataclass(frozen=True)
class GammaRow:
    """The verified row LP j of gamma*:  max h_j  s.t.  h^T G = g_j^T A,
    h^T b <= 0, h_k >= 0 (k != j).  ``gamma = -max h_j`` (``-INF`` when the
    row LP is unbounded, ``INF`` when it is infeasible).  For an optimal row,
    ``dual = (y, lam)`` proves the bound:  g_k.y + lam b_k >= 0 (k != j),
    g_j.y + lam b_j = 1, lam >= 0 and (A^T g_j).y = max h_j.  For an
    unbounded row, ``h`` is feasible and ``ray`` increases h_j."""

    gamma: Fraction | Infinity
    lp: LPResult = field(repr=False)

    @property
    def path(self) -> str:
        return self.lp.path

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

    ``value`` is a Fraction, ``INF`` (P is not invariant; ``witness`` then
    holds a :class:`FacetWitness`) or ``-INF`` (every row LP is unbounded,
    e.g. for a lower-dimensional P).  ``H`` attains the value (for a finite
    gamma*: H + gamma* I >= 0); ``binding_row`` is the row whose LP dual
    ``dual`` proves that no smaller gamma is feasible.  ``rows`` holds every
    verified row LP and ``paths`` counts which engine route produced them.
    """

    value: Fraction | Infinity
    H_flint: flint.fmpq_mat | None = field(repr=False)
    binding_row: int | None
    rows: tuple[GammaRow, ...] = field(repr=False)
    witness: FacetWitness | None
    system: LinearSystem = field(repr=False)
    polyhedron: Polyhedron = field(repr=False)

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
        ('1/2', [['-1/2', '1/2'], ['1/2', '-1/2']], 0, {'y': ['1/2'], 'lambda': '1/2'})
        >>> optimal_gamma(LinearSystem([[1]]), P).claims()[0]["witness"]
        {'x': ['1'], 'facet': 0, 'value': '1'}
        """
        claim = {"type": ClaimType.GAMMA_STAR, "value": encode_real(self.value), "paths": self.paths}
        if self.witness is not None:
            claim["witness"] = self.witness.record()
        elif isinstance(self.value, Infinity):  # -oo: a point and a ray per row
            claim["rows"] = [{"h": vec(r.h), "ray": vec(r.ray)} for r in self.rows]
            claim["H"] = mat(self.H)
        else:
            y, lam = self.dual
            m = self.H_flint.nrows()
            H = self.H_flint.entries()
            claim.update(H=[[str(v) for v in H[i * m:(i + 1) * m]] for i in range(m)], binding_row=self.binding_row,
                         dual={"y": vec(y), "lambda": str(lam)})
        return [claim]

    def to_latex(self) -> str:
        """LaTeX: gamma* with H, or gamma* = oo with the facet witness.

        >>> P = Polyhedron([[1], [-1]], [1, 1])
        >>> print(optimal_gamma(LinearSystem([[-1]]), P).to_latex())
        \\gamma^* = \\frac{1}{2}, \\quad H = \\begin{pmatrix} -\\frac{1}{2} & \\frac{1}{2} \\\\ \\frac{1}{2} & -\\frac{1}{2} \\end{pmatrix}
        """
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


# ---------------------------------------------------------------- the API
def optimal_gamma(system: LinearSystem, polyhedron: Polyhedron) -> OptimalGamma:
    """gamma* of the paper (Section 2), solved as m independent verified row LPs.

    Row j of H only meets row j of the constraints, so
    gamma* = max_j ( -max{h_j : h^T G = g_j^T A, h^T b <= 0, h_k >= 0 (k != j)} ).
    The m row LPs share their constraint matrix [G^T; b^T], so one float model
    is warm-started from row to row.  Exact: every row value is verified by
    primal and dual certificates in Q (see :mod:`exactinv.lp`).

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
    m, n = P.m, P.n
    GA = P.G_flint * S.A_flint
    constraint = flint.fmpq_mat(n + 1, m, P.G_flint.transpose().entries() + P.b_flint.entries())
    solver = ExactLPSolver(constraint, [True] * n + [False])
    costs = flint.fmpq_mat(m, m)  # column j: e_j
    for j in range(m):
        costs[j, j] = 1
    rhss = flint.fmpq_mat(n + 1, m, GA.transpose().entries() + [0] * m)  # column j: (A^T g_j, 0)
    signs = [[k != j for k in range(m)] for j in range(m)]
    rows = [_gamma_row(res) for res in solver.solve_many(costs, rhss, signs)]
    if any(row.gamma == INF for row in rows):
        witness = _continuous_witness(S, P, first=[j for j, r in enumerate(rows) if r.gamma == INF])
        return OptimalGamma(INF, None, None, tuple(rows), witness, S, P)
    value = max((row.gamma for row in rows), key=ExactKey)
    binding = None if value == -INF else next(j for j, r in enumerate(rows) if r.gamma == value)
    H = _assemble_H(rows, value)
    _recheck_continuous(S, P, H, value)
    return OptimalGamma(value, H, binding, tuple(rows), None, S, P)


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
            x = _push_along_ray(res.x, res.ray, objective, P.b[j])
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


# ---------------------------------------------------------------- helpers
def _gamma_row(res: LPResult) -> GammaRow:
    if res.status == OPTIMAL:
        return GammaRow(-res.value, res)
    return GammaRow(-INF if res.status == UNBOUNDED else INF, res)


def _assemble_H(rows: list[GammaRow], gamma) -> flint.fmpq_mat:
    """H from the row LPs; an unbounded row is pushed along its ray until
    h_jj >= -gamma* (for gamma* = -INF: h_jj >= 0, any gamma >= 0 then works)."""
    entries = []
    target = flint.fmpq(0) if isinstance(gamma, Infinity) else -fmpq_of(gamma)
    for j, row in enumerate(rows):
        h = row.lp.x_q
        ray = row.lp.ray_q
        if ray is not None and h[j, 0] < target:
            h = h + ray * ((target - h[j, 0]) / ray[j, 0])
        entries.extend(h.entries())
    return flint.fmpq_mat(len(rows), len(rows), entries)


def _push_along_ray(x, ray, objective, bound) -> Vector:
    slope = sum(c * d for c, d in zip(objective, ray))
    now = sum(c * xi for c, xi in zip(objective, x))
    t = max(Fraction(0), (bound - now) / slope) + 1
    return tuple(xi + t * d for xi, d in zip(x, ray))


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
            x = _push_along_ray(res.x, res.ray, objective, Fraction(0))
            return FacetWitness(x, j, sum(c * xi for c, xi in zip(objective, x)))
        if res.status == OPTIMAL and res.value > 0:
            return FacetWitness(res.x, j, res.value)
    raise VerificationFailed("continuous invariance: a row LP is infeasible but no facet witness was found")


def _recheck_continuous(S: LinearSystem, P: Polyhedron, Hq: flint.fmpq_mat, gamma) -> None:
    m = P.m
    ok = Hq * P.G_flint == P.G_flint * S.A_flint and all(v <= 0 for v in (Hq * P.b_flint).entries())
    entries = Hq.entries()
    for i in range(m):  # off-diagonal entries >= 0 (min runs in C)
        row = entries[i * m:(i + 1) * m]
        del row[i]
        ok = ok and (not row or min(row) >= 0)
    if not isinstance(gamma, Infinity):
        g = fmpq_of(gamma)
        ok = ok and all(entries[i * (m + 1)] + g >= 0 for i in range(m))
    if not ok:
        raise VerificationFailed("optimal_gamma: the assembled H failed its exact re-check")


def _recheck_discrete(P: Polyhedron, Ad: Matrix, H: Matrix) -> None:
    Hq = fmpq_matrix(H)
    ok = Hq * P.G_flint == P.G_flint * fmpq_matrix(Ad)
    ok = ok and all(fraction_of(v) <= beta for v, beta in zip((Hq * P.b_flint).entries(), P.b))
    ok = ok and all(v >= 0 for row in H for v in row)
    if not ok:
        raise VerificationFailed("discrete_invariance: the assembled H~ failed its exact re-check")

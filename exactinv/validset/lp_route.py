"""The LP route: exact valid sets from parametric LPs, without a vertex list (docs/design.md, "The LP route").

For a facet i, A_d(h) P is inside P along that facet iff
phi_i(h) = max{g_i A_d(h) x : x in P} <= b_i.  With D(h) = det h_r(hA) and
N(h) = D(h) r(hA) = sum_k h^k N_k (D = 1 for polynomial methods) let
c_i(h) = N(h)^T g_i and, for a basis B (n rows of G, nonsingular, its vertex
x_B = B^-1 b_B in P), z_B(h) = D(h) B^-T c_i(h), a vector of polynomials.
Where z_B(h) >= 0 and D(h) != 0, weak duality gives, for every x in P,
g_i A_d(h) x <= g_i A_d(h) x_B (module :mod:`exactinv.validset.lp_route`'s
design section proves it; the sign of D is folded into z_B).  So the route
splits [0, oo) for each facet into closed pieces [t_k, t_k+1], each with a basis
whose z_B is >= 0 on it; the condition of the piece is the vertex-facet
condition of x_B and facet i,

    p_ik(h) = (b_i D(h) - g_i N(h) x_B) D(h) >= 0,

and the valid set is exactly {h >= 0 : D(h) != 0, every p_ik(h) >= 0} --
each p_ik is necessary (x_B is a point of P), and together they suffice (h lies
in some piece of every facet, where x_B is a maximizer).  These are ordinary
:class:`~exactinv.conditions.polyhedron.Condition` objects, so the valid set,
the largest threshold and their certificates go through the same exact
interval code as the vertex route: the result is identical, end by end and
flag by flag.

The pieces come from the parametric simplex in h, facet by facet: at a
breakpoint t (0 first), a float LP (HiGHS through :class:`~exactinv.lp.floatlp.FloatLP`,
warm-started across facets) at a rational s just right of t proposes a basis,
or the exact LP chain (:class:`~exactinv.lp.solver.ExactLPSolver`) gives a
verified optimum at s from which a basis is read; the basis is accepted only
when every component of z_B is >= 0 just right of t (exact signs, also at an
algebraic t), and the piece then ends at the least root of odd multiplicity
beyond t of any component (certified root isolation).  A basis that fails is a
hint that did not help: s moves closer to t.  At h = 0 the optimal face is the
facet itself, a degenerate LP; "sign just right of 0" is the lexicographic
order of the powers of h, so the accepted basis is the lexicographically
optimal one, with no epsilon.

Unbounded (pointed) P: where the LP of facet i is unbounded, a *ray piece*
carries a ray d of P (G d <= 0) with r(h) = c_i(h)^T d D(h) > 0 on the open
piece, found by the dual simplex step whose ratio test meets no row (then
r = -z_leaving) or by the exact LP chain's verified ray; its condition is the
ray-facet condition -r >= 0, necessary because P is nonempty (the route keeps
a point of P) and violated on the whole piece.  A ray piece ends at every
root of r (so r > 0 on all of it); an end it leaves undecided (r = 0 there,
not a pole) is decided by the next piece: a basis piece, a point piece [t, t]
(a basis optimal at a rational t alone), or a ray piece positive at t (t
moved to a rational just left when irrational).  docs/design.md, "Unbounded
P: rays and lines", has the proofs and the degenerate cases.

The route declines (:class:`LPRouteDeclined`) a P with lines (rank G < n: :mod:`exactinv.validset.lp_lines` takes it) and
the rare irrational point where all of a facet's ray conditions vanish: the
vertex route handles those.  The cost is (facets) x (pieces) LPs and basis
solves, independent of the number of vertices.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any, Callable, TypeVar

import flint
import numpy as np

from ..conditions.polyhedron import Condition, ConditionSet, Kind, never_binds
from ..core.algebraic import FiniteReal, Real, RealAlgebraic, exact_lt
from ..core.encode import encode_real, vec
from ..core.flintq import fmpq_of, fraction_of
from ..core.float_hint import float_hint
from ..core.polys import no_root_between, shift, sign_at, sign_variations
from ..core.real_signs import (
    interval_signs,
    narrowed,
    next_sign_change,
    positive_after,
    rational_right_of,
    sign_at_real,
    sign_change_near,
    sign_right_of_real,
)
from ..core.roots import real_roots
from ..core.scalars import INF, Infinity
from ..errors import ExactinvException
from ..lp.backends import HighsHint
from ..lp.dual_form import DualFormHint
from ..lp.floatlp import FloatLP
from ..lp.hint import resolve_hint_backend
from ..lp.solver import OPTIMAL, UNBOUNDED, ExactLPSolver, LPResult
from .lp_duals import DualCertificate, dual_piece, dual_target, simplest_between

__all__ = ["LPRouteDeclined", "Piece", "FacetPieces", "LPRoute", "LPRouteCache", "lp_route", "vertex_bound"]

_ZERO = flint.fmpz(0)  # fmpz compared with fmpz runs in C (with a Python int: through a conversion)
_TRIES = 24  # widths w, w/16, w/256, ... tried right of a breakpoint before giving up


@dataclass(frozen=True)
class DualPolicy:
    """When the walk tries a dual piece (:mod:`exactinv.validset.lp_duals`): at the end a of a basis piece of
    facet i where the piece's condition has c(a) > ``slack`` D(a)^2 b_i (phi_i(a) below (1 - slack) b_i)
    and the facet's last ``after`` pieces are all basis pieces (the optimal basis changes while the facet
    is far from binding: what a dual piece skips); after a failed try, the next ``backoff`` pieces of that
    facet try none, and after ``give_up`` failed tries with no dual piece found the walk tries none; at the end
    of a dual piece, up to ``chain`` more dual pieces in a row (y_0 from the float LP's basis there, the
    previous piece's y(h) carried over where it reaches the cap).
    A heuristic only: every dual piece is exact, and a failed one falls back to basis pieces.
    ``DUAL_POLICY = None`` turns dual pieces off (tests force them on with
    ``DualPolicy(Fraction(0), 0, 1, 10**9)``)."""

    slack: Fraction = Fraction(1, 4)
    backoff: int = 3
    after: int = 2  # 3 before chained dual pieces (branch lp-dualcost): a chained piece reaches what the first misses
    give_up: int = 8  # after this many failed tries and no dual piece found at all, the walk tries no more
    chain: int = 1  # dual pieces that may follow a dual piece directly (y_0 from the float LP at its end)


DUAL_POLICY: DualPolicy | None = DualPolicy()


_TOUCH = ("an unbounded facet's ray conditions all vanish at h = {} (two rays of P change places there, or one "
          "touches 0): the LP route does not handle it, the vertex route does")


class LPRouteDeclined(ExactinvException):
    """The LP route does not handle this problem (P with lines; a basis or ray not found; an irrational
    point where all ray conditions of a facet vanish)."""


@dataclass(frozen=True)
class Piece:
    """[start, end] (end may be INF) on which ``basis`` (rows of G, sorted) is optimal; or, for a ray
    piece (``basis`` None), the open (start, end) on which the ray ``ray`` of P has
    c_i(h)^T d D(h) > 0: the LP is unbounded there and facet i is violated; or, for a dual piece
    (``dual`` set, ``basis`` and ``ray`` None), the closed [start, end] on which facet i is valid
    (:mod:`exactinv.validset.lp_duals`)."""

    start: Real
    end: Real
    basis: tuple[int, ...] | None
    ray: tuple[Fraction, ...] | None = None
    dual: DualCertificate | None = field(default=None, repr=False)


@dataclass(frozen=True)
class FacetPieces:
    """The pieces of one facet, consecutive closed intervals from 0 to the last ``end`` (INF, or a
    point at or beyond the horizon that bounds the valid set)."""

    facet: int
    pieces: tuple[Piece, ...]


@dataclass(frozen=True)
class LPRoute:
    """The LP route's result: the pieces of every facet, the vertex x_B of each piece
    (flattened, facet by facet: the ``generator`` of its condition; a ray piece's entry is ``point``),
    the number of LPs (float hints and exact solves), seconds per stage, and ``point``: a point of P,
    set when some piece is a ray piece (P is then unbounded; the point makes P nonempty, so every ray
    condition is necessary)."""

    facets: tuple[FacetPieces, ...]
    vertices: tuple[tuple[Fraction, ...], ...] = field(repr=False)
    float_lps: int = 0
    exact_lps: int = 0
    seconds: tuple[tuple[str, float], ...] = field(default=(), compare=False)
    point: tuple[Fraction, ...] | None = field(default=None, repr=False)

    @property
    def pieces(self) -> int:
        return sum(len(f.pieces) for f in self.facets)

    def record(self) -> dict:
        """The certificate's record: per facet the breakpoints (exact reals) and one basis per piece.

        >>> import exactinv as ei
        >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
        >>> _, route = lp_route(cs)
        >>> route.record()       # x <= 1: max (1 - h) x is attained at x = 1 until h = 1, then at x = -1
        {'facets': [{'ends': ['1', 'oo'], 'bases': [[0], [1]]}, {'ends': ['1', '2'], 'bases': [[1], [0]]}]}

        (Facet 0's last piece, walked first, ends at oo; its condition 2 - h >= 0 sets the horizon
        T = 2, where facet 1's walk stops.)
        """
        out: dict = {"facets": [{"ends": [encode_real(p.end) for p in f.pieces],
                                 "bases": [list(p.basis) if p.basis is not None else p.dual.record()
                                           if p.dual is not None else {"ray": vec(p.ray)}
                                           for p in f.pieces]} for f in self.facets]}
        if self.point is not None:
            out["point"] = vec(self.point)
        return out

    @property
    def rays(self) -> int:
        """How many pieces are ray pieces (facet i violated on the open piece)."""
        return sum(p.ray is not None for f in self.facets for p in f.pieces)

    @property
    def duals(self) -> int:
        """How many pieces are dual pieces (facet i valid on the piece, no condition)."""
        return sum(p.dual is not None for f in self.facets for p in f.pieces)



T = TypeVar("T")


def remembered(cache: Any, build: Callable[[], T]) -> T:
    """``build()``'s result, remembered in ``cache.found``; or the :class:`LPRouteDeclined` it raised,
    remembered in ``cache.declined`` and raised again on every call (the LP routes' caches on one
    :class:`ConditionSet`: :class:`LPRouteCache`, :class:`exactinv.validset.lp_lines.LPLinesCache`).

    >>> from types import SimpleNamespace
    >>> cache, calls = SimpleNamespace(found=None, declined=None), []
    >>> [remembered(cache, lambda: calls.append(1) or "pieces") for _ in range(2)], len(calls)
    (['pieces', 'pieces'], 1)
    >>> def refuse():
    ...     raise LPRouteDeclined("rank G < n")
    >>> cache = SimpleNamespace(found=None, declined=None)
    >>> remembered(cache, refuse)
    Traceback (most recent call last):
      ...
    exactinv.validset.lp_route.LPRouteDeclined: rank G < n
    >>> remembered(cache, lambda: "never built")
    Traceback (most recent call last):
      ...
    exactinv.validset.lp_route.LPRouteDeclined: rank G < n
    """
    if cache.found is None and cache.declined is None:
        try:
            cache.found = build()
        except LPRouteDeclined as exc:
            cache.declined = exc
    if cache.declined is not None:
        raise cache.declined
    assert cache.found is not None
    return cache.found


@dataclass
class LPRouteCache:
    """The LP route's work on one :class:`ConditionSet`, kept by ``ConditionSet.cache(LPRouteCache)``:
    ``found`` (the conditions and the pieces) or ``declined`` (why the route does not handle it)."""

    found: tuple[list[Condition], LPRoute] | None = None
    declined: LPRouteDeclined | None = None


class _Basis:
    """A basis B (rows of G, sorted) with B nonsingular and x_B = B^-1 b_B in P, kept in integers: the
    rows of G scaled to integers (row r times a positive lambda_r; the same P, the same x_B), B_int and
    x_B, and the slacks b - G x_B times positive integers per row (their signs, and the ratios of the dual
    simplex step's ratio test, are the slacks').  B_int^-T C and the columns of B_int^-1 come from exact
    solves; the inverse B_int^-T = M / den (M integral, den > 0) only once a dual piece asks for duals
    B^-T d (then every later product uses it).  B = Lambda^-1 B_int, so B^-T = Lambda B_int^-T."""

    __slots__ = ("rows", "x", "slack", "_B", "_Bt", "_inverse", "_inv_q", "_lam")

    def __init__(self, rows: tuple[int, ...], B: flint.fmpz_mat, x: flint.fmpq_mat, slack: list[flint.fmpz],
                 lam: tuple[int, ...] | None = None):
        self.rows, self._B, self.x, self.slack = rows, B, x, slack
        self._lam = lam  # lambda_r of the rows (None: all 1)
        self._Bt: flint.fmpz_mat | None = None
        self._inverse: tuple[flint.fmpz_mat, flint.fmpz] | None = None
        self._inv_q: flint.fmpq_mat | None = None

    def transposed(self) -> flint.fmpz_mat:
        """B_int^T (the scaled rows, transposed)."""
        if self._Bt is None:
            self._Bt = self._B.transpose()
        return self._Bt

    def inverse(self) -> tuple[flint.fmpz_mat, flint.fmpz]:
        """(M, den): B_int^-T = M / den, M integral, den > 0.  Computed once."""
        if self._inverse is None:
            self._inverse = self._inverse_q().numer_denom()
        return self._inverse

    def _inverse_q(self) -> flint.fmpq_mat:
        if self._inv_q is None:
            self._inv_q = flint.fmpq_mat(self.transposed()).inv()
        return self._inv_q

    @property
    def inv_t(self) -> flint.fmpq_mat:
        """B^-T in Q (B: the rows of G as given) = Lambda B_int^-T."""
        if self._lam is None:
            return self._inverse_q()
        M, den = self.inverse()
        return flint.fmpq_mat([[v * lam for v in row] for row, lam in zip(M.tolist(), self._lam)]) / den

    def components(self, C: flint.fmpz_mat) -> flint.fmpz_mat:
        """B_int^-T C times a positive integer, for an integer matrix C: one exact solve (or M C, when the
        inverse is known).  Row l is B^-T C's row l times lambda_(rows[l]) and a positive integer, so its signs
        and roots are B^-T C's."""
        if self._inverse is not None:
            return self._inverse[0] * C
        return self.transposed().solve(C).numer_denom()[0]

    def column(self, l: int) -> flint.fmpz_mat:
        """Column l of B_int^-1 times a positive integer (one exact solve B_int d = e_l, or row l of M): column
        l of B^-1 times a positive number (B^-1 = B_int^-1 Lambda)."""
        n = len(self.rows)
        if self._inverse is not None:
            M = self._inverse[0]
            return flint.fmpz_mat(n, 1, [M[l, k] for k in range(n)])
        return self._B.solve(flint.fmpz_mat(n, 1, [int(k == l) for k in range(n)])).numer_denom()[0]

    def dual_of(self, d_int: flint.fmpz_mat, d_den: flint.fmpz) -> list[flint.fmpq] | None:
        """B^-T d for d = d_int / d_den (d_den > 0), exactly, when it is >= 0; else None.  The sign test runs
        on integers (B_int^-T = M / den), the division only for a basis that serves: y = Lambda M d_int /
        (den d_den)."""
        M, den = self.inverse()
        Y = (M * d_int).entries()
        if any(v < _ZERO for v in Y):
            return None
        scale = den * d_den
        lam = self._lam
        return [flint.fmpq(v, scale) for v in Y] if lam is None else [flint.fmpq(v * lam[k], scale)
                                                                      for k, v in enumerate(Y)]

    @property
    def feasible(self) -> bool:
        return not any(v < _ZERO for v in self.slack)


class _DirectionBasis:
    """A basis B (rows of G) asked for duals B^-T d of a dual piece's directions d: a float B^-T tells how
    negative B^-T d is (a clearly negative one is not tested), and one exact solve B^T y = d tests the
    others (no x_B, no slacks, no inverse in Q)."""

    __slots__ = ("rows", "_Bt", "_inv_t_float", "_inv_max")

    def __init__(self, rows: tuple[int, ...]):
        self.rows = rows
        self._Bt: flint.fmpq_mat | None = None
        self._inv_t_float: np.ndarray | None | bool = None  # False: no float image (singular, out of range)
        self._inv_max = 0.0

    def margin(self, P: _Problem, d_float: np.ndarray | None, d_max: float) -> float | None:
        """A float hint: the least component of B^-T d relative to |B^-T| |d| (clearly negative: the exact
        test would fail), or None when floats say nothing (B singular in floats, d or B^-T out of range)."""
        if self._inv_t_float is None:
            self._inv_t_float = False
            if P.G_float is not None:
                with np.errstate(all="ignore"):
                    try:
                        inv = np.linalg.inv(P.G_float[list(self.rows)]).T
                        if np.all(np.isfinite(inv)):
                            self._inv_t_float, self._inv_max = inv, float(np.abs(inv).max())
                    except np.linalg.LinAlgError:
                        pass
        inv = self._inv_t_float
        if d_float is None or inv is False:
            return None
        with np.errstate(all="ignore"):
            y = inv @ d_float
            if not np.all(np.isfinite(y)):
                return None
            return float(y.min()) / (self._inv_max * d_max + 1.0)

    def dual_of(self, P: _Problem, d: flint.fmpq_mat) -> list[flint.fmpq] | None:
        """B^-T d exactly, by one solve B^T y = d, when it is >= 0 (and B nonsingular); else None."""
        if self._Bt is None:
            self._Bt = flint.fmpq_mat(P.n, P.n, [v for r in self.rows for v in P.G_rows[r]]).transpose()
        try:
            y_q = self._Bt.solve(d).entries()
        except ZeroDivisionError:
            return None
        return None if any(v < 0 for v in y_q) else y_q


class _Problem:
    """G, b, D and the facets' objective matrices, the float LP and the exact LP chain, shared by all facets."""

    def __init__(self, cs: ConditionSet):
        self.cs = cs
        self.G, self.n, self.m = cs.G, cs.polyhedron.n, cs.polyhedron.m
        self.b = flint.fmpq_mat(self.m, 1, cs.b)
        self.D = cs.D
        self.L = len(cs.N)
        self._exact: ExactLPSolver | None = None
        self._primal_lp: FloatLP | None = None
        self._bases: dict[tuple[int, ...], _Basis | None] = {}
        self._directions: dict[tuple[int, ...], _DirectionBasis] = {}
        self.b_float = _floats(cs.b)
        self.G_rows = self.G.tolist()
        G_float = _floats(self.G.entries())
        self.G_float = None if G_float is None else G_float.reshape(self.m, self.n)
        self.float_lp = self.hint_model()
        # each row of (G | b) times a positive integer lambda_r (1 for an integral row): the same P, the same
        # vertices, integer bases; the slacks and a basis's components only scale by positive numbers
        G_int_rows, b_int_list, self.lam = [], [], []
        for g, beta in zip(self.G_rows, cs.b):
            lam = math.lcm(beta.denominator, *(int(v.q) for v in g))
            G_int_rows.append([int(v.p) * (lam // int(v.q)) for v in g])
            b_int_list.append(beta.numerator * (lam // beta.denominator))
            self.lam.append(lam)
        self.integral = all(lam == 1 for lam in self.lam)
        self.G_int_rows, self.b_int_list = G_int_rows, b_int_list
        self.Gb_int = (flint.fmpz_mat(G_int_rows) if self.m else flint.fmpz_mat(0, self.n),
                       flint.fmpz_mat(self.m, 1, b_int_list))
        self._components: dict[int, tuple[flint.fmpq_mat, flint.fmpz_mat]] = {}
        self._float_components: dict[int, tuple[flint.fmpq_mat, np.ndarray | None]] = {}
        self.point_hints: dict[tuple[int, ...], flint.fmpq_mat] = {}  # x_B of a basis the ratio test named
        G_int_float = _floats(v for g in G_int_rows for v in g)
        self.G_int_float = None if G_int_float is None else G_int_float.reshape(self.m, self.n)
        self.float_lps = self.exact_lps = self.pivots = 0
        self.point: tuple[Fraction, ...] | None = None  # a point of P, kept when a ray is found

    def hint_model(self) -> FloatLP | DualFormHint:
        """A float model of max c^T x over P for basis hints, warm-started across its solves: HiGHS on the
        LP's dual form (:mod:`exactinv.lp.dual_form`: a basis of dimension n, not m) under the default
        HiGHS hint backend, else the configured backend through :class:`FloatLP`."""
        backend = resolve_hint_backend(None)
        if isinstance(backend, HighsHint) and self.G_float is not None and self.b_float is not None:
            return DualFormHint(self.G_float, self.b_float)
        return FloatLP(self.G, (False,) * self.m, backend)

    def primal_lp(self) -> FloatLP:
        """The float LP max c^T x s.t. G x <= b itself (its simplex ends at a vertex basis): asked where the dual
        form's optimum names no vertex (:attr:`DualFormHint.degenerate`)."""
        if self._primal_lp is None:
            self._primal_lp = FloatLP(self.G, (False,) * self.m, resolve_hint_backend(None))
        return self._primal_lp

    @property
    def exact(self) -> ExactLPSolver:
        if self._exact is None:
            self._exact = ExactLPSolver(self.G, (False,) * self.m)
        return self._exact

    def objective(self, i: int) -> flint.fmpq_mat:
        """C_i: the n x L matrix whose column k is (g_i N_k)^T, so c_i(h) = C_i (1, h, h^2, ..)^T."""
        GN = self.cs.GN
        return flint.fmpq_mat(self.n, self.L, [GN[k][i][l] for l in range(self.n) for k in range(self.L)])

    def direction_basis(self, rows: tuple[int, ...]) -> _DirectionBasis:
        """The basis of these rows for a dual piece's directions only (:class:`_DirectionBasis`).  Cached."""
        if rows not in self._directions:
            self._directions[rows] = _DirectionBasis(rows)
        return self._directions[rows]

    def basis(self, rows: tuple[int, ...]) -> _Basis | None:
        """The basis of these rows when B is nonsingular and x_B = B^-1 b_B is in P; else None.  Cached.
        Integers throughout: B_int x = b_int (one exact solve), the slacks b_int x_den - G_int x_num."""
        if rows not in self._bases:
            G_int, b_int = self.Gb_int
            B = flint.fmpz_mat(self.n, self.n, [v for r in rows for v in self.G_int_rows[r]])
            b_B = flint.fmpz_mat(self.n, 1, [self.b_int_list[r] for r in rows])
            out = None
            x = self.point_hints.pop(rows, None)  # the dual simplex step's point: checked, B x = b_B exactly
            if x is not None:
                x_num, x_den = x.numer_denom()
                if B * x_num != b_B * x_den or B.det() == 0:
                    x = None
            if x is None:
                try:
                    x = B.solve(b_B)
                except ZeroDivisionError:
                    x = None
            if x is not None:
                x_num, x_den = x.numer_denom()
                lam = None if self.integral else tuple(self.lam[r] for r in rows)
                out = _Basis(rows, B, x, (b_int * x_den - G_int * x_num).entries(), lam)
                if not out.feasible:
                    out = None
            self._bases[rows] = out
        return self._bases[rows]

    def float_components(self, C: flint.fmpq_mat) -> np.ndarray | None:
        """:meth:`components_matrix` in floats, each row scaled to max 1 (None beyond double range).  Cached."""
        found = self._float_components.get(id(C))
        if found is None or found[0] is not C:
            Z = self.components_matrix(C)
            with np.errstate(all="ignore"):
                try:
                    Zf = np.array([float_hint(v) for v in Z.entries()], dtype=float).reshape(Z.nrows(), Z.ncols())
                    Zf /= np.abs(Zf).max() or 1.0
                    if not np.all(np.isfinite(Zf)):
                        Zf = None
                except (OverflowError, ValueError):
                    Zf = None
            found = (C, Zf)
            self._float_components[id(C)] = found
        return found[1]

    def components_matrix(self, C: flint.fmpq_mat) -> flint.fmpz_mat:
        """The n x W integer matrix whose row l holds, times one positive integer, the coefficients of
        c_i's component l times D (c_i(h) = C (1, h, ..)^T): B_int^-T of it gives z_B's components up to
        positive factors per row.  Cached per objective."""
        found = self._components.get(id(C))
        if found is None or found[0] is not C:
            Z = C
            if self.D.degree() > 0:  # z_B = D B^-T c_i: each row times D
                Dm = self.D.coeffs()
                W0, W = C.ncols(), C.ncols() + len(Dm) - 1
                Z = C * flint.fmpq_mat(W0, W, [Dm[m - k] if 0 <= m - k < len(Dm) else 0
                                               for k in range(W0) for m in range(W)])
            found = (C, Z.numer_denom()[0])  # a positive common denominator: the same signs and roots
            self._components[id(C)] = found
        return found[1]

class _GuardedExact:
    """The exact LP chain for a dual piece's direction d_k, declined (None) when the float LP at d_k gave no
    optimal basis: there it is mostly unbounded (P unbounded: no y_k >= 0 exists, Farkas), whose exact proof
    (PPL) costs far more than the dual piece could save; the piece then just fails."""

    def __init__(self, P: _Problem):
        self.P, self.float_optimal = P, True

    def solve(self, c: flint.fmpq_mat, b: flint.fmpq_mat, nonnegative) -> LPResult | None:
        return self.P.exact.solve(c, b, nonnegative) if self.float_optimal else None


def _floats(values) -> np.ndarray | None:
    try:
        out = np.array([float(v) for v in values], dtype=float)
    except OverflowError:
        return None
    return out if np.all(np.isfinite(out)) else None


def _cost(C: flint.fmpq_mat, D: flint.fmpq_poly, s: Fraction) -> flint.fmpq_mat:
    """D(s) C_i (1, s, s^2, ..)^T exactly: the LP's objective at the rational s."""
    x = fmpq_of(s)
    powers = flint.fmpq_mat(C.ncols(), 1, [x ** k for k in range(C.ncols())])
    return C * powers * D(x)


def _hint_rows(P: _Problem, cost: flint.fmpq_mat, lp: FloatLP | DualFormHint | None = None) -> tuple[int, ...] | None:
    """The float LP's tight rows at this cost, when they are n of them (a vertex basis); None otherwise.
    ``lp``: another float image of the same LP (its own warm start; default the walk's).
    A hint never raises: a cost beyond double range or a failed solve only gives no hint."""
    c = _floats(cost.entries())
    if c is None or P.b_float is None:
        return None
    scale = float(np.abs(c).max()) if len(c) else 0.0
    if not scale > 0:
        return None
    P.float_lps += 1
    model = lp or P.float_lp
    if isinstance(model, DualFormHint):
        rows = model.basis_rows(c / scale)
        if rows is not None or not model.degenerate:
            return rows
        model = P.primal_lp()  # an optimal face the dual form named no vertex of
    hint = model.solve_floats(c / scale, P.b_float, (False,) * P.n)
    if hint.status != OPTIMAL:
        return None
    basis = hint.fetch_basis()
    if basis is None or len(basis[1]) != P.n:
        return None
    return tuple(sorted(basis[1]))


def _exact_rows(P: _Problem, cost: flint.fmpq_mat) -> tuple[int, ...] | tuple[Fraction, ...] | None:
    """A basis read off the exact LP chain's verified optimum at this cost: the rows of the dual's
    support, completed by rows tight at x to n independent ones (then z_B(s) is that dual and x_B = x).
    When the LP is unbounded (P is unbounded): the verified ray d instead (G d <= 0, cost . d > 0), as a
    :class:`_Ray`; its feasible point is kept as P's point."""
    P.exact_lps += 1
    res = P.exact.solve(cost, P.b, (False,) * P.n)
    if res.status == UNBOUNDED and res.ray_q is not None:
        if P.point is None and res.x_q is not None:
            P.point = tuple(fraction_of(v) for v in res.x_q.entries())
        return _Ray(_primitive(res.ray_q.entries()))
    if res.status != OPTIMAL:
        return None
    y, x = res.y_q.entries(), res.x_q
    slack = (P.b - P.G * x).entries()
    rows = [r for r in range(P.m) if y[r] != 0]
    chosen: list[int] = []
    for r in rows + [r for r in range(P.m) if slack[r] == 0 and y[r] == 0]:
        trial = chosen + [r]
        M = flint.fmpq_mat(len(trial), P.n, [P.G[q, l] for q in trial for l in range(P.n)])
        if M.rank() == len(trial):
            chosen = trial
        elif y[r] != 0:
            return None  # a dual that is not basic: no basis from it
        if len(chosen) == P.n:
            return tuple(sorted(chosen))
    return None


class _Ray(tuple):
    """A candidate ray d of P (a tuple of Fractions), told apart from a basis (a tuple of row indices)."""


def _primitive(entries) -> tuple[Fraction, ...]:
    """The positive multiple of a rational vector with coprime integer entries."""
    q = [fraction_of(v) for v in entries]
    den = math.lcm(*(v.denominator for v in q)) if q else 1
    ints = [int(v * den) for v in q]
    g = math.gcd(*ints) or 1
    return tuple(Fraction(v // g) for v in ints)


def _pivots(P: _Problem, basis: _Basis, leaving: int) -> list[tuple[int, ...]]:
    """The dual simplex step at a breakpoint: component ``leaving`` of z_B turns negative, so its row
    is released -- x moves along d with B d = -e_leaving (d = minus row ``leaving`` of B^-T) -- and
    the first rows of G that d meets (the ratio test, ties all kept) are candidates to enter.
    Only candidates: each is verified like any hint.  When no row stops d, d is a ray of P (G d <= 0)
    with c_i^T d D = -z_leaving > 0 just past the breakpoint: the one candidate is that ray (a
    :class:`_Ray`), the certificate of a ray piece."""
    P.pivots += 1
    d = -basis.column(leaving)  # minus column l of B^-1, times a positive integer
    Gd = (P.Gb_int[0] * d).entries()  # G d, row r times lambda_r > 0 (as the slacks)
    s = basis.slack  # the ratios slack_r / Gd_r compared by cross-multiplication (positive factors cancel)
    best, enter = None, []
    inside = set(basis.rows)
    s_best = g_best = _ZERO
    for r in range(P.m):
        g = Gd[r]
        if g > _ZERO and r not in inside:
            if best is None:
                best, enter, s_best, g_best = r, [r], s[r], g
                continue
            left, right = s[r] * g_best, s_best * g
            if left < right:
                best, enter, s_best, g_best = r, [r], s[r], g
            elif left == right:
                enter.append(r)
    if best is None:
        if P.point is None:
            P.point = tuple(fraction_of(v) for v in basis.x.entries())
        return [_Ray(_primitive(d.entries()))]
    out = basis.rows[:leaving] + basis.rows[leaving + 1:]
    # the point every candidate shares: x + tau d with tau = slack_best / (x_den Gd_best) (row best tight),
    # as a hint for P.basis, which checks B' x' = b_B' exactly instead of solving for it
    x_num, x_den = basis.x.numer_denom()
    point = flint.fmpq_mat(x_num * Gd[best] + d * s[best]) / (x_den * Gd[best])
    candidates = [tuple(sorted(out + (r,))) for r in enter]
    for rows in candidates:
        P.point_hints[rows] = point
    return candidates


_GRID = (np.arange(0, 65) / 64.0) ** 2  # 0, then 64 points on (0, 1], denser near 0


def _first_negative(P: _Problem, rows: tuple[int, ...], C: flint.fmpq_mat, n: int, lo: Fraction,
                    span: Fraction) -> tuple[list[float], list[float]]:
    """For each component of z_B (B the basis ``rows``, C facet i's objective), the first point of a float
    grid on (lo, lo + span], denser near lo, where its float image is negative (inf if none), and the
    grid point before it (lo for the first): a guess that only chooses which component's roots are
    computed first, and brackets its end for :func:`~exactinv.core.real_signs.sign_change_near`.  The
    float image is one float solve B_int^T Y = C D (no exact number turned into a float per piece);
    it never raises, and when floats say nothing every guess is 0 (every component is then tested)."""
    try:
        with np.errstate(all="ignore"):
            Cf = P.float_components(C)
            if Cf is None or P.G_int_float is None:
                return [0.0] * n, [0.0] * n
            M = np.linalg.solve(P.G_int_float[list(rows)].T, Cf)
            W = M.shape[1]
            grid = float(lo) + float(span) * _GRID
            values = M @ np.vander(grid[1:], W, increasing=True).T
            if not np.all(np.isfinite(values)):
                return [0.0] * n, [0.0] * n
            negative = values < 0
            at = negative.argmax(axis=1)
            found = negative.any(axis=1)
            first = np.where(found, grid[1:][at], math.inf)
            before = np.where(found, grid[at], math.inf)
        return first.tolist(), before.tolist()
    except (OverflowError, ValueError, np.linalg.LinAlgError):
        return [0.0] * n, [0.0] * n


def _tight(e: Real) -> Real:
    """An algebraic end with a narrow enclosure (Arb's, about 2^-53 relative), so that Descartes tests up
    to its upper end, and from its lower end on the next piece, see no neighbouring root."""
    if isinstance(e, RealAlgebraic) and e.upper - e.lower > (abs(e.lower) + 1) / 2**40:
        return narrowed(e)
    return e


def _row(Y: flint.fmpz_mat, l: int) -> flint.fmpq_poly:
    W = Y.ncols()
    return flint.fmpq_poly(Y.entries()[l * W:(l + 1) * W])


def _dual_components(P: _Problem, basis: _Basis, C: flint.fmpq_mat) -> flint.fmpz_mat:
    """z_B = D B^-T c_i as an integer matrix, up to a positive factor per row: row l holds the coefficients
    of component l (its signs and roots are z_B's component l's).  One exact solve B_int^T Y = C D."""
    return basis.components(P.components_matrix(C))


def _point_piece(P: _Problem, C: flint.fmpq_mat, t: FiniteReal) -> tuple[_Step | None, list[_Ray]]:
    """(the point piece [t, t] or None, the rays met): a basis with every component of z_B(t) >= 0
    (weak duality at t alone; exact signs at a rational or algebraic t).  Candidates: the exact LP's
    basis at t (t rational), or at the rationals just around t (t algebraic), then the bases met so far
    (where c_i(t) = 0 every feasible basis qualifies).  When those LPs are unbounded, their verified rays
    are returned instead: one of them may be positive at t itself."""
    if isinstance(t, RealAlgebraic):
        t = _tight(t)
        points = [t.lower, t.upper]
    else:
        points = [Fraction(t)]
    candidates: list = []
    rays: list[_Ray] = []
    for s in points:
        found = _exact_rows(P, _cost(C, P.D, s))
        if isinstance(found, _Ray):
            rays.append(found)
        elif found is not None:
            candidates.append(found)
    candidates += [rows for rows, basis in list(P._bases.items())[:64] if basis is not None]
    for rows in candidates:
        basis = P.basis(rows)
        if basis is None:
            continue
        Y = _dual_components(P, basis, C)
        if all(sign_at_real(_row(Y, l), t) >= 0 for l in range(P.n)):
            return _Step(Piece(t, t, rows), basis, -1, None, True), rays
    return None, rays


def _accept(P: _Problem, C: flint.fmpq_mat, rows: tuple[int, ...] | None, t: FiniteReal,
            cap: Fraction | None) -> tuple[_Basis, Real, int] | None:
    """(basis, end, leaving): the piece from t on which the basis is optimal, or None if it is not
    optimal just right of t.  Every component of z_B = D B^-T c_i must be >= 0 right of t; the piece
    ends at the least odd-multiplicity root beyond t of any component (the ``leaving`` one; -1 if
    none) -- or at ``cap`` (a rational beyond the horizon) if that comes first.

    Exact throughout; a float grid only guesses which component ends the piece.  Its end e is
    computed exactly, then one batch of Descartes tests on (lo, e) (lo = t, or a rational just
    below an algebraic t) proves most components positive there; only the others get exact signs
    right of t and exact roots."""
    if rows is None:
        return None
    basis = P.basis(rows)
    if basis is None:
        return None
    if cap is not None and not exact_lt(t, cap):
        cap = None  # a first piece when the horizon is 0: no cap, pieces have positive length
    Y = _dual_components(P, basis, C)
    lo = t.lower if isinstance(t, RealAlgebraic) else Fraction(t)
    end: Real = INF if cap is None else cap
    leaving = -1
    span = (cap - lo) if cap is not None and cap > lo else 2 * (1 + abs(lo))
    guess, before = _first_negative(P, rows, C, P.n, lo, span)
    done: set[int] = set()
    first = min(range(P.n), key=lambda l: guess[l])
    if guess[first] < math.inf:
        p = _row(Y, first)
        e = sign_change_near(p, t, before[first], guess[first])  # proves p > 0 on (t, e) too
        if e is None:  # the float bracket did not help
            if sign_right_of_real(p, t) < 0:
                return None
            e = _tight(next_sign_change(p, t))
        if exact_lt(e, end):
            end, leaving = e, first
        done.add(first)
    bound = _cap(end)
    signs = interval_signs(Y, lo, bound if bound is not None and bound > lo else None)
    for l in sorted(range(P.n), key=lambda l: guess[l]):
        if l in done or signs[l] > 0:
            continue  # > 0 on (lo, end), which holds (t, end)
        p = _row(Y, l)
        right = sign_right_of_real(p, t)
        if right < 0:
            return None
        bound = _cap(end)
        if bound is not None and positive_after(p, t, bound, right):
            continue  # > 0 on (t, bound), which holds (t, end)
        e = _tight(next_sign_change(p, t))
        if exact_lt(e, end):
            end, leaving = e, l
    return basis, end, leaving


def _first_width(t: FiniteReal) -> Fraction:
    top = t.upper if isinstance(t, RealAlgebraic) else Fraction(t)
    return (1 + abs(top)) / 64


def _cap(T: Real) -> Fraction | None:
    """A rational >= T (None for INF)."""
    if isinstance(T, Infinity):
        return None
    return T.upper if isinstance(T, RealAlgebraic) else Fraction(T)


@dataclass(frozen=True)
class _Step:
    """A piece found from t: a basis piece (``basis``, the ``leaving`` component that ends it, -1 if none)
    or a ray piece (``r`` = c_i^T d D > 0 on the open piece); ``covered``: the piece itself shows its finite
    end decided (a basis piece is closed; a ray piece only when r > 0 at that end, a rational cap, or when
    the end is a pole, D = 0)."""

    piece: Piece
    basis: _Basis | None
    leaving: int
    r: flint.fmpq_poly | None
    covered: bool


def _ray_poly(P: _Problem, C: flint.fmpq_mat, d: tuple[Fraction, ...]) -> flint.fmpq_poly:
    """r(h) = c_i(h)^T d D(h) = (g_i N(h) d) D(h): where r > 0 and d is a ray of P, g_i A_d(h) d > 0."""
    row = flint.fmpq_mat(1, P.n, [fmpq_of(v) for v in d]) * C
    return flint.fmpq_poly(row.entries()) * P.D


def _accept_ray(P: _Problem, C: flint.fmpq_mat, d: tuple[Fraction, ...], t: FiniteReal,
                cap: Fraction | None) -> _Step | None:
    """The ray piece from t: d must be a ray of P (G d <= 0, d != 0) with r = c_i^T d D > 0 just right of
    t (exact signs; at h = 0 the lexicographic order of the powers of h); it ends at r's next sign change
    (or at ``cap``, where r > 0 still), or at a root where r only touches 0.  None if d does not qualify."""
    Gd = (P.G * flint.fmpq_mat(P.n, 1, [fmpq_of(v) for v in d])).entries()
    if not any(d) or any(v > 0 for v in Gd):
        return None
    r = _ray_poly(P, C, d)
    if r.is_zero() or sign_right_of_real(r, t) <= 0:
        return None
    if cap is not None and not exact_lt(t, cap):
        cap = None
    end: Real = _next_root(r, t)
    covered = isinstance(end, Infinity) or _is_pole(P.D, end)
    if cap is not None and exact_lt(cap, end):
        end, covered = cap, True
    return _Step(Piece(t, end, None, tuple(d)), None, -1, r, covered)


def _is_pole(D: flint.fmpq_poly, t: FiniteReal) -> bool:
    """D(t) = 0 exactly (r(tA) does not exist: t is no steplength, and needs no piece to decide it)."""
    if D.degree() < 1:
        return False
    if isinstance(t, RealAlgebraic):
        return (D % flint.fmpq_poly(t.poly)).is_zero()
    return D(fmpq_of(Fraction(t))) == 0


def _next_root(r: flint.fmpq_poly, t: FiniteReal) -> Real:
    """The least real root of r greater than t, of any multiplicity (INF if none): a ray piece must have
    r > 0 on its whole open piece, so it also ends where r only touches 0."""
    for root, _ in real_roots(r):
        if exact_lt(t, root):
            return _tight(root)
    return INF


def _try(P: _Problem, C: flint.fmpq_mat, candidate, t: FiniteReal, cap: Fraction | None) -> _Step | None:
    """A candidate (rows of a basis, a :class:`_Ray` or None) verified as the piece from t, or None."""
    if isinstance(candidate, _Ray):
        return _accept_ray(P, C, candidate, t, cap)
    found = _accept(P, C, candidate, t, cap)
    if found is None:
        return None
    return _Step(Piece(t, found[1], candidate), found[0], found[2], None, True)


def _next_piece(P: _Problem, i: int, C: flint.fmpq_mat, t: FiniteReal, cap: Fraction | None,
                previous: _Step | None) -> _Step:
    """The piece of facet i from t: a basis optimal just right of t, ending where it stops being optimal
    (or at cap), or a ray of P showing the LP unbounded just right of t.  Candidates: the dual simplex
    step from the previous piece's basis (its ray when no row stops it), then float LP hints at
    rationals s ever closer to t, and the exact LP chain's answer at s (an optimum's basis, or an
    unbounded LP's verified ray) where the float LP names no basis, and from the fourth width on every
    other time.  A candidate that fails only costs time."""
    if previous is not None and previous.basis is not None and previous.leaving >= 0:
        for candidate in _pivots(P, previous.basis, previous.leaving):
            found = _try(P, C, candidate, t, cap)
            if found is not None:
                return found
    width = _first_width(t)
    for attempt in range(_TRIES):
        s = rational_right_of(t, width)
        cost = _cost(C, P.D, s)
        rows = _hint_rows(P, cost)
        found = _try(P, C, rows, t, cap)
        if found is None and (rows is None or (attempt >= 3 and attempt % 2 == 1)):
            # the exact chain where floats name no basis (an unbounded LP: its ray), else only once the
            # hints have failed at three widths: a hint that fails mostly met a breakpoint before s, where
            # the exact optimum at s fails too (R^20/200: 15 of 16 exact solves, 12 ms each)
            found = _try(P, C, _exact_rows(P, cost), t, cap)
        if found is not None:
            return found
        width /= 8
    raise LPRouteDeclined(f"facet {i}: no basis or ray found optimal just right of h = {t}")


def _rational_cover(r: flint.fmpq_poly, start: Real, t: FiniteReal) -> Fraction | None:
    """Two ray pieces meet at t, where the first one's r vanishes: a rational s in (start, t] with the
    second one's r > 0 on [s, t] (so the second piece, moved to start at s, decides s and t itself).
    None when r(t) = 0 too (or not proved > 0 near t)."""
    if not isinstance(t, RealAlgebraic):
        return Fraction(t) if sign_at(r, Fraction(t)) > 0 else None
    if sign_at_real(r, t) <= 0:  # exact: r(t) = 0 (t's polynomial divides r) or r(t) < 0
        return None
    bits = 16
    for _ in range(12):
        s = t.lower
        if exact_lt(start, s) and sign_at(r, s) > 0 and no_root_between(r, s, t.upper) and sign_at(r, t.upper) > 0:
            return s
        t.refine(bits)
        bits *= 2
    return None


def _bound(p: flint.fmpq_poly, T: Real) -> Real:
    """sup{h >= 0 : p(h) >= 0} when p's leading coefficient is negative (p(0) >= 0 for a piece's
    condition: x_B is in P): its largest real root, or 0; INF otherwise -- or INF when p has a
    root beyond the current horizon T (an odd count of sign variations beyond it), which then
    cannot lower T."""
    if p.degree() < 1 or p.coeffs()[-1] > 0:
        return INF
    cap = _cap(T)
    if cap is not None and sign_variations(shift(p, cap).coeffs()) % 2 == 1:
        return INF
    roots = real_roots(p)
    top = roots[-1][0] if roots else Fraction(0)
    return top if top > 0 else Fraction(0)


def lp_route(cs: ConditionSet) -> tuple[list[Condition], LPRoute]:
    """(conditions, route): the condition of every (facet, piece) that can bind, with ``generator``
    its index among the pieces (facet by facet), and the pieces themselves; computed once per
    :class:`ConditionSet`.  Raises :class:`LPRouteDeclined` for P with lines or unbounded.

    The walk of a facet stops at the horizon T: the least sup{h : p(h) >= 0} over the conditions
    p built so far (the first piece of every facet first).  The valid set lies in [0, T], each
    facet's pieces cover [0, T] at least, and so the conditions still give the valid set exactly.

    x' = -x on [-1, 1], forward Euler: facet x <= 1 has the piece [0, 1] with x = 1
    (condition h >= 0, never binding) and [1, oo) with x = -1: 1 + (1 - h) = 2 - h >= 0,
    which bounds the valid set by T = 2 (pieces 1 and 3: the vertex -1 on x <= 1, 1 on -x <= 1).

    >>> import exactinv as ei
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
    >>> conditions, route = lp_route(cs)
    >>> [(c.generator, c.facet, c.poly) for c in conditions]
    [(1, 0, (Fraction(2, 1), Fraction(-1, 1))), (3, 1, (Fraction(2, 1), Fraction(-1, 1)))]
    """
    return remembered(cs.cache(LPRouteCache), lambda: _build(cs))


def walk_facets(cs: ConditionSet, facets: int) -> tuple[list[Condition], LPRoute]:
    """:func:`lp_route`'s work, uncached, on the first ``facets`` rows of G only: the other rows bound
    the LP's feasible set but are not facets whose validity is asked (the P with lines of
    :mod:`exactinv.validset.lp_lines`: the rows l^T x <= 0 of a basis of ker G).

    The interval [-1, 1] with the row x <= 2 appended but not walked: only facets 0 and 1 get pieces.

    >>> import exactinv as ei
    >>> cs = ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1], [1]], [1, 1, 2]), ei.methods.taylor(1))
    >>> _, route = walk_facets(cs, 2)
    >>> [f.facet for f in route.facets]
    [0, 1]
    """
    return _build(cs, facets)


def _build(cs: ConditionSet, walked: int | None = None) -> tuple[list[Condition], LPRoute]:
    t0 = time.perf_counter()
    if cs.G.rank() < cs.polyhedron.n:
        raise LPRouteDeclined("P has lines (rank G < n): no basis exists; the vertex route handles it")
    P = _Problem(cs)
    asked = range(P.m if walked is None else walked)
    T: Real = INF
    objectives = [P.objective(i) for i in range(P.m)]
    # per facet (piece, its condition -- None for a dual piece --, its point: x_B, or None for a ray piece)
    walks: list[list[tuple[Piece, flint.fmpq_poly | None, tuple[Fraction, ...] | None]]] = [[] for _ in range(P.m)]

    last: list[_Step | None] = [None] * P.m
    policy = DUAL_POLICY
    backoff = [0] * P.m
    tally = [0, 0]  # dual pieces found, tries failed
    targets: dict[int, flint.fmpq_mat] = {}
    guard = _GuardedExact(P)
    dual_lp: dict[int, FloatLP | DualFormHint] = {}  # the dual pieces' float LP: its own warm start, apart from the walk's
    served: dict[int, list[tuple[int, ...]]] = {}  # facet (or -1: any) -> the bases whose duals served, latest first

    def suggest(i: int, k: int, d: flint.fmpq_mat):
        """Bases for the direction d = d_k of facet i, cheapest first (each costs one exact product B^-T d
        to test): those that served this facet (its Taylor coefficients point nearly along +-g_i), the
        bases of its own walk (optimal near +g_i), then those that served any facet; then the float LP's
        basis at d."""
        seen = set()
        walk = [p.basis for p, _, _ in reversed(walks[i]) if p.basis is not None]
        d_float = _floats(d.entries())
        d_max = 0.0 if d_float is None else float(np.abs(d_float).max())
        d_int, d_den = d.numer_denom()
        for rows in served.get(i, []) + walk[:4] + served.get(-1, []):
            if rows not in seen:
                seen.add(rows)
                direction = P.direction_basis(rows)
                margin = direction.margin(P, d_float, d_max)
                if margin is not None and margin < -1e-9:
                    continue  # clearly negative: the exact test would fail
                basis = P._bases.get(rows)  # a walk's basis: B^-T known in Q; else one solve B^T y = d
                y = basis.dual_of(d_int, d_den) if basis is not None else direction.dual_of(P, d)
                if y is not None:
                    yield rows, y
        if k not in dual_lp:
            dual_lp[k] = P.hint_model()
        rows = _hint_rows(P, d, dual_lp[k])
        guard.float_optimal = rows is not None
        if rows is not None and rows not in seen:  # one exact solve B^T y = d (no inverse, no feasibility)
            y = P.direction_basis(rows).dual_of(P, d)
            if y is not None:
                yield rows, y

    def used(i: int, k: int, rows: tuple[int, ...]) -> None:
        for key in (i, -1):
            recent = served.setdefault(key, [])
            if rows in recent:
                recent.remove(rows)
            recent.insert(0, rows)
            del recent[4:]

    def try_dual(i: int, t: FiniteReal) -> bool:
        """A dual piece of facet i from t (or from a rational just left of an algebraic t, the previous basis
        piece cut there), when the previous piece is a basis piece and facet i is far from binding at t; or
        right at the end t of a dual piece (:attr:`DualPolicy.chain`), with y_0 from the float LP's basis at t."""
        before = last[i]
        if policy is None or before is None or isinstance(t, Infinity):
            return False
        if before.basis is None:
            return before.piece.dual is not None and chain(i, t)
        if backoff[i] > 0:
            backoff[i] -= 1
            return False
        if tally[1] >= policy.give_up and not tally[0]:
            return False  # e.g. an unbounded P whose Taylor directions d_k are all unbounded: no y_k >= 0
        if len(walks[i]) < policy.after or any(p.basis is None for p, _, _ in walks[i][-policy.after:]):
            return False
        piece, c, _ = walks[i][-1]
        a = t.lower if isinstance(t, RealAlgebraic) else Fraction(t)
        if not exact_lt(piece.start, a):
            return False
        if isinstance(t, RealAlgebraic):  # cut the basis piece at a short rational within 1/64 of it below t
            low = _cap(piece.start)
            assert low is not None
            a = simplest_between(max(low, a - (a - low) / 64), a) if low < a else a
            if not exact_lt(piece.start, a):
                return False
        b_i, x = P.cs.b[i], fmpq_of(a)
        Da = P.D(x)
        if not (b_i > 0 and Da != 0 and c(x) > fmpq_of(policy.slack) * Da * Da * fmpq_of(b_i)):
            return False
        if i not in targets:
            targets[i] = dual_target(objectives[i], P.D)
        y0 = before.basis.dual_of(*_cost(objectives[i], P.D, a).numer_denom())  # B optimal at a: B^-T d_0 >= 0
        if y0 is None:
            return False
        cert = dual_piece(P.G, P.b, b_i, P.D, targets[i], (before.basis.rows, y0), guard, a, _cap(T),
                          lambda k, d: suggest(i, k, d), lambda k, rows: used(i, k, rows))
        if cert is None:
            backoff[i] = policy.backoff
            tally[1] += 1
            return False
        tally[0] += 1
        if a != t:
            walks[i][-1] = (replace(piece, end=a), c, walks[i][-1][2])
        found(i, cert)
        return True

    def chain(i: int, t: FiniteReal) -> bool:
        """A dual piece of facet i right at the end t (rational) of its dual piece: y_0 = B^-T d_0(t) >= 0 for the
        basis B of the float LP at d_0(t) (exact; the basis need not be primal feasible), taken when
        q(t) = D(t)^2 b_i - b^T y_0 > slack D(t)^2 b_i; at most ``chain`` such pieces in a row."""
        assert policy is not None
        run = 0
        for p, _, _ in reversed(walks[i]):
            if p.dual is None:
                break
            run += 1
        if run > policy.chain or not isinstance(t, Fraction) or tally[1] >= policy.give_up and not tally[0]:
            return False
        b_i, x = P.cs.b[i], fmpq_of(t)
        Da = P.D(x)
        if not (b_i > 0 and Da != 0):
            return False
        if i not in targets:
            targets[i] = dual_target(objectives[i], P.D)
        d0 = _cost(objectives[i], P.D, t)
        rows = _hint_rows(P, d0)
        y0 = None if rows is None else P.direction_basis(rows).dual_of(P, d0)
        if rows is None or y0 is None:
            return False
        beta = sum((v * P.b[r, 0] for r, v in zip(rows, y0)), flint.fmpq(0))
        if not Da * Da * fmpq_of(b_i) - beta > fmpq_of(policy.slack) * Da * Da * fmpq_of(b_i):
            return False
        cert = dual_piece(P.G, P.b, b_i, P.D, targets[i], (rows, y0), guard, t, _cap(T),
                          lambda k, d: suggest(i, k, d), lambda k, rows: used(i, k, rows), carry=walks[i][-1][0].dual)
        if cert is None:
            tally[1] += 1
            return False
        tally[0] += 1
        found(i, cert)
        return True

    def found(i: int, cert: DualCertificate) -> None:
        dual = Piece(cert.start, cert.end, None, None, cert)
        last[i] = _Step(dual, None, -1, None, True)
        walks[i].append((dual, None, walks[i][-1][2]))

    def step(i: int, t: FiniteReal) -> None:
        nonlocal T
        if try_dual(i, t):
            return
        found = _next_piece(P, i, objectives[i], t, _cap(T), last[i])
        before = last[i]
        if found.basis is None and before is not None and not before.covered:
            # two ray pieces meet at t, where the first one's r vanishes: the second must decide t (r > 0 at t),
            # or a point piece [t, t] (a basis optimal at t alone: r touches 0 there, or two rays change
            # places), or a third ray, of the LP unbounded at (or around) t, positive at t
            covering = cover(i, found.piece.ray, before, t)  # type: ignore[arg-type]
            if covering is None:
                point_piece, rays = _point_piece(P, objectives[i], t)
                if point_piece is not None:
                    add(i, point_piece)
                    covering = found
                for d in rays if covering is None else ():
                    covering = cover(i, d, before, t)
                    if covering is not None:
                        break
                if covering is None:
                    raise LPRouteDeclined(_TOUCH.format(t))
            found = covering
        add(i, found)

    def cover(i: int, d: tuple[Fraction, ...], before: _Step, t: FiniteReal) -> _Step | None:
        """The ray piece of d from a rational s <= t at which its r > 0 (moving the previous piece's end
        from t to s), or None."""
        s = _rational_cover(_ray_poly(P, objectives[i], d), before.piece.start, t)
        again = None if s is None else _accept_ray(P, objectives[i], d, s, _cap(T))
        if again is not None and s != t:
            old = walks[i][-1]
            walks[i][-1] = (replace(old[0], end=s), old[1], old[2])
        return again

    def add(i: int, found: _Step) -> None:
        nonlocal T
        last[i] = found
        if found.basis is not None:
            x = found.basis.x
            gNx = x.transpose() * objectives[i]  # 1 x L: g_i N_k x_B
            c = (P.D * P.cs.b[i] - flint.fmpq_poly(gNx.entries())) * P.D
            point: tuple[Fraction, ...] | None = tuple(fraction_of(v) for v in x.entries())
        else:
            c = -found.r  # the ray-facet condition -(g_i N d) D >= 0: negative on the open piece
            point = None
        bound = _bound(c, T)
        if exact_lt(bound, T):
            T = bound
        walks[i].append((found.piece, c, point))

    order = _nearby_order(P, asked)
    for i in order:  # the first piece of every facet: an early horizon
        step(i, Fraction(0))
    for i in order:  # on to the horizon, and past a ray piece's end that it leaves undecided
        while exact_lt(walks[i][-1][0].end, T) or not (last[i].covered or isinstance(walks[i][-1][0].end, Infinity)):
            step(i, walks[i][-1][0].end)  # type: ignore[arg-type]
    t1 = time.perf_counter()
    rays = any(piece.ray is not None for walk in walks for piece, _, _ in walk)
    conditions, vertices, facets = [], [], []
    for i, walk in enumerate(walks[:len(asked)]):
        facets.append(FacetPieces(i, tuple(piece for piece, _, _ in walk)))
        for piece, c, x in walk:
            vertices.append(x if x is not None else P.point)
            if c is not None and not never_binds(c.coeffs()):
                kind = Kind.VERTEX if piece.basis is not None else Kind.RAY
                conditions.append(Condition(kind, len(vertices) - 1, i, c))
    t2 = time.perf_counter()
    route = LPRoute(tuple(facets), tuple(vertices), P.float_lps, P.exact_lps,
                    (("pieces", t1 - t0), ("conditions", t2 - t1)), P.point if rays else None)
    return conditions, route


def _nearby_order(P: _Problem, asked: range) -> list[int]:
    """The facets in an order where each row g_i is close in angle to the one before (greedy nearest
    neighbour on the float rows): the float LPs of consecutive facets then have nearby costs, and HiGHS'
    warm start from the last basis is short.  Only an order: every facet is walked to the horizon all the
    same (index order when floats say nothing)."""
    facets = list(asked)
    if P.G_float is None or len(facets) < 3:
        return facets
    with np.errstate(all="ignore"):
        rows = P.G_float[facets]
        rows = rows / np.linalg.norm(rows, axis=1)[:, None]
        if not np.all(np.isfinite(rows)):
            return facets
        order, left = [0], np.ones(len(facets), dtype=bool)
        left[0] = False
        for _ in range(len(facets) - 1):  # O(m n) memory: one row of cosines at a time
            near = np.where(left, rows @ rows[order[-1]], -np.inf)
            k = int(near.argmax())
            order.append(k)
            left[k] = False
    return [facets[k] for k in order]


def vertex_bound(n: int, m: int) -> int:
    """McMullen's upper bound on the number of vertices of a polytope in R^n with m facets:
    C(m - ceil(n/2), floor(n/2)) + C(m - floor(n/2) - 1, ceil(n/2) - 1) -- the route choice's
    cheap estimate (no vertex is computed).

    >>> vertex_bound(2, 5), vertex_bound(3, 6), vertex_bound(10, 40)
    (5, 8, 371008)
    """
    if m <= n:
        return 1
    lo, hi = n // 2, (n + 1) // 2
    return math.comb(m - hi, lo) + math.comb(m - lo - 1, hi - 1)

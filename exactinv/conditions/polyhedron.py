"""The condition polynomials of the exact valid set (docs/design.md, section 1; beyond the paper).

A_d(dt) P is a subset of P iff A_d(dt) v is in P for every point v of a
minimal generator system of P, A_d(dt) r is in the recession cone for every
ray r, and A_d(dt) l is in the lineality space for every line l.  With
D(dt) = det h(dt A) (D = 1 for polynomial methods) and N(dt) = D(dt) A_d(dt),
a polynomial matrix, each condition is a polynomial sign condition:

    vertex v, facet j:  c(dt) = (b_j D(dt) - g_j N(dt) v) D(dt) >= 0,
    ray r,    facet j:  c(dt) = -(g_j N(dt) r) D(dt) >= 0,
    line l,   facet j:  e(dt) = g_j N(dt) l = 0.

N(dt) = sum_k dt^k N_k is computed once on the small n x n matrices
(:func:`method_matrices`; for a rational method by exact interpolation of
D(t) r(tA) at deg + 1 regular points, one n x n solve per point), and the
coefficients of a vertex-facet polynomial are g_j N_k v: products G N_k W
for all pairs at once, or one length-n dot product per selected pair.  A
polynomial whose coefficient signs show no positive root (Descartes) never
binds and is skipped.  :class:`ConditionSet` builds each of these once per
(system, polyhedron, method) and is shared by the valid set, the largest
threshold and the certificate.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from enum import StrEnum
from fractions import Fraction
from functools import cached_property
from typing import Iterable, TypeVar

import flint

from exactinv_check.format import GeneratorKind

from ..core.flintq import fmpq_of, fraction_of
from ..core.polys import integer_part
from ..model import LinearSystem, Method, Polyhedron
from ..model.methods import matrix_polynomial
from ..model.validate import check_problem

_Cache = TypeVar("_Cache")

__all__ = ["Kind", "Condition", "ConditionSet", "method_matrices", "never_binds", "conditions_of", "distinct_conditions"]


class Kind(StrEnum):
    """Which generator of P a condition is about (equal to the old strings); on an ellipsoid,
    ``COEFFICIENT``: the condition is h q_k(h) >= 0 of the k-th coefficient polynomial."""

    VERTEX = GeneratorKind.VERTEX.value  # the certificate's kinds (exactinv_check.format.GeneratorKind)
    RAY = GeneratorKind.RAY.value
    LINE = GeneratorKind.LINE.value
    COEFFICIENT = "coefficient"  # an ellipsoid's q_k (generator k): exactinv.validset.ellipsoid


@dataclass(frozen=True)
class Condition:
    """One polynomial condition: ``kind`` is "vertex", "ray" or "line";
    ``generator`` the index in P.vertices / P.rays / P.lines; ``facet`` the row
    of G; ``poly`` the coefficients (dt^0 ..) of c (>= 0 required) or e (= 0)."""

    kind: Kind
    generator: int
    facet: int
    p: flint.fmpq_poly = field(repr=False, compare=False)

    @property
    def poly(self) -> tuple[Fraction, ...]:
        return tuple(fraction_of(c) for c in self.p.coeffs())


def method_matrices(method: Method, A: flint.fmpq_mat) -> tuple[flint.fmpq_poly, list[flint.fmpq_mat]]:
    """(D, [N_0, N_1, ...]) with D(t) = det h(tA) and D(t) r(tA) = sum_k t^k N_k, exactly.

    Polynomial methods: D = 1, N_k = sigma_k A^k.  Rational methods: D and the
    n^2 entries of N are polynomials of degree <= max(n deg h, (n-1) deg h + deg g),
    interpolated from their values at that many + 1 points t = 0, 1, 2, ... where
    h(tA) is regular -- one n x n determinant and solve per point, then one
    product with the inverse Vandermonde matrix for all n^2 + 1 entries at once.

    >>> from exactinv.model import methods
    >>> D, N = method_matrices(methods.backward_euler(), flint.fmpq_mat([[2]]))
    >>> [int(c) for c in D.coeffs()], [int(Nk[0, 0]) for Nk in N]   # D = det(1 - 2t), N = D r(2t) = 1
    ([1, -2], [1])
    """
    n = A.nrows()
    if method.is_polynomial:
        out, power = [], flint.fmpq_mat(n, n, [int(i == j) for i in range(n) for j in range(n)])
        for k, s in enumerate(method.sigmas):
            if k:
                power = power * A
            out.append(power * fmpq_of(s))
        return flint.fmpq_poly([1]), out
    dh, dg = len(method.denominator) - 1, len(method.numerator) - 1
    count = max(n * dh, (n - 1) * dh + dg) + 1
    points, rows = [], []
    t = 0
    while len(points) < count:
        M = A * t
        H = matrix_polynomial(method.denominator, M)
        d = H.det()
        if d != 0:
            X = H.solve(matrix_polynomial(method.numerator, M)) * d
            points.append(t)
            rows.append([d] + X.entries())
        t += 1
    vandermonde = flint.fmpq_mat(count, count, [fmpq_of(p) ** e for p in points for e in range(count)])
    coeffs = vandermonde.inv() * flint.fmpq_mat(count, n * n + 1, [x for row in rows for x in row])
    D = flint.fmpq_poly([coeffs[e, 0] for e in range(count)])
    N = [flint.fmpq_mat(n, n, [coeffs[e, 1 + k] for k in range(n * n)]) for e in range(count)]
    while len(N) > 1 and not any(N[-1].entries()):
        N.pop()
    return D, N


def _generator_matrix(rows) -> flint.fmpq_mat | None:
    """The generators as the columns of an n x count matrix (None if there are none)."""
    if not rows:
        return None
    n, count = len(rows[0]), len(rows)
    return flint.fmpq_mat(n, count, [fmpq_of(rows[i][k]) for k in range(n) for i in range(count)])


def _integer_row(row: list) -> tuple[list[int], int]:
    """(d w, d) with d > 0 the least common denominator of the rationals w."""
    d = math.lcm(*(int(x.q) for x in row))
    return [int(x.p) * (d // int(x.q)) for x in row], d


def never_binds(coeffs) -> bool:
    """No sign variation and a positive coefficient: c > 0 on (0, oo) (Descartes) -- that is,
    every coefficient >= 0 (True for the zero polynomial, which is >= 0 everywhere).

    >>> never_binds([0, 1, 2]), never_binds([1, -1]), never_binds([])
    (True, False, True)
    """
    return min(coeffs, default=0) >= 0


class ConditionSet:
    """The conditions of one (system, polyhedron, method), each built at most once.

    ``D`` and ``N`` (:func:`method_matrices`) are computed on construction;
    :meth:`all` builds every generator-facet condition (FLINT products
    G N_k W), :meth:`pairs` only selected ones; both cache what they built."""

    def __init__(self, system: LinearSystem, polyhedron: Polyhedron, method: Method):
        system, polyhedron, method = check_problem(system, polyhedron, method)
        self.system, self.polyhedron, self.method = system, polyhedron, method
        self.D, self.N = method_matrices(method, system.A_flint)
        self.Dcoeffs = [fraction_of(c) for c in self.D.coeffs()]
        self.G = polyhedron.G_flint
        self.b = [fmpq_of(x) for x in polyhedron.b]
        # what a route derives once per problem, keyed by the function that derives it (the box route)
        self.derived: dict[object, object] = {}
        self._caches: dict[type, object] = {}
        self._generator_rows: dict[Kind, list[list]] = {}
        self._built: dict[tuple, Condition | None] = {}
        self._facet_matrices: dict[int, tuple[flint.fmpz_mat, list[int]]] = {}
        self._all: tuple[list[Condition], list[Condition]] | None = None

    def cache(self, kind: type[_Cache]) -> _Cache:
        """The one instance of ``kind`` kept for this problem, created (``kind()``) on first use: a route's
        typed cache, keyed by its class (the LP route's :class:`~exactinv.validset.lp_route.LPRouteCache`).

        >>> from exactinv.model import methods
        >>> cs = ConditionSet(LinearSystem([[-1]]), Polyhedron.box([-1], [1]), methods.forward_euler())
        >>> cs.cache(list) is cs.cache(list), cs.cache(list)
        (True, [])
        """
        found = self._caches.get(kind)
        if found is None:
            found = self._caches[kind] = kind()
        return found  # type: ignore[return-value]

    @cached_property
    def W(self) -> dict[Kind, flint.fmpq_mat | None]:
        """The generators of each kind as matrix columns (vertex enumeration on first use only)."""
        P = self.polyhedron
        return {Kind.VERTEX: _generator_matrix(P.vertices), Kind.RAY: _generator_matrix(P.rays),
                Kind.LINE: _generator_matrix(P.lines)}

    def count(self, kind: Kind) -> int:
        """How many generators of this kind P has.

        >>> from exactinv.model import methods
        >>> cs = ConditionSet(LinearSystem([[-1]]), Polyhedron.box([-1], [1]), methods.forward_euler())
        >>> cs.count(Kind.VERTEX), cs.count(Kind.RAY)   # [-1, 1]: the vertices -1 and 1, no ray
        (2, 0)
        """
        W = self.W[kind]
        return 0 if W is None else W.ncols()

    def _condition(self, kind: Kind, i: int, j: int, gN: list) -> Condition | None:
        """The condition of generator i of ``kind`` and facet j from g_j N_k w (k = 0, 1, ...)."""
        if kind == Kind.LINE:
            poly = flint.fmpq_poly(gN)
            return None if poly.is_zero() else Condition(kind, i, j, poly)
        q = -flint.fmpq_poly(gN)
        if kind == Kind.VERTEX:
            q += self.D * self.b[j]
        c = q * self.D
        return None if never_binds(c.coeffs()) else Condition(kind, i, j, c)

    def pairs(self, kind: Kind, pairs: Iterable[tuple[int, int]]) -> list[Condition]:
        """The nontrivial conditions of the (generator, facet) pairs given, each built once.

        x' = -x on [-1, 1] = {x <= 1, -x <= 1} (vertices -1, 1), forward Euler, N(dt) = 1 - dt:
        vertex -1, facet x <= 1 gives c = 1 + (1 - dt) = 2 - dt; vertex -1, facet -x <= 1
        gives c = 1 - (1 - dt) = dt, which never binds (Descartes) and is skipped.

        >>> from exactinv.model import methods
        >>> cs = ConditionSet(LinearSystem([[-1]]), Polyhedron.box([-1], [1]), methods.forward_euler())
        >>> [c.poly for c in cs.pairs(Kind.VERTEX, [(0, 0), (0, 1)])]
        [(Fraction(2, 1), Fraction(-1, 1))]
        """
        pairs = list(pairs)
        if not pairs:
            return []
        n = self.polyhedron.n
        if kind not in self._generator_rows:  # each generator as integers d_i w_i, with d_i > 0
            self._generator_rows[kind] = [_integer_row(r) for r in self.W[kind].transpose().tolist()]
        rows = self._generator_rows[kind]
        by_facet: dict[int, list[int]] = {}
        for i, j in pairs:
            if (kind, i, j) not in self._built:
                by_facet.setdefault(j, []).append(i)
        for j, generators in by_facet.items():  # one FLINT product per facet: rows d_i w_i, columns e_k (g_j N_k)^T
            Gz, e = self._facet_matrix(j)
            Wz = flint.fmpz_mat(len(generators), n, [x for i in generators for x in rows[i][0]])
            product = Wz * Gz
            width, d = product.ncols(), [rows[i][1] for i in generators]
            if kind != Kind.LINE and self.D.coeffs() == [1]:  # c = q: its integer rows decide it and build it
                self._build_from_rows(kind, j, generators, d, self._q_rows(kind, j, d, product, e), e)
                continue
            clear = self._clear_rows(kind, j, d, product, e)
            coeffs = product.entries()
            for r, i in enumerate(generators):
                self._built[kind, i, j] = None if clear[r] else self._condition(
                    kind, i, j, [flint.fmpq(coeffs[r * width + k], rows[i][1] * e[k]) for k in range(width)])
        out = []
        for i, j in pairs:
            c = self._built[kind, i, j]
            if c is not None:
                out.append(c)
        return out

    def _facet_matrix(self, j: int) -> tuple[flint.fmpz_mat, list[int]]:
        """(Gz, e): the n x L' integer matrix with columns e_k (g_j N_k)^T, e_k > 0 clearing the
        denominators of that column and of b_j D_k (L' = max(len N, len D)); cached per facet."""
        if j not in self._facet_matrices:
            n, Dc = self.polyhedron.n, self.D.coeffs()
            width = max(len(self.N), len(Dc))
            cols = [[self.GN[k][j][l] for l in range(n)] if k < len(self.N) else [flint.fmpq(0)] * n
                    for k in range(width)]
            e = [math.lcm(*(int(x.q) for x in col), int((self.b[j] * Dc[k]).q) if k < len(Dc) else 1)
                 for k, col in enumerate(cols)]
            Gz = flint.fmpz_mat(n, width, [int(cols[k][l].p) * (e[k] // int(cols[k][l].q))
                                          for l in range(n) for k in range(width)])
            self._facet_matrices[j] = (Gz, e)
        return self._facet_matrices[j]

    @cached_property
    def GN(self) -> list[list[list[flint.fmpq]]]:
        """The products G N_k as nested lists (row j of G N_k: g_j N_k).

        >>> from exactinv.model import methods
        >>> ConditionSet(LinearSystem([[-1]]), Polyhedron.box([-1], [1]), methods.forward_euler()).GN
        [[[1], [-1]], [[-1], [1]]]
        """
        return [(self.G * Nk).tolist() for Nk in self.N]

    def _q_rows(self, kind: Kind, j: int, d: list[int], product: flint.fmpz_mat, e: list[int]) -> list:
        """The integers d_r e_k q_k, row after row, of q = b_j D - g_j N w_r (vertices; -g_j N w_r
        for rays) from ``product`` (d_r e_k g_j N_k w_r): positive multiples of q's coefficients."""
        Dc, width = self.D.coeffs(), product.ncols()
        bj = self.b[j] if kind == Kind.VERTEX else 0
        brow = flint.fmpz_mat(1, width, [int(bj * Dc[k] * e[k]) if k < len(Dc) else 0 for k in range(width)])
        return (flint.fmpz_mat(len(d), 1, d) * brow - product).entries()

    def _clear_rows(self, kind: Kind, j: int, d: list[int], product: flint.fmpz_mat, e: list[int]) -> list[bool]:
        """Per row r of ``product`` (d_r e_k g_j N_k w_r, k = 0, 1, ...): True when every coefficient
        of q = b_j D - g_j N w (vertices; -g_j N w for rays) is >= 0 and so are D's -- then c = q D has
        no negative coefficient and never binds (Descartes).  Decided on the integers d_r e_k q_k."""
        if kind == Kind.LINE or any(c < 0 for c in self.D.coeffs()):
            return [False] * len(d)
        q, width = self._q_rows(kind, j, d, product, e), product.ncols()
        return [all(x >= 0 for x in q[r * width:(r + 1) * width]) for r in range(len(d))]

    def _build_from_rows(self, kind: Kind, j: int, generators: list[int], d: list[int], q: list, e: list[int]):
        """D = 1 (polynomial methods): c = q, decided and built from the integer rows d_r e_k q_k of
        :meth:`_q_rows` -- their signs are those of c's coefficients (:func:`never_binds`), and
        c_k = (d_r e_k q_k) (E / e_k) / (d_r E) with E = lcm(e), one integer polynomial over d_r E."""
        width, E = len(e), math.lcm(*e)
        f = [E // x for x in e]
        for r, i in enumerate(generators):
            row = q[r * width:(r + 1) * width]
            self._built[kind, i, j] = None if never_binds(row) else Condition(
                kind, i, j, flint.fmpq_poly([x * y for x, y in zip(row, f)], d[r] * E))

    def all(self) -> tuple[list[Condition], list[Condition]]:
        """(inequalities, equalities) over every generator-facet pair (built once).

        x' = -x on [-1, 1], forward Euler: each vertex v = +-1 gives 1 + v(1 - dt) >= 0 on the
        facet it does not lie on, 2 - dt >= 0 (the threshold 2); the other two are dt >= 0, skipped.

        >>> from exactinv.model import methods
        >>> cs = ConditionSet(LinearSystem([[-1]]), Polyhedron.box([-1], [1]), methods.forward_euler())
        >>> inequalities, equalities = cs.all()
        >>> [(c.generator, c.facet, c.poly) for c in inequalities], equalities
        ([(0, 0, (Fraction(2, 1), Fraction(-1, 1))), (1, 1, (Fraction(2, 1), Fraction(-1, 1)))], [])
        """
        if self._all is None:
            conditions: list[Condition] = []
            equalities: list[Condition] = []
            for kind in (Kind.VERTEX, Kind.RAY, Kind.LINE):
                if self.W[kind] is not None:
                    (equalities if kind == Kind.LINE else conditions).extend(self._all_of(kind))
            self._all = (conditions, equalities)
        return self._all

    def _all_of(self, kind: Kind) -> list[Condition]:
        W = self.W[kind]
        entries = [(self.G * (Nk * W)).entries() for Nk in self.N]
        cols, m, b = W.ncols(), self.G.nrows(), self.b
        Dc = self.D.coeffs()
        # D's coefficients all >= 0 (always for polynomial methods, D = 1): if those of
        # q = b_j D - g_j N w are too, c = q D has no negative coefficient and never binds
        cheap_skip = kind != Kind.LINE and all(c >= 0 for c in Dc)
        Dc = Dc + [flint.fmpq(0)] * (len(entries) - len(Dc))
        out = []
        for j in range(m):
            bj = b[j] if kind == Kind.VERTEX else 0
            for i in range(cols):
                idx = j * cols + i
                if cheap_skip and all(e[idx] <= bj * d for e, d in zip(entries, Dc)) and \
                        all(bj * d >= 0 for d in Dc[len(entries):]):
                    continue  # every coefficient of c is >= 0: never binds (Descartes), decided before building c
                c = self._condition(kind, i, j, [e[idx] for e in entries])
                if c is not None:
                    out.append(c)
        return out


def conditions_of(system: LinearSystem, P: Polyhedron, method: Method):
    """All vertex/ray inequality conditions c >= 0, line equalities e = 0, D and its coefficients.

    Backward Euler on x' = -x over [-1, 1]: D(dt) = 1 + dt and N(dt) = 1, so vertex -1 on the
    facet x <= 1 gives c = (D + 1) D = 2 + 3 dt + dt^2 > 0 -- no condition binds.

    >>> from exactinv.model import methods
    >>> inequalities, equalities, D, Dcoeffs = conditions_of(LinearSystem([[-1]]), Polyhedron.box([-1], [1]),
    ...                                                      methods.backward_euler())
    >>> inequalities, equalities, Dcoeffs
    ([], [], [Fraction(1, 1), Fraction(1, 1)])
    """
    cs = ConditionSet(system, P, method)
    conditions, equalities = cs.all()
    return conditions, equalities, cs.D, cs.Dcoeffs


def distinct_conditions(conditions: list[Condition]) -> dict[tuple, Condition]:
    """The conditions with distinct polynomials (up to a positive factor), first kept.

    Forward Euler on x' = -x over [-1, 1]: both vertices give c = 2 - dt, kept once.

    >>> from exactinv.model import methods
    >>> inequalities, _, _, _ = conditions_of(LinearSystem([[-1]]), Polyhedron.box([-1], [1]), methods.forward_euler())
    >>> distinct_conditions(inequalities)
    {(2, -1): Condition(kind=<Kind.VERTEX: 'vertex'>, generator=0, facet=0)}
    """
    seen: dict[tuple, Condition] = {}
    for c in conditions:
        key = tuple(map(int, integer_part(c.p).coeffs()))
        if key not in seen:
            seen[key] = c
    return seen

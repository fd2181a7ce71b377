"""An ``lp`` record: the LP route's pieces, proved; the valid set's conditions without a vertex list.

The record gives, for every facet i of P = {Gx <= b}, consecutive closed pieces
[s_0 = 0, e_0], [e_0, e_1], ..., [e_(K-2), e_(K-1)] (ends exact reals, strictly
increasing; the last may be oo) and one basis per piece: n rows of G.  The
kernel proves, for each piece with basis B (docs/design.md, "The LP route"):

1. B is nonsingular and x_B = B^-1 b_B lies in P (G x_B <= b, exactly);
2. z_B(h) = D(h) B^-T N(h)^T g_i >= 0 on the whole piece, component by
   component (D = det h_r(hA), N = D r(hA), rebuilt by the kernel): Descartes'
   rule on an interval holding the piece, else every root of the component
   isolated (Sturm) and its sign sampled on each cell of the piece between them.

Then weak duality gives, for h in the piece with D(h) != 0 and any x in P,
g_i A_d(h) x <= g_i A_d(h) x_B: B^T y = N^T g_i with D y >= 0, so
D g_i N x = D y^T B x <= D y^T b_B = D g_i N x_B, and dividing by D^2 > 0.
Hence with p_ik = (b_i D - g_i N x_B) D, the vertex-facet condition of x_B and
facet i, {h : every p_ik(h) >= 0, D(h) != 0} equals the valid set on
[0, E], E the least last end over the facets (every such h is in a piece of
every facet), and each p_ik >= 0 is necessary everywhere (x_B is a point of P).
When E < oo the kernel also requires that the set of these conditions lies in
[0, E] -- then it is the valid set exactly.  The conditions are built by
:func:`exactinv_check.conditions.condition_polynomials` on the points x_B.

No vertex enumeration and no edge walk: the work is priced first, per piece one
fraction-free n x n solve and n components of degree deg N + deg D.
"""

from fractions import Fraction
from types import SimpleNamespace

from . import polys
from .conditions import condition_polynomials, method_matrices, rebuild_size
from .linalg import integer_solve
from .rationals import WORK_BUDGET, integer, integer_matrix, integer_rows, require, within_budget
from .reals import Real, separate
from .validset import valid_set

MAX_PIECES = 200_000  # pieces over all facets: a bound before any parsing of their ends
LP_WORK_BUDGET = 50 * WORK_BUDGET  # all pieces of one record together (measured: ~5 ms a piece in R^16-R^20)


def parse(record, m, n):
    """[(ends, bases)] per facet, shape-checked: ends are proved reals, strictly increasing and > 0."""
    require(isinstance(record, dict) and set(record) == {"facets"}, "lp has the key facets")
    facets = record["facets"]
    require(isinstance(facets, list) and len(facets) == m, f"lp: one entry per facet ({m})")
    total = 0
    out = []
    for i, f in enumerate(facets):
        require(isinstance(f, dict) and set(f) == {"ends", "bases"}, f"lp facet {i}: the keys ends, bases")
        ends, bases = f["ends"], f["bases"]
        require(isinstance(ends, list) and isinstance(bases, list) and 1 <= len(ends) == len(bases),
                f"lp facet {i}: as many ends as bases, at least one")
        total += len(ends)
        require(total <= MAX_PIECES, f"lp: more than {MAX_PIECES} pieces")
        rows = []
        for basis in bases:
            require(isinstance(basis, list) and len(basis) == n, f"lp facet {i}: a basis is a list of {n} rows")
            r = tuple(integer(x, f"lp facet {i} basis row", 0, m) for x in basis)
            require(len(set(r)) == n, f"lp facet {i}: a basis repeats a row")
            rows.append(r)
        out.append((ends, rows))
    return out


def _price(problem, pieces):
    """Reject before any work.  One piece is one computation, priced against the kernel's budget of one
    (:func:`within_budget`): a Bareiss solve (n^3 w^2) and n components of degree d whose sign is decided
    on the piece (about d^2 w each); the rebuild of D and N likewise.  All pieces together are bounded by
    :data:`LP_WORK_BUDGET` (each piece is independent work, so the record's total is capped like the
    vertex route's MAX_CONDITIONS: about a minute or two of checking for R^20 with 200 facets)."""
    n = problem.n
    cost, d, w = rebuild_size(problem.A, problem.method.numerator, problem.method.denominator)
    within_budget(cost, f"D(h) and N(h) of a {n} x {n} problem")
    _, Gi = integer_matrix(problem.G)
    gw = 1 + max(abs(x).bit_length() for row in Gi for x in row) * n // 64
    one = n ** 3 * gw * gw + n * (n + d) * (2 * d + 2) ** 2 * (w + gw)
    within_budget(one, f"one piece of the LP route ({n} x {n}, degree {d})")
    require(pieces * one <= LP_WORK_BUDGET, f"over the kernel's work budget: the LP route's {pieces} pieces "
            f"(estimated {pieces * one:.2e} word operations > {LP_WORK_BUDGET:.0e})")


class _Bases:
    """The proved bases: B nonsingular and x_B in P; the integer rows of G."""

    def __init__(self, G, b):
        self.rows = integer_rows(G, b)  # (g, beta) in integers, the same half-spaces
        self.proved = {}

    def vertex(self, basis):
        """x_B as Fractions, after proving B nonsingular and G x_B <= b."""
        if basis not in self.proved:
            B = [self.rows[r][0] for r in basis]
            d, X = integer_solve(B, [[self.rows[r][1]] for r in basis])
            require(d != 0, f"the basis {list(basis)} is singular")
            x = [row[0] for row in X]  # x_B = x / d
            s = 1 if d > 0 else -1
            for k, (g, beta) in enumerate(self.rows):
                require(s * sum(a * v for a, v in zip(g, x) if a) <= s * beta * d,
                        f"x_B of the basis {list(basis)} violates row {k} of G x <= b")
            self.proved[basis] = [Fraction(v, d) for v in x]
        return self.proved[basis]


def _components(bases, basis, C_int, D_int):
    """The components of a positive multiple of z_B = D B^-T C (h), as integer coefficient lists
    (B^T with the integer rows of G: a positive row scaling of B scales each component by a
    positive factor)."""
    BT = [list(col) for col in zip(*(bases.rows[r][0] for r in basis))]
    d, X = integer_solve(BT, C_int)
    require(d != 0, f"the basis {list(basis)} is singular")
    s = 1 if d > 0 else -1
    out = []
    for row in X:
        p = polys.trim([s * v for v in row])
        if p and len(D_int) > 1:
            p = polys.trim(polys.mul_integers(p, D_int))
        out.append(p)
    return out


def _shift_signs(ints, a):
    """v^D p(a + y) for a = u/v (v > 0): integer coefficients with the signs of p(a + y)'s
    (Horner: r_D = c_D, r_k = r_(k+1) (u + v y) + c_k v^(D-k))."""
    u, v = a.numerator, a.denominator
    D = len(ints) - 1
    q = [ints[-1]]
    for k in range(D - 1, -1, -1):
        q = [u * q[0]] + [u * q[i] + v * q[i - 1] for i in range(1, len(q))] + [v * q[-1]]
        q[0] += ints[k] * v ** (D - k)
    return q


def _positive_around(ints, a, b):
    """True proves p > 0 on the open (a, b) (b None: (a, oo)); False says nothing."""
    if b is None:
        q = _shift_signs(ints, a)
        return all(c >= 0 for c in q) and any(c > 0 for c in q)
    return polys.descartes_variations(ints, a, b) == 0 and polys.sign_at(ints, (a + b) / 2) > 0


def _vanishes_at(p, r):
    """True if p(r) = 0 for an algebraic r (its squarefree polynomial has the one root r in (lo, hi)):
    gcd(p, r's polynomial) changes sign on (lo, hi).  False says nothing."""
    g = polys.gcd(p, r.poly)
    return len(g) > 1 and polys.sign_at(polys.integer_coefficients(g), r.lo) * \
        polys.sign_at(polys.integer_coefficients(g), r.hi) < 0


def _sliver(p, ints, r, inner):
    """True proves p > 0 on the part of r's enclosure inside the piece ([r, hi] when r starts it,
    [lo, r) when r ends it; ``inner`` is the other end of the enclosure, hi or lo): Descartes sees
    no root in (lo, hi), or exactly one and it is r itself; and p > 0 at ``inner``."""
    if polys.sign_at(ints, inner) <= 0:
        return False
    v = polys.descartes_variations(ints, r.lo, r.hi)
    return v == 0 or (v == 1 and _vanishes_at(p, r))


def _fast(p, ints, start, end):
    """True proves p >= 0 on [start, end]: Descartes on the open interval between the enclosures of
    the ends, and on each algebraic end's enclosure (:func:`_sliver`).  False says nothing."""
    a = start.hi if start.poly is not None else start.q
    b = None if end.inf else (end.lo if end.poly is not None else end.q)
    if b is not None and not a < b:
        return False
    if not _positive_around(ints, a, b):
        return False
    if start.poly is not None and not _sliver(p, ints, start, start.hi):
        return False
    return end.inf or end.poly is None or _sliver(p, ints, end, end.lo)


def _require_nonnegative(p, start, end, what):
    """p >= 0 on the closed piece [start, end] (end may be oo), or CheckFailure."""
    if not p:
        return
    ints = polys.integer_coefficients(p)
    a = start.bounds()[0]
    b = None if end.inf else end.bounds()[1]
    if _positive_around(ints, a, b) or _fast(p, ints, start, end):
        return  # p > 0 on (a, b), which holds (start, end); >= 0 at the ends by continuity
    points = [start]
    for lo, hi in polys.positive_roots(p):
        r = Real.root_in(p, lo, hi)
        if start.compare(r) < 0 and (end.inf or r.compare(end) < 0):
            points.append(r)
    points.append(end)
    for u, v in zip(points, points[1:]):
        if v.inf:
            q = u.bounds()[1] + 1
        else:
            a1, b0 = separate(u, v)
            q = (a1 + b0) / 2
        require(polys.sign_at(ints, q) > 0, f"{what} is negative inside its piece (at {q})")


def lp_conditions(problem, record):
    """(generators, D, inequalities, horizon): the pieces proved (module docstring), the conditions of their
    points x_B (keyed (kind, flat piece index, facet)) and E, the least last end over the facets."""
    n, m = problem.n, problem.m
    facets = parse(record, m, n)
    _price(problem, sum(len(ends) for ends, _ in facets))
    method = problem.method
    D, N = method_matrices(problem.A, method.numerator, method.denominator)
    D_int = polys.integer_coefficients(D)
    bases = _Bases(problem.G, problem.b)
    dN, N_int = integer_matrix([row for Nk in N for row in Nk])  # N_k = N_int[k n .. k n + n - 1] / dN
    points, facet_of = [], []
    horizon = None
    for i, (ends, rows) in enumerate(facets):
        # C_i: column k = (g_i N_k)^T, times one positive integer (the same for all of it)
        g = bases.rows[i][0]
        C_int = [[sum(g[j] * N_int[k * n + j][l] for j in range(n) if g[j]) for k in range(len(N))]
                 for l in range(n)]
        start = Real.rational(0)
        for k, (data, basis) in enumerate(zip(ends, rows)):
            end = Real.parse(data, f"lp facet {i} end {k}")
            require(start.compare(end) < 0, f"lp facet {i}: the ends are not increasing after piece {k}")
            require(not end.inf or k == len(ends) - 1, f"lp facet {i}: only the last piece may end at oo")
            x = bases.vertex(basis)
            for l, p in enumerate(_components(bases, basis, C_int, D_int)):
                _require_nonnegative(p, start, end, f"lp facet {i} piece {k}: component {l} of z_B")
            points.append(x)
            facet_of.append(i)
            start = end
        if horizon is None or start.compare(horizon) < 0:
            horizon = start
    generators = SimpleNamespace(vertices=points, rays=[], lines=[], counts=(len(points), 0, 0))
    D2, inequalities, _ = condition_polynomials(problem.A, problem.G, problem.b, method.numerator,
                                                method.denominator, generators, lambda kind, k: [facet_of[k]])
    return generators, D2, inequalities, horizon


def require_horizon(D, inequalities, horizon, context, key):
    """When the pieces stop at E < oo: the set of the conditions lies in [0, E] (then it is the valid set)."""
    if horizon.inf:
        return
    if key not in context:
        context[key] = valid_set(D, list(inequalities), [])
    W = context[key]
    require(W and not W[-1].hi.inf and W[-1].hi.compare(horizon) <= 0,
            f"the pieces stop at {horizon}, but their conditions allow steplengths beyond it")

"""The LP route on P with lines (exactinv/validset/lp_lines.py): P = L + Q, L = ker G; the pieces on
P' = P with a basis of L as rows l^T x <= 0 and the line equalities g_i N(h) l = 0.  Valid sets
worked out by hand (a slab, a strip times an interval, a rotated slab, a cylinder over a polygon),
the LP route against the vertex route and against PPL's exact simplex just inside and outside every
end, and forged ``lines`` records that the kernel rejects."""

import copy
import random
from fractions import Fraction

import flint
import ppl
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
import exactinv_check
from exactinv.conditions.polyhedron import ConditionSet
from exactinv.core.algebraic import RealAlgebraic
from exactinv.core.scalars import Infinity
from exactinv.errors import InvalidInput
from exactinv.validset.lp_lines import LPLinesRoute, lineality_basis, lp_lines
from exactinv.validset.lp_route import LPRouteDeclined

M = ei.methods
F = Fraction
INF = float("inf")


def _ends(V):
    return [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V]


def _routes(S, P, method):
    """The LP route's valid set (certificate checked by the kernel) after asserting it equals the vertex
    route's, end by end and flag by flag, and the largest thresholds agree."""
    V = ei.valid_steplengths(S, P, method, route="lp")
    W = ei.valid_steplengths(S, P, method, route="vertex")
    assert V.route == "lp" and isinstance(V.lp, LPLinesRoute)
    assert _ends(V) == _ends(W), (V, W)
    L1, L2 = (ei.largest_threshold(S, P, method, route=r) for r in ("lp", "vertex"))
    assert (L1.value, L1.attained) == (L2.value, L2.attained)
    assert exactinv_check.check(V.certificate).ok and exactinv_check.check(L1.certificate).ok
    return V


def _is_root_of(x, coeffs):
    """The exact algebraic x is a root of the integer polynomial (coefficients h^0 ..)."""
    assert isinstance(x, RealAlgebraic)
    return (flint.fmpz_poly(coeffs) % x.poly).is_zero()


# ------------------------------------------------------------------ worked by hand


def test_lineality_basis():
    assert lineality_basis(flint.fmpq_mat([[1, 0], [-1, 0]])) == ((0, 1),)
    assert lineality_basis(flint.fmpq_mat([[1, 1], [-1, -1]])) == ((-1, 1),)
    assert lineality_basis(flint.fmpq_mat([[2, 0, 4], [-1, 0, -2]])) == ((0, 1, 0), (-2, 0, 1))
    assert lineality_basis(flint.fmpq_mat([[1, 0], [0, 1]])) == ()


def test_a_slab_whose_line_is_invariant_by_hand():
    """|x_1| <= 1 in R^2 under x' = -x: A_d(h) = r(-h) I keeps the line x_2, and the slab iff |r(-h)| <= 1.
    Forward Euler |1 - h| <= 1: [0, 2]; Taylor(2) 1 - h + h^2/2 (>= 1/2) <= 1 iff h <= 2: [0, 2];
    backward Euler 1/(1 + h) in (0, 1]: [0, oo)."""
    S, P = ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    assert _ends(_routes(S, P, M.forward_euler())) == [(0, 2, True, True)]
    assert _ends(_routes(S, P, M.taylor(2))) == [(0, 2, True, True)]
    V = _routes(S, P, M.backward_euler())
    assert len(list(V)) == 1 and list(V)[0].lo == 0 and isinstance(list(V)[0].hi, Infinity)
    assert V.lp.lines == ((0, 1),) and V.certificate["claims"][0]["lp"]["lines"] == [["0", "1"]]


def test_a_slab_whose_line_feeds_the_facet_isolated_steplengths_by_hand():
    """|x_1| <= 1, A = [[-1, 1], [0, -1]]: r(hA) = [[r(-h), h r'(-h)], [0, r(-h)]], so the line (0, 1)
    leaves the slab unless e(h) = h r'(-h) = 0; there A_d = r(-h) I, valid iff |r(-h)| <= 1.
    Forward Euler (r' = 1): {0}.  Taylor(2) (r'(-h) = 1 - h): {0, 1}, r(-1) = 1/2.  Taylor(4):
    r'(-h) = 1 - h + h^2/2 - h^3/6 = 0 at the real root tau of h^3 - 3h^2 + 6h - 6 (tau ~ 1.596),
    where r(-tau) = tau^4/24 in [0, 1]: {0, tau}.  Isolated roots of the line equality, each decided
    by the pieces of P' at that point."""
    S, P = ei.LinearSystem([[-1, 1], [0, -1]]), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    assert _ends(_routes(S, P, M.forward_euler())) == [(0, 0, True, True)]
    assert _ends(_routes(S, P, M.taylor(2))) == [(0, 0, True, True), (1, 1, True, True)]
    V = _routes(S, P, M.taylor(4))
    assert len(list(V)) == 2 and _ends(V)[0] == (0, 0, True, True) and list(V)[1].lo == list(V)[1].hi
    assert _is_root_of(list(V)[1].lo, [-6, 6, -3, 1])


def test_a_slab_with_a_pole_and_the_sign_of_d():
    """|x_1| <= 1 under x' = diag(1, -1) x, backward Euler: r(hA) = diag(1/(1 - h), 1/(1 + h)),
    D(h) = (1 - h)(1 + h) changes sign at the pole h = 1.  The line (0, 1) is invariant;
    |1/(1 - h)| <= 1 iff h = 0 or h >= 2: V = {0} U [2, oo)."""
    S, P = ei.LinearSystem([[1, 0], [0, -1]]), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    V = _routes(S, P, M.backward_euler())
    assert _ends(V)[0] == (0, 0, True, True) and (list(V)[1].lo, list(V)[1].lo_closed) == (2, True)
    assert isinstance(list(V)[1].hi, Infinity)


def test_a_strip_times_an_interval_in_r3_by_hand():
    """P = {|x_1| <= 1, |x_3| <= 1} in R^3 (line e_2), A = [[-1, 0, 1], [3, -2, 5], [0, 0, -2]]:
    A e_2 = -2 e_2, so the facets see the quotient A' = [[-1, 1], [0, -2]] on [-1, 1]^2.
    Forward Euler [[1 - h, h], [0, 1 - 2h]]: |1 - h| + h <= 1 and |1 - 2h| <= 1 iff h <= 1.
    Taylor(2): row 2 is 1 - 2h + 2h^2 <= 1 iff h <= 1; row 1 is |1 - h + h^2/2| + |h - 3h^2/2|,
    1 - h^2 for h <= 2/3 and 1 - 2h + 2h^2 after: <= 1 iff h <= 1.  Both V = [0, 1]."""
    S = ei.LinearSystem([[-1, 0, 1], [3, -2, 5], [0, 0, -2]])
    P = ei.Polyhedron([[1, 0, 0], [-1, 0, 0], [0, 0, 1], [0, 0, -1]], [1, 1, 1, 1])
    for method in (M.forward_euler(), M.taylor(2)):
        V = _routes(S, P, method)
        assert _ends(V) == [(0, 1, True, True)]
        assert V.lp.lines == ((0, 1, 0),)


def test_a_rotated_slab_by_hand():
    """P = {|x_1 + x_2| <= 1} (line (1, -1)), A = [[-2, -1], [-1, -2]]: g A = -3 g for g = (1, 1) and
    A (1, -1) = -(1, -1), so A_d(h) g-direction is r(-3h): V = {h : |r(-3h)| <= 1}.  Forward Euler
    |1 - 3h| <= 1: [0, 2/3]; Taylor(2) 1 - 3h + 9h^2/2 <= 1 iff h <= 2/3; backward Euler 1/(1 + 3h):
    [0, oo).  With A = diag(-2, -1) instead the line feeds the facet: e(h) = g N(h) (1, -1) = -h for
    forward Euler, V = {0}."""
    P = ei.Polyhedron([[1, 1], [-1, -1]], [1, 1])
    S = ei.LinearSystem([[-2, -1], [-1, -2]])
    assert _ends(_routes(S, P, M.forward_euler())) == [(0, F(2, 3), True, True)]
    assert _ends(_routes(S, P, M.taylor(2))) == [(0, F(2, 3), True, True)]
    assert isinstance(list(_routes(S, P, M.backward_euler()))[0].hi, Infinity)
    V = _routes(ei.LinearSystem([[-2, 0], [0, -1]]), P, M.forward_euler())
    assert _ends(V) == [(0, 0, True, True)] and V.lp.lines == ((-1, 1),)


def test_a_cylinder_over_the_papers_box():
    """[-1, 1]^2 x R (line e_3) under A = [[-1, 1, 0], [-1, -1, 0], [2, 3, -1]]: A e_3 = -e_3 and the
    facets see the paper's A' = [[-1, 1], [-1, -1]] on the square, so Taylor(4)'s valid set is the
    paper's [0, L], L the real root of h^4 - 6h^2 + 12h - 12 (README) -- and equal to the 2-D one."""
    S = ei.LinearSystem([[-1, 1, 0], [-1, -1, 0], [2, 3, -1]])
    P = ei.Polyhedron([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]], [1, 1, 1, 1])
    V = _routes(S, P, M.taylor(4))
    assert len(list(V)) == 1 and list(V)[0].lo == 0 and list(V)[0].hi_closed and _is_root_of(list(V)[0].hi, [-12, 12, -6, 0, 1])
    flat = ei.valid_steplengths(ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1]),
                                M.taylor(4), route="vertex")
    assert _ends(V) == _ends(flat)


def test_a_cylinder_over_a_hexagon_equals_the_polygon():
    """A hexagon times R^2 (two lines) under a block-triangular A whose lines are invariant: the same
    valid set as the hexagon in R^2 under the leading block, for Taylor(3) and Pade(1, 1)."""
    hexagon = [[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [-1, -1]]
    b = [1, 1, 1, 1, F(3, 2), F(3, 2)]
    A2 = [[-1, 2], [-1, -1]]
    A4 = [[-1, 2, 0, 0], [-1, -1, 0, 0], [1, 0, -1, 2], [0, 3, 0, -2]]
    P = ei.Polyhedron([g + [0, 0] for g in hexagon], b)
    for method in (M.taylor(3), M.pade(1, 1)):
        V = _routes(ei.LinearSystem(A4), P, method)
        flat = ei.valid_steplengths(ei.LinearSystem(A2), ei.Polyhedron(hexagon, b), method, route="vertex")
        assert _ends(V) == _ends(flat)
        assert len(V.lp.lines) == 2


def test_auto_may_take_the_lp_route_on_p_with_lines():
    from exactinv.validset.engine import ROUTES
    from exactinv.validset.problem import ValidSetProblem
    S, P = ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    assert ROUTES["lp"].accepts(ValidSetProblem(S, P, M.taylor(1)))
    with pytest.raises(LPRouteDeclined, match="no lines"):
        lp_lines(ConditionSet(S, ei.Polyhedron.box([-1, -1], [1, 1]), M.taylor(1)))
    cs = ConditionSet(S, P, M.taylor(1))
    assert lp_lines(cs) is lp_lines(cs)  # cached on the condition set
    from exactinv.validset.engine import choose_route
    n, m = 8, 40  # a cylinder over a random polytope in R^6 (two lines): McMullen's bound makes auto take the LP route
    G = [[(7 * i + 3 * j) % 11 - 5 for j in range(n - 2)] + [0, 0] for i in range(m)]
    big = ValidSetProblem(ei.LinearSystem([[-int(i == j) for j in range(n)] for i in range(n)]),
                          ei.Polyhedron(G, [1] * m), M.taylor(2))
    assert [r.name for r in choose_route(big)][0] == "lp"


# ------------------------------------------------------------------ route against route, and PPL


@st.composite
def lined_problems(draw):
    """(S, P, method): P = {|g_k x| <= beta_k} plus a few rows, in R^n (n <= 4), whose G has a kernel of
    dimension 1 or 2 (columns of G built from the first n - k ones), then sheared."""
    n = draw(st.integers(2, 4))
    k = draw(st.integers(1, min(2, n - 1)))
    free = n - k
    rows = [[int(i == j) for j in range(free)] for i in range(free)]
    for _ in range(draw(st.integers(0, 2))):
        row = [draw(st.integers(-2, 2)) for _ in range(free)]
        if any(row):
            rows.append(row)
    G = rows + [[-x for x in r] for r in rows]
    mix = [[draw(st.integers(-1, 1)) for _ in range(k)] for _ in range(free)]  # x_free + mix x_lines
    G = [r + [sum(r[i] * mix[i][j] for i in range(free)) for j in range(k)] for r in G]
    b = [draw(st.integers(1, 3)) for _ in rows] * 2
    q = st.fractions(min_value=-2, max_value=2, max_denominator=2)
    A = [[draw(q) for _ in range(n)] for _ in range(n)]
    if draw(st.booleans()):  # the lines' block invariant: the facets see Q alone (identical e = 0)
        for i in range(free):
            for j in range(free, n):
                A[i][j] = F(0)
    method = draw(st.sampled_from([M.taylor(1), M.taylor(2), M.taylor(3), M.backward_euler(), M.pade(1, 1)]))
    return ei.LinearSystem(A), ei.Polyhedron(G, b), method


@settings(max_examples=25, deadline=None)
@given(lined_problems())
def test_lp_route_equals_the_vertex_route_on_p_with_lines(problem):
    S, P, method = problem
    try:
        V = ei.valid_steplengths(S, P, method, route="lp")
    except InvalidInput as exc:  # it may decline only where all ray conditions of a facet vanish
        assert "declines" in str(exc)
        return
    W = ei.valid_steplengths(S, P, method, route="vertex")
    assert _ends(V) == _ends(W), (V, W)
    assert exactinv_check.check(V.certificate).ok


def _integer_expression(coeffs, x):
    d = 1
    for v in coeffs:
        d = d * Fraction(v).denominator // __import__("math").gcd(d, Fraction(v).denominator)
    return sum((int(Fraction(v) * d) * xk for v, xk in zip(coeffs, x)), ppl.Linear_Expression(0))


def _ppl_valid(S, P, method, h):
    """A_d(h) P inside P by PPL's exact simplex (ppl.MIP_Problem): every facet's max is attained and <= b_i
    (unbounded, along a line of P: invalid); a pole: invalid."""
    try:
        Ad = method.matrix(S, h)
    except InvalidInput:
        return False
    n = P.n
    x = [ppl.Variable(k) for k in range(n)]
    cs = ppl.Constraint_System()
    for g, beta in zip(P.G, P.b):
        cs.insert(_integer_expression(list(g) + [-beta], x + [1]) <= 0)
    for g, beta in zip(P.G, P.b):
        c = [sum(g[j] * Ad[j][k] for j in range(n)) for k in range(n)]
        if not any(c):
            continue
        mip = ppl.MIP_Problem(n, cs, _integer_expression(c, x), "maximization")
        status = mip.solve()["status"]
        if status == "unbounded":
            return False
        point = mip.optimizing_point()
        coords = list(point.coefficients()) + [0] * (n - len(point.coefficients()))
        if sum(ck * Fraction(int(v), int(point.divisor())) for ck, v in zip(c, coords)) > beta:
            return False
    return True


def _probes(V):
    out = []
    for iv in V:
        for end in (iv.lo, iv.hi):
            if isinstance(end, Infinity):
                continue
            if isinstance(end, RealAlgebraic):
                end.refine(40)
                out += [end.lower, end.upper]
            else:
                out += [end, end - F(1, 2**30), end + F(1, 2**30)]
    return [t for t in out if t >= 0]


@pytest.mark.parametrize("seed", range(4))
def test_lp_route_with_lines_agrees_with_ppl_at_every_end(seed):
    """Random P with one line in R^3 (G's third column a combination of the first two): at rationals just
    inside and outside every end of the LP route's valid set (and a few more), PPL decides the same."""
    rng = random.Random(300 + seed)
    rows = [[1, 0], [0, 1]] + [[rng.randint(-3, 3), rng.randint(-3, 3)] for _ in range(2)]
    rows = [r for r in rows if any(r)]
    mix = (rng.randint(-1, 1), rng.randint(-1, 1))
    G = [r + [r[0] * mix[0] + r[1] * mix[1]] for r in rows]
    G += [[-v for v in r] for r in G]
    b = [rng.randint(1, 3) for _ in rows] * 2
    A = [[F(-1 if i == j else 0) + F(rng.randint(-3, 3), 4) for j in range(3)] for i in range(3)]
    if seed % 2 == 0:  # an invariant line: a genuine interval, not isolated points
        A[0][2] = A[1][2] = F(0)
    S, P = ei.LinearSystem(A), ei.Polyhedron(G, b)
    checked = 0
    for method in (M.taylor(4), M.pade(1, 1), M.taylor(1)):
        V = ei.valid_steplengths(S, P, method, route="lp")
        for t in _probes(V) + [F(1, 3), F(2), F(7)]:
            assert (t in V) == _ppl_valid(S, P, method, t), (method, t)
            checked += 1
    assert checked


# ------------------------------------------------------------------ forged records, rejected


def _slab_certificate(A, method):
    S, P = ei.LinearSystem(A), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    return ei.valid_steplengths(S, P, method, route="lp").certificate


def _rejected(cert, words):
    report = exactinv_check.check(cert)
    assert not report.ok and report.kind == "rejected" and words in str(report), report


def test_a_line_not_in_ker_g_is_rejected():
    cert = copy.deepcopy(_slab_certificate([[-1, 0], [0, -1]], M.taylor(1)))
    assert exactinv_check.check(cert).ok
    cert["claims"][0]["lp"]["lines"] = [["1", "1"]]
    _rejected(cert, "not in ker G")


def test_a_missing_line_is_rejected():
    """Without its line the record's bases name a row that G does not have; with a line missing from a
    two-dimensional ker G every basis of G and the given line is singular."""
    cert = copy.deepcopy(_slab_certificate([[-1, 0], [0, -1]], M.taylor(1)))
    del cert["claims"][0]["lp"]["lines"]
    _rejected(cert, "basis row")
    S = ei.LinearSystem([[-1, 0, 0], [0, -1, 0], [0, 0, -1]])
    P = ei.Polyhedron([[1, 0, 0], [-1, 0, 0]], [1, 1])
    cert = ei.valid_steplengths(S, P, M.taylor(1), route="lp").certificate
    assert exactinv_check.check(cert).ok and len(cert["claims"][0]["lp"]["lines"]) == 2
    forged = copy.deepcopy(cert)
    forged["claims"][0]["lp"]["lines"] = forged["claims"][0]["lp"]["lines"][:1]
    for f in forged["claims"][0]["lp"]["facets"]:
        f["bases"] = [[r for r in basis if r != 3] + [0 if 0 not in basis else 1] for basis in f["bases"]]
    _rejected(forged, "singular")


def test_a_point_piece_at_a_non_root_is_rejected():
    """The slab with A = [[-1, 1], [0, -1]], Taylor(2): V = {0, 1}.  A forged record splitting facet 0 at
    1/2 with a point piece [1/2, 1/2] whose basis is x_B = (-1, 0) (not a maximizer there: z_B(1/2) < 0)."""
    cert = copy.deepcopy(_slab_certificate([[-1, 1], [0, -1]], M.taylor(2)))
    assert exactinv_check.check(cert).ok
    facet = cert["claims"][0]["lp"]["facets"][0]
    first = facet["bases"][0]
    other = [1, 2] if sorted(first) == [0, 2] else [0, 2]
    facet["ends"] = ["1/2", "1/2"] + facet["ends"]
    facet["bases"] = [first, other] + facet["bases"]
    _rejected(cert, "negative")


def test_a_claim_that_ignores_the_line_equalities_is_rejected():
    """The kernel rebuilds g_i N(h) l = 0 itself: the slab with A = [[-1, 1], [0, -1]] (V = {0, 1} for
    Taylor(2)) claimed with the set [0, 2] of the invariant-line slab, on the same pieces, is rejected."""
    cert = copy.deepcopy(_slab_certificate([[-1, 1], [0, -1]], M.taylor(2)))
    honest = _slab_certificate([[-1, 0], [0, -1]], M.taylor(2))
    cert["claims"][0]["intervals"] = honest["claims"][0]["intervals"]
    assert not exactinv_check.check(cert).ok


def test_lines_on_a_pointed_p_are_rejected():
    S, P = ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    cert = copy.deepcopy(ei.valid_steplengths(S, P, M.taylor(1), route="lp").certificate)
    assert exactinv_check.check(cert).ok
    cert["claims"][0]["lp"]["lines"] = [["0", "1"]]
    _rejected(cert, "not in ker G")


def test_explain_names_the_lines():
    from exactinv.interfaces.explain import explain
    text = explain(_slab_certificate([[-1, 1], [0, -1]], M.taylor(2)))
    assert "P has 1 line" in text and "g_i N(dt) l = 0" in text

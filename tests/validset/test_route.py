"""The route protocol (exactinv/validset/route.py and engine.py): every route that accepts a
problem gives the identical valid set, end by end and open/closed flag by flag, and the same
largest threshold, and the kernel accepts each route's certificate; the set is the same whether
P is given by inequalities or by its vertices (rays, lines); each route's membership agrees with an independent exact test
(``discrete_invariance`` at rational steps); ``route="auto"`` reports the route it took, and a
forced route that does not accept the problem is refused with a message naming it and why."""

from fractions import Fraction

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.scalars import Infinity
from exactinv.errors import InvalidInput
from exactinv.validset.engine import ROUTES, accepting_routes, choose_route
from exactinv.validset.problem import ValidSetProblem

M = ei.methods
F = Fraction

# polynomial methods, rational ones (r(hA) has poles at h = 1/lambda for A's positive eigenvalues)
METHODS = [M.forward_euler(), M.taylor(2), M.taylor(3), M.taylor(4), M.polynomial([1, 1, 0, "1/4"]),
           M.backward_euler(), M.pade(1, 1), M.pade(0, 2), M.pade(2, 2), M.theta("1/3")]
POLYHEDRAL = ("vertex", "box", "lp")
STEPS = [F(1, 8), F(1, 3), F(1, 2), F(1), F(3, 2), F(2), F(3), F(5)]


def _ends(V):
    return [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V]


def _first_end(V):
    first = V.intervals.intervals[0]
    return first.hi, first.hi_closed or isinstance(first.hi, Infinity)


def _every_route(S, P, m, check=False):
    """{route: (valid set, largest threshold)} over the polyhedral routes that accept (S, P, m)
    and do not decline it while applying (the LP route on an unbounded P)."""
    out = {}
    for name in POLYHEDRAL:
        if not ROUTES[name].accepts(ValidSetProblem(S, P, m)):
            with pytest.raises(InvalidInput, match=f"route: '{name}' does not accept this problem"):
                ei.valid_steplengths(S, P, m, route=name)
            continue
        try:
            V = ei.valid_steplengths(S, P, m, route=name)
        except InvalidInput as exc:
            assert name == "lp" and "declines" in str(exc) and not P.is_bounded, exc
            continue
        L = ei.largest_threshold(S, P, m, route=name)
        assert V.route == L.route == name
        if check:  # the kernel, on the route's own record (box, lp pieces, generator lists)
            assert ei.check(V.certificate).ok and ei.check(L.certificate).ok
        out[name] = (V, L)
    assert "vertex" in out  # the vertex route accepts every polyhedron
    return out


def _same_everywhere(results):
    (V0, L0), *rest = results.values()
    for name, (V, L) in results.items():
        assert _ends(V) == _ends(V0), (name, V, V0)
        assert (L.value, L.attained) == (L0.value, L0.attained), (name, L, L0)
        assert (L.value, L.attained) == _first_end(V)
    return V0


def _independent(S, P, m, V):
    """h in V iff A_d(h) P subset of P, decided by ``discrete_invariance`` (no route involved)."""
    for h in STEPS:
        try:
            holds = ei.discrete_invariance(S, P, m, h).holds
        except InvalidInput:  # a pole: r(hA) is undefined, h is not in V
            assert h not in V
            continue
        assert (h in V) == holds, (h, V)


@st.composite
def systems(draw, n):
    q = st.fractions(min_value=-3, max_value=3, max_denominator=2)
    return ei.LinearSystem([[draw(q) for _ in range(n)] for _ in range(n)])


@st.composite
def polyhedral_problems(draw):
    """(system, P, method) with P one of: a box; a polytope (the box [-2, 2]^n cut by random rows,
    0 inside); a degenerate polytope (a row through a corner, so that corner lies on n + 1 facets);
    a pointed unbounded P (x >= -1 and rows along which (1, .., 1) is a ray); P with a line
    (no constraint on the last coordinate, then the columns sheared: the line e_n - a e_1)."""
    n = draw(st.integers(1, 3))
    kind = draw(st.sampled_from(["box", "polytope", "degenerate", "rays", "lines"] if n > 1
                                else ["box", "polytope", "rays"]))
    unit = [[int(i == j) for j in range(n)] for i in range(n)]
    if kind == "box":
        lo = [draw(st.fractions(min_value=-3, max_value=-F(1, 2), max_denominator=2)) for _ in range(n)]
        hi = [draw(st.fractions(min_value=F(1, 2), max_value=3, max_denominator=2)) for _ in range(n)]
        P = ei.Polyhedron.box(lo, hi)
    elif kind in ("polytope", "degenerate"):
        G = unit + [[-x for x in row] for row in unit]
        b = [2] * (2 * n)
        if kind == "degenerate":
            G.append([1] * n)
            b.append(2 * n)  # through the corner (2, .., 2)
        for _ in range(draw(st.integers(0 if kind == "degenerate" else 1, 3))):
            row = [draw(st.integers(-3, 3)) for _ in range(n)]
            assume(any(row))
            G.append(row)
            b.append(draw(st.integers(1, 4)))
        P = ei.Polyhedron(G, b)
    elif kind == "rays":
        G, b = [[-x for x in row] for row in unit], [1] * n
        for _ in range(draw(st.integers(0, 2))):
            row = [draw(st.integers(-3, 0)) for _ in range(n)]
            assume(any(row))
            G.append(row)
            b.append(draw(st.integers(1, 3)))
        P = ei.Polyhedron(G, b)
    else:  # a line along the last coordinate
        G = [row[:-1] + [0] for row in unit[:-1]] + [[-x for x in row[:-1]] + [0] for row in unit[:-1]]
        b = [1] * len(G)
        row = [draw(st.integers(-2, 2)) for _ in range(n - 1)] + [0]
        if any(row):
            G.append(row)
            b.append(2)
        a = draw(st.integers(-2, 2))  # a shear x_1 -> x_1 + a x_n of the columns: the line turns to e_n - a e_1
        G = [[g[0]] + g[1:-1] + [g[-1] + a * g[0]] for g in G]
        P = ei.Polyhedron(G, b)
    return draw(systems(n)), P, draw(st.sampled_from(METHODS)), kind


@pytest.mark.heavy
@settings(max_examples=60, deadline=None)
@given(polyhedral_problems())
def test_every_accepting_route_gives_the_same_valid_set(problem):
    """Route against route, and P by inequalities against P by its generators (vertices, rays,
    lines): identical ends and flags, identical (tau, attained); membership agrees with the exact
    invariance test at rational steps."""
    S, P, m, kind = problem
    V = _same_everywhere(_every_route(S, P, m, check=True))
    Q = ei.Polyhedron.from_vertices(P.vertices, P.rays, P.lines)  # the same set, given by its generators
    W = _same_everywhere(_every_route(S, Q, m))
    assert _ends(V) == _ends(W)
    _independent(S, P, m, V)
    if kind == "box":
        assert ei.valid_steplengths(S, P, m).route == "box"
    if kind == "lines":  # P with lines: the LP route runs on P' = P with a basis of ker G as rows, + equalities
        results = _every_route(S, P, m)
        assert "lp" in results or not P.is_bounded  # it may only decline at a point no piece decides


@st.composite
def ellipsoid_problems(draw):
    """E = {x^T Q x <= 1}, Q = L L^T + I with L lower triangular (positive definite), a random A."""
    n = draw(st.integers(1, 3))
    small = st.fractions(min_value=-2, max_value=2, max_denominator=2)
    L = [[draw(small) if j <= i else F(0) for j in range(n)] for i in range(n)]
    Q = [[sum(L[i][k] * L[j][k] for k in range(n)) + int(i == j) for j in range(n)] for i in range(n)]
    return draw(systems(n)), ei.Ellipsoid(Q), draw(st.sampled_from(METHODS))


@settings(max_examples=30, deadline=None)
@given(ellipsoid_problems())
def test_the_ellipsoid_route_through_the_one_engine(problem):
    """On an ellipsoid only the ellipsoid route accepts; the engine's set agrees with the exact
    invariance test (Q - A_d^T Q A_d >= 0, decided by an exact LDL^T) at rational steps, and the
    largest threshold is the end of its first interval."""
    S, E, m = problem
    assert [r.name for r in accepting_routes(ValidSetProblem(S, E, m))] == ["ellipsoid"]
    V, L = ei.valid_steplengths(S, E, m), ei.largest_threshold(S, E, m)
    assert V.route == L.route == "ellipsoid" and 0 in V
    assert ei.check(V.certificate).ok and ei.check(L.certificate).ok  # binding q_k included
    assert (L.value, L.attained) == _first_end(V)
    _independent(S, E, m, V)


def test_forward_euler_from_the_engine_on_every_set_type():
    """The engine's forward-Euler step (any route) agrees with the family's own derivation:
    x' = Ax, A = [[-1, 1], [-1, -1]] on the square: 1/gamma* = 1 (box route); on the unit disc
    A = [[-a, -b], [b, -a]] gives 2a/(a^2 + b^2) = 2/5 (ellipsoid route); on the triangle
    (vertex route) and the vertex-given square (box route again: the rows are found a box)."""
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    square = ei.Polyhedron.box([-1, -1], [1, 1])
    fe = ei.forward_euler_threshold(S, square)
    assert (fe.value, fe.by_gamma, fe.route) == (1, 1, "box")
    disc = ei.forward_euler_threshold(ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]]))
    assert (disc.value, disc.by_eigenvalue, disc.by_valid_set) == (F(2, 5), F(2, 5), F(2, 5))
    triangle = ei.Polyhedron([[-1, 0], [0, -1], [1, 1]], [0, 0, 1])
    fe = ei.forward_euler_threshold(ei.LinearSystem([[-1, 0], [0, -1]]), triangle)
    assert (fe.value, fe.route) == (1, "vertex")  # (1 - h) x stays in the triangle iff h <= 1
    assert ei.check(fe.certificate).ok


# ------------------------------------------------------------------ route choice and refusal


def test_auto_reports_the_route_it_chose():
    """Box on a box, vertex on a small polytope, LP when McMullen's vertex bound is large
    (R^6 with 40 facets: 11020 > LP_ABOVE), ellipsoid on an ellipsoid -- from cheap estimates,
    before anything is solved."""
    S2 = ei.LinearSystem([[-1, 1], [-1, -1]])
    triangle = ei.Polyhedron([[-1, 0], [0, -1], [1, 1]], [0, 0, 1])
    assert ei.valid_steplengths(S2, ei.Polyhedron.box([-1, -1], [1, 1]), M.taylor(2)).route == "box"
    assert ei.valid_steplengths(S2, ei.Polyhedron.box([-1, -1], [1, 1]), M.taylor(2), box=False).route == "vertex"
    assert ei.largest_threshold(S2, triangle, M.taylor(2)).route == "vertex"
    assert ei.valid_steplengths(S2, ei.Ellipsoid([[1, 0], [0, 1]]), M.taylor(2)).route == "ellipsoid"
    n, m = 6, 40
    G = [[(7 * i + 3 * j) % 11 - 5 for j in range(n)] for i in range(m)]
    big = ValidSetProblem(ei.LinearSystem([[-int(i == j) for j in range(n)] for i in range(n)]),
                          ei.Polyhedron(G, [1] * m), M.taylor(2))
    assert [r.name for r in choose_route(big)][0] == "lp"


def test_a_forced_route_that_does_not_accept_is_refused_by_name(monkeypatch):
    S2 = ei.LinearSystem([[-1, 0], [0, -1]])
    triangle = ei.Polyhedron([[-1, 0], [0, -1], [1, 1]], [0, 0, 1])
    disc = ei.Ellipsoid([[1, 0], [0, 1]])
    strip = ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    with pytest.raises(InvalidInput, match=r"route: 'box' does not accept this problem: P is not a box"):
        ei.valid_steplengths(S2, triangle, M.taylor(2), route="box")
    with pytest.raises(InvalidInput, match=r"route: 'lp' does not accept this problem: the lp route handles "
                                           r"polyhedra, not a ellipsoid"):
        ei.largest_threshold(S2, disc, M.taylor(2), route="lp")
    with pytest.raises(InvalidInput, match=r"route: 'ellipsoid' does not accept this problem"):
        ei.valid_steplengths(S2, triangle, M.taylor(2), route="ellipsoid")
    assert ei.valid_steplengths(S2, strip, M.taylor(2), route="lp").route == "lp"  # P with lines: accepted
    # an unbounded P is the LP route's own now (ray pieces); a route that declines while solving (the LP
    # route at a point no piece decides) is refused by name when forced, and route="auto" takes the next
    orthant = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    S = ei.LinearSystem([[1, 0], [0, -1]])
    assert ei.valid_steplengths(S, orthant, M.taylor(1), route="lp").intervals == \
        ei.valid_steplengths(S, orthant, M.taylor(1), route="vertex").intervals
    import exactinv.validset.lp as lp_module
    from exactinv.validset.lp_route import LPRouteDeclined

    def declines(cs):
        raise LPRouteDeclined("a point no piece decides")

    monkeypatch.setattr(lp_module, "lp_route", declines)
    with pytest.raises(InvalidInput, match=r"route: the lp route declines this problem: a point no piece decides"):
        ei.valid_steplengths(S, orthant, M.taylor(1), route="lp")
    with pytest.raises(InvalidInput, match=r"route: expected one of 'auto', 'vertex', 'box', 'lp', 'ellipsoid'"):
        ei.valid_steplengths(S2, triangle, M.taylor(2), route="simplex")
    with pytest.raises(InvalidInput, match="conditions: a ConditionSet is of a polyhedron"):
        ei.valid_steplengths(S2, disc, M.taylor(2), conditions=ei.ConditionSet(S2, triangle, M.taylor(2)))


def test_a_shared_condition_set_serves_both_results():
    """One ConditionSet for the valid set and the largest threshold: the box route's conditions are
    built once (the route's output is cached on the problem's ConditionSet, keyed by the route
    function, not by a name)."""
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    cs = ei.ConditionSet(S, P, M.taylor(3))
    V = ei.valid_steplengths(S, P, M.taylor(3), conditions=cs)
    L = ei.largest_threshold(S, P, M.taylor(3), conditions=cs)
    assert V.route == L.route == "box" and V.box is L.box
    assert not any(isinstance(key, str) for key in cs.derived)

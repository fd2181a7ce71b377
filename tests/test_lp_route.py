"""The LP route (exactinv/beyond/lp_route.py): exact valid sets from parametric LPs, one basis per
piece of [0, oo) and facet, no vertex list; the same set as the vertex and box routes, end by end
and flag by flag, and the same as an independent exact LP (PPL's MIP solver) at rational steps
just inside and outside every end."""

import math
import random
from fractions import Fraction

import ppl
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import exactinv as ei
import exactinv_check
from exactinv.beyond.conditions import ConditionSet
from exactinv.beyond.lp_route import LPRouteDeclined, lp_route, vertex_bound
from exactinv.core.real_algebraic import RealAlgebraic
from exactinv.core.scalars import Infinity
from exactinv.errors import InvalidInput
from exactinv.validset.lp import LP_ABOVE

M = ei.methods
F = Fraction


def _ends(V):
    return [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V]


# ------------------------------------------------------------------ worked by hand


def test_forward_euler_on_an_interval_by_hand():
    """x' = -x on [-1, 1]: max (1 - h) x over [-1, 1] is 1 - h at x = 1 for h <= 1 and h - 1 at
    x = -1 after: the facet x <= 1 is kept iff h - 1 <= 1, so V = [0, 2]; two pieces per facet,
    the breakpoint 1 where the objective vanishes (every basis optimal there)."""
    S, P = ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1])
    V = ei.valid_steplengths(S, P, M.forward_euler(), route="lp")
    assert V.route == "lp" and _ends(V) == [(0, 2, True, True)]
    pieces = V.lp.facets[0].pieces
    assert [(p.start, p.end, p.basis) for p in pieces][0] == (0, 1, (0,))
    assert pieces[1].start == 1 and pieces[1].basis == (1,)


def test_a_triangle_degenerate_at_zero_and_at_the_breakpoint():
    """P = {x >= 0, y >= 0, x + y <= 1}, A = -I, forward Euler: A_d = (1 - h) I maps P into P iff
    0 <= 1 - h <= 1, so V = [0, 1].  At h = 0 the optimal face of every facet is the facet (a
    degenerate LP: several bases); at h = 1 the objective is 0 (every basis optimal)."""
    S = ei.LinearSystem([[-1, 0], [0, -1]])
    P = ei.Polyhedron([[-1, 0], [0, -1], [1, 1]], [0, 0, 1])
    for method in (M.forward_euler(), M.taylor(2)):
        V = ei.valid_steplengths(S, P, method, route="lp")
        W = ei.valid_steplengths(S, P, method, route="vertex")
        assert _ends(V) == _ends(W)
    assert _ends(ei.valid_steplengths(S, P, M.forward_euler(), route="lp")) == [(0, 1, True, True)]


def test_an_irrational_breakpoint_and_end_by_hand():
    """x' = -x on [-1, 1], Taylor(2): r(h) = 1 - h + h^2/2 > 0, so max r(h) x = r(h) <= 1 iff
    h <= 2: V = [0, 2] (the box route agrees); the LP route's facet x <= 1 keeps x = 1 for all h."""
    S, P = ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1])
    V = ei.valid_steplengths(S, P, M.taylor(2), route="lp")
    assert _ends(V) == [(0, 2, True, True)] == _ends(ei.valid_steplengths(S, P, M.taylor(2), route="box"))
    S = ei.LinearSystem([[0, 1], [-2, -1]])
    P = ei.Polyhedron([[1, 1], [-1, 1], [-1, -1], [1, -1], [1, 0]], [2, 2, 2, 2, F(3, 2)])
    V, W = (ei.valid_steplengths(S, P, M.taylor(3), route=r) for r in ("lp", "vertex"))
    assert _ends(V) == _ends(W)
    assert any(isinstance(p.end, RealAlgebraic) for f in V.lp.facets for p in f.pieces)  # a breakpoint sqrt-like


def test_the_largest_threshold_and_its_binding_condition():
    S = ei.LinearSystem([[-1, 2], [-1, -1]])
    P = ei.Polyhedron([[1, 0], [0, 1], [-1, 0], [0, -1], [1, 1], [-1, -1]], [1, 1, 1, 1, F(3, 2), F(3, 2)])
    for method in (M.taylor(4), M.taylor(1), M.pade(1, 1)):
        L1, L2 = (ei.largest_threshold(S, P, method, route=r) for r in ("lp", "vertex"))
        assert (L1.value, L1.attained) == (L2.value, L2.attained)
        assert L1.route == "lp" and L2.route == "vertex"
        if L1.binding is not None:
            x = L1.lp.vertices[L1.binding.generator]
            assert P.contains(x)  # the binding condition is that of a point of P


# ------------------------------------------------------------------ the route keyword


def test_route_keyword_is_checked_and_reported():
    S, P = ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1])
    with pytest.raises(InvalidInput, match="route"):
        ei.valid_steplengths(S, P, M.taylor(1), route="simplex")
    with pytest.raises(InvalidInput, match="route"):
        ei.largest_threshold(S, P, M.taylor(1), route=None)
    triangle = ei.Polyhedron([[-1, 0], [0, -1], [1, 1]], [0, 0, 1])
    with pytest.raises(InvalidInput, match="box"):
        ei.valid_steplengths(ei.LinearSystem([[-1, 0], [0, -1]]), triangle, M.taylor(1), route="box")
    assert ei.valid_steplengths(S, P, M.taylor(1)).route == "box"
    assert ei.valid_steplengths(S, P, M.taylor(1), route="vertex").route == "vertex"
    assert ei.valid_steplengths(S, P, M.taylor(1), route="lp").route == "lp"


def test_auto_takes_the_lp_route_only_when_the_vertex_bound_is_large():
    assert vertex_bound(2, 7) == 7 and vertex_bound(3, 10) == 16  # polygons; simple 3-polytopes 2m - 4
    rng = random.Random(3)
    n, m = 6, 40  # McMullen's bound: 11020 > LP_ABOVE
    G = [[rng.randint(-5, 5) for _ in range(n)] for _ in range(m)]
    S = ei.LinearSystem([[F(-1 if i == j else 0) + F(rng.randint(-3, 3), 60) for j in range(n)] for i in range(n)])
    P = ei.Polyhedron(G, [1] * m)
    assert vertex_bound(n, m) > LP_ABOVE >= vertex_bound(3, 40)
    V = ei.valid_steplengths(S, P, M.taylor(2))
    assert V.route == "lp"
    assert _ends(V) == _ends(ei.valid_steplengths(S, P, M.taylor(2), route="vertex"))


def test_unbounded_and_non_pointed_polyhedra_are_declined():
    """The LP route declines P with lines (no basis) and unbounded P (an unbounded LP or an edge that
    is a ray); route="lp" says so, route="auto" falls back to the vertex route."""
    S = ei.LinearSystem([[-1, 0], [0, -1]])
    strip = ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])  # a line along y
    with pytest.raises(InvalidInput, match="lines"):
        ei.valid_steplengths(S, strip, M.taylor(1), route="lp")
    orthant = ei.Polyhedron([[-1, 0], [0, -1], [1, -1]], [0, 0, 1])  # unbounded, pointed
    with pytest.raises(InvalidInput, match="unbounded"):
        ei.valid_steplengths(ei.LinearSystem([[1, 0], [0, -1]]), orthant, M.taylor(1), route="lp")
    with pytest.raises(LPRouteDeclined):
        lp_route(ConditionSet(S, strip, M.taylor(1)))


def test_a_shared_condition_set_builds_the_lp_route_once():
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    P = ei.Polyhedron([[1, 0], [0, 1], [-1, 0], [0, -1], [1, 1]], [1, 1, 1, 1, F(3, 2)])
    cs = ConditionSet(S, P, M.taylor(3))
    V = ei.valid_steplengths(S, P, M.taylor(3), conditions=cs, route="lp")
    L = ei.largest_threshold(S, P, M.taylor(3), conditions=cs, route="lp")
    assert V.lp is L.lp


# ------------------------------------------------------------------ properties

METHODS = [M.taylor(p) for p in range(1, 6)] + [M.polynomial([1, 1, 0, "1/4"]), M.backward_euler(), M.pade(1, 1),
                                                M.pade(2, 2), M.theta("1/3")]


@st.composite
def polytopes(draw, box=False):
    """Random bounded polytopes in R^n, n <= 4: the box [-2, 2]^n (or a random one) cut by random rows
    g x <= beta (0 stays inside), a random rational A and a method."""
    n = draw(st.integers(1, 4 if box else 3))
    q = st.fractions(min_value=-3, max_value=3, max_denominator=3)
    A = [[draw(q) for _ in range(n)] for _ in range(n)]
    if box:
        lo = [draw(st.fractions(min_value=-3, max_value=-F(1, 3), max_denominator=3)) for _ in range(n)]
        hi = [draw(st.fractions(min_value=F(1, 3), max_value=3, max_denominator=3)) for _ in range(n)]
        P = ei.Polyhedron.box(lo, hi)
    else:
        G = [[int(i == j) * s for j in range(n)] for i in range(n) for s in (1, -1)]
        b = [2] * (2 * n)
        for _ in range(draw(st.integers(1, 4))):
            row = [draw(st.integers(-3, 3)) for _ in range(n)]
            assume(any(row))
            G.append(row)
            b.append(draw(st.integers(1, 4)))
        P = ei.Polyhedron(G, b)
    return ei.LinearSystem(A), P, draw(st.sampled_from(METHODS))


@settings(max_examples=40, deadline=None)
@given(polytopes())
def test_lp_route_equals_the_vertex_route(problem):
    """Intervals, ends, open/closed flags, tau and attained identical; the certificate checks."""
    S, P, m = problem
    V1, V2 = ei.valid_steplengths(S, P, m, route="lp"), ei.valid_steplengths(S, P, m, route="vertex")
    assert V1.route == "lp" and _ends(V1) == _ends(V2)
    L1, L2 = ei.largest_threshold(S, P, m, route="lp"), ei.largest_threshold(S, P, m, route="vertex")
    assert (L1.value, L1.attained) == (L2.value, L2.attained)
    assert exactinv_check.check(V1.certificate).ok


@settings(max_examples=25, deadline=None)
@given(polytopes(box=True))
def test_lp_route_equals_the_box_route_and_the_vertex_route(problem):
    S, P, m = problem
    V1, V2, V3 = (ei.valid_steplengths(S, P, m, route=r) for r in ("lp", "box", "vertex"))
    assert V2.route == "box" and _ends(V1) == _ends(V2) == _ends(V3)


# ------------------------------------------------------------------ an independent exact LP (PPL)


def _integer_expression(coeffs, x):
    d = math.lcm(*(v.denominator for v in coeffs))
    return sum((int(v * d) * xk for v, xk in zip(coeffs, x)), ppl.Linear_Expression(0)), d


def _ppl_valid(S, P, method, h):
    """A_d(h) P inside P, decided by PPL's exact simplex (ppl.MIP_Problem, not the engine's LP chain):
    g_i A_d(h) x* <= b_i at a maximizer x* of g_i A_d(h) x over P, for every i (False where r(hA)
    does not exist)."""
    try:
        Ad = method.matrix(S, h)
    except InvalidInput:
        return False
    n = P.n
    x = [ppl.Variable(k) for k in range(n)]
    cs = ppl.Constraint_System()
    for g, beta in zip(P.G, P.b):
        e, d = _integer_expression(list(g) + [-beta], x + [1])
        cs.insert(e <= 0)
    for g, beta in zip(P.G, P.b):
        c = [sum(g[j] * Ad[j][k] for j in range(n)) for k in range(n)]
        if not any(c):
            continue
        objective, _ = _integer_expression(c, x)
        mip = ppl.MIP_Problem(n, cs, objective, "maximization")
        assert mip.solve()["status"] == "optimized"
        point = mip.optimizing_point()
        coords = list(point.coefficients()) + [0] * (n - len(point.coefficients()))
        best = [Fraction(int(v), int(point.divisor())) for v in coords]
        if sum(ck * bk for ck, bk in zip(c, best)) > beta:
            return False
    return True


def _probes(V):
    """Rationals just inside and just outside every finite end of V (and the rational ends)."""
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
def test_lp_route_agrees_with_ppl_at_every_end(seed):
    rng = random.Random(seed)
    n, m = 3, 9
    G = [[rng.randint(-4, 4) for _ in range(n)] for _ in range(m)] + \
        [[int(i == j) * s for j in range(n)] for i in range(n) for s in (1, -1)]
    S = ei.LinearSystem([[F(-1 if i == j else 0) + F(rng.randint(-3, 3), 8) for j in range(n)] for i in range(n)])
    P = ei.Polyhedron(G, [1] * m + [2] * (2 * n))
    for method in (M.taylor(4), M.pade(1, 1)):
        V = ei.valid_steplengths(S, P, method, route="lp")
        probes = _probes(V)
        assert probes
        for t in probes:
            assert (t in V) == _ppl_valid(S, P, method, t), (method, t)

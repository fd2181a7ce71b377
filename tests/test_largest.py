from fractions import Fraction

import pytest
import sympy
from hypothesis import assume, given
from hypothesis import strategies as st
from strategies import metzler_cones as cones

import exactinv as ei
from exactinv import compare_thresholds, forward_euler_threshold, largest_threshold, valid_steplengths
from exactinv import methods as M

BOX_S = ei.LinearSystem([[-1, 1], [-1, -1]])
BOX = ei.Polyhedron.box([-1, -1], [1, 1])
E2_S = ei.LinearSystem([[-1, 2], [0, 1]])
ORTHANT = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])


def _box_by_hand(sigmas):
    """Independent: on [-1,1]^2, A_d P subset of P iff every row of A_d has l1 norm <= 1.
    With A^k computed by sympy, the largest h with max row sum <= 1 on [0, h]."""
    h = sympy.Symbol("h", nonnegative=True)
    A = sympy.Matrix([[-1, 1], [-1, -1]])
    Ad = sum((sympy.Rational(s.numerator, s.denominator) * (h * A) ** k for k, s in enumerate(sigmas)), sympy.zeros(2, 2))
    candidates = []
    for i in range(2):
        # |a| + |b| <= 1  <=>  the four sign combinations +-a +-b <= 1
        for sa in (1, -1):
            for sb in (1, -1):
                expr = sympy.expand(1 - sa * Ad[i, 0] - sb * Ad[i, 1])
                poly = sympy.Poly(expr, h)
                roots = sorted(r for r in poly.real_roots() if r > 0)
                for r in roots:  # first root where expr turns negative
                    eps = sympy.Rational(1, 10**12)
                    if expr.subs(h, r + eps) < 0:
                        candidates.append(r)
                        break
    return min(candidates) if candidates else sympy.oo


@pytest.mark.parametrize("p", [2, 4])
def test_box_taylor_against_the_norm_condition(p):
    L = largest_threshold(BOX_S, BOX, M.taylor(p))
    expected = _box_by_hand(M.taylor(p).sigmas)
    lo = sympy.Rational(L.lower.numerator, L.lower.denominator)
    hi = sympy.Rational(L.upper.numerator, L.upper.denominator)
    assert lo <= expected <= hi
    assert L.attained
    assert ei.discrete_invariance(BOX_S, BOX, M.taylor(p), L.lower).holds
    assert not ei.discrete_invariance(BOX_S, BOX, M.taylor(p), L.upper + Fraction(1, 10**6)).holds
    assert ei.check(L.certificate).ok


def test_taylor2_box_is_sqrt2():
    L = largest_threshold(BOX_S, BOX, M.taylor(2))
    assert L.value == ei.real_roots([-2, 0, 1])[1][0]


def test_erratum_e2_valid_set_is_half_open():
    V = valid_steplengths(E2_S, ORTHANT, M.backward_euler())
    assert len(V) == 1
    (iv,) = V
    assert iv.lo == 0 and iv.hi == 1 and iv.lo_closed and not iv.hi_closed
    assert Fraction(99, 100) in V and 1 not in V and 2 not in V
    L = largest_threshold(E2_S, ORTHANT, M.backward_euler())
    assert L.value == 1 and not L.attained and L.singular == 1
    assert ei.check(L.certificate).ok


def test_valid_set_with_a_gap():
    """x' = -x on [-1, 1] with r(z) = 1 + z/2 + 3z^2/4 + z^3/4: A_d(h) = r(-h) = 1 - h(h-1)(h-2)/4
    exceeds 1 exactly on (1, 2), so the valid set is [0, 1] U [2, t3] with -1 = A_d(t3)."""
    S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    m = M.polynomial([1, "1/2", "3/4", "1/4"])
    V = valid_steplengths(S, P, m)
    assert len(V) == 2
    first, second = V
    assert (first.lo, first.hi, second.lo) == (0, 1, 2) and first.hi_closed and second.lo_closed
    t3 = second.hi  # root of h^3 - 3h^2 + 2h - 8 = 0
    assert isinstance(t3, ei.RealAlgebraic) and t3 == ei.real_roots([-8, 2, -3, 1])[0][0]
    L = largest_threshold(S, P, m)
    assert L.value == 1 and L.attained
    for k in range(0, 80):
        t = Fraction(k, 20)
        value = 1 - t * (t - 1) * (t - 2) / 4
        assert (t in V) == (abs(value) <= 1) == ei.discrete_invariance(S, P, m, t).holds


def test_isolated_singular_point_is_excluded():
    """On the strip |x1| <= 1 with A = diag(-1, 1), backward Euler is singular only at dt = 1."""
    S, strip = ei.LinearSystem([[-1, 0], [0, 1]]), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    V = valid_steplengths(S, strip, M.backward_euler())
    assert [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V] == [(0, 1, True, False), (1, ei.INF, False, False)]
    assert 2 in V and 1 not in V
    assert ei.discrete_invariance(S, strip, M.backward_euler(), 2).holds
    assert ei.check(V.certificate).ok


def test_union_membership_and_repr():
    V = valid_steplengths(BOX_S, BOX, M.taylor(1))
    assert "[0, 1]" in repr(V) and 1 in V and Fraction(3, 2) not in V


@st.composite
def random_polytopes(draw):
    n = 2
    k = draw(st.integers(3, 6))
    pts = [[Fraction(draw(st.integers(-6, 6)), draw(st.integers(1, 3))) for _ in range(n)] for _ in range(k)]
    P = ei.Polyhedron.from_vertices(pts)
    assume(P.dimension == 2)
    A = [[Fraction(draw(st.integers(-4, 4)), draw(st.integers(1, 3))) for _ in range(n)] for _ in range(n)]
    return ei.LinearSystem(A), P


@st.composite
def unbounded(draw):
    """A polyhedron with a vertex, rays, and sometimes a line."""
    kind = draw(st.sampled_from(["strip", "shifted_cone"]))
    A = [[Fraction(draw(st.integers(-3, 3))) for _ in range(2)] for _ in range(2)]
    if kind == "strip":
        P = ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])  # a line along x2
    else:
        P = ei.Polyhedron.from_vertices([[1, 1]], rays=[[1, 0], [1, 2]])
    return ei.LinearSystem(A), P


@given(st.one_of(random_polytopes(), cones(), unbounded()))
def test_forward_euler_two_derivations_agree(problem):
    S, P = problem
    fe = forward_euler_threshold(S, P)  # raises VerificationFailed if they differ
    assert fe.by_gamma == fe.by_vertices
    L = largest_threshold(S, P, M.forward_euler())
    assert L.value == fe.value


@given(st.one_of(random_polytopes(), cones()),
       st.sampled_from([M.taylor(2), M.heun(), M.rk4(), M.trapezoid(), M.backward_euler(), M.theta("1/4")]))
def test_paper_threshold_never_exceeds_the_largest(problem, method):
    S, P = problem
    assume(ei.continuous_invariance(S, P).holds)
    t = ei.steplength_threshold(S, P, method)
    L = largest_threshold(S, P, method)
    assert not (L.value < t.value)
    if t.value == L.value:
        assert L.attained or not t.attained
    V = valid_steplengths(S, P, method)
    assert L.value == V.intervals[0].hi
    if L.value != ei.INF:
        assert L.attained == V.intervals[0].hi_closed


@given(random_polytopes(), st.sampled_from([M.taylor(2), M.taylor(3), M.trapezoid()]))
def test_largest_threshold_spot_checks(problem, method):
    S, P = problem
    L = largest_threshold(S, P, method)
    if L.value == ei.INF or L.value == 0:
        return
    inside = L.lower if L.attained else L.lower * Fraction(999, 1000)
    assert ei.discrete_invariance(S, P, method, inside).holds
    assert ei.discrete_invariance(S, P, method, inside / 3).holds
    beyond = L.upper + (L.upper - L.lower) + Fraction(1, 10**9)
    try:
        assert not ei.discrete_invariance(S, P, method, beyond).holds or beyond in valid_steplengths(S, P, method)
    except ei.InvalidInput:
        pass  # r(dt A) singular there


def test_compare_table():
    rows = compare_thresholds(BOX_S, BOX, [M.taylor(1), M.taylor(2), M.trapezoid()])
    assert [r.method for r in rows] == ["taylor(1)", "taylor(2)", "trapezoid"]
    assert rows[0].ratio == 1
    lo, hi = rows[1].ratio_interval
    assert lo <= Fraction(1, 1) / Fraction(14142, 10000) and hi >= Fraction(7071, 10000)
    assert rows[2].largest == ei.INF
    assert rows[1].row()["corrected/largest"] == "[0.707106, 0.707107]"


def test_bad_input():
    with pytest.raises(ei.InvalidInput):
        largest_threshold(BOX_S, BOX, "taylor")
    with pytest.raises(ei.InvalidInput):
        valid_steplengths(ei.LinearSystem([[1]]), BOX, M.taylor(1))
    with pytest.raises(ei.EmptyPolyhedron):
        forward_euler_threshold(ei.LinearSystem([[1]]), ei.Polyhedron([[1], [-1]], [0, -1]))

"""Floats a user can step with (issue 21, item 4): exact outward rounding to
doubles (exactinv.core.doubles), ``lower``/``upper`` of every threshold-like
result adjacent doubles around the exact value, and ``safe_float`` the largest
double d with [0, d] inside the valid steps -- judged by the exact oracle."""

import math
from fractions import Fraction
from math import isqrt
from pathlib import Path

from hypothesis import assume, given, settings
from hypothesis import strategies as st
from strategies import metzler_cones

import exactinv as ei
from exactinv import methods as M
from exactinv import oracle
from exactinv.core.doubles import DOUBLE_MAX, double_above, double_below
from exactinv.core.real_algebraic import RealAlgebraic
from exactinv.interfaces.problem import load_problem

ROOT = Path(__file__).parents[2]

# issue 21: RK4 on x' = [[0, 1], [-2, -3]]x, P = {|2x1 + x2| <= 1, |x1 + x2| <= 1}
RK4_S = ei.LinearSystem([[0, 1], [-2, -3]])
RK4_P = ei.Polyhedron([[2, 1], [-2, -1], [1, 1], [-1, -1]], [1, 1, 1, 1])
E2_S = ei.LinearSystem([[-1, 2], [0, 1]])
ORTHANT = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])


def _up(d: float) -> float:
    return math.nextafter(d, math.inf)


# ------------------------------------------------------------------ core.doubles

def _floor_double(q: Fraction) -> Fraction:
    """Independent: the largest double <= q > 0 in the normal range, by integer
    scaling: m = floor(q 2^k) with 2^52 <= m < 2^53, the double m 2^-k."""
    k = 52 - (q.numerator.bit_length() - q.denominator.bit_length())
    while True:
        m = (q.numerator << k) // q.denominator if k >= 0 else q.numerator // (q.denominator << -k)
        if m < 2**52:
            k += 1
        elif m >= 2**53:
            k -= 1
        else:
            return Fraction(m, 2**k) if k >= 0 else Fraction(m * 2**-k)


positive_rationals = st.builds(lambda n, d, e: Fraction(n, d) * Fraction(2) ** e,
                               st.integers(1, 10**30), st.integers(1, 10**30), st.integers(-900, 900))


@given(positive_rationals)
def test_double_below_and_above_a_rational(q):
    lo, hi = double_below(q), double_above(q)
    assert Fraction(lo) == _floor_double(q)
    assert Fraction(lo) <= q <= Fraction(hi)
    assert hi == (lo if Fraction(lo) == q else _up(lo))  # adjacent doubles, or q itself
    strict = double_below(q, strict=True)
    assert Fraction(strict) < q and Fraction(_up(strict)) >= q


@given(st.integers(2, 10**12).filter(lambda k: isqrt(k) ** 2 != k), st.integers(-40, 40))
def test_double_below_a_square_root(k, e):
    """sqrt(k 4^e), irrational: the largest double d with d^2 < k 4^e, by isqrt."""
    a = RealAlgebraic.from_isolating_interval([-k, 0, 1], 0, k) * Fraction(2) ** e
    d = double_below(a)
    # sqrt(k) floored to 60 fractional bits: every double <= sqrt(k) (k >= 2: a multiple of 2^-52) is <= it
    by_hand = Fraction(isqrt(k << 120), 2**60) * Fraction(2) ** e
    assert Fraction(d) ** 2 < k * Fraction(4) ** e < Fraction(_up(d)) ** 2
    assert Fraction(d) == _floor_double(by_hand)
    assert double_above(a) == _up(d)


def test_the_ends_of_the_double_range():
    huge, tiny = Fraction(10) ** 400, Fraction(1, 10**400)
    assert double_below(huge) == DOUBLE_MAX and double_above(huge) == math.inf
    assert double_below(tiny) == 0.0 and double_above(tiny) == 5e-324
    assert double_below(-tiny) == -5e-324 and double_above(-huge) == -DOUBLE_MAX
    assert double_below(ei.INF) == DOUBLE_MAX and double_below(Fraction(0), strict=True) == -5e-324


# ---------------------------------------------------- the RK4 example

def test_rk4_safe_float_is_the_largest_valid_double():
    L = ei.largest_threshold(RK4_S, RK4_P, M.rk4())
    assert L.attained and isinstance(L.value, RealAlgebraic)
    d = L.safe_float
    assert d == 1.3926467817026406 and Fraction(d) < L.value < Fraction(_up(d))
    assert oracle.judge_threshold(RK4_S, RK4_P, M.rk4(), d).status == oracle.Status.TIGHT
    verdict = oracle.judge_threshold(RK4_S, RK4_P, M.rk4(), _up(d))  # the next double up: invalid, with a witness
    assert verdict.status == oracle.Status.INVALID
    assert not ei.discrete_invariance(RK4_S, RK4_P, M.rk4(), verdict.counterexample["dt"]).holds
    # the old failure: the double nearest the value rounds up past it
    assert float(L.value) == _up(d) and not oracle.judge_threshold(RK4_S, RK4_P, M.rk4(), float(L.value))
    # lower/upper are those two adjacent doubles, exactly
    assert L.lower == Fraction(d) and float(L.lower) == L.lower and L.upper == Fraction(_up(d))


def test_rk4_paper_threshold_and_forward_euler():
    t = ei.steplength_threshold(RK4_S, RK4_P, M.rk4())
    fe = ei.forward_euler_threshold(RK4_S, RK4_P)
    for x in (t, fe):
        assert Fraction(x.safe_float) <= x.value < Fraction(_up(x.safe_float))
        assert float(x.lower) == x.lower == Fraction(x.safe_float)


def test_a_threshold_that_is_not_attained():
    """Erratum E2: backward Euler on the orthant is valid on [0, 1): the safe float is the double below 1."""
    L = ei.largest_threshold(E2_S, ORTHANT, M.backward_euler())
    assert L.value == 1 and not L.attained
    assert L.safe_float == math.nextafter(1.0, 0) and L.lower == Fraction(L.safe_float) and L.upper == 1
    assert oracle.judge_threshold(E2_S, ORTHANT, M.backward_euler(), L.safe_float)
    assert not oracle.judge_threshold(E2_S, ORTHANT, M.backward_euler(), 1.0)


def test_an_ellipsoid_threshold_that_is_no_double():
    """Forward Euler on the unit disc with A = [[-1, -2], [2, -1]]: 2/5 exactly, above the double 0.4."""
    problem = load_problem(ROOT / "examples" / "ellipsoid_disc_taylor2.json")
    fe = ei.forward_euler_threshold(problem.system, problem.polyhedron)
    assert fe.value == Fraction(2, 5) and Fraction(0.4) > Fraction(2, 5)
    assert fe.safe_float == math.nextafter(0.4, 0) and fe.upper == Fraction(0.4)
    L = ei.largest_threshold(problem.system, problem.polyhedron, M.taylor(2))
    assert Fraction(L.safe_float) < L.value < Fraction(_up(L.safe_float))
    assert oracle.judge_threshold(problem.system, problem.polyhedron, M.taylor(2), L.safe_float)
    assert not oracle.judge_threshold(problem.system, problem.polyhedron, M.taylor(2), _up(L.safe_float))


def test_an_infinite_threshold():
    """x' = 0 on a box: every step is valid; the safe float is the largest finite double."""
    L = ei.largest_threshold(ei.LinearSystem([[0]]), ei.Polyhedron.box([-1], [1]), M.rk4())
    assert L.value == ei.INF and L.lower == ei.INF and L.upper == ei.INF
    assert L.safe_float == DOUBLE_MAX


def test_the_radius_of_absolute_monotonicity():
    """rho of Pade(2, 1) is the root of k^2 + 6k - 18 (-3 + 3 sqrt 3); its safe float is the double below it."""
    rho = ei.absolute_monotonicity_radius(M.pade(2, 1))
    assert rho.value == RealAlgebraic.from_isolating_interval([-18, 6, 1], 2, 3)
    assert Fraction(rho.safe_float) < rho.value < Fraction(_up(rho.safe_float)) and rho.lower == Fraction(rho.safe_float)


# ------------------------------------------------------- the property test

@st.composite
def polytopes(draw):
    pts = [[Fraction(draw(st.integers(-6, 6)), draw(st.integers(1, 3))) for _ in range(2)]
           for _ in range(draw(st.integers(3, 5)))]
    P = ei.Polyhedron.from_vertices(pts)
    assume(P.dimension == 2)
    A = [[Fraction(draw(st.integers(-4, 4)), draw(st.integers(1, 3))) for _ in range(2)] for _ in range(2)]
    return ei.LinearSystem(A), P


@given(st.one_of(polytopes(), metzler_cones()),
       st.sampled_from([M.taylor(2), M.heun(), M.rk4(), M.trapezoid(), M.backward_euler(), M.theta("1/4")]))
def test_every_threshold_has_a_float_safe_lower_end(problem, method):
    S, P = problem
    results = [ei.largest_threshold(S, P, method)]
    if ei.continuous_invariance(S, P).holds:
        results += [ei.steplength_threshold(S, P, method), ei.forward_euler_threshold(S, P)]
    for x in results:
        if x.value == ei.INF:
            assert x.safe_float == DOUBLE_MAX
            continue
        lo, d = x.lower, x.safe_float
        assert float(lo) == lo and Fraction(float(lo)) <= x.value and Fraction(d) == lo
        assert float(x.upper) == x.upper and x.upper >= x.value
        # the largest: the next double up is beyond the value (or is the value, not attained)
        nxt = Fraction(_up(d))
        assert nxt > x.value or (nxt == x.value and not x.attained)
        if not x.attained and x.value > 0:
            assert Fraction(d) < x.value
    L = results[0]
    if L.value != ei.INF:
        assert oracle.judge_threshold(S, P, method, L.safe_float)  # valid per the exact oracle
        assert ei.discrete_invariance(S, P, method, L.lower).holds


@st.composite
def ellipsoid_problems(draw):
    """A Q-dissipative A = (J - R) Q on E = {x^T Q x <= 1}, n = 2 (as tests/validset/test_ellipsoid.py)."""
    q = st.builds(Fraction, st.integers(-3, 3), st.integers(1, 3))
    B = [[draw(q) for _ in range(2)] for _ in range(2)]
    Q = [[sum(B[k][i] * B[k][j] for k in range(2)) + (i == j) for j in range(2)] for i in range(2)]
    s, c = draw(q), [draw(q), draw(q)]
    JR = [[-c[0] * c[0], s - c[0] * c[1]], [-s - c[0] * c[1], -c[1] * c[1]]]
    A = [[sum(JR[i][k] * Q[k][j] for k in range(2)) for j in range(2)] for i in range(2)]
    return ei.LinearSystem(A), ei.Ellipsoid(Q)


@given(ellipsoid_problems(), st.sampled_from([M.taylor(1), M.taylor(2), M.heun(), M.rk4()]))
@settings(max_examples=10)
def test_every_ellipsoid_threshold_has_a_float_safe_lower_end(problem, method):
    S, E = problem
    for x in (ei.largest_threshold(S, E, method), ei.forward_euler_threshold(S, E)):
        if x.value == ei.INF:
            assert x.safe_float == DOUBLE_MAX
            continue
        d = x.safe_float
        assert float(x.lower) == x.lower == Fraction(d) and Fraction(d) <= x.value
        assert Fraction(_up(d)) > x.value or (Fraction(_up(d)) == x.value and not x.attained)
        if x.value > 0:
            assert ei.discrete_invariance(S, E, method if isinstance(x, ei.LargestThreshold) else M.taylor(1),
                                          x.lower).holds

from fractions import Fraction

import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

import exactinv as ei
from exactinv import methods as M
from exactinv.monotonicity.radius import absolute_monotonicity_radius, taylor_coefficient_polynomials


@pytest.mark.parametrize("method, expected", [
    (M.forward_euler(), 1),
    (M.taylor(1), 1), (M.taylor(2), 1), (M.taylor(4), 1), (M.taylor(7), 1),
    (M.ssprk_s1(2), 2), (M.ssprk_s1(3), 3), (M.ssprk_s1(5), 5),
    (M.trapezoid(), 2),
    (M.theta("1/4"), Fraction(4, 3)), (M.theta("1/2"), 2), (M.theta("3/4"), 4), (M.theta("9/10"), 10),
    (M.backward_euler(), ei.INF), (M.theta(1), ei.INF),
    (M.rational([1], [1, -1, "1/2"]), 0),
    (M.lobatto_iiic2(), 0), (M.radau_iia2(), 0), (M.pade(2, 2), 0), (M.gauss2(), 0),
    (M.heun(), 1), (M.ssprk33(), 1), (M.rk4(), 1),
])
def test_known_radii(method, expected):
    assert absolute_monotonicity_radius(method).value == expected


@pytest.mark.parametrize("s", [2, 3, 4, 5, 6])
def test_shifted_power(s):
    """((s-1)/s)(1 + z/(s-1))^s + 1/s has radius s - 1."""
    z = sympy.Symbol("z")
    e = sympy.Rational(s - 1, s) * (1 + z / (s - 1)) ** s + sympy.Rational(1, s)
    coeffs = [Fraction(str(c)) for c in reversed(sympy.Poly(e, z).all_coeffs())]
    assert absolute_monotonicity_radius(M.polynomial(coeffs)).value == s - 1


def test_erratum_e1_j_zero_matters():
    """E1: with derivatives j >= 1 only, r(z) = 1 + 2z would have rho = oo; with j = 0, rho = 1/2."""
    m = M.polynomial([1, 2])
    assert absolute_monotonicity_radius(m).value == Fraction(1, 2)
    d = taylor_coefficient_polynomials(m, 2)
    assert ei.nonnegative_until(d[1]) == ei.INF  # c_1 = 2 > 0 for all kappa: the paper's definition sees nothing
    # and the consequence: x' = -x on [-1, 1], A_d = 1 - 2 dt leaves [-1, 1] for dt > 1
    S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    assert ei.discrete_invariance(S, P, m, 1).holds
    assert not ei.discrete_invariance(S, P, m, "1001/1000").holds


def _rho_from_derivatives(sigmas):
    """Independent route: r^(j)(-kappa) by sympy differentiation, first sign change by sympy."""
    kappa, z = sympy.symbols("kappa z")
    r = sum(sympy.Rational(s.numerator, s.denominator) * z**k for k, s in enumerate(sigmas))
    best = sympy.oo
    for j in range(len(sigmas)):
        poly = sympy.Poly(sympy.expand(sympy.diff(r, z, j).subs(z, -kappa)), kappa)
        if poly.is_zero:
            continue
        low = next(c for c in reversed(poly.all_coeffs()) if c != 0)
        if low < 0:
            return sympy.Integer(0)
        counts = {}
        for root in poly.real_roots():
            counts[root] = counts.get(root, 0) + 1
        odd = sorted(r0 for r0, mlt in counts.items() if r0 > 0 and mlt % 2)
        if odd:
            best = sympy.Min(best, odd[0])
    return best


@given(st.lists(st.fractions(min_value=0, max_value=3, max_denominator=6), min_size=1, max_size=5))
def test_polynomial_radius_two_routes(tail):
    sigmas = [Fraction(1)] + tail
    ours = absolute_monotonicity_radius(M.polynomial(sigmas))
    theirs = _rho_from_derivatives(sigmas)
    if theirs == sympy.oo:
        assert ours.value == ei.INF
    else:
        lo = sympy.Rational(ours.lower.numerator, ours.lower.denominator)
        hi = sympy.Rational(ours.upper.numerator, ours.upper.denominator)
        assert lo <= theirs <= hi


def _float_radius(method, terms=40, top=64.0):
    """A small float bisection (NodePy 1.1.1's linear_monotonicity_radius returned 0 for
    SSP22 and -inf for backward Euler here, so it is not used): Taylor coefficients at -kappa by
    float series division, kappa bisected on [0, top]."""
    g = [float(c) for c in method.numerator]
    h = [float(c) for c in method.denominator]
    from math import comb

    def ok(k):
        def shift(p):
            return [sum(p[i] * comb(i, j) * (-k) ** (i - j) for i in range(j, len(p))) for j in range(len(p))]
        G, H = shift(g), shift(h)
        if H[0] <= 0:
            return False
        c = []
        for j in range(terms):
            v = G[j] if j < len(G) else 0.0
            v -= sum(H[i] * c[j - i] for i in range(1, min(j, len(H) - 1) + 1))
            c.append(v / H[0])
        scale = max(1.0, max(abs(x) for x in c))
        return all(x >= -1e-12 * scale for x in c)

    if not ok(0.0):
        return 0.0
    if ok(top):
        return float("inf")
    lo, hi = 0.0, top
    for _ in range(60):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return lo


@pytest.mark.parametrize("name", ["forward_euler", "heun", "ssprk22", "ssprk33", "rk4", "trapezoid", "backward_euler",
                                  "radau_iia2", "lobatto_iiic2", "gauss2"])
def test_float_cross_check_on_presets(name):
    method = M.preset(name)
    exact = absolute_monotonicity_radius(method).value
    approx = _float_radius(method)
    if exact == ei.INF:
        assert approx == float("inf")
    else:
        assert abs(approx - float(exact)) < 1e-6


def test_bad_argument():
    with pytest.raises(ei.InvalidInput):
        absolute_monotonicity_radius("trapezoid")

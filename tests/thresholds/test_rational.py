from fractions import Fraction

import flint
import pytest
from hypothesis import given
from hypothesis import strategies as st
from strategies import metzler_cones as cones

import exactinv as ei
from exactinv import methods as M
from exactinv.core.flintq import fmpq_matrix
from exactinv.thresholds.rational import rational_threshold, spectral_abscissa

E2_SYSTEM = ei.LinearSystem([[-1, 2], [0, 1]])
ORTHANT = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])


def test_erratum_e2_backward_euler_on_the_orthant():
    """E2: the paper gives tau = oo (rho = oo); (I - dt A)^-1 has a negative entry for every dt > 1."""
    t = ei.steplength_threshold(E2_SYSTEM, ORTHANT, M.backward_euler())
    assert t.paper == ei.INF
    assert t.value == 1 and not t.attained
    assert t.spectral_abscissa == 1 and t.pole == 1
    for dt in ("1/2", "99/100"):
        assert ei.discrete_invariance(E2_SYSTEM, ORTHANT, M.backward_euler(), dt).holds
    for dt in ("101/100", 2, 10):
        result = ei.discrete_invariance(E2_SYSTEM, ORTHANT, M.backward_euler(), dt)
        assert not result.holds and ORTHANT.contains(result.witness.x)
    with pytest.raises(ei.InvalidInput, match="singular"):
        ei.discrete_invariance(E2_SYSTEM, ORTHANT, M.backward_euler(), 1)
    assert ei.check(t.certificate).ok


def test_erratum_e2_gamma_nonpositive_is_not_infinity_for_rational_methods():
    """Theorem 3.13 for rational methods: gamma* <= 0 but dt >= 1 fails for backward Euler."""
    S = ei.LinearSystem([[0, 1], [1, 0]])  # Metzler, gamma* = 0 on the orthant, eigenvalue 1
    assert ei.optimal_gamma(S, ORTHANT).value == 0
    t = ei.steplength_threshold(S, ORTHANT, M.backward_euler())
    assert t.paper == ei.INF and t.value == 1 and not t.attained
    assert not ei.discrete_invariance(S, ORTHANT, M.backward_euler(), 2).holds


def test_polynomial_methods_agree_through_both_routes():
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    g = ei.optimal_gamma(S, P)
    for m in (M.taylor(1), M.taylor(3), M.ssprk_s1(3), M.heun(), M.polynomial([1, 1, "1/3"]), M.polynomial([1, 2])):
        assert rational_threshold(m, g).value == ei.steplength_threshold(S, P, m).value


def test_spectral_abscissa_is_exact():
    assert spectral_abscissa(fmpq_matrix([[Fraction(-1), Fraction(2)], [Fraction(0), Fraction(1)]])) == 1
    alpha = spectral_abscissa(fmpq_matrix([[Fraction(0), Fraction(1)], [Fraction(2), Fraction(0)]]))
    assert isinstance(alpha, ei.RealAlgebraic) and alpha == ei.real_roots([-2, 0, 1])[1][0]


@st.composite
def polytopes(draw):
    n = draw(st.integers(1, 2))
    A = [[Fraction(draw(st.integers(-3, 3)), draw(st.integers(1, 3))) for _ in range(n)] for _ in range(n)]
    for i in range(n):
        A[i][i] = -sum(abs(A[i][j]) for j in range(n) if j != i) - Fraction(draw(st.integers(0, 3)), 2)
    return ei.LinearSystem(A), ei.Polyhedron.box([-1] * n, [1] * n)


METHODS = [M.taylor(2), M.heun(), M.rk4(), M.trapezoid(), M.theta("1/4"), M.backward_euler(),
           M.rational([1, "1/2"], [1, -1, "1/4"]), M.ssprk_s1(2)]


@given(st.one_of(cones(), polytopes()), st.sampled_from(METHODS))
def test_returned_thresholds_are_valid(problem, method):
    """No threshold is larger than the true largest one: exact spot checks below it."""
    S, P = problem
    t = ei.steplength_threshold(S, P, method)
    if t.value == ei.INF:
        points = [Fraction(7), Fraction(1000)]
    elif t.value == 0:
        return
    else:
        top = t.lower if t.attained else t.lower * Fraction(999, 1000)
        points = [top, top / 2, top / 5]
    for dt in points:
        assert ei.discrete_invariance(S, P, method, dt).holds, (method.name, dt, t)
    assert ei.check(t.certificate).ok


def test_the_e2_bound_uses_the_best_certificate_H():
    """gamma* = -oo (the line x1 = 0, A = -I): the gamma*-optimal H is pushed to H >= 0 and has
    alpha(H) > 0, but the unpushed row points give alpha(H) < 0, hence tau = oo for backward Euler."""
    S, line = ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron([[1, 0], [-1, 0]], [0, 0])
    t = ei.steplength_threshold(S, line, M.backward_euler())
    assert t.value == ei.INF and t.certificate_H is not None
    assert ei.discrete_invariance(S, line, M.backward_euler(), 1000).holds
    cert = t.certificate
    assert ei.check(cert).ok
    claim = next(c for c in cert["claims"] if c["type"] == "rational_threshold")
    claim["H"]["sparse"][0] = [[1, "-1"]]  # no longer a certificate (version 3: H by rows)
    assert not ei.check(cert).ok


def test_erratum_e2_prime_lineality_space_hides_a_singular_point():
    """Backward Euler, A = diag(-1, 1), P = {x1 <= 1}: H sees only the row of G,
    alpha(H) = -1, so the E2 bound says infinity; but I - dt A is singular at dt = 1."""
    S, P = ei.LinearSystem([[-1, 0], [0, 1]]), ei.Polyhedron([[1, 0]], [1])
    m = ei.methods.backward_euler()
    t = ei.steplength_threshold(S, P, m)
    assert t.value == 1 and t.attained is False
    assert t.paper == ei.INF  # the paper (and the E2 bound alone) say infinity
    V = ei.valid_steplengths(S, P, m)
    assert [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V] == [(0, 1, True, False), (1, ei.INF, False, False)]
    with pytest.raises(ei.ExactinvError):  # r(dt A) does not exist at dt = 1
        m.matrix(S, Fraction(1))
    assert ei.check(t.certificate).ok


def test_erratum_e2_prime_strip_trapezoid_not_attained():
    """Trapezoid, A = diag(-3/2, 3/2), strip 0 <= x1 <= 3/2: 4/3 is singular."""
    S = ei.LinearSystem([["-3/2", 0], [0, "3/2"]])
    P = ei.Polyhedron([[1, 0], [-1, 0]], ["3/2", 0])
    t = ei.steplength_threshold(S, P, ei.methods.trapezoid())
    assert t.value == Fraction(4, 3) and t.attained is False
    L = ei.largest_threshold(S, P, ei.methods.trapezoid())
    assert L.value == Fraction(4, 3) and L.attained is False
    assert ei.check(t.certificate).ok


def test_the_e2_bound_with_two_irrational_ingredients_is_exact():
    """z_p = (5 - sqrt 5)/2 and alpha(H) both irrational: their quotient is the root
    of x^2 + 15x - 45 (red team, round 2: interpolating the resultant at t = 0
    gave a wrong polynomial, in the kernel and in the engine)."""
    S, P = ei.LinearSystem([[0, "1/3"], ["1/3", "1/3"]]), ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    t = ei.steplength_threshold(S, P, M.rational([1], [1, -1, "1/5"]))
    assert t.attained is False and t.value.poly == flint.fmpz_poly([-45, 15, 1])
    assert ei.check(t.certificate).ok
